"""``sph-kepler-ring``: a cold ring of gas (or test) particles orbiting a point-mass star.

Particles fill an annulus :math:`R_0 - w/2 < R < R_0 + w/2` in the x-y plane (concentric rows,
equal arc spacing, so the surface density is uniform) around a star of :math:`GM = 1` at the
origin, each on the circular Keplerian orbit of the (softened) point mass,
:math:`v_\\phi = \\sqrt{GM R^2/(R^2+\\epsilon^2)^{3/2}}`. With ``particles = "gas"`` they are
isothermal SPH gas of sound speed :math:`c_s \\ll v_K` (a cold ring, slowly spreading under its
own pressure); with ``particles = "test"`` they feel the star only. In 3D the ring has
``layers`` rows in z and the gas also feels nothing but the star.

Every force is central (the star's) or along the line joining two particles (pressure and
viscosity), so the total angular momentum about the z axis is conserved to round-off; one
orbit at :math:`R_0 = 1` takes :math:`2\\pi`.
"""

from __future__ import annotations

import numpy as np

from ..config import Param, with_defaults
from ..runner import RUN_SCHEMA
from ..sph import TEST, Box, EquationOfState, ExternalForces, ParticleSet, SPHEngine, get_kernel
from ..sph.schema import SPH_SCHEMA, options_from_config
from . import Problem, register

__all__ = ["SPHKeplerRing", "ring_positions"]


def ring_positions(radius: float, width: float, rows: int, layers: int = 1) -> np.ndarray:
    """Points on ``rows`` concentric circles across the annulus, spaced ``width/rows`` along each
    circle, and ``layers`` copies spaced alike in z (centred on z = 0); ``(N, 3)``."""
    spacing = width / rows
    out = []
    for i in range(rows):
        r = radius - 0.5 * width + (i + 0.5) * spacing
        n = max(3, int(round(2 * np.pi * r / spacing)))
        phi = 2 * np.pi * (np.arange(n) + 0.5 * (i % 2)) / n
        ring = np.stack([r * np.cos(phi), r * np.sin(phi), np.zeros(n)], 1)
        for k in range(layers):
            layer = ring.copy()
            layer[:, 2] = (k - 0.5 * (layers - 1)) * spacing
            out.append(layer)
    return np.concatenate(out)


@register
class SPHKeplerRing(Problem):
    name = "sph-kepler-ring"
    summary = "Cold gas (or test-particle) ring on Keplerian orbits around a point-mass star."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=2 * np.pi, dt_snapshot=np.pi / 2, log_every=1000),
        "sph": with_defaults(SPH_SCHEMA, switch="none", alpha=0.1, alpha_u=0.0),
        "problem": {
            "particles": Param("gas", "isothermal SPH gas or test particles", choices=("gas", "test")),
            "ndim": Param(2, "2: a planar ring; 3: a ring with a few layers in z", choices=(2, 3)),
            "radius": Param(1.0, "ring radius R_0", "code length", min=0.0, min_open=True),
            "width": Param(0.2, "ring width w", "code length", min=0.0, min_open=True),
            "rows": Param(8, "concentric rows across the ring", min=1),
            "layers": Param(4, "rows in z (3D only)", min=1),
            "ring_mass": Param(1e-3, "total ring mass", "M_star", min=0.0, min_open=True),
            "cs": Param(0.02, "isothermal sound speed", "v_K(R_0)", min=0.0, min_open=True),
            "softening": Param(0.0, "Plummer softening of the star", "code length", min=0.0),
            "accretion_radius": Param(0.1, "particles closer to the star are accreted", "code length", min=0.0),
        },
    }

    def build(self, cfg) -> SPHEngine:
        p, opts = cfg.problem, options_from_config(cfg.sph)
        ndim = p.ndim
        pos = ring_positions(p.radius, p.width, p.rows, p.layers if ndim == 3 else 1)
        n = len(pos)
        R = np.hypot(pos[:, 0], pos[:, 1])
        r2 = R**2 + pos[:, 2] ** 2 + p.softening**2
        vphi = np.sqrt(R**2 / r2**1.5)
        vel = np.zeros_like(pos)
        vel[:, 0] = -vphi * pos[:, 1] / R
        vel[:, 1] = vphi * pos[:, 0] / R
        spacing = p.width / p.rows
        kernel = get_kernel(opts.kernel, ndim)
        hfact = opts.hfact or kernel.default_hfact
        particles = ParticleSet.create(pos[:, :ndim], vel[:, :ndim], mass=p.ring_mass / n, h=hfact * spacing,
                                       alpha=opts.alpha)
        if p.particles == "test":
            particles.ptype[:] = TEST
        star = ExternalForces(star_gm=1.0, softening=p.softening, accretion_radius=p.accretion_radius)
        return SPHEngine(particles, Box.open_box(ndim), EquationOfState.isothermal(p.cs), opts, star)
