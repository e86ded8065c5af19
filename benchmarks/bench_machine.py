"""What this machine lets two threads gain, before any of our ratios is read.

Two measurements, each in its own process, nothing else should be running:

* ``compute``: a register-only numba loop (no memory traffic beyond L1), 2000 items x 2000
  multiply-adds per call, calls of about 3 ms, timed in 0.5 s windows for ``--seconds`` on one
  thread, then on two. Its ratio is the ceiling of any two-thread figure: 1.95-2.0 on
  2026-12-03 with every window within 4 % of the others.
* ``si-linA``: the coupled particle-gas step of the default job (64^2 cells, 4096 particles) in
  ``--pairs`` pairs of adjacent blocks of ``--steps`` steps, one on one thread and one on two (the
  order alternating), in one process; each pair between two in-process probes of the vectorised
  loop of ``_cores.py``. The machine moves under a two-thread figure within seconds: on
  2026-12-03 (22:53) one-thread blocks of 500 steps ranged over 1.50-2.27 ms per step and
  two-thread blocks over 0.95-1.94 ms within three minutes, and on 2026-12-06 (AMD) two-thread
  blocks fell into two groups, near 0.65 ms and near 0.89 ms, while the one-thread blocks stayed
  at 1.16-1.25 ms. A pair's ratio is the two-thread gain of the code at that moment. The probes
  beside the pairs did not tell the slow two-thread blocks from the fast ones there (they read
  1.6-2.0, two cores, around both), nor did the cost of an empty parallel region (1.1-1.2 µs
  throughout) or a cache line's round trip between the two CPUs (50-160 ns, not related to the
  blocks' times): the slow state is in the host, outside what these probes see. Since 2026-12-07
  a second probe stands beside each pair, the 3 MB streaming loop of ``_cores.py`` (no
  synchronisation, no sharing between the threads, about the step's working set), and the
  script prints how a pair's gain goes with each probe and the pairs whose stream probe read
  >= 1.9 on both sides. That day (01:27-01:30) the stream loop itself gained 0.84-2.1 from one
  second to the next: the slow state slows two threads streaming through the L3 whatever code
  runs. A pair's gain went with it only loosely (correlation 0.61, 0.63 and 0.15 in three sets),
  since a probe sees the second before and after a pair, not the pair.

Run alone::

    flock benchmarks/.lock python benchmarks/bench_machine.py [--seconds 6] [--steps 200] [--pairs 60]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

from _cores import STREAM_PROBE, VECTOR_PROBE, describe, stream_gain, vector_gain

ROOT = Path(__file__).resolve().parents[1]
#: the stream probe's two-thread gain above which a pair counts as measured on a quiet machine (the
#: probe gains 1.94-1.96 when nothing slows the host, 2026-12-07 00:47)
QUIET_STREAM = 1.9

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

STEPS = VECTOR_PROBE + STREAM_PROBE + """
import sys
from dustygas.api import _get_problem, build_engine
problem = _get_problem("si-linA")
engine = build_engine(problem, problem.config([], [], None))
for t in (1, 2):
    numba.set_num_threads(t)
    for _ in range(50):
        engine.advance(engine.timestep())
steps = int(sys.argv[1])
for pair in range(int(sys.argv[2])):
    before = vector_probe(4000, 3)
    stream_before = stream_probe(10, 2)
    seconds = {}
    for t in ((1, 2) if pair % 2 == 0 else (2, 1)):
        numba.set_num_threads(t)
        t0 = time.perf_counter()
        for _ in range(steps):
            engine.advance(engine.timestep())
        seconds[t] = (time.perf_counter() - t0) / steps
    print(min(before, vector_probe(4000, 3)), min(stream_before, stream_probe(10, 2)), seconds[1], seconds[2])
