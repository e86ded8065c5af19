"""``dustyshock``: a Sod-like shock tube in a dusty gas (Laibe & Price 2012b).

Left :math:`(\\rho_g, P) = (1, 1)`, right :math:`(0.125, 0.1)`, gas and dust at rest, dust-to-gas ratio
:math:`\\mu = 1` on both sides, :math:`\\gamma = 5/3`. There is no closed form at finite drag; as
:math:`K \\to \\infty` the dust moves with the gas and the mixture is one ideal gas of density
:math:`\\rho_g + \\rho_d` and the gas pressure (its thermal energy per unit mixture mass is
:math:`(1-\\epsilon)u`, so :math:`P = (\\gamma-1)\\rho_{\\rm mix}(1-\\epsilon)u` with the same :math:`\\gamma`): the Riemann
problem :math:`(2, 0, 1) | (0.25, 0, 0.1)`, with :math:`P_* = 0.29395`, :math:`u_* = 0.59481`,
:math:`\\rho_{*L} = 0.95938`, :math:`\\rho_{*R} = 0.45961` (mixture) and shock speed 1.30424
(Toro 2009's exact solver, :mod:`dustygas.physics.exact_riemann`; :meth:`DustyShock.asymptotic_solution`). :func:`star_state` averages the
simulated pressure, velocities and densities over the plateaus of that solution.

The tube is periodic, :math:`-1 \\le x < 1`, as in ``sph-sod``; the mirrored interface at
:math:`x = \\pm1` launches waves that stay outside :math:`|x| < 0.5` until :math:`t \\approx 0.35`. Two-fluid:
dust particles on the gas particles, each with the mass of its gas particle times :math:`\\mu`
(Phantom's dusty shock set-up at v2026.0.1 creates *no* dust -- a local variable shadows the
dust-to-gas ratio it reads; here :meth:`DustyShock.build` checks that the dust mass is
:math:`\\mu` times the gas mass). One-fluid: mixture particles with :math:`\\epsilon = \\mu/(1+\\mu)`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError, SetupError
from ..physics.exact_riemann import RiemannSolution
from ..runner import RUN_SCHEMA
from ..sph import DUST, GAS, Box, EquationOfState, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, one_fluid_from_config, two_fluid_from_config
from ..sph.dust.setup import dusty_particles, species
from ..sph.schema import SPH_SCHEMA, options_from_config
from . import Problem, register
from .sph_sod import SOD_STATES

__all__ = ["DustyShock", "star_state"]


def star_state(engine: SPHEngine, solution: RiemannSolution, mu: float, margin: float) -> dict[str, float]:
    """Simulated star state, averaged over the plateaus of the K -> infinity ``solution``.

    Pressure and velocities over :math:`x_{\\rm tail} + \\delta < x < x_{\\rm shock} - \\delta`; the gas and dust
    densities left and right of the contact (within ``margin`` :math:`\\delta` of no wave), returned as
    the equivalent mixture densities :math:`(1+\\mu)\\rho_g` and :math:`(1+\\mu)\\rho_d/\\mu`.
    """
    t = engine.t
    g = solution.gamma
    c_star = np.sqrt(g * solution.p_star / solution.rho_star_left)
    tail, contact, shock = (solution.u_star - c_star) * t, solution.u_star * t, solution.shock_speed_right * t
    sp = species(engine)
    p = engine.particles
    one_fluid = not (p.ptype == DUST).any()
    xg = sp["gas"][0][:, 0]
    xd = sp["dust"][0][:, 0]
    star = (xg > tail + margin) & (xg < shock - margin)
    left = (xg > tail + margin) & (xg < contact - margin)
    right = (xg > contact + margin) & (xg < shock - margin)
    dleft = (xd > tail + margin) & (xd < contact - margin)
    dright = (xd > contact + margin) & (xd < shock - margin)
    dstar = (xd > tail + margin) & (xd < shock - margin)
    if one_fluid:
        P, rho_mix = engine.P, engine.rho
        rho_g = rho_mix * (1.0 - p.extra["dust_fraction"])
        rho_d = rho_mix - rho_g
    else:
        gas, dust = p.ptype == GAS, p.ptype == DUST
        P, rho_g, rho_d = engine.P[gas], engine.rho[gas], engine.rho[dust]
    return {"P": float(np.mean(P[star])),
            "v_gas": float(np.mean(sp["gas"][1][star, 0])),
            "v_dust": float(np.mean(sp["dust"][1][dstar, 0])),
            "rho_left_gas": float(np.mean(rho_g[left])) * (1.0 + mu),
            "rho_right_gas": float(np.mean(rho_g[right])) * (1.0 + mu),
            "rho_left_dust": float(np.mean(rho_d[dleft])) * (1.0 + mu) / mu,
            "rho_right_dust": float(np.mean(rho_d[dright])) * (1.0 + mu) / mu}


@register
class DustyShock(Problem):
    name = "dustyshock"
    summary = "Sod-like shock tube in a dusty gas (Laibe & Price 2012); K -> infinity star state for comparison."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=0.2, dt_snapshot=0.05, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA),
        "dust": with_defaults(DUST_SCHEMA, K=1000.0, reconstruction="mc", integration="implicit"),
        "problem": {
            "nx": Param(256, "gas particles in -0.5 < x < 0 (left state)", min=8),
            **SOD_STATES,
            "dust_to_gas": Param(1.0, "dust-to-gas density ratio mu on both sides", min=0.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        ratio = cfg.problem.rho_left / cfg.problem.rho_right
        if abs(ratio - round(ratio)) > 1e-12 * ratio:
            raise ConfigError("problem.rho_left/rho_right must be an integer (equal-mass particles on both sides)")

    def asymptotic_solution(self, cfg) -> RiemannSolution:
        """The :math:`K \\to \\infty` solution: one ideal gas of the mixture density (module docstring)."""
        p = cfg.problem
        m = 1.0 + p.dust_to_gas
        return RiemannSolution(m * p.rho_left, 0.0, p.p_left, m * p.rho_right, 0.0, p.p_right, p.gamma)

    def build(self, cfg) -> SPHEngine:
        p, d, opts = cfg.problem, cfg.dust, options_from_config(cfg.sph)
        dx_left = 0.5 / p.nx
        n_left = 2 * p.nx
        n_right = int(round(n_left * p.rho_right / p.rho_left))
        x = np.concatenate([-1.0 + (np.arange(n_left) + 0.5) * dx_left, (np.arange(n_right) + 0.5) / n_right])
        pos = np.zeros((x.size, 3))
        pos[:, 0] = x
        left = x < 0
        rho_g = np.where(left, p.rho_left, p.rho_right)
        u = np.where(left, p.p_left, p.p_right) / ((p.gamma - 1.0) * rho_g)
        volume = (p.rho_left + p.rho_right) / float(np.mean(rho_g))  # equal masses: mean(rho) volume / n
        kernel = get_kernel(opts.kernel, 1)
        particles, init = dusty_particles(d.method, pos, volume, rho_g, p.dust_to_gas * rho_g, 0.0, 0.0,
                                          opts.hfact or kernel.default_hfact, 1, u_gas=u)
        if d.method == "one-fluid":
            module = one_fluid_from_config(d, init["dust_fraction"], p.gamma, delta_v=init["delta_v"])
        else:
            dust, gas = particles.ptype == DUST, particles.ptype == GAS
            ratio = particles.mass[dust].sum() / particles.mass[gas].sum()
            if abs(ratio - p.dust_to_gas) > 1e-12 * p.dust_to_gas:
                raise SetupError(f"dusty shock set-up: dust/gas mass {ratio:.6g}, expected {p.dust_to_gas:g}")
            module = two_fluid_from_config(d, p.gamma)
        return SPHEngine(particles, Box.periodic_box(1, (-1.0,), (1.0,)), EquationOfState.adiabatic(p.gamma), opts,
                         modules=(module,))
