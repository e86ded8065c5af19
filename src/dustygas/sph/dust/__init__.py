"""Dust in the SPH engine: one-fluid and two-fluid formulations, drag laws, grain sizes (thesis §2-3).

Modules
-------
drag_law
    Constant K, constant stopping time, Epstein drag from the grain size (via :mod:`dustygas.physics.drag`).
one_fluid, one_fluid_kernels
    Mixture particles with a dust fraction: terminal-velocity approximation (Price & Laibe 2015)
    or full one-fluid equations with the relative velocity (Laibe & Price 2014); arithmetic
    (thesis eq. 3.4) or upwind (eqs. 3.15-3.17) dust exchange; :math:`\\sqrt{\\rho\\epsilon}` variable
    (Ballabio et al. 2018); optional, counted clamping (§3.2.4).
two_fluid, two_fluid_kernels
    Dust particles coupled to gas particles by the projected (Monaghan & Kocharyan 1995, thesis
    eq. 3.19) or non-projected (eq. 3.18) drag with the double-hump kernel, explicit or
    pairwise-exponential (implicit) in time, with the velocity reconstruction of Price & Laibe (2020)
    against over-damping, and drag heating.
grain_size
    Local growth and fragmentation (eqs. 3.6-3.7), advection with the exchanged dust (eqs. 3.11-3.14).
schema
    The ``[dust]`` configuration section shared by the dust problems.
"""

from .drag_law import DRAG_LAWS, DragLaw
from .grain_size import GrainGrowth
from .one_fluid import OneFluidDust, OneFluidOptions
from .two_fluid import TwoFluidDust, TwoFluidOptions

__all__ = ["DRAG_LAWS", "DragLaw", "GrainGrowth", "OneFluidDust", "OneFluidOptions", "TwoFluidDust",
           "TwoFluidOptions"]
