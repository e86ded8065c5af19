r"""Analytic growth rates of the settling-enhanced streaming instability (thesis §4.1.4, Fig 4.3).

Two leading-order (μ → 0) results for one dust species explain every feature of the growth
rate along a fixed direction k̂ (thesis Fig 4.3): the peak is a *resonant drag instability*
(Squire & Hopkins 2018, hereafter SH18), the large-|k| tail a *non-resonant plateau*. Both are
derived here from the equations of :mod:`dustygas.linear.operator`; the tests check the
operator against them (``tests/linear/test_settling.py``).

Notation: Ω = 1, velocities in ηv_K, k in 1/(ηr), c = c_s = 1/Π. In the frame of the gas the
dust drifts at w = V − U (NSH radial/azimuthal drift, thesis eq. 4.8, plus the vertical drift
v̄_z, eq. 4.19). k̂ = (sin θ_k, 0, σ cos θ_k) with θ_k = tan⁻¹(|k_x|/|k_z|) (measured from the
vertical, as in the thesis) and σ = ±1 the sign of k_z; W = k̂·w. A dust grain whose drag time
is short against the wave period follows a slowly varying gas velocity u as δv = M u with

.. math::

    M = \frac{1}{1+τ^2}\begin{pmatrix} 1 & 2τ & 0 \\ -τ/2 & 1 & 0 \\ 0 & 0 & 1+τ^2 \end{pmatrix}

(drag + Coriolis + tidal terms at zero Doppler-shifted frequency; the same matrix maps the NSH
gas velocity onto the dust velocity).

Resonance (SH18 §2-3; Zhuravlev 2019)
-------------------------------------
Without dust feedback the gas carries inertial waves, the slow roots of
ω⁴ − ω²(c²k² + Ω²) + c²k_z²Ω² = 0 (ω → ±Ω k_z/k for c → ∞), and the dust carries density
waves ω = k·w (gas frame). They cross where ω_I(k) = kW, at

.. math:: |k|^2 = \frac{c^2 \hat k_z^2 - W^2}{W^2 (c^2 - W^2)} \quad (\to \hat k_z^2/W^2 \text{ incompressible}),

and there the feedback μ splits the double root: ω = ω_0 + δ with
δ² = (μ/τ) cᵀ adj A(ω_0) w / (d det A/dω)(ω_0), where A(ω)u = F is the gas momentum equation
(continuity used to eliminate δρ_g) forced by the drag of the dust density wave,
F = (μ/τ) δρ_p w, and cᵀu = k·δv = k·M u − β (k·M w) k·u/ω_0 (β = 1 for Epstein drag). In the
incompressible limit the same steps give the reduced dispersion relation (gas frame)

.. math::

    (ω^2 - \hat k_z^2)(ω - |k|W) = \frac{μ \hat k_x \hat k_z |k|}{1+τ^2}
        \Big[(\hat k_z w_x - \hat k_x w_z)(1 - iωτ) + 2 w_y (τ \hat k_z + iω/\hat k_z)\Big],

whose double root ω_0 = |k|W = ±k̂_z splits by δ² = (right-hand side at ω_0)/(2ω_0);
and for pure settling (w_x = w_y = 0) and τ_s → 0 the growth rate is

.. math:: s = \mathrm{Im}\,δ = \sqrt{μ/2}\;|k_x|/k \;Ω,

independent of grain size (SH18's abstract) and equal to the square root of μ/2 times the
"coupling term" k_x² v̄_z² at k = Ω/|v̄_z| (Zhuravlev 2019, arXiv:1903.12492). The NSH radial
drift, x = w_x/w_z ≈ 2Π/(1+μ) for eq. 4.19, multiplies it by [(sc − σx c²)/(sc + σx s²)]^½
(s, c = sin θ_k, cos θ_k; τ_s → 0): +11.5 % for σ = −1 and −11.5 % for σ = +1 at θ_k = 30°,
Π = 0.05, μ = 0.01, which is why the peaks of Fig 4.3 (0.0394 Ω at μ = 0.01) exceed
√(μ/2) sin 30° = 0.0354 Ω.

Large-|k| plateau (derived here)
--------------------------------
Far beyond the resonance (|k| W ≫ ω_I) the dust density wave ω = k·V + δ is not resonant with
any gas wave. Its drag forces a gas response of order μ/k (transverse part i F_⊥/(kW), the
longitudinal part through the pressure, with δρ_g = −i k F_L /(k²(c² − W²))), which the dust
follows through M, and δ = k·δv/δρ_p tends to the |k|-independent growth rate

.. math::

    s_∞ = \frac{μ}{τ}\Big[\hat k·M w_⊥\Big(\frac1W + \frac{βW}{c^2 - W^2}\Big)
          - (1-β)\frac{W^2\, \hat k·M\hat k}{c^2 - W^2}\Big], \qquad
    \frac{\hat k·M w_⊥}{τ} = \frac{\hat k_x (2w_y - τ w_{⊥x})}{1+τ^2},

w_⊥ = w − W k̂ (β = 0: fixed stopping time, the "consistent" and "yj07" linearisations, which
agree at this order; β = 1: Epstein t_s ∝ 1/ρ_g). The first term (the incompressible plateau)
is positive; the second, the gas compression by the drag of the dust wave felt by grains of
fixed t_s, is negative and of order μτ k̂_z² when v̄_z ~ c_s τ_s (eq. 4.19), *whatever* Π. With
Epstein drag the compression also lowers the stopping time and the two effects cancel:
s_∞(Epstein) = c²/(c² − W²) × s_∞(incompressible) > 0.

High-|k| resonance along k̂ ⟂ w (SH18 "high-k regime"; Zhuravlev 2019b, arXiv:1907.09626)
------------------------------------------------------------------------------------------
Where k̂·w = 0 (tan θ_⊥ = |w_z/w_x|, k_z of sign −sign(w_x w_z); θ_⊥ ≈ 84° for eq. 4.19 at
Π = 0.05) the dust density wave stays resonant with the gas at every |k|. Once the growth
exceeds the inertial frequency Ω|k̂_z| (and while s τ_s ≪ 1) the reduced dispersion relation
above becomes ω³ = μ k̂_x k̂_z |k| (k̂_z w_x − k̂_x w_z)/(1 + τ²), i.e.

.. math:: s = \frac{\sqrt3}{2}\Big(\frac{μ |k|\, |w_x w_z|}{|w_{xz}|\,(1+τ_s^2)}\Big)^{1/3},

growing without bound ∝ (μ|k|)^{1/3}, and only if the dust drifts *both* radially and
vertically. Fixed-angle cuts such as Fig 4.3's θ_k = 30° miss this branch.
"""

