"""``dustygas plot RUN``: the history curves and snapshot images of a run of any engine, and movies.

* :func:`history_figure` -- every column of ``history.h5`` (or the chosen ones) against time,
  one panel each, labelled with its units; the real and imaginary parts of a mode amplitude
  (``X_re``, ``X_im``) are drawn as one panel ``|X|``; a column spanning more than three decades
  with one sign is drawn on a logarithmic axis (growing modes, decaying errors).
* :func:`plot_snapshot` -- one snapshot, through :func:`dustygas.plot.maps.snapshot_figure`.
* :func:`write_movie` -- one frame per snapshot with fixed colour limits (the range over all
  frames), written with matplotlib's animation writers: ``.mp4`` through ffmpeg, ``.gif``
  through Pillow.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Sequence

import numpy as np

from ..errors import UserError
from ..io.hdf5 import read_h5
from ..io.rundir import RunDirectory
from ..io.schema import history_quantity
from .maps import axis_label, grid_image, image_figure, snapshot_figure, sph_image
from .style import house_style

__all__ = ["history_figure", "plot_snapshot", "write_movie", "movie_frames"]


def _run(path: str | Path) -> RunDirectory:
    rundir = RunDirectory(path)
    if not rundir.config_file.exists():
        raise UserError(f"{path}: not a run directory (no config.toml)")
    return rundir


def history_figure(run: str | Path, columns: Sequence[str] | None = None) -> Any:
    """Figure of the history columns of ``run`` (all but ``time`` and ``cycle`` by default)."""
    cols, attrs = _run(run).read_history()
    time = cols["time"]
    if not columns:  # complex amplitudes X_re, X_im are drawn as |X| (one panel, log axis)
        for key in [k for k in cols if k.endswith("_re") and k[:-3] + "_im" in cols]:
            cols[f"|{key[:-3]}|"] = np.hypot(cols.pop(key), cols.pop(key[:-3] + "_im"))
    names = list(columns) if columns else [k for k in cols if k not in ("time", "cycle")]
    unknown = [n for n in names if n not in cols]
    if unknown:
        raise UserError(f"--history {unknown[0]!r}: no such column; choose from {', '.join(sorted(cols))}")
    ncol = min(3, len(names))
    nrow = math.ceil(len(names) / ncol)
    from matplotlib.figure import Figure

    with house_style():
        fig = Figure(figsize=(3.6 * ncol, 2.5 * nrow), layout="constrained")
        axes = fig.subplots(nrow, ncol, sharex=True, squeeze=False)
        for ax, name in zip(axes.flat, names):
            y = np.asarray(cols[name])
            ax.plot(time, y, lw=1.2)
            finite = y[np.isfinite(y)]
            if finite.size and (np.all(finite > 0) or np.all(finite < 0)):
                ratio = np.abs(finite).max() / max(np.abs(finite).min(), 1e-300)
                if ratio > 1e3:
                    ax.set_yscale("log" if np.all(finite > 0) else "symlog")
            ax.set_ylabel(axis_label(name, history_quantity(name.strip("|") + "_re" if name.startswith("|")
                                                           else name).units), fontsize=8)
            ax.tick_params(labelsize=7)
        for ax in axes.flat[len(names):]:
            ax.set_visible(False)
        for ax in axes[-1]:
            ax.set_xlabel(axis_label("time", "code_time"))
        fig.suptitle(f"{attrs.get('problem', '')}: history", fontsize=10)
    return fig


def plot_snapshot(run: str | Path, index: int = -1, field: str = "rho", kind: str = "slice",
                  axis: str | None = None, at: float | None = None, log: bool = False,
                  vmin: float | None = None, vmax: float | None = None, npix: int = 256) -> Any:
    """Figure of snapshot ``index`` of ``run`` (see :func:`dustygas.plot.maps.snapshot_figure`)."""
    arrays, attrs = read_h5(_run(run).snapshot_at(index))
    try:
        return snapshot_figure(arrays, attrs, field, kind, axis, at, log, vmin, vmax, npix)
    except ValueError as exc:
        raise UserError(f"plot: {exc}") from None


def movie_frames(run: str | Path, field: str = "rho", kind: str = "slice", axis: str | None = None,
                 at: float | None = None, npix: int = 256) -> list[tuple[float, Any]]:
    """``(time, MapImage)`` of every snapshot of a 2D/3D run (the frames of :func:`write_movie`)."""
    frames = []
    for path in _run(run).snapshots():
        arrays, attrs = read_h5(path)
        try:
            if "pos" in arrays and "h" in arrays:
                image = sph_image(arrays, attrs, field, kind, axis or "z", 0.0 if at is None else at, npix)
            else:
                image = grid_image(arrays, attrs, field, kind, axis, at)
        except ValueError as exc:
            raise UserError(f"plot --movie: {exc}") from None
        frames.append((float(attrs.get("time", 0.0)), image))
    if not frames:
        raise UserError(f"{run}: no snapshots for a movie")
    return frames


def write_movie(run: str | Path, output: str | Path, field: str = "rho", kind: str = "slice",
                axis: str | None = None, at: float | None = None, log: bool = False, fps: int = 5,
                npix: int = 256) -> Path:
    """Animate ``field`` over the snapshots of ``run`` into ``output`` (``.mp4`` or ``.gif``)."""
    from matplotlib import animation

    output = Path(output)
    if output.suffix not in (".mp4", ".gif"):
        raise UserError(f"--movie {output}: the file must end in .mp4 (ffmpeg) or .gif (Pillow)")
    if output.suffix == ".mp4" and not animation.FFMpegWriter.isAvailable():
        raise UserError("--movie *.mp4 needs ffmpeg on PATH (apt-get install ffmpeg), or write a .gif")
    frames = movie_frames(run, field, kind, axis, at, npix)
    values = np.concatenate([img.values.ravel() for _, img in frames])
    finite = values[np.isfinite(values) & ((values > 0) if log else True)]
    vmin, vmax = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    if vmax <= vmin:
        vmax = vmin + (abs(vmin) or 1.0) * 1e-12
    writer = animation.FFMpegWriter(fps=fps, codec="libx264", extra_args=["-pix_fmt", "yuv420p"]) \
        if output.suffix == ".mp4" else animation.PillowWriter(fps=fps)
    with house_style():
        t0, first = frames[0]
        fig = image_figure(first, t0, log, vmin, vmax)
        ax = fig.axes[0]
        im = ax.images[0]
        output.parent.mkdir(parents=True, exist_ok=True)
        tmp = output.with_name(f".{output.stem}.tmp{output.suffix}")
        try:
            with writer.saving(fig, str(tmp), dpi=100):
                for t, image in frames:
                    im.set_data(image.values)
                    ax.set_title(f"t = {t:.4g}" + (f", {image.title}" if image.title else ""), loc="left", fontsize=9)
                    writer.grab_frame()
            tmp.replace(output)
        finally:
            tmp.unlink(missing_ok=True)
    return output
