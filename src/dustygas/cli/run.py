"""``dustygas run``: run a registered problem, or continue a run from its checkpoint."""

from __future__ import annotations

import argparse
import sys

from ..errors import EXIT_WALLTIME, UserError
from ..parallel.comm import is_writer

HELP = "run a registered problem (dustygas problems lists them) or restart a run"
DESCRIPTION = f"""Run a registered problem into a run directory.

  dustygas run si-linA                          small default, output in runs/si-linA
  dustygas run si-linA -o myrun --set grid.nx=128 --set run.tlim=4
  dustygas run si-linA -c params.toml           TOML file layered over the defaults
  dustygas run --restart myrun                  continue from the newest intact checkpoint
  dustygas run --restart myrun --set run.tlim=12    extend a finished run
  dustygas run si3d-selfgravity --from runs/si3d    start from another problem's checkpoint

A run writes config.toml, log.txt, history.h5, snapshots/ and checkpoints/ and ends with a
checkpoint. SIGTERM, Ctrl-C or --walltime write a checkpoint before stopping; --restart
continues bit-identically and may change only run.* parameters. One process at a time writes
a run directory.

exit status: 0 finished; 2 bad input (nothing written); 3 stopped on an invalid state or a
failed write; {EXIT_WALLTIME} stopped at --walltime (resubmit with --restart); 128+N signal N."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("problem", nargs="?", help="registered problem name")
    p.add_argument("-c", "--config", action="append", default=[], metavar="FILE",
                   help="TOML parameter file (repeatable; later files win)")
    p.add_argument("-s", "--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override one parameter (repeatable; wins over files)")
    p.add_argument("-o", "--output", metavar="DIR", help="run directory (default runs/PROBLEM)")
    p.add_argument("--overwrite", action="store_true", help="replace the run in a non-empty output directory")
    p.add_argument("--restart", metavar="DIR", help="continue the run in DIR from its newest checkpoint")
    p.add_argument("--from", dest="source", metavar="RUN",
                   help="start PROBLEM from the newest checkpoint of another problem's run RUN, whose physics "
                        "it keeps (e.g. si3d-selfgravity from an si3d run before gravity.t_on)")
    p.add_argument("--walltime", type=float, metavar="SECONDS",
                   help=f"checkpoint and stop (exit status {EXIT_WALLTIME}) after this many wall-clock seconds")
    p.add_argument("--threads", type=int, metavar="N",
                   help="numba threads (default: chosen automatically from measured step times)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress output")
    p.add_argument("--dry-run", action="store_true",
                   help="validate the configuration and print the memory and cost estimate; allocate and write nothing")


def main(args: argparse.Namespace) -> int:
    from .. import api
    from ._compile_notice import compile_notice

    overrides = list(args.set)
    if args.threads is not None:
        if args.threads < 1:
            raise UserError(f"--threads {args.threads}: expected a positive integer")
        overrides.append(f"run.threads={args.threads}")
    progress = False if args.quiet else None
    if args.dry_run:
        if not args.problem or args.restart:
            raise UserError("--dry-run takes a problem name (and no --restart)")
        for line in api.dry_run(args.problem, config=args.config, set=overrides):
            print(line)
        return 0
    with compile_notice(enabled=not args.quiet):
        if args.restart is not None:
            if args.source is not None:
                raise UserError("--restart DIR and --from RUN exclude each other")
            if args.problem or args.config or args.output is not None or args.overwrite:
                raise UserError("--restart DIR takes no problem name, --config, --output or --overwrite")
            result = api.restart(args.restart, set=overrides, walltime=args.walltime, progress=progress)
        elif args.source is not None:
            if not args.problem:
                raise UserError("--from RUN: give the problem to start from it (e.g. si3d-selfgravity)")
            result = api.branch(args.problem, args.source, output=args.output, config=args.config, set=overrides,
                                overwrite=args.overwrite, walltime=args.walltime, progress=progress)
        else:
            if not args.problem:
                raise UserError("run: give a problem name (see: dustygas problems) or --restart DIR")
            result = api.run(args.problem, output=args.output, config=args.config, set=overrides,
                             overwrite=args.overwrite, walltime=args.walltime, progress=progress)
    if not is_writer():  # under MPI: rank 0 reports
        return result.exit_code
    label = result.work_label or "updates"
    print(
        f"{result.status}: {result.path}  time={result.engine.t:.6g}  cycles={result.cycles}  "
        f"wall={result.wall:.4g}s  first_step={result.first_step:.3g}s  "
        f"throughput={result.throughput:.4g} {label}/s  threads={result.threads}",
        file=sys.stderr,
    )
    if result.status == "walltime":
        print(f"stopped at the wall-clock limit (exit status {EXIT_WALLTIME}); checkpoint written; "
              f"continue with: dustygas run --restart {result.path}", file=sys.stderr)
    elif result.status == "signal":
        print(f"checkpoint written; continue with: dustygas run --restart {result.path}", file=sys.stderr)
    return result.exit_code
