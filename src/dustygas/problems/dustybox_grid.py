"""``dustybox-grid``: relative velocity decay of uniform gas and particles (Laibe & Price 2011).

Uniform gas (density ``rho_g``, velocity ``v_g0`` along x) and a uniform lattice of particles
(dust density ``rho_d``, velocity ``v_d0``) in a periodic box without rotation, coupled by a
constant drag coefficient K (drag force per unit volume ``K (v_d - v_g)``): each particle has
the stopping time ``t_p = rho_d / K`` and the relative velocity decays on the mixture stopping
time ``t_s = rho_g rho_d / (K (rho_g + rho_d))``
(:func:`~dustygas.physics.drag.mixture_stopping_time`).

Everything stays uniform (the lattice moves as a whole and deposits a uniform density), so
the history's ``gas_vx`` and ``dust_vx`` compare directly with the exact solution
:func:`dustygas.physics.exact.dusty_box`. Defaults: Phantom's unit test (ρ_g = ρ_d = 1,
v_d0 = 1, v_g0 = 0, K = 0.35, c_s = 1).
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..grid import GridEngine, Mesh
from ..grid.params import GRID
from ..particles import ParticleGridEngine, ParticleStore
from ..particles.params import PARTICLES, lattice_positions, particle_engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, register
from .si_linear import SI_SCHEME

__all__ = ["DustyBoxGrid"]


class DustyBoxEngine(ParticleGridEngine):
    """Adds the mean gas and dust velocities along x to the history."""

    def history(self) -> dict[str, float]:
        out = super().history()
        out["gas_vx"] = out["momentum_x"] / out["mass"]
        out["dust_vx"] = out["particle_momentum_x"] / out["particle_mass"]
        return out


@register
class DustyBoxGrid(Problem):
    name = "dustybox-grid"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "Uniform gas + particles with constant drag: relative velocity decay (Laibe & Price 2011)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=5.0),
        "grid": with_defaults(GRID, nx=8, nz=8),
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "rho_g": Param(1.0, "gas density", min=0.0, min_open=True),
            "rho_d": Param(1.0, "dust density", min=0.0, min_open=True),
            "K": Param(0.35, "drag coefficient (force per volume = K (v_d - v_g))", min=0.0, min_open=True),
            "v_g0": Param(0.0, "initial gas velocity along x", "c_s"),
            "v_d0": Param(1.0, "initial dust velocity along x", "c_s"),
        },
    }

    def build(self, cfg):
        p, g, s = cfg.problem, cfg.grid, cfg.scheme
        mesh = Mesh((g.nx, g.ny, g.nz), (g.lx, g.ly, g.lz))
        gas = GridEngine(mesh, cs=1.0, integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter,
                         riemann=s.riemann, cfl=s.cfl)
        gas.set_primitive(p.rho_g, p.v_g0, 0.0, 0.0)
        lattice = cfg.particles.lattice
        pos = lattice_positions(mesh.shape, mesh.lower, mesh.dx, lattice,
                                0.0 if cfg.particles.kernel == "cic" and lattice % 2 else 0.5)
        vel = np.zeros_like(pos)
        vel[0] = p.v_d0
        mass = p.rho_d * mesh.cell_volume / lattice**mesh.ndim
        store = ParticleStore.create(pos, vel, 0, mass)
        return particle_engine_from_config(cfg, gas, store, [p.rho_d / p.K], cls=DustyBoxEngine)
