"""Orbital advection (FARGO): transport by the background shear as an exact remap.

With orbital advection the engine integrates the equations for the velocity relative to the
shear, ``v' = v + q Omega x y^``; the advection of everything by the background flow
``-q Omega x y^`` is split off and done once per step by shifting every azimuthal column by
``-q Omega x dt`` (Masset 2000; Johnson, Guan & Gammie 2008, hereafter JGG08; Stone & Gardiner
2010). The shift is an integer number of cells plus a reconstructed fractional part
(:func:`~dustygas.grid.remap.shift_column`), so it conserves every column's mass and momentum
to round-off and imposes no time-step limit: the Courant condition sees only ``|v'| + c_s``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from .remap import shift_column

__all__ = ["orbital_advection", "remap_columns"]


@njit(cache=True, error_model="numpy")
def remap_columns(u, dt, shear_rate, lay, sp, xc, method, limiter, c0, c1) -> None:
    """Shift y-columns ``c0 .. c1-1`` of ``u`` (all four variables) by ``-shear_rate x dt``.

    Parameters
    ----------
    u
        State ``(4, NZ, NY, NX)``; domain cells are remapped in place, ghosts untouched.
    shear_rate
        ``q Omega``.
    xc
        Cell-centre x coordinates, ghosts included.
    method, limiter
        Reconstruction of the fractional shift.
    c0, c1
        Column range; column ``c`` is domain ``(i, k) = (c % nx, c // nx)``.
    """
    nx, ny, nz, gx, gy, gz = lay
    if ny == 1:
        return
    col = np.empty(ny)
    out = np.empty(ny)
    work = np.empty(4 * ny + 19)
    for item in range(c0, c1):
        i = gx + item % nx
        k = gz + item // nx
        shift = -shear_rate * xc[i] * dt / sp.dy
        for v in range(4):
            column = u[v, k, gy:gy + ny, i]  # a strided view: loop indices start at 0
            for j in range(ny):
                col[j] = column[j]
            shift_column(col, ny, shift, method, limiter, out, work)
            for j in range(ny):
                column[j] = out[j]


@njit(cache=True, parallel=True, error_model="numpy")
def orbital_advection(u, dt, shear_rate, lay, sp, xc, method, limiter, nchunk) -> None:
    """Advect ``u`` by the background shear for ``dt`` (all columns; see :func:`remap_columns`)."""
    ncol = lay.nx * lay.nz
    nchunk = min(ncol, nchunk)
    for c in prange(nchunk):
        remap_columns(u, dt, shear_rate, lay, sp, xc, method, limiter, c * ncol // nchunk, (c + 1) * ncol // nchunk)
