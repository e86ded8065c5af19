"""``dustywave``: a linear sound wave in a dust-gas mixture with constant drag (Laibe & Price 2011).

The exact initial-value solution of the linearised isothermal two-fluid equations (thesis eq. 2.5
with constant :math:`K`) is :func:`dustygas.physics.exact.dusty_wave`. The initial state is
Phantom's: both densities :math:`\\rho_0[1 + A\\sin k(x-x_0)]`, both velocities
:math:`Ac_s\\sin k(x-x_0)`. Defaults: :math:`\\rho_g = \\rho_d = 1`, :math:`c_s = 1`, :math:`\\lambda = 1`,
:math:`A = 10^{-4}`, :math:`K = 1000`, two-fluid with dust particles on the gas particles.
``dustywave-3d`` is Phantom's 3D set-up: 64 particles per wavelength on a hexagonal-close-packed
lattice 12 rows and layers across (9216 gas + 9216 dust particles), quintic kernel,
:math:`t = 0.1`. :func:`velocity_errors` gives the RMS velocity error of each species in units
of :math:`Ac_s`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..physics.exact import dusty_wave
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, SPHEngine, get_kernel
from ..sph.dust.schema import DUST_SCHEMA, drag_law_from_config, one_fluid_from_config, two_fluid_from_config
from ..sph.dust.setup import dusty_particles, lattice, species
from ..sph.lattice import sine_density_positions
from ..sph.schema import INVISCID, SPH_SCHEMA, options_from_config
from . import Problem, preset, register

__all__ = ["DustyWave", "velocity_errors"]

X0 = -0.5  # left edge of the box and phase origin (Phantom's set-up)


def _background_K(cfg) -> float:
    """The drag coefficient of the unperturbed mixture (the one the linear system needs)."""
    p = cfg.problem
    rho = p.rho_gas + p.rho_dust
    ts = drag_law_from_config(cfg.dust).one_fluid_stopping_time(np.array([rho]), np.array([p.rho_dust / rho]),
                                                                 np.array([p.cs]))[0]
    return p.rho_gas * p.rho_dust / (float(ts) * rho)


def velocity_errors(engine: SPHEngine, cfg) -> dict[str, float]:
    """RMS error of :math:`v_x` of the gas and of the dust against :func:`~dustygas.physics.exact.dusty_wave`, in
    units of :math:`Ac_s`."""
    p = cfg.problem
    out = {}
    for i, (name, (pos, vel)) in enumerate(species(engine).items()):
        exact = dusty_wave(pos[:, 0], engine.t, amplitude=p.amplitude, K=_background_K(cfg), cs=p.cs,
                           rho_gas=p.rho_gas, rho_dust=p.rho_dust, x0=X0)
        out[name] = float(np.sqrt(np.mean((vel[:, 0] - exact[2 + i]) ** 2)) / (p.amplitude * p.cs))
    return out


@register
class DustyWave(Problem):
    name = "dustywave"
    summary = "Linear sound wave in a dusty gas (Laibe & Price 2011); exact 4x4 matrix-exponential solution."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=0.5, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA, **INVISCID, kernel="quintic",
                             h_tolerance=1e-6),
        "dust": with_defaults(DUST_SCHEMA, K=1000.0),
        "problem": {
            "ndim": Param(1, "number of dimensions", choices=(1, 3)),
            "nx": Param(64, "particles of each species per wavelength", min=8),
            "layers": Param(12, "rows and layers across the 3D box (even)", min=2),
            "amplitude": Param(1e-4, "relative amplitude A", min=0.0, max=0.1, min_open=True),
            "cs": Param(1.0, "isothermal sound speed", "code velocity", min=0.0, min_open=True),
            "rho_gas": Param(1.0, "mean gas density", min=0.0, min_open=True),
            "rho_dust": Param(1.0, "mean dust density", min=0.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        if cfg.problem.ndim == 3 and cfg.problem.layers % 2:
            raise ConfigError(f"problem.layers = {cfg.problem.layers}: a close-packed lattice needs an even number")

    def build(self, cfg) -> SPHEngine:
        p, d, opts = cfg.problem, cfg.dust, options_from_config(cfg.sph)
        pos, hi = lattice(p.ndim, p.nx, p.layers, X0)
        k = 2.0 * np.pi
        pos[:, 0] = sine_density_positions(pos[:, 0] - X0, p.amplitude, k, 0.0) + X0
        lo = np.array([X0, 0.0, 0.0][: p.ndim])
        phase = np.sin(k * (pos[:, 0] - X0))
        factor = 1.0 + p.amplitude * phase
        v = p.amplitude * p.cs * phase
        kernel = get_kernel(opts.kernel, p.ndim)
        particles, init = dusty_particles(d.method, pos, float(np.prod(hi - lo)), p.rho_gas * factor,
                                          p.rho_dust * factor, v, v, opts.hfact or kernel.default_hfact, p.ndim)
        if d.method == "one-fluid":
            module = one_fluid_from_config(d, init["dust_fraction"], delta_v=init["delta_v"])
        else:
            module = two_fluid_from_config(d)
        box = Box.periodic_box(p.ndim, tuple(lo), tuple(hi))
        return SPHEngine(particles, box, EquationOfState.isothermal(p.cs), opts, modules=(module,))


preset("dustywave-3d", DustyWave, "Phantom's 3D dustywave: 9216 gas + 9216 dust particles, K = 1000, quintic.",
       run={"tlim": 0.1}, problem={"ndim": 3, "nx": 64, "layers": 12}, sph={"h_tolerance": 1e-4})
