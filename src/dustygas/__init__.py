"""dustygas: dust and gas in protoplanetary disks.

The public API is :mod:`dustygas.api`, re-exported here (``import dustygas as dg``):

* run problems: :func:`run`, :func:`restart`, :func:`branch`, :func:`problem_names`, :func:`get_problem`,
  :func:`problem_parameters`;
* read and export runs: :func:`open_run` (xarray Datasets), :func:`export`;
* look at runs: :func:`plot_history`, :func:`plot_snapshot`, :func:`movie`;
* analyses: :func:`measure_growth`, :func:`growth_theory`, the linear theory
  :mod:`dustygas.linear` and the formulas :mod:`dustygas.physics`;
* thesis figures: :func:`figure_names`, :func:`reproduce_figures` (not to be confused with the
  package :mod:`dustygas.reproduce` of figure functions).
"""

from ._launch import hold_if_launched as _hold_if_launched

_hold_if_launched()  # an MPI rank: before numpy starts the BLAS threads (see dustygas._launch)

from ._numba_cache import install as _install_numba_cache_guard
from ._version import __version__

_install_numba_cache_guard()  # before any kernel module is imported (see dustygas._numba_cache)

from .api import (
    dry_run,
    export,
    figure_names,
    get_problem,
    growth_theory,
    measure_growth,
    movie,
    open_run,
    plot_history,
    plot_snapshot,
    problem_names,
    problem_parameters,
    reproduce_figures,
    restart,
    branch,
    run,
)

__all__ = ["__version__", "run", "restart", "branch", "dry_run", "problem_names", "get_problem", "problem_parameters", "open_run",
           "export", "plot_history", "plot_snapshot", "movie", "measure_growth", "growth_theory",
           "figure_names", "reproduce_figures"]
