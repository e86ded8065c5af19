"""The shearing box: rotating-frame source terms and the shear of the radial images.

Frame (thesis §4.1, §4.3.1; Hawley, Gammie & Balbus 1995): a box co-rotating with the disk at
angular frequency Omega, x radial, y azimuthal (along the rotation), z vertical. The steady
background is the linear shear ``v_y = -q Omega x`` (q = 3/2 for a Keplerian disk). The gas
momentum equation is thesis eq. 4.2b written for the full velocity ``v``:

.. math::

    \\partial_t(\\rho v) + \\nabla\\cdot(\\rho v v + P I) =
    \\rho\\left[2\\Omega v_y + 2q\\Omega^2 x + 2\\eta v_K\\Omega\\right]\\hat x
    - 2\\Omega\\rho v_x \\hat y - \\Omega^2\\rho z\\,\\hat z .

The first bracket holds the Coriolis force, the tidal force (centrifugal minus radial
gravity) and the global radial pressure gradient of the disk as a constant force (thesis
4.2b); the last term is optional vertical gravity. Under orbital advection the engine stores
the velocity relative to the shear, ``v' = v + q Omega x y^``, whose equation has no tidal
term and a reduced y-Coriolis coefficient (Masset 2000; Johnson, Guan & Gammie 2008;
Stone & Gardiner 2010):

.. math:: S_x = \\rho(2\\Omega v'_y + 2\\eta v_K\\Omega), \\qquad S_y = -(2-q)\\Omega\\rho v'_x,

which is thesis eq. 4.2b as printed (there q = 3/2, so ``(2 - q) Omega = Omega / 2``).

The radial images of the box slide in y: the fluid at ``(x - Lx, y)`` is the fluid at
``(x, y + q Omega Lx t)`` with ``v_y`` larger by ``q Omega Lx`` (the latter only when the full
velocity is stored). :func:`shear_offset` is that displacement modulo Ly.

Vertical gravity in a box periodic in z (:func:`periodic_tidal_potential`) uses the tidal
potential of Athena's stratified particle-gas boxes (Bai & Stone 2010b), folded into the box and
flattened within a smoothing length of its faces so that the force vanishes there and the
potential is periodic and smooth.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit

__all__ = ["RotatingFrame", "rotating_frame", "SourceTerms", "source_terms", "momentum_source", "shear_offset",
           "shear_velocity_jump", "periodic_tidal_potential", "periodic_tidal_lever"]


class RotatingFrame(NamedTuple):
    """Coefficients of the rotating-frame acceleration of gas and particles alike (thesis
    eq. 4.2b-d): ``a_x = coriolis_x v_y + tidal_x x``, ``a_y = -coriolis_y v_x``."""

    coriolis_x: float
    coriolis_y: float
    tidal_x: float


def rotating_frame(omega: float = 0.0, q: float = 1.5, orbital_advection: bool = False) -> RotatingFrame:
    """The Coriolis and tidal coefficients of a box rotating at ``omega`` with shear ``q``.

    Full velocities: ``(2 Omega v_y + 2 q Omega^2 x, -2 Omega v_x)``; velocities relative to the
    shear ``v' = v + q Omega x y^`` (orbital advection): ``(2 Omega v'_y, -(2 - q) Omega v'_x)``
    (module docstring). The one place these coefficients are written; the gas source terms and
    the particle force term both use it.

    >>> rotating_frame(1.0, 1.5)
    RotatingFrame(coriolis_x=2.0, coriolis_y=2.0, tidal_x=3.0)
    >>> rotating_frame(1.0, 1.5, orbital_advection=True).coriolis_y
    0.5
    """
    if orbital_advection:
        return RotatingFrame(2.0 * omega, (2.0 - q) * omega, 0.0)
    return RotatingFrame(2.0 * omega, 2.0 * omega, 2.0 * q * omega**2)


class SourceTerms(NamedTuple):
    """Coefficients of the momentum source ``S = rho * (...)`` (see module docstring).

    ``S_x = rho (coriolis_x v_y + tidal_x x + force_x)``, ``S_y = -coriolis_y rho v_x``,
    ``S_z = -gravity_z rho z``.
    """

    coriolis_x: float
    tidal_x: float
    coriolis_y: float
    gravity_z: float
    force_x: float
    active: bool


def source_terms(
    omega: float = 0.0,
    q: float = 1.5,
    orbital_advection: bool = False,
    vertical_gravity: bool = False,
    eta_vK: float = 0.0,
) -> SourceTerms:
    """Coefficients for a box rotating at ``omega`` with shear parameter ``q``.

    Parameters
    ----------
    omega
        Angular frequency Omega of the frame (0: no rotation, no shearing-box terms).
    q
        Shear parameter, ``-d ln Omega / d ln r`` (3/2 Keplerian).
    orbital_advection
        Velocities are stored relative to the background shear.
    vertical_gravity
        Include ``-Omega^2 z`` on the gas.
    eta_vK
        The velocity ``eta v_K`` of the global radial pressure gradient; the force per unit
        mass is ``2 eta v_K Omega`` along +x (thesis eq. 4.2b).

    Examples
    --------
    >>> st = source_terms(omega=1.0, q=1.5)
    >>> st.coriolis_x, st.tidal_x, st.coriolis_y
    (2.0, 3.0, 2.0)
    >>> source_terms(omega=1.0, q=1.5, orbital_advection=True).coriolis_y
    0.5
    """
    frame = rotating_frame(omega, q, orbital_advection)
    grav = omega**2 if vertical_gravity else 0.0
    force = 2.0 * eta_vK * omega
    active = omega != 0.0 or force != 0.0 or grav != 0.0
    return SourceTerms(frame.coriolis_x, frame.tidal_x, frame.coriolis_y, grav, force, active)


@njit(cache=True, error_model="numpy")
def momentum_source(rho: float, vx: float, vy: float, x: float, z: float, st: SourceTerms) -> tuple[float, float, float]:
    """Momentum source density ``(S_x, S_y, S_z)`` of one cell (thesis eq. 4.2b)."""
    sx = rho * (st.coriolis_x * vy + st.tidal_x * x + st.force_x)
    sy = -st.coriolis_y * rho * vx
    sz = -st.gravity_z * rho * z
    return sx, sy, sz


@njit(cache=True, error_model="numpy")
def shear_offset(t: float, q_omega_lx: float, ly: float) -> float:
    """Azimuthal displacement ``q Omega Lx t`` of the radial images, reduced to ``[0, Ly)``.

    >>> shear_offset(2.0, 1.5, 4.0)
    3.0
    """
    d = q_omega_lx * t
    return d - ly * math.floor(d / ly)


def shear_velocity_jump(q: float, omega: float, lx: float, orbital_advection: bool) -> float:
    """``q Omega Lx``: how much larger ``v_y`` is in the inner image than in the outer one."""
    return 0.0 if orbital_advection else q * omega * lx


def _fold(z: np.ndarray, z_lo: float, lz: float) -> np.ndarray:
    """``z`` folded into the box ``[z_lo, z_lo + lz)``, measured from its centre."""
    z = np.asarray(z, dtype=np.float64)
    return z - lz * np.floor((z - z_lo) / lz) - (z_lo + 0.5 * lz)


def periodic_tidal_potential(z: np.ndarray, *, z_lo: float, lz: float, smoothing: float) -> np.ndarray:
    r"""Vertical tidal potential per ``Omega^2`` of a box periodic in z, 0 at the midplane.

    With ``a = |z|`` folded into the box (midplane at its centre), ``z_0 = L_z/2 + L_s`` and the
    smoothing length ``L_s``:

    .. math::

        \phi(a)/\Omega^2 = \frac{a^2}{2} - \frac{L_s^3\,(2a - z_0)}{2\,(z_0 - a)^2}
                           - \frac{L_s^3}{2 z_0},

    the ``Omega^2 z^2 / 2`` of thesis eq. 4.2b less a term that flattens it at the faces (the
    "third-order sharp" smoothing of Athena's stratified boxes, Bai & Stone 2010b, with ``L_s``
    the ghost depth): its slope :func:`periodic_tidal_lever` vanishes at ``a = L_z/2``. The
    isothermal column in hydrostatic balance with it is ``rho_0 exp(-phi / c_s^2)``.

    >>> float(periodic_tidal_potential(0.0, z_lo=-0.15, lz=0.3, smoothing=0.01))
    0.0
    >>> round(float(periodic_tidal_potential(0.1, z_lo=-0.15, lz=0.3, smoothing=0.01)), 6)  # 0.005 unsmoothed
    0.004991
    """
    a = np.abs(_fold(z, z_lo, lz))
    z0 = 0.5 * lz + smoothing
    s3 = smoothing**3
    return 0.5 * a * a - s3 * (2.0 * a - z0) / (2.0 * (z0 - a) ** 2) - s3 / (2.0 * z0)


def periodic_tidal_lever(z: np.ndarray, *, z_lo: float, lz: float, smoothing: float) -> np.ndarray:
    r"""The lever ``zeta`` of the vertical gravity ``g_z = -Omega^2 zeta`` in a box periodic in z:
    ``d(phi/Omega^2)/dz`` of :func:`periodic_tidal_potential`,

    .. math:: \zeta = z\,\left[1 - \left(\frac{L_s}{z_0 - |z|}\right)^3\right]

    with ``z`` folded into the box (ghost cells take the values of the cells they copy). It is
    ``z`` at the midplane and 0 at the faces.

    >>> [round(float(v), 6) + 0.0 for v in periodic_tidal_lever([0.0, 0.1, 0.15, 0.16], z_lo=-0.15, lz=0.3,
    ...                                                           smoothing=0.01)]
    [0.0, 0.099537, 0.0, -0.1225]
    """
    z = _fold(z, z_lo, lz)
    z0 = 0.5 * lz + smoothing
    return z * (1.0 - (smoothing / (z0 - np.abs(z))) ** 3)
