"""Lagrangian dust particles in the grid engine (thesis §4.2, eqs. 4.22-4.25).

Modules
-------
store
    :class:`ParticleStore`: struct-of-arrays (position, velocity, species, id, mass), kept
    sorted by cell with a stable counting sort.
interp
    NGP/CIC/TSC assignment functions; one stencil for gathering (4.22) and depositing (4.24).
deposit
    Gas fields for the gather; the race-free, thread-count independent deposit by slabs.
drag
    Velocity update over a step: Bai & Stone (2010a) semi-implicit, or exact exponential.
boundaries
    Periodic and shear-periodic particle boundaries.
push
    The two compiled particle stages of a coupled VL2 step.
coupling
    :class:`ParticleGridEngine`: the run-loop engine of gas + particles, and the scheme.
diagnostics
    Fourier-mode amplitudes of gas and particles for the growth analysis.

The particles know the grid only through :class:`~dustygas.grid.GridGeometry` and the stage
interface of :class:`~dustygas.grid.GridEngine` (``stage_input``, ``advance_stage``).
"""

from .coupling import DRAG_LAWS, ParticleGridEngine  # noqa: E402
from .drag import DRAG_INTEGRATORS  # noqa: E402
from .interp import KERNELS  # noqa: E402
from .store import ParticleStore  # noqa: E402

__all__ = ["ParticleGridEngine", "ParticleStore", "KERNELS", "DRAG_INTEGRATORS", "DRAG_LAWS"]
