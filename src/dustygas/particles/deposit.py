"""Deposits onto the mesh: race-free, independent of the thread count and of the block split.

Deposit (thesis eq. 4.24): a particle adds ``W_a q`` to each cell ``a`` of its stencil, ``q``
being what it carries (its mass and momentum per unit volume, or the momentum per unit
volume and time it gives the gas). The stencil weights sum to one, so the mesh receives
exactly what the particles carry (eq. 4.25) up to the round-off of the sums.

Every deposit here is a *pull*: each domain cell collects the contributions of the particles
whose stencil covers it (:func:`pull_deposit`), in a fixed order -- the source row offsets
``(dk, dj)`` in turn, then the records of the source row in canonical order (by cell, then by
particle id; :mod:`dustygas.particles.store`), the image records beyond the faces
(:func:`~dustygas.particles.boundaries.build_images`) taking their place in that order. No two
threads write the same cell, and a cell's sum is the same whatever the number of threads and
whatever the split of the box into blocks (a neighbour's particles would be image records in
the same places). Rows are handed to threads with the z index varying fastest, so the work of
a thin dust layer at the midplane is split along y.

The grid-scale filter ``F = 1 - δ⁴/16`` (:func:`filter_field`) acts on padded fields, so that
the particles gather and deposit through the kernel ``F * W``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

__all__ = ["sort_images", "image_values", "pull_deposit", "filter_field", "ROW_CHUNKS"]

#: rows are split into this many chunks for the threads (more than threads: a balanced split)
ROW_CHUNKS = 64


@njit(cache=True, error_model="numpy")
def sort_images(m_total, lay, reach, pid, img_src, img_cell, img_w, img_dvy, row_start) -> None:
    """Order the image records by padded row ``(J, K)``, then cell ``I``, then particle id, and
    fill ``row_start`` (``(ny + 2 R_y)(nz + 2 R_z) + 1`` entries) with each row's first record."""
    ry, rz = reach[1], reach[2]
    nyr = lay.ny + 2 * ry
    nrow = row_start.shape[0] - 1
    for r in range(nrow + 1):
        row_start[r] = 0
    if m_total == 0:
        return
    rows = np.empty(m_total, dtype=np.int64)
    for m in range(m_total):
        rows[m] = (img_cell[m, 2] + rz) * nyr + img_cell[m, 1] + ry
        row_start[rows[m] + 1] += 1
    for r in range(nrow):
        row_start[r + 1] += row_start[r]
    ptr = row_start[:nrow].copy()
    order = np.empty(m_total, dtype=np.int64)
    for m in range(m_total):
        order[ptr[rows[m]]] = m
        ptr[rows[m]] += 1
    for r in range(nrow):  # within a row by (I, pid): few records per row
        a, b = row_start[r], row_start[r + 1]
        for q in range(a + 1, b):
            v = order[q]
            ki, kp = img_cell[v, 0], pid[img_src[v]]
            s = q - 1
            while s >= a and (img_cell[order[s], 0] > ki or (img_cell[order[s], 0] == ki and pid[img_src[order[s]]] > kp)):
                order[s + 1] = order[s]
                s -= 1
            order[s + 1] = v
    done = True
    for m in range(m_total):
        if order[m] != m:
            done = False
            break
    if done:  # already in order (the common case: the images are written row by row)
        return
    src = img_src[:m_total].copy()
    cell = img_cell[:m_total].copy()
    w = img_w[:m_total].copy()
    dvy = img_dvy[:m_total].copy()
    for m in range(m_total):
        o = order[m]
        img_src[m] = src[o]
        img_dvy[m] = dvy[o]
        for a in range(3):
            img_cell[m, a] = cell[o, a]
        for a in range(w.shape[1]):
            for s in range(w.shape[2]):
                img_w[m, a, s] = w[o, a, s]


