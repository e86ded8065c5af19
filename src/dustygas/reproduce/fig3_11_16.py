"""Thesis Figures 3.11-3.16: particle splitting and the :math:`\\tau_s = 1` dust ring at 52 au, split vs unsplit.

From the ``drift-ring-split`` run (gas split eight-fold in 40-70 au, four- and two-fold in 10 au
buffers, :func:`dustygas.sph.splitting.split_band`) and the 52 au ring of the ``drift-ring`` run
(:mod:`~dustygas.reproduce._disk_runs`), analysed with :mod:`dustygas.analysis.disk`:

* 3.11 -- gas particles within one smoothing length of the midplane inside 60 au, split and unsplit;
* 3.12 -- the spacing ratio :math:`l_u/l_s`, :math:`l = (m/\\rho)^{1/3}`, in bins of cylindrical radius
  (2, 1.6 and 1.26 expected in the eight-, four- and two-fold zones);
* 3.13 / 3.14 -- mean radial velocity / mean radius of the ring;
* 3.15 / 3.16 -- their standard deviations.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._disk_runs import disk_run, padded, ring_index

__all__ = ["fig3_11", "fig3_12", "fig3_13", "fig3_14", "fig3_15", "fig3_16"]

_DESC = "split run {split} and unsplit run {unsplit} (sph-disk problems, thesis §3.3.3)"
_COST = "6 min (the drift-ring-split run, shared with figs 3.12-3.16, and the drift-ring run)"


def _runs(output, quick, runs):
    return disk_run(True, output, quick, runs), disk_run(False, output, quick, runs)


@figure("fig3.11", "Midplane gas particles inside 60 au, split vs unsplit disk", cost=_COST)
def fig3_11(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..analysis.disk import midplane_positions
    from ..plot import Column, house_style, new_figure, save_figure

    split, unsplit = _runs(output, quick, runs)
    cols = []
    with house_style():
        fig, axes = new_figure(1, 2, width=8.0, height=4.2, sharey=True)
        for ax, run, label in zip(axes, (split, unsplit), ("split", "unsplit")):
            x, y = midplane_positions(run)
            ax.scatter(x, y, s=0.5, color="k", lw=0)
            ax.set_aspect("equal")
            ax.set_title(f"{label} ({x.size} particles)")
            ax.set_xlabel("x [au]")
            cols += [Column(f"x_{label}", x, "au", f"x of the {label} disk's midplane particles"),
                     Column(f"y_{label}", y, "au", f"y of the {label} disk's midplane particles")]
        axes[0].set_ylabel("y [au]")
        return save_figure(fig, output / "fig3_11.png", padded(cols),
                           title="thesis Figure 3.11: midplane particles, split vs unsplit",
                           description=_DESC.format(split=split, unsplit=unsplit) + "; |z| < h, R < 60 au, t = 0")


@figure("fig3.12", "Particle spacing ratio l_u/l_s, l = (m/rho)^(1/3), in radial bins (split vs unsplit)", cost=_COST)
def fig3_12(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..analysis.disk import spacing_profile
    from ..plot import Column, house_style, new_figure, save_figure

    split, unsplit = _runs(output, quick, runs)
    edges = np.arange(5.0, 125.0, 5.0)
    ratio = spacing_profile(unsplit, edges) / spacing_profile(split, edges)
    centre = 0.5 * (edges[1:] + edges[:-1])
    with house_style():
        fig, ax = new_figure(1, 1, width=5.5, height=3.4)
        ax.bar(centre, ratio, width=np.diff(edges) * 0.9, color="C0")
        for level in (2.0 ** (1 / 3), 4.0 ** (1 / 3), 2.0):
            ax.axhline(level, color="0.5", lw=0.8, ls="--")
        ax.set_xlabel(r"$R$ [au]")
        ax.set_ylabel(r"$l_u / l_s$")
        return save_figure(fig, output / "fig3_12.png",
                           [Column("R_lo", edges[:-1], "au", "inner edge of the bin"),
                            Column("R_hi", edges[1:], "au", "outer edge of the bin"),
                            Column("ratio", ratio, "", "mean spacing unsplit / split")],
                           title="thesis Figure 3.12: spacing ratio l_u/l_s",
                           description=_DESC.format(split=split, unsplit=unsplit) + "; dashed: 2^(1/3), 4^(1/3), 2")


def _ring_pair(output, quick, runs):
    from ..analysis.disk import ring_series

    split, unsplit = _runs(output, quick, runs)
    return (ring_series(split, ring_index(split, 52.0, 1.0)), ring_series(unsplit, ring_index(unsplit, 52.0, 1.0)),
            split, unsplit)


def _pair_figure(output, quick, runs, number, quantity, ylabel, unit, title):
    from ..plot import Column, house_style, new_figure, save_figure

    s, u, split, unsplit = _ring_pair(output, quick, runs)
    cols = []
    with house_style():
        fig, ax = new_figure(1, 1, width=5.5, height=3.6)
        for series, label, color in ((s, "split", "C3"), (u, "unsplit", "C0")):
            y = quantity(series)
            ax.plot(series.orbits, y, color=color, label=label)
            cols += [Column(f"orbits_{label}", series.orbits, "orbits", f"time at the {label} ring's mean radius"),
                     Column(f"value_{label}", y, unit, f"{title} ({label})")]
            if number == 13:
                ax.plot(series.orbits, series.drift_setup / series.v_kepler, color=color, ls="--", lw=0.9)
                cols.append(Column(f"drift_setup_{label}", series.drift_setup / series.v_kepler, unit,
                                   f"eq. 3.23 with the set-up's eta ({label})"))
        if number == 13:
            ax.plot([], [], "k--", lw=0.9, label=r"eq. 3.23, set-up $\eta$")
            ax.axhline(0.0, color="k", lw=0.5)
        ax.set_xlabel(r"time [orbits at $\langle R\rangle$]")
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=7)
        return save_figure(fig, output / f"fig3_{number}.png", padded(cols), title=f"thesis Figure 3.{number}: {title}",
                           description=_DESC.format(split=split, unsplit=unsplit) + "; tau_s = 1 ring at 52 au")


@figure("fig3.13", "Mean radial velocity of the tau_s = 1 ring at 52 au, split vs unsplit disk", cost=_COST)
def fig3_13(output: Path, quick: bool = True, runs=None) -> list[Path]:
    return _pair_figure(output, quick, runs, 13, lambda s: s.mean_vR / s.v_kepler, r"$\langle v_R\rangle / v_K$",
                        "v_K", "mean radial velocity of the dust")


@figure("fig3.14", "Mean radius of the tau_s = 1 ring at 52 au, split vs unsplit disk", cost=_COST)
def fig3_14(output: Path, quick: bool = True, runs=None) -> list[Path]:
    return _pair_figure(output, quick, runs, 14, lambda s: s.mean_R, r"$\langle R\rangle$ [au]", "au",
                        "mean radius of the dust")


@figure("fig3.15", "Standard deviation of the radial velocity of the tau_s = 1 ring at 52 au, split vs unsplit",
        cost=_COST)
def fig3_15(output: Path, quick: bool = True, runs=None) -> list[Path]:
    return _pair_figure(output, quick, runs, 15, lambda s: s.std_vR / s.v_kepler, r"$\sigma_{v_R} / v_K$",
                        "v_K", "standard deviation of the dust's radial velocity")


@figure("fig3.16", "Standard deviation of the radius of the tau_s = 1 ring at 52 au, split vs unsplit", cost=_COST)
def fig3_16(output: Path, quick: bool = True, runs=None) -> list[Path]:
    return _pair_figure(output, quick, runs, 16, lambda s: s.std_R, r"$\sigma_R$ [au]", "au",
                        "standard deviation of the dust's radii")
