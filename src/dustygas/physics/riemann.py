"""Exact solution of the isothermal Riemann problem (shock tubes).

Isothermal gas, ``P = c_s^2 rho``, initially in two uniform states ``(rho_L, u_L)`` for
``x < 0`` and ``(rho_R, u_R)`` for ``x > 0``. The solution depends on ``xi = x / t`` and
consists of a left and a right wave (shock or rarefaction) around a star state
``(rho*, u*)``; transverse velocities are carried passively and jump at the contact
``xi = u*`` (Toro 2009, ch. 4, specialised to ``gamma -> 1``; LeVeque 2002, §14.6).

Across a shock into state K the Rankine-Hugoniot conditions give the velocity change
``c_s (rho* - rho_K) / sqrt(rho* rho_K)`` and the shock speed ``u_K -/+ c_s sqrt(rho*/rho_K)``;
across a rarefaction the Riemann invariant ``u +/- c_s ln rho`` is constant, so the velocity
change is ``c_s ln(rho*/rho_K)`` and inside the fan ``u = xi +/- c_s``. The star density is the
root of

.. math:: f(\\rho_*) = g(\\rho_*, \\rho_L) + g(\\rho_*, \\rho_R) + (u_R - u_L)/c_s = 0, \\quad
    g(\\rho, \\rho_K) = \\begin{cases} (\\rho - \\rho_K)/\\sqrt{\\rho\\rho_K} & \\rho > \\rho_K \\\\
    \\ln(\\rho/\\rho_K) & \\rho \\le \\rho_K \\end{cases}

which is increasing in ``rho*`` and has exactly one root for any data (no vacuum forms in
isothermal gas).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["IsothermalRiemannSolution", "isothermal_star_state", "isothermal_riemann"]


def _g(rho: float, rho_k: float) -> float:
    if rho > rho_k:
        return (rho - rho_k) / math.sqrt(rho * rho_k)
    return math.log(rho / rho_k)


def isothermal_star_state(rho_l: float, u_l: float, rho_r: float, u_r: float, cs: float = 1.0) -> tuple[float, float]:
    """Density and velocity ``(rho*, u*)`` between the two waves.

    >>> rho, u = isothermal_star_state(1.0, 0.0, 1.0, 0.0)
    >>> rho, u
    (1.0, 0.0)
    """
    if min(rho_l, rho_r) <= 0 or cs <= 0:
        raise ValueError("densities and sound speed must be positive")
    du = (u_r - u_l) / cs

    def f(lnrho: float) -> float:
        rho = math.exp(lnrho)
        return _g(rho, rho_l) + _g(rho, rho_r) + du

    lo = math.log(min(rho_l, rho_r)) - 1.0
    hi = math.log(max(rho_l, rho_r)) + 1.0
    while f(lo) > 0:
        lo -= 2.0 * (hi - lo)
    while f(hi) < 0:
        hi += 2.0 * (hi - lo)
    if f(lo) == 0.0:
        rho = math.exp(lo)
    elif f(hi) == 0.0:
        rho = math.exp(hi)
    else:
        from scipy.optimize import brentq  # imported here: scipy.optimize costs every process 0.2 s

        rho = math.exp(brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=200))
    u = 0.5 * (u_l - cs * _g(rho, rho_l) + u_r + cs * _g(rho, rho_r))
    return rho, u


class IsothermalRiemannSolution(NamedTuple):
    """Sampled solution and its wave structure."""

    rho: np.ndarray
    u: np.ndarray
    v: np.ndarray  # transverse velocity (passive)
    rho_star: float
    u_star: float
    left_wave: tuple[float, float]  # (head, tail) speeds; equal for a shock
    right_wave: tuple[float, float]


def isothermal_riemann(xi: ArrayLike, rho_l: float, u_l: float, rho_r: float, u_r: float, cs: float = 1.0,
                       v_l: float = 0.0, v_r: float = 0.0) -> IsothermalRiemannSolution:
    """Sample the exact solution at ``xi = x / t`` (see module docstring).

    Examples
    --------
    A density jump of 10 at rest: a left rarefaction and a right shock.

    >>> s = isothermal_riemann([-1.0, 0.0, 1.0], 1.0, 0.0, 0.1, 0.0)
    >>> round(s.rho_star, 6), round(s.u_star, 6), [round(w, 6) for w in s.right_wave]
    (0.306928, 1.181141, [1.751937, 1.751937])
    """
    xi = np.asarray(xi, dtype=np.float64)
    rho_s, u_s = isothermal_star_state(rho_l, u_l, rho_r, u_r, cs)
    if rho_s > rho_l:
        s = u_l - cs * math.sqrt(rho_s / rho_l)
        left = (s, s)
    else:
        left = (u_l - cs, u_s - cs)
    if rho_s > rho_r:
        s = u_r + cs * math.sqrt(rho_s / rho_r)
        right = (s, s)
    else:
        right = (u_s + cs, u_r + cs)
    rho = np.empty_like(xi)
    u = np.empty_like(xi)
    # left of the left wave, inside its fan, star region, inside the right fan, right state
    m = xi < left[0]
    rho[m], u[m] = rho_l, u_l
    m = (xi >= left[0]) & (xi < left[1])
    u[m] = xi[m] + cs
    rho[m] = rho_l * np.exp((u_l - u[m]) / cs)
    m = (xi >= left[1]) & (xi <= right[0])
    rho[m], u[m] = rho_s, u_s
    m = (xi > right[0]) & (xi <= right[1])
    u[m] = xi[m] - cs
    rho[m] = rho_r * np.exp((u[m] - u_r) / cs)
    m = xi > right[1]
    rho[m], u[m] = rho_r, u_r
    v = np.where(xi < u_s, v_l, v_r)
    return IsothermalRiemannSolution(rho, u, v, rho_s, u_s, left, right)
