"""Pair kernels of hierarchical individual time steps: densities, forces and kicks of the active particles.

With block time steps (:mod:`~dustygas.sph.timesteps`) only a subset :math:`S` of the particles
is active at a sub-step, typically the inner disk. Each kernel here costs :math:`O(|S|)` and works
on :math:`S` (its *slots*, :math:`S` in tree order) and on the neighbour rows of
:func:`dustygas.sph.active_search.active_search`:

* :func:`active_densities` -- :math:`h` and :math:`\\rho` (thesis eq. 3.1) of the active particles;
* :func:`active_hydro` and :func:`active_drag` -- pair forces of the active particles (thesis
  eqs. 3.2-3.3 and 3.19), each stored per row entry without the partner's mass, so that the
  partner's share follows from the same number (:func:`kick_active`, :func:`kick_passive`);
* :func:`reverse_rows` -- for every inactive neighbour, the row entries it appears in;
* :func:`limit_levels` -- the time-step limiter.

Every pair term is symmetric before the partner's mass is applied, so the momentum one
particle receives is the momentum its partner loses, to round-off.

All loops gather into per-slot outputs (no atomics): deterministic for any thread count.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .density import row_buffers, solve_one_smoothing_length
from .dust.two_fluid_kernels import KERNEL_AVERAGE, KERNEL_OTHER, KERNEL_OWN, drag_pair
from .forces import NPACK, pack_row, pressure_pair
from .kernels import kernel_dshape, kernel_shape
from .neighbours import minimum_image
from .particles import GAS
from .viscosity import signal_speed, viscous_pair
from .workshare import CHUNK, WORKERS, new_counter, next_chunk

__all__ = ["active_densities", "pack_hydro", "active_hydro", "active_drag", "gas_at_dust", "reverse_rows", "kick_active",
           "kick_passive", "kick_external", "limit_levels", "HYDRO", "DRAG", "NPACK"]

HYDRO = 0
DRAG = 1
# columns of the packed per-particle table (:func:`dustygas.sph.forces.pack_row`) that the pair loop reads
_X, _Y, _Z, _VX, _VY, _VZ, _HINV, _GRADNORM, _M, _P, _RHOINV, _OMBAR, _FORM, _CS, _ALPHA = range(15)


# --------------------------------------------------------------------------- density


@njit(parallel=True, cache=True)
def active_densities(act, pos, mass, h_guess, h_search, same_start, same_index, same_count, shape, norm, ndim, hfact,
                     length, periodic, tol, maxiter, h_out, rho_out, omega_out, status, iterations):
    """Smoothing lengths and densities (thesis eq. 3.1) of the active particles from their same-species
    rows (:func:`dustygas.sph.density.solve_one_smoothing_length`); outputs per slot."""
    n = act.shape[0]
    nchunk = (n + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        c = next_chunk(counter)
        while c < nchunk:
            i0, i1 = c * CHUNK, min(n, (c + 1) * CHUNK)
            r, m = row_buffers(same_count, i0, i1)
            for i in range(i0, i1):
                a = act[i]
                h_out[i], rho_out[i], omega_out[i], status[i], iterations[i] = solve_one_smoothing_length(
                    pos[a, 0], pos[a, 1], pos[a, 2], mass[a], h_guess[i], h_search[i], same_index, same_start[i],
                    same_count[i], pos, mass, shape, norm, ndim, hfact, length, periodic, tol, maxiter, r, m)
            c = next_chunk(counter)


# --------------------------------------------------------------------------- hydrodynamics


@njit(parallel=True, cache=True)
def pack_hydro(rows, pos, vel, mass, h, rho, omega, P, cs, alpha, u, norm, ndim, form, out):
    """Write what a neighbour contributes to the pair forces into ``out[rows]`` (the rows the current
    sub-step reads: the active particles and their neighbours; :func:`dustygas.sph.forces.pack_row`).
    ``vel`` are the predicted velocities, one per row; the GASOLINE2 factor is :math:`1/\\Omega`."""
    for k in prange(rows.shape[0]):
        a = rows[k]
        pack_row(out, a, pos, vel[k, 0], vel[k, 1], vel[k, 2], mass, h, rho, omega, P, cs, alpha, u, 1.0 / omega[a],
                 norm, ndim, form)


@njit(parallel=True, cache=True)
def active_hydro(act, ptype, packed, same_start, same_index, same_count, shape, radius, length, periodic, form, beta,
                 gradients, pair_s, acc, divv, curlv, vsig, grad):
    """Pressure and artificial-viscosity pair forces of the active gas particles (thesis eqs. 3.2-3.3;
    :mod:`dustygas.sph.forces`), with :math:`\\nabla\\cdot v`, :math:`|\\nabla\\times v|` and signal speeds.

    ``pair_s[e]`` receives the pair factor :math:`s_{ab}/r_{ab}` of row entry ``e`` (symmetric in
    :math:`a \\leftrightarrow b`): the acceleration of :math:`a` is :math:`-m_b s_{ab}\\,\\mathbf r_{ab}/r_{ab}`
    and that of :math:`b` is :math:`+m_a s_{ab}\\,\\mathbf r_{ab}/r_{ab}`. ``acc`` (per slot) is the sum,
    used for the time step; the kicks are :func:`kick_active` / :func:`kick_passive`. ``grad`` (per slot,
    row-major :math:`\\partial_j v_k`) receives the SPH velocity gradient
    :math:`-(\\Omega_a\\rho_a)^{-1}\\sum_b m_b(\\mathbf v_a - \\mathbf v_b)\\,\\nabla_a W_{ab}(h_a)`
    (:func:`dustygas.sph.dust.two_fluid_kernels.velocity_gradient`) from the same pairs, and ``curlv``
    :math:`|\\nabla\\times v|`, only when ``gradients`` is true (zero otherwise: the drag's
    reconstruction is their only reader).
    """
    r2max = radius * radius
    n_items = act.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for i in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                a = act[i]
                ax = ay = az = 0.0
                div = cx = cy = cz = 0.0
                o = same_start[i]
                if ptype[a] != GAS:
                    for k in range(same_count[i]):
                        pair_s[o + k] = 0.0
                    acc[i, 0] = acc[i, 1] = acc[i, 2] = 0.0
                    divv[i] = curlv[i] = vsig[i] = 0.0
                    for c in range(9):
                        grad[i, c] = 0.0
                    continue
                xa, ya, za = packed[a, _X], packed[a, _Y], packed[a, _Z]
                vxa, vya, vza = packed[a, _VX], packed[a, _VY], packed[a, _VZ]
                wrap = periodic[0] or periodic[1] or periodic[2]
                hinv_a = packed[a, _HINV]
                gnorm_a = packed[a, _GRADNORM]
                cs_a = packed[a, _CS]
                alpha_a = packed[a, _ALPHA]
                ombar_a = packed[a, _OMBAR]
                form_a, P_a, rhoinv_a = packed[a, _FORM], packed[a, _P], packed[a, _RHOINV]
                vs = cs_a
                g0 = g1 = g2 = g3 = g4 = g5 = g6 = g7 = g8 = 0.0
                for k in range(same_count[i]):
                    b = same_index[o + k]  # the neighbour's columns read in place (a row view per pair costs ~15 %)
                    dx = xa - packed[b, _X]
                    dy = ya - packed[b, _Y]
                    dz = za - packed[b, _Z]
                    if wrap:
                        dx = minimum_image(dx, length[0], periodic[0])
                        dy = minimum_image(dy, length[1], periodic[1])
                        dz = minimum_image(dz, length[2], periodic[2])
                    r2 = dx * dx + dy * dy + dz * dz
                    hinv_b = packed[b, _HINV]
                    if r2 * hinv_a * hinv_a >= r2max and r2 * hinv_b * hinv_b >= r2max:
                        pair_s[o + k] = 0.0
                        continue
                    r = math.sqrt(r2)
                    rinv = 1.0 / r
                    dW_a = gnorm_a * kernel_dshape(shape, r * hinv_a)
                    dW_b = packed[b, _GRADNORM] * kernel_dshape(shape, r * hinv_b)
                    dvx = vxa - packed[b, _VX]
                    dvy = vya - packed[b, _VY]
                    dvz = vza - packed[b, _VZ]
                    vdotr = (dvx * dx + dvy * dy + dvz * dz) * rinv
                    s, _ = pressure_pair(form, form_a, packed[b, _FORM], dW_a, dW_b, P_a, packed[b, _P], rhoinv_a,
                                         packed[b, _RHOINV], vdotr)
                    qa, qb = viscous_pair(vdotr, alpha_a, cs_a, packed[b, _ALPHA], packed[b, _CS], beta, ombar_a,
                                          packed[b, _OMBAR])
                    s = (s + (qa * dW_a + qb * dW_b)) * rinv
                    pair_s[o + k] = s
                    m_b = packed[b, _M]
                    ax -= m_b * s * dx
                    ay -= m_b * s * dy
                    az -= m_b * s * dz
                    div += m_b * vdotr * dW_a
                    vs = max(vs, signal_speed(cs_a, packed[b, _CS], vdotr, beta))
                    if not gradients:
                        continue
                    w = m_b * dW_a * rinv
                    cx += w * (dvy * dz - dvz * dy)
                    cy += w * (dvz * dx - dvx * dz)
                    cz += w * (dvx * dy - dvy * dx)
                    g0 += w * dvx * dx
                    g1 += w * dvx * dy
                    g2 += w * dvx * dz
                    g3 += w * dvy * dx
                    g4 += w * dvy * dy
                    g5 += w * dvy * dz
                    g6 += w * dvz * dx
                    g7 += w * dvz * dy
                    g8 += w * dvz * dz
                acc[i, 0] = ax
                acc[i, 1] = ay
                acc[i, 2] = az
                divv[i] = -ombar_a * div
                curlv[i] = ombar_a * math.sqrt(cx * cx + cy * cy + cz * cz)
                vsig[i] = vs
                grad[i, 0], grad[i, 1], grad[i, 2] = -ombar_a * g0, -ombar_a * g1, -ombar_a * g2
                grad[i, 3], grad[i, 4], grad[i, 5] = -ombar_a * g3, -ombar_a * g4, -ombar_a * g5
                grad[i, 6], grad[i, 7], grad[i, 8] = -ombar_a * g6, -ombar_a * g7, -ombar_a * g8
            chunk = next_chunk(counter)


# --------------------------------------------------------------------------- drag


@njit(parallel=True, cache=True)
def active_drag(act, ptype, table, cross_start, cross_index, cross_count, shape, ndim, length, periodic, c_const,
                projected, gas_kernel, tau, implicit, grad, gas_slope, pair_f, acc, tmin):
    """Two-fluid drag (thesis eqs. 3.18-3.19, :func:`dustygas.sph.dust.two_fluid_kernels.drag_pair`) on the
    active particles from their other-species rows; ``table`` holds one row per particle (gas and dust).

    ``pair_f[e]`` receives the acceleration of :math:`a` due to row entry ``e`` (the partner's share is
    :math:`-m_a/m_j` times it), ``acc`` the sum and ``tmin`` the smallest pair stopping time (per slot).
    ``gas_kernel``: the drag kernel uses only the gas particle's smoothing length (eq. 3.19 as written).
    ``implicit``: the pairwise exponential average over the pair step :math:`\\min(\\tau_a, \\tau_j)` (``tau`` per
    particle), with the non-drag accelerations in ``table``'s last three columns. ``gas_slope``: the
    relative velocity at the dust particle, the gas's velocity extrapolated with its gradient ``grad``
    (per particle; :func:`dustygas.sph.dust.two_fluid_kernels.drag_pair`).
    """
    n_items = act.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for i in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                a = act[i]
                side = KERNEL_AVERAGE
                if gas_kernel:
                    side = KERNEL_OWN if ptype[a] == GAS else KERNEL_OTHER
                ax = ay = az = 0.0
                tm = math.inf
                o = cross_start[i]
                for k in range(cross_count[i]):
                    j = cross_index[o + k]
                    dt_pair = min(tau[a], tau[j]) if implicit else 0.0
                    fx, fy, fz, _, tp = drag_pair(table, grad, table, grad, a, j, shape, ndim, length, periodic,
                                                  c_const, projected, gas_slope, False, dt_pair, False, side,
                                                  (1 if ptype[a] == GAS else 2) if gas_slope else 0)
                    pair_f[o + k, 0] = fx
                    pair_f[o + k, 1] = fy
                    pair_f[o + k, 2] = fz
                    ax += fx
                    ay += fy
                    az += fz
                    tm = min(tm, tp)
                acc[i, 0] = ax
                acc[i, 1] = ay
                acc[i, 2] = az
                tmin[i] = tm
            chunk = next_chunk(counter)


@njit(parallel=True, cache=True)
def gas_at_dust(act, ptype, pos, mass, h, rho, cs, cross_start, cross_index, cross_count, shape, norm, ndim, rho_out,
                cs_out):
    """Gas density and sound speed at the active dust particles from their gas neighbours, with the
    gas particles' kernels: :math:`\\rho_g = \\sum_a m_a W(r, h_a)` and the normalised interpolant
    :math:`c_s = \\sum_a (m_a/\\rho_a) c_{s,a} W / \\sum_a (m_a/\\rho_a) W` (zero without neighbours)."""
    n_items = act.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for i in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                d = act[i]
                rs = cw = ww = 0.0
                if ptype[d] != GAS:
                    for e in range(cross_start[i], cross_start[i] + cross_count[i]):
                        a = cross_index[e]
                        dx = pos[d, 0] - pos[a, 0]
                        dy = pos[d, 1] - pos[a, 1]
                        dz = pos[d, 2] - pos[a, 2]
                        hinv = 1.0 / h[a]
                        w = norm * hinv**ndim * kernel_shape(shape, math.sqrt(dx * dx + dy * dy + dz * dz) * hinv)[0]
                        rs += mass[a] * w
                        v = mass[a] / rho[a] * w
                        cw += v * cs[a]
                        ww += v
                rho_out[i] = rs
                cs_out[i] = cw / ww if ww > 0.0 else 0.0
            chunk = next_chunk(counter)


# --------------------------------------------------------------------------- kicks


@njit(cache=True)
def reverse_rows(act, slot, ptype, same_start, same_index, same_count, cross_start, cross_index, cross_count):
    """The inactive particles that appear in active rows (``passive``, ascending), and for each the
    entries it appears in: CSR ``ptr`` over ``(e_slot, e_pos, e_kind)`` (slot of the active particle,
    position in the same- or cross-row buffer, ``HYDRO`` or ``DRAG``), in slot order (a counting sort,
    serial: :math:`O(N)` plus the entries)."""
    n_all = slot.shape[0]
    fill = np.zeros(n_all, np.int64)  # entries per particle, then the next free position of its run
    total = 0
    for i in range(act.shape[0]):
        if ptype[act[i]] == GAS:
            for e in range(same_start[i], same_start[i] + same_count[i]):
                b = same_index[e]
                if slot[b] < 0:
                    fill[b] += 1
                    total += 1
        for e in range(cross_start[i], cross_start[i] + cross_count[i]):
            b = cross_index[e]
            if slot[b] < 0:
                fill[b] += 1
                total += 1
    n_passive = 0
    for b in range(n_all):
        n_passive += fill[b] > 0
    passive = np.empty(n_passive, np.int64)
    ptr = np.zeros(n_passive + 1, np.int64)
    u = 0
    run = 0
    for b in range(n_all):
        c = fill[b]
        if c > 0:
            passive[u] = b
            fill[b] = run
            run += c
            u += 1
            ptr[u] = run
    e_slot = np.empty(total, np.int64)
    e_pos = np.empty(total, np.int64)
    e_kind = np.empty(total, np.int8)
    for i in range(act.shape[0]):
        if ptype[act[i]] == GAS:
            for e in range(same_start[i], same_start[i] + same_count[i]):
                b = same_index[e]
                if slot[b] < 0:
                    f = fill[b]
                    e_slot[f], e_pos[f], e_kind[f] = i, e, HYDRO
                    fill[b] = f + 1
        for e in range(cross_start[i], cross_start[i] + cross_count[i]):
            b = cross_index[e]
            if slot[b] < 0:
                f = fill[b]
                e_slot[f], e_pos[f], e_kind[f] = i, e, DRAG
                fill[b] = f + 1
    return passive, ptr, e_slot, e_pos, e_kind


@njit(inline="always")
def _weights(a, b, tau_old, tau_new, last_tick, tick, tick_dt):
    """Closing and opening kick weights of the pair (a, b) (:func:`kick_active`)."""
    elapsed = (tick - max(last_tick[a], last_tick[b])) * tick_dt
    return elapsed - 0.5 * min(tau_old[a], tau_old[b]), 0.5 * min(tau_new[a], tau_new[b])


@njit(parallel=True, cache=True)
def kick_active(act, ptype, pos, mass, tau_old, tau_new, last_tick, tick, tick_dt, same_start, same_index, same_count,
                pair_s, cross_start, cross_index, cross_count, pair_f, acc_ext, ext_old, ext_new, last_ext, length,
                periodic, close, open_):
    """Closing and opening half kicks of the active particles.

    A pair was last evaluated (and opened with half its expected step, :math:`\\min(\\Delta t_a, \\Delta t_b)/2`
    with the steps ``tau_old`` then set) at the later of its particles' last activations ``last_tick``;
    it is closed with the time elapsed since then minus that opening weight -- half the pair step when
    the step ran its full length, less when a particle was woken early -- and opened again with half
    its new step (``tau_new``). The external acceleration ``acc_ext`` (per slot) is treated alike
    with the particle's own external-force steps (``ext_old``, ``ext_new``, ``last_ext``). Both
    particles of a pair get the same weights: momentum is conserved to round-off whatever the steps.
    """
    n_items = act.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for i in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                a = act[i]
                wc = (tick - last_ext[a]) * tick_dt - 0.5 * ext_old[a]
                wo = 0.5 * ext_new[a]
                c0 = wc * acc_ext[i, 0]
                c1 = wc * acc_ext[i, 1]
                c2 = wc * acc_ext[i, 2]
                o0 = wo * acc_ext[i, 0]
                o1 = wo * acc_ext[i, 1]
                o2 = wo * acc_ext[i, 2]
                if ptype[a] == GAS:
                    xa, ya, za = pos[a, 0], pos[a, 1], pos[a, 2]
                    for e in range(same_start[i], same_start[i] + same_count[i]):
                        s = pair_s[e]
                        if s == 0.0:
                            continue
                        b = same_index[e]
                        f = -mass[b] * s
                        fx = f * minimum_image(xa - pos[b, 0], length[0], periodic[0])
                        fy = f * minimum_image(ya - pos[b, 1], length[1], periodic[1])
                        fz = f * minimum_image(za - pos[b, 2], length[2], periodic[2])
                        wc, wo = _weights(a, b, tau_old, tau_new, last_tick, tick, tick_dt)
                        c0 += wc * fx
                        c1 += wc * fy
                        c2 += wc * fz
                        o0 += wo * fx
                        o1 += wo * fy
                        o2 += wo * fz
                for e in range(cross_start[i], cross_start[i] + cross_count[i]):
                    wc, wo = _weights(a, cross_index[e], tau_old, tau_new, last_tick, tick, tick_dt)
                    c0 += wc * pair_f[e, 0]
                    c1 += wc * pair_f[e, 1]
                    c2 += wc * pair_f[e, 2]
                    o0 += wo * pair_f[e, 0]
                    o1 += wo * pair_f[e, 1]
                    o2 += wo * pair_f[e, 2]
                close[i, 0], close[i, 1], close[i, 2] = c0, c1, c2
                open_[i, 0], open_[i, 1], open_[i, 2] = o0, o1, o2
            chunk = next_chunk(counter)


@njit(parallel=True, cache=True)
def kick_passive(passive, ptr, e_slot, e_pos, e_kind, act, pos, mass, tau_old, tau_new, last_tick, tick, tick_dt,
                 pair_s, pair_f, length, periodic, vel):
    """Kick every inactive neighbour by its share of the active pairs (closing and opening weights
    together, :func:`kick_active`), in place on ``vel``."""
    n_items = passive.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for u in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                b = passive[u]
                kx = ky = kz = 0.0
                for f in range(ptr[u], ptr[u + 1]):
                    a = act[e_slot[f]]
                    e = e_pos[f]
                    wc, wo = _weights(a, b, tau_old, tau_new, last_tick, tick, tick_dt)
                    w = wc + wo
                    if e_kind[f] == HYDRO:
                        c = w * mass[a] * pair_s[e]  # + m_a s r_ab / r_ab
                        kx += c * minimum_image(pos[a, 0] - pos[b, 0], length[0], periodic[0])
                        ky += c * minimum_image(pos[a, 1] - pos[b, 1], length[1], periodic[1])
                        kz += c * minimum_image(pos[a, 2] - pos[b, 2], length[2], periodic[2])
                    else:
                        c = -w * mass[a] / mass[b]
                        kx += c * pair_f[e, 0]
                        ky += c * pair_f[e, 1]
                        kz += c * pair_f[e, 2]
                vel[b, 0] += kx
                vel[b, 1] += ky
                vel[b, 2] += kz
            chunk = next_chunk(counter)


@njit(parallel=True, cache=True)
def kick_external(ext, acc_ext, ext_old, ext_new, last_ext, tick, tick_dt, vel):
    """Closing and opening kicks by the external acceleration ``acc_ext`` (per entry of ``ext``) of
    particles whose external-force step ends at ``tick`` but not their SPH step (:func:`kick_active`)."""
    for i in prange(ext.shape[0]):
        a = ext[i]
        w = (tick - last_ext[a]) * tick_dt - 0.5 * ext_old[a] + 0.5 * ext_new[a]
        vel[a, 0] += w * acc_ext[i, 0]
        vel[a, 1] += w * acc_ext[i, 1]
        vel[a, 2] += w * acc_ext[i, 2]


@njit(parallel=True, cache=True)
def limit_levels(act, ptype, level, same_start, same_index, same_count, slot, delta, wake):
    """Time-step limiter (Saitoh & Makino 2009): an active gas particle takes a level at least
    ``max(neighbour levels) - delta``; an inactive gas neighbour more than ``delta`` levels slower
    than an active one is marked in ``wake`` (to be activated at the next sub-step). In place."""
    new = np.empty(act.shape[0], np.int64)
    for i in prange(act.shape[0]):
        a = act[i]
        top = level[a]
        if ptype[a] == GAS:
            for e in range(same_start[i], same_start[i] + same_count[i]):
                top = max(top, level[same_index[e]])
        new[i] = max(level[a], top - delta)
    for i in prange(act.shape[0]):
        level[act[i]] = new[i]
    for i in prange(act.shape[0]):
        a = act[i]
        if ptype[a] != GAS:
            continue
        for e in range(same_start[i], same_start[i] + same_count[i]):
            b = same_index[e]
            if slot[b] < 0 and level[b] < new[i] - delta:
                wake[b] = True  # every writer writes True: the same result in any order
