"""Figures of stratified particle runs: particle slabs, surface density and its FFT, time series.

Every function writes a PNG and the numbers behind it next to it (CSV through
:func:`~dustygas.plot.style.save_figure`; the 2D maps of :func:`surface_density_figure` also as
HDF5) and returns the written paths. Times are shown in orbits (``t / 2π``), densities in units
of the initial midplane gas density ``ρ_g0`` (1 in code units).
"""

from __future__ import annotations

from pathlib import Path
from typing import Sequence

import numpy as np

from ..analysis.stratified import (ORBIT, Snapshot, density_cdf, dominant_wavevector, fourier_power, midplane_density,
                                   slab, surface_density)
from ..io.hdf5 import write_h5
from .style import Column, house_style, new_figure, save_figure

__all__ = ["slab_figure", "surface_density_figure", "series_figure", "cdf_figure"]


def _scatter(ax, a, b, rho, vmax, size=2.0):
    order = np.argsort(rho)  # dense particles on top
    return ax.scatter(a[order], b[order], c=np.log10(np.maximum(rho[order], 1e-3)), s=size, cmap="magma",
                      vmin=-1.0, vmax=np.log10(max(vmax, 1.0)), linewidths=0, rasterized=True)


def slab_figure(snap: Snapshot, png: Path, view: str, half_width: float = 0.03, title: str = "",
                z_shown: float | None = None) -> list[Path]:
    """Particles near a plane, coloured by the dust density of their cell (log10 ρ_p/ρ_g0).

    ``view``: ``"xy"`` the midplane slab ``|z| < δ`` (thesis Fig 4.8); ``"xz"`` the azimuthal slab
    ``|y| < δ`` (Fig 4.9); ``"cube"`` the three panels of Fig 4.7: the midplane slab and the
    slabs within ``δ`` of the y and x boundaries, the vertical extent shown limited to
    ``|z| < z_shown`` (default all).
    """
    rho = snap.particle_density()
    pos = snap.pos
    lx, ly, lz = snap.box
    vmax = float(rho.max()) if rho.size else 1.0
    t_orb = snap.time / ORBIT
    cols: list[Column] = []
    with house_style():
        if view == "cube":
            fig, axes = new_figure(1, 3, width=12.0, height=4.2)
            zlim = 0.5 * lz if z_shown is None else z_shown
            panels = [("x", "y", slab(pos, 2, 0.0, half_width), f"midplane |z| < {half_width:g} H"),
                      ("x", "z", slab(pos, 1, -0.5 * ly, half_width) & (np.abs(pos[2]) < zlim),
                       f"y boundary, within {half_width:g} H"),
                      ("y", "z", slab(pos, 0, 0.5 * lx, half_width) & (np.abs(pos[2]) < zlim),
                       f"x boundary, within {half_width:g} H")]
        else:
            fig, ax = new_figure(1, 1, width=5.2 if view == "xy" else 6.0, height=4.6 if view == "xy" else 4.0)
            axes = [ax]
            if view == "xy":
                panels = [("x", "y", slab(pos, 2, 0.0, half_width), f"|z| < {half_width:g} H")]
            else:
                panels = [("x", "z", slab(pos, 1, 0.0, half_width), f"|y| < {half_width:g} H")]
        names = {"x": 0, "y": 1, "z": 2}
        sc = None
        for ax, (a, b, sel, label) in zip(axes, panels):
            sc = _scatter(ax, pos[names[a], sel], pos[names[b], sel], rho[sel], vmax)
            ax.set_xlabel(f"${a}/H$")
            ax.set_ylabel(f"${b}/H$")
            ax.set_title(label, fontsize=9)
            ax.set_aspect("equal")
            ax.text(0.98, 0.96, f"t = {t_orb:.2f} orbits", transform=ax.transAxes, ha="right", va="top", fontsize=8,
                    color="w", bbox=dict(fc="k", alpha=0.5, lw=0))
            tag = f"{a}{b}" if view != "cube" else f"{a}{b}_{len(cols) // 3}"
            cols += [Column(f"{tag}_{a}", pos[names[a], sel], "H", f"{a} of the particles in the slab"),
                     Column(f"{tag}_{b}", pos[names[b], sel], "H", f"{b} of the particles in the slab"),
                     Column(f"{tag}_rho_p", rho[sel], "rho_g0", "dust density of the particle's cell")]
        fig.colorbar(sc, ax=list(axes), label=r"$\log_{10}(\rho_p/\rho_{g0})$", shrink=0.85)
        if title:
            fig.suptitle(title, fontsize=10)
        # the panels hold different numbers of particles: one CSV per figure, padded with NaN
        n = max(len(c.values) for c in cols)
        cols = [Column(c.name, np.pad(np.asarray(c.values, dtype=float), (0, n - len(c.values)),
                                      constant_values=np.nan), c.unit, c.description) for c in cols]
        return save_figure(fig, png, cols, title or f"particle slab {view}",
                           f"snapshot time {snap.time:.6g} (code units) = {t_orb:.4g} orbits; NaN pads shorter panels")


