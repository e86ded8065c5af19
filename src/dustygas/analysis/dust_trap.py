"""Radial profiles of a dusty disk run and its gas pressure maxima: is there a (self-induced) dust trap?

For a snapshot of a ``dust-trap`` run (or any disk run with dust): in annuli of cylindrical radius,
the gas and dust surface densities, their ratio :math:`\\epsilon = \\Sigma_d/\\Sigma_g`, the dust-mass
weighted mean grain size :math:`s(r)`, and the gas pressure near the midplane (:math:`|z| < H/2`).
A *trap* is a radial pressure maximum: :func:`pressure_maxima` lists the annuli whose midplane
pressure exceeds both neighbours' by more than three standard errors of the difference (the SPH
noise of the annulus means), i.e. :math:`\\partial P/\\partial r > 0` inside and :math:`< 0` outside,
where dust of any size stops drifting (Gonzalez et al. 2017; Whipple 1972).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io.rundir import RunDirectory
from ..sph.particles import DUST, GAS
from ..units import DISK_UNITS
from .disk import disk_of

__all__ = ["trap_profiles", "pressure_maxima"]


def trap_profiles(run: str | Path, index: int = -1, edges: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """Profiles of snapshot ``index`` in annuli ``edges`` (default: 24 logarithmic bins over the disk):
    ``R`` (centres), ``sigma_gas``, ``sigma_dust``, ``dust_to_gas``, ``size_cm`` and the midplane pressure
    ``P_mid`` with its standard error ``P_err`` (code units), and ``time``."""
    arrays, attrs = RunDirectory(run).read_snapshot(index)
    disk = disk_of(run)
    if edges is None:
        edges = np.geomspace(disk.r_in, disk.r_out, 25)
    pos, m, t = arrays["pos"], arrays["mass"], arrays["ptype"]
    R = np.hypot(pos[:, 0], pos[:, 1])
    k = np.digitize(R, edges) - 1
    inside = (k >= 0) & (k < len(edges) - 1)
    nb = len(edges) - 1
    area = np.pi * np.diff(edges**2)

    def summed(weights, sel):
        return np.bincount(k[sel & inside], weights=weights[sel & inside], minlength=nb)

    gas, dust = t == GAS, t == DUST
    sigma_g = summed(m, gas) / area
    sigma_d = summed(m, dust) / area
    size = arrays.get("extra/grain_size", np.zeros_like(m))
    with np.errstate(invalid="ignore", divide="ignore"):
        s_mean = summed(m * size, dust) / summed(m, dust) * DISK_UNITS.length
        mid = gas & (np.abs(pos[:, 2]) < 0.5 * disk.scale_height(np.maximum(R, 1e-12)))
        n = summed(np.ones_like(m), mid)
        P = arrays["P"]
        P_mid = summed(P, mid) / n
        P_var = summed(P * P, mid) / n - P_mid**2
        P_err = np.sqrt(np.maximum(P_var, 0.0) / np.maximum(n - 1, 1))
        eps = sigma_d / sigma_g
    return {"R": np.sqrt(edges[1:] * edges[:-1]), "sigma_gas": sigma_g, "sigma_dust": sigma_d, "dust_to_gas": eps,
            "size_cm": s_mean, "P_mid": P_mid, "P_err": P_err, "time": np.array(float(attrs["time"]))}


def pressure_maxima(profile: dict[str, np.ndarray], significance: float = 3.0) -> np.ndarray:
    """Radii of the annuli whose midplane pressure exceeds both neighbours' by more than ``significance``
    standard errors of the difference (module docstring)."""
    P, e, R = profile["P_mid"], profile["P_err"], profile["R"]
    out = []
    for i in range(1, len(P) - 1):
        if not np.isfinite(P[i - 1 : i + 2]).all():
            continue
        if P[i] - P[i - 1] > significance * np.hypot(e[i], e[i - 1]) and \
                P[i] - P[i + 1] > significance * np.hypot(e[i], e[i + 1]):
            out.append(R[i])
    return np.array(out)
