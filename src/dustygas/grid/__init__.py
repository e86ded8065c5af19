"""Eulerian engine: isothermal Godunov gas on a uniform mesh, in 1D, 2D and 3D shearing boxes.

Modules
-------
mesh
    :class:`Mesh`: one block of cells with ghost zones; the integer/float records kernels get.
reconstruct, riemann
    PLM (minmod, van Leer, MC), PPM (Colella & Woodward 1984) and PPM with the Colella &
    Sekora (2008) extremum-preserving limiter; isothermal HLLE and HLLC fluxes.
sweep
    The fused per-pencil kernel: gather, reconstruct, Riemann solve, update, source terms.
sweep_columns
    The same kernel for the y and z sweeps, on blocks of neighbouring columns (vectorised across x).
integrator
    VL2 (Stone & Gardiner 2009), RK2, RK3 as stage tables; the particle coupling hook.
boundaries, remap
    Ghost zones (periodic, shear-periodic, outflow, reflecting, hydrostatic) and the
    conservative shift.
shearing_box, orbital_advection
    Coriolis/tidal/pressure-gradient/vertical-gravity sources (thesis eq. 4.2b); FARGO.
diagnostics
    Courant time step (thesis eqs. 2.12-2.13) and history sums.
engine
    :class:`GridEngine` (run-loop protocol) and :class:`GridGeometry` (for particles).
params
    Configuration sections shared by the grid problems and :func:`engine_from_config`.
"""

from .engine import GridEngine, GridGeometry  # noqa: E402
from .mesh import Mesh  # noqa: E402

__all__ = ["GridEngine", "GridGeometry", "Mesh"]
