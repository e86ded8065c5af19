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
the same places). Where every image is a periodic copy with its source's weights (a periodic
box, or a shear-periodic x-z box: :func:`~dustygas.particles.boundaries.images_wrap`) no records
are built: the walk reads the source rows and cells one box length away in their place, in the
same order. Rows are handed to threads in chunks with the z index varying fastest, so the
work of a thin dust layer at the midplane is split along y; a chunk walks the source rows that
reach its rows once, each record adding to all of them (:func:`pull_deposit`).

The grid-scale filter ``F = 1 - δ⁴/16`` (:func:`filter_field`) acts on padded fields, so that
the particles gather and deposit through the kernel ``F * W``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..grid.field_ghosts import row_x_ghosts, z_source_row
from ..grid.mesh import Layout

__all__ = ["sort_images", "pull_deposit", "filter_field", "filter_field_xz", "filter_pieces", "ROW_CHUNKS"]

#: the filter's planes are split into this many chunks for the threads (more than threads: a balanced split)
ROW_CHUNKS = 64
#: the length of the pieces of a row (elements) that the z pass of :func:`filter_field` hands to threads
FILTER_PIECE = 64


@njit(cache=True, error_model="numpy")
def sort_images(m_total, layout, reach, pid, img_src, img_cell, img_w, img_dvy, row_start) -> None:
    """Order the image records by padded row ``(J, K)``, then cell ``I``, then particle id, and
    fill ``row_start`` (``(ny + 2 R_y)(nz + 2 R_z) + 1`` entries) with each row's first record."""
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
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


@njit(cache=True, error_model="numpy", inline="always")
def _add_record(flat, start, I, w_r, wyz, rx, R, nx, vals_r, nv, nvo):
    """A record (weights ``w_r`` (3, W), values ``vals_r`` (nv,)) from cell ``I`` into the
    flattened target ``flat``, at element ``start + i nvo`` for cell ``i`` (``start``: the
    target row, the x ghosts and the record's first column).

    The element index is unsigned: numba then leaves out its negative-index wrap-around, and
    the compiler keeps the adds of the ``nv`` values together (linA: -15 to -21 % of a deposit)."""
    for di in range(-rx, rx + 1):
        i = I + di
        if 0 <= i < nx:
            w = wyz * w_r[0, R + di]
            if w != 0.0:
                o = np.uint64(start + i * nvo)
                if nv == 4:  # the deposits of the drag problem (4) and of the back-reaction (3), unrolled
                    flat[o] += w * vals_r[0]
                    flat[o + np.uint64(1)] += w * vals_r[1]
                    flat[o + np.uint64(2)] += w * vals_r[2]
                    flat[o + np.uint64(3)] += w * vals_r[3]
                elif nv == 3:
                    flat[o] += w * vals_r[0]
                    flat[o + np.uint64(1)] += w * vals_r[1]
                    flat[o + np.uint64(2)] += w * vals_r[2]
                else:
                    for c in range(nv):
                        flat[o + np.uint64(c)] += w * vals_r[c]


@njit(cache=True, error_model="numpy", inline="always")
def _add_particles(flat, p0, p1, c0, nt, t_row, t_sy, t_sz, rowlen, base, col, keys, wts, values, rx, R, nx, nv, nvo):
    """The sorted particles ``p0 .. p1-1`` of one source row into the ``nt`` target rows
    ``t_row`` (their y and z weight slots ``t_sy``, ``t_sz``), each from cell ``keys[p] - c0``."""
    for p in range(p0, p1):
        for t in range(nt):
            wyz = wts[p, 1, t_sy[t]] * wts[p, 2, t_sz[t]]
            if wyz != 0.0:
                _add_record(flat, t_row[t] * rowlen + base + col[p], keys[p] - c0, wts[p], wyz, rx, R, nx, values[p],
                            nv, nvo)


@njit(cache=True, error_model="numpy", inline="always")
def wrapped_index(c, n):
    """The domain index ``0 .. n-1`` of the cell (or row) ``c``, within one box length ``n`` of the domain."""
    return c + n if c < 0 else (c - n if c >= n else c)


