"""``dustygas export RUN``: a run's snapshots in the formats the field's tools read.

=========  ===========================================  ==============================================
format     what is written for snapshot ``NNNNN``       read by
=========  ===========================================  ==============================================
athdf      ``snap_NNNNN.athdf`` + ``.athdf.xdmf``        yt (``athena_pp``), ParaView, VisIt
           (grid fields, :mod:`dustygas.io.athdf`)
ytdata     ``snap_NNNNN.particles.h5``                   yt (``ytdata``): particle positions, masses,
           (:mod:`dustygas.io.ytdata`)                   velocities, ids (and SPH fields)
phantom    ``dump_NNNNN`` (:mod:`dustygas.io.phantom`)    sarracen, splash, plonk
csv        ``snap_NNNNN.csv``: one row per particle      sarracen.read_csv, pandas, spreadsheets
           (or cell), every field a column
auto       grid runs: athdf (+ ytdata for particles);
           SPH runs: phantom + ytdata
=========  ===========================================  ==============================================

Every file carries the snapshot's attributes (configuration, version, problem, time) and the
units of its fields in the run's code units (:mod:`dustygas.io.schema`).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable, Mapping

import numpy as np

from ..errors import UserError
from .atomic import atomic_write_text
from .hdf5 import read_h5
from .rundir import RunDirectory
from .schema import layout_of, snapshot_quantity

__all__ = ["FORMATS", "export_run", "export_snapshot", "write_csv"]

FORMATS = ("auto", "athdf", "ytdata", "phantom", "csv")


def _csv_columns(arrays: Mapping[str, np.ndarray]) -> list[tuple[str, np.ndarray, str]]:
    layout = layout_of(arrays)
    cols: list[tuple[str, np.ndarray, str]] = []
    if layout == "sph":
        n = len(arrays["pos"])
        for name, value in arrays.items():
            value = np.asarray(value)
            leaf = name.rsplit("/", 1)[-1]
            units = snapshot_quantity(leaf).units
            if value.shape == (n, 3):
                stem = {"pos": "", "vel": "v"}.get(leaf, f"{leaf}_")
                cols += [(f"{stem}{ax}", value[:, a], units) for a, ax in enumerate("xyz")]
            elif value.shape == (n,):
                cols.append((leaf, value, units))
    elif "particles/pos" in arrays:
        for name, value in arrays.items():
            if not name.startswith("particles/"):
                continue
            leaf, value = name[len("particles/"):], np.asarray(value)
            units = snapshot_quantity(leaf).units
            if value.ndim == 2:
                stem = {"pos": "", "vel": "v"}.get(leaf, f"{leaf}_")
                cols += [(f"{stem}{ax}", value[a], units) for a, ax in enumerate("xyz")]
            else:
                cols.append((leaf, value, units))
    else:
        shape = np.shape(arrays["rho"])
        z, y, x = np.meshgrid(arrays["z"], arrays["y"], arrays["x"], indexing="ij")
        cols += [(ax, c.ravel(), "code_length") for ax, c in zip("xyz", (x, y, z))]
        cols += [(name, np.asarray(v).ravel(), snapshot_quantity(name).units)
                 for name, v in arrays.items() if np.shape(v) == shape]
    return cols


def write_csv(path: str | Path, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
    """Particles (or, for a grid run without particles, cells) as CSV: ``#`` lines with the
    problem, time, version and each column's units, then a header row and the values."""
    path = Path(path)
    cols = _csv_columns(arrays)
    lines = [f"# dustygas {attrs.get('dustygas_version', '')} problem {attrs.get('problem', '')} "
             f"time {float(attrs.get('time', 0.0))!r} cycle {attrs.get('cycle', '')}"]
    lines += [f"# column {name} [{units}]: {snapshot_quantity(name).description}".rstrip(": ")
              for name, _, units in cols]
    config = str(attrs.get("config", ""))
    lines += [f"# config {ln}" for ln in config.splitlines()]
    lines.append(",".join(name for name, _, _ in cols))
    table = np.column_stack([np.asarray(v, dtype=np.float64) for _, v, _ in cols])
    body = "\n".join(",".join(map(repr, row)) for row in table.tolist())
    atomic_write_text(path, "\n".join(lines) + "\n" + body + "\n")
    return path


def export_snapshot(snapshot: str | Path, fmt: str, output: str | Path) -> list[Path]:
    """Write one snapshot file in format ``fmt`` (see :data:`FORMATS`) into the folder ``output``."""
    from .athdf import write_athdf, write_xdmf
    from .phantom import write_phantom
    from .ytdata import write_particles_ytdata

    snapshot, output = Path(snapshot), Path(output)
    arrays, attrs = read_h5(snapshot)
    layout = layout_of(arrays)
    stem = snapshot.stem  # snap_NNNNN
    index = stem.rsplit("_", 1)[-1]
    has_particles = layout == "sph" or "particles/pos" in arrays
    formats = [fmt]
    if fmt == "auto":
        formats = (["athdf"] + (["ytdata"] if has_particles else [])) if layout.startswith("grid") else ["phantom", "ytdata"]
    written: list[Path] = []
    for f in formats:
        if f == "athdf":
            if not layout.startswith("grid"):
                raise UserError(f"--format athdf: {snapshot} is an SPH snapshot (use phantom, ytdata or csv)")
            written.append(write_athdf(output / f"{stem}.athdf", arrays, attrs))
            written.append(write_xdmf(written[-1]))
        elif f == "ytdata":
            if not has_particles:
                raise UserError(f"--format ytdata: {snapshot} holds no particles (use athdf or csv)")
            written.append(write_particles_ytdata(output / f"{stem}.particles.h5", arrays, attrs))
        elif f == "phantom":
            if layout != "sph":
                raise UserError(f"--format phantom: {snapshot} is not an SPH snapshot (use athdf, ytdata or csv)")
            try:
                written.append(write_phantom(output / f"dump_{index}", arrays, attrs))
            except ValueError as exc:
                raise UserError(f"--format phantom: {exc}") from None
        elif f == "csv":
            written.append(write_csv(output / f"{stem}.csv", arrays, attrs))
        else:
            raise UserError(f"--format {f!r}: choose one of {', '.join(FORMATS)}")
    return written


def export_run(run: str | Path, fmt: str = "auto", output: str | Path | None = None,
               snapshots: Iterable[int] | None = None) -> list[Path]:
    """Export snapshots of the run directory ``run`` (all, or the positions in ``snapshots``;
    negative counts from the end) in format ``fmt`` into ``output`` (default ``RUN/export``)."""
    if fmt not in FORMATS:
        raise UserError(f"--format {fmt!r}: choose one of {', '.join(FORMATS)}")
    rundir = RunDirectory(run)
    if not rundir.config_file.exists():
        raise UserError(f"{run}: not a run directory (no config.toml)")
    files = rundir.require_snapshots(" to export")
    chosen = files if snapshots is None else [rundir.snapshot_at(i) for i in snapshots]
    out = Path(output) if output is not None else rundir.path / "export"
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    for path in chosen:
        written += export_snapshot(path, fmt, out)
    return written
