"""Settling-enhanced streaming instability (thesis §4.1.4, Fig 4.3) against the literature.

The operator with a vertical dust drift is checked against three analytic results, each to the
order in μ at which it is exact (:mod:`dustygas.linear.resonance` derives them):

* the resonant drag instability of Squire & Hopkins (2018): for pure settling and small grains
  s = √(μ/2) |k_x|/k Ω, independent of grain size (SH18; Zhuravlev 2019, arXiv:1903.12492),
  and its general form with radial drift and finite τ_s;
* the high-|k| branch along k ⟂ w: s = (√3/2)(μK|w_x w_z|/(|w|(1+τ_s²)))^{1/3}, growing as
  μ^{1/3} (SH18's high-k regime; Zhuravlev 2019b, arXiv:1907.09626);
* the non-resonant large-|k| plateau s_∞ behind the thesis's "plateau at large k", whose sign
  depends on the drag law.
"""

import math

import numpy as np
import pytest

from dustygas.errors import UserError
from dustygas.linear import growth_rate
from dustygas.linear.resonance import (
    high_k_growth,
    large_k_growth,
    perpendicular_direction,
    relative_drift,
    resonant_growth,
)


C2 = (1 / 0.05) ** 2  # c_s² at Π = 0.05


def _k(theta_deg, sign, K):
    t = math.radians(theta_deg)
    return {"kx": K * math.sin(t), "kz": sign * K * math.cos(t)}


def _peak(taus, mu, theta_deg, sign, K0, span=2e-3, n=2001, **kw):
    """Largest growth of the operator on |K| ∈ K0 (1 ± span) along a fixed direction."""
    K = K0 * np.linspace(1 - span, 1 + span, n)
    s = growth_rate(taus=taus, mu=mu, **_k(theta_deg, sign, K), **kw)
    i = int(np.argmax(s))
    assert 0 < i < n - 1, "maximum on the edge of the scanned window"
    return K[i], s[i]


@pytest.mark.parametrize("theta_deg", [30.0, 60.0])
@pytest.mark.parametrize("taus", [1e-2, 1e-3])
def test_pure_settling_growth_is_sh18_sqrt_mu_over_two(taus, theta_deg):
    """Published: s = √(μ/2) sin θ_k Ω at the resonance K = Ω/|v̄_z|, for any small τ_s (to 1e-3).

    Π = 1e-4 makes the NSH radial drift 2Π/(1+μ) ≈ 2e-4 of the eq. 4.19 settling speed
    (pure settling); μ = 1e-6 makes the O(μ) corrections to this O(√μ) result negligible."""
    mu, Pi = 1e-6, 1e-4
    vz = -(1 / Pi) * taus / (2 * taus**2 + 1)
    for sign in (1, -1):
        K, s = _peak(taus, mu, theta_deg, sign, 1.0 / abs(vz), Pi=Pi, vz="settling")
        assert s == pytest.approx(math.sqrt(mu / 2) * math.sin(math.radians(theta_deg)), rel=1e-3)
        assert K == pytest.approx(1.0 / abs(vz), rel=1e-3)


@pytest.mark.parametrize("drag", ["consistent", "epstein"])
@pytest.mark.parametrize("taus", [1.0, 0.1, 0.01, 0.001])
def test_resonance_with_radial_drift_at_thesis_parameters(taus, drag):
    """Fig 4.3's set-up (Π = 0.05, eq. 4.19, θ_k = 30°, both signs of k_z): the operator's peak
    is the compressible RDI resonance: |K| to 1e-5 and s to 1.2e-3 at μ = 1e-6 (the error is the
    O(√μ) next order: 1e-3 at τ_s = 1, 3e-6 at τ_s = 1e-3)."""
    mu = 1e-6
    for sign in (1, -1):
        K_res, s_res = resonant_growth(taus=taus, mu=mu, theta_deg=30.0, kz_sign=sign, drag=drag)
        K, s = _peak(taus, mu, 30.0, sign, K_res, vz="settling", drag=drag)
        assert K == pytest.approx(K_res, rel=1e-5)
        assert s == pytest.approx(s_res, rel=1.2e-3)


