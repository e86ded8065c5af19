"""Lagrangian dust particles in the grid engine (thesis §4.2, eqs. 4.22-4.25).

Modules
-------
store
    :class:`ParticleStore`: growable struct-of-arrays (position, velocity, species, id, mass),
    kept in canonical order (by cell, then id) with a stable parallel counting sort.
interp
    NGP/CIC/TSC assignment weights around the containing cell; one stencil for gathering
    (4.22) and depositing (4.24).
boundaries
    Particle boundaries per axis (periodic, shear-periodic, outflow, reflecting): the exchange
    step and the image records of the deposits -- the one place that knows about neighbours.
deposit
    Pull deposits (thread-count and block-split independent) and the grid-scale filter.
drag
    Stopping-time laws; the local drag problem of a cell with any number of species, exact in
    the stiff limit; the exact particle update and vertical oscillator.
terms
    Forces on the particles and sources on the gas as composable terms.
push
    The compiled particle passes of a step.
coupling
    :class:`ParticleGridEngine`: the run-loop engine of gas + particles, and the scheme.
diagnostics
    Fourier-mode amplitudes (growth analysis) and per-species moments (scale height,
    velocity dispersions).

The particles know the grid only through :class:`~dustygas.grid.GridGeometry`, the kernel
records of :mod:`dustygas.grid.mesh`, the field ghost fill of :mod:`dustygas.grid.boundaries`
and the stage interface of :class:`~dustygas.grid.GridEngine` (``stage_input``,
``advance_stage``).
"""

from .coupling import ParticleGridEngine
from .drag import DRAG_LAWS
from .interp import KERNELS
from .store import ParticleStore
from .terms import (ConstantAcceleration, GasConstantAcceleration, GasMeshAcceleration, MeshAcceleration,
                    RotatingFrame, VerticalGravity)

__all__ = ["ParticleGridEngine", "ParticleStore", "KERNELS", "DRAG_LAWS", "RotatingFrame", "VerticalGravity",
           "ConstantAcceleration", "MeshAcceleration", "GasConstantAcceleration", "GasMeshAcceleration"]
