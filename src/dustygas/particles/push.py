"""The particle loop and the two particle stages of a coupled VL2 step (compiled drivers; see
:mod:`dustygas.particles.coupling` for the scheme and its derivation).

:func:`particle_stage` with ``PREDICT`` (before the gas predictor)
    drift the particles by half a step, ``x^{n+1/2} = x^n + (Δt/2) v^n``; at the first step
    also gather the gas ``U^n`` at ``x^n`` and deposit the back-reaction of the drag at ``t^n``
    (later steps reuse the previous corrector's source, see :mod:`dustygas.particles.coupling`).
``CORRECT`` (before the gas corrector)
    gather the half-step gas ``U^{n+1/2}`` at ``x^{n+1/2}``, kick ``v^n -> v^{n+1}``
    (:mod:`dustygas.particles.drag`, forces at ``x^{n+1/2}``), deposit minus the drag impulse
    at ``x^{n+1/2}``, drift ``x^{n+1} = x^{n+1/2} + (Δt/2) v^{n+1}``, apply the boundaries,
    re-sort if needed, and return the largest speeds for the next time step.
:func:`deposit_density`
    the particles' mass density on the mesh (outputs, set-ups).

Each stage is one call into compiled code: a pass over the mesh for the gas fields, then two
parallel passes over chunks of slabs (:mod:`dustygas.particles.deposit`). Everything a particle
does happens in one loop, :func:`particle_chunk` -- stencil, gather, drag, deposit, drift,
boundaries -- with scalar helpers only (a compiled helper that writes into arrays costs a
reference-count update per call, more than the work of a particle). numba cannot cache a
parallel function called from another compiled function, so the ``prange`` loops are here.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit, prange

from ..physics.drag import epstein_stopping_time_scalar
from .boundaries import wrap_particle
from .deposit import filter_lines, gas_fields
from .drag import kick
from .interp import KERNEL_WIDTH, MAX_STENCIL, axis_weights, into_box
from .store import cell_key, counting_sort, slab_starts

__all__ = ["Forces", "Species", "FIXED", "EPSTEIN", "PREDICT", "CORRECT", "DENSITY", "particle_chunk",
           "particle_stage", "deposit_density"]

FIXED, EPSTEIN = 0, 1
#: what :func:`particle_chunk` does
PREDICT, CORRECT, DENSITY = 0, 1, 2


class Forces(NamedTuple):
    """Velocity-independent accelerations and Coriolis coefficients of the particles.

    ``a = (ax + tidal_x x, ay, az - gravity_z z)`` per unit mass, plus the Coriolis terms
    ``(coriolis_x v_y, -coriolis_y v_x)`` (see :mod:`dustygas.particles.drag`).
    """

    coriolis_x: float
    coriolis_y: float
    tidal_x: float
    gravity_z: float
    ax: float
    ay: float
    az: float


class Species(NamedTuple):
    """Per-species tables: drag law (:data:`FIXED` or :data:`EPSTEIN`), the stopping time of a
    fixed law, and for Epstein drag the product ``rho_grain s`` (code units) with the gas
    sound speed ``cs`` (thesis eq. 2.6 via :func:`~dustygas.physics.drag.epstein_stopping_time_scalar`)."""

    law: np.ndarray
    t_stop: np.ndarray
    grain: np.ndarray
    cs: float


@njit(cache=True, error_model="numpy")
def stopping_time(law: int, t_stop: float, grain: float, cs: float, rho: float) -> float:
    """Stopping time of a species with drag ``law`` in gas of density ``rho``."""
    if law == EPSTEIN:
        return epstein_stopping_time_scalar(grain, 1.0, rho, cs, 1.0)
    return t_stop


@njit(cache=True, error_model="numpy")
def _wrap_index(i: int, n: int) -> int:
    if i < 0:
        return i + n
    if i >= n:
        return i - n
    return i


@njit(cache=True, error_model="numpy")
def particle_chunk(stage, pos, vel, species, mass, fields, cells, order, sp, forces, method, feedback, dt, shift_a,
                   shift_b, ext, keys, axis, vmax, chunk, p0, p1) -> None:
    """Particles ``p0 .. p1-1`` through one stage (``PREDICT``, ``CORRECT`` or ``DENSITY``).

    ``shift_a``: shear offset at the time of the stencil (``t``, resp. ``t + dt/2``);
    ``shift_b``: at the time the drift ends (``t + dt/2``, resp. ``t + dt``). ``DENSITY``
    deposits ``m/V`` into ``ext[0]`` and moves nothing. ``CORRECT`` also writes the cell
    keys of the new positions and ``vmax[chunk]``, the largest ``|v_d|`` of the chunk.

    The stencil (see :mod:`dustygas.particles.interp`): along each active axis the cells of
    :func:`~dustygas.particles.interp.axis_weights`, wrapped periodically; a column reached
    through a radial boundary of a shear-periodic box takes the y weights of the image,
    ``y -/+ s_y`` for the inner/outer boundary, and the gas ``v_y`` there differs by
    ``+/- jump``.
    """
    index = np.empty(MAX_STENCIL, dtype=np.int64)
    weight = np.empty(MAX_STENCIL)
    side = np.empty(MAX_STENCIL)
    # per-axis stencils: x cells (wrapped), their weights and through which radial boundary
    # they were reached; z row offsets and weights; y cells and weights for the particle
    # (variant 0) and its inner (1) and outer (2) images
    xi = np.zeros(5, dtype=np.int64)
    xw = np.zeros(5)
    xs = np.zeros(5, dtype=np.int64)
    zi = np.zeros(5, dtype=np.int64)
    zw = np.zeros(5)
    yi = np.zeros((3, 5), dtype=np.int64)
    yw = np.zeros((3, 5))
    nx, ny, nz = cells.nx, cells.ny, cells.nz
    inv_dx, inv_dy, inv_dz = 1.0 / cells.dx, 1.0 / cells.dy, 1.0 / cells.dz
    width = KERNEL_WIDTH[order]
    wx = width if nx > 1 else 1
    wy = width if ny > 1 else 1
    wz = width if nz > 1 else 1
    xw[0] = zw[0] = 1.0  # inactive axes: one cell of weight 1
    yw[0, 0] = yw[1, 0] = yw[2, 0] = 1.0
    inv_vol = inv_dx * inv_dy * inv_dz
    h = 0.5 * dt
    need_stencil = stage != PREDICT or feedback
    ax = ay = az = 0.0
    for p in range(p0, p1):
        x, y, z = pos[0, p], pos[1, p], pos[2, p]
        vx, vy, vz = vel[0, p], vel[1, p], vel[2, p]
        m = 0
        if need_stencil:
            # ---- stencil: cells and weights (thesis eqs. 4.22 and 4.24 share them)
            images = False
            if nx > 1:
                i0, xw[0], xw[1], xw[2], xw[3], xw[4] = axis_weights((x - cells.x0) * inv_dx - 0.5, order)
                for a in range(wx):
                    i = i0 + a
                    sd = 0
                    if i < 0:
                        i += nx
                        sd = 1
                    elif i >= nx:
                        i -= nx
                        sd = 2
                    xi[a] = i
                    xs[a] = sd if cells.shear else 0
                    images = images or sd != 0
            if nz > 1:
                k0, zw[0], zw[1], zw[2], zw[3], zw[4] = axis_weights((z - cells.z0) * inv_dz - 0.5, order)
                for c in range(wz):
                    zi[c] = _wrap_index(k0 + c, nz) * ny
            if ny > 1:
                sy = (y - cells.y0) * inv_dy - 0.5
                j0, yw[0, 0], yw[0, 1], yw[0, 2], yw[0, 3], yw[0, 4] = axis_weights(sy, order)
                for b in range(wy):
                    yi[0, b] = _wrap_index(j0 + b, ny)
                if images and cells.shear:
                    for v in range(1, 3):
                        sv = into_box(sy - shift_a * inv_dy if v == 1 else sy + shift_a * inv_dy, ny)
                        j0, yw[v, 0], yw[v, 1], yw[v, 2], yw[v, 3], yw[v, 4] = axis_weights(sv, order)
                        for b in range(wy):
                            yi[v, b] = _wrap_index(j0 + b, ny)
            for c in range(wz):
                row = zi[c]
                wc = zw[c]
                for a in range(wx):
                    i = xi[a]
                    v = xs[a]
                    wca = wc * xw[a]
                    for b in range(wy):
                        index[m] = (row + yi[v, b]) * nx + i
                        weight[m] = wca * yw[v, b]
                        side[m] = 0.0 if v == 0 else (-1.0 if v == 1 else 1.0)
                        m += 1
        if stage == DENSITY:
            q = mass[p] * inv_vol
            for a in range(m):
                ext[0, index[a]] += weight[a] * q
            continue
        if need_stencil:
            # ---- gather (eq. 4.22)
            rho = ux = uy = uz = 0.0
            jump = cells.jump
            for a in range(m):
                cell = index[a]
                w = weight[a]
                rho += w * fields[0, cell]
                ux += w * fields[1, cell]
                uy += w * (fields[2, cell] - side[a] * jump)
                uz += w * fields[3, cell]
            s = species[p]
            ts = stopping_time(sp.law[s], sp.t_stop[s], sp.grain[s], sp.cs, rho)
            if stage == PREDICT:
                # back-reaction of the drag at t^n: m (v - u)/t_s per unit volume
                q = mass[p] * inv_vol / ts
                fx, fy, fz = q * (vx - ux), q * (vy - uy), q * (vz - uz)
            else:
                fx = forces.ax + forces.tidal_x * x
                fz = forces.az - forces.gravity_z * z
                vx, vy, vz, dvx, dvy, dvz = kick(method, vx, vy, vz, ux, uy, uz, fx, forces.ay, fz,
                                                 forces.coriolis_x, forces.coriolis_y, ts, dt)
                # the gas receives minus the drag impulse, per unit volume and time (eq. 4.24)
                q = -mass[p] * inv_vol / dt
                fx, fy, fz = q * dvx, q * dvy, q * dvz
            if feedback:
                for a in range(m):
                    cell = index[a]
                    w = weight[a]
                    ext[0, cell] += w * fx
                    ext[1, cell] += w * fy
                    ext[2, cell] += w * fz
        # ---- drift by half a step, boundaries
        if nx > 1:
            x += h * vx
        if ny > 1:
            y += h * vy
        if nz > 1:
            z += h * vz
        x, y, z, vy = wrap_particle(x, y, z, vy, cells, shift_b)
        pos[0, p] = x
        pos[1, p] = y
        pos[2, p] = z
        vel[0, p] = vx
        vel[1, p] = vy
        vel[2, p] = vz
        if stage == CORRECT:
            keys[p] = cell_key(x, y, z, cells, axis)
            ax = max(ax, abs(vx))
            ay = max(ay, abs(vy))
            az = max(az, abs(vz))
    if stage == CORRECT:
        vmax[chunk, 0] = ax
        vmax[chunk, 1] = ay
        vmax[chunk, 2] = az


@njit(cache=True, error_model="numpy")
def _speeds(vmax):
    vx = vy = vz = 0.0
    for c in range(vmax.shape[0]):
        vx = max(vx, vmax[c, 0])
        vy = max(vy, vmax[c, 1])
        vz = max(vz, vmax[c, 2])
    return vx, vy, vz


@njit(cache=True, error_model="numpy")
def _add_shear(fields, cells, sign, r0, r1) -> None:
    """``fields[2] += sign q Omega x`` for rows ``r0 .. r1-1`` (``q Omega = jump / L_x``)."""
    rate = sign * cells.jump / cells.lx
    nx = cells.nx
    for r in range(r0, r1):
        for i in range(nx):
            fields[2, r * nx + i] += rate * (cells.x0 + (i + 0.5) * cells.dx)


@njit(cache=True, error_model="numpy")
def _copy_rows(src, dst, nvar, ncell, c0, c1) -> None:
    """``dst[:nvar, c0:c1] = src[:nvar, c0:c1]``."""
    for v in range(nvar):
        for c in range(c0, c1):
            dst[v, c] = src[v, c]


@njit(inline="always")
def _filter_all_axes(field, nvar, work, cells, y_cells, ncell, ngroup) -> None:
    """Apply the grid-scale filter along every axis with more than one cell to the first ``nvar``
    rows of ``field`` ``(nvar, ncell)`` in place (``work`` holds each pass). Inlined into
    :func:`particle_stage`, so its loops are parallel regions of that kernel."""
    for a in range(3):
        n = cells.nx if a == 0 else (cells.ny if a == 1 else cells.nz)
        if n > 1:
            nlines = ncell // n
            nl = min(nlines, 64)
            for g in prange(nl):
                filter_lines(field, work, nvar, a, cells, y_cells, g * nlines // nl, (g + 1) * nlines // nl)
            for g in prange(ngroup):
                _copy_rows(work, field, nvar, ncell, g * ncell // ngroup, (g + 1) * ncell // ngroup)


@njit(cache=True, parallel=True, error_model="numpy")
def particle_stage(stage, pos, vel, species, pid, mass, u, cells, order, sp, forces, method, feedback, gas_az, dt,
                   shift_a, shift_b, fields, ext, starts, bounds, keys, axis, order_work, vmax, smooth, work):
    """One particle stage (module docstring): ``PREDICT`` before the gas predictor, ``CORRECT``
    before the gas corrector.

    Parameters
    ----------
    pos, vel, species, pid, mass
        The particle store's arrays (sorted by cell; ``starts`` holds the slab starts).
    u
        The gas state the stage reads, ``(4, NZ, NY, NX)`` (``U^n``, resp. ``U^{n+1/2}``;
        domain cells are read).
    cells, order, sp, forces, method
        :class:`~dustygas.particles.interp.Cells`, assignment-function code, :class:`Species`,
        :class:`Forces`, drag-integrator code.
    feedback
        Deposit the back-reaction into ``ext`` ``(3, ncell)``, initialised to zero and
        ``rho gas_az`` along z (a constant vertical acceleration of the gas). ``PREDICT``
        without feedback only drifts the particles and leaves ``ext`` alone.
    dt, shift_a, shift_b
        Step; shear offsets at the stencil time and at the end of the drift
        (``t, t + dt/2`` for ``PREDICT``; ``t + dt/2, t + dt`` for ``CORRECT``).
    fields
        ``(4, ncell)`` work array for the gas fields.
    starts, bounds
        Slab starts of the particles and slab bounds of the chunks
        (:func:`~dustygas.particles.deposit.chunk_bounds`).
    keys, axis, order_work, vmax
        Work arrays: cell keys ``(N,)``, the slab axis, ``(N,)`` int64, ``(nchunk, 3)``.
    smooth, work
        Apply the grid-scale filter ``F = 1 - δ⁴/16``
        (:func:`~dustygas.particles.deposit.filter_lines`) to the gathered gas fields and to
        the deposit, i.e. use the kernel ``F * W`` both ways; ``work`` is ``(4, ncell)``.

    Returns
    -------
    vx, vy, vz, resorted
        ``CORRECT``: the largest ``|v_d|`` of the new velocities and whether the particles
        were re-sorted (``starts`` is then updated); ``PREDICT``: zeros and False.
    """
    ncell = cells.nx * cells.ny * cells.nz
    y_cells = int(round(shift_a / cells.dy)) if cells.ny > 1 else 0
    ngroup = min(ncell, 64)
    if stage != PREDICT or feedback:  # a drift-only predictor needs neither
        rows = cells.ny * cells.nz
        nrow = min(rows, 64)
        for g in prange(nrow):
            gas_fields(u, cells, gas_az, fields, ext, True, g * rows // nrow, (g + 1) * rows // nrow)
        if smooth:  # the particles gather the filtered gas fields (kernel F*W)
            if cells.jump != 0.0:  # full v_y in a shearing box: filter the periodic v_y + q Omega x
                for g in prange(nrow):
                    _add_shear(fields, cells, 1.0, g * rows // nrow, (g + 1) * rows // nrow)
            _filter_all_axes(fields, 4, work, cells, y_cells, ncell, ngroup)
            if cells.jump != 0.0:
                for g in prange(nrow):
                    _add_shear(fields, cells, -1.0, g * rows // nrow, (g + 1) * rows // nrow)
    nchunk = bounds.shape[0] - 1
    npair = (nchunk + 1) // 2  # chunks 2c in the first pass, 2c + 1 in the second
    for colour in range(2):
        for c2 in prange(npair):
            c = 2 * c2 + colour
            if c < nchunk:
                particle_chunk(stage, pos, vel, species, mass, fields, cells, order, sp, forces, method, feedback, dt,
                               shift_a, shift_b, ext, keys, axis, vmax, c, starts[bounds[c]], starts[bounds[c + 1]])
    if smooth and feedback:  # ... and deposit through the same kernel F*W
        _filter_all_axes(ext, 3, work, cells, y_cells, ncell, ngroup)
    if stage != CORRECT:
        return 0.0, 0.0, 0.0, False
    vx, vy, vz = _speeds(vmax)
    resorted = counting_sort(keys, ncell, pos, vel, species, pid, mass, order_work)
    nslab = starts.shape[0] - 1
    slab_starts(keys, ncell // nslab, nslab, starts)
    return vx, vy, vz, resorted


def deposit_density(pos, mass, cells, order, y_shift) -> np.ndarray:
    """Mass density ``(ncell,)`` of the particles with the assignment function ``order``
    (serial; for outputs and set-ups)."""
    n = pos.shape[1]
    ext = np.zeros((3, cells.nx * cells.ny * cells.nz))
    dummy = np.zeros((1, 3))
    particle_chunk(DENSITY, pos, np.zeros((3, n)), np.zeros(n, dtype=np.int32), mass, np.zeros((4, 1)), cells, order,
                   Species(np.zeros(1, dtype=np.int64), np.ones(1), np.zeros(1), 1.0),
                   Forces(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), 0, False, 1.0, y_shift, y_shift, ext,
                   np.zeros(n, dtype=np.int64), 0, dummy, 0, 0, n)
    return ext[0]
