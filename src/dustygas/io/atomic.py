"""Atomic file writes: write to a temporary name in the same directory, then rename.

A reader (or a restart after ``kill -9``) therefore sees either the old file or the complete
new one, never a half-written file. A write that fails (disk full, quota, permissions) removes
its temporary file and raises :class:`~dustygas.errors.OutputError` with one line naming the
file and the reason. Temporary names are ``.NAME.tmpPID``; :func:`remove_stale_temporaries`
clears those a killed writer left behind.
"""

from __future__ import annotations

import contextlib
import os
import re
from pathlib import Path
from typing import Iterator

from ..errors import OutputError

__all__ = ["atomic_path", "atomic_write_text", "output_error", "remove_stale_temporaries"]

_TEMPORARY = re.compile(r"^\..+\.tmp\d+$")


def output_error(path: str | Path, exc: BaseException) -> OutputError:
    """The one-line :class:`OutputError` for a failed write of ``path``."""
    errno = getattr(exc, "errno", None)
    reason = os.strerror(errno) if errno else (str(exc).splitlines() or [type(exc).__name__])[0]
    return OutputError(f"cannot write {path}: {reason}")


@contextlib.contextmanager
def atomic_path(path: str | Path) -> Iterator[Path]:
    """Yield a temporary path next to ``path``; on success fsync it and rename onto ``path``.

    On an exception the temporary file is removed and ``path`` is left untouched; an
    :class:`OSError` becomes an :class:`~dustygas.errors.OutputError`.
    """
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        yield tmp
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            tmp.unlink()
        if isinstance(exc, OSError):
            raise output_error(path, exc) from None
        raise


def atomic_write_text(path: str | Path, text: str) -> None:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")


def remove_stale_temporaries(*directories: str | Path) -> list[Path]:
    """Delete the ``.NAME.tmpPID`` files in ``directories`` (call only while holding the run's lock)."""
    removed = []
    for d in directories:
        try:
            entries = list(Path(d).iterdir())
        except OSError:
            continue
        for f in entries:
            if _TEMPORARY.match(f.name) and f.is_file():
                with contextlib.suppress(OSError):
                    f.unlink()
                    removed.append(f)
    return removed
