"""What this machine lets two threads gain, before any of our ratios is read.

Two measurements, each in its own process, nothing else should be running:

* ``compute``: a register-only numba loop (no memory traffic beyond L1), 2000 items x 2000
  multiply-adds per call, calls of about 3 ms, timed in 0.5 s windows for ``--seconds`` on one
  thread, then on two. Its ratio is the ceiling of any two-thread figure: 1.95-2.0 on
  2026-12-03 with every window within 4 % of the others.
* ``si-linA``: the coupled particle-gas step of the default job (64^2 cells, 4096 particles,
  everything cache-resident) in blocks of ``--steps`` steps, one thread, then two, in separate
  processes, twice. Its blocks show how much the machine itself moves a memory-touching kernel
  from one minute to the next: on 2026-12-03 (22:53) one-thread blocks of 500 steps ranged over
  1.50-2.27 ms per step and two-thread blocks over 0.95-1.94 ms within three minutes, so a
  ratio of single runs means little; the compute loop beside it stayed within 4 %.

Before and after, ``_cores.py`` probes whether the two CPUs are two cores or one core's two
hardware threads right now (the si-linA blocks' spread is mostly the machine moving between the
two: benchmarks/RESULTS.md, 2026-12-05).

Run alone::

    flock benchmarks/.lock python benchmarks/bench_machine.py [--seconds 6] [--steps 500]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from _cores import describe, vector_gain

ROOT = Path(__file__).resolve().parents[1]

COMPUTE = """
import sys, time, numba, numpy as np
from numba import njit, prange
@njit(parallel=True)
def work(a, n):
    s = np.zeros(a.size)
    for i in prange(a.size):
        x = a[i]
        for k in range(n):
            x = x * 1.0000001 + 1e-9
        s[i] = x
    return s
a = np.random.default_rng(1).random(2000)
work(a, 10)
numba.set_num_threads(int(sys.argv[1]))
end = time.perf_counter() + float(sys.argv[2])
while time.perf_counter() < end:
    t0, n = time.perf_counter(), 0
    while time.perf_counter() - t0 < 0.5:
        work(a, 2000)
        n += 1
    print(n / (time.perf_counter() - t0))
"""

STEPS = """
import sys, time, numba
from dustygas.api import _get_problem, build_engine
problem = _get_problem("si-linA")
engine = build_engine(problem, problem.config([], [], None))
numba.set_num_threads(int(sys.argv[1]))
for _ in range(20):
    engine.advance(engine.timestep())
for _ in range(int(sys.argv[3])):
    t0 = time.perf_counter()
    for _ in range(int(sys.argv[2])):
        engine.advance(engine.timestep())
    print((time.perf_counter() - t0) / int(sys.argv[2]))
"""


def run(code: str, *args: object) -> list[float]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = subprocess.run([sys.executable, "-c", code, *map(str, args)], env=env, capture_output=True, text=True,
                         check=True).stdout
    return [float(x) for x in out.split()]


def summary(values: list[float], scale: float, unit: str) -> str:
    v = sorted(x * scale for x in values)
    return f"median {statistics.median(v):.3g} {unit} [{v[0]:.3g}-{v[-1]:.3g}]"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seconds", type=float, default=6.0, help="length of each compute-loop measurement")
    ap.add_argument("--steps", type=int, default=500, help="si-linA steps per block")
    ap.add_argument("--blocks", type=int, default=8, help="si-linA blocks per process")
    args = ap.parse_args()
    print(f"# bench_machine {time.strftime('%Y-%m-%d %H:%M')} load {os.getloadavg()[0]:.2f}  "
          f"cores: {describe(vector_gain())}")
    rate = {t: run(COMPUTE, t, args.seconds) for t in (1, 2)}
    print(f"compute 1T {summary(rate[1], 1, 'calls/s')}  2T {summary(rate[2], 1, 'calls/s')}  "
          f"2T/1T {statistics.median(rate[2]) / statistics.median(rate[1]):.3f}")
    step: dict[int, list[float]] = {1: [], 2: []}
    for _ in range(2):
        for t in (1, 2):
            step[t] += run(STEPS, t, args.steps, args.blocks)
    print(f"si-linA step 1T {summary(step[1], 1e3, 'ms')}  2T {summary(step[2], 1e3, 'ms')}  "
          f"1T/2T of the medians {statistics.median(step[1]) / statistics.median(step[2]):.3f}  "
          f"load {os.getloadavg()[0]:.2f}  cores: {describe(vector_gain())}")


if __name__ == "__main__":
    main()
