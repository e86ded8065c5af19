"""Thesis Figure 3.2: vertical profiles of the dust fraction in the settling test, upwind vs arithmetic.

The ``dust-settle`` problem (1D Gaussian column, :math:`\\epsilon = 0.099`, :math:`\\tau_s = 0.01` at the
midplane, terminal-velocity one-fluid dust, no dust-fraction time-step limit as in the thesis's
runs) is run three times through the run loop: with the upwind exchange (thesis eq. 3.17), and with the arithmetic
exchange (eq. 3.4) with and without the floor/ceiling clamp of §3.2.4 (floor 0, ceiling 1).
:func:`settling_runs` is shared with Figure 3.3 (one set of runs per process and scale).
"""

from __future__ import annotations

import contextlib
import functools
import io
import math
import tempfile
from pathlib import Path

import numpy as np

from ..io import read_h5
from . import figure

__all__ = ["SCHEMES", "settling_runs", "fig3_2"]

#: label -> ``dust-settle`` overrides
SCHEMES = {
    "upwind": ("dust.exchange=upwind", "dust.clamp=true"),
    "arithmetic_clamped": ("dust.exchange=arithmetic", "dust.clamp=true"),
    "arithmetic": ("dust.exchange=arithmetic",),
}
ORBIT = 2.0 * math.pi


@functools.lru_cache(maxsize=2)
def settling_runs(quick: bool = True) -> dict:
    """Run the settling test with every scheme through the run loop (:func:`dustygas.api.run`, in a
    temporary directory); profiles from the snapshots at 0, 1/2, 1, 2 (and 4) orbits, the dust mass
    and clamp counts from the history, every 0.05/Omega. One numba thread (``run.threads = 1``): for
    a few hundred particles the cost of waking a second thread for every kernel exceeds the work."""
    import numba

    threads = numba.get_num_threads()
    try:
        with tempfile.TemporaryDirectory() as tmp:
            return _settling_runs(quick, Path(tmp))
    finally:
        numba.set_num_threads(threads)


def _settling_runs(quick: bool, workdir: Path) -> dict:
    from .. import api
    from ..io.rundir import RunDirectory

    particles, orbits = (400, 2.0) if quick else (1600, 4.0)
    profile_orbits = [0.0, 0.5, 1.0, 2.0] + ([] if quick else [4.0])
    out = {"particles": particles, "profile_orbits": profile_orbits, "schemes": {}}
    for label, overrides in SCHEMES.items():
        with contextlib.redirect_stderr(io.StringIO()):  # the clamp events go to the run's log.txt only
            res = api.run("dust-settle", output=workdir / label,
                          set=[f"problem.particles={particles}", *overrides, f"run.tlim={orbits * ORBIT!r}",
                               f"run.dt_snapshot={0.5 * ORBIT!r}", "run.dt_history=0.05", "run.checkpoint_wall=0",
                               "run.threads=1"])
        run = RunDirectory(res.path)
        hist, _ = run.read_history()
        profiles = []
        for snap in run.snapshots():
            arrays, attrs = read_h5(snap)
            if any(abs(attrs["time"] / ORBIT - o) < 0.01 for o in profile_orbits):
                z = arrays["pos"][:, 0]
                order = np.argsort(z)
                profiles.append((z[order], arrays["extra/dust_fraction"][order]))
        m0 = hist["dust_mass"][0]
        clamped = "clamp_events" in hist
        out["schemes"][label] = {
            "time": hist["time"], "mass": hist["dust_mass"] / m0, "eps_min": hist["min_dust_fraction"],
            "clamps": hist["clamp_events"] if clamped else np.zeros_like(hist["time"]), "profiles": profiles,
            "created": float(hist["clamp_mass_created"][-1]) if clamped else 0.0,
            "destroyed": float(hist["clamp_mass_destroyed"][-1]) if clamped else 0.0,
            "m0": m0, "final_mass": hist["dust_mass"][-1] / m0}
    return out


@figure("fig3.2", "Settling test: dust fraction eps(z) at several times, upwind (eq. 3.17) vs arithmetic (eq. 3.4)",
        cost="10 s")
def fig3_2(output: Path, quick: bool = True) -> list[Path]:
    from ..plot import Column, house_style, new_figure, save_figure

    runs = settling_runs(quick)
    times = runs["profile_orbits"]
    cols = []
    with house_style():
        fig, axes = new_figure(len(times), 2, width=7.0, height=1.9 * len(times), sharex=True, sharey=True)
        for row, t_orb in enumerate(times):
            for col, (label, title) in enumerate([("upwind", "upwind (eq. 3.17)"),
                                                  ("arithmetic_clamped", "arithmetic (eq. 3.4)")]):
                ax = axes[row, col]
                z, eps = runs["schemes"][label]["profiles"][row]
                ax.plot(z, eps, color="C0" if col == 0 else "C3", lw=1.3,
                        label="clamped to [0, 1]" if col == 1 else None)
                cols += [Column(f"z_{label}_{row}", z, "H", f"height of each particle at {t_orb:g} orbits ({label})"),
                         Column(f"eps_{label}_{row}", eps, "", f"dust fraction at {t_orb:g} orbits ({label})")]
                if col == 1:
                    z2, eps2 = runs["schemes"]["arithmetic"]["profiles"][row]
                    ax.plot(z2, eps2, color="0.45", lw=0.9, ls="--", label="no clamp")
                    cols += [Column(f"z_arithmetic_{row}", z2, "H", f"height at {t_orb:g} orbits (arithmetic, no clamp)"),
                             Column(f"eps_arithmetic_{row}", eps2, "", f"dust fraction at {t_orb:g} orbits "
                                    "(arithmetic, no clamp)")]
                ax.axhline(0.0, color="k", lw=0.5)
                ax.text(0.03, 0.85, f"{t_orb:g} orbit{'' if t_orb == 1 else 's'}", transform=ax.transAxes, fontsize=8)
                if row == 0:
                    ax.set_title(title)
                if row == len(times) - 1:
                    ax.set_xlabel(r"$z/H$")
                if col == 0:
                    ax.set_ylabel(r"$\epsilon$")
        axes[0, 1].legend(loc="upper right", fontsize=7)
        return save_figure(fig, output / "fig3_2.png", cols,
                           title="thesis Figure 3.2: dust fraction in the settling test",
                           description=f"dust-settle, {runs['particles']} particles, tau_s = 0.01 at the midplane, "
                                       "terminal-velocity one-fluid dust, no eps time-step limit")
