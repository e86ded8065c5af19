"""One writer per run directory: an advisory ``flock`` on ``RUN/.lock``.

A process that writes a run directory (a fresh run, ``--overwrite``, ``--restart``) holds an
exclusive :func:`fcntl.flock` on ``RUN/.lock`` for as long as it writes, and records its PID,
host and start time in the file. A second writer is refused with one line naming the holder.
The kernel releases the lock when its holder exits, however it exits (``kill -9`` included), so
a lock left by a dead process is simply taken over: the file still names the dead holder, which
the new holder reports in the log, and the dead writer's temporary files are removed.
On file systems without ``flock`` (and on Windows) the directory is not locked.
"""

from __future__ import annotations

import contextlib
import os
import socket
import time
from pathlib import Path

from ..errors import UserError

try:
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None

__all__ = ["RunLock", "LOCK_NAME"]

LOCK_NAME = ".lock"


class RunLock:
    """Exclusive lock of the run directory ``path`` (which must exist); a context manager.

    Attributes
    ----------
    previous
        What the lock file said before it was taken: empty if the last writer released it,
        ``"PID host time"`` of a writer that died holding it.
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self.file = self.path / LOCK_NAME
        self.previous = ""
        self.created = False
        self._fh = None

    def acquire(self) -> "RunLock":
        self.created = not self.file.exists()
        try:
            fh = open(self.file, "a+", encoding="utf-8")
        except OSError as exc:
            raise UserError(f"cannot lock run directory {self.path}: {exc.strerror}") from None
        if fcntl is not None:
            try:
                fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                holder = _read(fh)
                fh.close()
                raise UserError(f"run directory {self.path} is being written by {_describe(holder)}: "
                                "wait for it to finish, or stop it first") from None
            except OSError:  # no flock on this file system: go on unlocked
                pass
        self.previous = _read(fh)
        fh.seek(0)
        fh.truncate()
        fh.write(f"{os.getpid()} {socket.gethostname()} {time.strftime('%Y-%m-%dT%H:%M:%S')}\n")
        fh.flush()
        self._fh = fh
        return self

    def release(self, discard: bool = False) -> None:
        """Release the lock (``discard``: and remove the lock file if :meth:`acquire` created it)."""
        if self._fh is not None:
            if discard and self.created:
                with contextlib.suppress(OSError):
                    self.file.unlink()
            with contextlib.suppress(OSError):
                self._fh.seek(0)
                self._fh.truncate()  # an empty lock file: the last writer finished
            with contextlib.suppress(OSError):
                self._fh.close()  # closing the descriptor releases the flock
            self._fh = None

    def __enter__(self) -> "RunLock":
        return self.acquire() if self._fh is None else self

    def __exit__(self, *exc) -> None:
        self.release()

    @property
    def held(self) -> bool:
        return self._fh is not None


def _read(fh) -> str:
    with contextlib.suppress(OSError, UnicodeDecodeError):
        fh.seek(0)
        return fh.read(200).strip()
    return ""


def _describe(holder: str) -> str:
    parts = holder.split()
    if len(parts) >= 3 and parts[0].isdigit():
        return f"process {parts[0]} on {parts[1]} (since {parts[2]}; kill {parts[0]} stops it with a checkpoint)"
    return "another process"