def surface_density_figure(snaps: Sequence[Snapshot], png: Path, title: str = "", every: Sequence[Snapshot] = ()
                           ) -> list[Path]:
    """Σ_d(x, y) and |Σ̂_d(k_x, k_y)| of the snapshots ``snaps`` (one row each; thesis Fig 4.10),
    and the dominant wave vector and its angle θ_k of every snapshot of ``every`` (default
    ``snaps``) in the CSV; the maps also go to an HDF5 file next to the PNG."""
    every = list(every) or list(snaps)
    rows = []
    maps = {}
    for s in every:
        sig = surface_density(s.rho_p, s.dx[2])
        amp, kx, ky = fourier_power(sig, s.box[0], s.box[1])
        nonaxi = float(amp[np.abs(ky) > 0].max() / sig.mean() * np.sqrt(len(s.mass)))
        rows.append((s.time / ORBIT, *dominant_wavevector(amp, kx, ky), float(sig.max() / sig.mean()), nonaxi))
    with house_style():
        fig, axes = new_figure(len(snaps), 2, width=8.4, height=3.4 * len(snaps))
        axes = np.atleast_2d(axes)
        for r, s in enumerate(snaps):
            sig = surface_density(s.rho_p, s.dx[2])
            amp, kx, ky = fourier_power(sig, s.box[0], s.box[1])
            kxd, kyd, th = dominant_wavevector(amp, kx, ky)
            lx, ly = s.box[0], s.box[1]
            im = axes[r, 0].imshow(sig / sig.mean(), origin="lower", cmap="viridis",
                                   extent=(-lx / 2, lx / 2, -ly / 2, ly / 2))
            fig.colorbar(im, ax=axes[r, 0], label=r"$\Sigma_d/\langle\Sigma_d\rangle$")
            axes[r, 0].set_xlabel("$x/H$")
            axes[r, 0].set_ylabel("$y/H$")
            axes[r, 0].text(0.97, 0.95, f"t = {s.time / ORBIT:.2f} orb", transform=axes[r, 0].transAxes, ha="right",
                            va="top", color="w", fontsize=8)
            dk = (kx[1] - kx[0], ky[1] - ky[0])
            im = axes[r, 1].imshow(np.log10(np.maximum(amp / sig.mean(), 1e-6)), origin="lower", cmap="magma",
                                   extent=(kx[0] - dk[0] / 2, kx[-1] + dk[0] / 2, ky[0] - dk[1] / 2, ky[-1] + dk[1] / 2))
            fig.colorbar(im, ax=axes[r, 1], label=r"$\log_{10}|\hat\Sigma_d|/\langle\Sigma_d\rangle$")
            axes[r, 1].plot([kxd, -kxd], [kyd, -kyd], "c+", ms=10)
            axes[r, 1].set_xlabel(r"$k_x H$")
            axes[r, 1].set_ylabel(r"$k_y H$")
            axes[r, 1].set_title(rf"peak $\theta_k$ = {th:.1f}°", fontsize=9)
            maps[f"t{r}/sigma_d"] = sig
            maps[f"t{r}/fft_amplitude"] = amp
            maps[f"t{r}/kx"] = kx
            maps[f"t{r}/ky"] = ky
            maps[f"t{r}/time"] = np.array(s.time)
        if title:
            fig.suptitle(title, fontsize=10)
        arr = np.array(rows)
        cols = [Column("t_orbits", arr[:, 0], "orbits", "time t/(2 pi / Omega)"),
                Column("kx", arr[:, 1], "1/H", "k_x of the largest FFT peak (folded to k_x >= 0)"),
                Column("ky", arr[:, 2], "1/H", "k_y of the largest FFT peak"),
                Column("theta_k", arr[:, 3], "deg", "arctan(k_y/k_x) of the peak (0: axisymmetric)"),
                Column("sigma_max_over_mean", arr[:, 4], "1", "max of Sigma_d over its mean"),
                Column("nonaxisymmetric_over_noise", arr[:, 5], "1",
                       "largest |FFT| with k_y != 0 over the particle shot noise <Sigma_d>/sqrt(N)")]
        paths = save_figure(fig, png, cols, title or "dust surface density and its 2D FFT",
                            "Sigma_d = sum_z rho_p dz; FFT of Sigma_d - <Sigma_d>, amplitudes over the cell count")
    h5 = Path(png).with_suffix(".h5")
    write_h5(h5, maps, {"description": "Sigma_d(x, y) and |FFT| per shown time; kx, ky fft-shifted (1/H)"})
    return paths + [h5]


