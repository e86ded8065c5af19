"""The gas's own gravity as a momentum source of the grid engine's stages.

:class:`GasSelfGravity` is a stage hook for :meth:`~dustygas.grid.GridEngine.advance_with_sources`:
before each stage it solves ``∇²Φ = 4πG ρ_gas`` for the state that stage reads and returns the
momentum source ``S = -ρ ∇Φ`` (per unit volume and time). Its cell sum is zero to round-off
(see :mod:`dustygas.grid.gravity`), so self-gravity leaves the gas's total momentum unchanged.
The gas is isothermal, so there is no energy source.
"""

from __future__ import annotations

import numpy as np

from ...errors import SetupError
from .poisson import PoissonSolver

__all__ = ["GasSelfGravity", "gravity_boundaries"]


def gravity_boundaries(engine_boundaries: tuple[str, str, str], active: tuple[bool, bool, bool],
                       z_boundary: str) -> tuple[str, str, str]:
    """The potential's boundaries for a mesh whose gas has ``engine_boundaries``.

    x must be periodic or shear-periodic and y periodic (an inactive axis is fine whatever it is
    called); z is ``z_boundary`` ("periodic" needs periodic gas, "vacuum" goes with any).
    """
    bx, by, bz = engine_boundaries
    if active[0] and bx not in ("periodic", "shear-periodic"):
        raise SetupError(f"gravity: x boundary '{bx}' is not supported: self-gravity needs periodic or "
                         "shear-periodic x")
    if active[1] and by != "periodic":
        raise SetupError(f"gravity: y boundary '{by}' is not supported: self-gravity needs periodic y")
    if z_boundary not in ("periodic", "vacuum"):
        raise SetupError(f"gravity: z boundary '{z_boundary}': choose periodic or vacuum")
    if z_boundary == "periodic" and active[2] and bz != "periodic":
        raise SetupError(f"gravity: a periodic potential in z needs periodic z boundaries, not '{bz}' "
                         "(use vacuum)")
    return ("shear-periodic" if bx == "shear-periodic" else "periodic", "periodic", z_boundary)


class GasSelfGravity:
    """Stage hook returning ``-ρ∇Φ`` of the gas's own gravity (module docstring).

    Parameters
    ----------
    engine
        The :class:`~dustygas.grid.GridEngine` whose gas gravitates.
    four_pi_G
        ``4πG`` (code units: ``G̃``).
    z_boundary
        "periodic" or "vacuum" (with a single z cell: a razor-thin sheet whose density
        variable is the surface density).
    order
        Order of the centred differences of ``∇Φ`` (2 or 4).
    """

    def __init__(self, engine, four_pi_G: float, z_boundary: str = "periodic", order: int = 2):
        mesh = engine.mesh
        self._geometry = engine.geometry
        bounds = gravity_boundaries(engine.boundary_kinds, mesh.active, z_boundary)
        self.solver = PoissonSolver(mesh.shape, mesh.size, four_pi_G, bounds, order)
        self._inner = (0,) + mesh.interior()
        nx, ny, nz = mesh.shape
        self._acc = np.empty((3, nz, ny, nx))

    def __call__(self, stage: int, u: np.ndarray, t: float, dt: float) -> np.ndarray:
        rho = u[self._inner]
        acc = self.solver.acceleration(np.ascontiguousarray(rho), self._geometry.shear_offset(t), out=self._acc)
        return acc * rho[None]
