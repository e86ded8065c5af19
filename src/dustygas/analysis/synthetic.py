"""Synthetic particle snapshots with known clumps, to validate the clump finder and the mass function.

:func:`plummer_sphere` samples a Plummer (1911) sphere; :func:`planted_clumps` scatters such
spheres in a uniform, noisy background of a shearing box (a clump near a radial face wraps into
the sheared image, as a simulation's particles do); :func:`write_snapshot_run` writes the
result as a run directory whose snapshot the analysis reads like a simulation's.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["plummer_sphere", "PlantedClumps", "planted_clumps", "write_snapshot_run"]


def plummer_sphere(n: int, mass: float, scale: float, G: float, rng: np.random.Generator,
                   coldness: float = 0.5) -> tuple[np.ndarray, np.ndarray]:
    """Positions and velocities ``(3, n)`` of a Plummer sphere about the origin.

    Radii from the cumulative mass ``M(<r)/M = r³/(r² + a²)^{3/2}`` (inverted:
    ``r = a (u^{-2/3} - 1)^{-1/2}``), isotropic directions; velocities isotropic Gaussian with
    the local dispersion of the Jeans equilibrium, ``σ² = G M / (6 (r² + a²)^{1/2})``, times
    ``coldness`` (1: equilibrium; less: colder, every particle more deeply bound).
    """
    u = rng.uniform(1e-12, 1.0, n)
    r = scale / np.sqrt(u ** (-2.0 / 3.0) - 1.0)
    direction = rng.normal(size=(3, n))
    direction /= np.linalg.norm(direction, axis=0)
    sigma = np.sqrt(coldness * G * mass / (6.0 * np.sqrt(r * r + scale * scale)))
    return r * direction, sigma * rng.normal(size=(3, n))


@dataclass
class PlantedClumps:
    """Particles of a synthetic snapshot and the truth: ``clump[i]`` is the planted clump of
    particle ``i`` (-1: background)."""

    pos: np.ndarray
    vel: np.ndarray
    mass: np.ndarray
    clump: np.ndarray
    centres: np.ndarray  # (k, 3)
    masses: np.ndarray  # (k,)
    box: tuple[float, float, float]
    shear_offset: float


def planted_clumps(centres, masses, *, box, G, shear_offset, particles_per_clump, background_density,
                   background_particles, hill_fraction=0.05, q=1.5, omega=1.0, noise=0.01,
                   seed=0) -> PlantedClumps:
    """Plummer spheres of ``masses`` at ``centres`` ``(k, 3)`` in a uniform background.

    Each sphere has the scale ``a = hill_fraction r_H`` and moves with the shear at its centre,
    ``v_y = -qΩx_c``; the background particles are uniform, moving with the shear plus Gaussian
    ``noise``. Particles outside the box radially re-enter through the sheared image
    (``(x ∓ L_x, y ± s)``, ``v_y ± qΩL_x``); those beyond the z faces are dropped.
    """
    from ..physics.gravity import hill_radius

    rng = np.random.default_rng(seed)
    lx, ly, lz = box
    pos, vel, mass, tag = [], [], [], []
    for k, (c, m) in enumerate(zip(np.asarray(centres, dtype=np.float64), masses)):
        scale = hill_fraction * float(hill_radius(m, G, omega, q))
        p, v = plummer_sphere(particles_per_clump, m, scale, G, rng)
        p += c[:, None]
        v[1] += -q * omega * c[0]
        pos.append(p)
        vel.append(v)
        mass.append(np.full(particles_per_clump, m / particles_per_clump))
        tag.append(np.full(particles_per_clump, k))
    nb = int(background_particles)
    p = rng.uniform(-0.5, 0.5, (3, nb)) * np.array(box)[:, None]
    v = noise * rng.normal(size=(3, nb))
    v[1] += -q * omega * p[0]
    pos.append(p)
    vel.append(v)
    mass.append(np.full(nb, background_density * lx * ly * lz / nb))
    tag.append(np.full(nb, -1))
    pos, vel, mass, tag = (np.concatenate(a, axis=-1) for a in (pos, vel, mass, tag))
    n = np.floor((pos[0] + 0.5 * lx) / lx)
    pos[0] -= n * lx
    pos[1] += n * shear_offset
    vel[1] += n * q * omega * lx
    pos[1] = (pos[1] + 0.5 * ly) % ly - 0.5 * ly
    keep = np.abs(pos[2]) < 0.5 * lz
    return PlantedClumps(pos[:, keep], vel[:, keep], mass[keep], tag[keep], np.asarray(centres, dtype=np.float64),
                         np.asarray(masses, dtype=np.float64), tuple(box), float(shear_offset))


def write_snapshot_run(path: str | Path, planted: PlantedClumps, *, cells: tuple[int, int, int], G: float,
                       q: float = 1.5, omega: float = 1.0, time: float = 0.0) -> Path:
    """A run directory holding one snapshot of ``planted`` in the particle engine's layout."""
    from ..io.rundir import RunDirectory

    run = RunDirectory(path)
    run.create(overwrite=True)
    run.write_config('problem = "synthetic-clumps"\n')
    lx, ly, lz = planted.box
    n = planted.mass.size
    arrays = {"particles/pos": planted.pos, "particles/vel": planted.vel, "particles/mass": planted.mass,
              "particles/pid": np.arange(n, dtype=np.int64), "particles/species": np.zeros(n, dtype=np.int32),
              "x": -0.5 * lx + (np.arange(cells[0]) + 0.5) * lx / cells[0],
              "y": -0.5 * ly + (np.arange(cells[1]) + 0.5) * ly / cells[1],
              "z": -0.5 * lz + (np.arange(cells[2]) + 0.5) * lz / cells[2]}
    attrs = {"lx": lx, "ly": ly, "lz": lz, "q": q, "omega": omega, "shear_offset": planted.shear_offset,
             "orbital_advection": False, "gravity_G": G, "time": time, "cycle": 0, "problem": "synthetic-clumps"}
    run.write_snapshot(0, arrays, attrs)
    return run.path
