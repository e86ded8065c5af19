"""Self-gravity's share of a coupled step: ``si3d-selfgravity`` at 64³ (one particle per cell).

The box of the problem (shear-periodic x, periodic y, vacuum z for the potential; 0.2 × 0.2 ×
0.3 H) at 64 × 64 × 64 cells and 262,144 particles in the settled initial layer (H_p = 0.02 H),
gravity on from t = 0. Times ``engine.advance(engine.timestep())`` (best and median of
``--steps`` after two warm-up steps) and, inside it, the self-gravity term's ``update`` (the
particle density the drag deposited, the FFT solve restricted to the rows the particles reach,
``-∇Φ``), and the same solve over the whole box (``layers=None``: what a layer filling the box
would cost). Thread count: numba's and scipy.fft's workers alike (``--threads``).

Usage::

    flock benchmarks/.lock python benchmarks/bench_selfgravity_step.py --threads 1
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--steps", type=int, default=6)
    ap.add_argument("--n", type=int, default=64)
    args = ap.parse_args()
    import numba

    numba.set_num_threads(args.threads)
    from dustygas.particles.gravity import SelfGravity
    from dustygas.problems import get_problem

    prob = get_problem("si3d-selfgravity")
    n = args.n
    cfg = prob.config(overrides=[f"grid.nx={n}", f"grid.ny={n}", f"grid.nz={n}", "gravity.t_on=0"])
    eng = prob.build(cfg)
    term = next(t for t in eng.particle_terms if isinstance(t, SelfGravity))
    spent = []
    update = term.update

    def timed(*a, **k):
        t0 = time.perf_counter()
        update(*a, **k)
        spent.append(time.perf_counter() - t0)

    term.update = timed
    for _ in range(2):
        eng.advance(eng.timestep())
    steps, solves = [], []
    for _ in range(args.steps):
        spent.clear()
        t0 = time.perf_counter()
        eng.advance(eng.timestep())
        steps.append(time.perf_counter() - t0)
        solves.append(sum(spent))
    rho = eng.prepared_particle_density()
    full = []
    for _ in range(args.steps):
        t0 = time.perf_counter()
        term.solver.acceleration(rho, 0.1, out=term.field)
        full.append(time.perf_counter() - t0)
    rows = eng.field_rows
    load = os.getloadavg()[0]
    print(f"si3d-selfgravity {n}^3, {eng.particles.n} particles, threads {args.threads}, load {load:.2f}")
    print(f"  step   best {min(steps) * 1e3:8.1f} ms  median {statistics.median(steps) * 1e3:8.1f} ms")
    print(f"  gravity term (rows {rows[0]}..{rows[1]} of {n})  best {min(solves) * 1e3:7.1f} ms  median "
          f"{statistics.median(solves) * 1e3:7.1f} ms  = {statistics.median(solves) / statistics.median(steps):.1%}"
          " of the step (median/median)")
    print(f"  full-box solve  best {min(full) * 1e3:7.1f} ms  median {statistics.median(full) * 1e3:7.1f} ms  = "
          f"{statistics.median(full) / statistics.median(steps):.1%} of the step")


if __name__ == "__main__":
    main()
