"""Aerodynamic drag between gas and dust grains: Epstein and Stokes regimes (thesis §2.1).

Naming, used throughout :mod:`dustygas`
---------------------------------------
``mu`` is **always** the dust-to-gas density ratio :math:`\\mu = \\rho_d/\\rho_g` (thesis eq.
2.8), and ``dust_fraction`` / ``eps`` is **always** the dust fraction of the total density
:math:`\\epsilon = \\rho_d/(\\rho_d+\\rho_g)` (thesis eq. 2.7). Youdin & Johansen (2007) call
the dust-to-gas ratio ":math:`\\epsilon`": their :math:`\\epsilon` is our ``mu``.

Grains are spheres of radius ``s`` and material (intrinsic) density ``rho_grain``, so a grain
has mass :math:`m = (4\\pi/3)\\rho_{\\rm grain} s^3`. All quantities are cgs.

Epstein regime (grain smaller than the gas mean free path)
----------------------------------------------------------
A grain moving at :math:`\\Delta v \\ll c_s` through gas of density :math:`\\rho_g` and mean
thermal speed :math:`v_{\\rm th} = \\sqrt{8/(\\pi\\gamma)}\\,c_s` feels the force
:math:`F = -(4\\pi/3)\\rho_g s^2 v_{\\rm th}\\Delta v` (Epstein 1924; Weidenschilling 1977).
Per unit volume, with :math:`n_d = \\rho_d/m` grains, the drag coefficient of the two-fluid
equations (thesis eqs. 2.2, 2.5) and the stopping time of one grain are

.. math::

    K = \\frac{\\rho_d \\rho_g v_{\\rm th}}{\\rho_{\\rm grain} s}, \\qquad
    t_s = \\frac{\\rho_d}{K} = \\frac{\\rho_{\\rm grain} s}{\\rho_g v_{\\rm th}}
        = \\sqrt{\\frac{\\pi\\gamma}{8}}\\,\\frac{\\rho_{\\rm grain} s}{\\rho_g c_s}

(Laibe & Price 2012, MNRAS 420, 2345). **The thesis
prints** :math:`K = \\frac{4\\pi}{3}\\frac{\\rho_d\\rho_g}{\\rho_{\\rm grain}s}\\sqrt{8/(\\pi\\gamma)}\\,c_s`
(eq. 2.3) and :math:`t_s = \\frac{3}{4\\pi}\\frac{\\rho_{\\rm grain}s}{\\rho_g c_s}\\sqrt{\\pi\\gamma/8}`
(eq. 2.6). The factor :math:`4\\pi/3` is the one in the grain mass and in the force; it
cancels between them (:math:`n_d F = \\rho_d F/m`), so it does not belong in :math:`K`. The
printed forms also contradict the thesis's own drift size (eqs. 3.9-3.10 put :math:`\\tau_s = 1`
at :math:`s = \\rho_g c_s/(\\rho_{\\rm grain}\\Omega)`, which agrees with the Epstein law up to
its :math:`\\sqrt{\\pi\\gamma/8}` factor but not with the printed :math:`3/(4\\pi)`) and the
growth-box solution of Vericel et al. (2021). We implement the standard result above.

Single grain versus mixture stopping time
-----------------------------------------
The relative velocity :math:`\\Delta v = v_d - v_g` of the two-fluid system decays on the
*mixture* stopping time :math:`t_s = \\rho_g\\rho_d/(K(\\rho_g+\\rho_d))
= \\rho_{\\rm grain}s/((\\rho_g+\\rho_d) v_{\\rm th})` (Laibe & Price 2014, MNRAS 440, 2136;
the stopping time of one-fluid codes and of Vericel et al. 2021). :func:`epstein_stopping_time`
returns it when ``rho_d`` is given, and the single-grain time otherwise.

Stokes regime (grain larger than the mean free path)
----------------------------------------------------
Mean free path :math:`\\lambda = \\mu_{\\rm mol} m_H/(\\rho_g\\sigma_{H_2})`, molecular viscosity
:math:`\\nu_{\\rm mol} = \\lambda v_{\\rm th}/2`, Reynolds number :math:`Re = 2s|\\Delta v|/\\nu_{\\rm mol}`
and drag coefficient (Weidenschilling 1977, MNRAS 180, 57; Birnstiel, Dullemond & Brauer 2010,
A&A 513, A79)

.. math::

    C_D = \\begin{cases} 24/Re & Re < 1 \\\\ 24\\,Re^{-0.6} & 1 \\le Re < 800 \\\\
    0.44 & Re \\ge 800 \\end{cases}, \\qquad
    t_s = \\frac{8\\rho_{\\rm grain}s}{3 C_D\\rho_g|\\Delta v|}.

For :math:`Re < 1` this is :math:`t_s = 2\\rho_{\\rm grain}s^2/(9\\nu_{\\rm mol}\\rho_g)`,
independent of :math:`\\Delta v`, and equals the Epstein time at :math:`s = 9\\lambda/4`,
where :func:`stopping_time` switches regime. The published piecewise :math:`C_D` is
continuous at :math:`Re = 1` but not at :math:`Re = 800`
(:math:`24 \\cdot 800^{-0.6} = 0.43487` versus 0.44: :math:`C_D` jumps up by 1.18 per cent).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import ArrayLike

from ..units import MEAN_MOLECULAR_WEIGHT, m_H, sigma_H2

__all__ = [
    "thermal_speed",
    "epstein_drag_coefficient",
    "epstein_stopping_time",
    "epstein_stopping_time_scalar",
    "epstein_grain_size",
    "stokes_number",
    "mean_free_path",
    "molecular_viscosity",
    "reynolds_number",
    "stokes_drag_coefficient",
    "stokes_stopping_time",
    "stopping_time",
    "dust_fraction",
    "dust_to_gas_ratio",
    "ratio_to_fraction",
    "fraction_to_ratio",
    "mixture_stopping_time",
]

#: Re below which the Stokes drag is linear (C_D = 24/Re) and above which C_D = 24 Re^-0.6.
REYNOLDS_LINEAR = 1.0
#: Re above which C_D = 0.44 (Weidenschilling 1977).
REYNOLDS_QUADRATIC = 800.0


def _f(x: ArrayLike) -> np.ndarray:
    return np.asarray(x, dtype=np.float64)


def thermal_speed(c_s: ArrayLike, gamma: ArrayLike = 1.0) -> np.ndarray:
    """Mean thermal speed of the gas molecules :math:`v_{\\rm th} = \\sqrt{8/(\\pi\\gamma)}\\,c_s`.

    ``c_s`` is the (adiabatic, or isothermal for ``gamma = 1``) sound speed; the result has
    its units.
    """
    return np.sqrt(8.0 / (np.pi * _f(gamma))) * _f(c_s)


def epstein_drag_coefficient(
    rho_g: ArrayLike, rho_d: ArrayLike, s: ArrayLike, rho_grain: ArrayLike, c_s: ArrayLike,
    gamma: ArrayLike = 1.0,
) -> np.ndarray:
    """Epstein drag coefficient :math:`K = \\rho_d\\rho_g v_{\\rm th}/(\\rho_{\\rm grain}s)` [g cm^-3 s^-1].

    Thesis eq. 2.3 corrected (see the module docstring: the printed :math:`4\\pi/3` cancels);
    Epstein (1924); Laibe & Price (2012). Drag force per unit volume on the dust is
    :math:`-K(v_d - v_g)`.
    """
    return _f(rho_d) * _f(rho_g) * thermal_speed(c_s, gamma) / (_f(rho_grain) * _f(s))


def epstein_stopping_time(
    s: ArrayLike, rho_grain: ArrayLike, rho_g: ArrayLike, c_s: ArrayLike,
    gamma: ArrayLike = 1.0, rho_d: ArrayLike | None = None,
) -> np.ndarray:
    """Epstein stopping time :math:`t_s = \\sqrt{\\pi\\gamma/8}\\,\\rho_{\\rm grain}s/(\\rho\\,c_s)` [s].

    Thesis eq. 2.6 corrected (module docstring); Weidenschilling (1977); Laibe & Price (2012).

    Parameters
    ----------
    s, rho_grain
        Grain radius [cm] and material density [g/cm^3].
    rho_g, c_s
        Gas density [g/cm^3] and sound speed [cm/s].
    gamma
        Adiabatic index in :math:`v_{\\rm th} = \\sqrt{8/(\\pi\\gamma)}c_s` (1: isothermal).
    rho_d
        Dust density. ``None`` (default): the stopping time of one grain, with
        :math:`\\rho = \\rho_g`. Given: the *mixture* stopping time with
        :math:`\\rho = \\rho_g + \\rho_d`, on which :math:`v_d - v_g` decays
        (Laibe & Price 2014; used by one-fluid codes and by Vericel et al. 2021).

    Examples
    --------
    A 1 mm silicate grain in gas of 1e-9 g/cm^3 at c_s = 1 km/s:
    t_s = sqrt(pi/8) * 2.6 * 0.1 / (1e-9 * 1e5) s = 1629.3 s.

    >>> round(float(epstein_stopping_time(0.1, 2.6, 1e-9, 1e5)), 1)
    1629.3
    """
    rho = _f(rho_g) if rho_d is None else _f(rho_g) + _f(rho_d)
    return _f(rho_grain) * _f(s) / (rho * thermal_speed(c_s, gamma))


@njit(cache=True)
def epstein_stopping_time_scalar(s: float, rho_grain: float, rho_g: float, c_s: float, gamma: float = 1.0) -> float:
    """:func:`epstein_stopping_time` of one grain for compiled kernels (scalars, no ``rho_d``).

    The same formula, thesis eq. 2.6 corrected (module docstring), Weidenschilling (1977),
    Laibe & Price (2012): :math:`t_s = \\sqrt{\\pi\\gamma/8}\\,\\rho_{\\rm grain}s/(\\rho_g c_s)`.
    numba kernels (the particle drag of :mod:`dustygas.particles`) call this one; tests check
    that both agree.

    >>> round(epstein_stopping_time_scalar(0.1, 2.6, 1e-9, 1e5), 1)
    1629.3
    """
    return rho_grain * s / (rho_g * math.sqrt(8.0 / (math.pi * gamma)) * c_s)


def epstein_grain_size(
    taus: ArrayLike, rho_grain: ArrayLike, rho_g: ArrayLike, c_s: ArrayLike, Omega: ArrayLike,
    gamma: ArrayLike = 1.0, rho_d: ArrayLike | None = None,
) -> np.ndarray:
    """Grain radius [cm] whose Epstein stopping time is :math:`\\tau_s/\\Omega` (inverse of eq. 2.6).

    :math:`s = \\tau_s\\sqrt{8/(\\pi\\gamma)}\\,\\rho c_s/(\\rho_{\\rm grain}\\Omega)`; with
    ``taus = 1`` this is the size that drifts fastest, :math:`\\sqrt{8/(\\pi\\gamma)}` times
    the thesis's :math:`s_{\\rm drift}` (eq. 3.9, :func:`dustygas.physics.growth.drift_size`).
    """
    rho = _f(rho_g) if rho_d is None else _f(rho_g) + _f(rho_d)
    return _f(taus) * rho * thermal_speed(c_s, gamma) / (_f(rho_grain) * _f(Omega))


def stokes_number(t_s: ArrayLike, Omega: ArrayLike) -> np.ndarray:
    """Dimensionless stopping time (Stokes number) :math:`\\tau_s = t_s\\Omega` (thesis eq. 1.1)."""
    return _f(t_s) * _f(Omega)


def mean_free_path(
    rho_g: ArrayLike, mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT,
    cross_section: float = sigma_H2,
) -> np.ndarray:
    """Mean free path of gas molecules :math:`\\lambda = \\mu m_H/(\\rho_g\\sigma_{H_2})` [cm].

    Weidenschilling (1977); Birnstiel et al. (2010). Defaults:
    :math:`\\mu = 2.34`, :math:`\\sigma_{H_2} = 2\\times10^{-15}` cm^2 (:mod:`dustygas.units`).
    """
    return mean_molecular_weight * m_H / (_f(rho_g) * cross_section)


def molecular_viscosity(
    rho_g: ArrayLike, c_s: ArrayLike, gamma: ArrayLike = 1.0,
    mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT, cross_section: float = sigma_H2,
) -> np.ndarray:
    """Molecular kinematic viscosity :math:`\\nu_{\\rm mol} = \\lambda v_{\\rm th}/2` [cm^2/s]."""
    return 0.5 * mean_free_path(rho_g, mean_molecular_weight, cross_section) * thermal_speed(c_s, gamma)


def reynolds_number(s: ArrayLike, delta_v: ArrayLike, nu_mol: ArrayLike) -> np.ndarray:
    """Particle Reynolds number :math:`Re = 2s|\\Delta v|/\\nu_{\\rm mol}` (grain diameter 2s)."""
    return 2.0 * _f(s) * np.abs(_f(delta_v)) / _f(nu_mol)


def stokes_drag_coefficient(Re: ArrayLike) -> np.ndarray:
    """Drag coefficient :math:`C_D(Re)`: 24/Re, 24 Re^-0.6, 0.44 (Weidenschilling 1977).

    Branches: :math:`Re < 1`, :math:`1 \\le Re < 800`, :math:`Re \\ge 800`.

    >>> [round(float(c), 4) for c in stokes_drag_coefficient([0.5, 1.0, 799.999, 800.0])]
    [48.0, 24.0, 0.4349, 0.44]
    """
    Re = _f(Re)
    with np.errstate(divide="ignore"):
        return np.where(Re < REYNOLDS_LINEAR, 24.0 / Re,
                        np.where(Re < REYNOLDS_QUADRATIC, 24.0 * Re**-0.6, 0.44))


def stokes_stopping_time(
    s: ArrayLike, rho_grain: ArrayLike, rho_g: ArrayLike, delta_v: ArrayLike, nu_mol: ArrayLike,
) -> np.ndarray:
    """Stokes-regime stopping time :math:`t_s = 8\\rho_{\\rm grain}s/(3C_D\\rho_g|\\Delta v|)` [s].

    For :math:`Re < 1` the closed form :math:`2\\rho_{\\rm grain}s^2/(9\\nu_{\\rm mol}\\rho_g)` is
    used, which is the same expression and stays finite at :math:`\\Delta v = 0`.
    """
    s, rho_grain, rho_g = _f(s), _f(rho_grain), _f(rho_g)
    dv, nu = np.abs(_f(delta_v)), _f(nu_mol)
    Re = reynolds_number(s, dv, nu)
    linear = 2.0 * rho_grain * s**2 / (9.0 * nu * rho_g)
    with np.errstate(divide="ignore", invalid="ignore"):
        nonlinear = 8.0 * rho_grain * s / (3.0 * stokes_drag_coefficient(Re) * rho_g * dv)
    return np.where(Re < REYNOLDS_LINEAR, linear, nonlinear)


def stopping_time(
    s: ArrayLike, rho_grain: ArrayLike, rho_g: ArrayLike, c_s: ArrayLike,
    delta_v: ArrayLike = 0.0, gamma: ArrayLike = 1.0,
    mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT, cross_section: float = sigma_H2,
) -> np.ndarray:
    """Stopping time of one grain, Epstein for :math:`s < 9\\lambda/4` and Stokes above [s].

    Weidenschilling (1977); Birnstiel et al. (2010); the switch at :math:`s = 9\\lambda/4` makes
    :math:`t_s` continuous for :math:`Re < 1`. ``delta_v`` is the grain's speed relative to
    the gas [cm/s]; it only matters in the Stokes regime at :math:`Re \\ge 1`.
    """
    lam = mean_free_path(rho_g, mean_molecular_weight, cross_section)
    nu = 0.5 * lam * thermal_speed(c_s, gamma)
    epstein = epstein_stopping_time(s, rho_grain, rho_g, c_s, gamma)
    stokes = stokes_stopping_time(s, rho_grain, rho_g, delta_v, nu)
    return np.where(_f(s) < 2.25 * lam, epstein, stokes)


def dust_fraction(rho_d: ArrayLike, rho_g: ArrayLike) -> np.ndarray:
    """Dust fraction :math:`\\epsilon = \\rho_d/(\\rho_d+\\rho_g)` (thesis eq. 2.7)."""
    return _f(rho_d) / (_f(rho_d) + _f(rho_g))


def dust_to_gas_ratio(rho_d: ArrayLike, rho_g: ArrayLike) -> np.ndarray:
    """Dust-to-gas ratio :math:`\\mu = \\rho_d/\\rho_g` (thesis eq. 2.8; YJ07's :math:`\\epsilon`)."""
    return _f(rho_d) / _f(rho_g)


def ratio_to_fraction(mu: ArrayLike) -> np.ndarray:
    """:math:`\\epsilon = \\mu/(1+\\mu)` (eqs. 2.7-2.8).

    >>> float(ratio_to_fraction(1.0)), float(fraction_to_ratio(0.5))
    (0.5, 1.0)
    """
    mu = _f(mu)
    return mu / (1.0 + mu)


def fraction_to_ratio(eps: ArrayLike) -> np.ndarray:
    """:math:`\\mu = \\epsilon/(1-\\epsilon)` (eqs. 2.7-2.8)."""
    eps = _f(eps)
    return eps / (1.0 - eps)


def mixture_stopping_time(K: ArrayLike, rho_g: ArrayLike, rho_d: ArrayLike) -> np.ndarray:
    """Stopping time of the relative velocity for a drag coefficient ``K``:
    :math:`t_s = \\rho_g\\rho_d/(K(\\rho_g+\\rho_d))`.

    Eqs. 2.5a-b with a constant :math:`K`: :math:`v_d - v_g` decays as :math:`e^{-t/t_s}` (Laibe &
    Price 2011, the dustybox); the one-fluid equations (Laibe & Price 2014)
    use this :math:`t_s`. For the Epstein :math:`K` it equals :func:`epstein_stopping_time` with
    ``rho_d``.

    >>> float(mixture_stopping_time(0.35, 1.0, 1.0))  # Phantom's dustybox: 1/(2K)
    1.4285714285714286
    """
    rho_g, rho_d = _f(rho_g), _f(rho_d)
    return rho_g * rho_d / (_f(K) * (rho_g + rho_d))
