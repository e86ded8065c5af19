"""Steady drift of gas and dust in a pressure-supported disk (Nakagawa, Sekiya & Hayashi 1986).

Frame and units: local shearing sheet, x radial, y azimuthal, velocities measured relative to
the Keplerian shear flow and given in units of :math:`\\eta v_K` (pass ``eta_vK`` for other
units). The gas feels the global pressure gradient as the force :math:`2\\eta v_K \\Omega\\,\\hat x`
(thesis eq. 4.2b); dust species :math:`j` with stopping time :math:`\\tau_j = t_{s,j}\\Omega` and
dust-to-gas density ratio :math:`\\mu_j = \\rho_{d,j}/\\rho_g` couple to it by linear drag.

Single species (thesis eq. 4.8, Nakagawa et al. 1986), with :math:`D = (1+\\mu)^2 + \\tau_s^2`:

.. math::

    u_x = \\frac{2\\mu\\tau_s}{D}, \\quad u_y = -\\frac{1+\\mu+\\tau_s^2}{D}, \\quad
    v_x = -\\frac{2\\tau_s}{D}, \\quad v_y = -\\frac{1+\\mu}{D}.

N species (Tanaka, Himeno & Ida 2005; Bai & Stone 2010c, eqs. 6-9; Benítez-Llambay, Krapp &
Pessah 2019, eqs. 79-82), with :math:`A = \\sum_j \\mu_j/(1+\\tau_j^2)`,
:math:`B = \\sum_j \\mu_j\\tau_j/(1+\\tau_j^2)` and :math:`\\Delta = (1+A)^2 + B^2`:

.. math::

    u_x = \\frac{2B}{\\Delta}, \\quad u_y = -\\frac{1+A}{\\Delta}, \\quad
    v_{x,j} = \\frac{u_x + 2\\tau_j u_y}{1+\\tau_j^2}, \\quad
    v_{y,j} = \\frac{u_y - \\tau_j u_x/2}{1+\\tau_j^2}.

The N-species form reduces to eq. 4.8 for one species (:math:`\\Delta = D/(1+\\tau_s^2)`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["NSHEquilibrium", "nsh_velocities", "nsh_velocities_multi", "nsh_velocities_moments"]


class NSHEquilibrium(NamedTuple):
    """Steady velocities; dust entries have a trailing species axis in the N-species form."""

    gas_vx: np.ndarray
    gas_vy: np.ndarray
    dust_vx: np.ndarray
    dust_vy: np.ndarray


def nsh_velocities(taus: ArrayLike, mu: ArrayLike, eta_vK: ArrayLike = 1.0) -> NSHEquilibrium:
    """NSH drift velocities of gas and one dust species (thesis eq. 4.8).

    Parameters
    ----------
    taus
        Dimensionless stopping time :math:`\\tau_s = t_s\\Omega` (thesis eq. 1.1), > 0.
    mu
        Dust-to-gas density ratio :math:`\\mu = \\rho_d/\\rho_g` (thesis eq. 2.8; YJ07's
        :math:`\\epsilon`), >= 0.
    eta_vK
        Velocity unit :math:`\\eta v_K`; 1 gives velocities in units of :math:`\\eta v_K`.

    Returns
    -------
    NSHEquilibrium
        ``(gas_vx, gas_vy, dust_vx, dust_vy)`` broadcast over the inputs.

    Examples
    --------
    YJ07 linA (tau_s = 0.1, eps = 3): U = (+0.03747658, -0.25046846), W = (-0.01249219, -0.24984385)

    >>> eq = nsh_velocities(0.1, 3.0)
    >>> [round(float(v), 8) for v in eq]
    [0.03747658, -0.25046846, -0.01249219, -0.24984385]
    """
    taus = np.asarray(taus, dtype=np.float64)
    mu = np.asarray(mu, dtype=np.float64)
    eta_vK = np.asarray(eta_vK, dtype=np.float64)
    d = (1.0 + mu) ** 2 + taus**2
    return NSHEquilibrium(
        gas_vx=2.0 * mu * taus / d * eta_vK,
        gas_vy=-(1.0 + mu + taus**2) / d * eta_vK,
        dust_vx=-2.0 * taus / d * eta_vK,
        dust_vy=-(1.0 + mu) / d * eta_vK,
    )


def nsh_velocities_multi(taus: ArrayLike, mus: ArrayLike, eta_vK: ArrayLike = 1.0) -> NSHEquilibrium:
    """NSH drift velocities of gas and N dust species sharing one gas.

    Parameters
    ----------
    taus, mus
        Stopping times :math:`\\tau_j` and dust-to-gas ratios :math:`\\mu_j`, shape ``(..., N)``;
        the last axis is the species axis.
    eta_vK
        Velocity unit, broadcast against the leading axes.

    Returns
    -------
    NSHEquilibrium
        Gas velocities of shape ``(...)``, dust velocities of shape ``(..., N)``.
    """
    taus = np.atleast_1d(np.asarray(taus, dtype=np.float64))
    mus = np.atleast_1d(np.asarray(mus, dtype=np.float64))
    taus, mus = np.broadcast_arrays(taus, mus)
    q = 1.0 / (1.0 + taus**2)
    a = np.sum(mus * q, axis=-1)
    b = np.sum(mus * taus * q, axis=-1)
    return nsh_velocities_moments(a, b, taus, eta_vK)


def nsh_velocities_moments(a: ArrayLike, b: ArrayLike, taus: ArrayLike, eta_vK: ArrayLike = 1.0) -> NSHEquilibrium:
    """NSH drift from the moments :math:`A` and :math:`B` of the dust (module docstring).

    For a continuous size distribution :math:`\\sigma(\\tau)` (dust-to-gas ratio per unit
    stopping time) the moments are the integrals :math:`A = \\int \\sigma/(1+\\tau^2)\\,d\\tau`
    and :math:`B = \\int \\sigma\\tau/(1+\\tau^2)\\,d\\tau`, the continuum limit of the sums
    (Paardekooper, McNally & Lovascio 2020); the dust velocities are then wanted at any ``taus``
    (trailing species axis).
    """
    a = np.asarray(a, dtype=np.float64)
    b = np.asarray(b, dtype=np.float64)
    taus = np.asarray(taus, dtype=np.float64)
    eta_vK = np.asarray(eta_vK, dtype=np.float64)
    q = 1.0 / (1.0 + taus**2)
    delta = (1.0 + a) ** 2 + b**2
    ux = 2.0 * b / delta
    uy = -(1.0 + a) / delta
    vx = (ux[..., None] + 2.0 * taus * uy[..., None]) * q
    vy = (uy[..., None] - 0.5 * taus * ux[..., None]) * q
    e = eta_vK[..., None] if eta_vK.ndim else eta_vK
    return NSHEquilibrium(ux * eta_vK, uy * eta_vK, vx * e, vy * e)
