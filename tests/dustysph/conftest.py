"""Dusty SPH tests run their numba kernels on one thread (the pair sums gather per particle, so
results do not depend on the thread count; one thread keeps these short runs cheap on a machine
whose cores other test sessions share)."""

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)
