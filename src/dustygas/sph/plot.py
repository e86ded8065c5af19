"""Figures of SPH snapshots: particle profiles against x (or R), and rendered maps.

Both functions take a snapshot file written by the run loop (``RUN/snapshots/snap_NNNNN.h5``)
or the ``(arrays, attrs)`` pair of :meth:`SPHEngine.snapshot`, and return the matplotlib
figure (saved to ``output`` when given).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable

import numpy as np

from ..io import read_h5
from .render import render_plane

__all__ = ["plot_profiles", "plot_map"]

_LABELS = {"rho": r"$\rho$", "vx": r"$v_x$", "P": r"$P$", "u": r"$u$", "vphi": r"$v_\phi$", "alpha": r"$\alpha$"}


def _load(snapshot) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    if isinstance(snapshot, (str, Path)):
        return read_h5(snapshot)
    return snapshot


def _field(arrays: dict[str, np.ndarray], name: str) -> np.ndarray:
    if name == "vx":
        return arrays["vel"][:, 0]
    if name == "vphi":
        x, y = arrays["pos"][:, 0], arrays["pos"][:, 1]
        return (x * arrays["vel"][:, 1] - y * arrays["vel"][:, 0]) / np.hypot(x, y)
    return arrays[name]


def plot_profiles(snapshot, fields=("rho", "vx", "P"), radial: bool = False,
                  exact: Callable[[np.ndarray, float], dict[str, np.ndarray]] | None = None,
                  output: str | Path | None = None):
    """Each particle's ``fields`` against x (or the cylindrical radius with ``radial``), with an
    optional exact solution ``exact(x, t) -> {field: values}`` drawn as a line."""
    import matplotlib.pyplot as plt

    arrays, attrs = _load(snapshot)
    pos = arrays["pos"]
    x = np.hypot(pos[:, 0], pos[:, 1]) if radial else pos[:, 0]
    fig, axes = plt.subplots(1, len(fields), figsize=(4.2 * len(fields), 3.4), squeeze=False)
    t = float(attrs.get("time", 0.0))
    line = None
    if exact is not None:
        xs = np.linspace(x.min(), x.max(), 2000)
        line = (xs, exact(xs, t))
    for ax, name in zip(axes[0], fields):
        ax.plot(x, _field(arrays, name), ".", ms=1.5, color="C0", label="SPH")
        if line is not None and name in line[1]:
            ax.plot(line[0], line[1][name], "k-", lw=0.8, label="exact")
        ax.set_xlabel("R" if radial else "x")
        ax.set_ylabel(_LABELS.get(name, name))
    axes[0][0].set_title(f"t = {t:.4g}", loc="left", fontsize=9)
    if line is not None:
        axes[0][0].legend(fontsize=8, frameon=False)
    fig.tight_layout()
    if output is not None:
        fig.savefig(output, dpi=150)
    return fig


def plot_map(snapshot, field: str = "rho", npix: int = 256, extent=None, z0: float = 0.0, log: bool = False,
             output: str | Path | None = None):
    """Rendered map of ``field`` (:func:`~dustygas.sph.render.render_plane`) of a 2D or 3D snapshot."""
    import matplotlib.pyplot as plt

    arrays, attrs = _load(snapshot)
    ndim = int(attrs["ndim"])
    pos = arrays["pos"]
    if extent is None:
        lo, hi = pos[:, :2].min(axis=0), pos[:, :2].max(axis=0)
        extent = (lo[0], hi[0], lo[1], hi[1])
    img = render_plane(pos, arrays["mass"], arrays["rho"], arrays["h"], _field(arrays, field), str(attrs["kernel"]),
                       ndim, extent, npix, z0=z0)
    fig, ax = plt.subplots(figsize=(5.2, 4.4))
    shown = np.log10(np.maximum(img, 1e-300)) if log else img
    im = ax.imshow(shown, origin="lower", extent=extent, cmap="magma", aspect="equal")
    fig.colorbar(im, ax=ax, label=("log " if log else "") + _LABELS.get(field, field))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_title(f"t = {float(attrs.get('time', 0.0)):.4g}" + (f", z = {z0:g}" if ndim == 3 else ""), fontsize=9)
    fig.tight_layout()
    if output is not None:
        fig.savefig(output, dpi=150)
    return fig
