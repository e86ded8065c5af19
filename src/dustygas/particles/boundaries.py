"""Particle boundaries: periodic and shear-periodic (thesis §4.3.1; Hawley, Gammie & Balbus 1995).

A particle that leaves the box re-enters through the opposite face. Across the radial (x)
faces of a shearing box the images of the box slide along y: image ``n`` of a point
``(x, y)`` of the box is ``(x + n L_x, y - n s_y)`` with ``s_y = q Ω L_x t`` (the same
convention as the gas ghost zones of :mod:`dustygas.grid.boundaries`, where the inner
image at ``x - L_x`` holds the content at ``y - s_y``), and its full azimuthal velocity is
smaller by ``n q Ω L_x`` (the background shear ``-q Ω x`` one box further out). So a particle
found at ``x`` beyond the outer face (``n = +1``) re-enters at
``(x - L_x, y + s_y)`` with ``v_y + q Ω L_x``, one beyond the inner face (``n = -1``) at
``(x + L_x, y - s_y)`` with ``v_y - q Ω L_x``; velocities stored relative to the shear
(orbital advection) do not jump. y and z are periodic. Inactive axes are left alone.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["wrap_particle"]


@njit(cache=True, error_model="numpy")
def _periods(v: float, lo: float, length: float) -> int:
    """How many box lengths ``v`` lies beyond ``[lo, lo + length)`` (comparisons first: a particle
    rarely moves by more than a box, and a call to floor is slow)."""
    if v < lo:
        if v >= lo - length:
            return -1
    elif v < lo + length:
        return 0
    elif v < lo + 2.0 * length:
        return 1
    return int(math.floor((v - lo) / length))


@njit(cache=True, error_model="numpy")
def wrap_particle(x, y, z, vy, cells, y_shift):
    """Position and ``v_y`` of a particle mapped back into the box (module docstring) at shear
    offset ``y_shift``; returns ``(x, y, z, v_y)``.

    (Scalars in, scalars out: a compiled helper that writes into arrays costs a reference-count
    update per call, more than the whole wrap.)
    """
    if cells.nx > 1:
        n = _periods(x, cells.x0, cells.lx)
        if n != 0:
            x -= n * cells.lx
            if cells.shear:
                if cells.ny > 1:
                    y += n * y_shift
                vy += n * cells.jump
    if cells.ny > 1:
        n = _periods(y, cells.y0, cells.ly)
        if n != 0:
            y -= n * cells.ly
    if cells.nz > 1:
        n = _periods(z, cells.z0, cells.lz)
        if n != 0:
            z -= n * cells.lz
    return x, y, z, vy
