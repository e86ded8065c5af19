"""Dusty SPH tests run their numba kernels on one thread (the pair sums gather per particle, so
results do not depend on the thread count; one thread keeps these short runs cheap on a machine
whose cores other test sessions share)."""

import numba
import pytest


@pytest.fixture(autouse=True)
def _one_numba_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)
