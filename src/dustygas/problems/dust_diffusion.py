"""``dust-diffusion``: the terminal-velocity dust fraction spreading in gas at rest (Price & Laibe 2015).

Particles are held fixed (only :math:`\\epsilon` evolves) in a uniform gas of density :math:`\\rho` with
:math:`P = c_s^2\\rho_g = c_s^2(1-\\epsilon)\\rho` and a constant stopping time :math:`t_s`, so the
terminal-velocity equation (thesis eq. 2.11b) is a non-linear diffusion equation with the exact
spreading solution :func:`dustygas.physics.exact.dust_diffusion` (Price & Laibe 2015, eq. 51),
:math:`\\epsilon = \\epsilon_0(1 - r^2/r_c^2)` inside :math:`r_c` at :math:`t = 0`. Phantom's test: a
:math:`32^3` cubic lattice in :math:`[-1/2, 1/2)^3`, :math:`\\rho = 3`, :math:`t_s = 0.1`, :math:`c_s = 1`,
:math:`\\epsilon_0 = 0.1`, :math:`r_c = 0.25`, fixed step :math:`\\Delta t = 0.05` to :math:`t = 10`, cubic kernel,
error :math:`L_2 = [\\sum(\\epsilon - \\epsilon_{\\rm exact})^2/N]^{1/2}` over the :math:`N` particles where the exact
solution is positive, at most :math:`2.6\\times10^{-3}` at every step (:func:`l2_error`). Phantom holds the
particles by evolving only the dust; here ``hold_gas`` zeroes the accelerations, so the same
engine step moves nothing but :math:`\\epsilon`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..physics.exact import dust_diffusion
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, ParticleSet, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, one_fluid_from_config
from ..sph.dust.setup import dust_module
from ..sph.lattice import cubic_lattice
from ..sph.schema import INVISCID, SPH_SCHEMA, options_from_config
from . import Problem, register

__all__ = ["DustDiffusion", "l2_error"]


def l2_error(engine: SPHEngine, cfg) -> float:
    """Phantom's :math:`L_2` error of the dust fraction over the particles where the exact one is > 0."""
    p = cfg.problem
    r = np.linalg.norm(engine.particles.pos, axis=1)
    exact = dust_diffusion(r, engine.t, eta=cfg.dust.ts * p.cs**2, eps0=p.eps0, r_c=p.r_c)
    inside = exact > 0
    eps = dust_module(engine).dust_fractions(engine)
    return float(np.sqrt(np.mean((eps[inside] - exact[inside]) ** 2)))


@register
class DustDiffusion(Problem):
    name = "dust-diffusion"
    summary = "Dust fraction diffusing through gas at rest (Price & Laibe 2015); exact solution, Phantom's set-up."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=10.0, dt_snapshot=1.0, log_every=20),
        "sph": with_defaults(SPH_SCHEMA, **INVISCID, fixed_dt=0.05),
        "dust": with_defaults(DUST_SCHEMA, method="one-fluid", drag="constant-ts", ts=0.1),
        "problem": {
            "nx": Param(32, "particles per side of the cubic lattice", min=8),
            "rho": Param(3.0, "density", min=0.0, min_open=True),
            "cs": Param(1.0, "isothermal sound speed", "code velocity", min=0.0, min_open=True),
            "eps0": Param(0.1, "central dust fraction", min=0.0, max=1.0, min_open=True, max_open=True),
            "r_c": Param(0.25, "initial radius of the dusty region", min=0.0, max=0.5, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        from ..errors import ConfigError

        d = cfg.dust
        if d.method != "one-fluid" or d.model != "terminal-velocity" or d.drag != "constant-ts":
            raise ConfigError("dust-diffusion is the terminal-velocity one-fluid test with a constant stopping time: "
                              "dust.method = one-fluid, dust.model = terminal-velocity, dust.drag = constant-ts")

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        n = p.nx
        pos = cubic_lattice((n, n, n), (-0.5,) * 3, (0.5,) * 3)
        mass = p.rho / n**3
        kernel = get_kernel(opts.kernel, 3)
        hfact = opts.hfact or kernel.default_hfact
        particles = ParticleSet.create(pos, mass=mass, h=hfact * (mass / p.rho) ** (1.0 / 3.0), alpha=opts.alpha)
        eps = dust_diffusion(np.linalg.norm(pos, axis=1), 0.0, eta=cfg.dust.ts * p.cs**2, eps0=p.eps0, r_c=p.r_c)
        module = one_fluid_from_config(cfg.dust, eps, hold_gas=True)
        box = Box.periodic_box(3, (-0.5,) * 3, (0.5,) * 3)
        return SPHEngine(particles, box, EquationOfState.isothermal(p.cs), opts, modules=(module,))
