"""``dust-settle``: the thesis's vertical settling test for one-fluid dust (thesis §3.2.5, Figs 3.2-3.3).

A vertical column of the dust-gas mixture (1D, the coordinate is the height :math:`z` over the
midplane) in hydrostatic equilibrium under the vertical gravity :math:`-\\Omega^2 z` of a disk:
isothermal gas with :math:`c_s = H\\Omega`, the same dust fraction :math:`\\epsilon_0 = 0.099` everywhere,
and the Gaussian density that balances the gas pressure :math:`P = c_s^2(1-\\epsilon_0)\\rho` against
gravity (:func:`dustygas.physics.exact.dusty_column_density`: a Gaussian of scale height
:math:`H_{\\rm mix} = \\sqrt{1-\\epsilon_0}\\,H`; the dust adds weight, not pressure), realised by equal-mass
particles at equally spaced quantiles of the mass. Grains are small (Epstein drag with
:math:`\\tau_s = t_s\\Omega = 0.01` at the midplane for the default grain size, growing as :math:`1/\\rho`
with height), the dust is
evolved in the terminal-velocity approximation and settles towards :math:`z = 0` at
:math:`v_z \\approx -t_s\\Omega^2 z` (the :math:`\\tau_s \\ll 1` limit of :math:`-z/t_{\\rm settle}`, thesis eq. 4.18), piling up at the midplane and emptying the
upper layers, where the density is lowest.

That is where the arithmetic exchange (thesis eq. 3.4) fails: a particle that has little dust
left gives away the *average* of its own and its neighbour's dust, more than it holds, and its
dust fraction goes negative -- unless clamped (thesis §3.2.4), which creates dust mass. The upwind
exchange (eqs. 3.15-3.17) takes outflowing dust from the particle that has it and keeps
:math:`\\epsilon \\ge 0` with the dust mass exact. By default the dust-fraction time-step criterion
is off, as in the thesis's CHANGA runs (``dust.c_eps = 0``); ``run.tlim`` is in units of
:math:`1/\\Omega` (an orbit is :math:`2\\pi`).

Units: :math:`\\Sigma = H = \\Omega = 1`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..physics.exact import dusty_column_density
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, ParticleSet, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, one_fluid_from_config
from ..sph.modules import SPHModule
from ..sph.schema import SPH_SCHEMA, options_from_config
from . import Problem, register

__all__ = ["DustSettle", "VerticalGravity", "midplane_stokes_number"]



def midplane_stokes_number(grain_size: float, grain_density: float, eps0: float = 0.099) -> float:
    """Epstein :math:`\\tau_s = \\sqrt{\\pi/8}\\,\\rho_{\\rm grain}s\\Omega/(\\rho_{\\rm mid}c_s)` at the midplane
    (mixture density, :func:`~dustygas.physics.drag.epstein_stopping_time`)."""
    from ..physics.drag import epstein_stopping_time

    rho_mid = float(dusty_column_density(0.0, dust_fraction=eps0))
    return float(epstein_stopping_time(grain_size, grain_density, (1 - eps0) * rho_mid, 1.0, rho_d=eps0 * rho_mid))


class VerticalGravity(SPHModule):
    """The disk's vertical gravity :math:`-\\Omega^2 z` along the single axis of a 1D column."""

    name = "vertical_gravity"

    def __init__(self, omega: float):
        self.omega2 = float(omega) ** 2

    def add_derivatives(self, engine, vel, u) -> None:
        engine.acc[:, 0] -= self.omega2 * engine.particles.pos[:, 0]

    def history(self, engine, out) -> None:
        p = engine.particles
        epot = 0.5 * self.omega2 * float(np.sum(p.mass * p.pos[:, 0] ** 2))
        out["potential_energy"] += epot
        out["total_energy"] += epot


@register
class DustSettle(Problem):
    name = "dust-settle"
    summary = "Vertical settling of small grains in a Gaussian gas column (thesis Figs 3.2-3.3), one-fluid dust."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=4 * np.pi, dt_snapshot=np.pi / 2, dt_history=0.05, log_every=2000),
        "sph": with_defaults(SPH_SCHEMA, alpha=0.1),
        "dust": with_defaults(DUST_SCHEMA, method="one-fluid", drag="epstein", grain_size=0.0067068,
                              grain_density=1.0, c_eps=0.0),
        "problem": {
            "particles": Param(400, "particles in the column", min=16),
            "eps0": Param(0.099, "initial dust fraction everywhere", min=0.0, max=1.0, min_open=True,
                          max_open=True),
        },
    }

    def validate(self, cfg) -> None:
        if cfg.dust.method != "one-fluid":
            raise ConfigError("dust-settle is a one-fluid test: dust.method = one-fluid")

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        n = p.particles
        from scipy.special import erfinv  # imported here: scipy.special costs every process 0.15 s at start-up

        z = np.sqrt(2.0 * (1.0 - p.eps0)) * erfinv(2.0 * (np.arange(n) + 0.5) / n - 1.0)
        mass = 1.0 / n
        kernel = get_kernel(opts.kernel, 1)
        hfact = opts.hfact or kernel.default_hfact
        particles = ParticleSet.create(z[:, None], mass=mass, h=hfact * mass / dusty_column_density(z, dust_fraction=p.eps0),
                                       alpha=opts.alpha)
        module = one_fluid_from_config(cfg.dust, p.eps0)
        return SPHEngine(particles, Box.open_box(1), EquationOfState.isothermal(1.0), opts,
                         modules=(VerticalGravity(1.0), module))
