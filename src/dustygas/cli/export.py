"""``dustygas export``: a run's snapshots for yt, ParaView/VisIt, sarracen/splash or a spreadsheet."""

from __future__ import annotations

import argparse

HELP = "write a run's snapshots as Athena++ athdf + XDMF, yt particle data, Phantom dumps or CSV"
DESCRIPTION = """Write the snapshots of a run directory in the formats the field's tools read.

  dustygas export runs/si-linA                       grid: athdf + XDMF (+ yt particles)
  dustygas export runs/dust-settle                   SPH: Phantom dumps + yt particles
  dustygas export RUN --format csv --snapshot -1     the last snapshot as CSV
  dustygas export RUN -o DIR                         into DIR (default RUN/export)

Formats: athdf (yt.load, ParaView/VisIt through the .athdf.xdmf sidecar), ytdata (yt.load:
particle positions, velocities, masses, ids), phantom (sarracen.read_phantom, splash), csv
(sarracen.read_csv, pandas), auto (athdf for grid runs, phantom for SPH, plus ytdata where
there are particles). Every file carries the configuration, the version and the units."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    from ..io.export import FORMATS

    p.add_argument("run", metavar="RUN", help="run directory")
    p.add_argument("--format", "-f", default="auto", choices=FORMATS, help="output format (default: auto)")
    p.add_argument("--snapshot", "-s", type=int, action="append", metavar="N",
                   help="snapshot position (repeatable; negative from the end; default: all)")
    p.add_argument("-o", "--output", metavar="DIR", help="output directory (default: RUN/export)")


def main(args: argparse.Namespace) -> int:
    from ..io.export import export_run

    for path in export_run(args.run, args.format, args.output, args.snapshot):
        print(path)
    return 0
