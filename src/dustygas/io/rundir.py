"""The run directory: the unit of output of every simulation.

Layout::

    RUN/
      config.toml            fully merged parameters, with the problem name and dustygas version
      log.txt                human-readable log (append-only, one line per event)
      history.h5             time series of scalar diagnostics (rewritten atomically)
      snapshots/snap_NNNNN.h5
      checkpoints/chk_NNNNN.h5   full restart state with a checksum (the newest ``keep`` are kept)
      crash.h5               state dump written when a run stops on an invalid state
      .lock                  held (flock) by the one process writing the directory

Every file except the append-only log is written to a temporary name and renamed. Only the
process holding the lock (:meth:`RunDirectory.lock`, :mod:`dustygas.io.lock`) writes; it
removes the temporary files a killed writer left behind.
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ..errors import OutputError, UserError
from .atomic import atomic_write_text, output_error, remove_stale_temporaries
from .hdf5 import read_h5, write_h5
from .lock import LOCK_NAME, RunLock
from .schema import annotate_history, annotate_snapshot

__all__ = ["RunDirectory", "default_run_path", "check_output_path"]

_SNAP = re.compile(r"snap_(\d{5,})\.h5$")
_CHK = re.compile(r"chk_(\d{5,})\.h5$")


def default_run_path(problem: str, base: str | Path = "runs") -> Path:
    """``runs/<problem>``: a run refuses to start there if it holds another run."""
    return Path(base) / problem


def check_output_path(path: str | Path) -> Path:
    """Refuse (one line) an output path that cannot become a run directory; return it.

    Checked before anything is built or written: an empty name, a NUL byte, a name too long, a
    component that is an existing file, a parent where no directory can be created.
    """
    text = os.fspath(path)
    if not text.strip():
        raise UserError("output path is empty: give a directory name (-o DIR)")
    if "\0" in text:
        raise UserError(f"output path {text!r} contains a NUL byte")
    p = Path(text)
    try:
        _check_creatable(p)
    except OSError as exc:
        raise UserError(f"output path {_short(p)}: {exc.strerror}") from None
    return p


def _short(p: Path) -> str:
    text = str(p)
    return text if len(text) <= 80 else text[:77] + "..."


def _check_creatable(p: Path) -> None:
    if p.exists() and not p.is_dir():
        raise UserError(f"output path {p} exists and is not a directory")
    ancestor = p
    while not ancestor.exists():
        if ancestor.parent == ancestor:
            break
        ancestor = ancestor.parent
    if ancestor.exists() and not ancestor.is_dir():
        raise UserError(f"output path {p}: {ancestor} is a file, not a directory")
    if ancestor == p:
        if not os.access(p, os.W_OK | os.X_OK):
            raise UserError(f"output directory {p} is not writable")
        return
    first = p  # access() trusts the permission bits; /proc or a read-only mount refuse mkdir
    while first.parent != ancestor:
        first = first.parent
    try:  # a uniquely named probe: MPI ranks check the same path at the same moment
        os.rmdir(tempfile.mkdtemp(prefix=f".{first.name}.probe-", dir=ancestor))
    except OSError as exc:
        raise UserError(f"output path {_short(p)}: cannot create {_short(first)} ({exc.strerror})") from None


class RunDirectory:
    """Paths and writers of one run directory.

    Parameters
    ----------
    path
        Directory of the run. Nothing is created until :meth:`create` is called.
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self._lock: RunLock | None = None
        self.stale_removed: list[Path] = []  # temporary files of a dead writer, removed by lock()

    # ----------------------------------------------------------------- layout
    @property
    def config_file(self) -> Path:
        return self.path / "config.toml"

    @property
    def log_file(self) -> Path:
        return self.path / "log.txt"

    @property
    def history_file(self) -> Path:
        return self.path / "history.h5"

    @property
    def crash_file(self) -> Path:
        return self.path / "crash.h5"

    def snapshot_file(self, index: int) -> Path:
        return self.path / "snapshots" / f"snap_{index:05d}.h5"

    def checkpoint_file(self, index: int) -> Path:
        return self.path / "checkpoints" / f"chk_{index:05d}.h5"

    def snapshots(self) -> list[Path]:
        """Snapshot files in index order."""
        d = self.path / "snapshots"
        files = [p for p in d.glob("snap_*.h5") if _SNAP.search(p.name)] if d.is_dir() else []
        return sorted(files, key=lambda p: int(_SNAP.search(p.name).group(1)))

    def require_snapshots(self, purpose: str = "") -> list[Path]:
        """:meth:`snapshots`, or a one-line :class:`~dustygas.errors.UserError` if the directory
        does not exist or holds no snapshot (``purpose`` ends that message, e.g. ``" to export"``)."""
        if not self.path.is_dir():
            raise UserError(f"{self.path}: no such run directory")
        files = self.snapshots()
        if not files:
            raise UserError(f"{self.path}: no snapshots{purpose}")
        return files

    def snapshot_at(self, index: int) -> Path:
        """Snapshot ``index`` (position in :meth:`snapshots`, negative from the end), or a one-line
        :class:`~dustygas.errors.UserError` naming the positions the run has."""
        files = self.require_snapshots()
        index, n = int(index), len(files)
        if not -n <= index < n:
            raise UserError(f"--snapshot {index}: the run has {n} snapshots (0 .. {n - 1}; negative from the end)")
        return files[index]

    def checkpoints(self) -> list[Path]:
        """Checkpoint entries in index order (damaged ones included: see :mod:`dustygas.io.checkpoint`)."""
        d = self.path / "checkpoints"
        files = [p for p in d.glob("chk_*.h5") if _CHK.search(p.name)] if d.is_dir() else []
        return sorted(files, key=lambda p: int(_CHK.search(p.name).group(1)))

    # ----------------------------------------------------------------- locking
    def lock(self) -> RunLock:
        """Take the directory's lock (it must exist); one line naming the holder if it is taken.

        Temporary files left by a dead writer are removed once the lock is held.
        """
        if self._lock is None or not self._lock.held:
            self._lock = RunLock(self.path).acquire()
            self.stale_removed = remove_stale_temporaries(self.path, self.path / "snapshots", self.path / "checkpoints")
        return self._lock

    def unlock(self, discard: bool = False) -> None:
        """Release the lock; ``discard``: also remove the lock file if taking the lock created it."""
        if self._lock is not None:
            self._lock.release(discard)

    # ----------------------------------------------------------------- creation
    def check_new(self, overwrite: bool = False) -> None:
        """Refuse (one line) to start a fresh run in a non-empty directory."""
        check_output_path(self.path)
        if self.path.is_dir() and not overwrite and any(p.name != LOCK_NAME for p in self.path.iterdir()):
            raise UserError(
                f"output directory {self.path} already holds a run: continue it with --restart {self.path}, "
                "replace it with --overwrite, or choose another with -o DIR"
            )

    def create(self, overwrite: bool = False) -> None:
        """Create the directory, take its lock, then the tree (clearing old outputs if ``overwrite``)."""
        self.check_new(overwrite)
        try:
            self.path.mkdir(parents=True, exist_ok=True)
        except OSError as exc:
            raise UserError(f"cannot create output directory {self.path}: {exc.strerror}") from None
        self.lock()
        self.check_new(overwrite)  # again under the lock: another run may have started meanwhile
        try:
            if overwrite:
                for sub in ("snapshots", "checkpoints"):
                    for f in (self.path / sub).glob("*.h5"):
                        f.unlink()
                for f in (self.config_file, self.log_file, self.history_file, self.crash_file):
                    f.unlink(missing_ok=True)
            (self.path / "snapshots").mkdir(exist_ok=True)
            (self.path / "checkpoints").mkdir(exist_ok=True)
        except OSError as exc:
            self.unlock()
            raise UserError(f"cannot prepare output directory {self.path}: {exc.strerror}") from None

    # ----------------------------------------------------------------- writers
    def write_config(self, text: str) -> None:
        atomic_write_text(self.config_file, text)

    def log(self, message: str) -> None:
        stamp = time.strftime("%Y-%m-%d %H:%M:%S")
        try:
            with open(self.log_file, "a", encoding="utf-8") as fh:
                fh.write(f"{stamp} {message}\n")
        except OSError as exc:
            raise output_error(self.log_file, exc) from None

    def write_snapshot(self, index: int, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
        path = self.snapshot_file(index)
        write_h5(path, arrays, attrs, annotate=annotate_snapshot)
        return path

    def write_history(self, columns: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> None:
        write_h5(self.history_file, columns, attrs, annotate=annotate_history)

    def write_checkpoint(
        self, index: int, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], keep: int = 2
    ) -> Path:
        """Write checkpoint ``index`` with a checksum, then delete all but the newest ``keep``."""
        path = self.checkpoint_file(index)
        write_h5(path, arrays, attrs, checksum=True)
        for old in self.checkpoints()[:-keep] if keep > 0 else []:
            try:
                old.unlink()
            except IsADirectoryError:
                pass
            except OSError as exc:
                raise OutputError(f"cannot remove old checkpoint {old}: {exc.strerror}") from None
        return path

    def write_crash(self, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
        write_h5(self.crash_file, arrays, attrs)
        return self.crash_file

    # ----------------------------------------------------------------- readers
    def read_snapshot(self, index: int = -1) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """Read snapshot ``index`` (position in the sorted list; -1 = last)."""
        return read_h5(self.snapshot_at(index))

    def read_history(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        if not self.history_file.exists():
            raise UserError(f"{self.path}: no history.h5")
        return read_h5(self.history_file)
