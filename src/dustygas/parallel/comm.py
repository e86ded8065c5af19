"""How this process was launched, without importing MPI unless it must.

``mpiexec`` (MPICH's Hydra, Open MPI, Slurm's PMI) puts the rank and the world size into the
environment of every process it starts; a plain ``python`` or ``dustygas`` run has none of them,
so a one-process run never loads :mod:`mpi4py` (nor the MPI library behind it).
"""

from __future__ import annotations

from .._launch import rank_and_size

__all__ = ["launched_under_mpi", "rank_and_size", "world", "agreed", "is_writer", "check_ranks"]


def launched_under_mpi() -> bool:
    """True when a launcher started this process as one of several ranks."""
    return rank_and_size()[1] > 1


def world():
    """``MPI.COMM_WORLD`` (imports :mod:`mpi4py` on the first call). A rank holds its stop
    signals from ``import dustygas`` on (:mod:`dustygas._launch`)."""
    from mpi4py import MPI

    return MPI.COMM_WORLD


def agreed(action):
    """``action()`` on every rank; a :class:`~dustygas.errors.UserError` on any rank is raised on
    all of them (the first in rank order), so that no rank goes on into a collective step that
    the others have left. Without MPI: just ``action()``."""
    if not launched_under_mpi():
        return action()
    from ..errors import UserError

    try:
        result, message = action(), None
    except UserError as exc:
        result, message = None, str(exc)
    messages = world().allgather(message)
    first = next((m for m in messages if m is not None), None)
    if first is not None:
        raise UserError(first)
    return result


def is_writer() -> bool:
    """Whether this process writes the run's files (rank 0, or a plain process)."""
    return rank_and_size()[0] == 0


def check_ranks(problem) -> None:
    """Refuse (one line) to run a problem on several ranks whose engine does not decompose."""
    if launched_under_mpi() and not getattr(problem, "runs_on_ranks", False):
        from ..errors import UserError

        raise UserError(f"problem {problem.name} does not run on several MPI ranks yet "
                        "(the grid and particle-grid problems do): run it with one process")
