"""Local grain growth and fragmentation (thesis §3.2.2; Stepinski & Valageas 1996; Gonzalez et al. 2017).

Turbulent relative velocity and growth rate
-------------------------------------------
Grains of Stokes number :math:`\\tau_s` in α-turbulence collide at (thesis eq. 3.7;
Stepinski & Valageas 1996)

.. math:: V_{\\rm rel} = \\sqrt{2\\tilde\\alpha}\\,\\frac{\\sqrt{\\tau_s}}{1+\\tau_s}\\,c_s,
          \\qquad \\tilde\\alpha = \\sqrt2\\,Ro\\,\\alpha,

with Rossby number :math:`Ro` (> 3/2 for the model to hold; 3 in Gonzalez et al. 2017 and
Phantom), and grow or fragment at (thesis eq. 3.6, with :math:`\\epsilon\\rho = \\rho_d`)

.. math:: \\frac{ds}{dt} = \\pm\\frac{\\rho_d}{\\rho_{\\rm grain}}V_{\\rm rel},
          \\quad + \\text{ if } V_{\\rm rel} < V_{\\rm frag}, \\ - \\text{ otherwise.}

Fragmentation sizes (thesis eq. 3.9; Gonzalez et al. 2017, App. A)
-------------------------------------------------------------------
Write :math:`A = \\tilde\\alpha c_s^2/V_{\\rm frag}^2`. :math:`V_{\\rm rel} = V_{\\rm frag}` is
:math:`2\\tilde\\alpha c_s^2\\tau_s = V_{\\rm frag}^2(1+\\tau_s)^2`, i.e. the quadratic
:math:`\\tau_s^2 - 2(A-1)\\tau_s + 1 = 0` with roots

.. math:: \\tau_\\pm = A - 1 \\pm \\sqrt{A}\\sqrt{A-2},

real only for :math:`A \\ge 2`; their product is 1. Grains between the roots fragment, the
others grow. In the Epstein regime :math:`s \\propto \\tau_s`, so :math:`s_{\\rm frag}^\\pm =
s_1\\tau_\\pm` with :math:`s_1` the size of unit Stokes number. The thesis (following Gonzalez
et al.) takes :math:`s_1 = s_{\\rm drift} = \\rho_g c_s/(\\rho_{\\rm grain}\\Omega)`; with the
Epstein law of :mod:`dustygas.physics.drag`, :math:`s_1 = \\sqrt{8/(\\pi\\gamma)}\\,s_{\\rm drift}`
(:func:`~dustygas.physics.drag.epstein_grain_size` with ``taus=1``). :func:`fragmentation_sizes`
takes :math:`s_1` as an argument so either convention can be used explicitly.

For a vertically Gaussian disk :math:`\\rho_g = \\Sigma/(\\sqrt{2\\pi}H)` and :math:`H = c_s/\\Omega`,
so :math:`s_{\\rm drift} = \\Sigma/(\\sqrt{2\\pi}\\rho_{\\rm grain})`: 46 cm for
:math:`\\Sigma = 300` g/cm^2 and :math:`\\rho_{\\rm grain} = 2.6` g/cm^3 (thesis eq. 3.10).

Analytic growth in a uniform box (Vericel et al. 2021, MNRAS 507, 2318)
-----------------------------------------------------------------------
With the mixture Epstein Stokes number :math:`St = \\sqrt{\\pi\\gamma/8}\\,\\rho_{\\rm grain}s\\Omega/(\\rho c_s)`,
:math:`\\rho = \\rho_g+\\rho_d`, and uniform, constant :math:`\\rho_g, \\rho_d, c_s`, eq. 3.6 becomes

.. math:: \\frac{dSt}{dt} = \\pm\\frac{1}{\\tau}\\frac{\\sqrt{St}}{1+St}, \\qquad
          \\tau = \\frac{\\rho/\\rho_d}{\\sqrt{2^{3/2}Ro\\,\\alpha}\\;\\Omega\\sqrt{\\pi\\gamma/8}},

(multiply :math:`ds/dt` by :math:`dSt/ds`; :math:`\\sqrt{2\\tilde\\alpha} = \\sqrt{2^{3/2}Ro\\,\\alpha}`).
Separating, :math:`(1+St)St^{-1/2}dSt = \\pm dt/\\tau` integrates to
:math:`T \\equiv 2\\sqrt{St}(1 + St/3) = T_0 \\pm t/\\tau`. With :math:`x = \\sqrt{St}` this is the
depressed cubic :math:`x^3 + 3x - 3T/2 = 0`, whose real root (Cardano) gives

.. math:: G = \\left(8 + 9T^2 + 3T\\sqrt{16 + 9T^2}\\right)^{1/3}, \\qquad
          St = \\frac{G}{2} + \\frac{2}{G} - 2 = \\frac{(G-2)^2}{2G}.

``+``: pure growth, ``-``: pure fragmentation (Vericel et al. 2021), valid
until :math:`T = 0` (:math:`St = 0`) at :math:`t = T_0\\tau`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "DEFAULT_ROSSBY",
    "alpha_tilde",
    "relative_velocity",
    "growth_rate",
    "drift_size",
    "drift_size_midplane",
    "fragmentation_stokes_numbers",
    "fragmentation_sizes",
    "growth_timescale",
    "growth_variable",
    "stokes_number_growth",
]

#: Rossby number of the Stepinski & Valageas (1996) turbulence model in Gonzalez et al.
#: (2017) and Phantom (Vericel et al. 2021).
DEFAULT_ROSSBY = 3.0


def _f(x: ArrayLike) -> np.ndarray:
    return np.asarray(x, dtype=np.float64)


def alpha_tilde(alpha: ArrayLike, rossby: ArrayLike = DEFAULT_ROSSBY) -> np.ndarray:
    """:math:`\\tilde\\alpha = \\sqrt2\\,Ro\\,\\alpha` (thesis, below eq. 3.7)."""
    return np.sqrt(2.0) * _f(rossby) * _f(alpha)


def relative_velocity(
    taus: ArrayLike, c_s: ArrayLike, alpha: ArrayLike, rossby: ArrayLike = DEFAULT_ROSSBY
) -> np.ndarray:
    """Turbulent grain-grain velocity :math:`V_{\\rm rel} = \\sqrt{2\\tilde\\alpha}\\sqrt{\\tau_s}c_s/(1+\\tau_s)`.

    Thesis eq. 3.7 (Stepinski & Valageas 1996); units of ``c_s``. Maximal,
    :math:`\\sqrt{\\tilde\\alpha/2}\\,c_s`, at :math:`\\tau_s = 1`.
    """
    taus = _f(taus)
    return np.sqrt(2.0 * alpha_tilde(alpha, rossby)) * np.sqrt(taus) / (1.0 + taus) * _f(c_s)


def growth_rate(
    rho_d: ArrayLike, rho_grain: ArrayLike, v_rel: ArrayLike, v_frag: ArrayLike = np.inf
) -> np.ndarray:
    """Local :math:`ds/dt = \\pm(\\rho_d/\\rho_{\\rm grain})V_{\\rm rel}` (thesis eq. 3.6).

    Growth (+) where :math:`V_{\\rm rel} < V_{\\rm frag}`, fragmentation (-) where
    :math:`V_{\\rm rel} \\ge V_{\\rm frag}`; the default ``v_frag = inf`` is pure growth.
    ``rho_d`` is :math:`\\epsilon\\rho`, the dust density.
    """
    v_rel = _f(v_rel)
    rate = _f(rho_d) / _f(rho_grain) * v_rel
    return np.where(v_rel < _f(v_frag), rate, -rate)


def drift_size(rho_g: ArrayLike, c_s: ArrayLike, Omega: ArrayLike, rho_grain: ArrayLike) -> np.ndarray:
    """Drift size :math:`s_{\\rm drift} = \\rho_g c_s/(\\rho_{\\rm grain}\\Omega)` [cm] (thesis, below eq. 3.9).

    The thesis's "grain size for :math:`\\tau_s = 1`"; with the Epstein law of
    :mod:`~dustygas.physics.drag` unit Stokes number is reached at
    :math:`\\sqrt{8/(\\pi\\gamma)}\\,s_{\\rm drift}` (see the module docstring).
    """
    return _f(rho_g) * _f(c_s) / (_f(rho_grain) * _f(Omega))


def drift_size_midplane(Sigma: ArrayLike, rho_grain: ArrayLike) -> np.ndarray:
    """:math:`s_{\\rm drift}` at the midplane of a Gaussian disk, :math:`\\Sigma/(\\sqrt{2\\pi}\\rho_{\\rm grain})`.

    The general form behind thesis eq. 3.10; for :math:`\\Sigma = \\Sigma_0(r/r_0)^{-1}`,
    :math:`s_{\\rm drift} = 46\\,{\\rm cm}\\,(\\Sigma_0/300\\,{\\rm g\\,cm^{-2}})
    (\\rho_{\\rm grain}/2.6\\,{\\rm g\\,cm^{-3}})^{-1}(r/r_0)^{-1}`.

    >>> round(float(drift_size_midplane(300.0, 2.6)), 2)
    46.03
    """
    return _f(Sigma) / (np.sqrt(2.0 * np.pi) * _f(rho_grain))


def fragmentation_stokes_numbers(
    alpha_tilde: ArrayLike, c_s: ArrayLike, v_frag: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Stokes numbers :math:`(\\tau_-, \\tau_+)` at which :math:`V_{\\rm rel} = V_{\\rm frag}` (eq. 3.9).

    :math:`\\tau_\\pm = A - 1 \\pm \\sqrt{A(A-2)}`, :math:`A = \\tilde\\alpha c_s^2/V_{\\rm frag}^2`;
    NaN where :math:`A < 2` (:math:`V_{\\rm rel} < V_{\\rm frag}` for every size: no root).
    :math:`\\tau_-` is computed as :math:`1/\\tau_+` (the roots' product is 1), which avoids the
    cancellation of the printed form when :math:`A \\gg 1`.

    >>> lo, hi = fragmentation_stokes_numbers(2.0, 1.0, 1.0)
    >>> float(lo), float(hi)
    (1.0, 1.0)
    """
    A = _f(alpha_tilde) * (_f(c_s) / _f(v_frag)) ** 2
    with np.errstate(invalid="ignore"):
        disc = np.sqrt(np.where(A >= 2.0, A * (A - 2.0), np.nan))
    tau_plus = A - 1.0 + disc
    return 1.0 / tau_plus, tau_plus


