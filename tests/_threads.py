"""The autouse fixture that runs an area's tests on one numba thread.

Used by the conftest.py of the engine test areas (grid, particles, sph, dustysph): their kernels
give results independent of the thread count (each area has a test that checks it bit for bit),
and one thread keeps the many small kernel launches of short test runs cheap on a machine whose
cores other jobs share (numba's OpenMP threads spin-wait at the end of each parallel region).
"""

import numba
import pytest


@pytest.fixture(autouse=True)
def one_numba_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)
