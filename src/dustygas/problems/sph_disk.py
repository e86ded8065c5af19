"""``sph-disk`` and ``drift-ring``: a 3D protoplanetary gas disk in SPH, with dust rings (thesis §3.3.1-3.3.3).

The disk of thesis §3.3.1 (:mod:`dustygas.sph.disk`): a 1 M_sun star (a point mass at the origin that
accretes particles within ``disk.accretion_radius``), a gas disk of 5e-3 M_sun with
:math:`\\Sigma \\propto R^{-1}` from 5 to 200 au, :math:`T \\propto R^{-1/2}` with :math:`H/R = 0.05` at
20 au (so :math:`\\eta = 6.9\\times10^{-3}` there, thesis eq. 3.24), locally isothermal, vertically
Gaussian, rotating with its pressure support. ``disk.relax = "rotation"`` (the default) then puts
each gas particle on the circular orbit that balances the SPH forces it feels at the start
(:func:`dustygas.sph.disk.balance_rotation`), which removes the epicyclic ringing of a discrete disk
whose pressure forces differ from the analytic ones (with :math:`10^4` particles :math:`h \\approx 2H` at
20 au); ``"damped"`` first evolves the gas alone for ``disk.relax_orbits`` orbits at ``r_ref`` with its
radial and vertical velocities damped on the local orbital time (:func:`dustygas.sph.disk.relax_disk`).
The thesis used :math:`10^5` gas particles (the ``*-thesis`` presets); the defaults use
:math:`10^4` so that a run takes minutes. Units: au, M_sun, yr/(2 pi) (:data:`dustygas.units.DISK_UNITS`).

Time integration: hierarchical individual time steps with pairwise kicks
(:mod:`dustygas.sph.timesteps`); ``steps.individual = false`` gives one global step. The artificial
viscosity is the linear term alone, :math:`\\alpha = 0.1`, :math:`\\beta = 0`: the quadratic term acts on
the Keplerian shear between neighbours (approaching pairs) and, at :math:`10^4` particles, drains the
disk inside 15 au into the star within three orbits at 20 au (measured: 74 % of the 10-15 au annulus
with :math:`\\beta = 2`, 5 % with :math:`\\beta = 0`).

Dust rings (``dust.enabled``, ``dust.ring_radii``, ``dust.ring_taus``): ``dust.n_ring`` two-fluid dust particles each,
on a midplane circle, of mass ``dust.mass_ratio`` times a gas particle's (so that they barely act on
the gas), with the Epstein grain radius that gives the Stokes number ``ring_taus`` in the midplane
gas at the ring, starting with the steady drift of eq. 3.23 (``dust.drifting``). The drag is the
projected form of thesis eq. 3.19 with the gas particle's kernel :math:`D_{ai}(h_a)`
(``dust.drag_kernel = "gas"``, as eq. 3.19 is written; ``"average"`` is Laibe & Price 2012a), with the
relative velocity taken at the dust particle: the gas velocity is extrapolated there with the gas
particle's SPH velocity gradient (``dust.reconstruction = "gas"``). Without it the Keplerian shear
across a kernel of :math:`h/R \\approx 0.1` enters the relative velocity of every pair and, weighted by
the density gradient, acts as a spurious tailwind: the :math:`\\tau_s = 10` ring at 20 au then hardly
drifts (measured +1e-4 v_K over two orbits instead of the -7e-4 to -9e-4 v_K of eq. 3.23).
``drift-ring`` holds the thesis's rings at 20 au (:math:`\\tau_s` = 1 and 10, Figs 3.6-3.9) and at
52 au (:math:`\\tau_s = 1`, the unsplit curves of Figs 3.13-3.16) in one run, since the rings do not
interact; ``drift-ring-split`` splits the gas in 40-70 au into eight (four and two in 10 au buffers,
:func:`dustygas.sph.splitting.split_band`) around a :math:`\\tau_s = 1` ring at 52 au.

Diagnostics (:mod:`dustygas.sph.disk_diagnostics`): per ring and the gas around it, and the
:math:`R`, :math:`z` of gas particles started nearest to ``diagnostics.track_radii`` in the midplane.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..physics.drag import mean_free_path
from ..runner import RUN_SCHEMA
from ..sph import Box, ExternalForces
from ..sph.disk import DiskModel, balance_rotation, cylindrical, merge_particles, relax_disk, ring_particles
from ..sph.disk_diagnostics import RING, TRACK, DiskDiagnostics
from ..sph.dust.drag_law import DragLaw
from ..sph.dust.two_fluid import DRAG_FORMS, DRAG_INTEGRATIONS, DRAG_KERNELS, TwoFluidOptions
from ..sph.kernels import get_kernel
from ..sph.particles import GAS
from ..sph.schema import SPH_SCHEMA, options_from_config
from ..sph.splitting import split_band
from ..sph.timesteps import BlockStepEngine, BlockStepOptions
from ..units import DISK_UNITS
from . import Problem, preset, register

__all__ = ["SPHDisk", "disk_model", "orbits"]

#: the orbital period at 20 au in code units (2 pi 20^1.5)
ORBIT_20 = 2.0 * math.pi * 20.0**1.5
ORBIT_52 = 2.0 * math.pi * 52.0**1.5


def disk_model(cfg) -> DiskModel:
    """The :class:`~dustygas.sph.disk.DiskModel` of a validated configuration."""
    d = cfg.disk
    return DiskModel(star_mass=d.star_mass, disk_mass=d.disk_mass, r_in=d.r_in, r_out=d.r_out, p=d.p, q=d.q,
                     aspect_ratio=d.aspect_ratio, r_ref=d.r_ref)


def orbits(t, radius: float, star_mass: float = 1.0):
    """Time in orbital periods at ``radius`` (code units)."""
    return np.asarray(t) / (2.0 * math.pi * math.sqrt(radius**3 / star_mass))


@register
class SPHDisk(Problem):
    name = "sph-disk"
    summary = "3D locally isothermal protoplanetary gas disk (5-200 au, 5e-3 M_sun) with optional dust rings, in SPH."
    #: a few cycles of 1e4-1e5 particles (tree, relaxation, deep block levels) take tens of seconds to minutes
    smoke_overrides = ("disk.n_gas=600", "dust.n_ring=16", "steps.max_level=8")
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=10 * ORBIT_20, dt_snapshot=ORBIT_20, log_every=20),
        "sph": with_defaults(SPH_SCHEMA, switch="none", alpha=0.1, alpha_min=0.0, beta=0.0, alpha_u=0.0,
                             neighbour_search="tree", reorder_every=10),
        "disk": {
            "n_gas": Param(10000, "number of gas particles (the thesis: 100000)", min=100),
            "star_mass": Param(1.0, "stellar mass", "M_sun", min=0.0, min_open=True),
            "disk_mass": Param(5e-3, "gas disk mass", "M_sun", min=0.0, min_open=True),
            "r_in": Param(5.0, "inner radius", "au", min=0.0, min_open=True),
            "r_out": Param(200.0, "outer radius", "au", min=0.0, min_open=True),
            "p": Param(1.0, "surface density exponent, Sigma ~ R^-p", min=0.0, max=1.9),
            "q": Param(0.5, "temperature exponent, T ~ R^-q", min=0.0, max=1.0),
            "aspect_ratio": Param(0.05, "H/R at r_ref", min=0.0, max=0.3, min_open=True),
            "r_ref": Param(20.0, "reference radius of the aspect ratio (and of steps.dt_max)", "au", min=0.0,
                           min_open=True),
            "accretion_radius": Param(2.5, "particles closer to the star are accreted", "au", min=0.0),
            "relax": Param("rotation", "set-up relaxation: none; rotation balancing the initial SPH forces; or damped "
                           "evolution of the gas for disk.relax_orbits, then that rotation",
                           choices=("none", "rotation", "damped")),
            "relax_orbits": Param(1.0, "duration of the damped relaxation", "orbits at r_ref", min=0.0, min_open=True),
        },
        "steps": {
            "individual": Param(True, "hierarchical individual time steps (false: one global step)"),
            "dt_max": Param(0.05, "longest block step", "orbits at r_ref", min=0.0, min_open=True),
            "max_level": Param(24, "deepest level of the step hierarchy", min=1, max=40),
            "rebuild_fraction": Param(0.25, "rebuild the k-d tree when this fraction is active (else refit)",
                                      min=0.0, max=1.0, min_open=True),
        },
        "dust": {
            "enabled": Param(False, "add dust rings"),
            "ring_radii": Param([20.0], "radii of the dust rings", "au", type="float_list", min=0.0, min_open=True),
            "ring_taus": Param([1.0], "Stokes number of each ring's grains in the midplane gas at the ring",
                               type="float_list", min=1e-3, max=1e3),
            "n_ring": Param(1000, "dust particles per ring", min=1),
            "mass_ratio": Param(1e-6, "dust particle mass over gas particle mass", min=0.0, max=1.0, min_open=True),
            "grain_density": Param(3.0, "grain material density", "g/cm^3", min=0.0, min_open=True),
            "drifting": Param(True, "start the dust with the steady drift of eq. 3.23 (false: Keplerian)"),
            "form": Param("projected", "drag along the pair (eq. 3.19) or not (eq. 3.18)", choices=DRAG_FORMS),
            "drag_kernel": Param("gas", "drag kernel D_ai(h_a) of the gas particle (eq. 3.19) or the pair average",
                                 choices=DRAG_KERNELS),
            "c_drag": Param(0.9, "explicit-drag time-step factor dt <= c_drag t_s", min=0.0, min_open=True),
            "reconstruction": Param("gas", "relative velocity of a pair: as it is (none), or at the dust particle "
                                    "with the gas velocity extrapolated by the gas's SPH gradient (gas)",
                                    choices=("none", "gas")),
            "integration": Param("explicit", "drag in time: explicit (dt <= c_drag t_s, eq. 2.15) or the pairwise "
                                 "exponential average over the pair step (implicit)", choices=DRAG_INTEGRATIONS),
        },
        "split": {
            "enabled": Param(False, "split the particles of a radial band into eight (thesis §3.3.3)"),
            "r1": Param(40.0, "inner edge of the eight-fold band", "au", min=0.0),
            "r2": Param(70.0, "outer edge of the eight-fold band", "au", min=0.0),
            "buffers": Param([10.0, 10.0], "widths of the four-fold and two-fold buffer zones", "au",
                             type="float_list", min=0.0, length=2),
            "dust": Param(False, "split the dust particles in the band too"),
            "seed": Param(1, "seed of the random split orientations", min=0),
        },
        "diagnostics": {
            "track_radii": Param([10.0, 20.0, 40.0], "start radii of the tracked gas particles (Fig. 3.10)", "au",
                                 type="float_list", min=0.0),
            "annulus": Param(1.0, "half-width of the gas annulus around a ring", "H", min=0.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        d, s, dust = cfg.disk, cfg.split, cfg.dust
        if d.r_in >= d.r_out:
            raise ConfigError(f"disk.r_in = {d.r_in:g} must be smaller than disk.r_out = {d.r_out:g}")
        if d.accretion_radius >= d.r_in:
            raise ConfigError(f"disk.accretion_radius = {d.accretion_radius:g} must be smaller than "
                              f"disk.r_in = {d.r_in:g}")
        if s.enabled and not (d.r_in < s.r1 < s.r2 < d.r_out):
            raise ConfigError(f"split.r1 = {s.r1:g}, split.r2 = {s.r2:g}: the splitting band must lie inside the disk "
                              f"(disk.r_in = {d.r_in:g} < r1 < r2 < disk.r_out = {d.r_out:g})")
        if not dust.enabled:
            return
        if len(dust.ring_taus) != len(dust.ring_radii):
            raise ConfigError(f"dust.ring_taus has {len(dust.ring_taus)} values for {len(dust.ring_radii)} "
                              "dust.ring_radii: give one Stokes number per ring")
        model = disk_model(cfg)
        for R, taus in zip(dust.ring_radii, dust.ring_taus):
            if not d.r_in < R < d.r_out:
                raise ConfigError(f"dust.ring_radii = {R:g} au lies outside the disk ({d.r_in:g}, {d.r_out:g}) au")
            rho_cgs = float(model.density(R)) * DISK_UNITS.density
            size = model.grain_size(taus, R, dust.grain_density / DISK_UNITS.density) * DISK_UNITS.length
            limit = 2.25 * float(mean_free_path(rho_cgs))
            if size > limit:
                raise ConfigError(f"dust.ring_taus = {taus:g} at {R:g} au needs grains of {size:.3g} cm, beyond the "
                                  f"Epstein regime (s < 9/4 mean free path = {limit:.3g} cm); choose a smaller "
                                  "Stokes number")

    def build(self, cfg) -> BlockStepEngine:
        d, dust, s, diag = cfg.disk, cfg.dust, cfg.split, cfg.diagnostics
        opts = options_from_config(cfg.sph)
        model = disk_model(cfg)
        hfact = opts.hfact or get_kernel(opts.kernel, 3).default_hfact
        gas = model.gas_particles(d.n_gas, hfact, alpha=opts.alpha)
        gas.extra[RING] = np.full(len(gas), -1, np.int64)
        gas.extra[TRACK] = np.full(len(gas), -1, np.int64)
        gas.extra["grain_size"] = np.zeros(len(gas))
        R, _ = cylindrical(gas.pos)
        for j, Rt in enumerate(diag.track_radii):
            gas.extra[TRACK][int(np.argmin((R - Rt) ** 2 + gas.pos[:, 2] ** 2))] = j
        if s.enabled:
            gas = split_band(gas, s.r1, s.r2, tuple(s.buffers), s.seed)
        if d.relax == "damped":  # the gas alone settles first; the dust rings are added to the settled disk
            relaxing = self._engine(cfg, model, opts, gas, None, ())
            relax_disk(relaxing, d.relax_orbits * float(model.orbital_period(d.r_ref)), d.star_mass)
            gas = relaxing.particles
        m_gas = d.disk_mass / d.n_gas
        rho_grain = dust.grain_density / DISK_UNITS.density
        sets = [gas]
        rings = list(zip(dust.ring_radii, dust.ring_taus)) if dust.enabled else []
        for k, (Rk, taus) in enumerate(rings):
            spacing = 2.0 * math.pi * Rk / dust.n_ring
            ring = ring_particles(model, dust.n_ring, Rk, dust.mass_ratio * m_gas, taus, hfact * spacing,
                                  drifting=dust.drifting)
            ring.alpha[:] = opts.alpha
            ring.extra[RING] = np.full(len(ring), k, np.int64)
            ring.extra[TRACK] = np.full(len(ring), -1, np.int64)
            ring.extra["grain_size"] = np.full(len(ring), model.grain_size(taus, Rk, rho_grain))
            if s.enabled and s.dust:
                ring = split_band(ring, s.r1, s.r2, tuple(s.buffers), s.seed + 1 + k)
            sets.append(ring)
        particles = merge_particles(*sets) if len(sets) > 1 else sets[0]
        drag = None
        if rings:
            drag = TwoFluidOptions(drag=DragLaw("epstein", grain_density=rho_grain), form=dust.form,
                                   reconstruction=dust.reconstruction, integration=dust.integration, c_drag=dust.c_drag, heating=False,
                                   drag_kernel=dust.drag_kernel)
        diagnostics = DiskDiagnostics(model, n_rings=len(rings), n_tracks=len(diag.track_radii),
                                      annulus=diag.annulus)
        engine = self._engine(cfg, model, opts, particles, drag, (diagnostics,))
        if d.relax != "none":
            engine.timestep()  # one evaluation of every force at t = 0
            p = engine.particles
            balance_rotation(p.pos, p.vel, engine.acc, p.ptype == GAS)
            engine.reset()
        return engine

    @staticmethod
    def _engine(cfg, model, opts, particles, drag, diagnostics) -> BlockStepEngine:
        d, st = cfg.disk, cfg.steps
        steps = BlockStepOptions(individual=st.individual, max_level=st.max_level,
                                 dt_max=st.dt_max * float(model.orbital_period(d.r_ref)),
                                 rebuild_fraction=st.rebuild_fraction)
        return BlockStepEngine(particles, Box.open_box(3), model.eos(), opts,
                               ExternalForces(star_gm=d.star_mass, accretion_radius=d.accretion_radius), drag=drag,
                               steps=steps, diagnostics=diagnostics)


_RINGS = {"enabled": True, "ring_radii": [20.0, 20.0, 52.0], "ring_taus": [1.0, 10.0, 1.0]}
preset("sph-disk-thesis", SPHDisk, "The thesis's gas disk with 1e5 particles.", disk={"n_gas": 100000})
preset("drift-ring", SPHDisk, "Radial-drift rings of two-fluid dust at 20 au (tau_s = 1, 10) and 52 au (tau_s = 1).",
       run={"tlim": 5 * ORBIT_52, "dt_snapshot": ORBIT_20}, dust=_RINGS)
preset("drift-ring-thesis", SPHDisk, "drift-ring with the thesis's 1e5 gas particles.",
       run={"tlim": 5 * ORBIT_52, "dt_snapshot": ORBIT_20}, dust=_RINGS, disk={"n_gas": 100000})
preset("drift-ring-split", SPHDisk, "A tau_s = 1 dust ring at 52 au in a disk split eight-fold in 40-70 au.",
       run={"tlim": 5 * ORBIT_52, "dt_snapshot": ORBIT_52}, dust={"enabled": True, "ring_radii": [52.0], "ring_taus": [1.0]},
       split={"enabled": True})
preset("drift-ring-split-thesis", SPHDisk, "drift-ring-split with the thesis's 1e5 gas particles.",
       run={"tlim": 5 * ORBIT_52, "dt_snapshot": ORBIT_52}, dust={"enabled": True, "ring_radii": [52.0], "ring_taus": [1.0]},
       split={"enabled": True}, disk={"n_gas": 100000})
