"""``soundwave``: a linear isothermal sound wave in a periodic box, with its exact solution.

The wave vector holds an integer number of wavelengths along each active axis,
``k = 2 pi (m_x / L_x, m_y / L_y, m_z / L_z)``, so the wave is periodic in the box; a 2D or 3D
wave with several non-zero ``m`` runs obliquely to the mesh. The initial state (and the exact
solution at any time) is :func:`dustygas.physics.exact.sound_wave`, sampled at the cell centres.

Presets: ``soundwave-2d`` (64^2, k along the diagonal), ``soundwave-3d`` (32^3, along (1,1,1)).
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..grid.params import GAS, GRID, SCHEME, engine_from_config
from ..physics.exact import sound_wave
from ..runner import RUN_SCHEMA
from . import Problem, preset, register

__all__ = ["SoundWave", "wave_vector"]


def wave_vector(waves, box) -> np.ndarray:
    """``k = 2 pi (m_x / L_x, m_y / L_y, m_z / L_z)`` of ``waves`` wavelengths across ``box``."""
    return np.array([2 * np.pi * m / length for m, length in zip(waves, box)], dtype=np.float64)


@register
class SoundWave(Problem):
    runs_on_ranks = True  # gas only: engine_from_config decomposes the mesh under mpiexec
    name = "soundwave"
    summary = "Linear isothermal sound wave in a periodic box (1D, or oblique in 2D/3D); exact solution."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=1.0, dt_history=0.01),
        "grid": with_defaults(GRID, nx=64),
        "scheme": SCHEME,
        "gas": GAS,
        "problem": {
            "amplitude": Param(1e-6, "relative density amplitude A", min=0.0, min_open=True, max=0.1),
            "rho0": Param(1.0, "background density", min=0.0, min_open=True),
            "waves": Param([1, 0, 0], "wavelengths across the box along x, y, z (0 on inactive axes)",
                           type="int_list", length=3),
            "direction": Param(1, "+1: the wave moves along k, -1: against it", choices=(1, -1)),
        },
    }

    def validate(self, cfg) -> None:
        waves, g = cfg.problem.waves, cfg.grid
        for m, n, axis in zip(waves, (g.nx, g.ny, g.nz), "xyz"):
            if m != 0 and n == 1:
                raise ConfigError(f"problem.waves has {m} wavelengths along {axis}, but n{axis} = 1 (inactive axis)")
        if not any(waves):
            raise ConfigError("problem.waves = [0, 0, 0]: give at least one non-zero number of wavelengths")

    def build(self, cfg):
        eng = engine_from_config(cfg)
        p = cfg.problem
        eng.set_primitive(*sound_wave(*eng.mesh.meshgrid(), 0.0, k=wave_vector(p.waves, eng.mesh.size),
                                      amplitude=p.amplitude, cs=cfg.gas.cs, rho0=p.rho0, direction=p.direction))
        return eng


preset("soundwave-2d", SoundWave, "Oblique linear sound wave on a 64^2 mesh, k along the diagonal.",
       grid={"nx": 64, "ny": 64}, problem={"waves": [1, 1, 0]})
preset("soundwave-3d", SoundWave, "Oblique linear sound wave on a 32^3 mesh, k along (1, 1, 1).",
       grid={"nx": 32, "ny": 32, "nz": 32}, scheme={"cfl": 0.3}, problem={"waves": [1, 1, 1]})
