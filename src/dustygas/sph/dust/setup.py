"""Set-up helpers shared by the dust problems: lattices, one- or two-fluid particle sets, species views.

:func:`dusty_particles` turns a gas lattice into either mixture particles (one-fluid: total
density, dust fraction) or gas particles plus dust particles at the same positions (two-fluid,
as Phantom's dust set-ups do), and :func:`species` reads gas and dust positions and velocities
back from either, so that problems and tests compare both formulations with one exact solution.

Examples
--------
>>> import numpy as np
>>> pos, hi = lattice(1, 4, 2, -0.5)
>>> pos[:, 0].tolist(), hi.tolist()
([-0.375, -0.125, 0.125, 0.375], [0.5])
"""

from __future__ import annotations

import numpy as np

from ..lattice import close_packed_lattice, cubic_lattice
from ..particles import DUST, GAS, ParticleSet

__all__ = ["lattice", "dusty_particles", "species", "dust_module"]


def lattice(ndim: int, nx: int, layers: int, x0: float, length: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """``nx`` particles along :math:`x_0 \\le x < x_0 + L` (a row in 1D; hexagonal-close-packed with
    ``layers`` rows and layers across, starting at 0, in 3D). Returns positions and the upper corner."""
    spacing = length / nx
    if ndim == 1:
        return cubic_lattice((nx,), (x0,), (x0 + length,)), np.array([x0 + length])
    if ndim == 3:
        return close_packed_lattice((nx, layers, layers), spacing, (x0, 0.0, 0.0))
    raise ValueError("dust problems are 1D or 3D")


def dusty_particles(method: str, pos: np.ndarray, volume: float, rho_gas, rho_dust, vel_gas, vel_dust,
                    hfact: float, ndim: int, u_gas=0.0) -> tuple[ParticleSet, dict]:
    """Particles for ``method`` (``one-fluid`` or ``two-fluid``) on the lattice ``pos``.

    ``rho_gas``, ``rho_dust`` (per lattice point or scalars) are the densities the lattice
    represents (its points must already be placed for that profile), ``vel_gas``/``vel_dust`` the
    velocities ``(N, 3)`` or scalars along x. Equal-mass particles: each species' total mass is its
    mean density times ``volume``. Returns the set and, for one-fluid, ``{"dust_fraction",
    "delta_v"}`` to initialise the module (empty for two-fluid).
    """
    n = len(pos)
    rg = np.broadcast_to(np.asarray(rho_gas, dtype=np.float64), (n,))
    rd = np.broadcast_to(np.asarray(rho_dust, dtype=np.float64), (n,))

    def vec(v):
        v = np.asarray(v, dtype=np.float64)
        if v.ndim == 2:
            return v
        out = np.zeros((n, 3))
        out[:, 0] = v
        return out

    vg, vd = vec(vel_gas), vec(vel_dust)
    if method == "one-fluid":
        rho = rg + rd
        mass = float(np.mean(rho)) * volume / n
        eps = rd / rho
        vbar = (rg[:, None] * vg + rd[:, None] * vd) / rho[:, None]
        p = ParticleSet.create(pos, vbar, mass=mass, h=hfact * (mass / rho) ** (1.0 / ndim), u=u_gas)
        return p, {"dust_fraction": eps, "delta_v": vd - vg}
    m_g = float(np.mean(rg)) * volume / n
    m_d = float(np.mean(rd)) * volume / n
    gas = ParticleSet.create(pos, vg, mass=m_g, h=hfact * (m_g / rg) ** (1.0 / ndim), u=u_gas, ptype=GAS)
    dust = ParticleSet.create(pos, vd, mass=m_d, h=hfact * (m_d / rd) ** (1.0 / ndim), u=0.0, ptype=DUST)
    both = {name: np.concatenate([getattr(gas, name), getattr(dust, name)])
            for name in ("pos", "vel", "mass", "h", "u", "alpha", "ptype")}
    p = ParticleSet(**both, pid=np.arange(2 * n, dtype=np.int64))
    return p, {}


def species(engine) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """``{"gas": (positions, velocities), "dust": (positions, velocities)}`` of a dusty engine.

    Two-fluid: the particles of each type. One-fluid: every mixture particle, with
    :math:`\\mathbf v_g = \\mathbf v - \\epsilon\\Delta\\mathbf v` and :math:`\\mathbf v_d = \\mathbf v + (1-\\epsilon)\\Delta\\mathbf v`
    (:math:`\\Delta\\mathbf v = 0` in the terminal-velocity approximation, where the species share
    the barycentric velocity to first order in :math:`t_s`).
    """
    p = engine.particles
    if (p.ptype == DUST).any():
        g, d = p.ptype == GAS, p.ptype == DUST
        return {"gas": (p.pos[g], p.vel[g]), "dust": (p.pos[d], p.vel[d])}
    eps = p.extra["dust_fraction"][:, None]
    dv = p.extra.get("delta_v", np.zeros_like(p.vel))
    return {"gas": (p.pos, p.vel - eps * dv), "dust": (p.pos, p.vel + (1.0 - eps) * dv)}


def dust_module(engine):
    """The one-fluid or two-fluid module of ``engine``."""
    from .one_fluid import OneFluidDust
    from .two_fluid import TwoFluidDust

    for module in engine.modules:
        if isinstance(module, (OneFluidDust, TwoFluidDust)):
            return module
    raise LookupError("the engine has no dust module")
