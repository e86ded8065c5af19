"""``sph-soundwave``: a linear sound wave in a periodic SPH box, with its exact solution.

A right-going wave of one wavelength :math:`\\lambda = 1` along x,

.. math:: \\rho = \\rho_0[1 + A\\sin k(x - c_s t)], \\qquad v_x = c_s A \\sin k(x - c_s t),

is set up on a lattice (a row in 1D; hexagonal or hexagonal-close-packed in 2D/3D, a few
rows/layers thick) whose x coordinates are mapped to the density profile exactly
(:func:`~dustygas.sph.lattice.sine_density_positions`). With no dissipation the SPH error is
:math:`O(h^2)`; :func:`velocity_error` measures it against the exact solution. Default: 1D,
64 particles per wavelength, one wave period. The 2D and 3D presets use the quintic kernel: on
close-packed lattices the cubic M4 kernel (h_fact 1.2) converges in 1D but not in 2D, where its
error levels off at about 11 % of the amplitude (a lattice-sum error of the gradient that does not
shrink with resolution, only with more neighbours; measured 0.26, 0.15, 0.11 at 16, 32, 64 per
wavelength, against 0.135, 0.035, 0.0086 with M6), and in 3D its 68 lattice neighbours make the
lattice unstable (pairing instability).
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..runner import RUN_SCHEMA
from ..sph import Box, EquationOfState, ParticleSet, SPHEngine, get_kernel
from ..sph.lattice import close_packed_lattice, cubic_lattice, sine_density_positions
from ..sph.schema import INVISCID, SPH_SCHEMA, options_from_config
from . import Problem, preset, register

__all__ = ["SPHSoundWave", "soundwave_exact", "velocity_error"]


def soundwave_exact(x: np.ndarray, t: float, amplitude: float, cs: float, wavelength: float = 1.0):
    """:math:`(\\rho/\\rho_0, v_x)` of the linear right-going wave at positions ``x``, time ``t``."""
    phase = np.sin(2 * np.pi / wavelength * (np.asarray(x) - cs * t))
    return 1.0 + amplitude * phase, cs * amplitude * phase


def velocity_error(engine: SPHEngine, amplitude: float, cs: float) -> float:
    """RMS error of :math:`v_x` against :func:`soundwave_exact`, in units of :math:`c_s A`."""
    p = engine.particles
    _, v = soundwave_exact(p.pos[:, 0], engine.t, amplitude, cs)
    return float(np.sqrt(np.mean((p.vel[:, 0] - v) ** 2)) / (cs * amplitude))


@register
class SPHSoundWave(Problem):
    name = "sph-soundwave"
    summary = "Linear sound wave in a periodic SPH box (1/2/3D) with its exact solution."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=1.0, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA, **INVISCID, h_tolerance=1e-6),
        "problem": {
            "ndim": Param(1, "number of dimensions", choices=(1, 2, 3)),
            "nx": Param(64, "particles per wavelength along x", min=8),
            "layers": Param(8, "rows/layers across the box in 2D/3D (even)", min=2),
            "lattice": Param("close-packed", "particle arrangement in 2D/3D", choices=("close-packed", "cubic")),
            "amplitude": Param(1e-4, "relative density amplitude A", min=0.0, max=0.1, min_open=True),
            "cs": Param(1.0, "sound speed", "code velocity", min=0.0, min_open=True),
            "rho0": Param(1.0, "mean density", "code density", min=0.0, min_open=True),
            "eos": Param("isothermal", "equation of state", choices=("isothermal", "adiabatic")),
            "gamma": Param(5.0 / 3.0, "adiabatic index (adiabatic eos)", min=1.0, min_open=True),
        },
    }

    def validate(self, cfg) -> None:
        p = cfg.problem
        if p.ndim > 1 and p.lattice == "close-packed" and p.layers % 2:
            raise ConfigError(f"problem.layers = {p.layers}: a close-packed lattice needs an even number")

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        ndim = p.ndim
        spacing = 1.0 / p.nx
        if ndim == 1 or p.lattice == "cubic":
            shape = (p.nx,) + (p.layers,) * (ndim - 1)
            hi = np.array((1.0,) + (p.layers * spacing,) * (ndim - 1))
            pos = cubic_lattice(shape, (0.0,) * ndim, tuple(hi))
        else:
            pos, hi = close_packed_lattice((p.nx,) + (p.layers,) * (ndim - 1), spacing, (0.0,) * ndim)
        k = 2 * np.pi
        pos[:, 0] = sine_density_positions(pos[:, 0], p.amplitude, k, 0.0)
        _, vx = soundwave_exact(pos[:, 0], 0.0, p.amplitude, p.cs)
        n = len(pos)
        mass = p.rho0 * float(np.prod(hi)) / n
        kernel = get_kernel(opts.kernel, ndim)
        hfact = opts.hfact or kernel.default_hfact
        if p.eos == "adiabatic":
            eos = EquationOfState.adiabatic(p.gamma)
            u = p.cs**2 / (p.gamma * (p.gamma - 1.0)) * (1.0 + (p.gamma - 1.0) * p.amplitude *
                                                          np.sin(k * pos[:, 0]))
        else:
            eos = EquationOfState.isothermal(p.cs)
            u = 0.0
        vel = np.zeros_like(pos)
        vel[:, 0] = vx
        rho = p.rho0 * (1.0 + p.amplitude * np.sin(k * pos[:, 0]))
        particles = ParticleSet.create(pos, vel, mass=mass, h=hfact * (mass / rho) ** (1.0 / ndim), u=u,
                                       alpha=opts.alpha)
        box = Box.periodic_box(ndim, (0.0,) * ndim, tuple(hi))
        support = kernel.radius * hfact * (mass / p.rho0) ** (1.0 / ndim) * (1 + opts.neighbour_buffer)
        if ndim > 1 and 2 * support > min(hi[1:]):
            raise ConfigError(f"problem.layers = {p.layers} is too thin for the {opts.kernel} kernel: the box "
                              f"must be at least {2 * support:.3g} across")
        return SPHEngine(particles, box, eos, opts)


preset("sph-soundwave-2d", SPHSoundWave, "Linear sound wave in a periodic 2D SPH box (hexagonal lattice, quintic).",
       problem={"ndim": 2, "nx": 32}, sph={"kernel": "quintic"})
preset("sph-soundwave-3d", SPHSoundWave, "Linear sound wave in a periodic 3D SPH box (close-packed, quintic).",
       problem={"ndim": 3, "nx": 32}, sph={"kernel": "quintic"})
