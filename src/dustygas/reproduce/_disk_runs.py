"""The disk runs behind thesis Figures 3.6-3.16, shared by their figure functions.

Two runs: ``drift-ring`` (the thesis's disk with dust rings at 20 au, :math:`\\tau_s` = 1 and 10, and at
52 au, :math:`\\tau_s = 1`) and ``drift-ring-split`` (the disk split eight-fold in 40-70 au around a
:math:`\\tau_s = 1` ring at 52 au). By default (``quick``) the reduced presets run, through the run loop,
into ``OUTPUT/runs/<preset>`` (a finished run there is reused); ``--full`` runs the ``*-thesis``
presets (10^5 gas particles); ``--from RUN`` uses existing run directories instead, recognised by
their configuration (split or not, ring radii and Stokes numbers). A run stopped before its end
(SIGTERM, Ctrl-C) is continued from its newest checkpoint by the next figure that needs it, not
started again.
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import UserError
from ._runs import finished_run

__all__ = ["disk_run", "ring_index", "padded", "ORBIT_20"]

ORBIT_20 = 2.0 * np.pi * 20.0**1.5
_PRESETS = {False: "drift-ring", True: "drift-ring-split"}


def disk_run(split: bool, output: Path, quick: bool, runs: Sequence[str | Path] | None = None) -> Path:
    """A finished run directory of ``drift-ring`` (``split=False``) or ``drift-ring-split`` (module docstring)."""
    from ..analysis.disk import disk_config

    if runs:
        for run in runs:
            cfg = disk_config(run)
            if bool(cfg["split"]["enabled"]) == split and cfg["dust"].get("enabled"):
                return Path(run)
        kind = "a split disk (split.enabled = true)" if split else "an unsplit disk with dust rings"
        raise UserError(f"--from: none of {', '.join(map(str, runs))} is a run of {kind}")
    name = _PRESETS[split] + ("" if quick else "-thesis")
    return finished_run(name, Path(output) / "runs" / name)


def ring_index(run: str | Path, radius: float, taus: float) -> int:
    """Index of the run's ring at ``radius`` with Stokes number ``taus`` (a one-line error if none)."""
    from ..analysis.disk import disk_config

    dust = disk_config(run)["dust"]
    for k, (R, t) in enumerate(zip(dust.get("ring_radii", []), dust.get("ring_taus", []))):
        if abs(R - radius) < 1e-9 and abs(t - taus) < 1e-9 and dust.get("enabled"):
            return k
    raise UserError(f"{run}: has no dust ring at {radius:g} au with tau_s = {taus:g}")


def padded(columns: list) -> list:
    """The ``Column``s padded with NaN to a common length (series of different lengths in one CSV)."""
    from ..plot import Column

    n = max(np.asarray(c.values).size for c in columns)
    out = []
    for c in columns:
        v = np.full(n, np.nan)
        a = np.asarray(c.values, dtype=np.float64).ravel()
        v[: a.size] = a
        out.append(Column(c.name, v, c.unit, c.description + (" (NaN-padded)" if a.size < n else "")))
    return out
