"""dustygas: dust and gas in protoplanetary disks.

Public API (the names below are the stable surface; submodules hold the details):

* :mod:`dustygas.physics` -- formulas of the thesis as vectorised functions;
* :func:`run` -- run a registered problem into a run directory;
* :func:`problem_names`, :func:`get_problem` -- the problem registry;
* :mod:`dustygas.linear`, :mod:`dustygas.grid`, :mod:`dustygas.sph` -- the engines
  (added as they land).
"""

from ._numba_cache import install as _install_numba_cache_guard
from ._version import __version__

_install_numba_cache_guard()  # before any kernel module is imported (see dustygas._numba_cache)

from .api import get_problem, problem_names, run

__all__ = ["__version__", "run", "problem_names", "get_problem"]
