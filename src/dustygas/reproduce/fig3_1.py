"""Thesis Figure 3.1 (Gonzalez, Laibe & Maddison 2017, MNRAS 467, 1984, App. A, Fig. A1).

Fragmentation sizes :math:`s_{\\rm frag}^\\pm` (thesis eq. 3.9) and the drift size versus
radius in the initial midplane of a flat disk (:math:`\\Sigma` constant, top panel) and a disk
with :math:`\\Sigma \\propto r^{-1}` (bottom panel). Grains between the two branches of one
:math:`V_{\\rm frag}` fragment; grains below the lower branch, above the upper one, or outside
its radial extent (:math:`\\tilde\\alpha c_s^2/V_{\\rm frag}^2 < 2`) grow.

Sizes come from :mod:`dustygas.physics`: :math:`s_{\\rm frag}^\\pm = s_1\\tau_\\pm` with
:math:`s_1` the Epstein size of unit Stokes number, :math:`\\sqrt{8/\\pi}\\,s_{\\rm drift}`
(:func:`~dustygas.physics.drag.epstein_grain_size`; the thesis writes :math:`s_1 = s_{\\rm drift}
= \\rho_g c_s/(\\rho_{\\rm grain}\\Omega)`, see :mod:`dustygas.physics.growth`). Both
:math:`s_1` (solid black) and the thesis's :math:`s_{\\rm drift}` (dotted) are drawn and saved.

Disk parameters
---------------
Only the abstract of Gonzalez et al. (2017) could be consulted from this project's sources,
so the values below are stated with their provenance; change :data:`DISKS` to explore.

=======================  ==============================  ===========================================
quantity                 value                           source
=======================  ==============================  ===========================================
star mass                1 M_sun                         Gonzalez et al. (2017), recalled
disk gas mass            0.01 M_sun                      Gonzalez et al. (2017), recalled
radial extent            4 - 120 au                      assumed (their initial disk, recalled)
:math:`\\Sigma \\propto r^{-p}`  p = 0 (flat), p = 1           thesis Figure 3.1 caption
:math:`T \\propto r^{-q}`       q = 1/2                         assumed
aspect ratio             H/r = 0.05 at 100 au             assumed (thin SPH disk of that group)
alpha                    0.01                             assumed (:math:`\\alpha_{\\rm SS}\\sim10^{-2}`)
Rossby number            Ro = 3                           Gonzalez et al. (2017); Phantom default
grain density            1 g/cm^3                         assumed (:math:`\\rho_s = 1000` kg m^-3)
:math:`V_{\\rm frag}`     10, 15, 20, 25 m/s               assumed (their range of thresholds)
adiabatic index          :math:`\\gamma = 1`                 isothermal disk
mean molecular weight    2.34                             :mod:`dustygas.units` default
=======================  ==============================  ===========================================

The radius where a branch ends is set by :math:`A = \\sqrt2 Ro\\,\\alpha c_s^2/V_{\\rm frag}^2 = 2`
alone, independent of :math:`\\Sigma`; the surface density only moves the sizes.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..physics.disk import PowerLawDisk, surface_density_normalisation
from ..physics.drag import epstein_grain_size
from ..physics.growth import alpha_tilde, drift_size, fragmentation_sizes
from ..plot import Column, house_style, new_figure, save_figure
from ..units import M_sun, au
from . import figure


@dataclass(frozen=True)
class GonzalezDisk:
    """Initial disk of Gonzalez et al. (2017) with surface-density exponent ``p`` (module table)."""

    label: str
    p: float
    disk_mass: float = 0.01 * M_sun
    M_star: float = M_sun
    r_in: float = 4.0 * au
    r_out: float = 120.0 * au
    q: float = 0.5
    aspect_ratio: float = 0.05
    r_aspect: float = 100.0 * au
    alpha: float = 0.01
    rossby: float = 3.0
    rho_grain: float = 1.0
    gamma: float = 1.0

    def disk(self) -> PowerLawDisk:
        Sigma0 = surface_density_normalisation(self.disk_mass, self.r_in, self.r_out, au, self.p)
        return PowerLawDisk.from_aspect_ratio(Sigma0, au, self.p, self.aspect_ratio, self.r_aspect, self.q, self.M_star)


#: The two panels of Figure 3.1.
DISKS = (GonzalezDisk("flat", 0.0), GonzalezDisk("steep", 1.0))
#: Fragmentation thresholds [m/s].
V_FRAG = (10.0, 15.0, 20.0, 25.0)
TITLES = {"flat": r"flat disk, $\Sigma = $ const", "steep": r"$\Sigma \propto r^{-1}$"}


def profiles(model: GonzalezDisk, r: np.ndarray) -> dict[str, np.ndarray]:
    """Midplane profiles and sizes [cm] of ``model`` at radii ``r`` [cm]."""
    d = model.disk()
    rho_g, c_s, Omega = d.midplane_density(r), d.sound_speed(r), d.omega(r)
    out = {
        "Sigma": d.sigma(r),
        "c_s": c_s,
        "s_drift": drift_size(rho_g, c_s, Omega, model.rho_grain),
        "s_unit_stokes": epstein_grain_size(1.0, model.rho_grain, rho_g, c_s, Omega, model.gamma),
    }
    at = alpha_tilde(model.alpha, model.rossby)
    for v in V_FRAG:
        lo, hi = fragmentation_sizes(at, c_s, v * 100.0, out["s_unit_stokes"])
        out[f"s_frag_minus_v{v:g}"] = lo
        out[f"s_frag_plus_v{v:g}"] = hi
    return out


@figure("fig3.1", "Fragmentation and drift sizes versus radius, flat and r^-1 disks (thesis Fig. 3.1)",
        cost="1 s")
def fig3_1(output: Path, quick: bool = True) -> list[Path]:
    """Write ``fig3_1.png`` and ``fig3_1.csv`` into ``output``; ``quick`` does not matter here."""
    r = np.geomspace(DISKS[0].r_in, DISKS[0].r_out, 1200 if quick else 6000)
    data = {m.label: profiles(m, r) for m in DISKS}
    colours = ["C0", "C1", "C2", "C3"]
    with house_style():
        fig, axes = new_figure(2, 1, width=5.0, height=7.0, sharex=True)
        for ax, model in zip(axes, DISKS):
            prof = data[model.label]
            for v, col in zip(V_FRAG, colours):
                lo, hi = prof[f"s_frag_minus_v{v:g}"], prof[f"s_frag_plus_v{v:g}"]
                ax.loglog(r / au, hi, color=col, label=rf"$s_{{\rm frag}}^\pm$, $V_{{\rm frag}}$ = {v:g} m/s")
                ax.loglog(r / au, lo, color=col)
                ok = np.flatnonzero(np.isfinite(hi))
                if ok.size and ok[-1] < r.size - 1:  # close the branch at its outer end (A = 2)
                    i = ok[-1]
                    ax.plot([r[i] / au] * 2, [lo[i], hi[i]], color=col)
            ax.loglog(r / au, prof["s_unit_stokes"], color="k", label=r"$s(\tau_s = 1)$, Epstein")
            ax.loglog(r / au, prof["s_drift"], color="k", ls=":", label=r"$s_{\rm drift} = \rho_g c_s/(\rho_{\rm grain}\Omega)$")
            ax.set_title(TITLES[model.label], fontsize=10)
            ax.set_ylabel(r"grain radius $s$ [cm]")
            ax.set_ylim(1e-3, 1e4)
            for y, text in ((4e3, "growth"), (2e-3, "growth")):
                ax.text(4.3, y, text, fontsize=8, va="center", color="0.25")
        axes[0].text(4.3, 4.5, "fragmentation inside\neach pair of branches", fontsize=8, va="center", color="0.25")
        axes[-1].set_xlabel(r"radius $r$ [au]")
        axes[-1].set_xlim(r[0] / au, r[-1] / au)
        axes[-1].set_xticks([4, 10, 20, 50, 100], ["4", "10", "20", "50", "100"])
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=2, fontsize=8)
        cols = [Column("r", r / au, "au", "cylindrical radius")]
        for model in DISKS:
            prof, lab = data[model.label], model.label
            cols += [
                Column(f"{lab}_Sigma", prof["Sigma"], "g/cm^2", f"gas surface density, p = {model.p:g}"),
                Column(f"{lab}_c_s", prof["c_s"], "cm/s", "isothermal sound speed"),
                Column(f"{lab}_s_drift", prof["s_drift"], "cm", "rho_g c_s/(rho_grain Omega), thesis eq. 3.9-3.10"),
                Column(f"{lab}_s_unit_stokes", prof["s_unit_stokes"], "cm", "Epstein grain radius with tau_s = 1"),
            ]
            for v in V_FRAG:
                for sign in ("minus", "plus"):
                    cols.append(Column(f"{lab}_s_frag_{sign}_v{v:g}", prof[f"s_frag_{sign}_v{v:g}"], "cm",
                                       f"s_frag {sign} branch, V_frag = {v:g} m/s (NaN: no fragmentation)"))
        m = DISKS[0]
        return save_figure(
            fig, Path(output) / "fig3_1.png", cols,
            title="dustygas: thesis Figure 3.1 (Gonzalez et al. 2017, Fig. A1), fragmentation and drift sizes",
            description=(f"M_star = {m.M_star / M_sun:g} M_sun, M_disk = {m.disk_mass / M_sun:g} M_sun, "
                         f"r = {m.r_in / au:g}-{m.r_out / au:g} au, T ~ r^-{m.q:g}, H/r = {m.aspect_ratio:g} at "
                         f"{m.r_aspect / au:g} au, alpha = {m.alpha:g}, Ro = {m.rossby:g}, "
                         f"rho_grain = {m.rho_grain:g} g/cm^3, gamma = {m.gamma:g}, mu = 2.34\n"
                         "assumed values: see dustygas.reproduce.fig3_1"),
        )
