"""Thesis Figs 4.7-4.10 and the analogues of Figs 1.10 and 1.13 from a stratified particle run.

The thesis's Athena run (§4.5, Fig 4.7 caption) is ``dustygas run si3d-thesis``; these figures
come from the laptop preset ``si3d`` (the same physics at 32 × 32 × 48 cells; ``dustygas
reproduce --full``), run once into ``<output>/runs/si3d`` and reused by every figure (66 min as
two MPI ranks on two cores; in one process with two threads somewhat longer), or from any
finished run given with ``dustygas reproduce ... --from RUN``. The quick default (``reproduce
--all`` included) runs 10 of its 30 orbits at half the resolution, 16 × 16 × 24 (a sixteenth of
the cost per orbit), into ``<output>/runs/si3d-quick``:

* Fig 4.7 -- particles near the midplane (``|z| < 0.03 H``) and near two boundaries, coloured by
  the dust density, at the end of the run;
* Fig 4.8 -- the midplane slab ``|z| < 0.03 H`` (x-y) halfway through and at the end;
* Fig 4.9 -- the azimuthal slab ``|y| < 0.03 H`` (x-z) at the start and at the end;
* Fig 4.10 -- the surface density ``Σ_d`` and its 2D FFT at three times, and the dominant angle
  ``θ_k(t)`` of every snapshot in the CSV;
* Fig 1.10 (analogue of Johansen et al. 2007, without self-gravity) -- the largest dust density
  and the mean midplane dust density versus time;
* Fig 1.13 (analogue of Bai & Stone 2010b) -- the particle scale height of every species
  versus time (one species in ``si3d``; seven in ``si3d-bs10b``).
"""

from __future__ import annotations

from pathlib import Path

from . import figure

SLAB = 0.03  # H: the slab half-width of thesis Figs 4.7-4.9


#: the quick default: the si3d preset at half its resolution and to 10 of its 30 orbits (18 179
#: steps, 62 s on the quiet 2-core machine with two threads, 2026-12-04). Too short for Fig 1.13's
#: steady-layer check, which it reports as not judged (si3d_checks.SATURATED_AFTER); the layer
#: still thickens at this resolution (to 15 orbits: second half / first half of H_p 2.3)
QUICK = ("grid.nx=16", "grid.ny=16", "grid.nz=24", "run.tlim=62.83185307179586")


def si3d_run(output: Path, run: Path | None = None, quick: bool = True) -> Path:
    """The run directory behind the figures: ``run`` if given, else the ``si3d`` preset in
    ``output/runs/si3d`` (``quick``: at :data:`QUICK` in ``output/runs/si3d-quick``), run, or
    continued from its checkpoint, if not finished."""
    return cached_run("si3d", output, run, quick, QUICK)


def cached_run(problem: str, output: Path, run: Path | None, quick: bool, quick_set=()) -> Path:
    """``run`` if given, else the finished run of ``problem`` in ``output/runs/<problem>``
    (``quick``: with the overrides ``quick_set``, in ``output/runs/<problem>-quick``), run, or
    continued from its checkpoint, if not finished (:func:`~dustygas.reproduce._runs.finished_run`)."""
    from ._runs import finished_run

    Path(output).mkdir(parents=True, exist_ok=True)
    if run is not None:
        return Path(run)
    path = Path(output) / "runs" / (f"{problem}-quick" if quick else problem)
    return finished_run(problem, path, quick_set if quick else (), progress=None)


def _snaps(run: Path, which: list[float]):
    from ..analysis.stratified import read_snapshot
    from ..io.rundir import RunDirectory

    n = len(RunDirectory(run).snapshots())
    return [read_snapshot(run, min(n - 1, int(round(f * (n - 1))))) for f in which]


@figure("fig4.7", "Dust particles near the midplane and the boundaries, coloured by density (si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig4_7(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..plot.particles import slab_figure

    path = si3d_run(output, run, quick)
    (snap,) = _snaps(path, [1.0])
    return slab_figure(snap, Path(output) / "fig4_7.png", "cube", SLAB,
                       f"Fig 4.7: {path.name}, dust near the midplane and two boundaries", z_shown=0.10)


@figure("fig4.8", "Midplane slab |z| < 0.03 H of the dust (x-y), halfway and at the end (si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig4_8(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..plot.particles import slab_figure

    path = si3d_run(output, run, quick)
    out = []
    for tag, snap in zip(("a", "b"), _snaps(path, [0.5, 1.0])):
        out += slab_figure(snap, Path(output) / f"fig4_8{tag}.png", "xy", SLAB, f"Fig 4.8{tag}: {path.name}")
    return out


@figure("fig4.9", "Azimuthal slab |y| < 0.03 H of the dust (x-z), at the start and at the end (si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig4_9(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..plot.particles import slab_figure

    path = si3d_run(output, run, quick)
    out = []
    for tag, snap in zip(("a", "b"), _snaps(path, [0.0, 1.0])):
        out += slab_figure(snap, Path(output) / f"fig4_9{tag}.png", "xz", SLAB, f"Fig 4.9{tag}: {path.name}")
    return out


@figure("fig4.10", "Dust surface density and its 2D FFT; the dominant angle theta_k(t) (si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig4_10(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..analysis.stratified import read_snapshot
    from ..io.rundir import RunDirectory
    from ..plot.particles import surface_density_figure

    path = si3d_run(output, run, quick)
    every = [read_snapshot(path, i) for i in range(len(RunDirectory(path).snapshots()))]
    return surface_density_figure(_snaps(path, [1 / 3, 2 / 3, 1.0]), Path(output) / "fig4_10.png",
                                  f"Fig 4.10: {path.name}, surface density and |FFT|", every=every)


@figure("fig1.10", "Maximum dust density versus time (Johansen et al. 2007 analogue, si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig1_10(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..analysis.stratified import read_series, read_snapshot
    from ..plot.particles import series_figure

    path = si3d_run(output, run, quick)
    snap = read_snapshot(path, -1)
    return series_figure(read_series(path), Path(output) / "fig1_10.png", "max_density",
                         f"Fig 1.10 analogue: {path.name} (no self-gravity)", area=snap.box[0] * snap.box[1])


@figure("fig1.13", "Particle scale height of every species versus time (Bai & Stone 2010b analogue, si3d run)",
        cost="1 min (shared si3d run; --full: 1-2 h)")
def fig1_13(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    from ..analysis.stratified import read_series
    from ..config import load_toml
    from ..io.rundir import RunDirectory
    from ..plot.particles import series_figure

    path = si3d_run(output, run, quick)
    cfg = load_toml(RunDirectory(path).config_file)
    taus = cfg.get("problem", {}).get("taus", [])
    names = [f"τs = {t:.3g}" for t in taus]
    return series_figure(read_series(path), Path(output) / "fig1_13.png", "scale_height",
                         f"Fig 1.13 analogue: {path.name}", names=names)