from __future__ import annotations

import math
from typing import Union

import numpy as np
from numpy.typing import ArrayLike

from ..errors import UserError
from ..physics import nsh_velocities_multi
from .operator import DRAG_MODELS, drag_code, resolve_vz

__all__ = ["relative_drift", "dust_response_matrix", "resonant_growth", "large_k_growth", "perpendicular_direction",
           "high_k_growth"]


def _check(taus: float, mu: float, Pi: float, theta_deg: float, kz_sign: int) -> None:
    if not (taus > 0 and math.isfinite(taus)):
        raise UserError(f"taus = {taus!r}: must be finite and > 0")
    if not (mu >= 0 and math.isfinite(mu)):
        raise UserError(f"mu = {mu!r}: must be finite and >= 0")
    if not (Pi >= 0 and math.isfinite(Pi)):
        raise UserError(f"Pi = {Pi!r}: must be finite and >= 0")
    if not 0 < theta_deg < 90:
        raise UserError(f"theta_deg = {theta_deg!r}: the formulas need 0 < θ_k < 90°")
    if kz_sign not in (1, -1):
        raise UserError(f"kz_sign = {kz_sign!r}: must be +1 or -1")


def relative_drift(*, taus: float, mu: float, Pi: float = 0.05, vz: Union[float, str] = "settling") -> np.ndarray:
    """Dust drift through the gas w = V − U = (w_x, w_y, w_z) in ηv_K (thesis eqs. 4.8, 4.19).

    >>> [round(float(x), 6) for x in relative_drift(taus=1.0, mu=0.1)]
    [-0.995475, 0.452489, -6.666667]
    """
    eq = nsh_velocities_multi([taus], [mu])
    if isinstance(vz, str) and Pi == 0:
        raise UserError("vz='settling' (eq. 4.19, speed ~ c_s) needs Pi > 0")
    wz = float(resolve_vz(vz, np.array([taus]), Pi)[0])
    return np.array([float(eq.dust_vx[0] - eq.gas_vx), float(eq.dust_vy[0] - eq.gas_vy), wz])


