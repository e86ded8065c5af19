"""Pencil and cell kernels of the corner-transport-upwind integrator (:mod:`dustygas.grid.ctu`).

Face arrays have the shape of a state, ``(4, NZ, NY, NX)`` flattened to ``(4, NTOT)``: the face
between cells ``c - 1`` and ``c`` along an axis is stored at cell ``c``. States on faces are
conserved variables and fluxes are in the conserved order ``(rho, rho v_x, rho v_y, rho v_z)``,
whatever the axis; inside a pencil the variables are in the pencil order of
:mod:`dustygas.grid.sweep` (density, normal, two transverse).

A *transverse term* ``(slot, stride, coef)`` adds ``coef (F[slot][cell + stride] - F[slot][cell])``
to both face states of a cell along another axis: ``coef = -Delta t / (2 Delta x_b)`` with the
1D fluxes of axis b is the 2D corner-transport correction, ``-Delta t / (3 Delta x_b)`` the
first and ``-Delta t / (2 Delta x_b)`` with the corrected fluxes the second correction of the
3D one (Saltzman 1994).

Loops index views that start at the first element they need, with indices from 0, so that
numba drops its negative-index handling (see :mod:`dustygas.grid.reconstruct`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .diagnostics import cell_rate, fold_rate
from .reconstruct import DONOR, reconstruct_faces
from .riemann import riemann_fluxes
from .shearing_box import momentum_source
from .sweep import gather_primitives, pencil_frame, pencil_order
from .trace import trace_pencil

__all__ = ["predict_pencils", "transverse_rows", "transverse_pencils", "half_step_rows", "final_rows"]


@njit(cache=True, error_model="numpy")
def _ext_index(i, n, g, wrap):
    """Domain index of padded index ``i`` for the external source: periodic image or nearest cell."""
    d = i - g
    if d < 0:
        return d + n if wrap else 0
    if d >= n:
        return d - n if wrap else n - 1
    return d


@njit(cache=True, error_model="numpy")
def predict_pencils(u, axis, lay, sp, scheme, st, xc, zc, ext, use_ext, wrap, dt, ql, qr, flux1, p0, p1) -> None:
    """Traced half-step face states and their fluxes along ``axis``, pencils ``p0 .. p1-1``.

    The pencils cover the domain and one ghost layer on each side of the active transverse
    axes (the corner-transport correction of the faces next to them needs their fluxes).
    Each cell's states get half a step of the momentum sources (shearing box and ``ext``,
    evaluated in that cell at the start of the step) as velocity increments. Writes the
    conserved states ``ql``, ``qr`` ``(4, NTOT)`` on both sides of faces ``lo .. hi`` and their
    fluxes ``flux1``.
    """
    method, limiter, solver, cs = scheme
    nx, ny, nz, gx, gy, gz = lay
    n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb = pencil_frame(axis, lay, sp, 1, 1)
    dtdx = dt / d
    half = 0.5 * dt
    c1, c2, c3, row_x, row_y, row_z = pencil_order(axis)
    comps = (0, c1, c2, c3)
    NTOT = u.shape[1] * u.shape[2] * u.shape[3]
    U = u.reshape(4, NTOT)
    E = ext.reshape(3, ext.size // 3)  # (3, 1) when there is no source
    N = n + 2 * g
    lo, hi = g, g + n
    nface = n + 1
    ncell = n + 2  # cells lo-1 .. hi: both states of every face
    w = np.empty((4, N))
    wl = np.empty((4, N + 1))
    wr = np.empty((4, N + 1))
    f = np.empty((4, N + 1))
    scratch = np.empty((2, N + 1))
    acc = np.empty((3, ncell))
    xs = np.empty(ncell)
    zs = np.empty(ncell)
    eidx = np.empty(ncell, dtype=np.int64)
    sources = st.active or use_ext
    width = na + 2 * ea
    w0, w1, w2, w3 = w[0], w[1], w[2], w[3]
    wax = (w[row_x, lo - 1:], w[row_y, lo - 1:])
    rho_c = w[0, lo - 1:]
    for p in range(p0, p1):
        ia = p % width - ea
        ib = p // width - eb
        off = (ia + ga) * sa + (ib + gb) * sb
        gather_primitives(U, off, stride, c1, c2, c3, w0, w1, w2, w3)
        reconstruct_faces(w, lo, hi, method, limiter, wl, wr, scratch)
        if method != DONOR:
            trace_pencil(w, wl, wr, lo - 1, hi + 1, cs, dtdx)
        if sources:
            # cells lo-1 .. hi: positions, then half a step of acceleration
            if axis == 0:
                xs[:] = xc[lo - 1:hi + 1]
                zs[:] = zc[ib + gb]
            elif axis == 1:
                xs[:] = xc[ia + ga]
                zs[:] = zc[ib + gb]
            else:
                xs[:] = xc[ia + ga]
                zs[:] = zc[lo - 1:hi + 1]
            vx_c, vy_c = wax
            for i in range(ncell):
                rho = rho_c[i]
                sx, sy, sz = momentum_source(rho, vx_c[i], vy_c[i], xs[i], zs[i], st)
                acc[0, i] = sx
                acc[1, i] = sy
                acc[2, i] = sz
            if use_ext:
                ta = _ext_index(ia + ga, na, ga, wrap[1] if axis == 0 else wrap[0])
                tb = _ext_index(ib + gb, nb, gb, wrap[1] if axis == 2 else wrap[2])
                for i in range(ncell):
                    dd = _ext_index(lo - 1 + i, n, g, wrap[axis])
                    if axis == 0:
                        eidx[i] = (tb * ny + ta) * nx + dd
                    elif axis == 1:
                        eidx[i] = (tb * ny + dd) * nx + ta
                    else:
                        eidx[i] = (dd * ny + tb) * nx + ta
                for i in range(ncell):
                    e = eidx[i]
                    acc[0, i] += E[0, e]
                    acc[1, i] += E[1, e]
                    acc[2, i] += E[2, e]
            for i in range(ncell):
                scale = half / rho_c[i]
                acc[0, i] *= scale
                acc[1, i] *= scale
                acc[2, i] *= scale
            for r, row in enumerate((row_x, row_y, row_z)):
                a_r = acc[r]
                a_next = acc[r, 1:]
                left = wl[row, lo:]
                right = wr[row, lo:]
                for i in range(nface):  # face lo + i: left state from cell lo-1+i, right from lo+i
                    left[i] += a_r[i]
                    right[i] += a_next[i]
        riemann_fluxes(wl, wr, lo, hi, cs, solver, f)
        start = off + lo * stride
        stop = start + nface * stride
        rl = wl[0, lo:]
        rr = wr[0, lo:]
        for v in range(4):
            comp = comps[v]
            out_l = ql[comp, start:stop:stride]
            out_r = qr[comp, start:stop:stride]
            out_f = flux1[comp, start:stop:stride]
            fv = f[v, lo:]
            if v == 0:
                for i in range(nface):
                    out_l[i] = rl[i]
                    out_r[i] = rr[i]
                    out_f[i] = fv[i]
            else:
                lv = wl[v, lo:]
                rv = wr[v, lo:]
                for i in range(nface):
                    out_l[i] = rl[i] * lv[i]
                    out_r[i] = rr[i] * rv[i]
                    out_f[i] = fv[i]


@njit(cache=True, error_model="numpy")
def transverse_rows(ql, qr, fluxes, axis, tslot, tstride, tcoef, lay, r0, r1) -> None:
    """Add the transverse terms to both face states of axis ``axis`` of each cell, in place.

    The cells are those whose states enter the domain faces of ``axis``: one ghost layer on
    each side along ``axis``, the domain along the others; ``r0 .. r1-1`` are rows along x
    of that region (``r = j' + n_j' k'`` over its extents in y and z).
    """
    nx, ny, nz, gx, gy, gz = lay
    NX = nx + 2 * gx
    NY = ny + 2 * gy
    sa = 1 if axis == 0 else (NX if axis == 1 else NX * NY)
    ex = 1 if axis == 0 else 0
    ey = 1 if axis == 1 else 0
    ez = 1 if axis == 2 else 0
    nxr = nx + 2 * ex
    nyr = ny + 2 * ey
    nterm = tslot.shape[0]
    for r in range(r0, r1):
        j = gy - ey + r % nyr
        k = gz - ez + r // nyr
        base = (k * NY + j) * NX + gx - ex
        for t in range(nterm):
            F = fluxes[tslot[t]]
            s = tstride[t]
            coef = tcoef[t]
            for v in range(4):
                fa = F[v, base:]
                fb = F[v, base + s:]
                left = ql[v, base + sa:]
                right = qr[v, base:]
                for i in range(nxr):
                    corr = coef * (fb[i] - fa[i])
                    left[i] += corr
                    right[i] += corr


@njit(cache=True, error_model="numpy")
def transverse_pencils(u, dst, axis, lay, sp, scheme, ql, qr, fluxes, tslot, tstride, tcoef, ext_a, ext_b, out,
                       first, dt, bflux, store_bflux, p0, p1) -> None:
    """Face states of ``axis`` plus transverse terms, their fluxes, and either their storage or
    the update, for pencils ``p0 .. p1-1``.

    Parameters
    ----------
    u, dst
        State ``U^n`` ``(4, NZ, NY, NX)`` and the array the fluxes update (``out < 0``).
    ql, qr
        Conserved face states of this axis from :func:`predict_pencils`, ``(4, NTOT)``.
    fluxes
        All face fluxes ``(nslot, 4, NTOT)``; the terms read slots ``tslot`` with the strides
        ``tstride`` of their axes and the factors ``tcoef`` (module docstring; none after
        :func:`transverse_rows` added them in place).
    ext_a, ext_b
        Extra ghost layers of the pencils along the two transverse axes (pencil order).
    out
        ``>= 0``: store the fluxes of faces ``lo .. hi`` in ``fluxes[out]``. ``< 0``: update
        the domain cells, ``dst = U^n - dt/dx (F_+ - F_-)`` if ``first``, else
        ``dst -= dt/dx (F_+ - F_-)``.
    bflux, store_bflux
        ``(2, 4, nz, ny)``: the fluxes through the inner and outer x faces, stored for the
        shear-periodic correction (x updates only).
    """
    method, limiter, solver, cs = scheme
    n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb = pencil_frame(axis, lay, sp, ext_a, ext_b)
    dtdx = dt / d
    c1, c2, c3, _, _, _ = pencil_order(axis)
    comps = (0, c1, c2, c3)
    NTOT = u.shape[1] * u.shape[2] * u.shape[3]
    U = u.reshape(4, NTOT)
    D = dst.reshape(4, NTOT)
    N = n + 2 * g
    lo, hi = g, g + n
    nface = n + 1
    wl = np.empty((4, N + 1))
    wr = np.empty((4, N + 1))
    f = np.empty((4, N + 1))
    cl = np.empty((4, nface))  # conserved states of the faces lo .. hi
    cr = np.empty((4, nface))
    nterm = tslot.shape[0]
    width = na + 2 * ea
    for p in range(p0, p1):
        ia = p % width - ea
        ib = p // width - eb
        off = (ia + ga) * sa + (ib + gb) * sb
        start = off + lo * stride
        stop = start + nface * stride
        for v in range(4):
            in_l = ql[v, start:stop:stride]
            in_r = qr[v, start:stop:stride]
            a_l = cl[v]
            a_r = cr[v]
            for i in range(nface):
                a_l[i] = in_l[i]
                a_r[i] = in_r[i]
            for t in range(nterm):
                F = fluxes[tslot[t]]
                s = tstride[t]
                coef = tcoef[t]
                cells = start - stride  # cells lo-1 .. hi
                fa = F[v, cells:stop:stride]
                fb = F[v, cells + s:stop + s:stride]
                fa1 = F[v, start:stop:stride]
                fb1 = F[v, start + s:stop + s:stride]
                for i in range(nface):
                    a_l[i] += coef * (fb[i] - fa[i])
                    a_r[i] += coef * (fb1[i] - fa1[i])
        for v in range(4):
            a_l = cl[comps[v]]
            a_r = cr[comps[v]]
            out_l = wl[v, lo:]
            out_r = wr[v, lo:]
            if v == 0:
                for i in range(nface):
                    out_l[i] = a_l[i]
                    out_r[i] = a_r[i]
            else:
                rl = cl[0]
                rr = cr[0]
                for i in range(nface):
                    out_l[i] = a_l[i] / rl[i]
                    out_r[i] = a_r[i] / rr[i]
        riemann_fluxes(wl, wr, lo, hi, cs, solver, f)
        if out >= 0:
            F = fluxes[out]
            for v in range(4):
                dv = F[comps[v], start:stop:stride]
                fv = f[v, lo:]
                for i in range(nface):
                    dv[i] = fv[i]
            continue
        if store_bflux:
            for v in range(4):
                bflux[0, comps[v], ib, ia] = f[v, lo]
                bflux[1, comps[v], ib, ia] = f[v, hi]
        last = start + n * stride
        for v in range(4):
            comp = comps[v]
            fv = f[v, lo:]
            dv = D[comp, start:last:stride]
            if first:
                uv = U[comp, start:last:stride]
                for i in range(n):
                    dv[i] = uv[i] - dtdx * (fv[i + 1] - fv[i])
            else:
                for i in range(n):
                    dv[i] -= dtdx * (fv[i + 1] - fv[i])


@njit(cache=True, error_model="numpy")
def half_step_rows(u, uh, flux1, lay, sp, st, xc, zc, ext, use_ext, dt, r0, r1) -> None:
    """Cell-centred ``U^{n+1/2} = U^n - (dt/2) sum_a (F_a,+ - F_a,-)/dx_a + (dt/2)(S(U^n) + ext)``
    with the 1D (predictor) fluxes, for rows ``r0 .. r1-1`` of domain cells (``r = j + ny k``).
    This is the gas state the particles gather at the half step (Bai & Stone 2010a, §2.3)."""
    nx, ny, nz, gx, gy, gz = lay
    NX = nx + 2 * gx
    NY = ny + 2 * gy
    NTOT = u.shape[1] * u.shape[2] * u.shape[3]
    U = u.reshape(4, NTOT)
    H = uh.reshape(4, NTOT)
    half = 0.5 * dt
    xs = xc[gx:]
    for r in range(r0, r1):
        j = r % ny
        k = r // ny
        base = ((k + gz) * NY + j + gy) * NX + gx
        z = zc[k + gz]
        u0, u1, u2, u3 = U[0, base:], U[1, base:], U[2, base:], U[3, base:]
        h0, h1, h2, h3 = H[0, base:], H[1, base:], H[2, base:], H[3, base:]
        for i in range(nx):
            rho = u0[i]
            sx, sy, sz = momentum_source(rho, u1[i] / rho, u2[i] / rho, xs[i], z, st)
            if use_ext:
                sx += ext[0, k, j, i]
                sy += ext[1, k, j, i]
                sz += ext[2, k, j, i]
            h0[i] = rho
            h1[i] = u1[i] + half * sx
            h2[i] = u2[i] + half * sy
            h3[i] = u3[i] + half * sz
        for a in range(3):
            n_a = nx if a == 0 else (ny if a == 1 else nz)
            if n_a == 1:
                continue
            s = 1 if a == 0 else (NX if a == 1 else NX * NY)
            q = half / (sp.dx if a == 0 else (sp.dy if a == 1 else sp.dz))
            for v in range(4):
                fa = flux1[a, v, base:]
                fb = flux1[a, v, base + s:]
                hv = H[v, base:]
                for i in range(nx):
                    hv[i] -= q * (fb[i] - fa[i])


@njit(cache=True, error_model="numpy")
def final_rows(u, us, lay, sp, st, xc, zc, ext, use_ext, dt, cs, y_source, rates, bads, r0, r1) -> None:
    """``U^{n+1}`` from ``U^n`` (``u``, overwritten) and the flux update ``U* = U^n - dt div F``
    (``us``), adding the momentum sources time-centred, for rows ``r0 .. r1-1``.

    Coriolis and tidal terms by Crank-Nicolson (Stone & Gardiner 2010): with
    ``C M = (c_x M_y, -c_y M_x)``, ``rho_bar = (rho^n + rho^{n+1})/2`` and
    ``R = U* + dt [rho_bar (tidal_x x + force_x, 0, -gravity_z z) + ext] + (dt/2) C M^n``,
    the momenta solve ``(1 - (dt/2) C) M^{n+1} = R``, a 2x2 system solved exactly:
    ``M_x = (R_x + a R_y)/(1 + a b)``, ``M_y = R_y - b M_x`` with ``a = c_x dt/2``,
    ``b = c_y dt/2``. It conserves the epicyclic invariant ``c_y M_x^2 + c_x M_y^2`` of the
    rotation exactly. Writes each row's sum of the y-momentum source
    ``-c_y (M_x^n + M_x^{n+1})/2`` (without ``ext``) and its Courant rate and first invalid cell.
    """
    nx, ny, nz, gx, gy, gz = lay
    a = 0.5 * dt * st.coriolis_x
    b = 0.5 * dt * st.coriolis_y
    inv = 1.0 / (1.0 + a * b)
    xs = xc[gx:]
    for r in range(r0, r1):
        j = r % ny
        k = r // ny
        z = zc[k + gz]
        kk, jj = k + gz, j + gy
        u0, u1, u2, u3 = u[0, kk, jj, gx:], u[1, kk, jj, gx:], u[2, kk, jj, gx:], u[3, kk, jj, gx:]
        s0, s1, s2, s3 = us[0, kk, jj, gx:], us[1, kk, jj, gx:], us[2, kk, jj, gx:], us[3, kk, jj, gx:]
        best = 0.0
        bad = -1
        ysum = 0.0
        for i in range(nx):
            rho1 = s0[i]
            rho_bar = 0.5 * (u0[i] + rho1)
            mx0 = u1[i]
            rx = s1[i] + dt * rho_bar * (st.tidal_x * xs[i] + st.force_x) + a * u2[i]
            ry = s2[i] - b * mx0
            rz = s3[i] - dt * st.gravity_z * z * rho_bar
            if use_ext:
                rx += dt * ext[0, k, j, i]
                ry += dt * ext[1, k, j, i]
                rz += dt * ext[2, k, j, i]
            mx = (rx + a * ry) * inv
            my = ry - b * mx
            ysum -= 0.5 * st.coriolis_y * (mx0 + mx)
            u0[i] = rho1
            u1[i] = mx
            u2[i] = my
            u3[i] = rz
            best, bad = fold_rate(cell_rate(rho1, mx, my, rz, lay, sp, cs), (k * ny + j) * nx + i, best, bad)
        y_source[r] = ysum
        rates[r] = best
        bads[r] = bad
