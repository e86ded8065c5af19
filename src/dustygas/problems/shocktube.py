"""``shocktube``: an isothermal Riemann problem along x, with the exact solution to compare.

Two uniform states meet at ``x = x0``; the exact self-similar solution is
:func:`dustygas.physics.riemann.isothermal_riemann`. The default (density 1 | 0.1 at rest,
c_s = 1, t = 0.2) has a left rarefaction and a right shock of Mach number 1.75; a transverse
velocity jump (``vy_l != vy_r``) adds a contact, which the HLLC solver keeps sharp.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..grid.params import BOUNDARY, GAS, GRID, SCHEME, engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, register

__all__ = ["ShockTube"]


@register
class ShockTube(Problem):
    runs_on_ranks = True  # gas only: engine_from_config decomposes the mesh under mpiexec
    name = "shocktube"
    summary = "Isothermal shock tube along x (rarefaction + shock); exact Riemann solution for comparison."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=0.2, dt_history=0.005),
        "grid": with_defaults(GRID, nx=256),
        "scheme": SCHEME,
        "gas": GAS,
        "boundary": with_defaults(BOUNDARY, x="outflow"),
        "problem": {
            "rho_l": Param(1.0, "density left of x0", min=0.0, min_open=True),
            "rho_r": Param(0.1, "density right of x0", min=0.0, min_open=True),
            "vx_l": Param(0.0, "velocity along the tube, left", "c_s"),
            "vx_r": Param(0.0, "velocity along the tube, right", "c_s"),
            "vy_l": Param(0.0, "transverse velocity, left", "c_s"),
            "vy_r": Param(0.0, "transverse velocity, right", "c_s"),
            "x0": Param(0.0, "initial position of the discontinuity (box is [-lx/2, lx/2])", "H"),
        },
    }

    def validate(self, cfg) -> None:
        g = cfg.grid
        if g.ny != 1 or g.nz != 1:
            raise ConfigError("shocktube runs along x: set grid.ny = grid.nz = 1")
        if not -0.5 * g.lx < cfg.problem.x0 < 0.5 * g.lx:
            raise ConfigError(f"problem.x0 = {cfg.problem.x0} lies outside the box [-{g.lx / 2}, {g.lx / 2}]")

    def build(self, cfg):
        eng = engine_from_config(cfg)
        p = cfg.problem
        x = eng.mesh.centers(0)
        left = x < p.x0
        eng.set_primitive(np.where(left, p.rho_l, p.rho_r), np.where(left, p.vx_l, p.vx_r),
                          np.where(left, p.vy_l, p.vy_r), 0.0)
        return eng