def dust_response_matrix(taus: float) -> np.ndarray:
    """M: quasi-static dust velocity δv = M u driven by a slowly varying gas velocity u."""
    q = 1.0 / (1.0 + taus * taus)
    return np.array([[q, 2 * taus * q, 0.0], [-0.5 * taus * q, q, 0.0], [0.0, 0.0, 1.0]])


def _unit_k(theta_deg: float, kz_sign: int) -> np.ndarray:
    th = math.radians(theta_deg)
    return np.array([math.sin(th), 0.0, kz_sign * math.cos(th)])


def _drift_along_k(taus, mu, theta_deg, kz_sign, Pi, vz, drag):
    """The set-up of the estimates along k̂: ``(beta, w, k̂, W = k̂·w)`` after checking the
    parameters (``beta``: the drag model's density exponent, :data:`~dustygas.linear.operator.DRAG_MODELS`;
    ``w``: :func:`relative_drift`)."""
    _check(taus, mu, Pi, theta_deg, kz_sign)
    beta = DRAG_MODELS[list(DRAG_MODELS)[drag_code(drag)]][1]
    w = relative_drift(taus=taus, mu=mu, Pi=Pi, vz=vz)
    kh = _unit_k(theta_deg, kz_sign)
    return beta, w, kh, float(kh @ w)


def _adjugate3(a: np.ndarray) -> np.ndarray:
    c = np.empty((3, 3), dtype=a.dtype)
    for i in range(3):
        for j in range(3):
            rows = [r for r in range(3) if r != i]
            cols = [s for s in range(3) if s != j]
            minor = a[rows[0], cols[0]] * a[rows[1], cols[1]] - a[rows[0], cols[1]] * a[rows[1], cols[0]]
            c[j, i] = (-1) ** (i + j) * minor  # transpose of the cofactor matrix
    return c


def _gas_matrix(omega: complex, k: np.ndarray, c2: float) -> tuple[np.ndarray, np.ndarray]:
    """A(ω) and dA/dω of the forced gas momentum equation A u = F (gas frame, δρ_g = k·u/ω)."""
    kx, kz = k[0], k[2]
    kk = np.array([[kx * kx, 0.0, kx * kz], [0.0, 0.0, 0.0], [kx * kz, 0.0, kz * kz]])
    rot = np.array([[0.0, -2.0, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]])  # minus Coriolis + tidal
    A = -1j * omega * np.eye(3) + rot + 1j * c2 * kk / omega
    dA = -1j * np.eye(3) - 1j * c2 * kk / omega**2
    return A, dA


def resonant_growth(
    *,
    taus: float,
    mu: float,
    theta_deg: float = 30.0,
    kz_sign: int = 1,
    Pi: float = 0.05,
    vz: Union[float, str] = "settling",
    drag: str = "consistent",
) -> tuple[float, float]:
    """Resonant wavenumber and growth rate (K_res, s) along k̂, to leading order in μ (SH18).

    Parameters
    ----------
    taus, mu
        Stopping time τ_s and dust-to-gas ratio μ of the single dust species.
    theta_deg, kz_sign
        Direction k̂ = (sin θ_k, 0, ±cos θ_k): θ_k = tan⁻¹(|k_x/k_z|) from the vertical, sign of k_z.
    Pi, vz, drag
        As in :class:`dustygas.linear.StreamingParams` (Π = 0: incompressible closed form). At
        this order only the Epstein term (t_s ∝ 1/ρ_g) of the drag linearisation matters.

    Returns
    -------
    (K_res, s)
        |k|ηr where the dust density wave meets the gas inertial wave, and Im δ there
        (``nan, nan`` if the direction has no subsonic resonance). Valid for
        s ≪ Ω k̂_z, 1/τ_s; corrections are O(μ) against the O(√μ) result.

    Examples
    --------
    τ_s = 0.001, μ = 1e-4 at θ_k = 30°, the faster sign of k_z (−): the operator peaks at
    K = 53.07 with s = 0.003945 Ω:

    >>> K, s = resonant_growth(taus=0.001, mu=1e-4, theta_deg=30.0, kz_sign=-1)
    >>> round(K, 2), round(s, 6)
    (53.06, 0.003945)
    """
    beta, w, kh, W = _drift_along_k(taus, mu, theta_deg, kz_sign, Pi, vz, drag)
    if W == 0.0:
        return math.nan, math.nan
    if Pi == 0:
        kmag = abs(kh[2] / W)
        om0 = kmag * W
        bracket = ((kh[2] * w[0] - kh[0] * w[2]) * (1 - 1j * om0 * taus)
                   + 2 * w[1] * (taus * kh[2] + 1j * om0 / kh[2]))
        d2 = mu * kh[0] * kh[2] * bracket / (2 * W * (1 + taus**2))
    else:
        c2 = 1.0 / Pi**2
        k2 = (c2 * kh[2] ** 2 - W**2) / (W**2 * (c2 - W**2))
        if not k2 > 0:
            return math.nan, math.nan
        kmag = math.sqrt(k2)
        k = kmag * kh
        om0 = kmag * W
        A, dA = _gas_matrix(om0, k, c2)
        adj = _adjugate3(A)
        ddet = np.trace(adj @ dA)  # Jacobi's formula
        Mk = k @ dust_response_matrix(taus)  # row vector k·M
        cvec = Mk - beta * (Mk @ w) * k / om0
        d2 = (mu / taus) * (cvec @ adj @ w) / ddet
    delta = np.sqrt(complex(d2))
    return float(kmag), float(abs(delta.imag))


