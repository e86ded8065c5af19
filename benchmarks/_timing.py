"""Timing shared by the SPH benchmarks: whole engine steps, thread counts interleaved."""

from __future__ import annotations

import time

import numba
import numpy as np


def interleaved_step_rates(engine, thread_counts: tuple[int, ...], steps: int, repeats: int,
                           updates_per_step: int) -> dict[int, tuple[float, float]]:
    """Best and median updates/s for each thread count over ``repeats`` timings of ``steps`` steps.

    Each step is ``engine.advance(engine.timestep())``. One untimed step per thread count first
    (compilation, first neighbour tables); then the thread counts alternate within every repeat,
    so that they see the same machine (it is shared: the best run is the least disturbed one).
    """
    for threads in thread_counts:
        numba.set_num_threads(threads)
        engine.advance(engine.timestep())
    times: dict[int, list[float]] = {t: [] for t in thread_counts}
    for _ in range(repeats):
        for threads in thread_counts:
            numba.set_num_threads(threads)
            t0 = time.perf_counter()
            for _ in range(steps):
                engine.advance(engine.timestep())
            times[threads].append(time.perf_counter() - t0)
    work = updates_per_step * steps
    return {t: (work / min(v), work / float(np.median(v))) for t, v in times.items()}
