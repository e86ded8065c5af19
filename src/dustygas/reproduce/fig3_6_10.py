"""Thesis Figures 3.6-3.10: the radial-drift rings at 20 au and the random walk of the gas particles.

All five come from one ``drift-ring`` run (:mod:`~dustygas.reproduce._disk_runs`): 1000 two-fluid
dust particles of :math:`\\tau_s = 1` and 1000 of :math:`\\tau_s = 10` on a ring at 20 au in the
thesis's gas disk (:mod:`dustygas.problems.sph_disk`), analysed with :mod:`dustygas.analysis.disk`.

* 3.6 -- ring positions in the x-y plane at four times, :math:`\\tau_s = 1` left, 10 right;
* 3.7 -- mean radial velocity of the :math:`\\tau_s = 1` dust against time in orbits at the ring's mean
  radius, with the drift of eq. 3.23 for the set-up's :math:`\\eta` and for the disk's own gas;
* 3.8 -- mean radius, with eq. 3.23 integrated from 20 au;
* 3.9 -- velocity dispersions :math:`\\sigma_R, \\sigma_\\phi, \\sigma_z` of the dust (solid) and of the gas
  around the ring (dashed) in units of :math:`v_K`, with :math:`|v_r|` of eq. 3.23 (grey dashed);
* 3.10 -- :math:`R`-:math:`z` paths of gas particles started in the midplane at 10, 20 and 40 au, with
  :math:`\\pm H`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._disk_runs import disk_run, padded, ring_index

__all__ = ["fig3_6", "fig3_7", "fig3_8", "fig3_9", "fig3_10"]

_DESC = "drift-ring run {run}: 3D gas disk 5-200 au, Sigma ~ 1/R, H/R = 0.05 at 20 au, two-fluid dust rings"


def _series(run, taus):
    from ..analysis.disk import ring_series

    return ring_series(run, ring_index(run, 20.0, taus))


@figure("fig3.6", "Dust-ring positions in the x-y plane at four times, tau_s = 1 and 10 (drift-ring run)",
        cost="3 min (the drift-ring run, shared with figs 3.7-3.10, 3.13-3.16)")
def fig3_6(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..analysis.disk import ring_positions
    from ..plot import Column, house_style, new_figure, save_figure

    run = disk_run(False, output, quick, runs)
    rings = [ring_index(run, 20.0, 1.0), ring_index(run, 20.0, 10.0)]
    snaps = ring_positions(run)
    orbits = np.array([s["time"] for s in snaps]) / ORBIT
    picks = [int(np.argmin(abs(orbits - o))) for o in (0.0, 1.0, 2.0, 4.0)]
    picks = sorted(set(picks))
    cols = []
    with house_style():
        fig, axes = new_figure(len(picks), 2, width=6.0, height=2.9 * len(picks), sharex=True, sharey=True)
        axes = np.asarray(axes).reshape(len(picks), 2)
        for row, i in enumerate(picks):
            for col, (k, taus) in enumerate(zip(rings, (1, 10))):
                x, y = snaps[i]["rings"][k]
                ax = axes[row, col]
                ax.scatter(x, y, s=1.5, color="C0" if col == 0 else "C3", lw=0)
                ax.set_aspect("equal")
                ax.text(0.04, 0.9, f"{orbits[i]:.1f} orbits", transform=ax.transAxes, fontsize=8)
                if row == 0:
                    ax.set_title(rf"$\tau_s = {taus}$")
                if row == len(picks) - 1:
                    ax.set_xlabel("x [au]")
                if col == 0:
                    ax.set_ylabel("y [au]")
                cols += [Column(f"x_tau{taus}_{row}", x, "au", f"x of the tau_s = {taus} dust at {orbits[i]:.2f} orbits"),
                         Column(f"y_tau{taus}_{row}", y, "au", f"y of the tau_s = {taus} dust at {orbits[i]:.2f} orbits")]
        return save_figure(fig, output / "fig3_6.png", padded(cols), title="thesis Figure 3.6: dust-ring positions",
                           description=_DESC.format(run=run) + "; times in orbits at 20 au")


ORBIT = 2.0 * np.pi * 20.0**1.5


def _mean_band(ax, x, mean, std):
    """The dust's mean with a one-sigma band."""
    ax.plot(x, mean, color="C0", label="dust, mean")
    ax.fill_between(x, mean - std, mean + std, color="C0", alpha=0.15, lw=0, label=r"$\pm 1\sigma$")