def test_incompressible_resonance_closed_form():
    """Π = 0: the closed-form δ² of the module docstring against the incompressible operator."""
    for taus in (0.1, 0.01):
        vz = -20.0 * taus / (2 * taus**2 + 1)
        for sign in (1, -1):
            K_res, s_res = resonant_growth(taus=taus, mu=1e-6, theta_deg=30.0, kz_sign=sign, Pi=0.0, vz=vz)
            assert K_res == pytest.approx(abs(math.cos(math.radians(30)) / (_unit(sign) @ relative_drift(
                taus=taus, mu=1e-6, Pi=0.0, vz=vz))), rel=1e-14)
            K, s = _peak(taus, 1e-6, 30.0, sign, K_res, Pi=0.0, vz=vz)
            assert s == pytest.approx(s_res, rel=2e-4)


def _unit(sign, theta_deg=30.0):
    t = math.radians(theta_deg)
    return np.array([math.sin(t), 0.0, sign * math.cos(t)])


def test_fig4_3_peaks_are_the_resonance():
    """At the thesis's own μ the small-grain peaks of Fig 4.3 are the leading-order resonance to
    < 0.3 % (μ = 0.01) and < 1 % (μ = 0.1): 0.0394 and 0.1230 Ω. They exceed SH18's pure-settling
    √(μ/2) sin 30° by the radial-drift factor [(sc + x c²)/(sc − x s²)]^½ (s, c = sin, cos θ_k,
    x = w_x/w_z ≈ 2Π/(1+μ); k_z < 0, the faster sign): +11.5 % (μ = 0.01), +10 % (μ = 0.1), to 1 %."""
    sn, cs = math.sin(math.radians(30)), math.cos(math.radians(30))
    for mu, tol in ((0.01, 3e-3), (0.1, 1e-2)):
        for taus in (0.01, 0.001):
            K_res, s_res = resonant_growth(taus=taus, mu=mu, theta_deg=30.0, kz_sign=-1)
            K, s = _peak(taus, mu, 30.0, -1, 1.07 * K_res, span=0.1, vz="settling")
            assert s == pytest.approx(s_res, rel=tol)
            w = relative_drift(taus=taus, mu=mu)
            x = w[0] / w[2]
            factor = math.sqrt((sn * cs + x * cs**2) / (sn * cs - x * sn**2))
            assert s == pytest.approx(math.sqrt(mu / 2) * sn * factor, rel=1e-2)


@pytest.mark.parametrize("drag", ["consistent", "yj07", "epstein"])
def test_large_k_plateau_matches_its_asymptote(drag):
    """The K-independent large-K growth of the dust density wave: operator at K = 1e3-1e4 vs s_∞
    at μ = 1e-3 (relative error O(μ) + O(1/K²): ≤ 1e-3), both signs of k_z, Π = 0.05 and Π = 0."""
    mu = 1e-3
    for taus, K in ((1.0, 1e3), (0.1, 1e4), (0.01, 1e4)):
        for Pi in (0.05, 0.0):
            if Pi == 0 and drag != "consistent":
                continue  # no δρ_g: the drag linearisations coincide
            vz = -20.0 * taus / (2 * taus**2 + 1)
            for sign in (1, -1):
                s_inf = large_k_growth(taus=taus, mu=mu, theta_deg=30.0, kz_sign=sign, Pi=Pi, vz=vz, drag=drag)
                s = float(growth_rate(taus=taus, mu=mu, **_k(30.0, sign, K), Pi=Pi, vz=vz, drag=drag))
                assert s == pytest.approx(s_inf, rel=1e-3), (taus, Pi, sign)


