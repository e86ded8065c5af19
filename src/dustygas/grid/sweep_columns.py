"""The y and z sweeps on blocks of neighbouring columns: the pencil kernel, vectorised across x.

The state is stored x fastest, so the cells of a y or z pencil lie a stride apart in memory,
and the x neighbours of a pencil are the next pencils. :func:`sweep_columns` takes up to
:data:`BLOCK` neighbouring pencils (consecutive x indices) together: it gathers their
primitive variables one row of the block at a time (contiguous loads), then reconstructs,
solves the Riemann problems and updates with the column index innermost, so that every loop
runs over contiguous memory and the compiler vectorises it across the columns -- the loop order
of Athena++'s x2 and x3 sweeps. A strided pencil-at-a-time z sweep gained only 1.20-1.50x
on two threads of a two-vCPU machine, where the x sweep gained 1.71-1.80x (2026-12-05).

The block is stored cell-major (cell ``s`` of column ``c`` at ``s BLOCK + c``), so that the
reconstruction and the Riemann solver of a pencil serve a block unchanged, with neighbouring
cells ``BLOCK`` entries apart (their argument ``k``): every cell gets the operations of
:func:`~dustygas.grid.sweep.sweep_pencils` in the same order, and the two kernels agree bit for bit, which
``tests/grid/test_sweep_columns.py`` checks for every reconstruction and solver. The block
kernel does the later sweeps of a stage (the first one also writes the sources and is an x
sweep unless the box is one-dimensional).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .reconstruct import reconstruct_faces
from .riemann import riemann_fluxes
from .sweep import gather_primitives, pencil_frame, pencil_order, pencil_rate

__all__ = ["BLOCK", "sweep_columns"]

#: columns per block (16 float64: two AVX-512 registers). In the z sweep of a 64^2 box, 8, 16 and 32
#: columns took 98, 97 and 90 µs on one thread (2026-12-05): wider blocks vectorise longer loops but
#: need buffers of 4 (n + 6) BLOCK values, which leave the L1 and then the L2 cache in tall boxes
BLOCK = 16


@njit(cache=True, error_model="numpy")
def _gather_rows(S, off, stride, bw, c1, c2, c3, w) -> None:
    """``w[:, s BLOCK + c]``: the primitive variables of cell ``s`` of column ``c``, one row of
    ``bw`` contiguous cells at a time (:func:`~dustygas.grid.sweep.gather_primitives` along x)."""
    for s in range(w.shape[1] // BLOCK):
        at = s * BLOCK
        gather_primitives(S, off + s * stride, 1, c1, c2, c3, w[0, at:at + bw], w[1, at:at + bw], w[2, at:at + bw],
                          w[3, at:at + bw])


@njit(cache=True, error_model="numpy")
def sweep_columns(src, dst, axis, dt, lay, sp, scheme, bflux, store_bflux, rates, bads, want_rate,
                  skip_radial_edges, p0, p1, c0, c1, seg, nseg) -> None:
    """Add the flux differences along ``axis`` (1 or 2) of ``src`` to ``dst`` for pencils
    ``p0 .. p1-1``, in their domain cells ``c0 .. c1-1`` along ``axis``, in blocks of up to
    :data:`BLOCK` neighbouring pencils.

    The parameters are those of :func:`~dustygas.grid.sweep.sweep_pencils` for a sweep that is
    not the first of its stage (``first=False``: no base, sources or external term); pencil
    ``p`` has x index ``p % nx``, so consecutive pencils of one row are neighbouring columns.
    """
    method, limiter, solver, cs = scheme
    ntot = src.shape[1] * src.shape[2] * src.shape[3]
    n_axis, g, stride, d, na, ga, sa, _, _, gb, sb, _ = pencil_frame(axis, lay, sp, 0, 0)
    dtdx = dt / d
    v1, v2, v3, row_x, row_y, row_z = pencil_order(axis)
    S = src.reshape(4, ntot)
    D = dst.reshape(4, ntot)
    n = c1 - c0
    N = n + 2 * g
    lo, hi = g, g + n
    # cell s of column c at s BLOCK + c, face f at f BLOCK + c; the face loops run over whole
    # blocks: the columns of a narrower last block past its width hold valid states of an earlier
    # block (or ones), and nothing is written from them
    w = np.ones((4, N * BLOCK))
    wl = np.ones((4, (N + 1) * BLOCK))
    wr = np.ones((4, (N + 1) * BLOCK))
    flux = np.empty((4, (N + 1) * BLOCK))
    scratch = np.empty((2, (N + 1) * BLOCK))
    f_rho = flux[0, lo * BLOCK:]
    f_x = flux[row_x, lo * BLOCK:]
    f_y = flux[row_y, lo * BLOCK:]
    f_z = flux[row_z, lo * BLOCK:]
    p = p0
    while p < p1:
        ia = p % na
        ib = p // na
        bw = min(BLOCK, p1 - p, na - ia)  # the block ends with the row of pencils
        off = (ia + ga) * sa + (ib + gb) * sb + c0 * stride  # the block's first ghost row
        _gather_rows(S, off, stride, bw, v1, v2, v3, w)
        reconstruct_faces(w, lo, hi, method, limiter, wl, wr, scratch, BLOCK)
        riemann_fluxes(wl, wr, lo, hi, cs, solver, flux, BLOCK)
        if store_bflux:
            for v in range(4):
                for c in range(bw):
                    if c0 == 0:
                        bflux[0, v, ib, ia + c] = flux[v, lo * BLOCK + c]
                    if c1 == n_axis:
                        bflux[1, v, ib, ia + c] = flux[v, hi * BLOCK + c]
        for i in range(n):  # domain cells: flux differences of faces i and i + 1
            row = off + (lo + i) * stride
            d_rho = D[0, row:row + bw]
            d_x = D[1, row:row + bw]
            d_y = D[2, row:row + bw]
            d_z = D[3, row:row + bw]
            at = i * BLOCK  # face i of the block (from lo) and face i + 1
            nxt = at + BLOCK
            lr, lx, ly, lz = f_rho[at:], f_x[at:], f_y[at:], f_z[at:]
            ur, ux, uy, uz = f_rho[nxt:], f_x[nxt:], f_y[nxt:], f_z[nxt:]
            for c in range(bw):
                d_rho[c] -= dtdx * (ur[c] - lr[c])
                d_x[c] -= dtdx * (ux[c] - lx[c])
                d_y[c] -= dtdx * (uy[c] - ly[c])
                d_z[c] -= dtdx * (uz[c] - lz[c])
        if want_rate:
            for c in range(bw):
                first_cell = off + lo * stride + c
                last = first_cell + n * stride
                pencil_rate(D[0, first_cell:last:stride], D[1, first_cell:last:stride], D[2, first_cell:last:stride],
                            D[3, first_cell:last:stride], axis, ia + c, ib, c0, lay, sp, cs, skip_radial_edges, rates,
                            bads, (p + c) * nseg + seg)
        p += bw
