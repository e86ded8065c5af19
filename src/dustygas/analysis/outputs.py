"""``dustygas analyze <kind> RUN`` for stratified particle runs: the numbers and the figure.

One function, :func:`analyze_stratified`, dispatches on the kind (module docstring of
:mod:`dustygas.analysis.stratified` defines the quantities) and writes into ``RUN/analysis``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import UserError
from ..io.rundir import RunDirectory
from .stratified import read_series, read_snapshot

__all__ = ["analyze_stratified", "spread_snapshots"]


def spread_snapshots(run, count: int = 4) -> list[int]:
    """Indices of ``count`` snapshots spread evenly over a run (the last included)."""
    n = len(RunDirectory(run).require_snapshots())
    return sorted({int(round(i)) for i in np.linspace(0, n - 1, min(count, n))})


def analyze_stratified(kind: str, run: str | Path, output: str | Path | None = None,
                       snapshots: Sequence[int] | None = None, slab_width: float = 0.03) -> list[Path]:
    """Write the PNG and numbers of ``kind`` for ``run``; returns the paths."""
    from ..plot.particles import cdf_figure, series_figure, slab_figure, surface_density_figure

    run = Path(run)
    out = Path(output) if output else run / "analysis"
    out.mkdir(parents=True, exist_ok=True)
    if kind in ("max-density", "scale-height", "dispersion"):
        series = read_series(run)
        snap = read_snapshot(run, -1)
        area = snap.box[0] * (snap.box[1] if len(snap.y) > 1 else 1.0)
        q = kind.replace("-", "_")
        return series_figure(series, out / f"{q}.png", q, f"{run.name}: {kind.replace('-', ' ')}", area=area)
    idx = list(snapshots) if snapshots else (spread_snapshots(run) if kind in ("surface-density", "cdf") else [-1])
    snaps = [read_snapshot(run, i) for i in idx]
    if kind == "surface-density":
        every = [read_snapshot(run, i) for i in range(len(RunDirectory(run).snapshots()))]
        return surface_density_figure(snaps, out / "surface_density.png", f"{run.name}: surface density",
                                      every=every)
    if kind == "cdf":
        return cdf_figure(snaps, out / "density_cdf.png", f"{run.name}: dust density distribution")
    if kind == "slabs":
        paths = []
        for view in ("xy", "xz"):
            paths += slab_figure(snaps[-1], out / f"slab_{view}.png", view, slab_width, f"{run.name}")
        return paths
    raise UserError(f"analyze: unknown analysis {kind!r}")
