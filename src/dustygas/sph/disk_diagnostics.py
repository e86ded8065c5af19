"""History entries of a disk run: dust rings, the gas around them, and tracked gas particles.

Computed by the engine at every history row (the run loop writes them to ``history.h5``) so that
the analysis (:mod:`dustygas.analysis.disk`) works from the run directory alone:

* ring ``k`` (dust particles with ``extra/ring == k``): mean and standard deviation of the
  cylindrical radius :math:`R`, of :math:`v_R`, of :math:`v_\\phi - v_K(R)` and of :math:`v_z`, and the
  mean height -- columns ``ring{k}_mean_R``, ``ring{k}_std_vR``, ... (thesis Figs 3.7-3.9, 3.13-3.16);
* the gas in the ring's annulus :math:`|R - \\bar R_k| < w H(\\bar R_k)`, :math:`|z| < H`: the same moments
  (``ring{k}_gas_*``; the gas dispersion of Fig. 3.9, and :math:`\\bar v_R` and :math:`\\bar v_\\phi` for
  the drift law eq. 3.23 with the disk's own :math:`\\eta` and :math:`v_{r,g}`);
* tracked gas particle ``j`` (``extra/track == j``): its :math:`R` and :math:`z` (Fig. 3.10).

Velocity dispersions are taken about the local Keplerian rotation :math:`v_K(R)` of each particle
(the azimuthal shear across the annulus is not counted as dispersion).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .disk import DiskModel, cylindrical
from .particles import GAS

__all__ = ["DiskDiagnostics", "RING", "TRACK"]

RING = "ring"
TRACK = "track"


@dataclass(frozen=True)
class DiskDiagnostics:
    """Ring, annulus and track entries of the history (module docstring).

    Attributes
    ----------
    disk
        The disk model (Keplerian velocity, scale height).
    n_rings, n_tracks
        Number of dust rings and of tracked gas particles.
    annulus
        Half-width of the gas annulus around each ring, in scale heights.
    """

    disk: DiskModel
    n_rings: int = 0
    n_tracks: int = 0
    annulus: float = 1.0

    @staticmethod
    def _moments(prefix: str, R, vR, dvphi, z, vz, row: dict) -> None:
        n = R.size
        row[f"{prefix}_n"] = float(n)
        for name, x in (("R", R), ("vR", vR), ("dvphi", dvphi), ("z", z), ("vz", vz)):
            row[f"{prefix}_mean_{name}"] = float(x.mean()) if n else 0.0
            row[f"{prefix}_std_{name}"] = float(x.std()) if n else 0.0

    def __call__(self, engine, row: dict) -> None:
        p = engine.particles
        ex = p.extra
        if not (self.n_rings or self.n_tracks):
            return
        R, _, vR, vphi = cylindrical(p.pos, p.vel)
        dvphi = vphi - self.disk.v_kepler(R)
        z, vz = p.pos[:, 2], p.vel[:, 2]
        gas = p.ptype == GAS
        for k in range(self.n_rings):
            sel = ex[RING] == k
            self._moments(f"ring{k}", R[sel], vR[sel], dvphi[sel], z[sel], vz[sel], row)
            Rk = row[f"ring{k}_mean_R"]
            H = float(self.disk.scale_height(Rk))
            band = gas & (np.abs(R - Rk) < self.annulus * H) & (np.abs(z) < H)
            self._moments(f"ring{k}_gas", R[band], vR[band], dvphi[band], z[band], vz[band], row)
            row[f"ring{k}_gas_mean_vphi"] = float(vphi[band].mean()) if band.any() else 0.0
        for j in range(self.n_tracks):
            sel = np.flatnonzero(ex[TRACK] == j)
            row[f"track{j}_R"] = float(R[sel[0]]) if sel.size else 0.0  # 0: accreted
            row[f"track{j}_z"] = float(z[sel[0]]) if sel.size else 0.0
