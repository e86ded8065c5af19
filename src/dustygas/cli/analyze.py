"""``dustygas analyze``: numbers from a run directory."""

from __future__ import annotations

import argparse
import json

HELP = "analyse a run directory (growth of the recorded linear mode; bound clumps)"
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
{growth_rate, frequency, problem} (empty for other problems)."""


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


def main(args: argparse.Namespace) -> int:
    from ..analysis.growth import MODE_FIELDS, measure_growth, theory_for_run
    from ..errors import UserError

    if args.analyze_command == "clumps":
        from . import analyze_clumps

        return analyze_clumps.main(args)
    if args.analyze_command != "growth":
        raise UserError("analyze: name a subcommand: growth or clumps (see dustygas analyze --help)")
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
