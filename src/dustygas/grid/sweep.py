"""The fused per-pencil kernel: reconstruct, solve Riemann problems, update, in one pass.

A *pencil* is a line of cells along one axis, ghosts included. For each pencil the kernel
gathers the primitive variables ``(rho, v_n, v_t1, v_t2)`` of the stage's input state into a
small buffer, reconstructs face states, computes the fluxes of all faces, and adds the flux
differences of its domain cells to the output state. Nothing the size of the mesh is
allocated and no face array is stored: the buffers live in L1 cache, one set per thread.
Pencils are independent, so the integrator distributes them over threads (``prange`` over
contiguous ranges of pencils) without races, and the result does not depend on the number
of threads. (The ``prange`` loops live in the top-level driver
:func:`~dustygas.grid.integrator.advance_gas` only: numba cannot cache a parallel function
that is called from another compiled function.)

One *stage* of an integrator updates

.. math::

    U_{out} = a\\,U_{base} + b\\,U_{in} + \\Delta t_{s}\\left[-\\sum_d
    \\frac{F_{d,+} - F_{d,-}}{\\Delta x_d}(U_{in}) + S(U_{in}) + S_{ext}\\right]

with one call of :func:`sweep_pencils` per active axis (over all its pencils). The first
call (``first=True``) writes ``a U_base + b U_in``, the source terms ``S`` of the shearing
box (evaluated from the same primitive buffer, thesis eq. 4.2b) and the optional external
momentum source ``S_ext`` (back-reaction of particles, given per unit volume and time); the
later calls add their flux differences. ``U_out`` may be the same array as ``U_base``
(in-place corrector); it must not be ``U_in``.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .diagnostics import cell_rate, fold_rate
from .reconstruct import reconstruct_faces
from .riemann import riemann_fluxes
from .shearing_box import momentum_source

__all__ = ["sweep_pencils", "pencil_count", "pencil_frame", "pencil_order", "pencil_rate", "gather_primitives"]


@njit(cache=True, error_model="numpy")
def pencil_frame(axis, lay, sp, ext_a, ext_b):
    """Geometry of the pencils along ``axis``: ``(n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb)``.

    ``n, g, stride, d`` are the domain cells, ghosts per side, flat stride and cell size along
    ``axis``; ``na, nb`` the domain cells of the two transverse axes (pencil order: ``(y, z)``
    for x pencils, ``(x, z)`` for y, ``(x, y)`` for z), ``ga, gb`` their ghosts, ``sa, sb``
    their strides and ``ea, eb`` the extra ghost layers covered on each side (``ext_a``,
    ``ext_b`` where the axis is active, else 0). Pencil ``p`` sits at transverse domain indices
    ``(p % (na + 2 ea) - ea, p // (na + 2 ea) - eb)`` and starts (first ghost cell) at the
    flat index ``(ia + ga) sa + (ib + gb) sb``.
    """
    nx, ny, nz, gx, gy, gz = lay
    NX = nx + 2 * gx
    NY = ny + 2 * gy
    if axis == 0:
        n, g, stride, d = nx, gx, 1, sp.dx
        na, ga, sa, nb, gb, sb = ny, gy, NX, nz, gz, NX * NY
    elif axis == 1:
        n, g, stride, d = ny, gy, NX, sp.dy
        na, ga, sa, nb, gb, sb = nx, gx, 1, nz, gz, NX * NY
    else:
        n, g, stride, d = nz, gz, NX * NY, sp.dz
        na, ga, sa, nb, gb, sb = nx, gx, 1, ny, gy, NX
    ea = ext_a if na > 1 else 0
    eb = ext_b if nb > 1 else 0
    return n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb


@njit(inline="always")
def pencil_order(axis):
    """The pencil order of ``axis``: ``(c1, c2, c3, row_x, row_y, row_z)``.

    Pencil variables 1, 2, 3 are the velocity normal to the faces and the two transverse
    ones, carried by the conserved components ``c1 = 1 + axis`` and ``c2, c3`` (the next two
    axes, cyclically); ``row_x, row_y, row_z`` are the pencil variables (and flux rows) that
    hold the x, y and z components.
    """
    return (1 + axis, 1 + (axis + 1) % 3, 1 + (axis + 2) % 3, 1 + (3 - axis) % 3, 1 + (4 - axis) % 3,
            1 + (5 - axis) % 3)


@njit(inline="always")
def gather_primitives(U, off, stride, c1, c2, c3, w0, w1, w2, w3) -> None:
    """Primitive variables of one pencil from the conserved state, in pencil order.

    ``w0[s], w1[s], w2[s], w3[s] = rho, m_n / rho, m_t1 / rho, m_t2 / rho`` (``v = m / rho``,
    thesis eq. 2.2's conserved variables ``(rho, rho v)``) for the ``N = w0.shape[0]`` cells
    ``off + s stride`` of the flattened state ``U`` ``(4, NTOT)``; ``c1, c2, c3`` from
    :func:`pencil_order`. Reads through views whose indices start at 0, so that numba drops
    its negative-index handling; inlined into the pencil kernels.
    """
    N = w0.shape[0]
    end = off + N * stride
    s_rho = U[0, off:end:stride]
    s_n = U[c1, off:end:stride]
    s_t1 = U[c2, off:end:stride]
    s_t2 = U[c3, off:end:stride]
    for s in range(N):
        rho = s_rho[s]
        inv = 1.0 / rho
        w0[s] = rho
        w1[s] = s_n[s] * inv
        w2[s] = s_t1[s] * inv
        w3[s] = s_t2[s] * inv


@njit(cache=True, error_model="numpy")
def pencil_count(axis: int, lay) -> int:
    """Number of pencils along ``axis``: the domain cells of the other two axes."""
    if axis == 0:
        return lay.ny * lay.nz
    if axis == 1:
        return lay.nx * lay.nz
    return lay.nx * lay.ny


@njit(cache=True, error_model="numpy")
def sweep_pencils(src, dst, base, axis, first, a, b, dt, lay, sp, scheme, st, xc, zc, ext, use_ext, bflux,
                  store_bflux, y_source, rates, bads, want_rate, skip_radial_edges, p0, p1, c0, c1, seg, nseg):
    """Add the flux differences along ``axis`` of ``src`` to ``dst`` for pencils ``p0 .. p1-1``,
    in their domain cells ``c0 .. c1-1`` along ``axis`` (a *segment*; ``0, n``: the whole pencil).

    Parameters
    ----------
    src, dst, base
        States ``(4, NZ, NY, NX)``: conserved density and momenta, ghost zones included
        (``src`` ghosts must be filled).
    axis
        0, 1, 2 for x, y, z.
    first
        Initialise ``dst = a base + b src + dt (S(src) + ext)`` before adding the fluxes.
    dt
        The stage's time-step factor ``Delta t_s``.
    lay, sp
        :class:`~dustygas.grid.mesh.Layout`, :class:`~dustygas.grid.mesh.Spacing`.
    scheme
        ``(reconstruction, limiter, riemann, cs)`` codes and the sound speed.
    st
        :class:`~dustygas.grid.shearing_box.SourceTerms`.
    xc, zc
        Cell-centre x and z coordinates, ghosts included.
    ext, use_ext
        External momentum source ``(3, nz, ny, nx)`` (domain cells) and whether to add it.
    bflux, store_bflux
        If ``store_bflux``, the fluxes through the first and last face of every pencil are
        stored in ``bflux[0 or 1, variable, ib, ia]``: ``(2, 4, nz, ny)`` in x sweeps (the
        shear-periodic flux correction), ``(2, 4, ny, nx)`` in z sweeps (the mass that leaves a
        box open in z).
    y_source
        ``(npencil,)``: in the first sweep, each pencil's sum of the y-momentum source of the
        shearing box (without ``ext``), for the momentum budget.
    rates, bads, want_rate, skip_radial_edges
        ``(npencil,)``: if ``want_rate`` (the last sweep of a step), each pencil's largest
        :func:`~dustygas.grid.diagnostics.cell_rate` of the values just written and its first
        invalid cell (flat domain index, -1 if none), leaving out the first and last radial
        cells if ``skip_radial_edges`` (a shear-periodic box corrects them afterwards).
    p0, p1
        Range of pencils; pencil ``p`` has transverse domain indices ``(p % na, p // na)``
        (``(j, k)`` for x, ``(i, k)`` for y, ``(i, j)`` for z).
    c0, c1, seg, nseg
        The segment: domain cells ``c0 .. c1-1`` along ``axis`` (read with the stencil's ghosts
        either side, so a segment's faces are computed from the same cells, bit for bit, as the
        whole pencil's), segment ``seg`` of ``nseg`` along each pencil: its rate goes to
        ``rates[p nseg + seg]`` (pencil order, then segment order: the first invalid cell of the
        step stays the first in pencil order); a stored boundary flux is the first face's if
        ``c0 = 0`` and the last face's if ``c1 = n``. A first sweep (``first``) must be whole
        (its ``y_source`` is per pencil).
    """
    method, limiter, solver, cs = scheme
    nx, ny, nz, gx, gy, gz = lay
    NTOT = src.shape[1] * src.shape[2] * src.shape[3]
    n_axis, g, stride, d, na, ga, sa, _, _, gb, sb, _ = pencil_frame(axis, lay, sp, 0, 0)
    dtdx = dt / d
    v1, v2, v3, row_x, row_y, row_z = pencil_order(axis)
    S = src.reshape(4, NTOT)
    D = dst.reshape(4, NTOT)
    B = base.reshape(4, NTOT)
    n = c1 - c0
    N = n + 2 * g
    lo, hi = g, g + n
    w = np.empty((4, N))
    wl = np.empty((4, N + 1))
    wr = np.empty((4, N + 1))
    flux = np.empty((4, N + 1))
    scratch = np.empty((2, N + 1))
    xs = np.empty(n)
    zs = np.empty(n)
    ext_x = np.zeros(n)
    ext_y = np.zeros(n)
    ext_z = np.zeros(n)
    w0, w1, w2, w3 = w[0], w[1], w[2], w[3]
    vx = w[row_x, lo:]
    vy = w[row_y, lo:]
    rho_c = w[0, lo:]
    f_rho = flux[0, lo:]
    f_x = flux[row_x, lo:]
    f_y = flux[row_y, lo:]
    f_z = flux[row_z, lo:]
    for p in range(p0, p1):
        ia = p % na
        ib = p // na
        off = (ia + ga) * sa + (ib + gb) * sb + c0 * stride  # the segment's first ghost cell
        gather_primitives(S, off, stride, v1, v2, v3, w0, w1, w2, w3)
        reconstruct_faces(w, lo, hi, method, limiter, wl, wr, scratch)
        riemann_fluxes(wl, wr, lo, hi, cs, solver, flux)
        if store_bflux:
            for v in range(4):
                if c0 == 0:
                    bflux[0, v, ib, ia] = flux[v, lo]
                if c1 == n_axis:
                    bflux[1, v, ib, ia] = flux[v, hi]
        # domain cells of the pencil: flux differences of faces i and i + 1
        first_cell = off + lo * stride
        last = first_cell + n * stride
        d_rho = D[0, first_cell:last:stride]
        d_x = D[1, first_cell:last:stride]
        d_y = D[2, first_cell:last:stride]
        d_z = D[3, first_cell:last:stride]
        if not first:
            for i in range(n):
                d_rho[i] -= dtdx * (f_rho[i + 1] - f_rho[i])
                d_x[i] -= dtdx * (f_x[i + 1] - f_x[i])
                d_y[i] -= dtdx * (f_y[i + 1] - f_y[i])
                d_z[i] -= dtdx * (f_z[i + 1] - f_z[i])
            if want_rate:
                pencil_rate(d_rho, d_x, d_y, d_z, axis, ia, ib, c0, lay, sp, cs, skip_radial_edges, rates, bads,
                             p * nseg + seg)
            continue
        # first sweep: base, input and source terms too
        if axis == 0:
            i0, j0, k0 = 0, ia, ib
            xs[:] = xc[c0 + lo:c0 + hi]
            zs[:] = zc[ib + gz]
        elif axis == 1:
            i0, j0, k0 = ia, 0, ib
            xs[:] = xc[ia + gx]
            zs[:] = zc[ib + gz]
        else:
            i0, j0, k0 = ia, ib, 0
            xs[:] = xc[ia + gx]
            zs[:] = zc[c0 + lo:c0 + hi]
        if use_ext:
            if axis == 0:
                ext_x[:] = ext[0, k0, j0, c0:c1]
                ext_y[:] = ext[1, k0, j0, c0:c1]
                ext_z[:] = ext[2, k0, j0, c0:c1]
            elif axis == 1:
                ext_x[:] = ext[0, k0, c0:c1, i0]
                ext_y[:] = ext[1, k0, c0:c1, i0]
                ext_z[:] = ext[2, k0, c0:c1, i0]
            else:
                ext_x[:] = ext[0, c0:c1, j0, i0]
                ext_y[:] = ext[1, c0:c1, j0, i0]
                ext_z[:] = ext[2, c0:c1, j0, i0]
        b_rho = B[0, first_cell:last:stride]
        b_x = B[1, first_cell:last:stride]
        b_y = B[2, first_cell:last:stride]
        b_z = B[3, first_cell:last:stride]
        u_rho = S[0, first_cell:last:stride]
        u_x = S[1, first_cell:last:stride]
        u_y = S[2, first_cell:last:stride]
        u_z = S[3, first_cell:last:stride]
        ysum = 0.0
        for i in range(n):
            sx, sy, sz = momentum_source(rho_c[i], vx[i], vy[i], xs[i], zs[i], st)
            ysum += sy
            sx += ext_x[i]
            sy += ext_y[i]
            sz += ext_z[i]
            d_rho[i] = a * b_rho[i] + b * u_rho[i] - dtdx * (f_rho[i + 1] - f_rho[i])
            d_x[i] = a * b_x[i] + b * u_x[i] + dt * sx - dtdx * (f_x[i + 1] - f_x[i])
            d_y[i] = a * b_y[i] + b * u_y[i] + dt * sy - dtdx * (f_y[i + 1] - f_y[i])
            d_z[i] = a * b_z[i] + b * u_z[i] + dt * sz - dtdx * (f_z[i + 1] - f_z[i])
        y_source[p] = ysum
        if want_rate:
            pencil_rate(d_rho, d_x, d_y, d_z, axis, ia, ib, c0, lay, sp, cs, skip_radial_edges, rates, bads,
                         p * nseg + seg)


@njit(cache=True, error_model="numpy")
def pencil_rate(d_rho, d_x, d_y, d_z, axis, ia, ib, c0, lay, sp, cs, skip_radial_edges, rates, bads, slot):
    """Largest cell rate of the values just written along a pencil's segment from domain cell
    ``c0`` (see sweep_pencils), into ``rates[slot]``, ``bads[slot]``."""
    nx, ny = lay.nx, lay.ny
    n = d_rho.shape[0]
    lo, hi = 0, n
    if skip_radial_edges:
        if axis == 0:
            lo, hi = 1, n - 1
        elif ia == 0 or ia == nx - 1:  # a radial boundary column (ia is the x index)
            lo, hi = 0, 0
    # flat domain index (k ny + j) nx + i of cell i of the segment: first + i * step
    if axis == 0:
        first, step = (ib * ny + ia) * nx, 1
    elif axis == 1:
        first, step = ib * ny * nx + ia, nx
    else:
        first, step = ib * nx + ia, nx * ny
    first += c0 * step
    best = 0.0
    bad = -1
    for i in range(lo, hi):
        best, bad = fold_rate(cell_rate(d_rho[i], d_x[i], d_y[i], d_z[i], lay, sp, cs), first + i * step, best, bad)
    rates[slot] = best
    bads[slot] = bad
