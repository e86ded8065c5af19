"""Thesis Fig 4.1: fastest streaming-instability growth over (μ, τ_s) (Youdin & Goodman 2005)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._linear_plots import k_range_text, plot_growth_map, write_json

#: YG05's set-up: incompressible gas (Π → 0), growth maximised over K_x at fixed K_z.
KZ = 1000.0
KX_RANGE = (0.1, 1e6)


@figure("fig4.1", "Streaming-instability growth over (mu, tau_s), max over Kx at Kz = 1000 (YG05)", cost="2 s")
def fig4_1(output: Path, quick: bool = True) -> list[Path]:
    from ..linear.maps import growth_map

    n = 60 if quick else 200
    mu = np.logspace(-2, 2, n)
    taus = np.logspace(-3, 1, n)
    gm = growth_map(mu=mu, taus=taus, method="kx", kz=KZ, kx_range=KX_RANGE, Pi=0.0)
    h5 = gm.save(output / "fig4_1.h5")
    js = write_json(output / "fig4_1.json", {"attrs": gm.attrs, "k_range": k_range_text(gm.attrs),
                                              "max_growth": float(np.nanmax(gm.growth))})
    png = plot_growth_map(gm, output / "fig4_1.png",
                          "Fig 4.1: fastest growth s (left) and its Kx (right); incompressible gas (YG05)")
    return [png, h5, js]
