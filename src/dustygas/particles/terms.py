"""Forces on the particles and sources on the gas as terms a problem composes.

A particle problem hands the engine two lists: ``particle_terms`` (accelerations per unit
mass of every particle) and ``gas_terms`` (momentum sources per unit volume on the gas, besides
the rotating-frame terms the grid engine applies itself). Each term states its equation and
provides a compiled function of arrays; adding a force (self-gravity, a planet, a pressure
bump) is adding a term.

Particle terms
--------------
:class:`RotatingFrame`
    ``a = (c_x v_y + t_x x, -c_y v_x, 0)`` -- Coriolis and tidal accelerations of the shearing
    box (thesis eq. 4.2c-d; coefficients from :func:`dustygas.grid.shearing_box.rotating_frame`,
    the same as the gas's).
:class:`VerticalGravity`
    ``a_z = -Ω_z² z`` (thesis eq. 4.18's source; integrated exactly with the drag, see
    :func:`~dustygas.particles.drag.oscillator_step`).
:class:`ConstantAcceleration`
    ``a = (a_x, a_y, a_z)``, e.g. the global pressure gradient in the particle frame
    ``(-2 η v_K Ω, 0, 0)``, or a settling drift held by a constant force.
:class:`MeshAcceleration`
    ``a = Σ_a W(x - x_a) g_a`` -- an acceleration field ``g`` on the mesh, gathered with the
    particle's weights (self-gravity ``g = -∇Φ``); :meth:`MeshAcceleration.update` is called
    with the gas state at the start of each stage.

Order within a step (:mod:`dustygas.particles.push`): mesh fields are gathered at the
time-centred position ``x^{n+1/2}``; the rotating frame, constant and mesh accelerations are
evaluated at ``(x^{n+1/2}, v^{n+1/2})`` (the velocity predicted over half a step) and held
over the step; vertical gravity and drag are integrated exactly together.

Gas terms
---------
:class:`GasConstantAcceleration`
    ``S = ρ_g (a_x, a_y, a_z)``.
:class:`GasMeshAcceleration`
    ``S = ρ_g g`` for a mesh acceleration field (self-gravity on the gas).

The drag back-reaction is not in this list: it is the engine's own (minus the drag impulse of
the particles, :mod:`dustygas.particles.drag`). Gas terms are added to the drag source in each
stage, evaluated on the state the stage reads.

Interface for a new term
------------------------
A particle term subclasses :class:`ParticleTerm` and fills its coefficients into the
:class:`ForceTable` (``contribute``); a mesh term also owns an acceleration field ``(3, nz, ny,
nx)`` on the domain cells that it refreshes in ``update(engine, rho_gas, t)``. A gas term
subclasses :class:`GasTerm` and adds its source in ``add_source(engine, rho_gas, t, out)``
(``out`` ``(3, nz, ny, nx)``, momentum per volume and time, to be added to). ``rho_gas`` is the
gas density ``(nz, ny, nx)`` of the state the stage reads, ``engine`` the
:class:`~dustygas.particles.coupling.ParticleGridEngine` (its ``dust_density()``, ``mesh``,
``t``). The engine calls ``update`` (particle mesh terms) and ``add_source`` (gas terms) once
per gas stage, in the order of the lists, before the stage; the particles gather the mesh
fields of the corrector's call.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
from numba import njit

from ..grid.shearing_box import rotating_frame

__all__ = ["ForceTable", "ParticleTerm", "RotatingFrame", "VerticalGravity", "ConstantAcceleration",
           "MeshAcceleration", "GasTerm", "GasConstantAcceleration", "GasMeshAcceleration", "force_table",
           "frame_acceleration", "add_row_impulse"]


class ForceTable(NamedTuple):
    """The particle terms' coefficients as the kernels receive them (sums over the terms)."""

    coriolis_x: float
    coriolis_y: float
    tidal_x: float
    gravity_z: float  # Ω_z² of the vertical restoring acceleration
    ax: float
    ay: float
    az: float
    mesh: bool  # a mesh acceleration field is gathered


class ParticleTerm:
    """Base class: an acceleration of every particle (module docstring)."""

    def contribute(self, table: dict) -> None:
        raise NotImplementedError


@dataclass(frozen=True)
class RotatingFrame(ParticleTerm):
    """Coriolis and tidal accelerations, ``(c_x v_y + t_x x, -c_y v_x, 0)`` (thesis eq. 4.2c-d)."""

    omega: float
    q: float = 1.5
    relative_to_shear: bool = False

    def contribute(self, table: dict) -> None:
        f = rotating_frame(self.omega, self.q, self.relative_to_shear)
        table["coriolis_x"] += f.coriolis_x
        table["coriolis_y"] += f.coriolis_y
        table["tidal_x"] += f.tidal_x


