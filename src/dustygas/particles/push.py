"""The compiled particle passes of a coupled step (see :mod:`dustygas.particles.coupling` for the
order in which the engine calls them and :mod:`dustygas.particles.drag` for the drag).

* :func:`dust_values` -- what a particle deposits for the local drag problem (its mass and
  momentum per unit volume, in its species' columns) or for a density field;
* :func:`cell_trajectories` -- the local drag problem of every domain cell: the gas velocity
  the particles will see over the step (:func:`~dustygas.particles.drag.cell_model`);
* :func:`kick` -- gather, velocity update, the gas's share of the drag, the second half drift.

Every pass over particles is a ``prange`` over fixed chunks of the particle range (the work of a
particle does not depend on where it is, so the chunks balance whatever the dust does); the
passes over cells split rows with the z index fastest, along y.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..grid.mesh import Layout, Offsets, Spacing
from .drag import (FIXED, MAX_SPECIES, N_COEF, Species, cell_model_decay, one_species_mode, one_species_response,
                   relax_row, step_coefficients, step_decay, stopping_time)
from .terms import ForceTable, frame_acceleration

__all__ = ["PARTICLE_CHUNKS", "U0", "ACC", "RESPONSE", "trajectory_columns", "dust_values",
           "cell_trajectories", "explicit_drag_source", "kick", "copy_domain", "occupied_rows", "padded_rows",
           "shear_frame_forces"]

#: particle passes run over this many chunks of the particle range (fixed: sums per chunk do
#: not depend on the thread count)
PARTICLE_CHUNKS = 64
#: columns of the trajectory field: gas velocity u^n (3), acceleration A (3), the response R_s
#: (3) of every species, then (where needed) the gas density and a mesh acceleration (3)
U0, ACC, RESPONSE = 0, 3, 6


def trajectory_columns(nspecies: int, need_rho: bool, mesh: bool) -> tuple[int, int, int]:
    """``(ncolumns, column of ρ or -1, first column of the mesh acceleration or -1)``."""
    n = RESPONSE + 3 * nspecies
    c_rho = n if need_rho else -1
    n += 1 if need_rho else 0
    c_mesh = n if mesh else -1
    n += 3 if mesh else 0
    return n, c_rho, c_mesh


@njit(cache=True, parallel=True, error_model="numpy")
def dust_values(pos, vel, species, mass, n, inv_vol, momentum, shear_rate, back, out, col) -> None:
    """``out[p] = m/V (, m w/V)`` and ``col[p]`` = its species' first column (4 or 1 per species).

    ``w = (v_x, v_y + shear_rate x, v_z)`` is the velocity relative to the shear (``shear_rate
    = q Ω`` when full velocities are stored, else 0), with ``x = pos_x - back v_x`` the position
    at the time of ``v`` (``back``: the drift since then, 0 if x is inactive). It is the same for
    a particle and its radial images, so the deposit needs no image shift of ``v_y``.
    """
    nchunk = min(max(n, 1), PARTICLE_CHUNKS)
    width = 4 if momentum else 1
    for c in prange(nchunk):
        for p in range(c * n // nchunk, (c + 1) * n // nchunk):
            q = mass[p] * inv_vol
            out[p, 0] = q
            if momentum:
                out[p, 1] = q * vel[0, p]
                out[p, 2] = q * (vel[1, p] + shear_rate * (pos[0, p] - back * vel[0, p]))
                out[p, 3] = q * vel[2, p]
            col[p] = width * species[p]


@njit(cache=True, parallel=True, error_model="numpy")
def cell_trajectories(u_old, u_half, gas_g, s_drag, pred_dt, h, layout, spacing, offsets, dep, nsp, species_table,
                      forces, mesh_field, shear_rate, feedback, traj, gt, c_rho, c_mesh, k_lo, k_hi) -> None:
    """The trajectory field of the domain cells of rows ``k_lo .. k_hi-1`` (columns
    :func:`trajectory_columns`).

    ``u_old``, ``u_half``: the gas state at ``t^n`` and after the predictor (ghosts ``gas_g``);
    ``s_drag`` ``(3, nz, ny, nx)``: the drag source the predictor applied with step
    ``pred_dt``; the gas's non-drag acceleration is ``(u_free - u^n)/pred_dt`` with
    ``u_free = (m_half - pred_dt s_drag)/ρ_half``. ``dep`` ``(nz, ny, nx, 4 nsp)``: the dust
    density and momentum per species (with ``feedback``; velocities relative to the shear,
    :func:`dust_values`). ``shear_rate``: ``q Ω`` if the gas stores full velocities, else 0;
    the local problem is solved in the velocities relative to the shear, ``u_y + q Ω x``
    (periodic across a shearing box), with ``forces`` the forces of that frame
    (:func:`shear_frame_forces`): there the drift of a uniform dust through uniform gas
    (NSH) has constant velocities, A = 0 and B_k = 0. ``traj`` has ``gt = (gx, gy, gz)`` ghost
    layers (filled later). ``spacing``, ``offsets``: the whole mesh's spacing and the block's offsets
    (cell centres ``x0 + (i0 + i + 1/2) dx``, those of the whole mesh bit for bit).
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    off = Offsets(*offsets)
    sp_tab = Species(*species_table)
    ft = ForceTable(*forces)
    nx, ny = lay.nx, lay.ny
    gx, gy, gz = gas_g
    tx, ty, tz = gt
    nk = k_hi - k_lo
    nrows = ny * nk
    nchunk = min(nrows, 64)
    for chunk in prange(nchunk):
        u0 = np.empty(3)
        fg = np.empty(3)
        rho_s = np.zeros(MAX_SPECIES)
        vel_s = np.zeros((MAX_SPECIES, 3))
        acc_s = np.zeros((MAX_SPECIES, 3))
        ts_s = np.ones(MAX_SPECIES)
        out_a = np.empty(3)
        out_r = np.zeros((MAX_SPECIES, 3))
        work = np.empty((6, MAX_SPECIES))
        perm = np.empty(MAX_SPECIES, dtype=np.int64)
        bk = np.empty((MAX_SPECIES, 3))
        decay = np.empty((2, MAX_SPECIES))
        for s in range(nsp):
            if sp_tab.law[s] == FIXED:
                step_decay(h, sp_tab.t_stop, s, decay)
        for r in range(chunk * nrows // nchunk, (chunk + 1) * nrows // nchunk):
            k = k_lo + r % nk
            j = r // nk
            z = sp.z0 + (off.k0 + k + 0.5) * sp.dz
            for i in range(nx):
                x = sp.x0 + (off.i0 + i + 0.5) * sp.dx
                kk, jj, ii = k + gz, j + gy, i + gx
                rho0 = u_old[0, kk, jj, ii]
                rhoh = u_half[0, kk, jj, ii]
                for c in range(3):
                    u0[c] = u_old[1 + c, kk, jj, ii] / rho0
                    fg[c] = ((u_half[1 + c, kk, jj, ii] - pred_dt * s_drag[c, k, j, i]) / rhoh - u0[c]) / pred_dt
                u0[1] += shear_rate * x
                tk, tj, ti = k + tz, j + ty, i + tx
                traj[tk, tj, ti, U0] = u0[0]
                traj[tk, tj, ti, U0 + 1] = u0[1]
                traj[tk, tj, ti, U0 + 2] = u0[2]
                if c_rho >= 0:
                    traj[tk, tj, ti, c_rho] = rhoh
                if c_mesh >= 0:
                    for c in range(3):
                        traj[tk, tj, ti, c_mesh + c] = mesh_field[c, k, j, i]
                dusty = False
                if feedback:
                    for s in range(nsp):
                        if dep[k, j, i, 4 * s] > 0.0:
                            dusty = True
                if not dusty:
                    for c in range(3):
                        traj[tk, tj, ti, ACC + c] = fg[c]
                    for s in range(nsp):
                        for c in range(3):
                            traj[tk, tj, ti, RESPONSE + 3 * s + c] = 0.0
                    continue
                for s in range(nsp):
                    d = dep[k, j, i, 4 * s]
                    rho_s[s] = d
                    ts_s[s] = stopping_time(sp_tab.law[s], sp_tab.t_stop[s], sp_tab.grain[s], sp_tab.cs, rhoh)
                    if sp_tab.law[s] != FIXED:
                        step_decay(h, ts_s, s, decay)
                    if d > 0.0:
                        vx = dep[k, j, i, 4 * s + 1] / d
                        vy = dep[k, j, i, 4 * s + 2] / d
                        vz = dep[k, j, i, 4 * s + 3] / d
                        vel_s[s, 0], vel_s[s, 1], vel_s[s, 2] = vx, vy, vz
                        ax, ay, az = frame_acceleration(x, vx, vy, ft)
                        acc_s[s, 0] = ax + mesh_field[0, k, j, i]
                        acc_s[s, 1] = ay + mesh_field[1, k, j, i]
                        acc_s[s, 2] = az + mesh_field[2, k, j, i] - ft.gravity_z * z
                if nsp == 1:  # cell_model's one-species case without the call (most of its cost)
                    rho1 = rho_s[0]
                    tot = rhoh + rho1
                    T = ts_s[0]
                    eps = fac = 0.0
                    if tot != rhoh:
                        eps, fac = one_species_mode(rhoh, rho1, T, h, decay[0, 0], decay[1, 0])
                    for c in range(3):
                        out_a[c] = (rhoh * fg[c] + rho1 * acc_s[0, c]) / tot
                        out_r[0, c] = (one_species_response(eps, fac, T, u0[c] - vel_s[0, c], fg[c] - acc_s[0, c])
                                       if tot != rhoh else 0.0)
                else:
                    cell_model_decay(rhoh, u0, fg, nsp, rho_s, vel_s, acc_s, ts_s, h, decay, out_a, out_r, work, perm,
                                     bk)
                for c in range(3):
                    traj[tk, tj, ti, ACC + c] = out_a[c]
                for s in range(nsp):
                    for c in range(3):
                        traj[tk, tj, ti, RESPONSE + 3 * s + c] = out_r[s, c]


@njit(cache=True, parallel=True, error_model="numpy")
def explicit_drag_source(u_old, gas_g, spacing, offsets, shear_rate, dep, nsp, species_table, out) -> None:
    """The drag of the dust on the gas at ``t^n``, ``S = Σ_s ρ_s (V_s - u)/T_s`` per domain
    cell (momentum per volume and time, ``out`` ``(3, nz, ny, nx)``), from the dust deposit
    ``dep`` ``(nz, ny, nx, 4 nsp)`` (:func:`dust_values`: velocities relative to the shear
    ``shear_rate``) and the gas state ``u_old`` (ghosts ``gas_g``): the predictor's source at
    the first step, which has no previous corrector's. ``spacing``, ``offsets`` and
    ``species_table`` are the tuples of :class:`~dustygas.grid.mesh.Spacing`,
    :class:`~dustygas.grid.mesh.Offsets` and :class:`~dustygas.particles.drag.Species`.
    """
    sp = Spacing(*spacing)
    off = Offsets(*offsets)
    sp_tab = Species(*species_table)
    nc, nz, ny, nx = out.shape
    gx, gy, gz = gas_g
    for k in prange(nz):
        for j in range(ny):
            for i in range(nx):
                kk, jj, ii = k + gz, j + gy, i + gx
                rho = u_old[0, kk, jj, ii]
                shear = shear_rate * (sp.x0 + (off.i0 + i + 0.5) * sp.dx)
                for c in range(3):
                    out[c, k, j, i] = 0.0
                for s in range(nsp):
                    d = dep[k, j, i, 4 * s]
                    if d > 0.0:
                        ts = stopping_time(sp_tab.law[s], sp_tab.t_stop[s], sp_tab.grain[s], sp_tab.cs, rho)
                        for c in range(3):
                            u = u_old[1 + c, kk, jj, ii] / rho + (shear if c == 1 else 0.0)
                            out[c, k, j, i] += (dep[k, j, i, 4 * s + 1 + c] - d * u) / ts


@njit(cache=True, error_model="numpy", inline="always")
def gather_drag(flat, wts, p, R, base, nyt, nxt, rcol, rx, ry, rz):
    """Gather of particle ``p``'s drag columns from the trajectory field ``flat`` (cells, columns):
    ``u0`` (3), ``A`` (3) and the response ``R`` of its species (columns ``rcol .. rcol + 2``),
    interpolated with the weights ``wts[p]`` (thesis eq. 4.22) over the cells within ``(rx, ry,
    rz)`` of cell ``base`` (``nxt``, ``nyt``: the field's row lengths, ghosts included).

    Inlined; a call with literal reaches gives the compiler fixed, unrolled loops. The sums run
    in the same order for any reach, so the specialised and the general call agree bit for bit.
    """
    u0x = u0y = u0z = ax_ = ay_ = az_ = rx_ = ry_ = rz_ = 0.0
    for dk in range(-rz, rz + 1):
        wz = wts[p, 2, R + dk]
        if wz == 0.0:
            continue
        for dj in range(-ry, ry + 1):
            wyz = wz * wts[p, 1, R + dj]
            if wyz == 0.0:
                continue
            row = base + (dk * nyt + dj) * nxt
            for di in range(-rx, rx + 1):
                w = wyz * wts[p, 0, R + di]
                if w == 0.0:
                    continue
                cell = row + di
                u0x += w * flat[cell, U0]
                u0y += w * flat[cell, U0 + 1]
                u0z += w * flat[cell, U0 + 2]
                ax_ += w * flat[cell, ACC]
                ay_ += w * flat[cell, ACC + 1]
                az_ += w * flat[cell, ACC + 2]
                rx_ += w * flat[cell, rcol]
                ry_ += w * flat[cell, rcol + 1]
                rz_ += w * flat[cell, rcol + 2]
    return u0x, u0y, u0z, ax_, ay_, az_, rx_, ry_, rz_


@njit(cache=True, parallel=True, error_model="numpy")
def kick(pos, vel, species, mass, n, keys, wts, R, reach, layout, spacing, traj, gt, c_rho, c_mesh, species_table, coef,
         forces, shear_rate, h, inv_vol, active, values, budget, vmax, work):
    """Gather, velocity update and second half drift of particles ``0 .. n-1`` (module docstring).

    ``pos`` holds ``x^{n+1/2}`` and becomes ``x^{n+1}``; ``vel`` ``v^n`` -> ``v^{n+1}``. The
    update integrates the velocity relative to the shear, ``w_y = v_y + shear_rate x`` (taken
    at ``x^n`` and ``x^{n+1}``), with the forces ``forces`` of that frame (:func:`shear_frame_forces`)
    against the trajectory field, which holds the gas's ``u_y + shear_rate x``: a particle
    drifting radially at a constant ``w`` (NSH) is then a fixed point, where integrating ``v_y``
    with the gas velocity held at ``x^{n+1/2}`` is not (its ``v_y`` changes linearly in time).
    ``coef`` ``(nsp, N_COEF)``: the step coefficients of the species of fixed stopping time
    (:func:`~dustygas.particles.drag.step_coefficients`). ``values[p]`` receives minus the
    particle's drag impulse per unit volume and time, ``-m (v^{n+1} - v^n - g h)/(V h)`` (the
    gas's share, deposited next). ``budget`` ``(nz ny, 3)``: running totals per row of cells
    ``(k, j)`` (``keys // nx``) of the momentum the particles received from the non-drag terms,
    to which each row's sum over its particles, in their order, is added: a sum that does not
    depend on the chunks, the thread count or the block (:mod:`dustygas.parallel`) that holds
    the row. A row that two chunks share has its particles' impulses written to ``work``
    ``(>= 3, >= n)`` and summed after the parallel loop. ``vmax`` ``(>= nchunk, 3)``: the largest
    ``|v_d|`` per chunk (work space).

    Returns
    -------
    vx, vy, vz
        The largest ``|v_d|`` along each axis over the particles (0 without particles).
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    sp_tab = Species(*species_table)
    ft = ForceTable(*forces)
    nx, ny = lay.nx, lay.ny
    tx, ty, tz = gt
    rx, ry, rz = reach[0], reach[1], reach[2]
    w2 = ft.gravity_z
    nzt, nyt, nxt, nf = traj.shape
    flat = traj.reshape(nzt * nyt * nxt, nf)  # one index per cell: one negative-index check per load
    tsc_xz = rx == 1 and ry == 0 and rz == 1
    tsc_3d = rx == 1 and ry == 1 and rz == 1
    nchunk = min(max(n, 1), PARTICLE_CHUNKS)
    for c in prange(nchunk):
        own = np.empty((1, N_COEF))  # the step coefficients of an Epstein particle
        p0, p1 = c * n // nchunk, (c + 1) * n // nchunk
        # the first and last rows of the chunk, and whether the neighbouring chunks share them
        row_lo, row_hi = keys[p0] // nx if p1 > p0 else -1, keys[p1 - 1] // nx if p1 > p0 else -1
        shared_lo = p1 > p0 and p0 > 0 and keys[p0 - 1] // nx == row_lo
        shared_hi = p1 > p0 and p1 < n and keys[p1] // nx == row_hi
        cells_row = -1  # the row whose sum (bx, by, bz) is running
        bx = by = bz = 0.0
        mx = my = mz = 0.0
        for p in range(p0, p1):
            key = keys[p]
            u = key // nx  # the row (k, j)
            i, j, k = key - u * nx, u % ny, u // ny
            s = species[p]
            rcol = RESPONSE + 3 * s
            # the gathered u0 (3), A (3), R (3): scalars, which stay in registers (sums into an
            # array are stores the compiler cannot drop); the usual stencils with their reach
            # known to the compiler, which then unrolls the loops (linA: -16 % of the kick)
            base = ((k + tz) * nyt + j + ty) * nxt + i + tx
            if tsc_xz:
                u0x, u0y, u0z, ax_, ay_, az_, rx_, ry_, rz_ = gather_drag(flat, wts, p, R, base, nyt, nxt, rcol,
                                                                          1, 0, 1)
            elif tsc_3d:
                u0x, u0y, u0z, ax_, ay_, az_, rx_, ry_, rz_ = gather_drag(flat, wts, p, R, base, nyt, nxt, rcol,
                                                                          1, 1, 1)
            else:
                u0x, u0y, u0z, ax_, ay_, az_, rx_, ry_, rz_ = gather_drag(flat, wts, p, R, base, nyt, nxt, rcol,
                                                                          rx, ry, rz)
            rho_ = mx_ = my_ = mz_ = 0.0  # the optional columns: ρ, the mesh acceleration (3)
            if c_rho >= 0 or c_mesh >= 0:
                for dk in range(-rz, rz + 1):
                    for dj in range(-ry, ry + 1):
                        wyz = wts[p, 2, R + dk] * wts[p, 1, R + dj]
                        row = base + (dk * nyt + dj) * nxt
                        for di in range(-rx, rx + 1):
                            w = wyz * wts[p, 0, R + di]
                            if w == 0.0:
                                continue
                            if c_rho >= 0:
                                rho_ += w * flat[row + di, c_rho]
                            if c_mesh >= 0:
                                mx_ += w * flat[row + di, c_mesh]
                                my_ += w * flat[row + di, c_mesh + 1]
                                mz_ += w * flat[row + di, c_mesh + 2]
            x, y, z = pos[0, p], pos[1, p], pos[2, p]
            v0x, v0y, v0z = vel[0, p], vel[1, p], vel[2, p]
            x0 = x - 0.5 * h * v0x if active[0] else x
            w0y = v0y + shear_rate * x0
            ux, uy, uz = u0x, u0y, u0z
            if sp_tab.law[s] == FIXED:
                ts = sp_tab.t_stop[s]
                cf = coef  # row `row` of cf: no view per particle (a view costs a reference count)
                row = s
            else:
                ts = stopping_time(sp_tab.law[s], sp_tab.t_stop[s], sp_tab.grain[s], sp_tab.cs, rho_)
                step_coefficients(ts, w2, h, own[0])
                cf = own
                row = 0
            # the held accelerations at x^{n+1/2} and the velocity predicted over half a step
            ax0, ay0, az0 = frame_acceleration(x, v0x, w0y, ft)
            mgx, mgy, mgz = mx_, my_, mz_
            hx = relax_row(v0x, cf, row, 3, ts, ux, ax_, ax0 + mgx, 0.0)
            hy = relax_row(w0y, cf, row, 3, ts, uy, ay_, ay0 + mgy, 0.0)
            gx_, gy_, _ = frame_acceleration(x, hx, hy, ft)
            gx_ += mgx
            gy_ += mgy
            gz_ = az0 + mgz
            nvx = relax_row(v0x, cf, row, 0, ts, ux, ax_, gx_, rx_)
            nwy = relax_row(w0y, cf, row, 0, ts, uy, ay_, gy_, ry_)
            x1 = x + 0.5 * h * nvx if active[0] else x
            nvy = nwy - shear_rate * x1
            jx = nvx - v0x - gx_ * h
            jy = nwy - w0y - gy_ * h
            if w2 > 0.0:
                z0 = z - 0.5 * h * v0z
                b0 = gz_ + uz / ts
                b1 = az_ / ts
                zo = cf[row, 6] * z0 + cf[row, 7] * v0z + cf[row, 8] * b0 + cf[row, 9] * b1
                vo = cf[row, 10] * z0 + cf[row, 11] * v0z + cf[row, 12] * b0 + cf[row, 13] * b1
                nvz = vo + rz_
                nz_ = zo + 0.5 * h * rz_
                ext_z = gz_ * h - w2 * h * 0.5 * (z0 + nz_)
            else:
                nvz = relax_row(v0z, cf, row, 0, ts, uz, az_, gz_, rz_)
                ext_z = gz_ * h
                nz_ = z + 0.5 * h * nvz
            jz = nvz - v0z - ext_z
            q = -mass[p] * inv_vol / h
            values[p, 0] = q * jx
            values[p, 1] = q * jy
            values[p, 2] = q * jz
            m = mass[p]
            ix_ = m * gx_ * h
            iy_ = m * (nvy - v0y - jy)  # the change of the stored v_y that is not drag
            iz_ = m * ext_z
            if (shared_lo and u == row_lo) or (shared_hi and u == row_hi):
                work[0, p] = ix_
                work[1, p] = iy_
                work[2, p] = iz_
            else:
                if u != cells_row:
                    if cells_row >= 0:
                        budget[cells_row, 0] += bx
                        budget[cells_row, 1] += by
                        budget[cells_row, 2] += bz
                    cells_row = u
                    bx = by = bz = 0.0
                bx += ix_
                by += iy_
                bz += iz_
            vel[0, p] = nvx
            vel[1, p] = nvy
            vel[2, p] = nvz
            pos[0, p] = x1
            if active[1]:
                pos[1, p] = y + 0.5 * h * nvy
            if active[2]:
                pos[2, p] = nz_
            mx = max(mx, abs(nvx))
            my = max(my, abs(nvy))
            mz = max(mz, abs(nvz))
        if cells_row >= 0:
            budget[cells_row, 0] += bx
            budget[cells_row, 1] += by
            budget[cells_row, 2] += bz
        vmax[c, 0] = mx
        vmax[c, 1] = my
        vmax[c, 2] = mz
    # the rows two or more chunks share, each summed over its particles in order
    done = -1
    for edge in range(1, nchunk):  # names apart from the parallel loop's (numba would share them)
        at = edge * n // nchunk
        shared = keys[at] // nx
        if shared == done or keys[at - 1] // nx != shared:
            continue
        first, last = at - 1, at + 1
        while first > 0 and keys[first - 1] // nx == shared:
            first -= 1
        while last < n and keys[last] // nx == shared:
            last += 1
        sx = sy = sz = 0.0
        for q in range(first, last):
            sx += work[0, q]
            sy += work[1, q]
            sz += work[2, q]
        budget[shared, 0] += sx
        budget[shared, 1] += sy
        budget[shared, 2] += sz
        done = shared
    fastest_x = fastest_y = fastest_z = 0.0
    for part in range(nchunk):
        fastest_x = max(fastest_x, vmax[part, 0])
        fastest_y = max(fastest_y, vmax[part, 1])
        fastest_z = max(fastest_z, vmax[part, 2])
    return fastest_x, fastest_y, fastest_z


def shear_frame_forces(ft: ForceTable, shear_rate: float) -> ForceTable:
    """The particle terms ``ft`` written for the velocity relative to the shear,
    ``w_y = v_y + s x`` (``s = shear_rate``): ``dw_y/dt = dv_y/dt + s v_x`` and ``v_y = w_y - s x``
    give ``c_y -> c_y - s`` and ``t_x -> t_x - c_x s`` (the rotating frame of full velocities,
    ``(2Ω, 2Ω, 2qΩ²)``, becomes that of orbital advection, ``(2Ω, (2 - q)Ω, 0)``; thesis eq. 4.2).

    >>> from dustygas.particles.terms import RotatingFrame, force_table
    >>> shear_frame_forces(force_table([RotatingFrame(1.0)]), 1.5)[:3]
    (2.0, 0.5, 0.0)
    """
    return ft._replace(coriolis_y=ft.coriolis_y - shear_rate, tidal_x=ft.tidal_x - ft.coriolis_x * shear_rate)


@njit(cache=True, error_model="numpy")
def occupied_rows(keys, n: int, nx: int, ny: int, nz: int, margin: int, periodic_z: bool) -> tuple[int, int]:
    """The z rows ``[k_lo, k_hi)`` within ``margin`` of a particle's cell (sorted ``keys``): the
    fields the particles gather and deposit are needed there only. The whole column when the
    range comes within ``margin`` of a face of a periodic z axis (its ghosts copy the other side)."""
    if n == 0 or nz == 1:
        return 0, nz
    k0 = int(keys[0]) // (nx * ny)
    k1 = int(keys[n - 1]) // (nx * ny)
    lo, hi = k0 - margin, k1 + 1 + margin
    if periodic_z and (lo < 0 or hi > nz):
        return 0, nz
    return max(lo, 0), min(hi, nz)


@njit(cache=True, error_model="numpy")
def padded_rows(rows: tuple[int, int], gz: int, nz: int) -> tuple[int, int]:
    """The padded z rows ``[k_lo, k_hi)`` of a field with ``gz`` ghost layers that hold the domain
    rows ``rows`` of a mesh of ``nz`` rows, with the ghost rows beyond them where they reach a z face."""
    k_lo = rows[0] + gz if rows[0] > 0 else 0
    k_hi = rows[1] + gz if rows[1] < nz else nz + 2 * gz
    return k_lo, k_hi


@njit(cache=True, parallel=True, error_model="numpy")
def copy_domain(field, g, out, sign) -> None:
    """``out[c, k, j, i] = sign field[k + gz, j + gy, i + gx, c]`` (AoS padded -> SoA domain)."""
    nc, nz, ny, nx = out.shape
    gx, gy, gz = g
    for k in prange(nz):
        for j in range(ny):
            for i in range(nx):
                for c in range(nc):
                    out[c, k, j, i] = sign * field[k + gz, j + gy, i + gx, c]