@njit(cache=True, parallel=True, error_model="numpy")
def pull_deposit(out, g, layout, reach, R, cell_start, keys, wts, values, col, img_row_start, img_cell, img_w, img_src,
                 nchunk, clear=False, wrap=False) -> None:
    """Add to the domain cells of ``out`` ``(NZ, NY, NX, nv_out)`` (``g = (gx, gy, gz)`` ghost layers,
    which are left alone) the deposit of the sorted particles and their image records (module
    docstring); with ``clear``, set them to the deposit (zeroed first).

    Parameters
    ----------
    reach, R
        Cells the stencil reaches per axis (0 if inactive) and the kernel's reach (the weights
        of a record are ``w[axis, R + offset]``).
    cell_start, keys, wts
        The particles' canonical order, cells and weights ``(N, 3, 2R + 1)``.
    values, col
        ``(N, nv)`` what each particle deposits, into columns ``col[p] .. col[p] + nv - 1``.
    img_row_start, img_cell, img_w, img_src
        The image records, sorted by :func:`sort_images`; a record deposits the values of its
        source particle ``img_src[m]`` into that particle's columns.
    nchunk
        Chunks of the domain rows ``(k, j)`` (``r = j nz + k``: z fastest, so that the chunks of a thin
        dust layer split it along y) handed to the threads; any number gives the same sums.
    wrap
        Every active axis is periodic without a slide of the images (a shear-periodic x only
        with ``ny = 1``) and at least ``R`` cells long: the image records are not built (the
        image arguments are not read); a source row or cell beyond a face is read as the domain
        row or cell one box length away (:func:`wrapped_index`). An image record of that box
        has its source's weights and sits, once sorted, where this walk finds the source: the
        same records in the same order, the same sums to the last bit.

    A chunk owns its rows and walks the source rows ``(K, J)`` that reach them in ascending
    order, each record adding to every row of the chunk within its reach: a row receives its
    source rows in the order of the offsets ``(dk, dj)``, and the records of one source row in
    canonical order, whatever the chunks (the weights and values of a record are read once for
    the up to ``(2R_z + 1)(2R_y + 1)`` rows it reaches, not once per row).
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    rx, ry, rz = reach[0], reach[1], reach[2]
    gx, gy, gz = g[0], g[1], g[2]
    NZ, NY, NX, nvo = out.shape
    out2 = out.reshape((NZ * NY, NX * nvo))
    flat = out.reshape(out.size)
    rowlen = NX * nvo
    nyr = ny + 2 * ry
    nv = values.shape[1]
    nrows = ny * nz
    ntmax = (2 * rz + 1) * (2 * ry + 1)
    base = gx * nvo
    for chunk in prange(nchunk):
        r0 = chunk * nrows // nchunk
        r1 = (chunk + 1) * nrows // nchunk
        if r1 <= r0:
            continue
        j0, j1 = r0 // nz, (r1 - 1) // nz
        k0, k1 = (r0 % nz, (r1 - 1) % nz) if j0 == j1 else (0, nz - 1)
        if clear:
            for r in range(r0, r1):
                row = out2[(r % nz + gz) * NY + r // nz + gy]
                for q in range(nx * nvo):
                    row[base + q] = 0.0
        t_row = np.empty(ntmax, dtype=np.int64)  # the chunk's rows a source row reaches
        t_sy = np.empty(ntmax, dtype=np.int64)  # and the weight slots there
        t_sz = np.empty(ntmax, dtype=np.int64)
        for K in range(k0 - rz, k1 + rz + 1):
            for J in range(j0 - ry, j1 + ry + 1):
                nt = 0
                for dk in range(-rz, rz + 1):
                    k = K - dk
                    for dj in range(-ry, ry + 1):
                        j = J - dj
                        r = j * nz + k
                        if 0 <= k < nz and 0 <= j < ny and r0 <= r < r1:
                            t_row[nt] = (k + gz) * NY + j + gy
                            t_sy[nt] = R - dj
                            t_sz[nt] = R - dk
                            nt += 1
                if nt == 0:
                    continue
                if wrap:  # the source row one box length away; the cells beyond the x faces likewise
                    c0 = (wrapped_index(K, nz) * ny + wrapped_index(J, ny)) * nx
                    if rx > 0:  # the cells nx - rx .. nx - 1, as cells -rx .. -1
                        _add_particles(flat, cell_start[c0 + nx - rx], cell_start[c0 + nx], c0 + nx, nt, t_row, t_sy,
                                       t_sz, rowlen, base, col, keys, wts, values, rx, R, nx, nv, nvo)
                    _add_particles(flat, cell_start[c0], cell_start[c0 + nx], c0, nt, t_row, t_sy, t_sz, rowlen, base,
                                   col, keys, wts, values, rx, R, nx, nv, nvo)
                    if rx > 0:  # the cells 0 .. rx - 1, as cells nx .. nx + rx - 1
                        _add_particles(flat, cell_start[c0], cell_start[c0 + rx], c0 - nx, nt, t_row, t_sy, t_sz,
                                       rowlen, base, col, keys, wts, values, rx, R, nx, nv, nvo)
                    continue
                prow = (K + rz) * nyr + J + ry
                m = img_row_start[prow]
                mend = img_row_start[prow + 1]
                while m < mend and img_cell[m, 0] < 0:  # images beyond the lower x face first
                    src = img_src[m]
                    for t in range(nt):
                        wyz = img_w[m, 1, t_sy[t]] * img_w[m, 2, t_sz[t]]
                        if wyz != 0.0:
                            _add_record(flat, t_row[t] * rowlen + base + col[src], img_cell[m, 0], img_w[m], wyz,
                                        rx, R, nx, values[src], nv, nvo)
                    m += 1
                if 0 <= J < ny and 0 <= K < nz:
                    c0 = (K * ny + J) * nx
                    _add_particles(flat, cell_start[c0], cell_start[c0 + nx], c0, nt, t_row, t_sy, t_sz, rowlen, base,
                                   col, keys, wts, values, rx, R, nx, nv, nvo)
                while m < mend:
                    src = img_src[m]
                    for t in range(nt):
                        wyz = img_w[m, 1, t_sy[t]] * img_w[m, 2, t_sz[t]]
                        if wyz != 0.0:
                            _add_record(flat, t_row[t] * rowlen + base + col[src], img_cell[m, 0], img_w[m], wyz,
                                        rx, R, nx, values[src], nv, nvo)
                    m += 1


@njit(cache=True, error_model="numpy")
def _filter_into(row, m2, m1, c0, p1, p2, lo, hi):
    """``row[q] = F`` of the five rows ``m2, m1, c0, p1, p2`` (offsets -2 .. 2 along the axis) for
    ``q = lo .. hi-1``: ``(10 c0 + 4 (m1 + p1) - (m2 + p2))/16``."""
    for q in range(lo, hi):
        row[q] = 0.0625 * (10.0 * c0[q] + 4.0 * (m1[q] + p1[q]) - (m2[q] + p2[q]))


@njit(cache=True, error_model="numpy")
def _filter_x(row, buf, nv):
    """:func:`filter_field` along x of one flattened row ``(NX nv)`` in place (``buf`` its length)."""
    buf[:] = row
    _filter_x_into(buf, row, nv)


@njit(cache=True, error_model="numpy")
def _filter_x_into(a, x, nv):
    """:func:`filter_field` along x of the flattened row ``a`` ``(NX nv)`` into ``x`` (its length;
    the two outermost cells of either end copied)."""
    n = a.shape[0]
    e = 2 * nv
    _copy_into(a, x, e)
    _copy_into(a[n - e:], x[n - e:], e)
    # views at the five offsets, indexed from 0: an index `q - nv` would cost a negative-index
    # check per load and keep the loop from being vectorised (several times slower)
    _filter_into(x[e:], a, a[nv:], a[e:], a[e + nv:], a[2 * e:], 0, n - 2 * e)


@njit(cache=True, error_model="numpy")
def _filter_across(f3, axis, fixed, lo, hi, q0, q1, ring):
    """:func:`filter_field` in place across the rows of the flattened field ``f3`` ``(NZ, NY, NX nv)``:
    along y (``axis`` 1) the rows ``j = lo .. hi-1`` of plane ``k = fixed``, along z (``axis`` 2)
    the planes ``k = lo .. hi-1`` of row ``j = fixed``; elements ``q0 .. q1-1`` of each row.
    ``ring`` ``(3, >= q1 - q0)`` keeps the unfiltered rows ``m - 2, m - 1, m`` of row ``m``."""
    n = q1 - q0
    for m in range(lo - 2, hi):
        src = f3[fixed, m, q0:q1] if axis == 1 else f3[m, fixed, q0:q1]
        cur = ring[m % 3, :n]
        cur[:] = src
        if m >= lo:
            p1 = f3[fixed, m + 1, q0:q1] if axis == 1 else f3[m + 1, fixed, q0:q1]
            p2 = f3[fixed, m + 2, q0:q1] if axis == 1 else f3[m + 2, fixed, q0:q1]
            _filter_into(src, ring[(m - 2) % 3, :n], ring[(m - 1) % 3, :n], cur, p1, p2, 0, n)


@njit(cache=True, parallel=True, error_model="numpy")
def filter_field(f, active, k_lo, k_hi) -> None:
    """The grid-scale filter ``F = 1 - δ⁴/16`` along every active axis of the padded field ``f``
    ``(NZ, NY, NX, nv)`` (C-contiguous) in place: per axis
    ``(-a_{i-2} + 4 a_{i-1} + 10 a_i + 4 a_{i+1} - a_{i+2})/16``, whose transfer function
    ``1 - sin⁴(θ/2)`` (θ = k Δx) vanishes at the Nyquist scale and is ``1 - θ⁴/16`` for
    resolved waves; it is symmetric and keeps the sum of a field over a periodic line (or one
    with mirror ghosts). Each pass needs two filled ghost layers and leaves the outermost two
    of its axis unfiltered: with ``R + 2`` ghost layers the filtered field is valid ``R``
    cells beyond the domain.

    Only the padded z rows ``k_lo .. k_hi-1`` are filtered along x and y, and along z the rows
    ``k_lo + 2 .. k_hi - 3`` (the rest of the field is not needed: a thin dust layer).

    The passes x, y, z follow one another (each filters the output of the one before); x and y
    run over chunks of planes in one parallel region, z over pieces of the (y, x) rows in a second.
    Every element is the same expression of the same inputs whatever the split.
    """
    NZ, NY, NX, nv = f.shape
    L = NX * nv
    f3 = f.reshape((NZ, NY, L))
    if (active[0] or active[1]) and k_hi > k_lo:
        nk = k_hi - k_lo
        nchunk = min(nk, ROW_CHUNKS)
        for c in prange(nchunk):
            ring = np.empty((3, L))  # one scratch per chunk of planes
            for k in range(k_lo + c * nk // nchunk, k_lo + (c + 1) * nk // nchunk):
                if active[0]:
                    for j in range(NY):
                        _filter_x(f3[k, j], ring[0], nv)
                if active[1]:
                    _filter_across(f3, 1, k, 2, NY - 2, 0, L, ring)
    if active[2]:
        lo, hi = max(k_lo + 2, 2), min(k_hi - 2, NZ - 2)
        if hi > lo:
            # pieces of a row, of about FILTER_PIECE elements or more (shorter ones cost more in slicing
            # than they filter); in 2D (NY = 1) a multiple of 4 of them, for an even split over 2 or 4 threads
            nq = max(1, min(ROW_CHUNKS // NY, L // FILTER_PIECE))
            if NY == 1:
                nq = 4 * ((nq + 3) // 4)
            nchunk = NY * nq
            for c in prange(nchunk):
                j = c // nq
                q0 = (c % nq) * L // nq
                q1 = (c % nq + 1) * L // nq
                ring = np.empty((3, q1 - q0))
                _filter_across(f3, 2, j, lo, hi, q0, q1, ring)


@njit(cache=True, error_model="numpy")
def _copy_into(src, dst, n):
    """``dst[0 .. n-1] = src[0 .. n-1]``."""
    for q in range(n):
        dst[q] = src[q]


@njit(cache=True, error_model="numpy")
def filter_pieces(nthreads: int) -> int:
    """The pieces of rows :func:`filter_field_xz` splits a field into on ``nthreads`` threads (at
    most 8: each piece copies its neighbours' boundary rows)."""
    return max(1, min(nthreads, 8))


@njit(cache=True, parallel=True, error_model="numpy")
def filter_field_xz(f, out, k_lo, k_hi, npiece, gx, gz, kinds) -> None:
    """Ghosts and :func:`filter_field` of a 2D x-z field ``f`` ``(NZ, 1, NX, nv)`` (x and z active),
    out of place: ``out`` (the same shape) receives exactly what
    :func:`~dustygas.grid.field_ghosts.fill_field_ghosts` (``gx``, ``gz`` layers, rules ``kinds``,
    x ghosts in the padded rows ``k_lo .. k_hi-1``) followed by :func:`filter_field` would leave in
    ``f``. One parallel region over ``npiece`` pieces of the padded z rows (any number: every
    element is the same expression of the same inputs). A piece first fills the ghosts of the
    rows it owns in ``f`` (a z ghost row takes the domain cells of the row it copies, then a row
    its x ghosts from its own domain cells: only domain cells of other rows are read, which no
    piece writes); it filters along x the rows it writes and the two beyond either end into a
    scratch (a neighbour's row from a private copy with its ghosts, as the neighbour may be
    filling them), then along z into ``out``; rows outside ``k_lo .. k_hi-1`` are copied. Rows,
    not columns, are split, as the kernels that write and read the field split them: with pieces
    of columns every thread read the rows the other had just written, and two threads took
    longer than one (64² cells, 2026-12-03); with the ghosts filled serially before the region the
    two linA fields took 41 µs on two threads, with them inside 33 µs (2026-12-05).
    """
    NZ, NY, NX, nv = f.shape
    L = NX * nv
    nx, nz = NX - 2 * gx, NZ - 2 * gz
    a2 = f.reshape((NZ, L))
    b2 = out.reshape((NZ, L))
    lo, hi = max(k_lo + 2, 2), min(k_hi - 2, NZ - 2)
    for c in prange(npiece):
        r0 = c * NZ // npiece
        r1 = (c + 1) * NZ // npiece
        for k in range(r0, r1):  # the ghosts of the piece's own rows
            src = z_source_row(k, nz, gz, kinds)
            if src != k:
                _copy_into(a2[src, gx * nv:], a2[k, gx * nv:], nx * nv)
            if k_lo <= k < k_hi:
                row_x_ghosts(a2[k], nv, nx, gx, kinds[0])
        x0 = max(max(r0, k_lo) - 2, k_lo)  # the rows filtered along x: x0 .. x1-1
        x1 = min(min(r1, k_hi) + 2, k_hi)
        xf = np.empty((max(x1 - x0, 0), L))
        mine = np.empty(L)
        for k in range(x0, x1):
            if r0 <= k < r1:
                _filter_x_into(a2[k], xf[k - x0], nv)
            else:  # a neighbour's row: its domain cells (or those its ghost rule copies), ghosts here
                _copy_into(a2[z_source_row(k, nz, gz, kinds), gx * nv:], mine[gx * nv:], nx * nv)
                row_x_ghosts(mine, nv, nx, gx, kinds[0])
                _filter_x_into(mine, xf[k - x0], nv)
        for k in range(r0, r1):
            b = b2[k]
            if k < k_lo or k >= k_hi:
                _copy_into(a2[k], b, L)
            elif k < lo or k >= hi:
                _copy_into(xf[k - x0], b, L)
            else:
                r = k - x0
                _filter_into(b, xf[r - 2], xf[r - 1], xf[r], xf[r + 1], xf[r + 2], 0, L)
