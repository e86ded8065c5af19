"""``dust-trap``: the self-induced dust trap of Gonzalez, Laibe & Maddison (2017) in a two-fluid SPH disk.

Gonzalez et al. (2017, MNRAS 467, 1984) proposed that growing grains drifting inward pile up where
their drag back-reaction on the gas, pushing it outward against its viscous inflow, builds a gas
pressure maximum that traps more dust -- a *self-induced* trap. The thesis tried to reproduce it and
could not (§3.4). This problem sets up the experiment with the pieces of :mod:`dustygas.sph`:

* a viscous gas disk (:mod:`dustygas.sph.disk`; the viscosity is SPH's artificial viscosity,
  :math:`\\alpha_{\\rm SS} \\approx \\alpha_{\\rm AV}\\,h/(10H)`, Lodato & Price 2010) and a dust disk of
  equal-mass two-fluid dust particles at the gas particles' places, dust-to-gas ratio
  ``dust.dust_to_gas``, with back-reaction (projected drag, thesis eq. 3.19, Epstein);
* local growth and fragmentation of every dust particle's grains (thesis eqs. 3.6-3.7,
  :class:`~dustygas.sph.dust.grain_size.GrainGrowth`), from ``dust.grain_size`` (10 µm) with the
  threshold ``growth.v_frag``;
* hierarchical individual time steps (:mod:`dustygas.sph.timesteps`).

The disk parameters are those of thesis Figure 3.1 (:mod:`dustygas.reproduce.fig3_1`, with their
provenance): 1 M_sun, 0.01 M_sun of gas from 4 to 120 au with :math:`\\Sigma \\propto r^{-1}`,
:math:`T \\propto r^{-1/2}`, :math:`H/r = 0.05` at 100 au, :math:`\\alpha = 0.01`, Ro = 3,
:math:`\\rho_{\\rm grain} = 1` g/cm^3, :math:`V_{\\rm frag} = 15` m/s, dust-to-gas ratio 0.01, 10 µm grains.
The reduced default holds 4000 gas and 4000 dust particles and runs for 20 orbits at 10 au;
:mod:`dustygas.analysis.dust_trap` reads the grain sizes, dust-to-gas ratios and the midplane gas
pressure against radius from its snapshots and looks for pressure maxima.
"""

from __future__ import annotations

import math

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..runner import RUN_SCHEMA
from ..sph import Box, ExternalForces
from ..sph.disk import DiskModel, balance_rotation, merge_particles
from ..sph.dust.drag_law import DragLaw
from ..sph.dust.grain_size import GrainGrowth
from ..sph.dust.two_fluid import TwoFluidOptions
from ..sph.kernels import get_kernel
from ..sph.particles import DUST, GAS
from ..sph.schema import SPH_SCHEMA, options_from_config
from ..sph.timesteps import BlockStepEngine, BlockStepOptions
from ..units import DISK_UNITS
from . import Problem, register

__all__ = ["DustTrap"]

ORBIT_10 = 2.0 * math.pi * 10.0**1.5


