"""Configuration section shared by the particle problems, and particle set-up helpers.

::

    [particles]  lattice kernel feedback cfl drag_cfl smooth boundary_x boundary_y boundary_z

``lattice`` particles per cell along each active axis (1: one particle per cell in 2D and 3D),
``kernel`` the assignment function, ``cfl`` the particle Courant number (0: the gas's),
``drag_cfl`` an optional limit ``Δt <= drag_cfl t_s`` (the drag integrator needs none),
``boundary_*`` the particle boundary of each axis (``auto``: the gas's periodic kinds, and
``outflow`` where the gas is open).
"""

from __future__ import annotations

import numpy as np

from ..config import Config, Param
from ..parallel.comm import launched_under_mpi
from .boundaries import PARTICLE_BOUNDARIES
from .coupling import ParticleGridEngine
from .interp import KERNELS
from .store import ParticleStore

__all__ = ["PARTICLES", "lattice_positions", "particle_engine_from_config", "particle_boundaries"]

PARTICLES: dict[str, Param] = {
    "lattice": Param(1, "particles per cell along each active axis (lattice^ndim per cell)", min=1),
    "kernel": Param("tsc", "assignment function for gather and deposit (thesis eqs. 4.22, 4.24)",
                    choices=tuple(KERNELS)),
    "feedback": Param(True, "back-reaction of the drag on the gas"),
    "cfl": Param(0.0, "particle Courant number (0: that of the gas)", min=0.0, max=1.0),
    "drag_cfl": Param(0.0, "if > 0, limit the step to drag_cfl times the smallest stopping time (not needed: the "
                      "drag is integrated exactly)", min=0.0),
    "smooth": Param(True, "gather and deposit through the grid-scale filter 1 - d^4/16 (removes the aliasing "
                    "instability of drifting particles at the grid scale)"),
    **{f"boundary_{a}": Param("auto", f"particle boundary along {a} (auto: periodic where the gas is, else outflow)",
                              choices=("auto",) + tuple(PARTICLE_BOUNDARIES)) for a in "xyz"},
}


def particle_boundaries(cfg: Config, gas_kinds: tuple[str, str, str]) -> tuple[str, str, str]:
    """The particle boundary of each axis from ``[particles] boundary_*`` (``auto`` resolved)."""
    out = []
    for a, gas in zip("xyz", gas_kinds):
        kind = cfg.particles[f"boundary_{a}"] if f"boundary_{a}" in cfg.particles else "auto"
        if kind == "auto":
            kind = gas if gas in ("periodic", "shear-periodic") else "outflow"
        out.append(kind)
    return tuple(out)


def lattice_positions(shape: tuple[int, int, int], lower, dx, lattice: int, offset: float = 0.5) -> np.ndarray:
    """Positions ``(3, N)`` of ``lattice`` particles per cell and active axis, evenly spaced
    (at ``(j + offset)/lattice`` of each cell), sorted like the cells (x fastest).

    Put a lattice where the assignment function is smooth: CIC's weights have a kink at the
    cell centres (use ``offset = 0`` for an odd ``lattice``), NGP's a jump at the faces.

    >>> lattice_positions((2, 1, 1), (0.0, 0.0, 0.0), (1.0, 1.0, 1.0), 2)[0].tolist()
    [0.25, 0.75, 1.25, 1.75]
    """
    axes = []
    for n, lo, d in zip(shape, lower, dx):
        if n > 1:
            m = n * lattice
            axes.append(lo + (np.arange(m) + offset) * d / lattice)
        else:
            axes.append(np.zeros(1))
    z, y, x = np.meshgrid(axes[2], axes[1], axes[0], indexing="ij")
    return np.stack([x.ravel(), y.ravel(), z.ravel()])


def particle_engine_from_config(cfg: Config, gas, store: ParticleStore, t_stop, cls=ParticleGridEngine,
                                **kwargs) -> ParticleGridEngine:
    """A :class:`ParticleGridEngine` (or subclass ``cls``) with the ``[particles]`` section of ``cfg``;
    under ``mpiexec``, its :class:`~dustygas.parallel.coupled.DistributedParticleEngine`."""
    p = cfg.particles
    kwargs.setdefault("boundaries", particle_boundaries(cfg, gas.geometry.boundaries))
    engine = cls(gas, store, t_stop, kernel=p.kernel, feedback=p.feedback, cfl=p.cfl if p.cfl > 0 else None,
                 drag_cfl=p.drag_cfl, smooth=p.smooth, **kwargs)
    if launched_under_mpi():  # the whole box on every rank, then each keeps its block (mpi4py imported only here)
        from ..parallel.coupled import distribute

        return distribute(engine)  # type: ignore[return-value]
    return engine
