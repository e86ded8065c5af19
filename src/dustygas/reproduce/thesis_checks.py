"""Quantitative checks of the thesis figures of chapters 3 and 4 (shown in the gallery).

Each function reads what its figure wrote into ``output`` and compares numbers with an analytic
result, a published formula or an independent evaluation (the fastest eigenvalue of the
linear operator from LAPACK, :func:`numpy.linalg.eigvals`, rather than the figure's own
root-finding and maximisation). Registered with :func:`dustygas.reproduce.register_checks`.
"""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import numpy as np

from ..plot import read_table
from . import register_checks
from .checks import Check, compare, within


def _csv(path: Path) -> dict[str, np.ndarray]:
    """CSV with ``#`` comment lines and a header row (either writer of this package)."""
    with open(path, encoding="utf-8") as fh:
        rows = list(csv.reader(ln for ln in fh if not ln.startswith("#")))
    names, values = rows[0], np.array(rows[1:], dtype=float)
    return {name: values[:, i] for i, name in enumerate(names)}


def _lapack_growth(taus: float, mu: float, kx: float, kz: float, Pi: float, vz: float | str = 0.0,
                   drag: str = "consistent") -> float:
    from ..linear import StreamingParams, operator_matrix

    return float(np.linalg.eigvals(operator_matrix(StreamingParams(taus=taus, mu=mu, kx=kx, kz=kz, Pi=Pi, vz=vz,
                                                                   drag=drag))).real.max())


@register_checks("fig3.1")
def fig3_1_checks(output: Path) -> list[Check]:
    from ..physics.growth import alpha_tilde
    from .fig3_1 import DISKS

    data = read_table(output / "fig3_1.csv")
    r = data["r"]
    out = []
    ratio = max(float(np.max(np.abs(data[f"{d.label}_s_unit_stokes"] / data[f"{d.label}_s_drift"] / math.sqrt(8 / math.pi) - 1)))
                for d in DISKS)
    out.append(compare("Epstein size of tau_s = 1 over s_drift, max deviation from sqrt(8/pi)", ratio, 0.0, atol=1e-12,
                       reference="Epstein drag t_s = rho_grain s/(rho_g v_th), v_th = sqrt(8/pi) c_s"))
    flat = DISKS[0]
    c0 = data["flat_c_s"][0]
    v = 2500.0  # 25 m/s in cm/s
    # branch ends where alpha_tilde c_s^2 / V^2 = 2, with c_s^2 proportional to r^-q (q = 1/2)
    r_end = r[0] * (float(alpha_tilde(flat.alpha, flat.rossby)) * c0**2 / (2 * v**2)) ** (1 / flat.q)
    last = float(r[np.isfinite(data["flat_s_frag_plus_v25"])][-1])
    step = float(np.max(np.diff(r)))
    out.append(compare("flat disk, V_frag = 25 m/s: outermost radius with s_frag (au)", last, r_end, atol=step,
                       reference="eq. 3.8 has roots only where alpha_tilde c_s^2/V_frag^2 >= 2 (c_s^2 ~ r^-1/2)"))
    return out


@register_checks("fig3.2")
def fig3_2_checks(output: Path) -> list[Check]:
    data = read_table(output / "fig3_2.csv")
    up = min(float(np.min(v)) for k, v in data.items() if k.startswith("eps_upwind_"))
    ar = min(float(np.min(v)) for k, v in data.items() if k.startswith("eps_arithmetic_") and "clamped" not in k)
    top0 = float(np.max(data["eps_upwind_0"]))
    return [
        within("upwind exchange: smallest dust fraction at every time", up, 0.0, top0,
               reference="eq. 3.17 moves dust only out of particles that hold it: eps stays >= 0"),
        within("arithmetic exchange without clamp: smallest dust fraction", ar, -1.0, -1e-12,
               reference="thesis sec. 3.2.4: eq. 3.4 drives eps negative at the top of the column"),
    ]


@register_checks("fig3.3")
def fig3_3_checks(output: Path) -> list[Check]:
    data = read_table(output / "fig3_3.csv")
    return [
        compare("upwind: max |M_d(t)/M_d(0) - 1|", float(np.max(np.abs(data["mass_upwind"] - 1))), 0.0, atol=1e-12,
                reference="eq. 3.17 exchanges dust pairwise and antisymmetrically: exact conservation"),
        compare("arithmetic, no clamp: max |M_d(t)/M_d(0) - 1|", float(np.max(np.abs(data["mass_arithmetic"] - 1))),
                0.0, atol=1e-12, reference="eq. 3.4 is antisymmetric too (but allows eps < 0)"),
        within("arithmetic with clamp: dust created, M_d(end)/M_d(0) - 1", float(data["mass_arithmetic_clamped"][-1] - 1),
               1e-9, 1.0, reference="thesis sec. 3.2.4: clamping negative eps to 0 adds mass"),
    ]


