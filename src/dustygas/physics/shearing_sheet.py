"""Closed-form solutions of the shearing sheet (gas only).

Frame of thesis §4.1 and §4.3.1: x radial, y azimuthal, background shear ``v_y = -q Omega x``
(thesis eq. 4.2 has q = 3/2), velocities relative to that shear.

Epicycles
    A uniform velocity perturbation obeys ``du_x/dt = 2 Omega u_y``,
    ``du_y/dt = -(2 - q) Omega u_x`` (thesis eq. 4.2b without pressure or drag) and oscillates
    at the epicyclic frequency ``kappa = sqrt(2 (2 - q)) Omega`` (kappa = Omega for q = 3/2).

Vortical shearing wave
    An incompressible perturbation ``u(t) exp(i (k_x(t) x + k_y y))`` is carried by the shear,
    so its radial wavenumber grows linearly, ``k_x(t) = k_x0 + q Omega k_y t`` (a leading wave,
    ``k_x/k_y < 0``, swings to trailing at ``t = -k_x0 / (q Omega k_y)``). Incompressibility
    ``k . u = 0`` and conservation of the vorticity perturbation ``i (k_x u_y - k_y u_x)``
    (the background vorticity ``(q - 2) Omega`` is uniform and the flow divergence-free) give
    Kelvin's (1887) solution, the limit ``c_s -> infinity`` of the compressible shearing wave
    of Johnson & Gammie (2005, ApJ 635, 149):

    .. math::

        u_x(t) = u_{x0} \\frac{k^2(0)}{k^2(t)}, \\qquad u_y = -\\frac{k_x}{k_y} u_x, \\qquad
        \\frac{\\delta P}{\\rho_0} = 2 i \\Omega u_x \\frac{k^2 - q k_y^2}{k_y k^2}

    (the pressure from the radial momentum equation
    ``du_x/dt = 2 Omega u_y - i k_x delta P / rho_0``). Compressibility corrects it at order
    ``(Omega / (c_s k))^2``.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["epicyclic_frequency", "VorticalWave", "vortical_shearing_wave"]


def epicyclic_frequency(omega: ArrayLike = 1.0, q: ArrayLike = 1.5) -> np.ndarray:
    """Epicyclic frequency ``kappa = sqrt(2 (2 - q)) Omega``.

    >>> float(epicyclic_frequency(1.0, 1.5))
    1.0
    """
    return np.sqrt(2.0 * (2.0 - np.asarray(q, dtype=np.float64))) * np.asarray(omega, dtype=np.float64)


class VorticalWave(NamedTuple):
    """Complex amplitudes of the incompressible shearing wave at the requested times."""

    kx: np.ndarray
    ux: np.ndarray
    uy: np.ndarray
    pressure: np.ndarray  # delta P / rho_0


def vortical_shearing_wave(t: ArrayLike, kx0: float, ky: float, ux0: complex = 1.0, q: float = 1.5,
                           omega: float = 1.0) -> VorticalWave:
    """Kelvin's incompressible shearing wave (module docstring) at times ``t``.

    Parameters
    ----------
    t
        Times (code units, 1/Omega).
    kx0, ky
        Wavenumbers at ``t = 0``; ``ky != 0``.
    ux0
        Radial velocity amplitude at ``t = 0``.

    Examples
    --------
    A leading wave with ``k_x0 = -2 k_y`` is amplified ``k^2(0)/k_y^2 = 5`` times at the swing:

    >>> w = vortical_shearing_wave([0.0, 2.0 / 1.5], kx0=-2.0, ky=1.0)
    >>> [round(float(abs(u)), 12) for u in w.ux]
    [1.0, 5.0]
    """
    t = np.asarray(t, dtype=np.float64)
    kx = kx0 + q * omega * ky * t
    k2 = kx**2 + ky**2
    ux = ux0 * (kx0**2 + ky**2) / k2
    uy = -kx / ky * ux
    pressure = 2j * omega * ux * (k2 - q * ky**2) / (ky * k2)
    return VorticalWave(kx, ux + 0j, uy + 0j, pressure)