def large_k_growth(
    *,
    taus: float,
    mu: float,
    theta_deg: float = 30.0,
    kz_sign: int = 1,
    Pi: float = 0.05,
    vz: Union[float, str] = "settling",
    drag: str = "consistent",
) -> float:
    """Growth rate s_∞ of the dust density wave as |k| → ∞ along k̂ (the plateau), to O(μ).

    Parameters are those of :func:`resonant_growth`. ``nan`` where k̂ ⟂ w or the drift along k̂
    is sonic (W = 0 or W² = c²), where the wave is resonant at every |k|.

    Examples
    --------
    Thesis Fig 4.3, τ_s = 1, μ = 0.1 (faster sign): fixed t_s gives 0.0150 (operator: 0.0145),
    Epstein drag 0.0231 (operator: 0.0222):

    >>> [round(large_k_growth(taus=1.0, mu=0.1, theta_deg=30.0, kz_sign=-1, drag=d), 4) for d in ("consistent", "epstein")]
    [0.015, 0.0231]
    """
    beta, w, kh, W = _drift_along_k(taus, mu, theta_deg, kz_sign, Pi, vz, drag)
    c2 = math.inf if Pi == 0 else 1.0 / Pi**2
    if W == 0.0 or W * W == c2:
        return math.nan
    M = dust_response_matrix(taus)
    w_perp = w - W * kh
    transverse = float(kh @ M @ w_perp)
    if Pi == 0:
        return mu / taus * transverse / W
    compress = float(kh @ M @ kh)
    sub = c2 - W * W
    return mu / taus * (transverse * (1.0 / W + beta * W / sub) - (1.0 - beta) * W * W * compress / sub)


def perpendicular_direction(*, taus: float, mu: float, Pi: float = 0.05,
                            vz: Union[float, str] = "settling") -> tuple[float, int]:
    """(θ_⊥ in degrees, sign of k_z) of the axisymmetric direction k̂ ⟂ w (the high-|k| RDI).

    >>> th, sign = perpendicular_direction(taus=0.01, mu=0.1)
    >>> round(th, 2), sign
    (84.8, -1)
    """
    _check(taus, mu, Pi, 45.0, 1)
    w = relative_drift(taus=taus, mu=mu, Pi=Pi, vz=vz)
    if w[0] == 0.0 or w[2] == 0.0:
        raise UserError("k̂ ⟂ w needs a drift with both radial and vertical components")
    return math.degrees(math.atan(abs(w[2] / w[0]))), int(-np.sign(w[0] * w[2]))


def high_k_growth(*, taus: float, mu: float, K: ArrayLike, Pi: float = 0.05,
                  vz: Union[float, str] = "settling") -> np.ndarray:
    """Leading-order growth ∝ (μK)^{1/3} along k̂ ⟂ w at wavenumber K = |k|ηr (module docstring).

    Valid for Ω|k̂_z| ≪ s ≪ 1/τ_s (corrections of relative order k̂_z²Ω²/s² and s τ_s).

    >>> round(float(high_k_growth(taus=0.001, mu=0.01, K=1e5)), 4)
    1.0857
    """
    _check(taus, mu, Pi, 45.0, 1)
    w = relative_drift(taus=taus, mu=mu, Pi=Pi, vz=vz)
    K = np.asarray(K, dtype=np.float64)
    return math.sqrt(3.0) / 2.0 * np.cbrt(mu * K * abs(w[0] * w[2]) / (math.hypot(w[0], w[2]) * (1 + taus**2)))
