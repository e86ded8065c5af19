"""``shearing-wave``: a vortical shearing wave swinging from leading to trailing.

A plane wave ``exp(i (k_x x + k_y y))`` of the velocity relative to the shear is sheared by
the flow, ``k_x(t) = k_x0 + q Omega k_y t``. Its incompressible (vortical) form has Kelvin's
closed-form solution (:func:`dustygas.physics.shearing_sheet.vortical_shearing_wave`): the
radial velocity grows as ``k^2(0) / k^2(t)`` up to the swing (``k_x = 0``) and decays after.
The gas here is compressible; the wave is nearly incompressible when ``c_s k >> Omega``: the
default box is a quarter of a scale height across, one wavelength along y and two along x
(``k_x0 = -2 k_y``, ``|k| H`` from 25 at the swing up to 56), where the compressible solution
differs from Kelvin's by 0.15 % of the peak (Johnson & Gammie 2005). The run covers
``t = 0 .. 8/3``: five-fold amplification at the swing (t = 4/3), then decay back.

The initial state holds the incompressible pressure perturbation as a density perturbation,
``delta rho / rho_0 = delta P / (rho_0 c_s^2)``, so that hardly any sound is launched.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..grid.mesh import Mesh
from ..grid.params import BOUNDARY, GAS, GRID, SCHEME, SHEARING_BOX, engine_from_config
from ..physics.shearing_sheet import vortical_shearing_wave
from ..runner import RUN_SCHEMA
from . import Problem, register

__all__ = ["ShearingWave", "shearing_wave_fields", "wavenumbers"]


def wavenumbers(p, mesh: Mesh) -> tuple[float, float]:
    """``(k_x0, k_y)`` of the ``[problem]`` section ``p`` in the box of ``mesh``."""
    return 2 * np.pi * p.waves_x / mesh.size[0], 2 * np.pi * p.waves_y / mesh.size[1]


def shearing_wave_fields(mesh: Mesh, t: float, kx0: float, ky: float, amplitude: float, q: float = 1.5,
                         omega: float = 1.0, cs: float = 1.0, rho0: float = 1.0):
    """Kelvin's wave at time ``t`` on the cell centres: ``(rho, dvx, dvy)``.

    ``dvx, dvy`` are the velocity relative to the shear (add ``-q Omega x`` to ``dvy`` for the
    full velocity); ``amplitude`` is the radial velocity at ``t = 0``.
    """
    x, y, _ = mesh.meshgrid()
    w = vortical_shearing_wave(t, kx0, ky, amplitude, q, omega)
    phase = np.exp(1j * (w.kx * x + ky * y))
    shape = tuple(reversed(mesh.shape))
    rho = rho0 * (1.0 + np.broadcast_to((w.pressure * phase).real, shape) / cs**2)
    return rho, np.broadcast_to((w.ux * phase).real, shape), np.broadcast_to((w.uy * phase).real, shape)


@register
class ShearingWave(Problem):
    runs_on_ranks = True  # gas only: engine_from_config decomposes the mesh under mpiexec
    name = "shearing-wave"
    summary = "Nearly incompressible vortical shearing wave through its swing (Kelvin's closed form)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=8.0 / 3.0, dt_history=0.01),
        "grid": with_defaults(GRID, nx=64, ny=64, lx=0.25, ly=0.25),
        "scheme": SCHEME,
        "gas": GAS,
        "boundary": with_defaults(BOUNDARY, x="shear-periodic"),
        "shearing_box": SHEARING_BOX,
        "problem": {
            "amplitude": Param(1e-4, "radial velocity of the wave at t = 0", "c_s", min=0.0, min_open=True),
            "rho0": Param(1.0, "background density", min=0.0, min_open=True),
            "waves_x": Param(-2, "wavelengths across the box along x at t = 0 (negative: leading)"),
            "waves_y": Param(1, "wavelengths across the box along y", min=1),
        },
    }

    def validate(self, cfg) -> None:
        g = cfg.grid
        if g.ny == 1 or g.nz != 1:
            raise ConfigError("shearing-wave runs in the x-y plane: set grid.ny > 1 and grid.nz = 1")
        if cfg.shearing_box.omega == 0.0:
            raise ConfigError("shearing-wave needs shearing_box.omega > 0")

    def build(self, cfg):
        eng = engine_from_config(cfg)
        p, sb = cfg.problem, cfg.shearing_box
        kx0, ky = wavenumbers(p, eng.mesh)
        rho, dvx, dvy = shearing_wave_fields(eng.mesh, 0.0, kx0, ky, p.amplitude, sb.q, sb.omega, cfg.gas.cs, p.rho0)
        x = eng.mesh.centers(0)[None, None, :]
        eng.set_primitive(rho, dvx, dvy - sb.q * sb.omega * x, 0.0)
        return eng