def fragmentation_sizes(
    alpha_tilde: ArrayLike, c_s: ArrayLike, v_frag: ArrayLike, size_at_unit_stokes: ArrayLike
) -> tuple[np.ndarray, np.ndarray]:
    """Fragmentation sizes :math:`(s_{\\rm frag}^-, s_{\\rm frag}^+) = s_1(\\tau_-, \\tau_+)` (thesis eq. 3.9).

    ``size_at_unit_stokes`` is :math:`s_1`, the grain radius whose Stokes number is 1: the
    thesis's :math:`s_{\\rm drift}` (:func:`drift_size`) to reproduce eq. 3.9 as printed, or
    :func:`~dustygas.physics.drag.epstein_grain_size` at ``taus=1`` for the Epstein law with
    its :math:`\\sqrt{8/(\\pi\\gamma)}` factor. NaN where no root exists.
    """
    tau_minus, tau_plus = fragmentation_stokes_numbers(alpha_tilde, c_s, v_frag)
    s1 = _f(size_at_unit_stokes)
    return s1 * tau_minus, s1 * tau_plus


def growth_timescale(
    rho_g: ArrayLike, rho_d: ArrayLike, Omega: ArrayLike, alpha: ArrayLike,
    rossby: ArrayLike = DEFAULT_ROSSBY, gamma: ArrayLike = 1.0,
) -> np.ndarray:
    """Growth time :math:`\\tau = ((\\rho_g+\\rho_d)/\\rho_d)/(\\sqrt{2^{3/2}Ro\\,\\alpha}\\,\\Omega\\sqrt{\\pi\\gamma/8})`.

    The time unit of :func:`stokes_number_growth` (Vericel et al. 2021); units of 1/Omega.
    """
    rho_g, rho_d = _f(rho_g), _f(rho_d)
    return ((rho_g + rho_d) / rho_d) / (
        np.sqrt(2.0**1.5 * _f(rossby) * _f(alpha)) * _f(Omega) * np.sqrt(np.pi * _f(gamma) / 8.0)
    )