@dataclass(frozen=True)
class VerticalGravity(ParticleTerm):
    """``a_z = -Ω² z``: the vertical component of the star's gravity near the midplane."""

    omega: float = 1.0

    def contribute(self, table: dict) -> None:
        table["gravity_z"] += self.omega**2


@dataclass(frozen=True)
class ConstantAcceleration(ParticleTerm):
    """``a = (a_x, a_y, a_z)`` on every particle."""

    ax: float = 0.0
    ay: float = 0.0
    az: float = 0.0

    def contribute(self, table: dict) -> None:
        table["ax"] += self.ax
        table["ay"] += self.ay
        table["az"] += self.az


@dataclass
class MeshAcceleration(ParticleTerm):
    """``a = Σ_a W(x - x_a) g_a``: a field ``g`` ``(3, nz, ny, nx)`` on the mesh, gathered with the
    particle's weights. Subclasses refresh :attr:`field` in :meth:`update`."""

    field: np.ndarray = field(default_factory=lambda: np.zeros((3, 1, 1, 1)))

    def contribute(self, table: dict) -> None:
        table["mesh"] = True

    def update(self, engine, rho_gas: np.ndarray, t: float) -> None:
        """Refresh :attr:`field` for the stage that reads gas of density ``rho_gas`` at ``t``."""


def force_table(terms) -> ForceTable:
    """The :class:`ForceTable` of a list of particle terms (at most one mesh term).

    >>> force_table([RotatingFrame(1.0), VerticalGravity(1.0), ConstantAcceleration(ax=-0.1)])
    ForceTable(coriolis_x=2.0, coriolis_y=2.0, tidal_x=3.0, gravity_z=1.0, ax=-0.1, ay=0.0, az=0.0, mesh=False)
    """
    table = dict(coriolis_x=0.0, coriolis_y=0.0, tidal_x=0.0, gravity_z=0.0, ax=0.0, ay=0.0, az=0.0, mesh=False)
    if sum(isinstance(t, MeshAcceleration) for t in terms) > 1:
        raise ValueError("at most one mesh acceleration term (sum the fields into one)")
    for t in terms:
        t.contribute(table)
    return ForceTable(**table)


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def frame_acceleration(x, vx, vy, ft):
    """The velocity-independent and Coriolis part ``(a_x, a_y, a_z)`` of the particle terms at
    ``x``, ``(v_x, v_y)`` (without vertical gravity and mesh fields, handled apart)."""
    return (ft.coriolis_x * vy + ft.tidal_x * x + ft.ax, -ft.coriolis_y * vx + ft.ay, ft.az)


class GasTerm:
    """Base class: a momentum source on the gas (module docstring)."""

    def add_source(self, engine, rho_gas: np.ndarray, t: float, out: np.ndarray) -> None:
        raise NotImplementedError


@dataclass(frozen=True)
class GasConstantAcceleration(GasTerm):
    """``S = ρ_g (a_x, a_y, a_z)``: e.g. the force that cancels the mean back-reaction of a dust
    drifting vertically through the gas (``si-settling``)."""

    ax: float = 0.0
    ay: float = 0.0
    az: float = 0.0

    def add_source(self, engine, rho_gas: np.ndarray, t: float, out: np.ndarray) -> None:
        for c, a in enumerate((self.ax, self.ay, self.az)):
            if a != 0.0:
                out[c] += a * rho_gas


@dataclass
class GasMeshAcceleration(GasTerm):
    """``S = ρ_g g`` for the field of a :class:`MeshAcceleration` term (the same field the
    particles gather)."""

    term: MeshAcceleration

    def add_source(self, engine, rho_gas: np.ndarray, t: float, out: np.ndarray) -> None:
        out += rho_gas * self.term.field


@njit(cache=True, error_model="numpy")
def add_row_impulse(ext, base, with_base, factor, rows) -> None:
    """``rows[k ny + j, c] += factor Σ_i (ext - base)[c, k, j, i]``: the momentum the gas terms gave
    each row of cells ``(k, j)`` in a step (``factor = h V``; ``ext`` the stage's source, which
    holds the drag source ``base`` if ``with_base``), summed along the row in cell order, so that
    it does not depend on the block that holds the row (:mod:`dustygas.parallel`)."""
    _, nz, ny, nx = ext.shape
    for k in range(nz):
        for j in range(ny):
            sx = sy = sz = 0.0
            for i in range(nx):
                bx = base[0, k, j, i] if with_base else 0.0
                by = base[1, k, j, i] if with_base else 0.0
                bz = base[2, k, j, i] if with_base else 0.0
                sx += ext[0, k, j, i] - bx
                sy += ext[1, k, j, i] - by
                sz += ext[2, k, j, i] - bz
            u = k * ny + j
            rows[u, 0] += sx * factor
            rows[u, 1] += sy * factor
            rows[u, 2] += sz * factor
