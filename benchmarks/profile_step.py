"""Where the time of a coupled particle-gas step goes: CPU time per compiled call, and the rest.

Builds a particle problem (default ``si-linA`` with the CTU gas step at Courant 0.8), takes
``--warmup`` steps, then times ``--steps`` steps with every compiled kernel that the coupled
engine and the gas engine call wrapped in a timer (``time.process_time``: CPU time, robust on a
loaded machine at one thread; a call of it costs ~2 µs here, which the figures of the kernels
include, and so does numba's dispatch of the call). Prints µs per step for each kernel (CPU, and
wall by ``time.perf_counter``), their sum, and the difference to the whole step: the Python glue
between the compiled calls (attribute look-ups, numpy operations on small arrays) plus most of
the timers' own cost -- on the linA step 55-75 µs, of which the glue alone is 11 µs (2026-12-05:
the step replayed with stub kernels, ``benchmarks/RESULTS.md``).

Run it on one thread (``NUMBA_NUM_THREADS=1``) for the serial-share figure of issue 16: at one
thread the CPU time of a step splits into the kernels' parallel loops, their serial parts and
the Python between them.

Usage::

    NUMBA_NUM_THREADS=1 python benchmarks/profile_step.py --steps 400
    NUMBA_NUM_THREADS=1 python benchmarks/profile_step.py --set scheme.integrator=vl2 --set scheme.cfl=0.4
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections import defaultdict
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))


#: compiled calls without a parallel region (``fill_field_ghosts`` fills a 2D x-y field serially; a
#: 2D x-z field's ghosts are filled inside ``filter_field_xz``); ``ctu_stage`` and ``advance_gas``
#: hold serial parts too (2D ghost fills of CTU, the radial flux correction, the sums), counted
#: with the parallel kernels here
SERIAL = ("build_images", "sort_images", "image_values", "fill_field_ghosts", "step_coefficients", "compact")


def wrap_module(module, names, totals, walls, counts):
    """Replace ``module.name`` by a timing wrapper for every compiled function among ``names``."""
    clock, wall = time.process_time, time.perf_counter
    for name in names:
        fn = getattr(module, name, None)
        if fn is None or not hasattr(fn, "py_func"):
            continue

        def timed(*args, _fn=fn, _key=name, **kw):
            t0, w0 = clock(), wall()
            out = _fn(*args, **kw)
            walls[_key] += wall() - w0
            totals[_key] += clock() - t0
            counts[_key] += 1
            return out

        setattr(module, name, timed)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--problem", default="si-linA")
    ap.add_argument("--set", action="append", default=[], help="configuration override (repeatable)")
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--warmup", type=int, default=20)
    ap.add_argument("--repeat", type=int, default=3, help="untimed whole-step timings, best of")
    args = ap.parse_args()
    sets = args.set or ["scheme.integrator=ctu", "scheme.cfl=0.8"]

    import numba

    from dustygas.grid import engine as grid_engine
    from dustygas.particles import coupling
    from dustygas.problems import get_problem

    prob = get_problem(args.problem)
    eng = prob.build(prob.config(overrides=sets))
    for _ in range(args.warmup):
        eng.advance(eng.timestep())
    # whole steps without wrappers: CPU and wall time per step
    best_cpu = best_wall = float("inf")
    for _ in range(args.repeat):
        c0, w0 = time.process_time(), time.perf_counter()
        for _ in range(args.steps):
            eng.advance(eng.timestep())
        best_cpu = min(best_cpu, (time.process_time() - c0) / args.steps)
        best_wall = min(best_wall, (time.perf_counter() - w0) / args.steps)
    totals: dict[str, float] = defaultdict(float)
    walls: dict[str, float] = defaultdict(float)
    counts: dict[str, int] = defaultdict(int)
    # per-kernel timers need the Python sequence of the step: the periodic x-z box otherwise runs the whole
    # step as one compiled call (dustygas.particles.step_xz), and no wrapper would see its kernels
    eng.compiled_step = False
    wrap_module(coupling, [n for n in dir(coupling) if not n.startswith("__")], totals, walls, counts)
    wrap_module(grid_engine, [n for n in dir(grid_engine) if not n.startswith("__")], totals, walls, counts)
    c0, w0 = time.process_time(), time.perf_counter()
    for _ in range(args.steps):
        eng.advance(eng.timestep())
    wrapped = (time.process_time() - c0) / args.steps
    wrapped_wall = (time.perf_counter() - w0) / args.steps
    n = args.steps
    print(f"{args.problem} {' '.join(sets)}: {numba.get_num_threads()} thread(s), load {os.getloadavg()[0]:.2f}")
    print(f"{'µs per step':<28}{'calls':>7}{'CPU':>9}{'wall':>9}")
    ksum = wsum = 0.0
    for name, tot in sorted(totals.items(), key=lambda kv: -kv[1]):
        ksum += tot
        wsum += walls[name]
        print(f"{name:<28}{counts[name] / n:>7.1f}{1e6 * tot / n:>9.1f}{1e6 * walls[name] / n:>9.1f}")
    print(f"{'compiled calls, sum':<35}{1e6 * ksum / n:>9.1f}{1e6 * wsum / n:>9.1f}")
    print(f"{'step with wrappers':<35}{1e6 * wrapped:>9.1f}{1e6 * wrapped_wall:>9.1f}")
    print(f"{'Python between the calls':<35}{1e6 * (wrapped - ksum / n):>9.1f}{1e6 * (wrapped_wall - wsum / n):>9.1f}")
    print(f"{'step without wrappers (best)':<35}{1e6 * best_cpu:>9.1f}{1e6 * best_wall:>9.1f}")
    serial = sum(tot for name, tot in totals.items() if name in SERIAL) / n
    python = wrapped - ksum / n
    print(f"serial share of the step (CPU): Python {100 * python / wrapped:.1f} % + serial kernels "
          f"{100 * serial / wrapped:.1f} % = {100 * (python + serial) / wrapped:.1f} % (kernels with parallel "
          f"regions {100 * (ksum / n - serial) / wrapped:.1f} %)")


if __name__ == "__main__":
    main()
