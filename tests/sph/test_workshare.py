"""The dynamic work sharing of the SPH pair loops (:mod:`dustygas.sph.workshare`).

Workers of a ``prange`` take chunks from a counter with an atomic fetch-and-add: every chunk
must be processed exactly once, whatever the number of threads and however they interleave.
"""

import numpy as np
from _threads import assert_identical, results_at_threads
from numba import njit, prange

from dustygas.sph.workshare import WORKERS, next_chunk

N_ITEMS = 20_003  # a last, partial chunk
CHUNK = 7


@njit(parallel=True)
def _take_chunks(x, chunk, taken, out):
    """The kernels' pattern (counter allocated in the kernel, never read after the loop): each item
    counts how often it was processed and gets a few microseconds of work, so both threads take part."""
    n = x.shape[0]
    nchunk = (n + chunk - 1) // chunk
    counter = np.zeros(1, np.int64)
    for _worker in prange(WORKERS):
        c = next_chunk(counter)
        while c < nchunk:
            for i in range(c * chunk, min(n, (c + 1) * chunk)):
                s = x[i]
                for k in range(500):
                    s = np.sqrt(s + k)
                out[i] = s
                taken[i] += 1
            c = next_chunk(counter)


def chunk_case() -> dict:
    x = np.linspace(0.0, 1.0, N_ITEMS)
    taken = np.zeros(N_ITEMS, np.int64)
    out = np.zeros(N_ITEMS)
    _take_chunks(x, CHUNK, taken, out)
    return {"taken": taken, "out": out}


def test_every_chunk_taken_once_at_one_and_two_threads(tmp_path):
    """Each of the 20,003 items (2,858 chunks) is processed exactly once at 1 and at 2 threads
    (each in its own interpreter: a counter private to a thread or a worker would process items
    2 or 64 times), and the results are bit-identical."""
    one, two = results_at_threads("sph.test_workshare:chunk_case", tmp_path)
    for result in (one, two):
        np.testing.assert_array_equal(result["taken"], np.ones(N_ITEMS, np.int64))
    assert_identical([one, two])
