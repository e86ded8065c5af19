"""``dustygas run``: run a registered problem, or continue a run from its checkpoint."""

from __future__ import annotations

import argparse
import sys

from ..errors import UserError

HELP = "run a registered problem (dustygas problems lists them) or restart a run"
DESCRIPTION = """Run a registered problem into a run directory.

  dustygas run si-linA                          small default, output in runs/si-linA
  dustygas run si-linA -o myrun --set grid.nx=128 --set run.tlim=4
  dustygas run si-linA -c params.toml           TOML file layered over the defaults
  dustygas run --restart myrun                  continue from the newest checkpoint

A run writes config.toml, log.txt, history.h5, snapshots/ and checkpoints/. SIGTERM or
--walltime write a checkpoint before stopping; --restart continues bit-identically."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("problem", nargs="?", help="registered problem name")
    p.add_argument("-c", "--config", action="append", default=[], metavar="FILE",
                   help="TOML parameter file (repeatable; later files win)")
    p.add_argument("-s", "--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                   help="override one parameter (repeatable; wins over files)")
    p.add_argument("-o", "--output", metavar="DIR", help="run directory (default runs/PROBLEM)")
    p.add_argument("--overwrite", action="store_true", help="reuse a non-empty output directory")
    p.add_argument("--restart", metavar="DIR", help="continue the run in DIR from its newest checkpoint")
    p.add_argument("--walltime", type=float, metavar="SECONDS",
                   help="checkpoint and stop after this many wall-clock seconds")
    p.add_argument("--threads", type=int, metavar="N", help="numba threads (default: all)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress output")
    p.add_argument("--dry-run", action="store_true",
                   help="validate the configuration and print the memory and cost estimate; allocate and write nothing")


def main(args: argparse.Namespace) -> int:
    from .. import api

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
    if args.restart:
        if args.problem or args.config or args.output:
            raise UserError("--restart DIR takes no problem name, --config or --output")
        result = api.restart(args.restart, set=overrides, walltime=args.walltime, progress=progress)
    else:
        if not args.problem:
            raise UserError("run: give a problem name (see: dustygas problems) or --restart DIR")
        result = api.run(args.problem, output=args.output, config=args.config, set=overrides,
                         overwrite=args.overwrite, walltime=args.walltime, progress=progress)
    label = result.work_label or "updates"
    print(
        f"{result.status}: {result.path}  time={result.engine.t:.6g}  cycles={result.cycles}  "
        f"wall={result.wall:.3g}s  throughput={result.throughput:.4g} {label}/s",
        file=sys.stderr,
    )
    if result.status in ("walltime", "signal"):
        print(f"checkpoint written; continue with: dustygas run --restart {result.path}", file=sys.stderr)
    return result.exit_code
