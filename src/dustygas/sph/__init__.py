"""Smoothed particle hydrodynamics (thesis §3.1 and §2.3).

Modules
-------
kernels
    M4, M6, Wendland C2/C4 kernels in 1/2/3D and the Laibe & Price (2012) double-hump drag kernels.
neighbours, kdtree, pairs
    Periodic/open domains (:class:`Box`); cell-list and k-d tree neighbour searches behind one
    :class:`NeighbourFinder`, and the pair geometry (minimum image, neighbour rows) both share.
density
    Density summation (eq. 3.1) with self-consistent smoothing lengths and grad-h terms.
eos, viscosity, forces, external
    Equations of state; artificial viscosity, conductivity and the Morris & Monaghan and
    Cullen & Dehnen switches; the GASOLINE2 and
    Price (2012) pressure forces with the energy equation (eqs. 3.2-3.3); external forces.
integrator
    The kick-drift-kick leapfrog (time-step criteria, eqs. 2.13-2.15: :mod:`dustygas.physics.timestep`).
particles, engine, modules, schema
    The struct-of-arrays particle store, :class:`SPHEngine` for the run loop, the hooks through
    which extra physics plugs into it, and the ``[sph]`` configuration section shared by the SPH
    problems.
dust
    One-fluid and two-fluid dust, grain sizes (thesis §3.2-3.3).
lattice, render
    Initial particle arrangements and SPH interpolation onto grids.
"""

from .engine import SPHEngine, SPHOptions
from .eos import EquationOfState
from .external import ExternalForces
from .kernels import KERNEL_NAMES, KernelSpec, get_kernel
from .neighbours import Box, NeighbourFinder, NeighbourList
from .particles import DUST, GAS, TEST, ParticleSet

__all__ = [
    "SPHEngine",
    "SPHOptions",
    "EquationOfState",
    "ExternalForces",
    "KERNEL_NAMES",
    "KernelSpec",
    "get_kernel",
    "Box",
    "NeighbourFinder",
    "NeighbourList",
    "ParticleSet",
    "GAS",
    "DUST",
    "TEST",
]
