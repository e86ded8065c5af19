"""``dustygas reproduce``: regenerate the computational figures of the thesis."""

from __future__ import annotations

import argparse
import inspect
import sys
from pathlib import Path

from ..errors import UserError

HELP = "regenerate thesis figures (PNG + the numbers behind them, checks, DIR/index.html)"
DESCRIPTION = """Regenerate thesis figures into DIR (default: figures).

  dustygas reproduce --list               the registered figures
  dustygas reproduce fig3.5 fig4.2        two figures
  dustygas reproduce --all -o figures     every registered figure

Each figure writes its PNG and the numbers behind it (CSV, HDF5 or JSON); its quantitative
checks (numbers against published or analytic values) are printed, and DIR/index.html shows
every figure made into DIR beside its thesis caption, its checks and its data. The exit status
is 1 if a check failed or a figure could not be made."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("figures", nargs="*", metavar="FIG", help="figure names, e.g. fig3.1 fig3.5")
    p.add_argument("--all", action="store_true", help="every registered figure")
    p.add_argument("--list", action="store_true", help="list the figures and stop")
    p.add_argument("-o", "--output", default="figures", metavar="DIR", help="output directory (default: figures)")
    p.add_argument("--full", action="store_true", help="thesis-scale resolution instead of the quick default")
    p.add_argument("--from", dest="runs", action="append", metavar="RUN",
                   help="use this run directory instead of running (figures made from runs; repeat for several;"
                        " a figure drawn from one run, like Figs 4.7-4.10, takes the first)")


def main(args: argparse.Namespace) -> int:
    from ..reproduce import figure_names, get_figure

    if args.list:
        names = figure_names()
        width = max(map(len, names))
        for name in names:
            spec = get_figure(name)
            print(f"{name:<{width}}  {spec.summary}  [{spec.cost}]")
        return 0
    names = figure_names() if args.all else args.figures
    if not names:
        raise UserError("reproduce: name at least one figure, or --all (see: dustygas reproduce --list)")
    specs = [get_figure(n) for n in names]  # validate every name before writing anything
    runs = getattr(args, "runs", None)
    if runs:
        for spec in specs:
            if not {"runs", "run"} & set(inspect.signature(spec.function).parameters):
                raise UserError(f"reproduce --from: {spec.name} is not made from a run directory")
        for run in runs:
            if not Path(run).is_dir():
                raise UserError(f"reproduce --from {run}: no such run directory")
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    out.mkdir(parents=True, exist_ok=True)
    from ..reproduce.checks import verdict
    from ..reproduce.gallery import make_figures

    def log(record) -> None:
        files = ", ".join(str(out / f) for f in record.files)
        print(f"{record.name}: {files} ({record.wall:.1f} s)", file=sys.stderr)
        if record.error:
            print(f"{record.name}: FAILED: {record.error}", file=sys.stderr)
        for c in record.checks:
            if verdict(c) == "NOT JUDGED":
                print(f"  NOT JUDGED {c['name']}: {c['value']:.6g} ({c['tolerance']})", file=sys.stderr)
                continue
            exp = c["expected"] if isinstance(c["expected"], str) else f"{c['expected']:.6g}"
            print(f"  {verdict(c)} {c['name']}: {c['value']:.6g} vs {exp} ({c['tolerance']})", file=sys.stderr)

    extra = {"runs": list(runs), "run": Path(runs[0])} if runs else {}
    records = make_figures([s.name for s in specs], out, quick=not args.full, log=log, **extra)
    failed = [r.name for r in records if not r.passed]
    print(f"gallery: {out / 'index.html'} ({len(records)} figures"
          f"{', failed: ' + ' '.join(failed) if failed else ''})", file=sys.stderr)
    return 1 if failed else 0
