"""Protoplanetary-disk initial conditions for SPH: a power-law gas disk around a star, and dust rings.

Code units: au, M_sun and yr/(2 pi) (:data:`dustygas.units.DISK_UNITS`, :math:`G = 1`). The gas disk
(thesis §3.3.1) has :math:`\\Sigma \\propto R^{-p}` between :math:`R_{\\rm in}` and :math:`R_{\\rm out}`,
total mass :math:`M_d`, a locally isothermal temperature :math:`T \\propto R^{-q}` set by the aspect
ratio :math:`H/R` at :math:`R_{\\rm ref}`, and is vertically Gaussian,
:math:`\\rho = \\Sigma/(\\sqrt{2\\pi}H)\\,e^{-z^2/2H^2}` with :math:`H = c_s/\\Omega_K`
(:mod:`dustygas.physics.disk`). Each gas particle rotates with the pressure-supported velocity of its
position (thesis eq. 3.25 at the midplane),

.. math:: v_\\phi^2 = \\frac{GM_\\star R^2}{(R^2+z^2)^{3/2}} + c_s^2\\,\\frac{\\partial\\ln P}{\\partial\\ln R},

(:func:`dustygas.physics.disk.vertical_pressure_gradient_exponent`). Equal-mass particles are placed
without random noise: radii at equal steps of the enclosed mass, azimuths and heights from the
two-dimensional golden-ratio sequence of Roberts (2018), heights through the inverse Gaussian
distribution. :func:`balance_rotation` replaces the analytic rotation by the one that balances the
SPH forces actually felt (the optional relaxation of the set-up).

Dust rings (thesis §3.3.1): ``n`` dust particles evenly spaced on a circle in the midplane, with the
grain radius that gives a chosen Stokes number :math:`\\tau_s` in the local gas
(:func:`dustygas.physics.drag.epstein_grain_size`) and, optionally, the steady drift velocities of
eq. 3.23 and :func:`~dustygas.physics.disk.azimuthal_drift_velocity`.

Examples
--------
>>> disk = DiskModel()
>>> round(float(disk.aspect_ratio_at(20.0)), 6), round(float(disk.eta(20.0)), 6)
(0.05, 0.006875)
>>> pos = disk.positions(1000)
>>> bool(np.all((np.hypot(pos[:, 0], pos[:, 1]) > 5) & (np.hypot(pos[:, 0], pos[:, 1]) < 200)))
True
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import SetupError
from ..physics.disk import (azimuthal_drift_velocity, eta_armitage, keplerian_angular_velocity, keplerian_velocity,
                            midplane_density, pressure_exponent, radial_drift_velocity, surface_density,
                            surface_density_normalisation, vertical_pressure_gradient_exponent)
from ..physics.drag import epstein_grain_size
from .eos import EquationOfState
from .particles import DUST, GAS, ParticleSet

__all__ = ["DiskModel", "balance_rotation", "relax_disk", "ring_particles", "merge_particles", "cylindrical"]

#: Roberts (2018) generalised golden ratio for two dimensions (the plastic number)
_PLASTIC = 1.324717957244746


def cylindrical(pos: np.ndarray, vel: np.ndarray | None = None):
    """Cylindrical radius, azimuth and (with ``vel``) the radial and azimuthal velocities."""
    R = np.hypot(pos[:, 0], pos[:, 1])
    phi = np.arctan2(pos[:, 1], pos[:, 0])
    if vel is None:
        return R, phi
    c, s = pos[:, 0] / R, pos[:, 1] / R
    return R, phi, vel[:, 0] * c + vel[:, 1] * s, -vel[:, 0] * s + vel[:, 1] * c


@dataclass(frozen=True)
class DiskModel:
    """A locally isothermal power-law gas disk in code units (module docstring).

    Attributes
    ----------
    star_mass, disk_mass
        :math:`M_\\star` and :math:`M_d` [M_sun].
    r_in, r_out
        Radial extent [au].
    p, q
        :math:`\\Sigma \\propto R^{-p}`, :math:`T \\propto R^{-q}` (so :math:`c_s \\propto R^{-q/2}`).
    aspect_ratio, r_ref
        :math:`H/R` at :math:`R_{\\rm ref}` [au].
    """

    star_mass: float = 1.0
    disk_mass: float = 5e-3
    r_in: float = 5.0
    r_out: float = 200.0
    p: float = 1.0
    q: float = 0.5
    aspect_ratio: float = 0.05
    r_ref: float = 20.0

    def __post_init__(self) -> None:
        if not 0 < self.r_in < self.r_out:
            raise SetupError(f"disk: need 0 < r_in < r_out (r_in = {self.r_in:g}, r_out = {self.r_out:g})")
        if not (self.star_mass > 0 and self.disk_mass > 0 and 0 < self.aspect_ratio < 1):
            raise SetupError("disk: star_mass and disk_mass must be > 0 and 0 < aspect_ratio < 1")

    @property
    def sigma0(self) -> float:
        """:math:`\\Sigma` at :math:`R = 1` au."""
        return surface_density_normalisation(self.disk_mass, self.r_in, self.r_out, 1.0, self.p)

    def sigma(self, R):
        return surface_density(R, self.sigma0, 1.0, self.p)

    def omega(self, R):
        return keplerian_angular_velocity(R, self.star_mass, G=1.0)

    def v_kepler(self, R):
        return keplerian_velocity(R, self.star_mass, G=1.0)

    @property
    def cs_ref(self) -> float:
        return float(self.aspect_ratio * self.v_kepler(self.r_ref))

    def sound_speed(self, R):
        return self.cs_ref * (np.asarray(R, dtype=np.float64) / self.r_ref) ** (-0.5 * self.q)

    def scale_height(self, R):
        return self.sound_speed(R) / self.omega(R)

    def aspect_ratio_at(self, R):
        return self.scale_height(R) / np.asarray(R, dtype=np.float64)

    def density(self, R, z=0.0):
        H = self.scale_height(R)
        return midplane_density(self.sigma(R), H) * np.exp(-0.5 * (np.asarray(z) / H) ** 2)

    @property
    def pressure_exponent(self) -> float:
        return float(pressure_exponent(self.p, self.q))

    def eta(self, R):
        """:math:`\\eta` of thesis eq. 3.24 at the midplane."""
        return eta_armitage(self.pressure_exponent, self.sound_speed(R), self.v_kepler(R))

    def orbital_period(self, R):
        return 2.0 * np.pi / self.omega(R)

    def eos(self) -> EquationOfState:
        """The locally isothermal equation of state :math:`c_s = c_{s,\\rm ref}(R/R_{\\rm ref})^{-q/2}`."""
        return EquationOfState.locally_isothermal(self.cs_ref, self.r_ref, 0.5 * self.q)

    # ---------------------------------------------------------------- particles
    def positions(self, n: int) -> np.ndarray:
        """``n`` positions sampling the disk's density without random noise (module docstring)."""
        i = np.arange(n)
        u = (i + 0.5) / n
        if abs(self.p - 2.0) < 1e-12:
            R = self.r_in * (self.r_out / self.r_in) ** u
        else:
            a, b = self.r_in ** (2.0 - self.p), self.r_out ** (2.0 - self.p)
            R = (a + u * (b - a)) ** (1.0 / (2.0 - self.p))
        phi = 2.0 * np.pi * np.mod(0.5 + i / _PLASTIC, 1.0)
        from scipy.special import ndtri  # imported here: scipy.special costs every process 0.15 s at start-up

        z = self.scale_height(R) * ndtri(np.mod(0.5 + i / _PLASTIC**2, 1.0))
        return np.stack([R * np.cos(phi), R * np.sin(phi), z], axis=1)

    def velocities(self, pos: np.ndarray) -> np.ndarray:
        """Pressure-supported circular velocities at ``pos`` (module docstring)."""
        R, _ = cylindrical(pos)
        z = pos[:, 2]
        v2 = self.star_mass * R**2 / (R**2 + z**2) ** 1.5
        v2 = v2 + self.sound_speed(R) ** 2 * vertical_pressure_gradient_exponent(self.p, self.q,
                                                                                  z / self.scale_height(R))
        if np.any(v2 <= 0):
            raise SetupError("disk: pressure support exceeds gravity somewhere (aspect ratio too large)")
        vphi = np.sqrt(v2)
        vel = np.zeros_like(pos)
        vel[:, 0] = -vphi * pos[:, 1] / R
        vel[:, 1] = vphi * pos[:, 0] / R
        return vel

    def gas_particles(self, n: int, hfact: float, alpha: float = 0.0) -> ParticleSet:
        """``n`` equal-mass gas particles with smoothing lengths from the analytic density."""
        pos = self.positions(n)
        m = self.disk_mass / n
        R, _ = cylindrical(pos)
        h = hfact * (m / self.density(R, pos[:, 2])) ** (1.0 / 3.0)
        return ParticleSet.create(pos, self.velocities(pos), mass=m, h=h, alpha=alpha, ptype=GAS)

    def grain_size(self, taus: float, radius: float, grain_density: float) -> float:
        """Grain radius whose Epstein stopping time in the midplane gas at ``radius`` is :math:`\\tau_s/\\Omega`."""
        return float(epstein_grain_size(taus, grain_density, self.density(radius), self.sound_speed(radius),
                                        self.omega(radius)))


