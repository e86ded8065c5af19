"""Reading checkpoints back: the newest one that is intact, with a warning for each skipped.

A checkpoint (written by :meth:`RunDirectory.write_checkpoint`) carries a SHA-256 over all its
values (:mod:`dustygas.io.hdf5`), the problem name, the dustygas version and the full
configuration. :func:`newest_checkpoint` walks the run's checkpoints from the newest and takes
the first that is a readable HDF5 file, whose checksum matches and that belongs to the run's
problem; every one it passes over (truncated by a full disk, a flipped bit, an empty file, a
directory, another run's file copied in) is named in a warning. ``keep_checkpoints >= 2``
therefore makes a damaged newest checkpoint cost only the steps since the one before.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from ..errors import UserError
from .hdf5 import ChecksumError, read_h5
from .rundir import RunDirectory

__all__ = ["Checkpoint", "CheckpointDamaged", "read_checkpoint", "newest_checkpoint"]


class CheckpointDamaged(Exception):
    """A checkpoint that cannot be used; the message says why (one line)."""


@dataclass
class Checkpoint:
    """A verified checkpoint: its file, datasets and root attributes, and the warnings of the search."""

    path: Path
    arrays: dict[str, np.ndarray]
    attrs: dict[str, Any]
    skipped: list[str] = field(default_factory=list)


def read_checkpoint(path: str | Path, problem: str | None = None, required: Iterable[str] = ()) -> Checkpoint:
    """Read and verify one checkpoint; :class:`CheckpointDamaged` says what is wrong with it."""
    path = Path(path)
    if not path.is_file():
        raise CheckpointDamaged("not a file")
    try:
        arrays, attrs = read_h5(path, verify=True)
    except ChecksumError as exc:
        raise CheckpointDamaged(str(exc)) from None
    except (OSError, RuntimeError, ValueError, KeyError, TypeError, UnicodeDecodeError) as exc:
        detail = (str(exc).splitlines() or [type(exc).__name__])[0]
        raise CheckpointDamaged(f"unreadable ({detail[:120]})") from None
    missing = [key for key in ("problem", "dustygas_version", *required) if key not in attrs]
    if missing:
        raise CheckpointDamaged(f"not a dustygas checkpoint (no {', '.join(missing)})")
    if problem is not None and attrs["problem"] != problem:
        raise CheckpointDamaged(f"a checkpoint of problem '{attrs['problem']}', not '{problem}'")
    return Checkpoint(path, arrays, attrs)


def newest_checkpoint(rundir: RunDirectory, problem: str | None = None, required: Iterable[str] = ()) -> Checkpoint:
    """The newest intact checkpoint of ``rundir``; one-line :class:`UserError` if there is none."""
    required = tuple(required)
    skipped: list[str] = []
    for path in reversed(rundir.checkpoints()):
        try:
            found = read_checkpoint(path, problem, required)
        except CheckpointDamaged as exc:
            skipped.append(f"{path.name}: {exc}")
            continue
        found.skipped = skipped
        return found
    if skipped:
        raise UserError(f"{rundir.path}: no usable checkpoint ({'; '.join(skipped)})")
    raise UserError(f"{rundir.path}: no checkpoint to restart from")
