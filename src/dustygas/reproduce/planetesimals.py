"""``planetesimal-mass-function``: the cumulative mass function of the bound clumps (thesis §4.5).

The clumps of the last snapshot of a self-gravitating particle run
(:func:`dustygas.analysis.planetesimals.run_clumps`: Hill-density seeds, Hill spheres, the bound
particles in the rotating frame) and their cumulative number ``N(>M)``, with the
maximum-likelihood power law ``dN/dM ∝ M^{-p}`` (Simon et al. 2016: p ≈ 1.6) and exponentially
truncated power law (Abod et al. 2019) of :mod:`dustygas.analysis.mass_function`, bootstrap
errors and the BIC's choice.

Where the run comes from: ``--from RUN`` (e.g. a finished ``si3d-selfgravity``); otherwise the
figure runs its own in ``DIR/runs/``. ``--full``: the ``si3d-selfgravity`` preset itself
(32 × 32 × 48, gravity on at 5 orbits, to 8: about an hour of one core). The quick default (minutes: 947
steps to t = 3 took 594 s on the loaded 2-core machine; it stops at t = 2): the same box at
16 × 16 × 24 with the gravity on from the start and strong, ``G̃ = 10`` (Hill density
0.9 ρ_g0, below the initial midplane dust density Z/H_p = 1.5): the settled layer is
gravitationally unstable and fragments within a fraction of an orbit (two bound clumps holding
90 % of the dust at t = 3) -- a demonstration of the
pipeline, not the streaming-instability-seeded mass function of Simon et al.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from . import figure

__all__ = ["planetesimal_mass_function", "QUICK", "selfgravity_run"]

#: the quick default's overrides of ``si3d-selfgravity``
QUICK = ("grid.nx=16", "grid.ny=16", "grid.nz=24", "gravity.t_on=0", "gravity.g_tilde=10", "run.tlim=2",
         "run.dt_snapshot=1")


def selfgravity_run(output: Path, run: Path | None = None, quick: bool = True) -> Path:
    """``run`` if given, else ``si3d-selfgravity`` in ``output/runs/`` (quick: :data:`QUICK`), run
    or continued from its checkpoint if not finished."""
    from .si3d_figures import cached_run

    return cached_run("si3d-selfgravity", output, run, quick, QUICK)


@figure("planetesimal-mass-function",
        "Cumulative mass function N(>M) of the bound clumps, power-law and truncated fits (self-gravitating run)",
        cost="5 min (--full: hours)",
        caption="Cumulative number N(>M) of the gravitationally bound clumps (planetesimals) in the last "
                "snapshot of a self-gravitating particle run, with the maximum-likelihood power law "
                "dN/dM ~ M^-p and exponentially truncated power law (bootstrap errors; the BIC chooses).")
def planetesimal_mass_function(output: Path, quick: bool = True, run: Path | None = None) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..analysis.mass_function import cumulative_number, fit_mass_function
    from ..analysis.planetesimals import run_clumps
    from ..io.atomic import atomic_path, atomic_write_text

    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    path = selfgravity_run(output, run, quick)
    (result,) = run_clumps(path, "last")
    cat = result.catalogue
    m, n = cumulative_number(cat.mass)
    fits = fit_mass_function(cat.mass, bootstrap=200) if len(cat) >= 3 else None
    csv = output / "planetesimal_mass_function.csv"
    rows = ["# clumps of " + str(result.snapshot) + f" (t = {result.time:.6g}); mass in code units (rho_g0 H^3)",
            "mass,N_ge,particle_count,hill_radius,radius"]
    order = np.argsort(cat.mass)[::-1]
    rows += [f"{cat.mass[i]:.10g},{k + 1},{int(cat.particle_count[i])},{cat.hill_radius[i]:.6g},{cat.radius[i]:.6g}"
             for k, i in enumerate(order)]
    atomic_write_text(csv, "\n".join(rows) + "\n")
    summary = {"run": str(path), "snapshot": str(result.snapshot), "time": result.time, "clumps": len(cat),
               "mass_in_clumps": float(cat.mass.sum()), "catalogue": str(result.catalogue_file)}
    if fits:
        summary["fits"] = {k: {kk: v for kk, v in fits[k].to_dict().items() if kk != "model"}
                           for k in ("power-law", "truncated-power-law")}
        summary["preferred"] = fits["preferred"]
    js = output / "planetesimal_mass_function.json"
    atomic_write_text(js, json.dumps(summary, indent=1) + "\n")
    fig, ax = plt.subplots(figsize=(5.5, 4.2))
    if len(cat):
        ax.step(m[::-1], n[::-1], where="pre", color="k", marker="o", ms=3,
                label=f"{len(cat)} bound clumps, t = {result.time:.3g}")
    if fits:
        grid = np.geomspace(m.min(), m.max(), 100)
        pl, tr = fits["power-law"], fits["truncated-power-law"]
        ax.plot(grid, pl.cumulative(grid), "C0--", label=f"power law p = {pl.params['p']:.2f} ± {pl.errors['p']:.2f}")
        ax.plot(grid, tr.cumulative(grid), "C3:", label=f"truncated p = {tr.params['p']:.2f}, "
                f"M_e = {tr.params['M_e']:.2g}")
        ax.set_title(f"{path.name}: preferred (BIC) {fits['preferred']}", fontsize=9)
    else:
        ax.set_title(f"{path.name}: {len(cat)} clumps (no fit below 3)", fontsize=9)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(r"clump mass $M$ [$\rho_{g0} H^3$]")
    ax.set_ylabel(r"$N(>M)$")
    ax.legend(fontsize=8)
    fig.tight_layout()
    png = output / "planetesimal_mass_function.png"
    with atomic_path(png) as tmp:
        with open(tmp, "wb") as fh:
            fig.savefig(fh, format="png", dpi=120)
    plt.close(fig)
    return [png, csv, js]
