"""LAPACK on one BLAS thread in the linear-theory tests.

The eigenproblems of these tests (up to 1032² in the default suite, 2056² in the slow one) are
too small for a second BLAS thread to pay, and OpenBLAS's threads spin-wait like numba's: on the
two-core machine with the other core busy (load 6, 2026-12-03), psitools' N = 257 case of
``test_polydisperse.py`` took 1.85 CPU-s (7.6 s wall) on one OpenBLAS thread and 34.8 CPU-s (106 s
wall) on two. The tests' tolerances do not depend on it (LAPACK's eigenvalues agree to rounding
whatever its thread count).
"""

import pytest
from threadpoolctl import threadpool_limits


@pytest.fixture(autouse=True, scope="session")
def one_blas_thread():
    with threadpool_limits(limits=1, user_api="blas"):
        yield
