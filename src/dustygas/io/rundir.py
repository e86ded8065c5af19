"""The run directory: the unit of output of every simulation.

Layout::

    RUN/
      config.toml            fully merged parameters, with the problem name and dustygas version
      log.txt                human-readable log (append-only, one line per event)
      history.h5             time series of scalar diagnostics (rewritten atomically)
      snapshots/snap_NNNNN.h5
      checkpoints/chk_NNNNN.h5   full restart state (the newest ``keep`` are kept)
      crash.h5               state dump written when a run stops on an invalid state

Every file except the append-only log is written to a temporary name and renamed.
"""

from __future__ import annotations

import re
import time
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from ..errors import UserError
from .atomic import atomic_write_text
from .hdf5 import read_h5, write_h5
from .schema import annotate_history, annotate_snapshot

__all__ = ["RunDirectory", "default_run_path"]

_SNAP = re.compile(r"snap_(\d{5,})\.h5$")
_CHK = re.compile(r"chk_(\d{5,})\.h5$")


def default_run_path(problem: str, base: str | Path = "runs") -> Path:
    """``runs/<problem>``, or ``runs/<problem>.1``, ``.2``, ... if that already exists."""
    base = Path(base)
    path = base / problem
    n = 0
    while path.exists():
        n += 1
        path = base / f"{problem}.{n}"
    return path


class RunDirectory:
    """Paths and writers of one run directory.

    Parameters
    ----------
    path
        Directory of the run. Nothing is created until :meth:`create` is called.
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)

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

    def checkpoints(self) -> list[Path]:
        """Checkpoint files in index order."""
        d = self.path / "checkpoints"
        files = [p for p in d.glob("chk_*.h5") if _CHK.search(p.name)] if d.is_dir() else []
        return sorted(files, key=lambda p: int(_CHK.search(p.name).group(1)))

    # ----------------------------------------------------------------- creation
    def check_new(self, overwrite: bool = False) -> None:
        """Refuse (one line) to start a fresh run in a non-empty directory."""
        if self.path.exists() and not self.path.is_dir():
            raise UserError(f"output path {self.path} exists and is not a directory")
        if self.path.is_dir() and any(self.path.iterdir()) and not overwrite:
            raise UserError(
                f"output directory {self.path} is not empty: use --overwrite, "
                f"or continue it with --restart {self.path}"
            )

    def create(self, overwrite: bool = False) -> None:
        """Create the directory tree (clearing old outputs if ``overwrite``)."""
        self.check_new(overwrite)
        if overwrite and self.path.is_dir():
            for sub in ("snapshots", "checkpoints"):
                for f in (self.path / sub).glob("*.h5"):
                    f.unlink()
            for f in (self.config_file, self.log_file, self.history_file, self.crash_file):
                if f.exists():
                    f.unlink()
        (self.path / "snapshots").mkdir(parents=True, exist_ok=True)
        (self.path / "checkpoints").mkdir(parents=True, exist_ok=True)

    # ----------------------------------------------------------------- writers
    def write_config(self, text: str) -> None:
        atomic_write_text(self.config_file, text)

    def log(self, message: str) -> None:
        stamp = time.strftime("%Y-%m-%d %H:%M:%S")
        with open(self.log_file, "a", encoding="utf-8") as fh:
            fh.write(f"{stamp} {message}\n")

    def write_snapshot(self, index: int, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
        path = self.snapshot_file(index)
        write_h5(path, arrays, attrs, annotate=annotate_snapshot)
        return path

    def write_history(self, columns: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> None:
        write_h5(self.history_file, columns, attrs, annotate=annotate_history)

    def write_checkpoint(
        self, index: int, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], keep: int = 2
    ) -> Path:
        path = self.checkpoint_file(index)
        write_h5(path, arrays, attrs)
        for old in self.checkpoints()[:-keep] if keep > 0 else []:
            old.unlink()
        return path

    def write_crash(self, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
        write_h5(self.crash_file, arrays, attrs)
        return self.crash_file

    # ----------------------------------------------------------------- readers
    def read_snapshot(self, index: int = -1) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """Read snapshot ``index`` (position in the sorted list; -1 = last)."""
        files = self.snapshots()
        if not files:
            raise UserError(f"{self.path}: no snapshots")
        return read_h5(files[index])

    def read_history(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        if not self.history_file.exists():
            raise UserError(f"{self.path}: no history.h5")
        return read_h5(self.history_file)
