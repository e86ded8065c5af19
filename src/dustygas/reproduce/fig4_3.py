"""Thesis Fig 4.3: as Fig 4.2 with the vertical settling drift of thesis eq. 4.19."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._linear_plots import plot_growth_vs_k, write_csv, write_json
from .fig4_2 import PI, THETA, growth_curves, header


@figure("fig4.3", "Growth rate vs |K| with vertical dust settling (eq. 4.19): plateau at large K", cost="3 s")
def fig4_3(output: Path, quick: bool = True) -> list[Path]:
    k, curves = growth_curves(quick, "settling")
    csv = write_csv(output / "fig4_3.csv", {"K": k, **curves}, header("settling (eq. 4.19, downward)"))
    # the large-K plateau: growth at the largest K and its spread over the last decade
    tail = k >= k[-1] / 10
    plateau = {name: {"s_at_Kmax": float(s[-1]), "relative_spread_last_decade":
                      float(np.ptp(s[tail]) / max(abs(s[-1]), 1e-300)), "peak": float(np.max(s)),
                      "K_peak": float(k[np.argmax(s)])} for name, s in curves.items()}
    js = write_json(output / "fig4_3.json", {"plateau": plateau, "K_range": [float(k[0]), float(k[-1])],
                                              "theta_deg": THETA, "Pi": PI})
    best = max(plateau.items(), key=lambda kv: kv[1]["s_at_Kmax"])
    note = (f"θk = ±{THETA:g}° (faster of ±Kz), Π = {PI:g}, settling drift v̄z = −cs τs/(2τs²+1)\n"
            f"large-K plateau: {best[0]}: s → {best[1]['s_at_Kmax']:.3g} Ω (damped for τs ≤ 0.1 at large K)")
    png = plot_growth_vs_k(k, list(curves.items()), output / "fig4_3.png",
                           "Fig 4.3: growth versus wavenumber with vertical dust settling", note)
    return [png, csv, js]
