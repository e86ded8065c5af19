"""``nsh``: the Nakagawa-Sekiya-Hayashi steady drift of gas and N dust species (thesis eq. 4.8).

Uniform gas and uniform lattices of particles, one lattice per species, in a shearing box
with the global pressure gradient, start in the NSH equilibrium of
:func:`dustygas.physics.nsh_velocities_multi` (one species: thesis eq. 4.8; N species:
Tanaka, Himeno & Ida 2005, Bai & Stone 2010c). The equilibrium is an exact steady state of
the discrete scheme (the drag, solved in the velocities relative to the shear, keeps a steady
drift, and a drifting lattice deposits a uniform density), so the run measures how well the
engine holds it (to round-off, 1e-14 over ten orbits): the history
has every species' mean velocity relative to the shear, ``species_<s>_vx``, ``_vy``, and
the gas's, ``gas_vx``, ``gas_vy``, in units of ``η v_K``.

Units ``Ω = c_s = H = 1``, ``ρ_g = 1``, ``η v_K = Π``. Default: a 2D x-z box of 16² cells,
0.1 H on a side, shear-periodic in x with the full azimuthal velocity stored (particles that
cross the radial boundary change ``v_y`` by ``q Ω L_x``), ten orbits.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..grid import GridEngine, Mesh
from ..grid.params import GRID
from ..particles import ConstantAcceleration, ParticleGridEngine, ParticleStore, RotatingFrame
from ..particles.params import PARTICLES, lattice_positions, particle_engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, register
from .si_linear import SI_SCHEME

__all__ = ["NSH", "NSHEngine"]


class NSHEngine(ParticleGridEngine):
    """:class:`~dustygas.particles.ParticleGridEngine` whose history adds the mean velocities."""

    eta_vK: float = 1.0

    def history(self) -> dict[str, float]:
        out = super().history()
        p = self.particles
        shear = 0.0 if self.geometry.velocity_relative_to_shear else self.geometry.q * self.geometry.omega
        vy = p.vel[1] + shear * p.pos[0]
        for s in range(len(self.species.t_stop)):
            sel = p.species == s
            m = p.mass[sel]
            out[f"species_{s}_vx"] = float(m @ p.vel[0, sel] / m.sum()) / self.eta_vK
            out[f"species_{s}_vy"] = float(m @ vy[sel] / m.sum()) / self.eta_vK
        out["gas_vx"] = out["momentum_x"] / out["mass"] / self.eta_vK
        out["gas_vy"] = out["momentum_y"] / out["mass"] / self.eta_vK
        return out


@register
class NSH(Problem):
    name = "nsh"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "NSH steady drift of gas and N dust species (thesis eq. 4.8) in a shearing box with particles."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=20.0 * math.pi, dt_history=0.1),
        "grid": with_defaults(GRID, nx=16, nz=16, lx=0.1, lz=0.1),
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "taus": Param([0.1], "stopping time tau_s = Omega t_s of each species", "1/Omega", min=0.0, min_open=True),
            "mu": Param([1.0], "dust-to-gas density ratio of each species", min=0.0, min_open=True),
            "Pi": Param(0.05, "eta v_K / c_s", min=0.0, min_open=True),
            "orbital_advection": Param(False, "store velocities relative to the shear (else full velocities)"),
            "pressure_frame": Param("gas", "global pressure gradient as a force on the gas, or the opposite force "
                                    "on the particles", choices=("gas", "particles")),
        },
    }

    def validate(self, cfg) -> None:
        p = cfg.problem
        if len(p.taus) != len(p.mu):
            raise ConfigError(f"problem.taus has {len(p.taus)} species but problem.mu has {len(p.mu)}")
        if cfg.grid.nx == 1:
            raise ConfigError("grid.nx = 1: the NSH drift is radial, x must be active")

    def build(self, cfg):
        from ..physics import nsh_velocities_multi

        p, g, s = cfg.problem, cfg.grid, cfg.scheme
        mesh = Mesh((g.nx, g.ny, g.nz), (g.lx, g.ly, g.lz))
        gas_frame = p.pressure_frame == "gas"
        gas = GridEngine(mesh, cs=1.0, integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter,
                         riemann=s.riemann, cfl=s.cfl, omega=1.0, q=1.5, orbital_advection=p.orbital_advection,
                         boundaries=("shear-periodic", "periodic", "periodic"), eta_vK=p.Pi if gas_frame else 0.0)
        eq = nsh_velocities_multi(np.array(p.taus), np.array(p.mu))
        boost = 0.0 if gas_frame else 1.0
        x = mesh.centers(0)[None, None, :]
        shape = tuple(reversed(mesh.shape))
        gas.set_primitive(1.0, float(eq.gas_vx) * p.Pi,
                          (float(eq.gas_vy) + boost) * p.Pi - 1.5 * x + np.zeros(shape), 0.0)
        lattice = cfg.particles.lattice
        pos0 = lattice_positions(mesh.shape, mesh.lower, mesh.dx, lattice,
                                 0.0 if cfg.particles.kernel == "cic" and lattice % 2 else 0.5)
        per = pos0.shape[1]
        nsp = len(p.taus)
        pos = np.tile(pos0, nsp)
        species = np.repeat(np.arange(nsp), per)
        mass = np.repeat(np.array(p.mu) * mesh.cell_volume / lattice**mesh.ndim, per)
        shear = 0.0 if p.orbital_advection else -1.5
        vel = np.zeros((3, pos.shape[1]))
        vel[0] = np.repeat(eq.dust_vx, per) * p.Pi
        vel[1] = (np.repeat(eq.dust_vy, per) + boost) * p.Pi + shear * pos[0]
        store = ParticleStore.create(pos, vel, species, mass)
        terms = [RotatingFrame(1.0, 1.5, relative_to_shear=p.orbital_advection),
                 ConstantAcceleration(0.0 if gas_frame else -2.0 * p.Pi, 0.0, 0.0)]
        engine = particle_engine_from_config(cfg, gas, store, list(p.taus), cls=NSHEngine, particle_terms=terms)
        engine.eta_vK = p.Pi
        return engine
