"""Array helpers for the compiled kernels.

Inside a function compiled with ``parallel=True``, numba turns ``np.zeros``, ``np.ones`` and
``np.full`` into parallel loops of their own: each one a parallel region, whose start and end
cost about a microsecond on two threads (more when a thread has to be woken) for arrays of a
few dozen elements. Kernels that only need small work arrays take them from :func:`serial_full`,
compiled without ``parallel``, so that their only parallel regions are the loops they mean.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["serial_full"]


@njit(cache=True)
def serial_full(n, value):
    """A 1D array of ``n`` elements all ``value`` (its type: ``-1`` gives int64, ``0.0`` float64),
    filled by one thread (for small arrays inside a parallel kernel).

    >>> serial_full(3, -1).tolist(), serial_full(2, 0.0).tolist()
    ([-1, -1, -1], [0.0, 0.0])
    """
    return np.full(n, value)
