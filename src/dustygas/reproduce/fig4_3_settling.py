"""Thesis eq. 4.20: does settling-enhanced growth beat settling? t_growth/t_settle maps."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import figure
from ._linear_plots import k_range_text, pyplot, write_csv
from .fig4_2 import PI, THETA


@figure("fig4.3-settling", "t_growth/t_settle (eq. 4.20) for settling-enhanced growth over (mu, tau_s) and vs |K|",
        cost="5 s")
def fig4_3_settling(output: Path, quick: bool = True) -> list[Path]:
    from ..linear.maps import growth_map, settling_ratio
    from .fig4_2 import growth_curves

    n = 24 if quick else 100
    mu = np.logspace(-3, 0, n)
    taus = np.logspace(-3, 0.5, n)
    gm = growth_map(mu=mu, taus=taus, method="angle", theta_deg=THETA, k_range=(1e-2, 1e5), Pi=PI, vz="settling",
                    mirror=True, coarse=40 if quick else 60)
    ratio = settling_ratio(growth=gm.growth, taus=taus[:, None])
    gm.attrs["quantity"] = "t_growth/t_settle = (Omega/s) taus/(2 taus^2 + 1), thesis eq. 4.20"
    h5 = gm.save(output / "fig4_3_settling.h5")
    import h5py

    with h5py.File(h5, "a") as f:
        f.create_dataset("t_growth_over_t_settle", data=ratio)
    k, curves = growth_curves(quick, "settling")
    rcurves = {name: settling_ratio(growth=s, taus=float(name.split()[0].split("=")[1])) for name, s in curves.items()}
    csv = write_csv(output / "fig4_3_settling.csv", {"K": k, **rcurves},
                    ["t_growth/t_settle versus K for the Fig 4.3 curves (inf: not growing)",
                     f"theta_k = +-{THETA:g} deg, Pi = {PI:g}, settling drift eq. 4.19"])
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.6), constrained_layout=True)
    X, Y = np.meshgrid(mu, taus)
    lr = np.log10(np.where(np.isfinite(ratio), ratio, np.nan))
    c = axes[0].contourf(X, Y, lr, levels=np.arange(-3, 3.01, 0.25), cmap="coolwarm", extend="both")
    axes[0].contour(X, Y, lr, levels=[0.0], colors="k", linewidths=1.5)
    fig.colorbar(c, ax=axes[0], label=r"$\log_{10}(t_{\rm growth}/t_{\rm settle})$ (black: = 1)")
    axes[0].set_xscale("log")
    axes[0].set_yscale("log")
    axes[0].set_xlabel(r"dust-to-gas ratio $\mu$")
    axes[0].set_ylabel(r"stopping time $\tau_s$")
    axes[0].set_title("settling-enhanced growth (thesis eq. 4.20) beats settling below the black line\n"
                      + k_range_text(gm.attrs) + f", Π = {PI:g}", fontsize=9)
    for name, r in rcurves.items():
        axes[1].loglog(k, np.where(np.isfinite(r), r, np.nan), label=name, lw=1.3)
    axes[1].axhline(1.0, color="k", lw=1)
    axes[1].set_xlabel(r"wavenumber $|K| = |k|\eta r$")
    axes[1].set_ylabel(r"$t_{\rm growth}/t_{\rm settle}$")
    axes[1].set_ylim(1e-3, 1e4)
    axes[1].legend(fontsize=7, ncol=2, loc="upper right")
    axes[1].set_title(f"Fig 4.3 curves (θk = ±{THETA:g}°, Π = {PI:g}, fixed ts); eq. 4.20 needs < 1\n"
                      "only the resonant peaks (SH18) beat settling, never the large-K tails", fontsize=9)
    png = output / "fig4_3_settling.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png, h5, csv]