def growth_variable(stokes: ArrayLike) -> np.ndarray:
    """:math:`T(St) = 2\\sqrt{St}(1 + St/3)`, which changes at the constant rate :math:`\\pm1/\\tau`."""
    st = _f(stokes)
    return 2.0 * np.sqrt(st) * (1.0 + st / 3.0)


def stokes_number_growth(
    t: ArrayLike, stokes0: ArrayLike, tau: ArrayLike, fragmentation: bool = False
) -> np.ndarray:
    """Exact Stokes number :math:`St(t)` of grains growing (or fragmenting) in a uniform box.

    Vericel et al. (2021). ``tau`` from :func:`growth_timescale`,
    ``stokes0`` the initial (mixture, Epstein) Stokes number. With ``fragmentation=True`` the
    grains shrink at the same rate (eq. 3.6 with :math:`V_{\\rm rel} > V_{\\rm frag}`
    throughout); the result is NaN after the size would reach zero.

    >>> round(float(stokes_number_growth(0.0, 0.25, 1.0)), 12)
    0.25
    """
    sign = -1.0 if fragmentation else 1.0
    T = growth_variable(stokes0) + sign * _f(t) / _f(tau)
    root = np.sqrt(16.0 + 9.0 * T**2)
    G3_minus_8 = 9.0 * T**2 + 3.0 * T * root
    G = np.cbrt(8.0 + G3_minus_8)
    G_minus_2 = G3_minus_8 / (G**2 + 2.0 * G + 4.0)  # G - 2 without cancellation
    stokes = G_minus_2**2 / (2.0 * G)
    return np.where(T >= 0.0, stokes, np.nan)
