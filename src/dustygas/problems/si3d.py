"""``si3d``: the non-linear streaming instability in a stratified shearing box (thesis §4.3-4.5).

The box of thesis Figs 4.7-4.10 (and of Athena's ``par_strat3d``, Bai & Stone 2010b): x
radial and shear-periodic, y azimuthal and periodic, z vertical; units ``Ω = c_s = H = 1``,
midplane gas density ``ρ_0 = 1``. The gas is the isothermal column ``ρ = ρ_0 e^{-φ/c_s²}`` at
rest in the box of Athena's ``par_strat3d`` that made the thesis's figure, periodic in z: the
tidal potential ``φ = Ω² z²/2`` flattened within the ghost depth of the faces so that it is
periodic and smooth (:func:`~dustygas.grid.shearing_box.periodic_tidal_potential`); the
particles keep ``-Ω² z`` (they never come near the faces). ``problem.gas_boundary_z =
"hydrostatic"`` gives instead open faces that keep the column ``ρ_0 e^{-z²/2H²}`` at rest
(:mod:`dustygas.grid.boundaries`), with the particles leaving through them
(``particles.boundary_z = "auto"``). Once the dust pushes it, the gas column flows through
such open faces as a whole (Li, Youdin & Simon 2018, ApJ 862, 14, report the same of outflow
boundaries): up to 0.06 c_s in the 2D box at 160/H, which carries the layer up to 0.05 H off
the midplane and keeps it several cells thicker than in the periodic box.
The gas feels the global radial pressure gradient ``2 η v_K Ω x̂`` with
``η v_K = Π c_s``. Particles of one or more species (stopping times ``τ_s``, fixed) feel the
rotating frame and vertical gravity; they start uniformly in x and y and Gaussian in z with
scale height ``H_p``, with the multi-species NSH drift of the local dust-to-gas ratio at their
height (Bai & Stone 2010b, eqs. 6-9; Athena's ``ipert = 0``), and the gas cells with the gas's.
The dust mass is ``Z`` times the gas column ``Σ_g = √(2π) ρ_0 H``, split between species in
proportion to ``τ_s^mass_power``.

Presets
-------
``si3d`` (default, a laptop)
    thesis Fig 4.7 physics -- ``τ_s = 1``, ``Z = 0.03``, ``Π = 0.05``, box ``0.2 × 0.2 × 0.3 H`` --
    at 32 × 32 × 48 cells and one particle per cell, for 30 orbits. At this resolution (160 cells
    per H) the settled τ_s = 1 layer is about one cell thick, in Athena 4.2 as in dustygas
    (``benchmarks/compare_layer.py``; benchmarks/RESULTS.md, 2026-12-04): the preset shows the
    non-linear state, not a converged layer.
``si3d-thesis``
    exactly thesis Fig 4.7: 256 × 256 × 384 cells, 1.8e7 particles (``dustygas run si3d-thesis
    --dry-run`` prints its memory and cost).
``si3d-bs10b``
    seven species, ``τ_s`` log-spaced from 1e-4 to 0.1 with mass ``∝ τ_s^{1/2}`` per
    logarithmic bin, ``Z = 0.03`` (the size distributions of Bai & Stone 2010b).

The unstratified non-linear runs of Johansen & Youdin (2007) are :mod:`dustygas.problems.si_ab`.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError, SetupError
from ..grid import GridEngine, Mesh
from ..grid.params import GRID
from ..particles import ParticleStore, RotatingFrame, VerticalGravity
from ..particles.boundaries import make_particle_boundaries
from ..particles.params import PARTICLES, particle_boundaries, particle_engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, preset, register
from .si_linear import SI_SCHEME

__all__ = ["SI3D", "resources", "nsh_profile"]

ORBIT = 2.0 * math.pi
#: bytes per particle the engine holds (store, sort, weights, deposit values, image share)
BYTES_PER_PARTICLE = 330
#: bytes per cell and field column of the particle side (trajectory, deposits, filter copies)
BYTES_PER_FIELD = 8


def nsh_profile(z: np.ndarray, taus, masses, Hp, Pi: float):
    """NSH velocities (gas ``(ux, uy)`` and dust ``(vx, vy)`` per species, relative to the shear)
    at heights ``z`` for Gaussian layers of column ``masses[s]`` (in units of ``Σ_g``) and scale
    height ``Hp[s]`` in the isothermal column (Bai & Stone 2010b eqs. 6-9, as Athena's
    ``par_strat3d``)."""
    from ..physics import nsh_velocities_multi

    z = np.atleast_1d(z)
    taus = np.asarray(taus, dtype=np.float64)
    eps = np.stack([m / h * np.exp(-0.5 * z**2 * (1.0 / h**2 - 1.0)) for m, h in zip(masses, Hp)], axis=-1)
    eq = nsh_velocities_multi(np.broadcast_to(taus, eps.shape), eps, Pi)
    return eq


def resources(cfg) -> dict:
    """Memory (bytes) and cost (zone-cycles, particle-updates to ``run.tlim``) of a configuration,
    computed without allocating anything."""
    g, p = cfg.grid, cfg.problem
    shape = (g.nx, g.ny, g.nz)
    active = [n > 1 for n in shape]
    ncell = int(np.prod(shape))
    padded = int(np.prod([n + 6 if a else 1 for n, a in zip(shape, active)]))
    nsp = len(p.taus)
    npart = int(round(p.per_cell * ncell)) * nsp if p.per_species else int(round(p.per_cell * ncell))
    columns = (10 + 3 * nsp) * 2 + 4 * nsp + 3 * 2 + nsp + 9  # trajectory (+filter copy), deposits, sources
    gas = 2 * 4 * 8 * padded
    mem = gas + columns * BYTES_PER_FIELD * padded + BYTES_PER_PARTICLE * npart
    dx = min(L / n for L, n in zip((g.lx, g.ly, g.lz), shape) if n > 1)
    vmax = 1.0 + 0.5 * p.Pi + (0.0 if cfg.problem.orbital_advection else 1.5 * 0.5 * g.lx)
    steps = int(math.ceil(cfg.run.tlim / (cfg.scheme.cfl * dx / vmax)))
    return {"cells": ncell, "particles": npart, "memory_bytes": int(mem), "steps": steps,
            "zone_cycles": float(steps) * ncell, "particle_updates": float(steps) * npart}


def available_memory() -> int:
    """Physical memory of this machine in bytes (0 if unknown)."""
    try:
        return int(__import__("os").sysconf("SC_PAGE_SIZE") * __import__("os").sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):
        return 0


@register
class SI3D(Problem):
    name = "si3d"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = ("Stratified shearing box, non-linear streaming instability (thesis Fig 4.7 physics at laptop size: "
               "tau_s = 1, Z = 0.03, Pi = 0.05, 32x32x48, 1 ppc).")
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=30 * ORBIT, dt_history=0.1, dt_snapshot=ORBIT, checkpoint_wall=600.0),
        "grid": with_defaults(GRID, nx=32, ny=32, nz=48, lx=0.2, ly=0.2, lz=0.3),
        "scheme": with_defaults(SI_SCHEME, cfl=0.3),
        "particles": PARTICLES,
        "problem": {
            "taus": Param([1.0], "stopping time tau_s = Omega t_s of each species (fixed)", "1/Omega", min=0.0,
                          min_open=True),
            "Z": Param(0.03, "dust-to-gas column ratio Sigma_p / Sigma_g (Sigma_g = sqrt(2 pi) rho_0 H)", min=0.0,
                       min_open=True),
            "mass_power": Param(0.0, "species masses in proportion to tau_s**mass_power"),
            "Pi": Param(0.05, "eta v_K / c_s: the global radial pressure gradient", min=0.0),
            "Hp": Param(0.02, "initial particle scale height (Gaussian in z)", "H", min=0.0, min_open=True),
            "per_cell": Param(1.0, "particles per cell (per species if per_species)", min=0.0, min_open=True),
            "per_species": Param(False, "per_cell counts each species (else all species share it)"),
            "velocities": Param("nsh", "initial velocities: the local multi-species NSH drift, or zero relative to "
                                "the shear", choices=("nsh", "zero")),
            "gas_gravity": Param(True, "vertical gravity on the gas (a hydrostatic column); false: uniform gas"),
            "gas_boundary_z": Param("periodic", "gas boundary along z (periodic: with gas_gravity the potential "
                                    "smoothed at the faces, as Athena's par_strat3d; hydrostatic: open, keeps the "
                                    "column at rest; particles.boundary_z = auto follows: periodic, else outflow)",
                                    choices=("hydrostatic", "reflecting", "outflow", "periodic")),
            "orbital_advection": Param(True, "store velocities relative to the shear and advect by it exactly "
                                       "(FARGO)"),
            "seed": Param(1, "random seed of the particle positions", min=0),
        },
    }

    def validate(self, cfg) -> None:
        g, p = cfg.grid, cfg.problem
        if g.nz == 1:
            raise ConfigError("grid.nz = 1: the stratified box needs an active z axis")
        if 3.0 * p.Hp > 0.5 * g.lz:
            raise ConfigError(f"problem.Hp = {p.Hp:g}: the layer (3 H_p = {3 * p.Hp:g} H) does not fit in the box "
                              f"(grid.lz / 2 = {0.5 * g.lz:g} H); lower problem.Hp or raise grid.lz")
        if not p.gas_gravity and p.gas_boundary_z == "hydrostatic":
            raise ConfigError("problem.gas_boundary_z = 'hydrostatic' needs problem.gas_gravity = true")
        if len(p.taus) > 32:
            raise ConfigError(f"problem.taus has {len(p.taus)} species: at most 32")
        gas_kinds = ("shear-periodic", "periodic", p.gas_boundary_z)
        active = (g.nx > 1, g.ny > 1, True)
        make_particle_boundaries(particle_boundaries(cfg, gas_kinds), gas_kinds, active, 0.0, 0.0,
                                 ("particles.boundary_x", "particles.boundary_y", "particles.boundary_z"))
        res = resources(cfg)
        avail = available_memory()
        if avail and res["memory_bytes"] > 0.8 * avail:
            raise SetupError(f"problem.per_cell = {p.per_cell:g} with grid {g.nx}x{g.ny}x{g.nz}: "
                             f"{res['particles']:.3g} particles and {res['cells']:.3g} cells need "
                             f"{res['memory_bytes'] / 2**30:.1f} GiB, this machine has {avail / 2**30:.1f} GiB")

    def estimate(self, cfg) -> dict:
        return resources(cfg)

    def build(self, cfg):
        g, p, s = cfg.grid, cfg.problem, cfg.scheme
        mesh = Mesh((g.nx, g.ny, g.nz), (g.lx, g.ly, g.lz))
        kinds = ("shear-periodic", "periodic", p.gas_boundary_z)
        gas = GridEngine(mesh, cs=1.0, integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter,
                         riemann=s.riemann, cfl=s.cfl, boundaries=kinds, omega=1.0, q=1.5,
                         orbital_advection=p.orbital_advection, vertical_gravity=p.gas_gravity, eta_vK=p.Pi)
        taus = np.asarray(p.taus, dtype=np.float64)
        nsp = len(taus)
        weights = taus**p.mass_power
        masses = p.Z * weights / weights.sum()  # column of each species in units of Sigma_g
        Hp = np.full(nsp, p.Hp)
        x, y, z = mesh.meshgrid()
        shape = tuple(reversed(mesh.shape))
        rho = np.exp(-gas.tidal_potential(z)) if p.gas_gravity else np.ones_like(z)  # c_s = Omega = 1
        shear = 0.0 if p.orbital_advection else -1.5
        if p.velocities == "nsh":
            eq = nsh_profile(mesh.centers(2), taus, masses, Hp, p.Pi)
            ux = np.asarray(eq.gas_vx)[:, None, None]
            uy = np.asarray(eq.gas_vy)[:, None, None]
        else:
            ux = uy = np.zeros((g.nz, 1, 1))
        gas.set_primitive(np.broadcast_to(rho, shape), np.broadcast_to(ux, shape), uy + shear * x + np.zeros(shape), 0.0)
        # particles: uniform in x, y; Gaussian in z, truncated to the box
        rng = np.random.default_rng(p.seed)
        per = int(round(p.per_cell * mesh.ncells)) if p.per_species else int(round(p.per_cell * mesh.ncells / nsp))
        if per < 1:
            raise SetupError(f"problem.per_cell = {p.per_cell:g}: fewer than one particle per species")
        sigma_g = math.sqrt(2.0 * math.pi)
        pos, vel, species, mass = [], [], [], []
        area = g.lx * (g.ly if g.ny > 1 else 1.0)
        for sp in range(nsp):
            xs = mesh.lower[0] + g.lx * rng.random(per)
            ys = mesh.lower[1] + g.ly * rng.random(per) if g.ny > 1 else np.zeros(per)
            zs = Hp[sp] * rng.standard_normal(per)
            bad = np.abs(zs) >= 0.5 * g.lz
            while np.any(bad):
                zs[bad] = Hp[sp] * rng.standard_normal(int(bad.sum()))
                bad = np.abs(zs) >= 0.5 * g.lz
            v = np.zeros((3, per))
            if p.velocities == "nsh":
                eq = nsh_profile(zs, taus, masses, Hp, p.Pi)
                v[0] = np.asarray(eq.dust_vx)[:, sp]
                v[1] = np.asarray(eq.dust_vy)[:, sp]
            v[1] += shear * xs
            pos.append(np.stack([xs, ys, zs]))
            vel.append(v)
            species.append(np.full(per, sp))
            mass.append(np.full(per, masses[sp] * sigma_g * area / per))
        store = ParticleStore.create(np.concatenate(pos, axis=1), np.concatenate(vel, axis=1),
                                     np.concatenate(species), np.concatenate(mass))
        return particle_engine_from_config(cfg, gas, store, list(taus), particle_terms=self.particle_terms(cfg))

    def particle_terms(self, cfg) -> list:
        """The forces on the particles: the rotating frame and vertical gravity."""
        return [RotatingFrame(1.0, 1.5, relative_to_shear=cfg.problem.orbital_advection), VerticalGravity(1.0)]


preset("si3d-thesis", SI3D, "Thesis Fig 4.7 exactly: 256x256x384 cells, 1.8e7 particles (validate with --dry-run).",
       smoke_overrides=("grid.nx=16", "grid.ny=16", "grid.nz=24"),
       grid={"nx": 256, "ny": 256, "nz": 384}, problem={"per_cell": 1.8e7 / (256 * 256 * 384)},
       run={"tlim": 40 * ORBIT, "dt_snapshot": ORBIT / 4})
preset("si3d-bs10b", SI3D, "Seven species, tau_s log-spaced 1e-4 .. 0.1, mass ~ tau_s^0.5, Z = 0.03 (Bai & Stone 2010b).",
       problem={"taus": [float(t) for t in np.logspace(-4, -1, 7)], "mass_power": 0.5, "per_cell": 1.0})
