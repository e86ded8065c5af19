"""Grain growth and fragmentation (thesis §3.2.2) and the Vericel et al. (2021) growth box."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from dustygas import units
from dustygas.physics import disk, drag, growth


def test_drift_size_46_cm():
    """Thesis eq. 3.10: Sigma0 = 300 g/cm^2, rho_grain = 2.6 g/cm^3 at r = r0:
    s_drift = 300 / (sqrt(2 pi) * 2.6) cm = 300 / 6.5172 cm = 46.0318 cm (printed: 46 cm)."""
    s = float(growth.drift_size_midplane(300.0, 2.6))
    np.testing.assert_allclose(s, 46.031801584780695, rtol=1e-14)
    assert round(s) == 46


def test_drift_size_scales_as_inverse_radius():
    """For Sigma ~ r^-1, s_drift = rho_g c_s/(rho_grain Omega) ~ r^-1 whatever T(r) (eq. 3.10)."""
    r = np.geomspace(1.0, 300.0, 9) * units.au
    for q in (0.25, 0.5, 1.0):
        d = disk.PowerLawDisk(Sigma0=300.0, r0=units.au, p=1.0, T0=200.0, q=q, M_star=units.M_sun)
        s = growth.drift_size(d.midplane_density(r), d.sound_speed(r), d.omega(r), 2.6)
        np.testing.assert_allclose(s * r / units.au, 46.031801584780695, rtol=1e-13)


# (alpha, Ro, c_s [cm/s], A = alpha_tilde c_s^2 / V_frag^2): from just above the A = 2 limit to A >> 1
CASES = [(1e-3, 3.0, 4e4, 2.0002), (1e-4, 1.5, 2e4, 2.12), (1e-2, 3.0, 1.4e4, 3.7), (1e-3, 3.0, 1e4, 10.0),
         (1e-2, 3.0, 1e5, 424.0), (1e-2, 3.0, 1.4e6, 8.3e4)]


@pytest.mark.parametrize("alpha, rossby, c_s, A", CASES)
def test_fragmentation_sizes_are_the_roots_of_vrel_equals_vfrag(alpha, rossby, c_s, A):
    """s_frag+- from eq. 3.9 (with the Epstein size of unit Stokes number), put back through the
    drag law and eq. 3.7, give V_rel = V_frag to 1e-12; V_rel > V_frag strictly between them."""
    rho_g, rho_grain, Omega = 1e-11, 1.0, 2e-9
    at = growth.alpha_tilde(alpha, rossby)
    v_frag = c_s * np.sqrt(at / A)
    s1 = drag.epstein_grain_size(1.0, rho_grain, rho_g, c_s, Omega)
    s_lo, s_hi = growth.fragmentation_sizes(at, c_s, v_frag, s1)
    assert s_lo < s_hi
    np.testing.assert_allclose(s_lo * s_hi, s1**2, rtol=1e-13)

    def v_rel(s):
        taus = drag.stokes_number(drag.epstein_stopping_time(s, rho_grain, rho_g, c_s), Omega)
        return growth.relative_velocity(taus, c_s, alpha, rossby)

    np.testing.assert_allclose(v_rel(np.array([s_lo, s_hi])), v_frag, rtol=1e-12)
    inside = np.geomspace(s_lo, s_hi, 203)[1:-1]
    assert np.all(v_rel(inside) > v_frag)
    outside = np.concatenate([s_lo * np.geomspace(1e-6, 0.999, 20), s_hi * np.geomspace(1.001, 1e6, 20)])
    assert np.all(v_rel(outside) < v_frag)


def test_fragmentation_sizes_nan_without_root_and_touching_at_A_equal_2():
    """A < 2: V_rel < V_frag for every size (max V_rel = sqrt(alpha_tilde/2) c_s < V_frag): NaN.
    A = 2: the two roots merge at tau_s = 1."""
    lo, hi = growth.fragmentation_stokes_numbers(np.array([1.999, 0.5, 2.0]), 1.0, 1.0)
    assert np.isnan(lo[:2]).all() and np.isnan(hi[:2]).all()
    np.testing.assert_allclose([lo[2], hi[2]], [1.0, 1.0], rtol=1e-15)
    taus = np.geomspace(1e-4, 1e4, 2001)
    assert np.all(growth.relative_velocity(taus, 1.0, 1.999 / np.sqrt(2) / 3.0) < 1.0)


def test_fragmentation_roots_match_printed_thesis_form():
    """eq. 3.9 as printed: s = s_drift [A - 1 +- sqrt(A) sqrt(A - 2)]."""
    A = np.array([2.5, 10.0, 1e3])
    lo, hi = growth.fragmentation_sizes(A, 1.0, 1.0, 46.0)
    np.testing.assert_allclose(hi, 46.0 * (A - 1 + np.sqrt(A) * np.sqrt(A - 2)), rtol=1e-14)
    np.testing.assert_allclose(lo, 46.0 * (A - 1 - np.sqrt(A) * np.sqrt(A - 2)), rtol=1e-8)


def test_growth_rate_sign_and_magnitude():
    """eq. 3.6: ds/dt = +rho_d V_rel/rho_grain below V_frag, minus that above."""
    rate = growth.growth_rate(2e-12, 2.0, np.array([10.0, 30.0]), v_frag=20.0)
    np.testing.assert_allclose(rate, [1e-11, -3e-11], rtol=1e-15)
    np.testing.assert_allclose(growth.growth_rate(2e-12, 2.0, 30.0), 3e-11, rtol=1e-15)


BOX = dict(rho_g=1e-11, rho_d=1e-12, c_s=5e4, Omega=2e-8, alpha=1e-2, rossby=3.0, rho_grain=1.0)


def _box_dstokes_dt(stokes, sign=1.0):
    """dSt/dt from the thesis equations themselves: St(s) from the mixture Epstein time,
    ds/dt from eqs. 3.6-3.7 (chain rule dSt/dt = (St/s) ds/dt since St ~ s)."""
    b = BOX
    s = drag.epstein_grain_size(stokes, b["rho_grain"], b["rho_g"], b["c_s"], b["Omega"], rho_d=b["rho_d"])
    v_rel = growth.relative_velocity(stokes, b["c_s"], b["alpha"], b["rossby"])
    dsdt = sign * growth.growth_rate(b["rho_d"], b["rho_grain"], v_rel)
    return stokes / s * dsdt


def _box_tau():
    b = BOX
    return growth.growth_timescale(b["rho_g"], b["rho_d"], b["Omega"], b["alpha"], b["rossby"])


def test_growth_box_timescale_reproduces_the_growth_law():
    """dSt/dt = sqrt(St)/(1+St)/tau with tau = (rho/rho_d)/(sqrt(2^1.5 Ro alpha) Omega sqrt(pi/8))."""
    st = np.geomspace(1e-4, 1e2, 13)
    np.testing.assert_allclose(_box_dstokes_dt(st), np.sqrt(st) / (1 + st) / _box_tau(), rtol=1e-13)


@pytest.mark.parametrize("fragmentation", [False, True])
def test_growth_box_solution_solves_its_ode(fragmentation):
    """St(0) = St0, and a fourth-order central difference of St(t) equals +-sqrt(St)/((1+St) tau)."""
    tau, st0 = _box_tau(), 0.05
    sign = -1.0 if fragmentation else 1.0
    np.testing.assert_allclose(growth.stokes_number_growth(0.0, st0, tau, fragmentation), st0, rtol=1e-14)
    t_end = 0.9 * growth.growth_variable(st0) * tau if fragmentation else 30 * tau
    t = np.linspace(0.02, 0.98, 25) * t_end
    h = 1e-3 * tau
    f = lambda x: growth.stokes_number_growth(x, st0, tau, fragmentation)  # noqa: E731
    dstdt = (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h)
    st = f(t)
    np.testing.assert_allclose(dstdt, sign * np.sqrt(st) / (1 + st) / tau, rtol=1e-8)
    np.testing.assert_allclose(dstdt, _box_dstokes_dt(st, sign), rtol=1e-8)


def test_growth_box_matches_direct_integration_and_ends_at_zero_size():
    """Independent check: integrate dSt/dt (eqs. 3.6-3.7 + drag) with an adaptive RK (rtol 1e-11)."""
    tau, st0 = _box_tau(), 0.05
    t_eval = np.linspace(0, 20 * tau, 11)
    sol = solve_ivp(lambda t, y: _box_dstokes_dt(y), (0, t_eval[-1]), [st0], t_eval=t_eval, rtol=1e-11, atol=1e-14)
    np.testing.assert_allclose(growth.stokes_number_growth(t_eval, st0, tau), sol.y[0], rtol=1e-8)
    t_zero = growth.growth_variable(st0) * tau  # fragmenting grains vanish here
    st = growth.stokes_number_growth(np.array([t_zero * (1 - 1e-9), t_zero * (1 + 1e-9)]), st0, tau, True)
    assert 0 <= st[0] < 1e-17 and np.isnan(st[1])
