"""Self-gravity and planetesimal analysis: the Poisson solve against a gas step, the clump finder at 1e6 particles.

1. **Poisson solve at 64³** (``PoissonSolver.acceleration``: density in, ``-∇Φ`` out, shear
   offset 0.37 L_y so the sheared-frame phases are exercised; z periodic, z vacuum, and z vacuum
   restricted to a settled particle layer filling 24 of the 64 layers -- ±2H_p of a dust layer
   of H_p = 0.015 H in a box of height 0.2 H, ``occupied_only=True``), against
   one step of the grid engine's 64³ shearing box (the ``bench_grid.py`` 3d64 case:
   ``engine.advance(engine.timestep())``, VL2 with PLM/HLLE and PPM/HLLC). A coupled run solves
   once per step (at the particles' half-step positions), so the ratio solve/step is the
   fraction of a step that self-gravity adds to the gas alone; the particle stage adds more
   work to the step. Thread counts interleave (numba threads and scipy.fft workers alike); best
   and median of ``--repeat``.
2. **Clump finder at 1e6 particles on one core**: planted Plummer spheres (64 of 3000 particles
   each, masses log-uniform over a decade) in 808,000 background particles, 64x64x32 mesh,
   shear offset 0.3 L_y; wall time of :func:`~dustygas.analysis.clumps.find_clumps` after a
   warm-up call (numba compilation), best of ``--repeat``.

Usage::

    flock benchmarks/.lock python benchmarks/bench_gravity.py
    python benchmarks/bench_gravity.py --parts poisson --threads 1 --repeat 5
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numba  # noqa: E402

from bench_grid import build  # noqa: E402
from dustygas.grid.gravity import PoissonSolver  # noqa: E402


def best_of(fn, repeat: int, calls: int) -> tuple[float, float]:
    """Best and median seconds per call of ``fn`` over ``repeat`` timings of ``calls`` calls."""
    fn()
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(calls):
            fn()
        times.append((time.perf_counter() - t0) / calls)
    return min(times), statistics.median(times)


def poisson(threads: list[int], repeat: int) -> None:
    n = 64
    rho = 1.0 + 0.1 * np.random.default_rng(1).random((n, n, n))
    out = np.empty((3, n, n, n))
    layer = rho.copy()
    layer[:20] = 0.0
    layer[44:] = 0.0
    solvers = {z: PoissonSolver((n, n, n), (1.0, 1.0, 1.0), 0.05, ("shear-periodic", "periodic", z))
               for z in ("periodic", "vacuum")}
    solvers["vacuum, layer"] = solvers["vacuum"]
    inputs = {"periodic": (rho, False), "vacuum": (rho, False), "vacuum, layer": (layer, True)}
    engines = {s: build((n, n, n), "vl2", *s) for s in (("plm", "hlle"), ("ppm", "hllc"))}
    print(f"{'what':34} {'thr':>3} {'best ms':>9} {'median':>9}")
    rows = {}
    for _ in range(1):
        for t in threads:
            numba.set_num_threads(t)
            for z, solver in solvers.items():
                solver.workers = t
                dens, occupied = inputs[z]
                rows[("solve", z, t)] = best_of(lambda: solver.acceleration(dens, 0.37, out, occupied), repeat, 10)
            for s, eng in engines.items():
                rows[("step", s, t)] = best_of(lambda: eng.advance(eng.timestep()), repeat, 5)
    for t in threads:
        for z in solvers:
            b, m = rows[("solve", z, t)]
            print(f"{'Poisson 64^3 z ' + z:34} {t:3d} {1e3 * b:9.2f} {1e3 * m:9.2f}")
        for s in engines:
            b, m = rows[("step", s, t)]
            print(f"{'gas step 64^3 VL2/' + '/'.join(s).upper():34} {t:3d} {1e3 * b:9.2f} {1e3 * m:9.2f}")
        for z in solvers:
            for s in engines:
                ratio = rows[("solve", z, t)][0] / rows[("step", s, t)][0]
                print(f"  solve (z {z}) / step ({'/'.join(s).upper()}), {t} thread(s): {100 * ratio:.1f} %")


def clumps(repeat: int) -> None:
    from dustygas.analysis.clumps import find_clumps
    from dustygas.analysis.synthetic import planted_clumps
    from dustygas.physics.gravity import hill_density, hill_radius

    numba.set_num_threads(1)
    G, box, cells, shift = 0.1 / (4 * np.pi), (1.0, 1.0, 0.5), (64, 64, 32), 0.3
    rng = np.random.default_rng(3)
    k = 64
    masses = 10 ** rng.uniform(np.log10(3e-3), np.log10(3e-2), k)
    # centres on a jittered lattice 1/8 apart (Hill radii 1.4 .. 2.8 cells of 1/64, at most 0.044)
    grid = np.stack(np.meshgrid(np.arange(8), np.arange(8), indexing="ij"), -1).reshape(-1, 2)
    centres = np.column_stack(((grid[:, 0] + 0.5) / 8 - 0.5 + rng.uniform(-0.01, 0.01, k),
                               (grid[:, 1] + 0.5) / 8 - 0.5 + rng.uniform(-0.01, 0.01, k),
                               rng.uniform(-0.05, 0.05, k)))
    assert hill_radius(masses.max(), G) < 0.045
    planted = planted_clumps(centres, masses, box=box, G=G, shear_offset=shift, particles_per_clump=3000,
                             background_density=0.003 * float(hill_density(G)), background_particles=808_000,
                             hill_fraction=1 / 30, seed=4)
    n = planted.mass.size
    args = dict(box=box, cells=cells, G=G, shear_offset=shift)
    cat = find_clumps(planted.pos, planted.vel, planted.mass, **args)
    best, median = best_of(lambda: find_clumps(planted.pos, planted.vel, planted.mass, **args), repeat, 1)
    print(f"clump finder, {n:,} particles, 1 thread: best {best:.2f} s, median {median:.2f} s; "
          f"{len(cat)} clumps found of {k} planted, {cat.mass.sum() / masses.sum():.4f} of their mass")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--parts", nargs="+", default=["poisson", "clumps"], choices=["poisson", "clumps"])
    ap.add_argument("--threads", default="1,2", help="comma-separated thread counts (Poisson part)")
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args(argv)
    load = os.getloadavg()
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}  load {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}  "
          f"numba {numba.__version__} ({numba.config.NUMBA_NUM_THREADS} threads max)")
    if "poisson" in args.parts:
        poisson([int(t) for t in args.threads.split(",")], args.repeat)
    if "clumps" in args.parts:
        clumps(args.repeat)
    load = os.getloadavg()
    print(f"# done {time.strftime('%H:%M')}  load {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