def _drift_columns(s, tag):
    from ..plot import Column

    return [Column(f"time_{tag}", s.time, "yr/2pi", "time (code units)"),
            Column(f"orbits_{tag}", s.orbits, "orbits", "time in orbital periods at the ring's mean radius"),
            Column(f"mean_R_{tag}", s.mean_R, "au", "mean cylindrical radius of the dust"),
            Column(f"std_R_{tag}", s.std_R, "au", "standard deviation of the dust's radii"),
            Column(f"mean_vR_{tag}", s.mean_vR / s.v_kepler, "v_K", "mean radial velocity of the dust"),
            Column(f"std_vR_{tag}", s.std_vR / s.v_kepler, "v_K", "standard deviation of the dust's radial velocity"),
            Column(f"drift_setup_{tag}", s.drift_setup / s.v_kepler, "v_K", "eq. 3.23 with the set-up's eta"),
            Column(f"drift_disk_{tag}", s.drift_disk / s.v_kepler, "v_K",
                   "eq. 3.23 with the disk's gas rotation (eta) and radial velocity")]


@figure("fig3.7", "Mean radial velocity of the tau_s = 1 (and 10) dust rings vs time, with eq. 3.23 (drift-ring run)",
        cost="shares the drift-ring run")
def fig3_7(output: Path, quick: bool = True, runs=None) -> list[Path]:
    """The thesis's Figure 3.7 (tau_s = 1), with the tau_s = 10 ring of the same run below it."""
    from ..plot import house_style, new_figure, save_figure

    run = disk_run(False, output, quick, runs)
    cols = []
    with house_style():
        fig, axes = new_figure(2, 1, width=5.5, height=6.4)
        for ax, taus in zip(axes, (1.0, 10.0)):
            s = _series(run, taus)
            _mean_band(ax, s.orbits, s.mean_vR / s.v_kepler, s.std_vR / s.v_kepler)
            ax.plot(s.orbits, s.drift_setup / s.v_kepler, "k--", lw=1.2, label=r"eq. 3.23, set-up $\eta$")
            ax.plot(s.orbits, s.drift_disk / s.v_kepler, color="0.5", lw=1.0, label=r"eq. 3.23, the disk's gas")
            ax.axhline(0.0, color="k", lw=0.5)
            ax.set_ylabel(r"$\langle v_R\rangle / v_K$")
            ax.text(0.97, 0.9, rf"$\tau_s = {taus:g}$", transform=ax.transAxes, ha="right")
            cols += _drift_columns(s, f"tau{taus:g}")
        axes[0].legend(fontsize=7)
        axes[1].set_xlabel(r"time [orbits at $\langle R\rangle$]")
        return save_figure(fig, output / "fig3_7.png", padded(cols),
                           title="thesis Figure 3.7: mean radial velocity of the dust rings",
                           description=_DESC.format(run=run))


@figure("fig3.8", "Mean radius of the tau_s = 1 dust ring vs time, with eq. 3.23 integrated (drift-ring run)",
        cost="shares the drift-ring run")
