"""Clumps and their mass function for a run directory (``dustygas analyze clumps RUN``).

A snapshot qualifies if it holds the particle engine's arrays ``particles/pos``, ``particles/vel``
and ``particles/mass`` (``particles/pid`` for the member lists), the mesh coordinates ``x``,
``y``, ``z`` (the cells of the density deposit) and the attributes ``lx, ly, lz, q, omega,
shear_offset``; the gravitational constant comes from the attribute ``gravity_G`` (code
units) unless ``g_tilde`` (``G̃ = 4πGρ_g0/Ω²``, with ``ρ_g0 = 1``) is given. Each analysed
snapshot ``snapshots/snap_NNNNN.h5`` gets the catalogue ``clumps/clumps_NNNNN.h5``
(:class:`~dustygas.analysis.clumps.ClumpCatalogue`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..errors import UserError
from .clumps import ClumpCatalogue, find_clumps

__all__ = ["SnapshotClumps", "snapshot_clumps", "run_clumps", "catalogue_path"]

_REQUIRED = ("particles/pos", "particles/vel", "particles/mass", "x", "y", "z")


@dataclass
class SnapshotClumps:
    """The catalogue of one snapshot and where it came from and went."""

    snapshot: Path
    catalogue_file: Path | None
    time: float
    catalogue: ClumpCatalogue


def catalogue_path(run: str | Path, snapshot: Path) -> Path:
    """``RUN/clumps/clumps_NNNNN.h5`` for ``RUN/snapshots/snap_NNNNN.h5``."""
    index = re.search(r"snap_(\d+)\.h5$", snapshot.name)
    return Path(run) / "clumps" / f"clumps_{index.group(1) if index else snapshot.stem}.h5"


def snapshot_clumps(arrays: dict[str, np.ndarray], attrs: dict[str, Any], *, source: str = "snapshot",
                    g_tilde: float | None = None, threshold: float | None = None, min_particles: int = 10,
                    periodic_z: bool | None = None, vertical_tide: bool = True) -> ClumpCatalogue:
    """:func:`~dustygas.analysis.clumps.find_clumps` on one snapshot's arrays and attributes."""
    missing = [k for k in _REQUIRED if k not in arrays]
    missing += [k for k in ("lx", "ly", "lz", "omega") if k not in attrs]
    if missing:
        raise UserError(f"{source}: no {', '.join(missing)}: clump finding needs a particle snapshot "
                        "(particle positions, velocities, masses and the mesh)")
    omega, q = float(attrs["omega"]), float(attrs.get("q", 1.5))
    if g_tilde is not None:
        if not (g_tilde > 0 and math.isfinite(g_tilde)):
            raise UserError(f"--g-tilde {g_tilde}: must be positive (G~ = 4 pi G rho_g0 / Omega^2)")
        G = g_tilde * omega**2 / (4.0 * math.pi)
    elif "gravity_G" in attrs:
        G = float(attrs["gravity_G"])
    else:
        raise UserError(f"{source}: no gravity_G attribute (the run has no self-gravity): give --g-tilde")
    if omega <= 0:
        raise UserError(f"{source}: omega = {omega}: clumps are defined in a rotating frame (omega > 0)")
    cells = tuple(int(np.size(arrays[a])) for a in ("x", "y", "z"))
    box = tuple(float(attrs[k]) for k in ("lx", "ly", "lz"))
    bounds = attrs.get("boundaries")
    if periodic_z is None:
        periodic_z = bounds is None or list(bounds)[2] == "periodic"
    shear = bounds is None or list(bounds)[0] == "shear-periodic"
    mass = np.asarray(arrays["particles/mass"], dtype=np.float64)
    ids = arrays.get("particles/pid")
    return find_clumps(arrays["particles/pos"], arrays["particles/vel"], mass, box=box, cells=cells, G=G, omega=omega,
                       q=q, shear_offset=float(attrs.get("shear_offset", 0.0)), shear=shear, periodic_z=periodic_z,
                       threshold=threshold, min_particles=min_particles, vertical_tide=vertical_tide, ids=ids,
                       velocity_relative_to_shear=bool(attrs.get("orbital_advection", False)))


def run_clumps(run: str | Path, snapshots: str | Sequence[int] = "last", write: bool = True,
               **options: Any) -> list[SnapshotClumps]:
    """Catalogues of a run's snapshots (``"last"``, ``"all"`` or positions in the sorted list).

    ``options`` go to :func:`snapshot_clumps`. With ``write`` each catalogue is written next to
    the run's snapshots (``RUN/clumps/``), replacing an older one atomically.
    """
    from ..io.hdf5 import read_h5
    from ..io.rundir import RunDirectory

    rd = RunDirectory(run)
    files = rd.require_snapshots()
    if snapshots == "last":
        chosen = [files[-1]]
    elif snapshots == "all":
        chosen = files
    else:
        chosen = [rd.snapshot_at(i) for i in snapshots]
    out = []
    for snap in chosen:
        arrays, attrs = read_h5(snap)
        cat = snapshot_clumps(arrays, attrs, source=str(snap), **options)
        cat.attrs.update(time=float(attrs.get("time", math.nan)), snapshot=snap.name)
        target = None
        if write:
            target = catalogue_path(rd.path, snap)
            target.parent.mkdir(parents=True, exist_ok=True)
            cat.write(target)
        out.append(SnapshotClumps(snap, target, float(attrs.get("time", math.nan)), cat))
    return out
