"""Dominant wavevector of the dust surface density in a run (thesis §4.5, Fig 4.10).

The thesis Fourier-transforms the vertically integrated dust density Σ_d(x, y) of its 3D runs
and finds power concentrated along an angle θ_k in the k_x–k_y plane that evolves in time. This
module measures θ_k(t) from any run directory whose snapshots hold the dust: the deposited
particle density ``rho_p`` (nz, ny, nx), or particle positions and masses (``particles/pos``,
``particles/mass``, binned onto the snapshot's x–y cells). It is compared with the preferred
wavevector of the shearing-wave sweep (:mod:`dustygas.linear.sweep`) by ``dustygas linear angle``.

Shear-periodic boxes: Σ_d(x + L_x, y) = Σ_d(x, y + d) with d the snapshot's ``shear_offset``
(q Ω L_x t mod L_y; for a sheared wave k_x(t) = k_x0 + q k_y t this is exactly its phase
condition). The field is made periodic by the y-shift s(x) = d (x − x_0)/L_x, done exactly in
Fourier space along y, and the wavevector of the shifted field, k_x', is converted back to
the frame of the box: k_x = k_x' + k_y d/L_x.

Angles are θ_k = arctan(k_y/k_x) ∈ (−90°, 90°] (k and −k are the same real wave), in the
conventions of :mod:`dustygas.linear` (x radial, y azimuthal, shear −q Ω x ŷ: a trailing wave has
k_x k_y > 0, θ_k > 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import UserError

__all__ = ["SurfaceDensity", "surface_density", "dominant_wavevector", "angle_history"]


@dataclass
class SurfaceDensity:
    """Σ_d(x, y) on the cells of a snapshot: ``sigma`` has shape (ny, nx)."""

    sigma: np.ndarray
    lx: float
    ly: float
    shear_offset: float
    time: float
    source: str


def _lengths(arrays, attrs, axis: str) -> float:
    key = f"l{axis}"
    if key in attrs:
        return float(attrs[key])
    c = np.asarray(arrays.get(axis, []), dtype=np.float64)
    if c.size >= 2:
        return float(c.size * (c[1] - c[0]))
    raise UserError(f"snapshot has no box length '{key}' and no '{axis}' cell centres")


def surface_density(arrays: dict, attrs: dict) -> SurfaceDensity:
    """Σ_d(x, y) from one snapshot's arrays and attributes (``rho_p`` preferred, else particles)."""
    lx, ly = _lengths(arrays, attrs, "x"), _lengths(arrays, attrs, "y")
    t = float(attrs.get("time", math.nan))
    d = float(attrs.get("shear_offset", 0.0))
    if "rho_p" in arrays:
        rho = np.asarray(arrays["rho_p"], dtype=np.float64)
        if rho.ndim != 3:
            raise UserError(f"rho_p has shape {rho.shape}: expected (nz, ny, nx)")
        if rho.shape[1] < 2 or rho.shape[2] < 2:
            raise UserError(f"rho_p has shape {rho.shape}: the x-y plane needs at least 2 cells on each axis")
        return SurfaceDensity(rho.sum(axis=0), lx, ly, d, t, "rho_p")
    if "particles/pos" in arrays:
        pos = np.asarray(arrays["particles/pos"], dtype=np.float64)
        mass = np.asarray(arrays.get("particles/mass", np.ones(pos.shape[1])), dtype=np.float64)
        x = np.asarray(arrays.get("x", []), dtype=np.float64)
        y = np.asarray(arrays.get("y", []), dtype=np.float64)
        if x.size < 2 or y.size < 2:
            raise UserError("particle snapshot without x and y cell centres: cannot bin the surface density")
        x0, y0 = x[0] - 0.5 * lx / x.size, y[0] - 0.5 * ly / y.size
        sigma, _, _ = np.histogram2d(np.mod(pos[1] - y0, ly), np.mod(pos[0] - x0, lx), bins=(y.size, x.size),
                                     range=((0.0, ly), (0.0, lx)), weights=mass)
        return SurfaceDensity(sigma, lx, ly, d, t, "particles")
    raise UserError("snapshot holds no dust: expected a 'rho_p' field or 'particles/pos'")


def dominant_wavevector(sd: SurfaceDensity, exclude_axisymmetric: bool = True) -> dict[str, float]:
    """Strongest Fourier mode of δΣ = Σ/⟨Σ⟩ − 1 (k = 0 excluded; ``exclude_axisymmetric``: also
    k_y = 0). Returns ``kx, ky`` (code units: 2π/length; of ±k the one with k_y > 0), ``angle_deg``, ``amplitude`` (of δΣ) and
    ``mean_angle_deg``, the power-weighted axial mean of θ_k over the modes with at least a tenth
    of the strongest one's power."""
    sigma = sd.sigma
    ny, nx = sigma.shape
    mean = sigma.mean()
    if not mean > 0:
        raise UserError("the dust surface density is zero everywhere")
    f = np.fft.fft(sigma / mean - 1.0, axis=0)  # along y
    ky = 2 * np.pi * np.fft.fftfreq(ny, d=sd.ly / ny)
    if sd.shear_offset:
        x = (np.arange(nx) + 0.5) * sd.lx / nx
        f = f * np.exp(-1j * np.outer(ky, sd.shear_offset * x / sd.lx))
    f = np.fft.fft(f, axis=1) / (nx * ny)
    kxp = 2 * np.pi * np.fft.fftfreq(nx, d=sd.lx / nx)
    KY, KXP = np.meshgrid(ky, kxp, indexing="ij")
    KX = KXP + KY * sd.shear_offset / sd.lx
    power = np.abs(f) ** 2
    power[0, 0] = 0.0
    if exclude_axisymmetric:
        power[0, :] = 0.0
    if not np.any(power > 0):
        raise UserError("the dust surface density has no non-axisymmetric Fourier mode")
    j, i = np.unravel_index(np.argmax(power), power.shape)
    kx, ky_ = float(KX[j, i]), float(KY[j, i])
    if ky_ < 0 or (ky_ == 0 and kx < 0):  # k and -k are the same real wave: report k_y >= 0
        kx, ky_ = -kx, -ky_
    theta = np.arctan2(KY, KX)
    strong = power >= 0.1 * power[j, i]
    w = power[strong]
    mean2 = math.atan2(float(np.sum(w * np.sin(2 * theta[strong]))), float(np.sum(w * np.cos(2 * theta[strong]))))
    return {"kx": kx, "ky": ky_, "angle_deg": float(_axial(math.degrees(theta[j, i]))),
            "amplitude": float(2.0 * math.sqrt(power[j, i])), "mean_angle_deg": float(_axial(math.degrees(mean2) / 2))}


def _axial(deg: float) -> float:
    """An angle in (−90°, 90°]."""
    while deg > 90.0:
        deg -= 180.0
    while deg <= -90.0:
        deg += 180.0
    return deg


def angle_history(run: str | Path, exclude_axisymmetric: bool = True) -> dict[str, np.ndarray]:
    """θ_k(t) of every snapshot of ``run``: arrays ``time, kx, ky, angle_deg, amplitude, mean_angle_deg``."""
    from ..io.hdf5 import read_h5
    from ..io.rundir import RunDirectory

    snaps = RunDirectory(run).require_snapshots(" (the run must write snapshots holding the dust)")
    rows = []
    for path in snaps:
        arrays, attrs = read_h5(path)
        sd = surface_density(arrays, attrs)
        rows.append({"time": sd.time, **dominant_wavevector(sd, exclude_axisymmetric)})
    return {key: np.array([r[key] for r in rows]) for key in rows[0]}
