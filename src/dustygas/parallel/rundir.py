"""The run directory as seen by the ranks that do not write it.

Under MPI rank 0 writes every file of a run (snapshots, history, checkpoints, the log: one set
of files, whatever the rank count) and holds the directory's lock; the other ranks get a
:class:`ReadOnlyRunDirectory`, which reads like a :class:`~dustygas.io.rundir.RunDirectory`
and whose writers do nothing.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ..io.rundir import RunDirectory
from .comm import is_writer

__all__ = ["ReadOnlyRunDirectory", "run_directory"]


class _NoLock:
    previous = None
    held = True


class ReadOnlyRunDirectory(RunDirectory):
    """A run directory that this rank reads but never writes (rank 0 writes it)."""

    def lock(self):  # type: ignore[override]
        return _NoLock()

    def unlock(self, discard: bool = False) -> None:
        pass

    def check_new(self, overwrite: bool = False) -> None:
        pass

    def create(self, overwrite: bool = False) -> None:
        pass

    def write_config(self, text: str) -> None:
        pass

    def log(self, message: str) -> None:
        pass

    def write_snapshot(self, index: int, arrays: Any, attrs: Any) -> Path:
        return self.snapshot_file(index)

    def write_history(self, columns: Any, attrs: Any) -> None:
        pass

    def write_checkpoint(self, index: int, arrays: Any, attrs: Any, keep: int = 2) -> Path:
        return self.checkpoint_file(index)

    def write_crash(self, arrays: Any, attrs: Any) -> Path:
        return self.crash_file


def run_directory(path: str | Path) -> RunDirectory:
    """The writing :class:`RunDirectory` on rank 0 (and without MPI), a read-only view elsewhere."""
    return RunDirectory(path) if is_writer() else ReadOnlyRunDirectory(path)
