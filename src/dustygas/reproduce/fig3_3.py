"""Thesis Figure 3.3: total dust mass in the settling test, upwind vs arithmetic (with and without clamp).

Same runs as Figure 3.2 (:func:`~dustygas.reproduce.fig3_2.settling_runs`). The upwind exchange keeps
the dust mass to round-off without a single clamping event; the arithmetic exchange keeps it too,
but with negative dust fractions at the top of the column, and clamping those to zero (thesis
§3.2.4) creates dust: the mass grows by the reported ``clamp_mass_created``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from .fig3_2 import ORBIT, settling_runs

__all__ = ["fig3_3"]


@figure("fig3.3", "Settling test: total dust mass vs time, upwind vs arithmetic with and without the clamp",
        cost="10 s")
def fig3_3(output: Path, quick: bool = True) -> list[Path]:
    from ..plot import Column, house_style, new_figure, save_figure

    runs = settling_runs(quick)
    s = runs["schemes"]
    t = s["upwind"]["time"]
    styles = {"upwind": ("C0", "-", "upwind (eq. 3.17), clamp on: no events"),
              "arithmetic_clamped": ("C3", "-", "arithmetic (eq. 3.4) with clamp"),
              "arithmetic": ("0.45", "--", "arithmetic, no clamp")}
    with house_style():
        fig, (ax, ax2) = new_figure(1, 2, width=9.0, height=3.4)
        for label, (color, ls, text) in styles.items():
            ax.plot(s[label]["time"] / ORBIT, s[label]["mass"], color=color, ls=ls, label=text)
            ax2.plot(s[label]["time"] / ORBIT, s[label]["eps_min"], color=color, ls=ls, label=text)
        ax.set_xlabel("time [orbits]")
        ax.set_ylabel(r"$M_d(t)/M_d(0)$")
        ax.legend(fontsize=7, loc="upper left")
        ax.set_title("total dust mass", fontsize=10)
        ax2.axhline(0.0, color="k", lw=0.5)
        ax2.set_xlabel("time [orbits]")
        ax2.set_ylabel(r"$\min\,\epsilon$")
        ax2.set_title("smallest dust fraction", fontsize=10)
        n = min(len(s[label]["time"]) for label in styles)  # the runs' history rows (one per 0.05/Omega)
        cols = [Column("time", t[:n], "1/Omega", "time of the sample (upwind run; the others within one step)")]
        for label in styles:
            cols += [Column(f"mass_{label}", s[label]["mass"][:n], "M_d(0)", f"total dust mass ({label})"),
                     Column(f"clamp_events_{label}", s[label]["clamps"][:n], "", f"particles clamped so far ({label})"),
                     Column(f"min_eps_{label}", s[label]["eps_min"][:n], "", f"smallest dust fraction ({label})")]
        created = s["arithmetic_clamped"]["created"] / s["arithmetic_clamped"]["m0"]
        return save_figure(fig, output / "fig3_3.png", cols,
                           title="thesis Figure 3.3: dust mass conservation in the settling test",
                           description=f"dust-settle, {runs['particles']} particles; arithmetic+clamp created "
                                       f"{created:.4g} of the initial dust mass; upwind events: "
                                       f"{int(np.max(s['upwind']['clamps']))}")
