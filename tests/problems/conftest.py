"""Registry tests run their engines on one numba thread (results do not depend on it; the engine
areas check that), restored afterwards."""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
