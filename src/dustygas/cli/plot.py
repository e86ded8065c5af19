"""``dustygas plot``: history curves, snapshot images and movies of a run of any engine."""

from __future__ import annotations

import argparse

HELP = "draw a run's history curves and a snapshot (slice, projection or SPH rendering); --movie"
DESCRIPTION = """Draw the history curves and one snapshot of a run directory (grid, particle or SPH).

  dustygas plot runs/si-linA                          history.png + the last snapshot's rho
  dustygas plot RUN --field rho_p --snapshot 0        another field, the first snapshot
  dustygas plot RUN --kind projection --axis z        integrate along z (3D runs)
  dustygas plot RUN --field particles                 the Lagrangian particles' positions
  dustygas plot RUN --history mass rho_max            only these history columns
  dustygas plot RUN --movie rho.mp4                   one frame per snapshot (.mp4: ffmpeg; .gif: Pillow)

Grid runs: slices through the cell nearest --at (default the box centre) normal to --axis, or
projections (the integral along --axis); 1D runs as lines. SPH runs: the field interpolated
with the run's kernel on a pixel grid (2D plane, 3D cross-section at --at or projection); 1D
runs particle by particle. Axes and colour bars carry the code units. Files go to -o DIR
(default RUN/plots); their paths are printed."""


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("run", metavar="RUN", help="run directory")
    p.add_argument("--snapshot", "-s", type=int, default=-1, metavar="N", help="snapshot position (default: -1, the last)")
    p.add_argument("--field", default="rho", help="field to draw (default: rho; 'particles' for particle positions)")
    p.add_argument("--kind", default="slice", choices=("slice", "projection"), help="slice or projection (3D)")
    p.add_argument("--axis", choices=("x", "y", "z"), help="normal of the slice / projection axis (default z)")
    p.add_argument("--at", type=float, metavar="COORD", help="coordinate of the slice along --axis")
    p.add_argument("--log", action="store_true", help="logarithmic colour scale")
    p.add_argument("--npix", type=int, default=256, help="pixels across an SPH rendering (default 256)")
    p.add_argument("--history", nargs="+", metavar="COLUMN", help="history columns to draw (default: all)")
    p.add_argument("--no-history", action="store_true", help="do not draw the history")
    p.add_argument("--movie", metavar="FILE", help="also write an animation over all snapshots (.mp4 or .gif)")
    p.add_argument("--fps", type=int, default=5, help="frames per second of the movie (default 5)")
    p.add_argument("-o", "--output", metavar="DIR", help="output directory (default: RUN/plots)")


def main(args: argparse.Namespace) -> int:
    from pathlib import Path

    from ..errors import UserError
    from ..io.atomic import atomic_path
    from ..plot.run import _run, history_figure, plot_snapshot, write_movie

    rundir = _run(args.run)
    if args.npix < 8 or args.fps < 1:
        raise UserError("--npix must be >= 8 and --fps >= 1")
    out = Path(args.output) if args.output else rundir.path / "plots"
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    figures = []
    if not args.no_history and rundir.history_file.exists():
        figures.append(("history.png", history_figure(args.run, args.history)))
    snap = rundir.snapshot_at(args.snapshot)
    fig = plot_snapshot(args.run, args.snapshot, args.field, args.kind, args.axis, args.at, args.log, npix=args.npix)
    kind = "" if args.field == "particles" else f"_{args.kind}"
    figures.append((f"{snap.stem}_{args.field}{kind}.png", fig))
    out.mkdir(parents=True, exist_ok=True)
    for name, figure in figures:
        with atomic_path(out / name) as tmp:
            with open(tmp, "wb") as fh:
                figure.savefig(fh, format="png")
        print(out / name)
    if args.movie:
        movie = Path(args.movie)
        if not movie.is_absolute() and movie.parent == Path("."):
            movie = out / movie
        print(write_movie(args.run, movie, args.field, args.kind, args.axis, args.at, args.log, args.fps, args.npix))
    return 0
