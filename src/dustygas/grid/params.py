"""Configuration sections shared by the grid problems, and the engine they describe.

A grid problem's schema holds ``run`` plus some of the sections below (copied with its own
defaults through :func:`~dustygas.config.with_defaults`); :func:`engine_from_config` builds
the :class:`~dustygas.grid.engine.GridEngine` from them, so every grid problem spells the
mesh, the scheme and the shearing box the same way::

    [grid]      nx ny nz lx ly lz            cells (1: inactive axis) and box lengths
    [scheme]    integrator reconstruction limiter riemann cfl
    [gas]       cs                            isothermal sound speed
    [boundary]  x y z                         periodic | shear-periodic | outflow | reflecting
    [shearing_box] omega q orbital_advection vertical_gravity eta_vK

Code units of the shearing-box problems: Omega = c_s = H = 1 unless a problem says otherwise.
"""

from __future__ import annotations

from ..config import Config, Limit, Param
from ..errors import ConfigError
from .boundaries import BOUNDARY_KINDS
from ..parallel.comm import launched_under_mpi
from .engine import GridEngine
from .integrator import INTEGRATORS, courant_limit
from .mesh import Mesh
from .reconstruct import LIMITERS, RECONSTRUCTIONS
from .riemann import RIEMANN_SOLVERS

__all__ = ["GRID", "SCHEME", "GAS", "BOUNDARY", "SHEARING_BOX", "COURANT_LIMIT", "grid_ndim", "engine_from_config"]

GRID: dict[str, Param] = {
    "nx": Param(64, "cells along x (radial); 1 makes the axis inactive", min=1),
    "ny": Param(1, "cells along y (azimuthal); 1 makes the axis inactive", min=1),
    "nz": Param(1, "cells along z (vertical); 1 makes the axis inactive", min=1),
    "lx": Param(1.0, "box length along x (box centred on 0)", "H", min=0.0, min_open=True),
    "ly": Param(1.0, "box length along y", "H", min=0.0, min_open=True),
    "lz": Param(1.0, "box length along z", "H", min=0.0, min_open=True),
}

def grid_ndim(cfg: Config) -> int | None:
    """Active dimensions of the mesh a ``[grid]`` section describes (missing counts are 1);
    ``None`` without a ``[grid]`` section."""
    if "grid" not in cfg:
        return None
    return max(1, sum(int(cfg.grid.get(n, 1)) > 1 for n in ("nx", "ny", "nz")))


#: the Courant bound of :func:`~dustygas.grid.integrator.courant_limit` for the configured grid
#: and integrator
COURANT_LIMIT = Limit("1/ndim (1 in 1D, 0.5 in 2D, 1/3 in 3D; ctu: 1 in any dimension)",
                      lambda cfg: None if grid_ndim(cfg) is None
                      else courant_limit(grid_ndim(cfg), cfg.scheme.get("integrator", "vl2")))

SCHEME: dict[str, Param] = {
    "integrator": Param("vl2", "time integrator (vl2: Stone & Gardiner 2009; rk2, rk3: SSP Runge-Kutta; ctu: corner "
                        "transport upwind, Colella 1990)",
                        choices=tuple(INTEGRATORS)),
    "reconstruction": Param("plm", "face reconstruction (ppm: Colella & Woodward 1984; ppm-cs: with the "
                            "Colella & Sekora 2008 extremum-preserving limiter)", choices=tuple(RECONSTRUCTIONS)),
    "limiter": Param("mc", "PLM slope limiter", choices=tuple(LIMITERS)),
    "riemann": Param("hlle", "Riemann solver", choices=tuple(RIEMANN_SOLVERS)),
    "cfl": Param(0.4, "Courant number, per axis", min=0.0, max=COURANT_LIMIT, min_open=True),
}

GAS: dict[str, Param] = {
    "cs": Param(1.0, "isothermal sound speed", "H Omega", min=0.0, min_open=True),
}

BOUNDARY: dict[str, Param] = {
    axis: Param("periodic", f"boundary kind on both {axis} faces", choices=tuple(BOUNDARY_KINDS))
    for axis in "xyz"
}

SHEARING_BOX: dict[str, Param] = {
    "omega": Param(1.0, "angular frequency of the rotating frame (0: no rotation)", "Omega", min=0.0),
    "q": Param(1.5, "shear parameter -dlnOmega/dlnr (3/2: Keplerian)", min=0.0, max=2.0, max_open=True),
    "orbital_advection": Param(False, "advect by the background shear with an exact remap (FARGO)"),
    "vertical_gravity": Param(False, "vertical gravity -Omega^2 z on the gas"),
    "eta_vK": Param(0.0, "global radial pressure gradient as the force 2 eta v_K Omega x^ (thesis 4.2b)",
                    "H Omega"),
}


def engine_from_config(cfg: Config) -> GridEngine:
    """A :class:`GridEngine` (no initial state yet) from the sections present in ``cfg``."""
    g, s = cfg.grid, cfg.scheme
    cs = cfg.gas.cs if "gas" in cfg else 1.0
    kinds = tuple(cfg.boundary[a] for a in "xyz") if "boundary" in cfg else ("periodic",) * 3
    sb = dict(cfg.shearing_box) if "shearing_box" in cfg else {"omega": 0.0}
    if kinds[0] == "shear-periodic" and sb.get("omega", 0.0) == 0.0:
        raise ConfigError("boundary.x = 'shear-periodic' needs a rotating frame: set shearing_box.omega > 0")
    mesh = Mesh((g.nx, g.ny, g.nz), (g.lx, g.ly, g.lz))
    options = dict(cs=cs, integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter,
                   riemann=s.riemann, cfl=s.cfl, boundaries=kinds, **sb)
    if launched_under_mpi():  # one block per rank (mpi4py is imported only here)
        from ..parallel.gas import DistributedGridEngine

        return DistributedGridEngine(mesh, **options)  # type: ignore[return-value]
    return GridEngine(mesh, **options)