@njit(cache=True, error_model="numpy")
def image_values(m_total, img_src, img_dvy, values, vy_col, mass_col, out) -> None:
    """``out[m] = values[img_src[m]]``, plus ``img_dvy[m] values[., mass_col]`` in column ``vy_col``
    (the azimuthal momentum of a shear-periodic image; ``vy_col < 0``: none)."""
    nv = values.shape[1]
    for m in range(m_total):
        p = img_src[m]
        for c in range(nv):
            out[m, c] = values[p, c]
        if vy_col >= 0:
            out[m, vy_col] += img_dvy[m] * values[p, mass_col]


@njit(cache=True, error_model="numpy")
def _add_record(acc, I, wx, wyz, rx, R, nx, val, col, nv):
    for di in range(-rx, rx + 1):
        i = I + di
        if 0 <= i < nx:
            w = wyz * wx[R + di]
            if w != 0.0:
                for c in range(nv):
                    acc[i, col + c] += w * val[c]


@njit(cache=True, parallel=True, error_model="numpy")
def pull_deposit(out, g, lay, reach, R, cell_start, keys, wts, values, col, img_row_start, img_cell, img_w, img_val,
                 img_col) -> None:
    """Add to the domain cells of ``out`` ``(NZ, NY, NX, nv_out)`` (``g = (gx, gy, gz)`` ghost layers,
    which are left alone) the deposit of the sorted particles and their image records (module docstring).

    Parameters
    ----------
    reach, R
        Cells the stencil reaches per axis (0 if inactive) and the kernel's reach (the weights
        of a record are ``w[axis, R + offset]``).
    cell_start, keys, wts
        The particles' canonical order, cells and weights ``(N, 3, 2R + 1)``.
    values, col
        ``(N, nv)`` what each particle deposits, into columns ``col[p] .. col[p] + nv - 1``.
    img_row_start, img_cell, img_w, img_val, img_col
        The image records, sorted by :func:`sort_images`, with their values and columns.
    """
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    rx, ry, rz = reach[0], reach[1], reach[2]
    gx, gy, gz = g[0], g[1], g[2]
    nyr = ny + 2 * ry
    nv = values.shape[1]
    nrows = ny * nz
    nchunk = min(nrows, ROW_CHUNKS)
    for chunk in prange(nchunk):
        for r in range(chunk * nrows // nchunk, (chunk + 1) * nrows // nchunk):
            k = r % nz  # z fastest: a thread's rows span the layer, it splits along y
            j = r // nz
            acc = out[k + gz, j + gy, gx:gx + nx]
            for dk in range(-rz, rz + 1):
                K = k + dk
                sz = R - dk
                for dj in range(-ry, ry + 1):
                    J = j + dj
                    sy = R - dj
                    prow = (K + rz) * nyr + J + ry
                    m = img_row_start[prow]
                    mend = img_row_start[prow + 1]
                    while m < mend and img_cell[m, 0] < 0:  # images beyond the lower x face first
                        wyz = img_w[m, 1, sy] * img_w[m, 2, sz]
                        if wyz != 0.0:
                            _add_record(acc, img_cell[m, 0], img_w[m, 0], wyz, rx, R, nx, img_val[m], img_col[m], nv)
                        m += 1
                    if 0 <= J < ny and 0 <= K < nz:
                        c0 = (K * ny + J) * nx
                        for p in range(cell_start[c0], cell_start[c0 + nx]):
                            wyz = wts[p, 1, sy] * wts[p, 2, sz]
                            if wyz != 0.0:
                                _add_record(acc, keys[p] - c0, wts[p, 0], wyz, rx, R, nx, values[p], col[p], nv)
                    while m < mend:
                        wyz = img_w[m, 1, sy] * img_w[m, 2, sz]
                        if wyz != 0.0:
                            _add_record(acc, img_cell[m, 0], img_w[m, 0], wyz, rx, R, nx, img_val[m], img_col[m], nv)
                        m += 1


@njit(cache=True, error_model="numpy")
def _filter_line(src, dst, axis, a, b, lo, hi):
    """``dst = F src`` along ``axis`` on the line ``(a, b)`` (the other two indices) for cells ``lo .. hi-1``."""
    nv = src.shape[3]
    if axis == 0:
        s = src[a, b]
        d = dst[a, b]
        for m in range(lo, hi):
            for c in range(nv):
                d[m, c] = 0.0625 * (10.0 * s[m, c] + 4.0 * (s[m - 1, c] + s[m + 1, c]) - (s[m - 2, c] + s[m + 2, c]))
    elif axis == 1:
        s = src[a, :, b]
        d = dst[a, :, b]
        for m in range(lo, hi):
            for c in range(nv):
                d[m, c] = 0.0625 * (10.0 * s[m, c] + 4.0 * (s[m - 1, c] + s[m + 1, c]) - (s[m - 2, c] + s[m + 2, c]))
    else:
        s = src[:, a, b]
        d = dst[:, a, b]
        for m in range(lo, hi):
            for c in range(nv):
                d[m, c] = 0.0625 * (10.0 * s[m, c] + 4.0 * (s[m - 1, c] + s[m + 1, c]) - (s[m - 2, c] + s[m + 2, c]))


@njit(cache=True, error_model="numpy")
def _copy_line(src, dst, axis, a, b, lo, hi):
    if axis == 0:
        dst[a, b, lo:hi] = src[a, b, lo:hi]
    elif axis == 1:
        dst[a, lo:hi, b] = src[a, lo:hi, b]
    else:
        dst[lo:hi, a, b] = src[lo:hi, a, b]


@njit(cache=True, parallel=True, error_model="numpy")
def filter_field(f, tmp, active, k_lo, k_hi) -> None:
    """The grid-scale filter ``F = 1 - δ⁴/16`` along every active axis of the padded field ``f``
    ``(NZ, NY, NX, nv)`` in place (``tmp`` the same shape): per axis
    ``(-a_{i-2} + 4 a_{i-1} + 10 a_i + 4 a_{i+1} - a_{i+2})/16``, whose transfer function
    ``1 - sin⁴(θ/2)`` (θ = k Δx) vanishes at the Nyquist scale and is ``1 - θ⁴/16`` for
    resolved waves; it is symmetric and keeps the sum of a field over a periodic line (or one
    with mirror ghosts). Each pass needs two filled ghost layers and leaves the outermost two
    of its axis unfiltered: with ``R + 2`` ghost layers the filtered field is valid ``R``
    cells beyond the domain.

    Only the padded z rows ``k_lo .. k_hi-1`` are filtered along x and y, and along z the rows
    ``k_lo + 2 .. k_hi - 3`` (the rest of the field is not needed: a thin dust layer).
    """
    NZ, NY, NX, nv = f.shape
    for axis in range(3):
        if not active[axis]:
            continue
        if axis == 0:
            na, nb, lo, hi = k_hi - k_lo, NY, 2, NX - 2
        elif axis == 1:
            na, nb, lo, hi = k_hi - k_lo, NX, 2, NY - 2
        else:
            na, nb, lo, hi = NY, NX, max(k_lo + 2, 2), min(k_hi - 2, NZ - 2)
        nlines = na * nb
        nchunk = min(nlines, ROW_CHUNKS)
        for c in prange(nchunk):
            for line in range(c * nlines // nchunk, (c + 1) * nlines // nchunk):
                a = line // nb + (k_lo if axis < 2 else 0)
                _filter_line(f, tmp, axis, a, line % nb, lo, hi)
        for c in prange(nchunk):
            for line in range(c * nlines // nchunk, (c + 1) * nlines // nchunk):
                a = line // nb + (k_lo if axis < 2 else 0)
                _copy_line(tmp, f, axis, a, line % nb, lo, hi)
