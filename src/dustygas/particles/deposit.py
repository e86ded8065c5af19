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


__all__ = ["chunk_bounds", "gas_fields"]

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
