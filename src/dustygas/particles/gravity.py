"""Self-gravity of the particles as a mesh term (thesis §4.5; Johansen et al. 2007; Simon et al. 2016).

:class:`SelfGravity` is a :class:`~dustygas.particles.terms.MeshAcceleration`: at every step it
takes the particle density the engine deposited for the drag problem (positions ``x^{n+1/2}``,
the same assignment function, TSC by default, and the same weights), solves

.. math:: \\nabla^2 \\Phi = 4\\pi G \\rho_p = \\tilde G \\rho_p, \\qquad
          \\tilde G = \\frac{4\\pi G \\rho_{g0}}{\\Omega^2}

(Simon et al. 2016, ApJ 822, 55, eq. 6; code units ``Ω = ρ_g0 = 1``) with the FFT solver of
:mod:`dustygas.grid.gravity` at the shear offset of ``t^{n+1/2}``, and hands the engine the
field ``g = -∇Φ`` (centred differences), which every particle gathers with its own weights and
holds over the step with the rotating-frame terms.

Momentum: the deposit and the gather use the same weights, the Green's function is even and the
difference operator odd, and the grid-scale filter the particles gather through is an even
convolution too, so the mesh force of a pair of particles is antisymmetric and the net
self-gravity of the particles vanishes to round-off (Hockney & Eastwood 1981, §5-3) -- with
periodic axes and vacuum z; across a shear-periodic face the ghost cells of the gathered field
are interpolated and the cancellation holds only to that interpolation's error.

Like Athena's particle self-gravity (Simon et al. 2016), the gas feels none and contributes
none (``ρ_p ≫`` the gas in the collapsing filaments; the gas's own self-gravity is
:mod:`dustygas.grid.gravity.gas`). The term is off before ``t_on`` (e.g. switched on in the
saturated state of the streaming instability) and has no state of its own: a restart recomputes
the field from the particles, bit for bit.

Boundaries of the potential: x and y as the particles' (``periodic`` or ``shear-periodic``; an
open x or y has no FFT solution here), z ``periodic`` (particles periodic in z only) or
``vacuum`` (any particle z boundary; the solve is restricted to the layers the particles reach).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import SetupError
from ..grid.gravity import PoissonSolver
from .terms import MeshAcceleration

__all__ = ["SelfGravity", "GRAVITY_Z", "gravity_boundaries"]

#: vertical boundary of the potential
GRAVITY_Z = ("auto", "periodic", "vacuum")


class SelfGravity(MeshAcceleration):
    """Particle self-gravity, ``a = -Σ_a W(x - x_a) (∇Φ)_a`` with ``∇²Φ = G̃ ρ_p`` (module docstring).

    Parameters
    ----------
    g_tilde
        ``G̃ = 4πGρ_g0/Ω²`` (``4πG`` in code units); must be positive.
    t_on
        Time from which the term acts (before it the field is zero and nothing is solved).
    boundary_z
        ``"periodic"``, ``"vacuum"`` or ``"auto"`` (periodic if the particles are periodic in z,
        else vacuum).
    order
        Order of the centred differences of ``-∇Φ`` (2 or 4).
    keys
        Names of the configuration entries (``g_tilde``, ``boundary_z``) for error messages.
    """

    def __init__(self, g_tilde: float, t_on: float = 0.0, boundary_z: str = "auto", order: int = 2,
                 keys: tuple[str, str] = ("gravity.g_tilde", "gravity.boundary_z")):
        super().__init__()
        if not (math.isfinite(g_tilde) and g_tilde > 0):
            raise SetupError(f"{keys[0]} = {g_tilde}: must be positive and finite (G~ = 4 pi G rho_g0 / Omega^2)")
        if boundary_z not in GRAVITY_Z:
            raise SetupError(f"{keys[1]} = '{boundary_z}': choose one of {', '.join(GRAVITY_Z)}")
        self.g_tilde = float(g_tilde)
        self.t_on = float(t_on)
        self.boundary_z = boundary_z
        self.order = int(order)
        self.keys = keys
        self.solver: PoissonSolver | None = None
        self.active = False

    @property
    def G(self) -> float:
        """``G`` in code units, ``G̃ / 4π``."""
        return self.g_tilde / (4.0 * math.pi)

    def bind(self, engine) -> None:
        """Check the engine's axes and build the solver of its mesh (called by the engine)."""
        geom = engine.geometry
        shape = tuple(int(n) for n in geom.shape)
        self.boundaries = gravity_boundaries(shape, engine.boundary_kinds, self.boundary_z, self.keys[1])
        self.solver = PoissonSolver(shape, tuple(geom.box), self.g_tilde, self.boundaries, order=self.order, workers=None)
        self.field = np.zeros((3,) + tuple(reversed(shape)))

    def update(self, engine, rho_gas: np.ndarray, t: float) -> None:
        """``field = -∇Φ`` of the particles' deposit at ``t`` (zero before :attr:`t_on`)."""
        self.active = t >= self.t_on
        if not self.active:
            self.field[...] = 0.0
            return
        rho = engine.prepared_particle_density()
        layers = engine.field_rows if self.solver.vacuum_z else None
        self.solver.acceleration(rho, engine.geometry.shear_offset(t), out=self.field, layers=layers)

    # ------------------------------------------------------------------ outputs
    def potential(self, engine, rho_p: np.ndarray) -> np.ndarray:
        """The potential ``(nz, ny, nx)`` of the particle density ``rho_p`` at the engine's time."""
        return self.solver.potential(rho_p, engine.geometry.shear_offset(engine.t))

    def history(self, engine, rho_p: np.ndarray) -> dict[str, float]:
        """``gravity_on`` and the self-gravitational energy ``W = ½ Σ ρ_p Φ V`` (0 before :attr:`t_on`)."""
        on = engine.t >= self.t_on
        energy = 0.0
        if on:
            energy = 0.5 * float(np.sum(rho_p * self.potential(engine, rho_p))) * engine.mesh.cell_volume
        return {"gravity_on": float(on), "gravity_energy": energy}

    def snapshot(self, engine, rho_p: np.ndarray) -> dict[str, np.ndarray]:
        """The potential ``phi_p`` of the particles (written from :attr:`t_on` on)."""
        return {"phi_p": self.potential(engine, rho_p)} if engine.t >= self.t_on else {}

    def attrs(self) -> dict[str, Any]:
        """What ``dustygas analyze clumps`` reads: ``gravity_G`` (code units) and the set-up."""
        return {"gravity_G": self.G, "gravity_g_tilde": self.g_tilde, "gravity_t_on": self.t_on,
                "gravity_boundaries": list(self.boundaries)}