def fig3_8(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..analysis.disk import disk_of, grain_stokes
    from ..physics.disk import radial_drift_velocity
    from ..plot import Column, house_style, new_figure, save_figure

    run = disk_run(False, output, quick, runs)
    s = _series(run, 1.0)
    disk = disk_of(run)
    R = np.empty_like(s.time)  # eq. 3.23 integrated from the ring radius (grains of fixed size)
    R[0] = s.mean_R[0]
    for i in range(1, s.time.size):
        taus = grain_stokes(disk, R[i - 1], float(s.taus[0]), float(s.mean_R[0]))
        v = float(radial_drift_velocity(taus, disk.eta(R[i - 1]), disk.v_kepler(R[i - 1])))
        R[i] = R[i - 1] + v * (s.time[i] - s.time[i - 1])
    with house_style():
        fig, ax = new_figure(1, 1, width=5.5, height=3.6)
        _mean_band(ax, s.orbits, s.mean_R, s.std_R)
        ax.plot(s.orbits, R, "k--", lw=1.2, label=r"eq. 3.23, set-up $\eta$")
        ax.set_xlabel(r"time [orbits at $\langle R\rangle$]")
        ax.set_ylabel(r"$\langle R\rangle$ [au]")
        ax.legend(fontsize=7)
        cols = _drift_columns(s, "tau1") + [Column("R_eq323", R, "au", "eq. 3.23 integrated from the start")]
        return save_figure(fig, output / "fig3_8.png", cols,
                           title="thesis Figure 3.8: mean radius of the tau_s = 1 dust ring",
                           description=_DESC.format(run=run))


@figure("fig3.9", "Velocity dispersions (R, phi, z) of gas and dust around the tau_s = 1 and 10 rings (drift-ring run)",
        cost="shares the drift-ring run")
def fig3_9(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..plot import Column, house_style, new_figure, save_figure

    run = disk_run(False, output, quick, runs)
    cols = []
    with house_style():
        fig, axes = new_figure(2, 1, width=5.5, height=6.4, sharex=True)
        for ax, taus in zip(axes, (1.0, 10.0)):
            s = _series(run, taus)
            tag = f"tau{taus:g}"
            cols.append(Column(f"orbits_{tag}", s.orbits, "orbits", f"time at the tau_s = {taus:g} ring"))
            for comp, color in (("R", "C0"), ("phi", "C1"), ("z", "C2")):
                label = {"R": "R", "phi": r"\theta", "z": "z"}[comp]
                for sig, ls, who in ((s.dust_sigma, "-", "dust"), (s.gas_sigma, "--", "gas")):
                    y = sig[comp] / s.v_kepler
                    y = np.where(y > 1e-12, y, np.nan)  # the initial state (no dispersion) and empty annuli
                    ax.plot(s.orbits, y, color=color, ls=ls, label=rf"{who} $\sigma_{{{label}}}$")
                cols += [Column(f"dust_sigma_{comp}_{tag}", s.dust_sigma[comp] / s.v_kepler, "v_K",
                                f"dust velocity dispersion, {comp}"),
                         Column(f"gas_sigma_{comp}_{tag}", s.gas_sigma[comp] / s.v_kepler, "v_K",
                                f"gas velocity dispersion around the ring, {comp}")]
            ax.plot(s.orbits, np.abs(s.drift_setup) / s.v_kepler, color="0.5", ls="--", lw=1.0, label="|eq. 3.23|")
            cols.append(Column(f"drift_{tag}", np.abs(s.drift_setup) / s.v_kepler, "v_K", "|v_r| of eq. 3.23"))
            ax.set_yscale("log")
            ax.set_ylabel(r"$\sigma_v / v_K$")
            ax.text(0.03, 0.9, rf"$\tau_s = {taus:g}$", transform=ax.transAxes)
        axes[0].legend(fontsize=6, ncol=2)
        axes[1].set_xlabel(r"time [orbits at $\langle R\rangle$]")
        return save_figure(fig, output / "fig3_9.png", padded(cols),
                           title="thesis Figure 3.9: velocity dispersions of gas and dust",
                           description=_DESC.format(run=run) + "; dispersions about v_K(R) of each particle")


@figure("fig3.10", "Random walk of three gas particles in the R-z plane, with +-H (drift-ring run)",
        cost="shares the drift-ring run")
def fig3_10(output: Path, quick: bool = True, runs=None) -> list[Path]:
    from ..analysis.disk import disk_of, gas_tracks
    from ..plot import Column, house_style, new_figure, save_figure

    run = disk_run(False, output, quick, runs)
    tracks = gas_tracks(run)
    disk = disk_of(run)
    cols = []
    with house_style():
        fig, axes = new_figure(1, len(tracks), width=3.0 * len(tracks), height=3.2)
        for j, (ax, tr) in enumerate(zip(np.atleast_1d(axes), tracks)):
            R0 = tr["R"][0]
            span = max(np.ptp(tr["R"]), 4 * float(disk.scale_height(R0)))
            grid = np.linspace(R0 - span, R0 + span, 50)
            H = disk.scale_height(grid)
            ax.plot(grid, H, color="0.6", lw=0.8)
            ax.plot(grid, -H, color="0.6", lw=0.8)
            ax.plot(tr["R"], tr["z"], "r:", lw=0.9)
            ax.plot(tr["R"][0], tr["z"][0], "ko", ms=4)
            ax.plot(tr["R"][-1], tr["z"][-1], "ro", ms=4)
            ax.text(0.04, 0.9, f"{tr['orbits'][-1]:.1f} orbits", transform=ax.transAxes, fontsize=8)
            ax.set_xlabel("R [au]")
            if j == 0:
                ax.set_ylabel("z [au]")
            cols += [Column(f"time_{j}", tr["time"], "code time", f"time (track {j}, start {R0:.1f} au)"),
                     Column(f"R_{j}", tr["R"], "au", f"cylindrical radius (track {j})"),
                     Column(f"z_{j}", tr["z"], "au", f"height (track {j})"),
                     Column(f"H_{j}", tr["H"], "au", f"scale height at R (track {j})")]
        return save_figure(fig, output / "fig3_10.png", padded(cols),
                           title="thesis Figure 3.10: random walk of gas particles in R-z",
                           description=_DESC.format(run=run))
