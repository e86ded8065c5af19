"""Exact solution of the Riemann problem for an ideal gas (Toro 2009, *Riemann Solvers and
Numerical Methods for Fluid Dynamics*, chapter 4).

Two uniform states :math:`(\\rho_L, u_L, P_L)` and :math:`(\\rho_R, u_R, P_R)` meet at
:math:`x = x_0` at :math:`t = 0`. The star-region pressure :math:`P_*` is the root of

.. math:: f_L(P) + f_R(P) + u_R - u_L = 0,

with, for side :math:`K`, :math:`A_K = 2/((\\gamma+1)\\rho_K)`, :math:`B_K = (\\gamma-1)P_K/(\\gamma+1)`,

.. math::

    f_K(P) = \\begin{cases}
    (P - P_K)\\sqrt{A_K/(P + B_K)} & P > P_K \\text{ (shock)}\\\\
    \\frac{2 c_K}{\\gamma - 1}\\left[(P/P_K)^{(\\gamma-1)/2\\gamma} - 1\\right] & P \\le P_K \\text{ (rarefaction)}
    \\end{cases}

(Toro eqs. 4.5-4.7), and :math:`u_* = \\tfrac12(u_L + u_R) + \\tfrac12[f_R(P_*) - f_L(P_*)]`.
The self-similar solution is then sampled at :math:`\\xi = (x - x_0)/t` (Toro Sect. 4.5).
The shock tube of Sod (1978) is ``RiemannSolution(1, 0, 1, 0.125, 0, 0.1, gamma)``.

Examples
--------
Toro's test 1 (Sod, gamma = 1.4), Table 4.3: P* = 0.30313, u* = 0.92745

>>> s = RiemannSolution(1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 1.4)
>>> round(s.p_star, 5), round(s.u_star, 5), round(s.rho_star_left, 5), round(s.rho_star_right, 5)
(0.30313, 0.92745, 0.42632, 0.26557)
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["RiemannSolution"]


class RiemannSolution:
    """Exact ideal-gas Riemann solution (see module docstring); call it with :math:`\\xi = x/t`.

    Parameters
    ----------
    rho_left, u_left, p_left, rho_right, u_right, p_right
        Initial states (densities and pressures > 0).
    gamma
        Adiabatic index (> 1).

    Attributes
    ----------
    p_star, u_star
        Pressure and velocity between the left and right waves.
    rho_star_left, rho_star_right
        Densities on either side of the contact discontinuity.
    shock_speed_left, shock_speed_right
        Shock speeds (``nan`` where that wave is a rarefaction).
    """

    def __init__(self, rho_left: float, u_left: float, p_left: float, rho_right: float, u_right: float,
                 p_right: float, gamma: float):
        if min(rho_left, p_left, rho_right, p_right) <= 0 or gamma <= 1:
            raise ValueError("need positive densities and pressures and gamma > 1")
        self.gamma = g = float(gamma)
        self.left = (float(rho_left), float(u_left), float(p_left))
        self.right = (float(rho_right), float(u_right), float(p_right))
        cl = math.sqrt(g * p_left / rho_left)
        cr = math.sqrt(g * p_right / rho_right)
        self.c_left, self.c_right = cl, cr
        if 2.0 / (g - 1.0) * (cl + cr) <= u_right - u_left:
            raise ValueError("the initial states generate vacuum")

        def f(p: float, rho: float, pk: float, ck: float) -> float:
            if p > pk:
                a = 2.0 / ((g + 1.0) * rho)
                b = (g - 1.0) / (g + 1.0) * pk
                return (p - pk) * math.sqrt(a / (p + b))
            return 2.0 * ck / (g - 1.0) * ((p / pk) ** ((g - 1.0) / (2.0 * g)) - 1.0)

        def residual(p: float) -> float:
            return f(p, rho_left, p_left, cl) + f(p, rho_right, p_right, cr) + u_right - u_left

        hi = max(p_left, p_right)
        while residual(hi) < 0:
            hi *= 2.0
        from scipy.optimize import brentq  # imported here: scipy.optimize costs every process 0.2 s

        self.p_star = ps = brentq(residual, 1e-14 * hi, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps, maxiter=500)
        self.u_star = us = 0.5 * (u_left + u_right) + 0.5 * (f(ps, rho_right, p_right, cr) - f(ps, rho_left, p_left, cl))
        gm = (g - 1.0) / (g + 1.0)
        if ps > p_left:
            self.rho_star_left = rho_left * (ps / p_left + gm) / (gm * ps / p_left + 1.0)
            self.shock_speed_left = u_left - cl * math.sqrt((g + 1.0) / (2 * g) * ps / p_left + (g - 1.0) / (2 * g))
        else:
            self.rho_star_left = rho_left * (ps / p_left) ** (1.0 / g)
            self.shock_speed_left = math.nan
        if ps > p_right:
            self.rho_star_right = rho_right * (ps / p_right + gm) / (gm * ps / p_right + 1.0)
            self.shock_speed_right = u_right + cr * math.sqrt((g + 1.0) / (2 * g) * ps / p_right + (g - 1.0) / (2 * g))
        else:
            self.rho_star_right = rho_right * (ps / p_right) ** (1.0 / g)
            self.shock_speed_right = math.nan

    def __call__(self, xi: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Density, velocity and pressure at :math:`\\xi = (x - x_0)/t`."""
        xi = np.asarray(xi, dtype=np.float64)
        g, ps, us = self.gamma, self.p_star, self.u_star
        rho = np.empty_like(xi)
        u = np.empty_like(xi)
        p = np.empty_like(xi)
        for side, sign in ((self.left, -1.0), (self.right, 1.0)):
            rk, uk, pk = side
            ck = self.c_left if sign < 0 else self.c_right
            rstar = self.rho_star_left if sign < 0 else self.rho_star_right
            # work in the frame where this side is the "left" one: s = sign * xi
            mask = (xi < us) if sign < 0 else (xi >= us)
            x = xi[mask]
            if ps > pk:  # shock
                speed = self.shock_speed_left if sign < 0 else self.shock_speed_right
                outside = (x < speed) if sign < 0 else (x > speed)
                r = np.where(outside, rk, rstar)
                v = np.where(outside, uk, us)
                pr = np.where(outside, pk, ps)
            else:  # rarefaction
                cstar = ck * (ps / pk) ** ((g - 1.0) / (2.0 * g))
                head = uk + sign * ck
                tail = us + sign * cstar
                outside = (x < head) if sign < 0 else (x > head)
                inside_fan = ~outside & ((x < tail) if sign < 0 else (x > tail))
                fan = 2.0 / (g + 1.0) - sign * (g - 1.0) / ((g + 1.0) * ck) * (uk - x)
                fan = np.maximum(fan, 0.0)
                r = np.where(outside, rk, np.where(inside_fan, rk * fan ** (2.0 / (g - 1.0)), rstar))
                v = np.where(outside, uk, np.where(
                    inside_fan, 2.0 / (g + 1.0) * (-sign * ck + (g - 1.0) / 2.0 * uk + x), us))
                pr = np.where(outside, pk, np.where(inside_fan, pk * fan ** (2.0 * g / (g - 1.0)), ps))
            rho[mask], u[mask], p[mask] = r, v, pr
        return rho, u, p
