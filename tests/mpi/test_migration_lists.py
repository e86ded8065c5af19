"""The compiled sorting of a block's particles for migration (no MPI needed):
:func:`dustygas.parallel.particles.migration_lists` on planted owners."""

import numpy as np
import pytest

from dustygas.parallel.particles import migration_lists


def _lists(dest, block, lo, hi):
    n = len(dest)
    moving, keep = np.full(n, -7, dtype=np.int64), np.zeros(n, dtype=np.bool_)
    n_down, n_up, stray, gone = migration_lists(np.asarray(dest, dtype=np.int64), n, block, lo, hi, moving, keep)
    return list(moving[:n_down]), list(moving[n_down:n_down + n_up]), stray, gone, list(keep)


def test_down_up_stay_leave_and_stray_in_index_order():
    # block 2 of 5: 1 below, 3 above; -1 leaves the box, -2 a non-finite position (stays), 4 a stray
    dest = [2, 1, 3, -1, 2, 1, -2, 4, 3, 0]
    down, up, stray, gone, keep = _lists(dest, block=2, lo=1, hi=3)
    assert down == [1, 5] and up == [2, 8]
    assert stray == 7  # the first one that jumped past a neighbour: it stays (never clamped)
    assert gone == 5  # two down, two up, one out of the box
    assert keep == [True, False, False, False, True, False, True, True, False, True]


@pytest.mark.parametrize("lo, hi", [(1, 1), (-1, 1), (1, -1), (-1, -1)])
def test_two_blocks_around_a_periodic_axis_and_the_ends(lo, hi):
    """With two blocks lo == hi and every crossing particle goes "down"; at an end (-1) a
    particle for the missing side is a stray."""
    dest = [0, 1, 1, 0, -1]
    down, up, stray, gone, keep = _lists(dest, block=0, lo=lo, hi=hi)
    crossing = [1, 2]
    if lo == 1:
        assert down == crossing and up == [] and stray == -1
    elif hi == 1:
        assert down == [] and up == crossing and stray == -1
    else:
        assert down == [] and up == [] and stray == 1
    assert gone == 1 + (len(crossing) if stray < 0 else 0)
    assert sum(keep) == len(dest) - gone
