"""Particle tests run on one numba thread unless they say otherwise: results do not depend on
the thread count (a test checks that), and the machine is shared with other test runs."""

import numba
import pytest


@pytest.fixture(autouse=True)
def one_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)