def test_plateau_sign_at_thesis_parameters():
    """Fig 4.3 (μ = 0.1, 0.01; faster of ±K_z at K = 1e4): with fixed t_s only τ_s = 1 keeps a
    positive plateau; with Epstein drag every curve does, and s_∞(Epstein) = c²/(c² − W²) ×
    s_∞(incompressible) (to 1e-12: the same formula, two forms)."""
    for mu in (0.1, 0.01):
        for taus in (1.0, 0.1, 0.01, 0.001):
            fixed = max(float(growth_rate(taus=taus, mu=mu, **_k(30.0, sg, 1e4), vz="settling")) for sg in (1, -1))
            ep = max(float(growth_rate(taus=taus, mu=mu, **_k(30.0, sg, 1e4), vz="settling", drag="epstein"))
                     for sg in (1, -1))
            assert (fixed > 0) == (taus == 1.0)
            assert ep > 0
            for sg in (1, -1):
                W = _unit(sg) @ relative_drift(taus=taus, mu=mu)
                vz = relative_drift(taus=taus, mu=mu)[2]
                inc = large_k_growth(taus=taus, mu=mu, theta_deg=30.0, kz_sign=sg, Pi=0.0, vz=vz)
                assert large_k_growth(taus=taus, mu=mu, theta_deg=30.0, kz_sign=sg, drag="epstein") == pytest.approx(
                    inc * C2 / (C2 - W * W), rel=1e-12)


def test_thesis_plateau_value_needs_a_steeper_angle():
    """The thesis's "as high as s/Ω ~ 0.03 in τ_s = 1, μ = 0.1" (one significant digit, ±0.005):
    not at θ_k = 30° with fixed t_s (0.0145) or Epstein drag (0.0222), but at θ_k = 40° with
    fixed t_s (0.0285), where every Fig 4.3 curve keeps a positive plateau."""
    def tail(taus, mu, theta_deg, drag="consistent"):
        return max(float(growth_rate(taus=taus, mu=mu, **_k(theta_deg, sg, 1e4), vz="settling", drag=drag)) for sg in (1, -1))

    assert abs(tail(1.0, 0.1, 30.0) - 0.03) > 0.005
    assert abs(tail(1.0, 0.1, 30.0, "epstein") - 0.03) > 0.005
    assert tail(1.0, 0.1, 40.0) == pytest.approx(0.03, abs=0.005)
    assert all(tail(taus, mu, 40.0) > 0 for taus in (1.0, 0.1, 0.01, 0.001) for mu in (0.1, 0.01))


def test_high_k_branch_grows_as_mu_one_third():
    """Along k ⟂ w (θ_⊥ = tan⁻¹|w_z/w_x| ≈ 84°, k_z < 0) the growth keeps rising: for μK ≥ 1e3 the
    operator follows (√3/2)(μK|w_x w_z|/(|w|(1+τ²)))^{1/3} to 1 % (the next order is k̂_z²Ω²/s²),
    and d ln s/d ln μ and d ln s/d ln K are 1/3 to 1 %."""
    for taus in (0.01, 0.001):
        s = {}
        for mu, K in ((1e-2, 1e5), (1e-2, 1e6), (1e-3, 1e6)):
            th, sign = perpendicular_direction(taus=taus, mu=mu)
            assert sign == -1 and 84.0 < th < 85.0
            assert _unit(sign, th) @ relative_drift(taus=taus, mu=mu) == pytest.approx(0.0, abs=1e-14)
            s[mu, K] = float(growth_rate(taus=taus, mu=mu, **_k(th, sign, K), vz="settling"))
            assert s[mu, K] == pytest.approx(float(high_k_growth(taus=taus, mu=mu, K=K)), rel=1e-2)
        assert math.log10(s[1e-2, 1e6] / s[1e-3, 1e6]) == pytest.approx(1 / 3, rel=1e-2)
        assert math.log10(s[1e-2, 1e6] / s[1e-2, 1e5]) == pytest.approx(1 / 3, rel=1e-2)


def test_bad_input_is_one_line_user_error():
    with pytest.raises(UserError, match="taus"):
        resonant_growth(taus=-1.0, mu=0.1)
    with pytest.raises(UserError, match="theta_deg"):
        large_k_growth(taus=0.1, mu=0.1, theta_deg=90.0)
    with pytest.raises(UserError, match="Pi > 0"):
        relative_drift(taus=0.1, mu=0.1, Pi=0.0)
    with pytest.raises(UserError, match="kz_sign"):
        resonant_growth(taus=0.1, mu=0.1, theta_deg=30.0, kz_sign=0)
