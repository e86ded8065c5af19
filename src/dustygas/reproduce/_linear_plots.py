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


# ---------------------------------------------------------------------------- shearing-wave sweeps


def _cells(ax, values: np.ndarray, xs, ys, xlabel: str, ylabel: str, cmap: str, annotate: str | None = None,
           **kw):
    """A (len(ys), len(xs)) array as labelled cells (works for any grid, one point included)."""
    im = ax.pcolormesh(np.arange(len(xs) + 1) - 0.5, np.arange(len(ys) + 1) - 0.5, values, cmap=cmap,
                       shading="flat", **kw)
    step_x = max(1, -(-len(xs) // 6))
    step_y = max(1, -(-len(ys) // 8))
    ax.set_xticks(np.arange(len(xs))[::step_x], [f"{v:.3g}" for v in xs][::step_x])
    ax.set_yticks(np.arange(len(ys))[::step_y], [f"{v:.3g}" for v in ys][::step_y])
    ax.minorticks_off()
    ax.grid(False)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if annotate and values.size <= 64:
        from matplotlib import patheffects

        halo = [patheffects.withStroke(linewidth=2, foreground="w")]
        for (j, i), v in np.ndenumerate(values):
            if np.isfinite(v):
                ax.text(i, j, format(v, annotate), ha="center", va="center", fontsize=7, color="k", path_effects=halo)
    return im


def plot_sweep(result, outdir: Path) -> list[Path]:
    """Figures of a shearing-wave sweep (:class:`dustygas.linear.sweep.SweepResult`).

    ``sweep_amplification.png``: the largest ``metric`` over (K_x0, K_y) for every (μ, τ_s), and
    the (K_x0, K_y) map of ``log10 metric`` at the (μ, τ_s) where it is largest;
    ``sweep_angle.png``: the preferred angle arctan(K_y/K_x(t_end)) versus (μ, τ_s). Each with a
    CSV of the numbers drawn.
    """
    from ..plot.style import Column, house_style, new_figure, save_figure

    spec = result.spec
    metric = spec.metric
    pref = result.preferred()
    mu, taus = np.asarray(spec.mu), np.asarray(spec.taus)
    M, T = np.meshgrid(mu, taus, indexing="ij")
    t_end = "each leading wave's swing" if spec.t_end == "swing" else f"t_end = {spec.t_end:.4g}/Ω"
    note = (f"{metric} ({t_end}, initial state: {spec.initial}); Kz = {spec.kz:g}, Π = {spec.Pi:g}, "
            f"drag {spec.drag}")
    paths: list[Path] = []
    with house_style():
        fig, axes = new_figure(1, 2, width=10.0, height=4.2)
        with np.errstate(divide="ignore", invalid="ignore"):
            lv = np.log10(pref["value"])
        im = _cells(axes[0], lv.T, mu, taus, r"dust-to-gas ratio $\mu$", r"stopping time $\tau_s$", "viridis", ".2f")
        fig.colorbar(im, ax=axes[0], label=rf"$\log_{{10}}$ max {metric}")
        v = pref["value"]
        if np.isfinite(v).any():
            i, j = np.unravel_index(np.nanargmax(v), v.shape)
            with np.errstate(divide="ignore", invalid="ignore"):
                plane = np.log10(result[metric][i, j])
            kx, ky = np.asarray(spec.kx), np.asarray(spec.ky)
            im1 = _cells(axes[1], plane.T, kx, ky, r"initial $K_{x0} = k_{x0}\eta r$", r"$K_y = k_y\eta r$", "magma")
            ix, iy = int(np.argmin(np.abs(kx - pref["kx0"][i, j]))), int(np.argmin(np.abs(ky - pref["ky"][i, j])))
            axes[1].plot([ix], [iy], marker="x", color="c", ms=10, mew=2)
            axes[1].set_title(rf"$\mu$ = {mu[i]:.3g}, $\tau_s$ = {taus[j]:.3g}", fontsize=9)
            fig.colorbar(im1, ax=axes[1], label=rf"$\log_{{10}}$ {metric}")
        fig.suptitle("Shearing-wave sweep (thesis §4.6): amplification\n" + note, fontsize=9)
        paths += save_figure(fig, outdir / "sweep_amplification.png", [
            Column("mu", M, "1", "dust-to-gas ratio"), Column("taus", T, "1", "stopping time Omega t_s"),
            Column("max_value", pref["value"], "1", f"largest {metric} over (kx0, ky)"),
            Column("kx0", pref["kx0"], "1/(eta r)", "initial K_x of the maximum"),
            Column("ky", pref["ky"], "1/(eta r)", "K_y of the maximum")],
            title="shearing-wave sweep: largest amplification per (mu, taus)", description=note)
        fig, ax = new_figure(1, 1, width=5.6, height=4.2)
        im = _cells(ax, pref["angle_deg"].T, mu, taus, r"dust-to-gas ratio $\mu$", r"stopping time $\tau_s$",
                    "twilight_shifted", ".1f", vmin=-90.0, vmax=90.0)  # a cyclic map: -90 and 90 deg are one angle
        for (jj, ii), e in np.ndenumerate(pref["at_edge"].T):
            if e:
                ax.plot([ii], [jj - 0.3], marker="^", color="c", ms=4)
        if pref["at_edge"].any():
            note += "\ncyan triangles: maximum on the edge of the (K_x0, K_y) grid"
        fig.colorbar(im, ax=ax, label=r"preferred angle $\arctan(K_y/K_x(t_{end}))$ [deg]")
        ax.set_title("Preferred wavevector of the shearing-wave sweep\n" + note, fontsize=8)
        paths += save_figure(fig, outdir / "sweep_angle.png", [
            Column("mu", M, "1", "dust-to-gas ratio"), Column("taus", T, "1", "stopping time Omega t_s"),
            Column("angle_deg", pref["angle_deg"], "deg", "arctan(K_y / K_x(t_end)) of the most amplified wave"),
            Column("angle0_deg", pref["angle0_deg"], "deg", "arctan(K_y / K_x0), its initial angle"),
            Column("kx0", pref["kx0"], "1/(eta r)", "initial K_x"), Column("ky", pref["ky"], "1/(eta r)", "K_y"),
            Column("kx_end", pref["kx_end"], "1/(eta r)", "K_x at t_end"),
            Column("value", pref["value"], "1", metric),
            Column("at_edge", pref["at_edge"], "1", "1: the maximum is on the edge of the (K_x0, K_y) grid")],
            title="shearing-wave sweep: preferred wavevector angle", description=note)
    return paths
