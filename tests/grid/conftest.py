"""Grid tests run on one numba thread: results do not depend on the thread count (a test checks
that), and on a machine shared with other test runs, parallel regions only add waiting."""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
