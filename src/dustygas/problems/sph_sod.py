"""``sph-sod``: the Sod (1978) shock tube with SPH, against the exact Riemann solution.

Left state :math:`(\\rho, P) = (1, 1)` for :math:`x < 0`, right state :math:`(0.125, 0.1)`, gas at
rest, :math:`\\gamma = 5/3` (Phantom's default), equal-mass particles whose spacing jumps by
:math:`\\rho_L/\\rho_R` (1D) or its cube root (3D, close-packed lattices). The domain is
periodic, :math:`-1 \\le x < 1`: the second interface at :math:`x = \\pm 1` launches its own
waves, which stay outside :math:`|x| < 0.5` until :math:`t \\approx 0.28`, so up to the default
:math:`t = 0.2` the central region is the single Riemann problem of
:class:`~dustygas.physics.exact_riemann.RiemannSolution`. ``nx`` counts particles in
:math:`-0.5 < x < 0` as in Phantom's shock set-up. :func:`l1_errors` gives the mean absolute
errors of density, velocity and pressure over the particles with :math:`|x| < 0.5`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..physics.exact_riemann import RiemannSolution
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, ParticleSet, SPHEngine, get_kernel
from ..sph.lattice import close_packed_lattice
from ..sph.schema import SPH_SCHEMA, options_from_config
from . import Problem, preset, register

__all__ = ["SPHSod", "l1_errors"]


def l1_errors(engine: SPHEngine, solution: RiemannSolution, half_width: float = 0.5) -> dict[str, float]:
    """Mean absolute errors of rho, v_x and P over particles with ``|x| < half_width``."""
    p = engine.particles
    x = p.pos[:, 0]
    sel = np.abs(x) < half_width
    rho, v, pr = solution(x[sel] / engine.t)
    return {"rho": float(np.mean(np.abs(engine.rho[sel] - rho))),
            "vx": float(np.mean(np.abs(p.vel[sel, 0] - v))),
            "P": float(np.mean(np.abs(engine.P[sel] - pr)))}


#: the two states of Sod's (1978) shock tube, gas at rest, and the adiabatic index (shared with ``dustyshock``)
SOD_STATES = {
    "rho_left": Param(1.0, "left (gas) density", min=0.0, min_open=True),
    "p_left": Param(1.0, "left pressure", min=0.0, min_open=True),
    "rho_right": Param(0.125, "right (gas) density", min=0.0, min_open=True),
    "p_right": Param(0.1, "right pressure", min=0.0, min_open=True),
    "gamma": Param(5.0 / 3.0, "adiabatic index", min=1.0, min_open=True),
}


@register
class SPHSod(Problem):
    name = "sph-sod"
    summary = "Sod shock tube in SPH (1D or 3D) with the exact Riemann solution for comparison."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=0.2, dt_snapshot=0.05, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA),
        "problem": {
            "ndim": Param(1, "number of dimensions", choices=(1, 3)),
            "nx": Param(256, "particles in -0.5 < x < 0 (left state)", min=8),
            "layers": Param(6, "rows and layers across the 3D tube on the right (low-density) side", min=2),
            **SOD_STATES,
        },
    }

    def validate(self, cfg) -> None:
        p = cfg.problem
        if p.ndim == 3:
            ratio = round((p.rho_left / p.rho_right) ** (1 / 3))
            if abs(ratio**3 - p.rho_left / p.rho_right) > 1e-12 * ratio**3:
                raise ConfigError("problem.rho_left/rho_right must be a cube of an integer in 3D (lattices)")
            if p.layers % 2:
                raise ConfigError(f"problem.layers = {p.layers}: a close-packed lattice needs an even number")

    def solution(self, cfg) -> RiemannSolution:
        """The exact solution of the configured Riemann problem."""
        p = cfg.problem
        return RiemannSolution(p.rho_left, 0.0, p.p_left, p.rho_right, 0.0, p.p_right, p.gamma)

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        dx_left = 0.5 / p.nx
        if p.ndim == 1:
            ratio = p.rho_left / p.rho_right
            n_left = 2 * p.nx
            n_right = int(round(n_left / ratio))
            x_left = -1.0 + (np.arange(n_left) + 0.5) * dx_left
            x_right = (np.arange(n_right) + 0.5) * (1.0 / n_right)
            pos = np.zeros((n_left + n_right, 3))
            pos[:, 0] = np.concatenate([x_left, x_right])
            mass = p.rho_left * dx_left
            box = Box.periodic_box(1, (-1.0,), (1.0,))
        else:
            ratio = round((p.rho_left / p.rho_right) ** (1 / 3))
            a_left = dx_left
            a_right = ratio * a_left
            right, hi = close_packed_lattice((int(round(1.0 / a_right)), p.layers, p.layers), a_right, (0.0,) * 3)
            left, hi_l = close_packed_lattice((2 * p.nx, ratio * p.layers, ratio * p.layers), a_left, (-1.0, 0.0, 0.0))
            if not np.allclose(hi[1:], hi_l[1:]):
                raise ConfigError("problem.nx does not give commensurate left and right lattices")
            right[:, 0] *= 1.0 / hi[0]  # stretch the right block to exactly [0, 1)
            left[:, 0] = -1.0 + (left[:, 0] + 1.0) / (hi_l[0] + 1.0)
            pos = np.concatenate([left, right])
            mass = p.rho_left * float(np.prod(hi[1:])) / len(left)
            box = Box.periodic_box(3, (-1.0, 0.0, 0.0), (1.0, hi[1], hi[2]))
        kernel = get_kernel(opts.kernel, p.ndim)
        hfact = opts.hfact or kernel.default_hfact
        left_side = pos[:, 0] < 0
        rho = np.where(left_side, p.rho_left, p.rho_right)
        u = np.where(left_side, p.p_left, p.p_right) / ((p.gamma - 1.0) * rho)
        particles = ParticleSet.create(pos, mass=mass, h=hfact * (mass / rho) ** (1.0 / p.ndim), u=u, alpha=opts.alpha)
        return SPHEngine(particles, box, EquationOfState.adiabatic(p.gamma), opts)


preset("sph-sod-3d", SPHSod, "Sod shock tube in a 3D SPH tube of close-packed lattices (Phantom's set-up).",
       problem={"ndim": 3, "nx": 64, "layers": 8}, sph={"kernel": "quintic"})
