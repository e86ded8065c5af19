"""Disk runs: dust-ring drift and dispersion, gas random walk, resolution (thesis §3.3.1-3.3.3, Figs 3.6-3.16).

Everything is read from a run directory of the ``sph-disk`` problems (``drift-ring``,
``drift-ring-split``, ...): ``config.toml`` (the disk model), ``history.h5`` (the ring, annulus
and track columns of :mod:`dustygas.sph.disk_diagnostics`) and the snapshots.

The analytic drift is thesis eq. 3.23 (:func:`dustygas.physics.disk.radial_drift_velocity`),
:math:`v_r = (\\tau_s^{-1}v_{r,g} - \\eta v_K)/(\\tau_s + \\tau_s^{-1})`, evaluated at the ring's mean radius
in two ways:

* *set-up*: :math:`\\eta` of eq. 3.24 from the disk model and :math:`v_{r,g} = 0`;
* *disk*: the disk's own gas, :math:`\\eta = 1 - (\\bar v_{\\phi,g}/v_K)^2` (eq. 3.25 inverted) and
  :math:`v_{r,g} = \\bar v_{R,g}` measured in the annulus around the ring -- what the dust actually
  feels when the SPH gas does not rotate as the analytic disk does.

Times are given in orbital periods at the ring's mean radius (as in the thesis's figures).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..config import load_toml
from ..errors import UserError
from ..io.rundir import RunDirectory
from ..physics.disk import radial_drift_velocity
from ..sph.disk import DiskModel, cylindrical
from ..sph.particles import GAS

__all__ = ["RingSeries", "disk_config", "disk_of", "grain_stokes", "ring_series", "mean_drift", "gas_tracks", "ring_positions",
           "midplane_positions", "spacing_profile", "surface_density_profile"]


def disk_config(run: str | Path) -> dict:
    """The ``config.toml`` of a disk run (a one-line error if it is not one)."""
    cfg = load_toml(RunDirectory(run).config_file) if RunDirectory(run).config_file.exists() else None
    if cfg is None or "disk" not in cfg:
        raise UserError(f"{run}: not a run directory of an sph-disk problem (no [disk] in config.toml)")
    return cfg


def grain_stokes(disk: DiskModel, R, taus0: float, R0: float) -> np.ndarray:
    """Midplane Stokes number at ``R`` of grains that have :math:`\\tau_s` = ``taus0`` at ``R0``: the Epstein
    stopping time of a grain of fixed size scales as :math:`1/(\\rho_g c_s)` (thesis eq. 2.6), so
    :math:`\\tau_s \\propto \\Omega/(\\rho_g c_s)`."""
    R = np.asarray(R, dtype=np.float64)
    return taus0 * np.asarray(disk.omega(R) / disk.omega(R0) * disk.density(R0) * disk.sound_speed(R0)
                              / (disk.density(R) * disk.sound_speed(R)))


def disk_of(run: str | Path) -> DiskModel:
    """The :class:`~dustygas.sph.disk.DiskModel` a run was set up with."""
    d = disk_config(run)["disk"]
    return DiskModel(star_mass=d["star_mass"], disk_mass=d["disk_mass"], r_in=d["r_in"], r_out=d["r_out"],
                     p=d["p"], q=d["q"], aspect_ratio=d["aspect_ratio"], r_ref=d["r_ref"])


@dataclass
class RingSeries:
    """Time series of one dust ring and the gas around it (module docstring); velocities in code units."""

    ring: int
    taus: np.ndarray  # Stokes number of the ring's grains at its mean radius
    time: np.ndarray
    orbits: np.ndarray  # time in orbital periods at the ring's mean radius
    mean_R: np.ndarray
    std_R: np.ndarray
    mean_vR: np.ndarray
    std_vR: np.ndarray
    v_kepler: np.ndarray  # at the mean radius
    dust_sigma: dict[str, np.ndarray]  # "R", "phi", "z": velocity dispersions
    gas_sigma: dict[str, np.ndarray]
    gas_mean_vR: np.ndarray
    gas_mean_vphi: np.ndarray
    drift_setup: np.ndarray  # eq. 3.23 with the set-up's eta
    drift_disk: np.ndarray  # eq. 3.23 with the disk's own eta and gas radial velocity
    eta_setup: np.ndarray
    eta_disk: np.ndarray


def ring_series(run: str | Path, ring: int) -> RingSeries:
    """The history of ring ``ring`` of a disk run (module docstring)."""
    cfg = disk_config(run)
    dust = cfg.get("dust", {})
    if not dust.get("enabled") or not 0 <= ring < len(dust.get("ring_radii", [])):
        raise UserError(f"{run}: has no dust ring {ring}")
    hist, _ = RunDirectory(run).read_history()
    disk = disk_of(run)
    pre = f"ring{ring}"
    R = hist[f"{pre}_mean_R"]
    vK = np.asarray(disk.v_kepler(R))
    taus = grain_stokes(disk, R, float(dust["ring_taus"][ring]), float(dust["ring_radii"][ring]))
    eta_setup = np.asarray(disk.eta(R))
    vphi_g = hist[f"{pre}_gas_mean_vphi"]
    eta_disk = 1.0 - (vphi_g / vK) ** 2
    vr_g = hist[f"{pre}_gas_mean_vR"]
    sig = {c: hist[f"{pre}_std_{k}"] for c, k in (("R", "vR"), ("phi", "dvphi"), ("z", "vz"))}
    gsig = {c: hist[f"{pre}_gas_std_{k}"] for c, k in (("R", "vR"), ("phi", "dvphi"), ("z", "vz"))}
    t = hist["time"]
    return RingSeries(ring, taus, t, t / np.asarray(disk.orbital_period(R)), R, hist[f"{pre}_std_R"],
                      hist[f"{pre}_mean_vR"], hist[f"{pre}_std_vR"], vK, sig, gsig, vr_g, vphi_g,
                      radial_drift_velocity(taus, eta_setup, vK), radial_drift_velocity(taus, eta_disk, vK, vr_g),
                      eta_setup, eta_disk)


def mean_drift(series: RingSeries, orbits: tuple[float, float] = (0.0, 3.0)) -> dict[str, float]:
    """Mean radial drift over a window of orbits: measured (least-squares slope of the mean radius),
    and eq. 3.23 with the set-up's and with the disk's :math:`\\eta` averaged over the same window."""
    sel = (series.orbits >= orbits[0]) & (series.orbits <= orbits[1])
    if sel.sum() < 3:
        raise UserError(f"ring {series.ring}: fewer than three history rows within {orbits} orbits")
    slope = float(np.polyfit(series.time[sel], series.mean_R[sel], 1)[0])
    return {"measured": slope, "setup": float(series.drift_setup[sel].mean()),
            "disk": float(series.drift_disk[sel].mean()), "eta_setup": float(series.eta_setup[sel].mean()),
            "eta_disk": float(series.eta_disk[sel].mean()), "v_kepler": float(series.v_kepler[sel].mean())}


def gas_tracks(run: str | Path) -> list[dict[str, np.ndarray]]:
    """Paths of the tracked gas particles in the R-z plane: ``time``, ``orbits`` (at the starting
    radius), ``R``, ``z`` and the scale height ``H`` at ``R``."""
    cfg = disk_config(run)
    hist, _ = RunDirectory(run).read_history()
    disk = disk_of(run)
    out = []
    for j in range(len(cfg.get("diagnostics", {}).get("track_radii", []))):
        R, z = hist[f"track{j}_R"], hist[f"track{j}_z"]
        alive = R > 0
        t = hist["time"][alive]
        out.append({"time": t, "orbits": t / float(disk.orbital_period(R[alive][0])), "R": R[alive], "z": z[alive],
                    "H": np.asarray(disk.scale_height(R[alive]))})
    return out


def _snapshot(run, index):
    arrays, attrs = RunDirectory(run).read_snapshot(index)
    return arrays, float(attrs["time"])


def ring_positions(run: str | Path, indices=None) -> list[dict]:
    """Midplane positions of the dust of every ring in the snapshots ``indices`` (default: all):
    ``{"time": t, "rings": {k: (x, y)}}`` per snapshot."""
    files = RunDirectory(run).require_snapshots()
    indices = range(len(files)) if indices is None else indices
    out = []
    for i in indices:
        a, t = _snapshot(run, i)
        ring = a["extra/ring"]
        rings = {int(k): (a["pos"][ring == k, 0], a["pos"][ring == k, 1]) for k in np.unique(ring[ring >= 0])}
        out.append({"time": t, "rings": rings})
    return out


def midplane_positions(run: str | Path, index: int = 0, r_max: float = 60.0):
    """x, y of the gas particles within one smoothing length of the midplane and inside ``r_max``."""
    a, _ = _snapshot(run, index)
    gas = a["ptype"] == GAS
    R = np.hypot(a["pos"][:, 0], a["pos"][:, 1])
    sel = gas & (np.abs(a["pos"][:, 2]) < a["h"]) & (R < r_max)
    return a["pos"][sel, 0], a["pos"][sel, 1]


def spacing_profile(run: str | Path, edges: np.ndarray, index: int = 0) -> np.ndarray:
    """Mean particle spacing :math:`l = (m/\\rho)^{1/3}` of the gas in cylindrical-radius bins ``edges``."""
    a, _ = _snapshot(run, index)
    gas = a["ptype"] == GAS
    R = np.hypot(a["pos"][gas, 0], a["pos"][gas, 1])
    l = (a["mass"][gas] / a["rho"][gas]) ** (1.0 / 3.0)
    k = np.digitize(R, edges) - 1
    ok = (k >= 0) & (k < len(edges) - 1)
    s = np.bincount(k[ok], weights=l[ok], minlength=len(edges) - 1)
    n = np.bincount(k[ok], minlength=len(edges) - 1)
    return np.where(n > 0, s / np.maximum(n, 1), np.nan)


def surface_density_profile(run: str | Path, edges: np.ndarray, index: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Gas surface density in annuli ``edges`` (mass over area) and its mean rotation :math:`\\bar v_\\phi/v_K`."""
    a, _ = _snapshot(run, index)
    gas = a["ptype"] == GAS
    R, _, _, vphi = cylindrical(a["pos"][gas], a["vel"][gas])
    m = a["mass"][gas]
    k = np.digitize(R, edges) - 1
    ok = (k >= 0) & (k < len(edges) - 1)
    mass = np.bincount(k[ok], weights=m[ok], minlength=len(edges) - 1)
    vrel = np.bincount(k[ok], weights=(m * vphi * np.sqrt(R / disk_of(run).star_mass))[ok], minlength=len(edges) - 1)
    return mass / (np.pi * np.diff(edges**2)), np.where(mass > 0, vrel / np.maximum(mass, 1e-300), np.nan)


