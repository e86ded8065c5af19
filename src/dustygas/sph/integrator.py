"""Kick-drift-kick leapfrog for SPH particles (Price et al. 2018, Sect. 2.3.1; Verlet 1967).

One step of length :math:`\\Delta t` from :math:`(\\mathbf x^n, \\mathbf v^n, u^n)` with the
accelerations :math:`\\mathbf a^n` of the current state:

.. math::

    \\mathbf v^{n+1/2} &= \\mathbf v^n + \\tfrac12\\Delta t\\,\\mathbf a^n, \\\\
    \\mathbf x^{n+1} &= \\mathbf x^n + \\Delta t\\,\\mathbf v^{n+1/2}, \\\\
    \\mathbf v^* &= \\mathbf v^{n+1/2} + \\tfrac12\\Delta t\\,\\mathbf a^n
        \\quad\\text{(predicted velocity for the velocity-dependent forces)}, \\\\
    \\mathbf a^{n+1} &= \\mathbf a(\\mathbf x^{n+1}, \\mathbf v^*), \\\\
    \\mathbf v^{n+1} &= \\mathbf v^{n+1/2} + \\tfrac12\\Delta t\\,\\mathbf a^{n+1},

and the same for the thermal energy :math:`u` and the viscosity parameters :math:`\\alpha`.
For position-dependent forces it is the symplectic, time-reversible velocity Verlet scheme
(second order; energy errors bounded and :math:`\\propto\\Delta t^2`); with viscosity the
predictor keeps it second order. The smoothing length is predicted for the next density
iteration from :math:`dh/dt = h\\,\\nabla\\cdot\\mathbf v/d`.
"""

from __future__ import annotations

import math

from numba import njit, prange

__all__ = ["kick", "drift_and_predict"]


@njit(parallel=True, cache=True)
def kick(vel, acc, u, dudt, alpha, dalpha, dt, evolve_u, evolve_alpha, alpha_lo, alpha_hi):
    """:math:`v \\mathrel{+}= \\Delta t\\, a` (and :math:`u`, :math:`\\alpha`) for every particle."""
    for a in prange(vel.shape[0]):
        vel[a, 0] += dt * acc[a, 0]
        vel[a, 1] += dt * acc[a, 1]
        vel[a, 2] += dt * acc[a, 2]
        if evolve_u:
            u[a] += dt * dudt[a]
        if evolve_alpha:
            al = alpha[a] + dt * dalpha[a]
            alpha[a] = min(max(al, alpha_lo), alpha_hi)


@njit(parallel=True, cache=True)
def drift_and_predict(pos, vel, acc, u, dudt, alpha, dalpha, h, divv, dt, ndim, lo, length, periodic,
                      evolve_u, evolve_alpha, alpha_lo, alpha_hi, vel_pred, u_pred, alpha_pred):
    """Drift positions (wrapping periodic ones), predict :math:`h`, :math:`v^*`, :math:`u^*`, :math:`\\alpha^*`."""
    for a in prange(pos.shape[0]):
        for d in range(3):
            x = pos[a, d] + dt * vel[a, d]
            if periodic[d] and (x < lo[d] or x >= lo[d] + length[d]):
                x = lo[d] + (x - lo[d]) % length[d]
                if x >= lo[d] + length[d]:
                    x = lo[d]
            pos[a, d] = x
            vel_pred[a, d] = vel[a, d] + 0.5 * dt * acc[a, d]
        h[a] *= math.exp(dt * divv[a] / ndim)
        u_pred[a] = u[a] + 0.5 * dt * dudt[a] if evolve_u else u[a]
        if evolve_alpha:
            al = alpha[a] + 0.5 * dt * dalpha[a]
            alpha_pred[a] = min(max(al, alpha_lo), alpha_hi)
        else:
            alpha_pred[a] = alpha[a]
