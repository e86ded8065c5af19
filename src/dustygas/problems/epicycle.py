"""``epicycle``: uniform gas oscillating at the epicyclic frequency in a shearing box.

A uniform radial velocity ``delta v_x = A`` on top of the Keplerian shear ``v_y = -q Omega x``
exercises everything of the shearing box except pressure: Coriolis and tidal terms (or their
orbital-advection form), the shear-periodic boundaries with their velocity jump, and
orbital advection. The exact solution is ``delta v_x = A cos(kappa t)``,
``delta v_y = -(kappa / 2 Omega) A sin(kappa t)`` with
``kappa = sqrt(2 (2 - q)) Omega`` (:func:`dustygas.physics.shearing_sheet.epicyclic_frequency`;
kappa = Omega for q = 3/2). The default runs 10 orbits on a 32^2 box.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import Param, with_defaults
from ..grid.params import BOUNDARY, GAS, GRID, SCHEME, SHEARING_BOX, engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, register

__all__ = ["Epicycle"]


@register
class Epicycle(Problem):
    runs_on_ranks = True  # gas only: engine_from_config decomposes the mesh under mpiexec
    name = "epicycle"
    summary = "Uniform epicyclic oscillation in a 2D shearing box (frequency kappa = Omega for q = 3/2)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=20.0 * math.pi, dt_history=0.05),
        "grid": with_defaults(GRID, nx=32, ny=32),
        "scheme": SCHEME,
        "gas": GAS,
        "boundary": with_defaults(BOUNDARY, x="shear-periodic"),
        "shearing_box": SHEARING_BOX,
        "problem": {
            "amplitude": Param(0.01, "initial radial velocity delta v_x", "c_s"),
            "rho0": Param(1.0, "density", min=0.0, min_open=True),
        },
    }

    def build(self, cfg):
        eng = engine_from_config(cfg)
        p, sb = cfg.problem, cfg.shearing_box
        x = eng.mesh.centers(0)[None, None, :]
        eng.set_primitive(p.rho0, p.amplitude, -sb.q * sb.omega * x + np.zeros(tuple(reversed(eng.mesh.shape))), 0.0)
        return eng
