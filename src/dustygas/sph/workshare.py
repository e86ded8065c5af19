"""Dynamic sharing of a parallel loop's work between numba threads: chunks handed out by a counter.

numba's OpenMP layer splits a ``prange`` into one contiguous block of iterations per thread
(``parallel_chunksize`` only changes the number of blocks, which are still dealt out statically),
so a parallel region lasts as long as its slowest block: the one whose particles have the most
neighbours, or whose thread another process interrupted for a few milliseconds. The SPH pair
loops therefore share their work the way OpenMP's ``schedule(dynamic)`` does: the loop runs over
:data:`WORKERS` workers, which numba deals out to the threads as usual, and each worker takes the
next chunk of particles from a shared counter (:func:`next_chunk`, an atomic fetch-and-add) until
none is left, so a thread that falls behind simply takes fewer chunks (the workers that start after
the last chunk is gone return at once)::

    counter = new_counter()
    for _worker in prange(WORKERS):
        c = next_chunk(counter)
        while c < nchunk:
            ...  # the particles of chunk c
            c = next_chunk(counter)

The counter is allocated in the kernel by :func:`new_counter` before the loop and never read
after it: numba does not know that :func:`next_chunk` writes it, so it keeps the (zero-filling)
allocation before the loop, which reads the counter, but may move a later read of it before the
loop. :func:`new_counter` fills it on one thread: ``np.zeros`` in a parallel kernel would be a
parallel region of its own (:mod:`dustygas.arrays`). (``numba.get_num_threads()`` inside a kernel
would make it uncachable: it reads a C pointer.)
Each chunk writes only its own particles' results, computed the same way whichever thread takes
it, so the results are bit-identical for any thread count and any interleaving.
"""

from __future__ import annotations

from numba import njit, types
from numba.core import cgutils
from numba.extending import intrinsic

from ..arrays import serial_full

__all__ = ["CHUNK", "WORKERS", "new_counter", "next_chunk"]

#: iterations of the ``prange`` whose bodies take the chunks: at least the number of threads
WORKERS = 64
#: particles (or tree leaves) per chunk of a pair loop: fine enough to even out a few milliseconds'
#: interruption of one thread, coarse enough that the counter is touched once per ~0.1 ms of work
CHUNK = 32


@njit(cache=True)
def new_counter():
    """The shared chunk counter of a dynamically shared loop: one int64, zero."""
    return serial_full(1, 0)


@intrinsic
def next_chunk(typingctx, counter):
    """Atomically ``counter[0] += 1``; returns the value before the increment (``counter``: one int64)."""
    if not (isinstance(counter, types.Array) and counter.dtype == types.int64 and counter.ndim == 1):
        return None

    def codegen(context, builder, signature, args):
        array = context.make_array(signature.args[0])(context, builder, args[0])
        zero = context.get_constant(types.intp, 0)
        ptr = cgutils.get_item_pointer(context, builder, signature.args[0], array, [zero])
        one = context.get_constant(types.int64, 1)
        return builder.atomic_rmw("add", ptr, one, "monotonic")

    return types.int64(counter), codegen

