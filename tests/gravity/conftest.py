"""Gravity tests run on one numba thread (a test checks that results do not depend on it)."""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
