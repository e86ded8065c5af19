"""Self-gravity in the shearing box: its strength, the Hill (Roche) scale, Toomre's dispersion relation.

Code units: the shearing box's ``Omega = 1`` and the gas density scale ``rho_g0 = 1`` (thesis
§4.1), so the one free constant of the Poisson equation ``∇²Φ = 4πGρ`` is

.. math:: \\tilde G = \\frac{4\\pi G \\rho_{g0}}{\\Omega^2}

(Simon et al. 2016, ApJ 822, 55, §2), i.e. ``4πG = G̃`` in code units; streaming-instability
studies with self-gravity (Johansen et al. 2007, Nature 448, 1022; Simon et al. 2016, 2017)
use values of order 0.05.

Hill sphere and Hill density
    A clump of mass ``M`` in the tidal field of the shearing sheet (potential
    ``-q Ω² x² + Ω² z²/2``) has its Lagrange points L1/L2 at
    ``r_H = (G M / (2q Ω²))^(1/3)`` from its centre, the Hill radius
    (``(GM/3Ω²)^(1/3)`` for Keplerian ``q = 3/2``; Hill 1878). A particle of the clump is bound
    when its Jacobi energy relative to the clump is below the effective potential at L1,
    ``-G M/r_H - q Ω² r_H² = -3 q Ω² r_H²``. The mean density inside the Hill sphere is the
    Hill (Roche) density ``ρ_H = 9 Ω² / (4π G)`` for ``q = 3/2`` — the density above which a
    clump can collapse against the tidal shear (Johansen et al. 2007; Simon et al. 2016, §3.3);
    in code units ``ρ_H / ρ_g0 = 9 / G̃``.

Toomre's dispersion relation
    An axisymmetric wave ``exp(i (k x - ω t))`` in a razor-thin isothermal self-gravitating
    sheet of surface density ``Σ`` and sound speed ``c_s`` obeys

    .. math:: \\omega^2 = \\kappa^2 - 2\\pi G \\Sigma |k| + c_s^2 k^2

    (Toomre 1964, ApJ 139, 1217; Goldreich & Lynden-Bell 1965, MNRAS 130, 97; exact in the
    linearised shearing sheet, not a WKB limit), ``κ`` being the epicyclic frequency. It is
    unstable (``ω² < 0``) for some ``k`` iff ``Q = c_s κ / (π G Σ) < 1``; the fastest wave has
    ``k = π G Σ / c_s²``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["gravity_parameter", "gravitational_constant", "hill_density", "hill_radius", "hill_energy",
           "toomre_q", "toomre_frequency_squared", "fastest_toomre_wavenumber"]


def gravity_parameter(G: ArrayLike, rho_g0: ArrayLike = 1.0, omega: ArrayLike = 1.0) -> np.ndarray:
    """``G̃ = 4π G ρ_g0 / Ω²`` (Simon et al. 2016).

    >>> round(float(gravity_parameter(0.05 / (4 * np.pi))), 12)
    0.05
    """
    return 4.0 * np.pi * np.asarray(G, dtype=np.float64) * np.asarray(rho_g0) / np.asarray(omega) ** 2


def gravitational_constant(g_tilde: ArrayLike, rho_g0: ArrayLike = 1.0, omega: ArrayLike = 1.0) -> np.ndarray:
    """``G = G̃ Ω² / (4π ρ_g0)``, the inverse of :func:`gravity_parameter`."""
    return np.asarray(g_tilde, dtype=np.float64) * np.asarray(omega) ** 2 / (4.0 * np.pi * np.asarray(rho_g0))


def hill_density(G: ArrayLike, omega: ArrayLike = 1.0, q: ArrayLike = 1.5) -> np.ndarray:
    """Mean density inside the Hill sphere, ``ρ_H = 3 (2q) Ω² / (4π G)`` (``9Ω²/(4πG)`` for q = 3/2).

    >>> round(float(hill_density(1.0 / (4 * np.pi))), 12)
    9.0
    """
    return 6.0 * np.asarray(q, dtype=np.float64) * np.asarray(omega) ** 2 / (4.0 * np.pi * np.asarray(G))


def hill_radius(mass: ArrayLike, G: ArrayLike, omega: ArrayLike = 1.0, q: ArrayLike = 1.5) -> np.ndarray:
    """Distance of L1/L2 from a clump of ``mass``, ``r_H = (G M / (2q Ω²))^(1/3)``.

    >>> round(float(hill_radius(3.0, 1.0)), 12)
    1.0
    """
    return np.cbrt(np.asarray(G, dtype=np.float64) * np.asarray(mass) / (2.0 * np.asarray(q) * np.asarray(omega) ** 2))


def hill_energy(mass: ArrayLike, G: ArrayLike, omega: ArrayLike = 1.0, q: ArrayLike = 1.5) -> np.ndarray:
    """Jacobi energy per unit mass at L1/L2 relative to the clump, ``-3 q Ω² r_H²``.

    A particle with ``|v - v_c|²/2 - G M/r - q Ω² Δx² + Ω² Δz²/2`` below this cannot leave
    the clump's Hill sphere.

    >>> round(float(hill_energy(3.0, 1.0)), 12)
    -4.5
    """
    return -3.0 * np.asarray(q, dtype=np.float64) * np.asarray(omega) ** 2 * hill_radius(mass, G, omega, q) ** 2


def toomre_q(cs: ArrayLike, kappa: ArrayLike, G: ArrayLike, sigma: ArrayLike) -> np.ndarray:
    """Toomre's ``Q = c_s κ / (π G Σ)`` of an isothermal gas sheet.

    >>> round(float(toomre_q(1.0, 1.0, 1.0, 1.0 / np.pi)), 12)
    1.0
    """
    return np.asarray(cs, dtype=np.float64) * np.asarray(kappa) / (np.pi * np.asarray(G) * np.asarray(sigma))


def toomre_frequency_squared(k: ArrayLike, cs: ArrayLike, kappa: ArrayLike, G: ArrayLike,
                             sigma: ArrayLike) -> np.ndarray:
    """``ω² = κ² - 2π G Σ |k| + c_s² k²`` (module docstring); negative: growth at ``sqrt(-ω²)``.

    >>> float(toomre_frequency_squared(1.0, cs=1.0, kappa=1.0, G=1.0 / np.pi, sigma=1.0))
    0.0
    """
    k = np.abs(np.asarray(k, dtype=np.float64))
    return np.asarray(kappa) ** 2 - 2.0 * np.pi * np.asarray(G) * np.asarray(sigma) * k + np.asarray(cs) ** 2 * k**2


def fastest_toomre_wavenumber(cs: ArrayLike, G: ArrayLike, sigma: ArrayLike) -> np.ndarray:
    """``k = π G Σ / c_s²``, the minimum of :func:`toomre_frequency_squared`."""
    return np.pi * np.asarray(G, dtype=np.float64) * np.asarray(sigma) / np.asarray(cs) ** 2
