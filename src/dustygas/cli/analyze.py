"""``dustygas analyze``: numbers from a run directory."""

from __future__ import annotations

import argparse
import json

HELP = "analyse a run directory (growth of the recorded mode; bound clumps; dust in stratified runs)"
DESCRIPTION = """Analyse a run directory.

  dustygas analyze growth runs/si-linA            growth rate, frequency, fit window
  dustygas analyze growth runs/si-linA --json     the same as a JSON object
  dustygas analyze clumps RUN                     bound clumps and their mass function
                                                  (dustygas analyze clumps --help)

growth: fits ln|A| and arg A of the complex Fourier amplitude A(t) of the run's mode for the
eight fields (gas drho_g ux uy uz, dust drho_p wx wy wz; written to history.h5 by the
particle engine), A ~ exp(-i omega t): growth rate Im omega, frequency Re omega. The window
is automatic unless --window is given: it ends where a relative density amplitude exceeds
--nonlinear (or at the end of the run) and starts at the earliest of 11 candidate times (the
first half of the run, in steps of 1/20) at which the fields' growth rates agree within
--agree. For si-linear and si-settling runs the linear theory's values are shown too.

JSON keys: growth_rate, frequency, window [t0, t1], fields {name: {growth_rate, frequency}},
spread (max-min over mean of the fields' growth rates), samples, window_rule, theory
{growth_rate, frequency, problem} (empty for other problems).

Stratified particle runs (si3d and its presets); each writes PNG + CSV (and HDF5 for maps)
into RUN/analysis/ or -o DIR:

  dustygas analyze surface-density RUN      Sigma_d(x, y), its 2D FFT, the dominant angle theta_k(t)
  dustygas analyze max-density RUN          max rho_p / rho_g0 and the mean midplane density vs time
  dustygas analyze cdf RUN                  cumulative distribution of the dust density
  dustygas analyze scale-height RUN         particle scale height H_p of every species vs time
  dustygas analyze dispersion RUN           particle velocity dispersions of every species vs time
  dustygas analyze slabs RUN                particles near the midplane and the boundaries (x-y, x-z)"""

STRATIFIED = ("surface-density", "max-density", "cdf", "scale-height", "dispersion", "slabs")


def add_arguments(p: argparse.ArgumentParser) -> None:
    sub = p.add_subparsers(dest="analyze_command", metavar="SUBCOMMAND")
    g = sub.add_parser("growth", help="growth rate and frequency of the recorded mode",
                       description="Growth rate and frequency of the linear mode recorded in RUN/history.h5.")
    g.add_argument("run", metavar="RUN", help="run directory")
    g.add_argument("--json", action="store_true", help="print one JSON object")
    g.add_argument("--window", type=float, nargs=2, metavar=("T0", "T1"), help="fit window (default: automatic)")
    g.add_argument("--fields", nargs="+", metavar="FIELD", help="fields to fit (default: all eight)")
    g.add_argument("--nonlinear", type=float, default=0.01, help="relative density amplitude that ends the window")
    g.add_argument("--agree", type=float, default=0.005, help="relative agreement of the fields that starts it")
    from . import analyze_clumps

    analyze_clumps.add_arguments(sub)
    for name in STRATIFIED:
        a = sub.add_parser(name, help=f"{name} of a stratified particle run (PNG + CSV)")
        a.add_argument("run", metavar="RUN", help="run directory")
        a.add_argument("-o", "--output", metavar="DIR", help="output directory (default RUN/analysis)")
        a.add_argument("--snapshot", type=int, action="append", metavar="N",
                       help="snapshot index (repeatable; default: the newest, or four spread over the run)")
        a.add_argument("--slab", type=float, default=0.03, metavar="DELTA", help="slab half-width in H (slabs)")


def main(args: argparse.Namespace) -> int:
    from ..analysis.growth import MODE_FIELDS, measure_growth, theory_for_run
    from ..errors import UserError

    if args.analyze_command == "clumps":
        from . import analyze_clumps

        return analyze_clumps.main(args)
    if args.analyze_command in STRATIFIED:
        from ..analysis.outputs import analyze_stratified

        for path in analyze_stratified(args.analyze_command, args.run, args.output, args.snapshot, args.slab):
            print(path)
        return 0
    if args.analyze_command != "growth":
        raise UserError(f"analyze: name a subcommand: growth, clumps, {', '.join(STRATIFIED)} (see dustygas analyze --help)")
    fit = measure_growth(args.run, window=args.window, fields=args.fields or MODE_FIELDS,
                         nonlinear=args.nonlinear, agree=args.agree)
    fit.theory = theory_for_run(args.run)
    if args.json:
        print(json.dumps(fit.to_dict(), indent=1))
        return 0
    lo, hi = fit.window
    print(f"growth rate {fit.growth_rate:.6g}  frequency {fit.frequency:.6g}  (units of Omega; mean of "
          f"{len(fit.fields)} fields)")
    if fit.theory:
        s, f = fit.theory["growth_rate"], fit.theory["frequency"]
        print(f"linear theory {s:.6g}  {f:.6g}  -> growth error {100 * (fit.growth_rate / s - 1):+.2f} %")
    print(f"window t = {lo:.6g} .. {hi:.6g} ({fit.samples} samples; {fit.window_rule})")
    print(f"fields agree within {100 * fit.spread:.3f} %")
    for name, v in fit.fields.items():
        print(f"  {name:<7} {v['growth_rate']:.6g}  {v['frequency']:.6g}")
    return 0