@register
class DustTrap(Problem):
    name = "dust-trap"
    summary = "Gonzalez et al. (2017) self-induced dust trap: viscous two-fluid dusty disk with grain growth and " \
              "fragmentation."
    smoke_overrides = ("disk.n_gas=400", "steps.max_level=8")
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=20 * ORBIT_10, dt_snapshot=5 * ORBIT_10, log_every=20),
        "sph": with_defaults(SPH_SCHEMA, switch="none", alpha=0.1, alpha_min=0.0, beta=0.0, alpha_u=0.0,
                             neighbour_search="tree", reorder_every=10),
        "disk": {
            "n_gas": Param(4000, "number of gas particles (and of dust particles)", min=100),
            "star_mass": Param(1.0, "stellar mass", "M_sun", min=0.0, min_open=True),
            "disk_mass": Param(0.01, "gas disk mass", "M_sun", min=0.0, min_open=True),
            "r_in": Param(4.0, "inner radius", "au", min=0.0, min_open=True),
            "r_out": Param(120.0, "outer radius", "au", min=0.0, min_open=True),
            "p": Param(1.0, "surface density exponent, Sigma ~ R^-p", min=0.0, max=1.9),
            "q": Param(0.5, "temperature exponent, T ~ R^-q", min=0.0, max=1.0),
            "aspect_ratio": Param(0.05, "H/R at r_ref", min=0.0, max=0.3, min_open=True),
            "r_ref": Param(100.0, "reference radius of the aspect ratio", "au", min=0.0, min_open=True),
            "accretion_radius": Param(2.0, "particles closer to the star are accreted", "au", min=0.0),
        },
        "steps": {
            "dt_max": Param(0.05, "longest block step", "orbits at 10 au", min=0.0, min_open=True),
            "max_level": Param(24, "deepest level of the step hierarchy", min=1, max=40),
        },
        "dust": {
            "dust_to_gas": Param(0.01, "initial dust-to-gas mass ratio", min=0.0, max=1.0, min_open=True),
            "grain_size": Param(1e-3, "initial grain radius", "cm", min=0.0, min_open=True),
            "grain_density": Param(1.0, "grain material density", "g/cm^3", min=0.0, min_open=True),
            "c_drag": Param(0.9, "explicit-drag time-step factor dt <= c_drag t_s", min=0.0, min_open=True),
        },
        "growth": {
            "enabled": Param(True, "grow and fragment grains (thesis eqs. 3.6-3.7)"),
            "alpha": Param(1e-2, "turbulence alpha of V_rel", min=0.0, min_open=True),
            "rossby": Param(3.0, "Rossby number of alpha_tilde = sqrt(2) Ro alpha", min=0.0, min_open=True),
            "v_frag": Param(15.0, "fragmentation threshold V_frag", "m/s", min=0.0),
            "min_size": Param(1e-5, "smallest grain radius", "cm", min=0.0, min_open=True),
            "c_size": Param(0.1, "time-step factor dt <= c s/|ds/dt|", min=0.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        d = cfg.disk
        if d.r_in >= d.r_out:
            raise ConfigError(f"disk.r_in = {d.r_in:g} must be smaller than disk.r_out = {d.r_out:g}")
        if d.accretion_radius >= d.r_in:
            raise ConfigError(f"disk.accretion_radius = {d.accretion_radius:g} must be smaller than "
                              f"disk.r_in = {d.r_in:g}")

    def build(self, cfg) -> BlockStepEngine:
        d, dust, gr = cfg.disk, cfg.dust, cfg.growth
        opts = options_from_config(cfg.sph)
        model = DiskModel(star_mass=d.star_mass, disk_mass=d.disk_mass, r_in=d.r_in, r_out=d.r_out, p=d.p, q=d.q,
                          aspect_ratio=d.aspect_ratio, r_ref=d.r_ref)
        hfact = opts.hfact or get_kernel(opts.kernel, 3).default_hfact
        gas = model.gas_particles(d.n_gas, hfact, alpha=opts.alpha)
        dustp = gas.take(np.arange(len(gas)))
        dustp.mass[:] = dust.dust_to_gas * gas.mass
        dustp.ptype[:] = DUST
        dustp.h[:] = gas.h  # the dust density is dust_to_gas times the gas's: h from mass/density alike
        u = DISK_UNITS
        rho_grain = dust.grain_density / u.density
        gas.extra["grain_size"] = np.zeros(len(gas))
        dustp.extra["grain_size"] = np.full(len(gas), dust.grain_size / u.length)
        particles = merge_particles(gas, dustp)
        drag = TwoFluidOptions(drag=DragLaw("epstein", grain_density=rho_grain), form="projected",
                               reconstruction="gas", integration="implicit", c_drag=dust.c_drag, heating=False)
        growth = None
        if gr.enabled:
            growth = GrainGrowth(alpha=gr.alpha, rossby=gr.rossby, v_frag=gr.v_frag * 100.0 / u.velocity,
                                 grain_density=rho_grain, min_size=gr.min_size / u.length, c_size=gr.c_size)
        steps = BlockStepOptions(individual=True, max_level=cfg.steps.max_level,
                                 dt_max=cfg.steps.dt_max * ORBIT_10)
        engine = BlockStepEngine(particles, Box.open_box(3), model.eos(), opts,
                                 ExternalForces(star_gm=d.star_mass, accretion_radius=d.accretion_radius), drag=drag,
                                 growth=growth, steps=steps)
        engine.timestep()  # balance the gas's rotation with the SPH forces at t = 0 (dust: the same velocity)
        p = engine.particles
        balance_rotation(p.pos, p.vel, engine.acc, p.ptype == GAS)
        p.vel[p.ptype == DUST] = p.vel[p.ptype == GAS]
        engine.reset()
        return engine
