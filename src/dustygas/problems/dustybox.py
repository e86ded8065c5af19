"""``dustybox``: uniform gas and dust whose relative velocity decays by drag (Laibe & Price 2011).

With uniform densities nothing but drag acts; the centre-of-mass velocity stays constant and
the relative velocity decays on the mixture stopping time (:meth:`DustyBox.stopping_time`): the
exact solution is :func:`dustygas.physics.exact.dusty_box`.

Defaults are Phantom's unit test: :math:`\\rho_g = \\rho_d = 1`, :math:`v_d = 1`,
:math:`v_g = 0`, :math:`K = 0.35`, :math:`c_s = 1`, :math:`\\Delta t = 10^{-3}`, 100 steps, quintic kernel, in
a 3D periodic box of hexagonal-close-packed gas particles with dust particles at the same
positions (two-fluid); ``dust.method = one-fluid`` uses mixture particles with the full one-fluid
equations (the terminal-velocity approximation has no relative velocity to decay). With
``problem.eos = adiabatic`` the drag heats the gas and kinetic plus thermal energy is conserved.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, drag_law_from_config, one_fluid_from_config, two_fluid_from_config
from ..sph.dust.setup import dusty_particles, lattice
from ..sph.schema import INVISCID, SPH_SCHEMA, options_from_config
from . import Problem, preset, register

__all__ = ["DustyBox"]


@register
class DustyBox(Problem):
    name = "dustybox"
    summary = "Uniform gas and dust, relative velocity decaying by drag (Laibe & Price 2011); exact solution."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=0.1, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA, **INVISCID, kernel="quintic",
                             h_tolerance=1e-6, fixed_dt=1e-3),
        "dust": with_defaults(DUST_SCHEMA, K=0.35, model="full", reconstruction="none"),
        "problem": {
            "ndim": Param(3, "number of dimensions", choices=(1, 3)),
            "nx": Param(24, "particles of each species along x (box length 1)", min=8),
            "layers": Param(12, "rows and layers across the 3D box (even)", min=2),
            "rho_gas": Param(1.0, "gas density", min=0.0, min_open=True),
            "rho_dust": Param(1.0, "dust density", min=0.0, min_open=True),
            "v_gas": Param(0.0, "initial gas velocity along x", "code velocity"),
            "v_dust": Param(1.0, "initial dust velocity along x", "code velocity"),
            "cs": Param(1.0, "sound speed", "code velocity", min=0.0, min_open=True),
            "eos": Param("isothermal", "equation of state (adiabatic: drag heats the gas)",
                         choices=("isothermal", "adiabatic")),
            "gamma": Param(5.0 / 3.0, "adiabatic index", min=1.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        if cfg.dust.method == "one-fluid" and cfg.dust.model != "full":
            raise ConfigError("dust.model = terminal-velocity has no relative velocity: the dustybox needs "
                              "dust.model = full with dust.method = one-fluid")
        if cfg.problem.ndim == 3 and cfg.problem.layers % 2:
            raise ConfigError(f"problem.layers = {cfg.problem.layers}: a close-packed lattice needs an even number")

    def stopping_time(self, cfg) -> float:
        """Mixture stopping time of the configured densities (for :func:`~dustygas.physics.exact.dusty_box`)."""
        p = cfg.problem
        law = drag_law_from_config(cfg.dust, self._gamma(cfg))
        rho = p.rho_gas + p.rho_dust
        return float(law.one_fluid_stopping_time(np.array([rho]), np.array([p.rho_dust / rho]),
                                                 np.array([p.cs]))[0])

    @staticmethod
    def _gamma(cfg) -> float:
        return cfg.problem.gamma if cfg.problem.eos == "adiabatic" else 1.0

    def build(self, cfg) -> SPHEngine:
        p, d, opts = cfg.problem, cfg.dust, options_from_config(cfg.sph)
        pos, hi = lattice(p.ndim, p.nx, p.layers, -0.5)
        lo = np.array([-0.5, 0.0, 0.0][: p.ndim])
        volume = float(np.prod(hi - lo))
        kernel = get_kernel(opts.kernel, p.ndim)
        gamma = self._gamma(cfg)
        if p.eos == "adiabatic":
            eos = EquationOfState.adiabatic(gamma)
            u = p.cs**2 / (gamma * (gamma - 1.0))
        else:
            eos, u = EquationOfState.isothermal(p.cs), 0.0
        particles, init = dusty_particles(d.method, pos, volume, p.rho_gas, p.rho_dust, p.v_gas, p.v_dust,
                                          opts.hfact or kernel.default_hfact, p.ndim, u_gas=u)
        if d.method == "one-fluid":
            module = one_fluid_from_config(d, init["dust_fraction"], gamma, delta_v=init["delta_v"])
        else:
            module = two_fluid_from_config(d, gamma)
        return SPHEngine(particles, Box.periodic_box(p.ndim, tuple(lo), tuple(hi)), eos, opts, modules=(module,))


preset("dustybox-1d", DustyBox, "Dustybox in a 1D periodic row of particles (quintic kernel).",
       problem={"ndim": 1, "nx": 64})
