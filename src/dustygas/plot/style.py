"""House style for publication-quality PNGs, and atomic saving of a figure plus its data.

Every figure is written as ``NAME.png`` with ``NAME.csv`` next to it. The CSV starts with
``#`` comment lines (title, description, one line per column with its unit and meaning), then
one header row of column names, then the data at full double precision::

    # thesis Figure 3.5: radial drift velocity ...
    # column tau_s [1]: dimensionless stopping time t_s Omega
    # column minus_vr_over_vK [1]: -v_r / v_K of the dust (eq. 3.23)
    tau_s,minus_vr_over_vK
    0.001,4.4999955000045e-05

:func:`read_table` reads it back (so does ``pandas.read_csv(path, comment="#")``).
Both files are written to temporary names and renamed (:func:`dustygas.io.atomic_path`).
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from pathlib import Path
from typing import Iterator, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._version import __version__
from ..io.atomic import atomic_path

__all__ = ["HOUSE_STYLE", "Column", "house_style", "new_figure", "save_figure", "read_table"]

#: rcParams of the house style: serif mathtext, inward ticks on all sides, light grid, 150 dpi.
HOUSE_STYLE: dict = {
    "figure.dpi": 150,
    "savefig.dpi": 150,
    "savefig.bbox": "tight",
    "savefig.pad_inches": 0.05,
    "font.size": 10,
    "font.family": "serif",
    "mathtext.fontset": "dejavuserif",
    "axes.labelsize": 11,
    "axes.titlesize": 11,
    "axes.linewidth": 0.8,
    "axes.grid": True,
    "axes.grid.which": "major",
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    "lines.linewidth": 1.6,
    "legend.fontsize": 9,
    "legend.frameon": False,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "xtick.minor.visible": True,
    "ytick.minor.visible": True,
}


@dataclass(frozen=True)
class Column:
    """One column of a figure's data file: ``name`` (an identifier), values, unit, meaning."""

    name: str
    values: ArrayLike
    unit: str
    description: str = ""


@contextlib.contextmanager
def house_style() -> Iterator[None]:
    """Context in which figures are created and drawn with :data:`HOUSE_STYLE`."""
    import matplotlib

    with matplotlib.rc_context(HOUSE_STYLE):
        yield


def new_figure(nrows: int = 1, ncols: int = 1, width: float = 5.0, height: float = 3.6, **subplots_kw) -> tuple:
    """A :class:`~matplotlib.figure.Figure` (Agg, no pyplot) and its axes; size in inches."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=True, **subplots_kw)
    return fig, axes


def _check_columns(columns: Sequence[Column]) -> list[np.ndarray]:
    arrays = [np.asarray(c.values, dtype=np.float64).ravel() for c in columns]
    if not arrays:
        raise ValueError("save_figure: no data columns")
    if len({a.size for a in arrays}) != 1:
        raise ValueError("save_figure: columns differ in length: " + ", ".join(f"{c.name}={a.size}" for c, a in zip(columns, arrays)))
    for c in columns:
        if not c.name.isidentifier():
            raise ValueError(f"save_figure: column name {c.name!r} is not an identifier")
    return arrays


def save_figure(fig, png_path: str | Path, columns: Sequence[Column], title: str = "", description: str = "") -> list[Path]:
    """Write ``fig`` as a PNG and its data as a CSV next to it (same stem), both atomically.

    Returns ``[png_path, csv_path]``.
    """
    png_path = Path(png_path)
    csv_path = png_path.with_suffix(".csv")
    arrays = _check_columns(columns)
    lines = [f"# {title}" if title else None, *(f"# {ln}" for ln in description.splitlines() if ln.strip()),
             f"# written by dustygas {__version__}"]
    lines += [f"# column {c.name} [{c.unit}]: {c.description}".rstrip(": ") for c in columns]
    lines.append(",".join(c.name for c in columns))
    table = np.column_stack(arrays)
    body = "\n".join(",".join(map(repr, row)) for row in table.tolist())  # shortest exact repr
    text = "\n".join(ln for ln in lines if ln is not None) + "\n" + body + "\n"
    with atomic_path(csv_path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    with atomic_path(png_path) as tmp:
        with open(tmp, "wb") as fh:
            fig.savefig(fh, format="png")
    return [png_path, csv_path]


def read_table(path: str | Path) -> dict[str, np.ndarray]:
    """Read a CSV written by :func:`save_figure`: column name -> float array."""
    rows = [ln for ln in Path(path).read_text(encoding="utf-8").splitlines() if ln and not ln.startswith("#")]
    names = rows[0].split(",")
    data = np.array([[float(x) for x in ln.split(",")] for ln in rows[1:]], dtype=np.float64).reshape(-1, len(names))
    return {name: data[:, i] for i, name in enumerate(names)}