@register_checks("fig3.5")
def fig3_5_checks(output: Path) -> list[Check]:
    data = read_table(output / "fig3_5.csv")
    a, b = 3.75e-5, 7.5e-3  # -v_r,gas/v_K and eta of the thesis's caption
    tau_star = (math.hypot(a, b) - a) / b
    y = data["minus_vr_over_vK"]
    taus = data["tau_s"]
    step = float(np.log10(taus[1] / taus[0]))
    return [
        compare("peak of -v_r/v_K", float(y.max()), (math.hypot(a, b) + a) / 2, rtol=1e-3,
                reference="eq. 3.23: maximum (sqrt(a^2+b^2)+a)/2 at tau* = (sqrt(a^2+b^2)-a)/b"),
        compare("log10 tau_s of the peak", float(np.log10(taus[np.argmax(y)])), math.log10(tau_star), atol=step,
                reference="eq. 3.23 (Armitage 2013, Fig. 4.2: the peak at tau_s ~ 1)"),
    ]


@register_checks("fig4.1")
def fig4_1_checks(output: Path) -> list[Check]:
    import h5py

    with h5py.File(output / "fig4_1.h5", "r") as f:
        growth, kx, kz = f["growth_rate"][()], f["kx"][()], f["kz"][()]
        mu, taus, Pi = f["mu"][()], f["taus"][()], float(f.attrs["Pi"])
    i, j = np.unravel_index(np.nanargmax(growth), growth.shape)
    s = _lapack_growth(float(taus[i]), float(mu[j]), float(kx[i, j]), float(kz[i, j]), Pi)
    # a point of YG05's map with a resolved optimum: tau_s = 0.1, mu = 3 (the linA parameters)
    ti, mj = int(np.argmin(np.abs(np.log(taus / 0.1)))), int(np.argmin(np.abs(np.log(mu / 3.0))))
    s2 = _lapack_growth(float(taus[ti]), float(mu[mj]), float(kx[ti, mj]), float(kz[ti, mj]), Pi)
    return [
        compare("largest growth rate of the map (Omega) vs LAPACK at its (mu, tau_s, Kx, Kz)", float(growth[i, j]), s,
                rtol=1e-8, reference="YG05 dispersion relation, eigenvalues by numpy.linalg.eigvals"),
        compare(f"growth at tau_s = {taus[ti]:.3g}, mu = {mu[mj]:.3g} vs LAPACK", float(growth[ti, mj]), s2, rtol=1e-8,
                reference="YG05 dispersion relation, eigenvalues by numpy.linalg.eigvals"),
    ]


@register_checks("fig4.2")
def fig4_2_checks(output: Path) -> list[Check]:
    data = _csv(output / "fig4_2.csv")
    k = data["K"]
    theta = math.radians(30.0)
    out = []
    for name in ("taus=1 mu=0.1", "taus=0.1 mu=0.1"):
        s = data[name]
        i = int(np.nanargmax(s))
        taus, mu = (float(p.split("=")[1]) for p in name.split())
        ref = _lapack_growth(taus, mu, k[i] * math.sin(theta), k[i] * math.cos(theta), 0.05)
        out.append(compare(f"peak growth, {name.replace('taus', 'tau_s')} (K = {k[i]:.4g}) vs LAPACK", float(s[i]), ref,
                           rtol=1e-8, reference="SH18 Fig. 1 set-up (theta_k = 30 deg, Pi = 0.05); numpy.linalg.eigvals"))
    return out


@register_checks("fig4.3")
def fig4_3_checks(output: Path) -> list[Check]:
    curves = json.loads((output / "fig4_3.json").read_text())["curves"]
    out = []
    for name in ("taus=0.01 mu=0.1", "taus=0.001 mu=0.1", "taus=0.01 mu=0.01", "taus=0.001 mu=0.01"):
        c = curves[name]
        out.append(compare(f"resonant peak, {name.replace('taus', 'tau_s')}", c["peak"], c["resonance_growth"], rtol=0.02,
                           reference="Squire & Hopkins (2018) resonant drag instability, sqrt(mu/2) sin theta_k "
                                     "with the radial-drift factor"))
    c = curves["taus=1 mu=0.1"]
    out.append(compare("large-K plateau, tau_s = 1, mu = 0.1, fixed t_s", c["s_at_Kmax"], c["plateau_formula"], rtol=0.05,
                       reference="leading order in mu of the non-resonant dust density wave"))
    return out


@register_checks("fig4.3-settling")
def fig4_3_settling_checks(output: Path) -> list[Check]:
    import h5py

    with h5py.File(output / "fig4_3_settling.h5", "r") as f:
        s, ratio, taus = f["growth_rate"][()], f["t_growth_over_t_settle"][()], f["taus"][()]
    ok = (s > 0) & np.isfinite(ratio)
    expected = (taus[:, None] / (2 * taus[:, None] ** 2 + 1)) / np.where(ok, s, np.nan)
    dev = float(np.nanmax(np.abs(ratio[ok] / expected[ok] - 1)))
    return [compare("max relative deviation of t_growth/t_settle from (1/s) tau_s/(2 tau_s^2 + 1)", dev, 0.0, atol=1e-12,
                    reference="thesis eq. 4.20 with t_settle from eq. 4.19")]


@register_checks("fig4.6")
def fig4_6_checks(output: Path) -> list[Check]:
    pts = _csv(output / "fig4_6_points.csv")
    out = []
    for i in range(len(pts["taus"])):
        out.append(compare(f"measured growth, tau_s = {pts['taus'][i]:g}, mu = {pts['mu'][i]:g}, K = {pts['K'][i]:g}",
                           pts["growth"][i], pts["theory"][i], rtol=0.05,
                           reference="linear theory of the same background (fixed t_s, eq. 4.19 drift)"))
    return out
