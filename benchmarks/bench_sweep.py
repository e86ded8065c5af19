"""Wall time of a 10⁴-point shearing-wave sweep (``dustygas linear sweep``, thesis §4.6.2).

Grid (5 × 5 × 20 × 20 = 10⁴ waves): μ ∈ logspace(−1.5, 0.5, 5) (0.03 … 3), τ_s ∈ logspace(−2, 0, 5)
(0.01 … 1), K_x0 ∈ linspace(−30, 30, 20), K_y ∈ linspace(0.5, 5, 20); K_z = 0, Π = 0.05, consistent
drag, t_end = 2π (one orbit), the fastest eigenmode as initial state, rtol = 1e-6 (the defaults).
The work per wave grows with c_s|k| t_end (explicit steps resolve the sound waves), so the figure
holds for this grid; the script also prints the accepted steps and µs per step.

Prints the wall time and the CPU seconds (this process plus its workers) for the process pool
with 1 and 2 workers and the serial executor, with the machine's load. Target (issue 15): ≤ 60 s
on the 2-core machine.

Run alone: ``flock benchmarks/.lock python benchmarks/bench_sweep.py`` (``--quick``: 1/4 of the grid).
"""

from __future__ import annotations

import argparse
import os
import resource
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "src"))

from dustygas.linear.sweep import SweepSpec  # noqa: E402
from dustygas.linear.sweep_run import open_executor, run_sweep  # noqa: E402

TARGET_S = 60.0


def grid(quick: bool) -> SweepSpec:
    n = 10 if quick else 20
    return SweepSpec(mu=np.logspace(-1.5, 0.5, 5), taus=np.logspace(-2, 0, 5), kx=np.linspace(-30, 30, n),
                     ky=np.linspace(0.5, 5, n), t_end=2 * np.pi)


def cpu_seconds() -> float:
    own = resource.getrusage(resource.RUSAGE_SELF)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--executors", nargs="+", default=["process:2", "process:1", "serial"])
    args = ap.parse_args()
    spec = grid(args.quick)
    run_sweep(SweepSpec(mu=[1.0], taus=[0.1], kx=[-10.0], ky=[1.0]))  # compile / load the kernel cache
    print(f"sweep of {spec.size} waves, load {os.getloadavg()[0]:.2f} (1 min) before")
    reference = None
    for name in args.executors:
        kind, _, workers = name.partition(":")
        c0, t0 = cpu_seconds(), time.perf_counter()
        with open_executor(kind, workers=int(workers) if workers else None) as ex:
            r = run_sweep(spec, executor=ex)
        wall, cpu = time.perf_counter() - t0, cpu_seconds() - c0
        steps = int(r["steps"].sum())
        same = "" if reference is None else f", identical to {reference[0]}: " + str(
            all(np.array_equal(r[k], reference[1][k], equal_nan=True) for k in r.data))
        if reference is None:
            reference = (name, r.data)
        print(f"{name:10s} wall {wall:7.1f} s  cpu {cpu:7.1f} s  {spec.size / wall:8.1f} waves/s  "
              f"{steps:.3e} steps ({1e6 * cpu / steps:.2f} cpu-us/step)  load {os.getloadavg()[0]:.2f}"
              f"  target {'met' if wall <= TARGET_S else 'NOT met'} ({TARGET_S:g} s){same}")


if __name__ == "__main__":
    main()