def ring_particles(disk: DiskModel, n: int, radius: float, mass: float, taus: float, h: float,
                   drifting: bool = True) -> ParticleSet:
    """``n`` dust particles evenly spaced on a midplane circle of ``radius`` (module docstring).

    ``drifting``: start with the steady drift of grains of Stokes number ``taus`` (eq. 3.23 with
    :math:`v_{r,g} = 0`, and :func:`~dustygas.physics.disk.azimuthal_drift_velocity`); otherwise
    on circular Keplerian orbits.
    """
    if not (n >= 1 and disk.r_in < radius < disk.r_out):
        raise SetupError(f"dust ring: radius {radius:g} must lie inside the disk ({disk.r_in:g}, {disk.r_out:g})")
    phi = 2.0 * np.pi * (np.arange(n) + 0.5) / n
    pos = np.stack([radius * np.cos(phi), radius * np.sin(phi), np.zeros(n)], axis=1)
    vK = float(disk.v_kepler(radius))
    vr, vphi = 0.0, vK
    if drifting:
        eta = float(disk.eta(radius))
        vr = float(radial_drift_velocity(taus, eta, vK))
        vphi = vK + float(azimuthal_drift_velocity(taus, eta, vK))
    vel = np.stack([vr * np.cos(phi) - vphi * np.sin(phi), vr * np.sin(phi) + vphi * np.cos(phi), np.zeros(n)], 1)
    return ParticleSet.create(pos, vel, mass=mass, h=h, ptype=DUST)


