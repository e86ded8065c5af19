"""Whether this machine's two CPUs are two cores right now, or two hardware threads of one.

On the 2-core benchmark machine (a virtual machine) a two-thread figure has two values, minutes
apart (benchmarks/RESULTS.md, 2026-12-05 "Two threads of the linA step: a bimodal machine"). In
one state a loop of independent, vectorised multiply-adds on an L1-resident row per thread gains
1.6-1.75 on two threads; in the other it gains 0.7-0.8 (it loses), while a loop of one dependent
multiply-add chain per thread gains 2.0 in both -- what two hardware threads of one physical core
do (they share the vector units; a latency-bound chain leaves them idle for the other thread).
:func:`vector_gain` measures the first loop in a fresh process (about a second); the benchmarks
print it beside their two-thread figures so that each figure says which machine it ran on.

That reading holds for the AMD machine it was made on. On an Intel two-vCPU machine (2026-12-05
afternoon) the probe was bimodal too (0.43-1.87), but its state did not predict our kernels'
gains: a grid-box repeat probed as "two cores" gained 1.21 and two probed as "shared" 1.77 and
1.80 (benchmarks/RESULTS.md). There, read the per-repeat ratios, not the label.

:func:`stream_gain` (since 2026-12-07) times a second loop, each thread streaming through its own
half of 3 MB, about the si-linA step's working set: it tells whether the host lets two threads
move data at full speed right now (1.94-1.96), which the register-bound and L1-bound loops above
do not. Both probes describe the second they ran in, not the run after them.
"""

from __future__ import annotations

import os
import subprocess
import sys

#: below this vector gain the two CPUs share one core's vector units
SHARED_BELOW = 1.2

#: the vectorised loop and its two-thread gain (best of ``rounds`` calls of ``reps`` passes per thread
#: count); the source is run in a fresh process here and inside bench_machine's stepping process, and
#: defines ``two_thread_gain``, which the stream probe below uses too
VECTOR_PROBE = """
import time, numba, numpy as np
from numba import njit, prange
def two_thread_gain(call, rounds):
    best = {}
    for n in (1, 2, 1, 2):
        numba.set_num_threads(n)
        for _ in range(rounds):
            t0 = time.perf_counter()
            call(n)
            best[n] = min(best.get(n, 1e9), time.perf_counter() - t0)
    return best[1] / best[2]
@njit(parallel=True, fastmath=True)
def vector(x, reps):
    for c in prange(2):
        y = x[c]
        for r in range(reps):
            for i in range(y.size):
                y[i] = y[i] * 0.9999999 + 1e-7
x = np.ones((2, 1024))
vector(x, 1)
def vector_probe(reps, rounds):
    return two_thread_gain(lambda n: vector(x, reps), rounds)
"""

PROBE = VECTOR_PROBE + "print(vector_probe(20000, 8))\n"

#: a streaming loop over 3 MB -- about the arrays of the si-linA step (2.9 MB), more than one core's
#: L2 (1 MB), held in the L3 the vCPUs share with the host's other guests -- in two halves, and its
#: two-thread gain (best of ``rounds`` calls of ``passes`` passes per thread count). On 2026-12-07
#: (AMD) a 4 MB version gained 1.96 (median of 12 rounds) at 00:47 and the 3 MB one 0.84-2.11
#: (median 1.19, 16 rounds) at 01:27, beside si-linA steps that gained 0.96-1.87 (median 1.30) in
#: the same seconds (benchmarks/RESULTS.md): a loop with no synchronisation and nothing shared
#: between the threads loses as much as our step when the host is in its slow state. The source
#: runs after ``VECTOR_PROBE``, whose imports and ``two_thread_gain`` it uses
STREAM_PROBE = """
@njit(parallel=True)
def stream(x, nchunk, passes):
    n = x.size
    for c in prange(nchunk):
        lo, hi = c * n // nchunk, (c + 1) * n // nchunk
        for r in range(passes):
            for i in range(lo, hi):
                x[i] = x[i] * 0.9999999 + 1e-7
xs = np.ones(3 * 1024 * 1024 // 8)
stream(xs, 1, 1)
stream(xs, 2, 1)
def stream_probe(passes, rounds):
    return two_thread_gain(lambda n: stream(xs, n, passes), rounds)
"""

STREAM = VECTOR_PROBE + STREAM_PROBE + "print(stream_probe(20, 3))\n"


def vector_gain() -> float:
    """Two-thread gain of the vectorised loop (NaN if the machine has fewer than two CPUs)."""
    return _probe(PROBE)


def stream_gain() -> float:
    """Two-thread gain of the 3 MB streaming loop (NaN if the machine has fewer than two CPUs)."""
    return _probe(STREAM)


def _probe(code: str) -> float:
    """Run a probe's source in a fresh process with two numba threads; its last number printed."""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         env={**os.environ, "NUMBA_NUM_THREADS": "2"})
    try:
        return float(out.stdout.split()[-1])
    except (IndexError, ValueError):
        return float("nan")


def describe(gain: float) -> str:
    """``"2 cores (vector gain 1.71)"`` or ``"1 core's 2 hardware threads (vector gain 0.74)"``."""
    kind = "1 core's 2 hardware threads" if gain < SHARED_BELOW else "2 cores"
    return f"{kind} (vector gain {gain:.2f})"


if __name__ == "__main__":
    print(f"{describe(vector_gain())}; 3 MB stream gain {stream_gain():.2f}")
