"""Plots and data files shared by the linear-theory figures and ``dustygas linear``.

Self-contained matplotlib (Agg) until the project-wide :mod:`dustygas.plot` style lands:
labelled axes with units, legends, and the numbers behind every PNG written next to it.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path
from typing import Any, Sequence

import numpy as np


def pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def write_csv(path: Path, columns: dict[str, Sequence], header: Sequence[str] = ()) -> Path:
    """CSV with ``# key: value`` comment lines first (units, k-range, conventions)."""
    names = list(columns)
    n = len(next(iter(columns.values())))
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "w", newline="") as fh:
        for line in header:
            fh.write(f"# {line}\n")
        w = csv.writer(fh)
        w.writerow(names)
        for i in range(n):
            w.writerow([_fmt(columns[c][i]) for c in names])
    tmp.replace(path)
    return path


def _fmt(v: Any) -> str:
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    return str(v)


def write_json(path: Path, data: dict) -> Path:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data, indent=1, default=_json_default))
    tmp.replace(path)
    return path


def _json_default(o):
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, (np.floating, np.integer, np.bool_)):
        return o.item()
    raise TypeError(type(o))


def k_range_text(attrs: dict) -> str:
    """One line stating the wavenumber range a maximum was taken over."""
    method = attrs.get("method")
    if method == "kx":
        lo, hi = attrs["kx_range"]
        return f"max over {lo:g} ≤ Kx ≤ {hi:g} at Kz = {attrs['kz']:g}"
    if method == "box":
        (a, b), (c, d) = attrs["kx_range"], attrs["kz_range"]
        return f"max over {a:g} ≤ Kx ≤ {b:g}, {c:g} ≤ Kz ≤ {d:g}"
    lo, hi = attrs["k_range"]
    sign = "±" if attrs.get("mirror") else ""
    return f"max over {lo:g} ≤ |K| ≤ {hi:g} at θk = {sign}{attrs['theta_deg']:g}°"


def plot_growth_map(gmap, path: Path, title: str = "") -> Path:
    """Two panels: log10(2π s/Ω) and the wavenumber of the maximum over (μ, τ_s)."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    X, Y = np.meshgrid(gmap.mu, gmap.taus)
    with np.errstate(divide="ignore", invalid="ignore"):
        lg = np.log10(2 * math.pi * np.where(gmap.growth > 0, gmap.growth, np.nan))
    levels = np.arange(np.floor(np.nanmin(lg)) if np.isfinite(np.nanmin(lg)) else -6, 1.01, 0.5)
    c0 = axes[0].contourf(X, Y, lg, levels=levels, cmap="viridis", extend="both")
    axes[0].contour(X, Y, lg, levels=[-1.0], colors="w", linewidths=1.2)
    fig.colorbar(c0, ax=axes[0], label=r"$\log_{10}(2\pi s/\Omega)$  (white: $e$-folding in 10 orbits)")
    kname = "Kx" if gmap.attrs.get("method") in ("kx", "box") else "|K|"
    kval = gmap.kx if kname == "Kx" else np.hypot(gmap.kx, gmap.kz)
    c1 = axes[1].contourf(X, Y, np.log10(kval), levels=20, cmap="magma")
    fig.colorbar(c1, ax=axes[1], label=rf"$\log_{{10}}$ {kname} $= k\eta r$ of the fastest mode")
    if gmap.at_edge.any():
        axes[1].contour(X, Y, gmap.at_edge.astype(float), levels=[0.5], colors="c", linewidths=1.0)
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel(r"dust-to-gas ratio $\mu = \rho_{p0}/\rho_{g0}$")
        ax.set_ylabel(r"stopping time $\tau_s = \Omega t_s$")
    drag = "incompressible: the drag linearisations coincide" if gmap.attrs["Pi"] == 0 else f"drag: {gmap.attrs['drag']}"
    note = f"{k_range_text(gmap.attrs)};  Π = {gmap.attrs['Pi']:g} ({drag})"
    if gmap.at_edge.any():
        note += "  (cyan: maximum on the k-range edge)"
    fig.suptitle((title + "\n" if title else "") + note, fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _legend_label(name: str) -> str:
    """``"taus=0.1 mu=3"`` (the CSV column name) as ``τ_s = 0.1, μ = 3`` in mathtext."""
    symbols = {"taus": r"$\tau_s$", "mu": r"$\mu$"}
    parts = [p.split("=", 1) for p in name.split()]
    if not all(len(p) == 2 and p[0] in symbols for p in parts):
        return name
    return ", ".join(f"{symbols[key]} = {value}" for key, value in parts)


def plot_growth_vs_k(k, curves: list[tuple[str, np.ndarray]], path: Path, title: str, note: str,
                     ylim=(1e-6, 1.0), markers: Sequence[tuple[float, float, int]] = ()) -> Path:
    """Growth rate (log axis; damped or non-growing points left out) versus |K|.

    ``markers``: measured points ``(K, s, index of the curve they belong to)``, drawn as
    crosses in that curve's colour (thesis Fig 4.6).
    """
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.2, 4.8), constrained_layout=True)
    lines = []
    for label, s in curves:
        lines += ax.loglog(k, np.where(s > 0, s, np.nan), label=_legend_label(label), lw=1.4)
    for kk, s, i in markers:
        ax.plot([kk], [s], marker="x", ms=9, mew=2.2, ls="none", color=lines[i].get_color())
    ax.set_xlabel(r"wavenumber $|K| = |k|\eta r$")
    ax.set_ylabel(r"growth rate $s/\Omega$ of the fastest mode")
    ax.set_ylim(*ylim)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    ax.set_title(title + "\n" + note, fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
