"""SPH tests run their numba kernels on one thread.

Every SPH kernel gathers per particle (no reductions across threads), so results do not depend
on the thread count -- ``test_conservation.py::test_results_independent_of_thread_count`` checks
that bit for bit. One thread keeps the many small kernel launches of these short runs cheap on
a machine whose cores other test sessions share.
"""

import numba
import pytest


@pytest.fixture(autouse=True)
def _one_numba_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)
