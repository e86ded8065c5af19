"""Thesis Fig 4.2: growth rate versus |K| at θ_k = 30° (Squire & Hopkins 2018 parameters)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._linear_plots import plot_growth_vs_k, write_csv

#: The thesis's stopping times; μ = 0.1 (named in §4.1.4) and SH18's fiducial μ = 0.01.
TAUS = (1.0, 0.1, 0.01, 0.001)
MUS = (0.1, 0.01)
THETA = 30.0
PI = 0.05
K_RANGE = (1e-2, 1e5)


def growth_curves(quick: bool, vz, drag: str = "consistent") -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Growth vs |K| for every (τ_s, μ) of the figure; the fastest of (K_x, ±K_z) when settling."""
    from ..linear.maps import growth_vs_k

    k = np.logspace(np.log10(K_RANGE[0]), np.log10(K_RANGE[1]), 2500 if quick else 10000)
    curves = {}
    for mu in MUS:
        for taus in TAUS:
            curves[f"taus={taus:g} mu={mu:g}"] = growth_vs_k(taus=taus, mu=mu, k=k, theta_deg=THETA, Pi=PI, vz=vz,
                                                             mirror=vz != 0.0, drag=drag)
    return k, curves


def header(vz) -> list[str]:
    return [f"growth rate s/Omega of the fastest mode at theta_k = atan(Kx/Kz) = {THETA:g} deg"
            + (" (fastest of +Kz and -Kz)" if vz != 0.0 else ""),
            f"K = k eta r; Pi = eta v_K/c_s = {PI:g}; drag: consistent; vertical dust drift: {vz}",
            "conventions: exp(i k.x - i omega t), s = Im omega"]


@figure("fig4.2", "Growth rate vs |K| at theta_k = 30 deg for several (tau_s, mu) (SH18 parameters)", cost="2 s")
def fig4_2(output: Path, quick: bool = True) -> list[Path]:
    k, curves = growth_curves(quick, 0.0)
    csv = write_csv(output / "fig4_2.csv", {"K": k, **curves}, header(0.0))
    note = f"θk = {THETA:g}°, Π = {PI:g}, consistent drag, no vertical drift"
    png = plot_growth_vs_k(k, list(curves.items()), output / "fig4_2.png",
                           "Fig 4.2: streaming-instability growth versus wavenumber", note)
    return [png, csv]
