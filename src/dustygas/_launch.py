"""How this process was launched, read from its environment alone, and the stop signals an MPI
rank holds.

Imported first by :mod:`dustygas` (nothing here imports numpy or MPI), so that under an MPI
launcher SIGTERM and SIGINT are blocked before any helper thread exists: the BLAS library's
threads (started when numpy is imported), numba's and the MPI library's (MPICH starts an
``async`` progress thread at ``MPI_Init``) inherit the mask. Delivered at an arbitrary moment --
to one of those threads, or to the main thread in the middle of a message exchange -- a stop
signal sent to one rank of a two-rank run left the ranks one exchange apart and waiting for each
other forever (measured 2026-12-03: 2 hangs in 8 signals sent in the first steps of si-linA,
none in 10 with the signals held). Held, a signal stays pending until the run loop takes it at
its agreement point after each step (:meth:`dustygas.runner.RunLoop.loop`), where every rank
learns it in the same step. A one-process run is unaffected.
"""

from __future__ import annotations

import os
import signal

__all__ = ["rank_and_size", "STOP_SIGNALS", "hold_stop_signals", "release_stop_signals", "hold_if_launched"]

#: (rank variable, size variable) of the launchers we know
_LAUNCHER_VARIABLES = (
    ("PMI_RANK", "PMI_SIZE"),  # MPICH Hydra, Intel MPI
    ("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"),  # Open MPI
    ("PMIX_RANK", "PMIX_SIZE"),
)

#: the signals that ask a run to stop with a checkpoint
STOP_SIGNALS = frozenset({signal.SIGTERM, signal.SIGINT})


def rank_and_size() -> tuple[int, int]:
    """``(rank, size)`` from the launcher's environment; ``(0, 1)`` for a plain process.

    >>> import os
    >>> rank_and_size() if "PMI_RANK" not in os.environ else (0, 1)
    (0, 1)
    """
    for rank_var, size_var in _LAUNCHER_VARIABLES:
        if rank_var in os.environ and size_var in os.environ:
            return int(os.environ[rank_var]), int(os.environ[size_var])
    return 0, 1


def hold_stop_signals() -> None:
    """Block SIGTERM and SIGINT in this thread and in every thread it starts from now on."""
    signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)


def release_stop_signals() -> None:
    """Unblock SIGTERM and SIGINT in this thread (the threads already started keep them blocked,
    so a pending or later signal is delivered here)."""
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)


def hold_if_launched() -> None:
    """:func:`hold_stop_signals` when an MPI launcher started this process as one of several ranks."""
    if rank_and_size()[1] > 1:
        hold_stop_signals()