def merge_particles(*sets: ParticleSet) -> ParticleSet:
    """One set holding ``sets`` in order, with particle ids 0..N-1 (extra fields must agree)."""
    names = ("pos", "vel", "mass", "h", "u", "alpha", "ptype")
    out = {k: np.concatenate([getattr(s, k) for s in sets]) for k in names}
    n = len(out["mass"])
    extra = {}
    for key in set().union(*(s.extra for s in sets)):
        parts = [s.extra[key] if key in s.extra else np.zeros((len(s),) + sets[0].extra.get(key, np.zeros(1)).shape[1:])
                 for s in sets]
        extra[key] = np.concatenate(parts)
    return ParticleSet(**out, pid=np.arange(n, dtype=np.int64), extra=extra)


def balance_rotation(pos: np.ndarray, vel: np.ndarray, acc: np.ndarray, select: np.ndarray) -> int:
    """Set the particles ``select`` on circular orbits that balance the radial acceleration they feel,
    :math:`v_\\phi = \\sqrt{-R\\,a_R}` (in place; radial and vertical velocities zeroed). A particle
    pushed outward (:math:`a_R \\ge 0`, possible at the edges of a coarse disk) keeps its velocity;
    returns how many did."""
    idx = np.flatnonzero(select)
    R, _ = cylindrical(pos[idx])
    c, s = pos[idx, 0] / R, pos[idx, 1] / R
    aR = acc[idx, 0] * c + acc[idx, 1] * s
    ok = aR < 0
    vphi = np.sqrt(-R[ok] * aR[ok])
    i = idx[ok]
    vel[i, 0] = -vphi * s[ok]
    vel[i, 1] = vphi * c[ok]
    vel[i, 2] = 0.0
    return int((~ok).sum())


def relax_disk(engine, duration: float, star_mass: float = 1.0) -> int:
    """Relaxation stage of a gas disk: advance ``engine`` for ``duration`` damping every particle's radial
    and vertical velocity by :math:`e^{-\\Omega_K\\Delta t}` after each block (its local orbital time), so
    that the discrete disk settles into the vertical and radial structure its own SPH forces hold,
    then put it on the circular orbits those forces balance (:func:`balance_rotation`). Returns the
    number of particles left unbalanced (pushed outward)."""
    while engine.t < duration * (1 - 1e-12):
        engine.advance(min(engine.timestep(), duration - engine.t))
        p = engine.particles
        R, _, vR, vphi = cylindrical(p.pos, p.vel)
        f = np.exp(-engine.dt_block * np.sqrt(star_mass / R**3))
        c, s = p.pos[:, 0] / R, p.pos[:, 1] / R
        vR = f * vR
        p.vel[:, 0] = vR * c - vphi * s
        p.vel[:, 1] = vR * s + vphi * c
        p.vel[:, 2] *= f
        engine.v_sync[:] = p.vel
    p = engine.particles
    return balance_rotation(p.pos, p.vel, engine.acc, np.ones(len(p), np.bool_))
