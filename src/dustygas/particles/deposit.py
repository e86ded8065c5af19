"""Gather from the gas and deposit onto it, race-free and deterministic on several threads.

Gather (thesis eq. 4.22): each stage first turns the conserved gas state into the fields
``(rho, u_x, u_y, u_z)`` of the domain cells (:func:`gas_fields`, one pass over the mesh);
a particle then interpolates them with its stencil (the particle loop of
:mod:`dustygas.particles.push`).

Deposit (thesis eq. 4.24): a particle adds ``W_a f / V_cell`` to the momentum source of each
cell ``a`` of its stencil, ``f`` being the momentum per unit time it gives
the gas. The stencil weights sum to one, so the gas receives exactly what the particles lose
(eq. 4.25) up to the round-off of the sums.

Threads without races, results without dependence on the thread count
-----------------------------------------------------------------------
The particles are sorted by slab (:mod:`dustygas.particles.store`); the slabs are grouped into
an even number of *chunks* of at least four slabs (six for the five-cell compensated TSC;
:func:`chunk_bounds`). During a stage a particle moves by less than one cell along the slab
axis, and its stencil reaches one (two) cells further, so a chunk deposits only into its own
slabs and two (three) slabs on either side. Chunks
0, 2, 4, ... therefore write disjoint cells and run in parallel; then chunks 1, 3, 5, ...
Within a chunk the particles are processed in their (sorted) order, and every cell receives
its contributions chunk by chunk in a fixed order, so the deposited field is the same for any
number of threads -- bit for bit.
"""

from __future__ import annotations

import numpy as np
from numba import njit


__all__ = ["chunk_bounds", "gas_fields", "filter_lines"]

def chunk_bounds(nslab: int, reach: int = 1) -> np.ndarray:
    """Slab boundaries ``b[0] = 0 < b[1] < ... < b[m] = nslab`` of ``m`` chunks.

    A particle moves by less than one cell per stage and its stencil reaches ``reach`` cells
    on either side of its own, so a chunk writes into its own slabs and ``1 + reach`` more on
    each side: chunks of at least ``2 (1 + reach)`` slabs make chunks two apart disjoint. ``m``
    is even, or 1 if there are too few slabs for two chunks (the deposit then runs on one
    thread).

    >>> chunk_bounds(64)[:4], len(chunk_bounds(64)) - 1
    (array([ 0,  4,  8, 12]), 16)
    >>> chunk_bounds(10), chunk_bounds(7), len(chunk_bounds(64, reach=2)) - 1
    (array([ 0,  5, 10]), array([0, 7]), 10)
    """
    m = nslab // (2 * (1 + reach))
    m -= m % 2
    if m < 2:
        return np.array([0, nslab], dtype=np.int64)
    return np.array([c * nslab // m for c in range(m + 1)], dtype=np.int64)


@njit(cache=True, error_model="numpy")
def gas_fields(u, cells, gas_az, fields, ext, init_ext, r0, r1) -> None:
    """Rows ``r0 .. r1-1`` (row ``r = k ny + j``) of the gas fields and of the source.

    ``u`` is the conserved state ``(4, NZ, NY, NX)`` with ghost zones; ``fields`` ``(4, ncell)``
    receives ``rho, u_x, u_y, u_z`` of the domain cells (flat index ``(k ny + j) nx + i``). If
    ``init_ext``, ``ext`` ``(3, ncell)`` is set to ``(0, 0, rho gas_az)``: the constant vertical
    acceleration of the gas (zero unless a problem balances a settling drift with it).
    """
    nx, ny = cells.nx, cells.ny
    for r in range(r0, r1):
        j = r % ny
        k = r // ny
        d = u[0, k + cells.gz, j + cells.gy, cells.gx:cells.gx + nx]
        mx = u[1, k + cells.gz, j + cells.gy, cells.gx:cells.gx + nx]
        my = u[2, k + cells.gz, j + cells.gy, cells.gx:cells.gx + nx]
        mz = u[3, k + cells.gz, j + cells.gy, cells.gx:cells.gx + nx]
        base = r * nx
        f0 = fields[0, base:base + nx]
        f1 = fields[1, base:base + nx]
        f2 = fields[2, base:base + nx]
        f3 = fields[3, base:base + nx]
        for i in range(nx):
            rho = d[i]
            inv = 1.0 / rho
            f0[i] = rho
            f1[i] = mx[i] * inv
            f2[i] = my[i] * inv
            f3[i] = mz[i] * inv
        if init_ext:
            e0 = ext[0, base:base + nx]
            e1 = ext[1, base:base + nx]
            e2 = ext[2, base:base + nx]
            for i in range(nx):
                e0[i] = 0.0
                e1[i] = 0.0
                e2[i] = gas_az * d[i]


@njit(cache=True, error_model="numpy")
def filter_lines(src, dst, nvar, axis, cells, y_cells, l0, l1) -> None:
    """The grid-scale filter ``F = 1 - δ⁴/16`` along ``axis`` for lines ``l0 .. l1-1``.

    ``src``, ``dst`` are ``(nvar, ncell)`` domain fields (flat index ``(k ny + j) nx + i``);
    a line is every cell with the same two other indices. ``F`` is
    ``(-a_{i-2} + 4 a_{i-1} + 10 a_i + 4 a_{i+1} - a_{i+2})/16``: its transfer function is
    ``1 - sin⁴(θ/2)`` (θ = k Δx), zero at the grid's Nyquist wavenumber and ``1 - θ⁴/16`` for
    resolved waves; it is symmetric and keeps the sum of a field. Lines wrap periodically; in
    a shear-periodic box with an active y axis the x-lines continue across the radial
    boundary ``y_cells`` (the shear offset rounded to whole cells) further along y.
    """
    nx, ny, nz = cells.nx, cells.ny, cells.nz
    n = nx if axis == 0 else (ny if axis == 1 else nz)
    stride = 1 if axis == 0 else (nx if axis == 1 else nx * ny)
    shear = axis == 0 and cells.shear and ny > 1
    for line in range(l0, l1):
        if axis == 0:
            j, k = line % ny, line // ny
            base = (k * ny + j) * nx
        elif axis == 1:
            i, k = line % nx, line // nx
            base = k * ny * nx + i
        else:
            base = line
        for v in range(nvar):
            s = src[v]
            d = dst[v]
            for m in range(n):
                acc = 10.0 * s[base + m * stride]
                for off in (-2, -1, 1, 2):
                    q = m + off
                    c = 4.0 if off == -1 or off == 1 else -1.0
                    if 0 <= q < n:
                        acc += c * s[base + q * stride]
                    elif not shear:
                        acc += c * s[base + (q % n) * stride]
                    else:  # x-line of a shearing box: the image column, y shifted by whole cells
                        jj = (j - y_cells) % ny if q < 0 else (j + y_cells) % ny
                        acc += c * s[(k * ny + jj) * nx + q % n]
                d[base + m * stride] = acc * 0.0625
