"""Grid tests run on one numba thread: results do not depend on the thread count (a test checks
that), and on a machine shared with other test runs, parallel regions only add waiting."""

import numba
import pytest


@pytest.fixture(autouse=True)
def one_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)
