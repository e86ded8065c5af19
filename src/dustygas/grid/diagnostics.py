"""Reductions over the domain: the Courant time step, history sums, validity checks.

Every reduction forms one partial result per row of cells along x (rows ``r = j + ny k`` in
parallel) and then combines the rows in a fixed order, so the result is the same for any
number of threads. The row functions are serial; the integrator's driver runs them inside its
own ``prange`` loops, and the ``*_total`` wrappers here do the same for calls from Python.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..arrays import serial_full

__all__ = ["cell_rate", "row_signal_rate", "combine_rates", "max_signal_rate", "row_sums", "domain_sums"]


@njit(cache=True, error_model="numpy")
def cell_rate(rho: float, mx: float, my: float, mz: float, lay, sp, cs: float) -> float:
    """``max_d (|v_d| + c_s) / Delta x_d`` over the active axes of one cell; -1 if invalid.

    The Courant-Friedrichs-Lewy condition (thesis eq. 2.12, ``Delta t <= Delta x / C`` for a
    signal speed C; eq. 2.13 with the sound speed, ``Delta t <= h / c_s``), applied to the
    fastest signal of the isothermal Euler equations along each active axis, ``|v_d| + c_s``,
    gives ``Delta t = C_cfl / rate`` with the rate maximised over cells; the per-cell maximum
    over axes is Athena's convention (Stone et al. 2008), so Courant numbers compare directly.
    A cell is invalid if its density is not positive or any variable is not finite (or so
    large that their sum overflows). Every
    rate the engine uses comes from this function, wherever it is evaluated (a separate pass,
    the last sweep of a step, the orbital-advection remap), so the time step is the same.
    """
    if not (rho > 0.0 and math.isfinite(rho + mx + my + mz)):  # a NaN or inf anywhere spoils the sum
        return -1.0
    inv = 1.0 / rho
    best = 0.0
    if lay.nx > 1:
        best = max(best, (abs(mx) * inv + cs) * (1.0 / sp.dx))
    if lay.ny > 1:
        best = max(best, (abs(my) * inv + cs) * (1.0 / sp.dy))
    if lay.nz > 1:
        best = max(best, (abs(mz) * inv + cs) * (1.0 / sp.dz))
    return best


@njit(inline="always")
def fold_rate(rate: float, index: int, best: float, bad: int) -> tuple[float, int]:
    """Fold one cell's :func:`cell_rate` into a running ``(best, bad)``: the largest valid rate
    and the first invalid cell (``bad = index`` if the rate is negative and none was seen yet;
    -1: none). Every kernel that measures a Courant rate reduces its cells with this (the time
    step of thesis eq. 2.12 is ``C_cfl / best``); inlined into their loops.
    """
    if rate < 0.0:
        if bad < 0:
            bad = index
    elif rate > best:
        best = rate
    return best, bad


@njit(cache=True, error_model="numpy")
def row_signal_rate(u, r, lay, sp, cs) -> tuple[float, int]:
    """Largest :func:`cell_rate` in row ``r`` of domain cells, and its first invalid cell.

    The invalid cell is given as the flat domain index ``(k ny + j) nx + i`` (-1 if none).
    """
    nx, ny, nz, gx, gy, gz = lay
    j = r % ny
    k = r // ny
    best = 0.0
    bad = -1
    d_row = u[0, gz + k, gy + j, gx:gx + nx]  # views: loop indices from 0
    x_row = u[1, gz + k, gy + j, gx:gx + nx]
    y_row = u[2, gz + k, gy + j, gx:gx + nx]
    z_row = u[3, gz + k, gy + j, gx:gx + nx]
    for i in range(nx):
        rho = d_row[i]
        mx = x_row[i]
        my = y_row[i]
        mz = z_row[i]
        best, bad = fold_rate(cell_rate(rho, mx, my, mz, lay, sp, cs), (k * ny + j) * nx + i, best, bad)
    return best, bad


@njit(cache=True, error_model="numpy")
def combine_rates(rates, bads) -> tuple[float, int]:
    """Maximum rate and first invalid cell over rows, in row order."""
    rate = 0.0
    bad = -1
    for r in range(rates.shape[0]):
        rate = max(rate, rates[r])
        if bad < 0 and bads[r] >= 0:
            bad = bads[r]
    return rate, bad


@njit(cache=True, parallel=True, error_model="numpy")
def max_signal_rate(u, lay, sp, cs) -> tuple[float, int]:
    """:func:`row_signal_rate` over the whole domain (see there)."""
    rows = lay.ny * lay.nz
    rates = serial_full(rows, 0.0)
    bads = serial_full(rows, -1)
    for r in prange(rows):
        rates[r], bads[r] = row_signal_rate(u, r, lay, sp, cs)
    return combine_rates(rates, bads)


@njit(cache=True, error_model="numpy")
def row_sums(u, r, lay, xc, to_full, to_relative, out) -> None:
    """``out[:] = [mass, p_x, p_y, p_z, kinetic energy, rho_max, rho_min]`` of row ``r``.

    Per unit cell volume. ``p_y`` is the momentum of the full velocity
    ``v_y = v_y,stored - to_full * x`` (``to_full = q Omega`` under orbital advection, else 0);
    the kinetic energy is that of the velocity relative to the background shear,
    ``v_y,stored + to_relative * x`` (``to_relative = q Omega`` in a shearing box without
    orbital advection, else 0).
    """
    nx, ny, nz, gx, gy, gz = lay
    j = r % ny
    k = r // ny
    m = px = py = pz = ke = 0.0
    hi = -np.inf
    lo = np.inf
    for i in range(nx):
        rho = u[0, gz + k, gy + j, gx + i]
        mx = u[1, gz + k, gy + j, gx + i]
        my = u[2, gz + k, gy + j, gx + i]
        mz = u[3, gz + k, gy + j, gx + i]
        x = xc[gx + i]
        myr = my + to_relative * x * rho
        m += rho
        px += mx
        py += my - to_full * x * rho
        pz += mz
        ke += 0.5 * (mx * mx + myr * myr + mz * mz) / rho
        hi = max(hi, rho)
        lo = min(lo, rho)
    out[0] = m
    out[1] = px
    out[2] = py
    out[3] = pz
    out[4] = ke
    out[5] = hi
    out[6] = lo


@njit(cache=True, parallel=True, error_model="numpy")
def _row_sums_parallel(u, lay, xc, to_full, to_relative, part) -> None:
    for r in prange(part.shape[0]):
        row_sums(u, r, lay, xc, to_full, to_relative, part[r])


@njit(cache=True, error_model="numpy")
def _row_sums_serial(u, lay, xc, to_full, to_relative, part) -> None:
    for r in range(part.shape[0]):
        row_sums(u, r, lay, xc, to_full, to_relative, part[r])


@njit(cache=True, error_model="numpy")
def _combine_sums(part) -> np.ndarray:
    out = np.zeros(7)
    out[5] = -np.inf
    out[6] = np.inf
    for r in range(part.shape[0]):
        for c in range(5):
            out[c] += part[r, c]
        out[5] = max(out[5], part[r, 5])
        out[6] = min(out[6], part[r, 6])
    return out


#: below this many cells the sums run on one thread (a parallel region costs more)
PARALLEL_SUMS_CELLS = 1 << 17


def domain_sums(u, lay, xc, to_full, to_relative) -> np.ndarray:
    """:func:`row_sums` combined over rows in a fixed order (sums, maximum, minimum)."""
    part = np.empty((lay.ny * lay.nz, 7))
    rows = _row_sums_parallel if lay.nx * lay.ny * lay.nz >= PARALLEL_SUMS_CELLS else _row_sums_serial
    rows(u, lay, xc, to_full, to_relative, part)
    return _combine_sums(part)
