"""Artificial viscosity and conductivity in signal-velocity form, and the viscosity switch.

Shock capturing (not in thesis eq. 3.2, which omits it; see Monaghan 1997, Price 2012 Sect. 4,
Price et al. 2018 Sect. 2.2.7). For an approaching pair (:math:`\\mathbf v_{ab}\\cdot\\hat r_{ab} < 0`)

.. math::

    q^a_{ab} = -\\tfrac12 \\rho_a v_{{\\rm sig},a}\\, \\mathbf v_{ab}\\cdot\\hat r_{ab},
    \\qquad v_{{\\rm sig},a} = \\alpha_a c_{s,a} + \\beta |\\mathbf v_{ab}\\cdot\\hat r_{ab}|,

entering the momentum equation as
:math:`-\\sum_b m_b [q^a_{ab}\\nabla_a W_{ab}(h_a)/(\\Omega_a\\rho_a^2) + q^b_{ab}\\nabla_a W_{ab}(h_b)/(\\Omega_b\\rho_b^2)]`
and heating particle :math:`a` at the rate
:math:`\\sum_b m_b q^a_{ab}\\, \\mathbf v_{ab}\\cdot\\nabla_a W_{ab}(h_a)/(\\Omega_a\\rho_a^2)`, so that
total energy is conserved pair by pair.

Artificial conductivity (Price 2008) smooths the thermal energy at contact discontinuities:

.. math::

    \\left(\\frac{du_a}{dt}\\right)_{\\rm cond} = \\sum_b m_b \\alpha_u v^u_{\\rm sig} (u_a - u_b)
    \\tfrac12\\left[\\frac{F_{ab}(h_a)}{\\Omega_a\\rho_a} + \\frac{F_{ab}(h_b)}{\\Omega_b\\rho_b}\\right],
    \\qquad v^u_{\\rm sig} = \\sqrt{\\frac{|P_a - P_b|}{\\bar\\rho_{ab}}},

with :math:`F_{ab} = \\partial W/\\partial r \\le 0`.

Viscosity switch (Morris & Monaghan 1997, with the source of Rosswog et al. 2000): each particle
carries its own :math:`\\alpha_a`, evolved by

.. math::

    \\frac{d\\alpha_a}{dt} = -\\frac{\\alpha_a - \\alpha_{\\min}}{\\tau_a}
    + \\max(-\\nabla\\cdot\\mathbf v_a, 0)\\,(\\alpha_{\\max} - \\alpha_a),
    \\qquad \\tau_a = \\frac{h_a}{\\sigma c_{s,a}},

so that :math:`\\alpha` rises in converging flow and decays over a few smoothing lengths behind
a shock (:math:`\\sigma \\approx 0.1`).

Cullen & Dehnen (2010) switch, in the form of Price et al. (2018, eqs. 39-41): the shock
indicator is the *rate* at which the flow starts to converge,
:math:`A_a = \\xi_a\\max(-d(\\nabla\\cdot\\mathbf v_a)/dt, 0)`, limited in shear flows by
:math:`\\xi_a = (\\nabla\\cdot\\mathbf v)^2/[(\\nabla\\cdot\\mathbf v)^2 + |\\nabla\\times\\mathbf v|^2 + 10^{-4} c_s^2/h^2]`
(Balsara 1995), giving :math:`\\alpha_{\\rm loc} = \\min(10 h_a^2 A_a/c_{s,a}^2, \\alpha_{\\max})`;
:math:`\\alpha_a` jumps to :math:`\\alpha_{\\rm loc}` when larger and otherwise relaxes to it as
:math:`\\exp(-\\sigma c_s\\Delta t/h)`. Here :math:`d(\\nabla\\cdot\\mathbf v)/dt` is the change of
:math:`\\nabla\\cdot\\mathbf v` over the last step divided by the step (Phantom uses the
divergence of the acceleration instead), so :math:`\\alpha` responds one step later.
"""

from __future__ import annotations

import math

from numba import njit, prange

__all__ = ["viscous_pair", "conductivity_signal", "signal_speed", "morris_monaghan_rate", "cullen_dehnen_alpha"]


@njit(cache=True)
def viscous_pair(vdotr, alpha_a, cs_a, alpha_b, cs_b, beta, ombar_a, ombar_b):
    """:math:`q^a_{ab}/(\\Omega_a\\rho_a^2)` and :math:`q^b_{ab}/(\\Omega_b\\rho_b^2)` for ``vdotr < 0``.

    ``ombar`` is :math:`1/(\\Omega\\rho)`; both results are >= 0 (zero for receding pairs).
    """
    vneg = min(vdotr, 0.0)  # branch-free: zero for receding pairs
    qa = -0.5 * (alpha_a * cs_a - beta * vneg) * vneg * ombar_a
    qb = -0.5 * (alpha_b * cs_b - beta * vneg) * vneg * ombar_b
    return qa, qb


@njit(cache=True)
def conductivity_signal(P_a, P_b, rho_a, rho_b):
    """:math:`v^u_{\\rm sig} = \\sqrt{|P_a - P_b|/\\bar\\rho}` (Price 2008)."""
    return math.sqrt(abs(P_a - P_b) * 2.0 / (rho_a + rho_b))


@njit(cache=True)
def signal_speed(cs_a, cs_b, vdotr, beta):
    """Pair signal speed for the Courant condition: :math:`\\max(c_a, c_b) + \\beta\\max(0, -\\mathbf v_{ab}\\cdot\\hat r)`."""
    return max(cs_a, cs_b) - beta * min(vdotr, 0.0)


@njit(parallel=True, cache=True)
def morris_monaghan_rate(alpha, divv, h, cs, alpha_min, alpha_max, sigma, dalpha_dt):
    """:math:`d\\alpha_a/dt` of the Morris & Monaghan (1997) switch (module docstring)."""
    for a in prange(alpha.shape[0]):
        decay = (alpha[a] - alpha_min) * sigma * cs[a] / h[a]
        source = max(-divv[a], 0.0) * (alpha_max - alpha[a])
        dalpha_dt[a] = source - decay


@njit(parallel=True, cache=True)
def cullen_dehnen_alpha(alpha, divv, divv_old, curlv, h, cs, dt, alpha_min, alpha_max, sigma):
    """Update ``alpha`` in place with the Cullen & Dehnen (2010) switch (module docstring)."""
    for a in prange(alpha.shape[0]):
        c2h2 = cs[a] * cs[a] / (h[a] * h[a])
        d2 = divv[a] * divv[a]
        xi = d2 / (d2 + curlv[a] * curlv[a] + 1e-4 * c2h2) if c2h2 > 0.0 else 0.0
        rate = (divv[a] - divv_old[a]) / dt
        A = xi * max(-rate, 0.0)
        loc = min(10.0 * A / c2h2, alpha_max) if c2h2 > 0.0 else alpha_max
        loc = max(loc, alpha_min)
        if loc >= alpha[a]:
            alpha[a] = loc
        else:
            alpha[a] = loc + (alpha[a] - loc) * math.exp(-sigma * cs[a] * dt / h[a])
