"""SPH tests run their numba kernels on one thread.

Every SPH kernel gathers per particle (no reductions across threads), so results do not depend
on the thread count -- ``test_conservation.py::test_results_independent_of_thread_count`` checks
that bit for bit. One thread keeps the many small kernel launches of these short runs cheap on
a machine whose cores other test sessions share.
"""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