def gravity_boundaries(shape: tuple[int, int, int], particle_kinds: tuple[str, str, str], boundary_z: str = "auto",
                       key: str = "gravity.boundary_z") -> tuple[str, str, str]:
    """The potential's boundary per axis for particles with boundaries ``particle_kinds``
    (one-line :class:`~dustygas.errors.SetupError` for an axis the solver cannot support).

    >>> gravity_boundaries((32, 32, 48), ("shear-periodic", "periodic", "outflow"))
    ('shear-periodic', 'periodic', 'vacuum')
    """
    bounds = []
    for a in range(2):
        if shape[a] > 1 and particle_kinds[a] not in ("periodic", "shear-periodic"):
            raise SetupError(f"self-gravity along {'xy'[a]}: particles.boundary_{'xy'[a]} = '{particle_kinds[a]}' is "
                             f"not supported (the potential needs a periodic or shear-periodic {'xy'[a]})")
        bounds.append(particle_kinds[a] if shape[a] > 1 else "periodic")
    if shape[1] > 1 and bounds[1] == "shear-periodic":
        raise SetupError("self-gravity along y: particles.boundary_y = 'shear-periodic' is not supported (only x "
                         "can be shear-periodic)")
    if bounds[0] == "shear-periodic" and shape[1] == 1:
        bounds[0] = "periodic"  # x-z box: the shear offset moves nothing along an inactive y
    if boundary_z not in GRAVITY_Z:
        raise SetupError(f"{key} = '{boundary_z}': choose one of {', '.join(GRAVITY_Z)}")
    z = boundary_z
    if z == "auto":
        z = "periodic" if particle_kinds[2] == "periodic" else "vacuum"
    if shape[2] > 1 and z == "periodic" and particle_kinds[2] != "periodic":
        raise SetupError(f"{key} = 'periodic' with particles.boundary_z = '{particle_kinds[2]}': a periodic "
                         "potential needs particles periodic in z (use vacuum)")
    if shape[2] == 1:
        z = "periodic"  # a 2D x-y box is a column uniform in z, not a razor-thin sheet
    bounds.append(z)
    return tuple(bounds)
