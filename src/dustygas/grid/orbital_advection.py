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

from ..arrays import serial_full
from .diagnostics import cell_rate, combine_rates, fold_rate
from .remap import shift_column

__all__ = ["orbital_advection", "remap_columns"]


@njit(cache=True, error_model="numpy")
def remap_columns(u, dt, shear_rate, lay, sp, xc, method, limiter, cs, rates, bads, c0, c1) -> None:
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
    cs
        Sound speed (for the Courant rate).
    rates, bads
        ``(nx nz,)`` outputs: each column's largest Courant rate after the remap
        (:func:`~dustygas.grid.diagnostics.cell_rate`) and its first invalid cell (flat domain
        index, -1 if none).
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
        best = 0.0
        bad = -1
        d, mx, my, mz = u[0, k, gy:gy + ny, i], u[1, k, gy:gy + ny, i], u[2, k, gy:gy + ny, i], u[3, k, gy:gy + ny, i]
        first = (k - gz) * ny * nx + (i - gx)  # flat domain index of cell j: first + j nx
        for j in range(ny):
            best, bad = fold_rate(cell_rate(d[j], mx[j], my[j], mz[j], lay, sp, cs), first + j * nx, best, bad)
        rates[item] = best
        bads[item] = bad


@njit(cache=True, parallel=True, error_model="numpy")
def orbital_advection(u, dt, shear_rate, lay, sp, xc, method, limiter, cs, nchunk) -> tuple[float, int]:
    """Advect ``u`` by the background shear for ``dt`` (all columns; see :func:`remap_columns`);
    returns the largest Courant rate of the result and its first invalid cell."""
    ncol = lay.nx * lay.nz
    rates = serial_full(ncol, 0.0)
    bads = serial_full(ncol, -1)
    nchunk = min(ncol, nchunk)
    for c in prange(nchunk):
        remap_columns(u, dt, shear_rate, lay, sp, xc, method, limiter, cs, rates, bads, c * ncol // nchunk,
                      (c + 1) * ncol // nchunk)
    return combine_rates(rates, bads)
