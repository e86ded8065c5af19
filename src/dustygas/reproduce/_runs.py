"""The simulations behind the figures: run once into ``OUTPUT/runs/<name>``, reused after.

A figure that needs a run asks :func:`finished_run` for it: a finished run there (its history
reaches the configured ``run.tlim``) is reused as it is; a run of the same problem stopped before
its end (SIGTERM, Ctrl-C, wall time) is continued from its newest checkpoint; anything else is
run from the start through the run loop. So the figures of one run share it, and an interrupted
``dustygas reproduce`` picks up where it stopped instead of starting again.
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterable

from ..errors import UserError

__all__ = ["finished_run", "is_finished"]


def is_finished(path: str | Path) -> bool:
    """Whether the run directory ``path`` holds a run that reached its ``run.tlim``: its newest
    checkpoint (every run ends with one) or its history is at ``run.tlim``. The history alone
    can end a little before: its rows come at the ``run.dt_history`` cadence."""
    import h5py

    from ..config import load_toml
    from ..io.hdf5 import read_h5
    from ..io.rundir import RunDirectory

    rd = RunDirectory(path)
    if not rd.config_file.exists():
        return False
    tlim = float(load_toml(rd.config_file)["run"]["tlim"]) * (1 - 1e-12)
    for chk in reversed(rd.checkpoints()):
        try:
            with h5py.File(chk, "r") as f:
                return float(f.attrs["time"]) >= tlim
        except (OSError, KeyError, ValueError):
            continue  # damaged: the one before (restart falls back the same way)
    if not rd.history_file.exists():
        return False
    t = read_h5(rd.history_file)[0]["time"]
    return t.size > 0 and float(t[-1]) >= tlim


def finished_run(problem: str, path: str | Path, overrides: Iterable[str] = (), progress: bool | None = False) -> Path:
    """The finished run of ``problem`` (with the ``section.key=value`` ``overrides``) in ``path``.

    Reused if :func:`is_finished`; continued from its newest checkpoint if ``path`` holds a
    stopped run of ``problem``; else run from the start (``path`` overwritten). ``progress`` as
    in :func:`dustygas.api.run`. A run that stops before its end again raises a one-line
    :class:`~dustygas.errors.UserError` (the directory is kept for the next call to continue).
    """
    from ..api import restart, run
    from ..config import load_toml
    from ..io.rundir import RunDirectory

    path = Path(path)
    if is_finished(path):
        return path
    rd = RunDirectory(path)
    resumable = rd.config_file.exists() and load_toml(rd.config_file).get("dustygas", {}).get("problem") == problem \
        and bool(rd.checkpoints())
    if resumable:
        result = restart(path, progress=progress)
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        result = run(problem, path, overwrite=True, set=tuple(overrides), progress=progress)
    if result.status != "finished":  # stopped (signal, wall time): keep it for the next call to resume
        raise UserError(f"{path}: the {problem} run stopped ({result.status}) at time {result.engine.t:.6g}; "
                        "run the figure again to continue it from its checkpoint")
    return path
