"""``si-nonlinear``: the unstratified non-linear streaming instability (Johansen & Youdin 2007).

The standard non-linear check of streaming-instability codes (Johansen & Youdin 2007, runs AB
and BA; Bai & Stone 2010a, §5): a periodic box of uniform gas and dust without vertical
gravity, x shear-periodic, the global pressure gradient ``2 η v_K Ω x̂`` on the gas
(``Π = η v_K/c_s = 0.05``), units ``Ω = c_s = H = 1``, ``ρ_g = 1``. Gas and dust start in the NSH
drift (thesis eq. 4.8) and the particles at random positions (a random-noise start: the
instability grows from the shot noise of the particles); the runs saturate in a turbulent
state whose dust density distribution is the check.

Presets (box side in ``η r = Π H``, one particle per cell):

========== ====== ====== ========= ======================== =========
name        τ_s     ε      side       cells                    t_end
========== ====== ====== ========= ======================== =========
si-AB       0.1     1.0    2 η r     64 × 64 (x-z)            50 Ω⁻¹
si-AB-3d    0.1     1.0    2 η r     32 × 32 × 32             50 Ω⁻¹
si-BA       1.0     0.2    40 η r    64 × 64 (x-z)            200 Ω⁻¹
si-BA-3d    1.0     0.2    40 η r    32 × 32 × 32             200 Ω⁻¹
========== ====== ====== ========= ======================== =========
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..grid import GridEngine, Mesh
from ..particles import ParticleStore, RotatingFrame
from ..particles.params import PARTICLES, particle_engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, preset, register
from .si_linear import SI_SCHEME

__all__ = ["SINonlinear"]


@register
class SINonlinear(Problem):
    name = "si-nonlinear"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "Unstratified non-linear streaming instability from a random-noise start (Johansen & Youdin 2007)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=50.0, dt_history=0.1, dt_snapshot=5.0),
        "grid": {
            "nx": Param(64, "cells along x (radial)", min=4),
            "ny": Param(1, "cells along y (azimuthal; 1: the 2D x-z box)", min=1),
            "nz": Param(64, "cells along z (vertical)", min=4),
        },
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "taus": Param(0.1, "stopping time tau_s = Omega t_s (fixed)", "1/Omega", min=0.0, min_open=True),
            "eps": Param(1.0, "mean dust-to-gas density ratio", min=0.0, min_open=True),
            "side": Param(2.0, "box side along every active axis", "eta r", min=0.0, min_open=True),
            "Pi": Param(0.05, "eta v_K / c_s (length unit eta r = Pi H)", min=0.0, min_open=True),
            "per_cell": Param(1.0, "particles per cell", min=0.0, min_open=True),
            "seed": Param(1, "random seed of the particle positions", min=0),
        },
    }

    def build(self, cfg):
        from ..physics import nsh_velocities

        g, p, s = cfg.grid, cfg.problem, cfg.scheme
        side = p.side * p.Pi
        mesh = Mesh((g.nx, g.ny, g.nz), (side, side, side))
        gas = GridEngine(mesh, cs=1.0, integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter,
                         riemann=s.riemann, cfl=s.cfl, boundaries=("shear-periodic", "periodic", "periodic"),
                         omega=1.0, q=1.5, orbital_advection=True, eta_vK=p.Pi)
        eq = nsh_velocities(p.taus, p.eps, p.Pi)
        gas.set_primitive(1.0, float(eq.gas_vx), float(eq.gas_vy), 0.0)
        rng = np.random.default_rng(p.seed)
        n = int(round(p.per_cell * mesh.ncells))
        pos = np.zeros((3, n))
        for a, (lo, L, m) in enumerate(zip(mesh.lower, mesh.size, mesh.shape)):
            if m > 1:
                pos[a] = lo + L * rng.random(n)
        vel = np.zeros((3, n))
        vel[0], vel[1] = float(eq.dust_vx), float(eq.dust_vy)  # relative to the shear (orbital advection)
        volume = float(np.prod([L if m > 1 else 1.0 for L, m in zip(mesh.size, mesh.shape)]))
        store = ParticleStore.create(pos, vel, 0, p.eps * volume / n)
        return particle_engine_from_config(cfg, gas, store, [p.taus],
                                           particle_terms=[RotatingFrame(1.0, 1.5, relative_to_shear=True)])


preset("si-AB", SINonlinear, "Johansen & Youdin (2007) run AB: tau_s = 0.1, eps = 1, box 2 eta r, 64^2 x-z.")
preset("si-AB-3d", SINonlinear, "Run AB in 3D: tau_s = 0.1, eps = 1, box (2 eta r)^3, 32^3.",
       grid={"nx": 32, "ny": 32, "nz": 32}, scheme={"cfl": 0.3})
preset("si-BA", SINonlinear, "Johansen & Youdin (2007) run BA: tau_s = 1, eps = 0.2, box 40 eta r, 64^2 x-z.",
       run={"tlim": 200.0, "dt_snapshot": 20.0}, problem={"taus": 1.0, "eps": 0.2, "side": 40.0})
preset("si-BA-3d", SINonlinear, "Run BA in 3D: tau_s = 1, eps = 0.2, box (40 eta r)^3, 32^3.",
       grid={"nx": 32, "ny": 32, "nz": 32}, scheme={"cfl": 0.3}, run={"tlim": 200.0, "dt_snapshot": 20.0},
       problem={"taus": 1.0, "eps": 0.2, "side": 40.0})
