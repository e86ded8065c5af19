"""``growth-box``: grains growing or fragmenting in a uniform dusty box (Vericel et al. 2021).

A periodic box of one-fluid mixture particles with uniform gas and dust densities, gas at rest
and Epstein drag; every particle's grain size follows the local growth or fragmentation rate of
thesis eq. 3.6 with the turbulent relative velocity of eq. 3.7
(:mod:`~dustygas.sph.dust.grain_size`). In a uniform box the Stokes number
:math:`St = \\sqrt{\\pi\\gamma/8}\\,\\rho_{\\rm grain}s\\Omega/(\\rho c_s)` then has the exact solution of
Vericel et al. (2021), :func:`dustygas.physics.growth.stokes_number_growth` with the growth time
:func:`dustygas.physics.growth.growth_timescale` -- for pure growth
(:math:`V_{\\rm frag} = \\infty`, the default) and for pure fragmentation (:math:`V_{\\rm frag} = 0`,
``growth-box-fragmentation``), valid until the grains would reach zero size. Past that time the
sizes stop at ``growth.min_size`` instead of becoming negative.

:func:`stokes_numbers` returns the simulated :math:`St` of every particle and
:meth:`GrowthBox.exact` the analytic one. Neither depends on the SPH density error of the lattice:
:math:`dSt/dt` involves only :math:`\\rho_d/\\rho`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..physics.drag import epstein_grain_size, stokes_number
from ..physics.growth import growth_timescale, stokes_number_growth
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, ParticleSet, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, GROWTH_SCHEMA, one_fluid_from_config
from ..sph.dust.setup import dust_module
from ..sph.lattice import cubic_lattice
from ..sph.schema import INVISCID, SPH_SCHEMA, options_from_config
from . import Problem, preset, register

__all__ = ["GrowthBox", "stokes_numbers"]


def stokes_numbers(engine: SPHEngine, omega: float) -> np.ndarray:
    """Simulated :math:`St = t_s\\Omega` of every particle (mixture Epstein stopping time, local density)."""
    module = dust_module(engine)
    p = engine.particles
    ts = module.options.drag.one_fluid_stopping_time(engine.rho, module.dust_fractions(engine), engine.cs,
                                                     p.extra["grain_size"])
    return stokes_number(ts, omega)


@register
class GrowthBox(Problem):
    name = "growth-box"
    summary = "Grain growth (or fragmentation) in a uniform dusty box; Vericel et al. (2021) exact Stokes number."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=50.0, dt_history=0.5, log_every=10000),
        "sph": with_defaults(SPH_SCHEMA, **INVISCID),
        "dust": with_defaults(DUST_SCHEMA, method="one-fluid", drag="epstein", grain_density=1.0),
        "growth": with_defaults(GROWTH_SCHEMA, enabled=True),
        "problem": {
            "nx": Param(16, "particles in the periodic 1D box (length nx, spacing 1)", min=8),
            "rho_gas": Param(1.0, "gas density", min=0.0, min_open=True),
            "dust_to_gas": Param(1.0, "dust-to-gas density ratio", min=0.0, min_open=True),
            "cs": Param(1.0, "isothermal sound speed", "code velocity", min=0.0, min_open=True),
            "stokes0": Param(0.01, "initial Stokes number St = t_s Omega of every grain", min=0.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        d = cfg.dust
        if d.method != "one-fluid" or d.drag != "epstein" or not cfg.growth.enabled:
            raise ConfigError("growth-box needs dust.method = one-fluid, dust.drag = epstein, growth.enabled = true")

    def growth_time(self, cfg) -> float:
        """:math:`\\tau` of the analytic solution (:func:`~dustygas.physics.growth.growth_timescale`)."""
        p, g = cfg.problem, cfg.growth
        return float(growth_timescale(p.rho_gas, p.dust_to_gas * p.rho_gas, g.omega, g.alpha, g.rossby))

    def exact(self, cfg, t) -> np.ndarray:
        """Analytic Stokes number at time(s) ``t`` (NaN once fragmenting grains would have vanished)."""
        return stokes_number_growth(t, cfg.problem.stokes0, self.growth_time(cfg), cfg.growth.v_frag == 0.0)

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        if 0.0 < cfg.growth.v_frag < np.inf:
            raise ConfigError("growth-box: the analytic solution needs growth.v_frag = inf (growth) or 0 "
                              "(fragmentation)")
        n = p.nx
        pos = cubic_lattice((n,), (0.0,), (float(n),))
        rho_d = p.dust_to_gas * p.rho_gas
        rho = p.rho_gas + rho_d
        mass = rho
        kernel = get_kernel(opts.kernel, 1)
        particles = ParticleSet.create(pos, mass=mass, h=(opts.hfact or kernel.default_hfact), alpha=opts.alpha)
        # nominal size of St = stokes0, corrected below for the SPH density
        size0 = float(epstein_grain_size(p.stokes0, cfg.dust.grain_density, p.rho_gas, p.cs, cfg.growth.omega,
                                         rho_d=rho_d))
        module = one_fluid_from_config(cfg.dust, rho_d / rho, grain_size=size0, growth=cfg.growth)
        engine = SPHEngine(particles, Box.periodic_box(1, (0.0,), (float(n),)), EquationOfState.isothermal(p.cs),
                           opts, modules=(module,))
        # start from St = stokes0 with the SPH density of the lattice (which differs from rho by a lattice sum)
        engine.update_derivatives()
        engine.particles.extra["grain_size"] *= p.stokes0 / stokes_numbers(engine, cfg.growth.omega)
        engine.update_derivatives()
        return engine


preset("growth-box-fragmentation", GrowthBox, "Grains fragmenting in a uniform dusty box (V_frag = 0) from St = 1.",
       run={"tlim": 25.0}, growth={"v_frag": 0.0}, problem={"stokes0": 1.0})
