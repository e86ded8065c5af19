"""Particle tests run on one numba thread unless they say otherwise: results do not depend on
the thread count (a test checks that), and the machine is shared with other test runs."""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