def series_figure(series: dict, png: Path, quantity: str, title: str = "", area: float = 1.0,
                  names: Sequence[str] = ()) -> list[Path]:
    """Time series from a run's history: ``quantity`` = ``"max_density"`` (max ρ_p/ρ_g0 and the mean
    midplane dust density Σ_p/(√(2π) H_p); Fig 1.10), ``"scale_height"`` (H_p per species; Fig 1.13)
    or ``"dispersion"`` (σ_x, σ_y, σ_z per species)."""
    t = np.asarray(series["time"]) / ORBIT
    nsp = 0
    while f"species_{nsp}_mass" in series:
        nsp += 1
    names = list(names) or [f"species {s}" for s in range(nsp)]
    cols = [Column("t_orbits", t, "orbits", "time t/(2 pi / Omega)")]
    with house_style():
        fig, ax = new_figure(1, 1, width=5.6, height=3.8)
        if quantity == "max_density":
            rmax = np.asarray(series["rho_p_max"])
            hp = np.asarray(series["species_0_scale_height"])
            mass = sum(np.asarray(series[f"species_{s}_mass"]) for s in range(nsp))
            hp_all = np.sqrt(sum(np.asarray(series[f"species_{s}_mass"]) * np.asarray(series[f"species_{s}_scale_height"])**2
                                 for s in range(nsp)) / mass) if nsp > 1 else hp
            mid = midplane_density(mass, area, hp_all)
            ax.semilogy(t, rmax, label=r"max $\rho_p/\rho_{g0}$")
            ax.semilogy(t, mid, "--", label=r"mean midplane $\Sigma_p/(\sqrt{2\pi}H_p)$")
            ax.set_ylabel(r"dust density / $\rho_{g0}$")
            cols += [Column("rho_p_max", rmax, "rho_g0", "largest dust density in a cell"),
                     Column("rho_p_midplane", mid, "rho_g0", "mean midplane dust density Sigma_p/(sqrt(2 pi) H_p)")]
        elif quantity == "scale_height":
            for s in range(nsp):
                hp = np.asarray(series[f"species_{s}_scale_height"])
                ax.semilogy(t, hp, label=names[s])
                cols.append(Column(f"Hp_{s}", hp, "H", f"scale height of {names[s]} (std of z)"))
            ax.set_ylabel(r"particle scale height $H_p/H$")
        elif quantity == "dispersion":
            for s in range(nsp):
                for c, ls in zip("xyz", ("-", "--", ":")):
                    v = np.asarray(series[f"species_{s}_sigma_{c}"])
                    ax.semilogy(t, v, ls, label=f"{names[s]} $\\sigma_{c}$")
                    cols.append(Column(f"sigma_{c}_{s}", v, "c_s", f"velocity dispersion along {c}, {names[s]}"))
            ax.set_ylabel(r"velocity dispersion / $c_s$")
        else:
            raise ValueError(f"unknown quantity {quantity!r}")
        ax.set_xlabel("t (orbits)")
        ax.legend(fontsize=7)
        if title:
            ax.set_title(title, fontsize=9)
        return save_figure(fig, png, cols, title or quantity, "from the run's history.h5")


def cdf_figure(snaps: Sequence[Snapshot], png: Path, title: str = "") -> list[Path]:
    """Fraction of the dust mass in cells denser than ρ_p, for each snapshot (one curve each)."""
    grid = None
    curves = []
    for s in snaps:
        rho = s.rho_p[s.rho_p > 0]
        if grid is None:
            grid = np.logspace(np.log10(max(rho.min(), 1e-4)), np.log10(rho.max() * 4), 200)
        curves.append(density_cdf(s.rho_p, grid)[1])
    cols = [Column("rho_p", grid, "rho_g0", "dust density threshold")]
    with house_style():
        fig, ax = new_figure(1, 1, width=5.4, height=3.8)
        for s, c in zip(snaps, curves):
            ax.loglog(grid, np.maximum(c, 1e-8), label=f"t = {s.time / ORBIT:.1f} orb")
            cols.append(Column(f"P_t{len(cols)}", c, "1", f"mass fraction with rho_p >= threshold at t = {s.time:.6g}"))
        ax.set_xlabel(r"$\rho_p/\rho_{g0}$")
        ax.set_ylabel(r"mass fraction with density $\geq \rho_p$")
        ax.set_ylim(1e-6, 1.5)
        ax.legend(fontsize=7)
        if title:
            ax.set_title(title, fontsize=9)
        return save_figure(fig, png, cols, title or "cumulative distribution of the dust density")
