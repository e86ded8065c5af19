"""Analyses of the dust in stratified particle runs (thesis §4.5, Figs 1.10, 1.13, 4.7-4.10).

Pure functions of arrays, then readers that apply them to a run directory:

* :func:`surface_density` -- ``Σ_d(x, y) = ∫ ρ_p dz`` from a snapshot's dust density;
* :func:`fourier_power` and :func:`dominant_wavevector` -- the 2D FFT ``|Σ̂_d(k_x, k_y)|`` of the
  surface density (its mean removed) and the wave vector of its largest peak, with the angle
  ``θ_k = arctan(k_y / k_x)`` of the pattern in the ``k_x``-``k_y`` plane (Fig 4.10;
  ``θ_k = 0`` is axisymmetric, stripes along y; the sign of ``k`` is folded so that
  ``k_x >= 0``, and ``θ_k ∈ (-90°, 90°]``);
* :func:`density_cdf` -- the cumulative distribution of the dust density: the fraction of the
  dust mass in cells denser than ``ρ`` (Johansen & Youdin 2007; Bai & Stone 2010a, Fig 8);
* :func:`scale_height` -- the particle scale height ``H_p = sqrt(<(z - z̄)²>)`` (mass-weighted
  standard deviation of the heights; the ``σ`` of a Gaussian layer), per species;
* :func:`slab` -- the particles within ``δ`` of a plane (the midplane ``|z| < δ`` of Fig 4.8, the
  azimuthal slab ``|y| < δ`` of Fig 4.9, the boundary slabs of Fig 4.7), with the dust density
  of the cell each one sits in for the colours.

Time series (maximum dust density, scale heights and velocity dispersions per species) come
from the run's history, which the particle engine writes at every ``run.dt_history``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import UserError
from ..io.rundir import RunDirectory

__all__ = ["ORBIT", "surface_density", "fourier_power", "dominant_wavevector", "density_cdf", "scale_height", "slab",
           "Snapshot", "read_snapshot", "read_series", "midplane_density"]

#: orbital period in code units (Ω = 1)
ORBIT = 2.0 * math.pi


def surface_density(rho_p: np.ndarray, dz: float) -> np.ndarray:
    """``Σ_d[j, i] = Σ_k ρ_p[k, j, i] Δz`` of a dust density ``(nz, ny, nx)``.

    >>> surface_density(np.ones((4, 2, 3)), 0.25).tolist()
    [[1.0, 1.0, 1.0], [1.0, 1.0, 1.0]]
    """
    return np.asarray(rho_p).sum(axis=0) * dz


def fourier_power(sigma: np.ndarray, lx: float, ly: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``|Σ̂(k_x, k_y)|`` of ``Σ - <Σ>`` (``(ny, nx)``, numpy's FFT normalised by the number of cells,
    so a mode ``A cos(k·x)`` shows ``A/2`` at ``±k``) and the wave numbers ``k_x`` ``(nx,)``,
    ``k_y`` ``(ny,)`` in radians per length, both fft-shifted (zero in the middle)."""
    sigma = np.asarray(sigma, dtype=np.float64)
    ny, nx = sigma.shape
    amp = np.abs(np.fft.fft2(sigma - sigma.mean())) / sigma.size
    kx = 2 * np.pi * np.fft.fftfreq(nx, lx / nx)
    ky = 2 * np.pi * np.fft.fftfreq(ny, ly / ny)
    return np.fft.fftshift(amp), np.fft.fftshift(kx), np.fft.fftshift(ky)


def dominant_wavevector(amp: np.ndarray, kx: np.ndarray, ky: np.ndarray) -> tuple[float, float, float]:
    """``(k_x, k_y, θ_k in degrees)`` of the largest ``amp`` off ``k = 0`` (module docstring).

    >>> kx = ky = np.fft.fftshift(2 * np.pi * np.fft.fftfreq(8, 1 / 8))
    >>> a = np.zeros((8, 8)); a[4 + 1, 4 + 2] = 1.0   # k_y = 2 pi, k_x = 4 pi
    >>> [round(v, 6) for v in dominant_wavevector(a, kx, ky)]
    [12.566371, 6.283185, 26.565051]
    """
    a = np.array(amp, dtype=np.float64)
    j0, i0 = np.argmin(np.abs(ky)), np.argmin(np.abs(kx))
    a[j0, i0] = -np.inf
    j, i = np.unravel_index(np.argmax(a), a.shape)
    kxv, kyv = float(kx[i]), float(ky[j])
    if kxv < 0 or (kxv == 0 and kyv < 0):
        kxv, kyv = -kxv, -kyv
    theta = 90.0 if kxv == 0 else math.degrees(math.atan(kyv / kxv))
    return kxv, kyv, theta


