"""Particle-mesh assignment: NGP, CIC and TSC weights, one stencil for gathering and depositing.

A particle at position ``x`` exchanges momentum with the cells of a small stencil around it
(thesis §4.2; Hockney & Eastwood 1981, §5-3). Along one active axis with cell size ``Δx`` and
the particle at ``s = (x - x_0)/Δx - 1/2`` cell widths from the centre of cell 0, the
one-dimensional assignment functions are

=====  ===========================================================  =====================
NGP    ``W = 1`` in the nearest cell ``i = round(s)``                 1 cell
CIC    ``W = 1 - f, f`` in cells ``i, i + 1`` (``i = floor(s)``,      2 cells
       ``f = s - i``)
TSC    ``W = (1/2 - d)^2/2, 3/4 - d^2, (1/2 + d)^2/2`` in cells       3 cells
       ``i - 1, i, i + 1`` (``i = round(s)``, ``d = s - i``)
TSC-C  TSC convolved with the filter ``1 - δ²/8`` (``δ²u_j = u_{j+1} - 2u_j + u_{j-1}``):  5 cells
       weights ``-W_{-1}/8, W_{-1} - (W_0 - 2W_{-1})/8, ...``
=====  ===========================================================  =====================

and the weight of a cell in 2D and 3D is the product over the active axes. Every assignment
function sums to one over the cells for any position (a partition of unity), so a particle
deposits exactly its own mass and momentum, and a uniform lattice of particles deposits a
uniform density whatever its offset (for TSC and CIC; NGP needs the lattice on the cell
centres).

The stencil of a particle is assembled in the particle loop of :mod:`dustygas.particles.push`
(the only hot loop; compiled helpers that write into arrays cost a reference-count update per
call, so the assembly is written out there once for every use). The **same stencil and
weights** serve to gather the gas velocity at the particle (thesis eq.
4.22, :math:`\\bar u(x_d) = \\sum_a W(x_d - x_a) u_a`) and to deposit its back-reaction
(eq. 4.24), so the drag impulse the gas receives is exactly minus the one the particles
receive (eq. 4.25) and no particle accelerates itself (Youdin & Johansen 2007).

Boundaries: the stencil wraps periodically. In a shear-periodic box with an active y axis a
cell index beyond the radial boundary stands for a cell of the radial *image* of the box,
which slides in y by the shear offset ``s_y = q Ω L_x t`` (content at ``(x - L_x, y)`` is that
at ``(x, y - s_y)``): the columns reached through the inner boundary are weighted at
``y - s_y``, those through the outer boundary at ``y + s_y`` -- the weights of the particle's
image, so the stencil still sums to one. When the full azimuthal velocity is stored, gas
gathered through the inner (outer) boundary has ``v_y`` larger (smaller) by ``q Ω L_x``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

from numba import njit

__all__ = ["NGP", "CIC", "TSC", "TSC_C", "KERNELS", "KERNEL_WIDTH", "KERNEL_REACH", "MAX_STENCIL", "Cells",
           "axis_weights", "into_box"]

NGP, CIC, TSC, TSC_C = 0, 1, 2, 3
#: name -> code of the assignment functions
KERNELS = {"ngp": NGP, "cic": CIC, "tsc": TSC, "tsc-c": TSC_C}
#: cells per axis of each assignment function, by code
KERNEL_WIDTH = (1, 2, 3, 5)
#: cells a particle's stencil reaches on either side of its own cell, by code
KERNEL_REACH = (0, 1, 1, 2)
#: most cells a particle's stencil can hold (compensated TSC in 3D)
MAX_STENCIL = 125


class Cells(NamedTuple):
    """What the particle kernels know of the mesh (built from :class:`~dustygas.grid.GridGeometry`).

    ``n*``: domain cells per axis (1: inactive); ``g*``: ghost cells per side of the gas
    arrays; ``d*``, ``*0``, ``l*``: cell sizes, lower corner, box lengths; ``shear``: radial
    boundaries shear-periodic; ``jump``: ``q Ω L_x`` if the stored gas ``v_y`` is the full
    velocity, else 0; ``shear_rate``: ``q Ω L_x`` (the sliding speed of the images).
    """

    nx: int
    ny: int
    nz: int
    gx: int
    gy: int
    gz: int
    dx: float
    dy: float
    dz: float
    x0: float
    y0: float
    z0: float
    lx: float
    ly: float
    lz: float
    shear: bool
    jump: float
    shear_rate: float


@njit(cache=True, error_model="numpy")
def axis_weights(s: float, order: int):
    """First cell ``i`` and the weights ``(w0, ..., w4)`` of cells ``i, ..., i+4`` along one axis.

    ``s`` is the particle position in cell widths from the centre of cell 0; unused weights
    are 0 (NGP uses one cell, CIC two, TSC three, compensated TSC five).
    """
    # floor(v) as int(v + 2) - 2: exact for v > -2 (particles lie within a cell of the box) and
    # much cheaper than a call to floor
    if order == CIC:
        i = int(s + 2.0) - 2
        f = s - i
        return i, 1.0 - f, f, 0.0, 0.0, 0.0
    if order == NGP:
        return int(s + 2.5) - 2, 1.0, 0.0, 0.0, 0.0, 0.0
    i = int(s + 2.5) - 2
    d = s - i
    a = 0.5 - d
    b = 0.5 + d
    wm, w0, wp = 0.5 * a * a, 0.75 - d * d, 0.5 * b * b
    if order == TSC:
        return i - 1, wm, w0, wp, 0.0, 0.0
    # TSC convolved with the filter 1 - δ²/8 (δ² u_j = u_{j+1} - 2 u_j + u_{j-1})
    e = 0.125
    return (i - 2, -e * wm, wm - e * (w0 - 2.0 * wm), w0 - e * (wp - 2.0 * w0 + wm), wp - e * (w0 - 2.0 * wp),
            -e * wp)


@njit(cache=True, error_model="numpy")
def into_box(s: float, n: int) -> float:
    """``s`` (in cell widths from the centre of cell 0) moved by whole periods into [-1/2, n - 1/2)."""
    return s - n * math.floor((s + 0.5) / n)
