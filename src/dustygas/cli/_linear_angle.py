"""``dustygas linear angle``: θ_k(t) of a run's dust surface density next to the sweep's prediction."""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np

from ..errors import UserError

ANGLE_DESCRIPTION = """Measure the dominant wavevector angle theta_k = arctan(k_y/k_x) of the dust surface density
Sigma_d(x, y) in every snapshot of RUN (a 'rho_p' field or particle positions; shear-periodic boxes are
remapped with the snapshot's shear_offset) and, with --sweep, print it next to the preferred angle that
a shearing-wave sweep (dustygas linear sweep ... --times N) predicts at the same time since --t0, for the
(mu, tau_s) of the sweep grid nearest to the run's (from --mu/--taus or the run's config.toml).
Writes DIR/angle_comparison.png and DIR/angle_comparison.csv."""


def add_angle_arguments(a: argparse.ArgumentParser) -> None:
    a.add_argument("run", metavar="RUN", help="run directory with snapshots holding the dust")
    a.add_argument("--sweep", metavar="FILE.h5", help="sweep.h5 of dustygas linear sweep (with --times for theta(t))")
    a.add_argument("--mu", "--eps", dest="mu", type=float, help="dust-to-gas ratio of the run (default: its config)")
    a.add_argument("--taus", type=float, help="stopping time of the run (default: its config)")
    a.add_argument("--t0", type=float, default=None,
                   help="run time at which the sweep's waves start (default: the first snapshot's time)")
    a.add_argument("--keep-axisymmetric", action="store_true", help="also consider k_y = 0 modes")
    a.add_argument("-o", "--output", default=None, metavar="DIR", help="output directory (default: RUN)")


def _run_parameter(run: Path, names: tuple[str, ...]) -> float | None:
    from ..config import load_toml

    cfg_file = run / "config.toml"
    if not cfg_file.is_file():
        return None
    problem = load_toml(cfg_file).get("problem", {})
    for name in names:
        value = problem.get(name)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
    return None


def _nearest(grid, value: float, name: str) -> int:
    g = np.asarray(grid, dtype=np.float64)
    if value <= 0:
        raise UserError(f"--{name} {value:g}: must be > 0")
    return int(np.argmin(np.abs(np.log(g / value))))


def main(args) -> int:
    from ..analysis.wavevector import angle_history
    from ..linear.sweep import SweepResult

    run = Path(args.run)
    sweep = None
    if args.sweep:
        if not Path(args.sweep).is_file():
            raise UserError(f"--sweep {args.sweep}: no such file")
        sweep = SweepResult.load(args.sweep)
        mu = args.mu if args.mu is not None else _run_parameter(run, ("mu", "eps", "epsilon"))
        taus = args.taus if args.taus is not None else _run_parameter(run, ("taus", "tau_s", "stokes"))
        if mu is None or taus is None:
            raise UserError("give --mu and --taus (the run's config.toml has no problem.mu / problem.taus)")
        i, j = _nearest(sweep.spec.mu, mu, "mu"), _nearest(sweep.spec.taus, taus, "taus")
    out = Path(args.output) if args.output else run
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    hist = angle_history(run, exclude_axisymmetric=not args.keep_axisymmetric)
    t = hist["time"]
    t0 = float(t[0]) if args.t0 is None else float(args.t0)
    predicted = np.full(t.shape, np.nan)
    header = [f"dominant wavevector of the dust surface density of {run}"]
    if sweep is not None:
        mu_s, taus_s = sweep.spec.mu[i], sweep.spec.taus[j]
        header.append(f"sweep {args.sweep}: mu = {mu_s:g}, taus = {taus_s:g} (nearest to the run's {mu:g}, {taus:g}); "
                      f"waves start at t0 = {t0:g}")
        if sweep.spec.times:
            ser = sweep.preferred_series()
            ts, ang = ser["time"], ser["angle_deg"][i, j]
            inside = (t - t0 > 0) & (t - t0 <= ts[-1])
            predicted[inside] = np.interp(t[inside] - t0, ts, ang)
        else:
            pref = sweep.preferred()
            at = (np.abs(t - t0 - sweep.spec.t_end) <= 1e-9 * max(1.0, sweep.spec.t_end))
            predicted[at] = pref["angle_deg"][i, j]
            header.append("the sweep has no --times: its prediction is for t - t0 = t_end only")
    print("\n".join(f"# {h}" for h in header))
    print(f"{'time':>10} {'kx':>12} {'ky':>12} {'theta_k':>9} {'mean':>9} {'predicted':>9}")
    for row in zip(t, hist["kx"], hist["ky"], hist["angle_deg"], hist["mean_angle_deg"], predicted):
        print(f"{row[0]:10.4g} {row[1]:12.5g} {row[2]:12.5g} {row[3]:9.2f} {row[4]:9.2f} "
              + ("" if math.isnan(row[5]) else f"{row[5]:9.2f}"))
    out.mkdir(parents=True, exist_ok=True)
    from ..plot.style import Column, house_style, new_figure, save_figure

    with house_style():
        fig, ax = new_figure(1, 1, width=5.6, height=3.8)
        ax.plot(t, hist["angle_deg"], "o-", ms=3, label=r"run: strongest mode of $\Sigma_d$")
        ax.plot(t, hist["mean_angle_deg"], ":", label="run: power-weighted mean")
        if np.isfinite(predicted).any():
            ax.plot(t, predicted, "x--", label="shearing-wave sweep: most amplified wave")
        ax.set_xlabel(r"time $t\,\Omega$")
        ax.set_ylabel(r"$\theta_k = \arctan(k_y/k_x)$ [deg]")
        ax.legend()
        ax.set_title("\n".join(header), fontsize=7)
        paths = save_figure(fig, out / "angle_comparison.png", [
            Column("time", t, "1/Omega", "snapshot time"), Column("kx", hist["kx"], "2 pi/length", "k_x of the mode"),
            Column("ky", hist["ky"], "2 pi/length", "k_y of the strongest mode"),
            Column("angle_deg", hist["angle_deg"], "deg", "arctan(k_y/k_x) of the strongest mode"),
            Column("mean_angle_deg", hist["mean_angle_deg"], "deg", "power-weighted axial mean angle"),
            Column("predicted_deg", predicted, "deg", "the sweep's preferred angle at t - t0")],
            title="preferred wavevector: run versus shearing-wave sweep", description="\n".join(header))
    print("wrote " + ", ".join(str(p) for p in paths), file=sys.stderr)
    return 0