"""


def run(code: str, *args: object) -> list[float]:
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = subprocess.run([sys.executable, "-c", code, *map(str, args)], env=env, capture_output=True, text=True,
                         check=True).stdout
    return [float(x) for x in out.split()]


def summary(values: list[float], scale: float, unit: str) -> str:
    v = sorted(x * scale for x in values)
    return f"median {statistics.median(v):.4g} {unit} [{v[0]:.4g}-{v[-1]:.4g}]"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seconds", type=float, default=6.0, help="length of each compute-loop measurement")
    ap.add_argument("--steps", type=int, default=200, help="si-linA steps per block")
    ap.add_argument("--pairs", type=int, default=60, help="pairs of si-linA blocks (one thread, two threads)")
    args = ap.parse_args()
    print(f"# bench_machine {time.strftime('%Y-%m-%d %H:%M')} load {os.getloadavg()[0]:.2f}  "
          f"cores: {describe(vector_gain())}; 3 MB stream gain {stream_gain():.2f}")
    rate = {t: run(COMPUTE, t, args.seconds) for t in (1, 2)}
    print(f"compute 1T {summary(rate[1], 1, 'calls/s')}  2T {summary(rate[2], 1, 'calls/s')}  "
          f"2T/1T {statistics.median(rate[2]) / statistics.median(rate[1]):.3f}")
    rows = run(STEPS, args.steps, args.pairs)
    pairs = [(rows[i], rows[i + 1], rows[i + 2], rows[i + 3]) for i in range(0, len(rows), 4)]
    t1, t2 = [q[2] for q in pairs], [q[3] for q in pairs]
    gains = [a / b for a, b in zip(t1, t2)]
    streams = [q[1] for q in pairs]
    print(f"si-linA step, {len(pairs)} pairs of adjacent {args.steps}-step blocks on one and two threads:")
    print(f"  1T {summary(t1, 1e6, 'us')} (10-90 % {deciles(t1, 1e6, '.0f')})")
    print(f"  2T {summary(t2, 1e6, 'us')} (10-90 % {deciles(t2, 1e6, '.0f')})")
    print(f"  1T/2T of the medians {statistics.median(t1) / statistics.median(t2):.3f}; per pair median "
          f"{statistics.median(gains):.3f} (10-90 % {deciles(gains, 1, '.3f')}); vector probe beside the pairs median "
          f"{statistics.median([q[0] for q in pairs]):.2f} (10-90 % {deciles([q[0] for q in pairs], 1, '.2f')})")
    print(f"  3 MB stream probe beside the pairs median {statistics.median(streams):.2f} (10-90 % "
          f"{deciles(streams, 1, '.2f')}); correlation of a pair's gain with it {correlation(gains, streams):.2f}, "
          f"with the vector probe {correlation(gains, [q[0] for q in pairs]):.2f}")
    quiet = [g for g, q in zip(gains, streams) if q >= QUIET_STREAM]
    print(f"  pairs with the stream probe >= {QUIET_STREAM} on both sides (the host letting two threads stream at "
          f"full speed): {len(quiet)}" + (f", their per pair gain median {statistics.median(quiet):.3f} (10-90 % "
                                          f"{deciles(quiet, 1, '.3f')})" if quiet else ""))
    print(f"load {os.getloadavg()[0]:.2f}  cores: {describe(vector_gain())}; 3 MB stream gain {stream_gain():.2f}")


def correlation(a: list[float], b: list[float]) -> float:
    """Pearson's correlation of two lists (NaN where either is constant or shorter than two)."""
    try:
        return statistics.correlation(a, b)
    except statistics.StatisticsError:
        return float("nan")


def deciles(values: list[float], scale: float, fmt: str) -> str:
    """The 10 % and 90 % points of a list (its ends when shorter than 10)."""
    v = sorted(x * scale for x in values)
    if len(v) >= 10:
        q = statistics.quantiles(v, n=10)
        v = [q[0], q[-1]]
    return f"{v[0]:{fmt}}-{v[-1]:{fmt}}"


if __name__ == "__main__":
    main()