def density_cdf(rho: np.ndarray, thresholds: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Fraction of the dust mass in cells with density ``>= ρ``, at ``thresholds`` (default: the
    sorted cell densities): ``P(>ρ) = Σ_{ρ_c >= ρ} ρ_c / Σ ρ_c`` (equal cells).

    >>> r, p = density_cdf(np.array([1.0, 1.0, 2.0]))
    >>> r.tolist(), p.tolist()
    ([1.0, 2.0], [1.0, 0.5])
    """
    rho = np.asarray(rho, dtype=np.float64).ravel()
    rho = rho[rho > 0]
    order = np.sort(rho)
    if thresholds is None:
        thresholds = np.unique(order)
    thresholds = np.asarray(thresholds, dtype=np.float64)
    tail = np.cumsum(order[::-1])[::-1]  # tail[i] = sum of order[i:]
    idx = np.searchsorted(order, thresholds, side="left")
    frac = np.where(idx < len(order), tail[np.minimum(idx, len(order) - 1)], 0.0) / order.sum()
    return thresholds, frac


def scale_height(z: np.ndarray, mass: np.ndarray | None = None) -> float:
    """``H_p = sqrt(Σ m (z - z̄)² / Σ m)`` (the same moment the engine's history records).

    >>> round(scale_height(np.array([-1.0, 1.0])), 12)
    1.0
    """
    z = np.asarray(z, dtype=np.float64)
    m = np.ones_like(z) if mass is None else np.asarray(mass, dtype=np.float64)
    zm = float(m @ z) / float(m.sum())
    return float(np.sqrt(float(m @ (z - zm) ** 2) / float(m.sum())))


def slab(pos: np.ndarray, axis: int, center: float, half_width: float) -> np.ndarray:
    """Boolean mask of the particles with ``|pos[axis] - center| < half_width``."""
    return np.abs(np.asarray(pos)[axis] - center) < half_width


def midplane_density(total_dust_mass: float, area: float, hp: np.ndarray) -> np.ndarray:
    """Mean midplane dust density ``Σ_p / (√(2π) H_p)`` of a Gaussian layer of scale height ``H_p``."""
    return total_dust_mass / area / (math.sqrt(2 * math.pi) * np.asarray(hp, dtype=np.float64))


@dataclass
class Snapshot:
    """What the stratified analyses need from a snapshot of a particle run."""

    time: float
    rho_p: np.ndarray  # (nz, ny, nx)
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    box: tuple[float, float, float]
    pos: np.ndarray  # (3, N)
    vel: np.ndarray
    species: np.ndarray
    mass: np.ndarray

    @property
    def dx(self) -> tuple[float, float, float]:
        return tuple(L / len(c) if len(c) > 1 else 1.0 for L, c in zip(self.box, (self.x, self.y, self.z)))

    def particle_density(self) -> np.ndarray:
        """The dust density of the cell holding each particle (for colouring scatter plots)."""
        idx = []
        for a, c in enumerate((self.x, self.y, self.z)):
            if len(c) == 1:
                idx.append(np.zeros(self.pos.shape[1], dtype=int))
                continue
            lo = c[0] - 0.5 * (c[1] - c[0])
            d = c[1] - c[0]
            idx.append(np.clip(((self.pos[a] - lo) / d).astype(int), 0, len(c) - 1))
        return self.rho_p[idx[2], idx[1], idx[0]]


def read_snapshot(run: str | Path, index: int = -1) -> Snapshot:
    """A snapshot of a particle run (default the newest)."""
    arrays, attrs = RunDirectory(run).read_snapshot(index)
    if "rho_p" not in arrays or "particles/pos" not in arrays:
        raise UserError(f"{run}: not a particle run (its snapshots hold no rho_p)")
    return Snapshot(float(attrs["time"]), arrays["rho_p"], arrays["x"], arrays["y"], arrays["z"],
                    (float(attrs["lx"]), float(attrs["ly"]), float(attrs["lz"])), arrays["particles/pos"],
                    arrays["particles/vel"], arrays["particles/species"], arrays["particles/mass"])


def read_series(run: str | Path) -> dict[str, np.ndarray]:
    """The run's history columns (time in code units)."""
    cols, _ = RunDirectory(run).read_history()
    if "rho_p_max" not in cols:
        raise UserError(f"{run}: its history has no rho_p_max (not a stratified particle run)")
    return cols
