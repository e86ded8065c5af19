"""Corner-transport-upwind (CTU) integrator for the isothermal gas: one step, stable to Courant 1.

Colella (1990) for 2D, Saltzman (1994) for the 3D twelve-solve version; the form used by Athena
(Stone et al. 2008, ApJS 178, 137, §4; Gardiner & Stone 2008, JCP 227, 4123, §5), here for the
isothermal Euler equations with the shearing-box sources of Stone & Gardiner (2010, ApJS 189,
142). Unlike VL2 (Courant <= 1/ndim) the step is stable for ``max_d (|v_d| + c_s) dt/dx_d <= 1``
in 1D, 2D and 3D, so at Courant 0.8 it takes half the steps of VL2 at 0.4 in 2D.

One step ``U^n -> U^{n+1}``, in two stages (:func:`ctu_stage`):

*stage 0 (predictor)*
    1. ghost zones of ``U^n``;
    2. along each active axis a: reconstruct (PLM/PPM/PPM-CS in primitive variables),
       trace characteristically to time-centred face states (:mod:`dustygas.grid.trace`),
       add half a step of the momentum sources ``S(U^n) + S_ext`` to the velocities, solve the
       Riemann problems: the 1D fluxes ``F_a``. The pencils cover one ghost layer of the
       transverse axes too;
    3. (3D) the face states of axis a corrected by one transverse axis b,
       ``U - (dt/3dx_b) Delta_b F_b``, and their fluxes ``F_a^{|b}`` (six solves);
    4. the cell-centred half-step state ``U^{n+1/2} = U^n - (dt/2) sum_a Delta_a F_a / dx_a
       + (dt/2)(S(U^n) + S_ext)`` into slot 1: what the particles gather.

*stage 1 (corrector)*
    5. the face states of each axis corrected by the transverse flux differences,
       ``U - (dt/2dx_b) Delta_b F_b`` in 2D, ``U - (dt/2dx_b) Delta_b F_b^{|c} - (dt/2dx_c)
       Delta_c F_c^{|b}`` in 3D; their fluxes update ``U* = U^n - dt sum_a Delta_a F_a / dx_a``
       (slot 1);
    6. shear-periodic boxes: the radial-face fluxes averaged with their remapped images
       (:func:`~dustygas.grid.boundaries.correct_radial_items`);
    7. the momentum sources, Coriolis and tidal by Crank-Nicolson (Stone & Gardiner 2010,
       :func:`~dustygas.grid.ctu_pencils.final_rows`), ``dt S_ext`` explicitly;
    8. orbital advection (x-y boxes) remaps ``U^{n+1}`` (Masset 2000).

The external source ``S_ext`` of stage 0 shapes the predicted states and ``U^{n+1/2}``, that of
stage 1 enters ``U^{n+1}``: for the particle coupling (Bai & Stone 2010a, §2.3) stage 0 takes the
back-reaction of the previous corrector, the particles then gather ``U^{n+1/2}``, and stage 1
takes the time-centred back-reaction, exactly as for VL2 (:mod:`dustygas.grid.integrator`).

Memory: three conserved face-state and flux arrays per axis (``ql, qr`` and the 1D fluxes), plus
six corrected-flux arrays in 3D: 288 bytes per cell in 2D, 480 in 3D on top of the two state
slots (Athena's CTU keeps the same set of face arrays).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from .boundaries import SHEAR_PERIODIC, Boundaries, correct_radial_fluxes, fill_ghosts_threaded
from .budget import budget_offsets
from .ctu_pencils import final_rows, half_step_rows, predict_pencils, transverse_pencils, transverse_rows
from .diagnostics import combine_rates
from .mesh import Layout, Spacing
from .orbital_advection import remap_columns
from .shearing_box import SourceTerms
from .sweep import pencil_frame

__all__ = ["CTUWork", "ctu_work", "ctu_stage"]

# its Courant bound (1 in every dimension) is declared with the others in
# dustygas.grid.integrator.courant_limit


class CTUWork(NamedTuple):
    """Face arrays of one CTU step (module docstring), each ``(slots, 4, NTOT)``."""

    ql: np.ndarray  # conserved state left of each face, per axis
    qr: np.ndarray  # ... right of it
    fluxes: np.ndarray  # 0-2: 1D fluxes of x, y, z; 3 + 2a + m: flux of axis a corrected by its m-th other axis


def ctu_work(array_shape: tuple[int, int, int], ndim: int) -> CTUWork:
    """Allocate the face arrays for a block of ``array_shape = (NZ, NY, NX)`` cells."""
    ntot = int(np.prod(array_shape))
    nflux = 9 if ndim == 3 else 3
    return CTUWork(np.zeros((3, 4, ntot)), np.zeros((3, 4, ntot)), np.zeros((nflux, 4, ntot)))


@njit(cache=True, error_model="numpy")
def _others(axis):
    """The two other axes of ``axis`` in pencil order (the order of :func:`~dustygas.grid.sweep.pencil_frame`)."""
    if axis == 0:
        return 1, 2
    if axis == 1:
        return 0, 2
    return 0, 1


@njit(cache=True, error_model="numpy")
def _stride(axis, lay):
    NX = lay.nx + 2 * lay.gx
    NY = lay.ny + 2 * lay.gy
    return 1 if axis == 0 else (NX if axis == 1 else NX * NY)


@njit(cache=True, error_model="numpy")
def _spacing(axis, sp):
    return sp.dx if axis == 0 else (sp.dy if axis == 1 else sp.dz)


@njit(cache=True, error_model="numpy")
def _corrected_slot(axis, other):
    """Slot of the flux of ``axis`` corrected by ``other`` (3D)."""
    first, _ = _others(axis)
    return 3 + 2 * axis + (0 if other == first else 1)


@njit(cache=True, parallel=True, error_model="numpy")
def ctu_stage(states, stage, dt, t, layout, spacing, scheme, terms, bounds, xc, zc, oa_rate, ext, use_ext, wrap, ql,
              qr, fluxes, bflux, budget, nthreads) -> tuple[float, int]:
    """Stage ``stage`` (0 or 1) of the CTU step from ``t`` to ``t + dt`` (module docstring).

    ``states[0]`` is ``U^n`` (``U^{n+1}`` after stage 1), ``states[1]`` receives ``U^{n+1/2}``
    in stage 0 and serves as scratch in stage 1. ``ext`` ``(3, nz, ny, nx)``: the external
    momentum source of this stage if ``use_ext``; ``wrap``: per axis, whether a ghost cell takes
    the source of its periodic image (else of the nearest domain cell) in the predictor.
    ``budget`` (:mod:`dustygas.grid.budget`) accumulates the mass through the radial boundary
    per z plane and the y-momentum of the rotating-frame sources per row ``(k, j)``.

    Returns
    -------
    rate, bad
        Stage 1: the Courant rate of ``U^{n+1}`` and its first invalid cell; stage 0: 0, -1.
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    st = SourceTerms(*terms)
    bc = Boundaries(*bounds)
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    u = states[0]
    uh = states[1]
    active = (nx > 1, ny > 1, nz > 1)
    ndim = 0
    for a in range(3):
        if active[a]:
            ndim += 1
    shearing = bc.x_lo == SHEAR_PERIODIC
    nrow = ny * nz
    if stage == 0:
        fill_ghosts_threaded(u, t, lay, sp, bc, nthreads)
        for axis in range(3):
            if not active[axis]:
                continue
            n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb = pencil_frame(axis, lay, sp, 1, 1)
            npen = (na + 2 * ea) * (nb + 2 * eb)
            nchunk = min(npen, nthreads)
            for c in prange(nchunk):
                predict_pencils(u, axis, lay, sp, scheme, st, xc, zc, ext, use_ext, wrap, dt, ql[axis], qr[axis],
                                fluxes[axis], c * npen // nchunk, (c + 1) * npen // nchunk)
        if ndim == 3:  # fluxes of each axis corrected by one other axis (Saltzman 1994)
            tslot = serial_full(1, 0)
            tstride = serial_full(1, 0)
            tcoef = serial_full(1, 0.0)
            for axis in range(3):
                first, second = _others(axis)
                for m in range(2):
                    other = first if m == 0 else second
                    tslot[0] = other
                    tstride[0] = _stride(other, lay)
                    tcoef[0] = -dt / (3.0 * _spacing(other, sp))
                    # the corrected axis on the domain, the third axis with its ghost layer
                    ext_a = 0 if m == 0 else 1
                    ext_b = 1 - ext_a
                    n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb = pencil_frame(axis, lay, sp, ext_a, ext_b)
                    npen = (na + 2 * ea) * (nb + 2 * eb)
                    nchunk = min(npen, nthreads)
                    slot = 3 + 2 * axis + m
                    for c in prange(nchunk):
                        transverse_pencils(u, uh, axis, lay, sp, scheme, ql[axis], qr[axis], fluxes, tslot, tstride,
                                           tcoef, ext_a, ext_b, slot, False, dt, bflux, False,
                                           c * npen // nchunk, (c + 1) * npen // nchunk)
        nchunk = min(nrow, nthreads)
        for c in prange(nchunk):
            half_step_rows(u, uh, fluxes, lay, sp, st, xc, zc, ext, use_ext, dt, c * nrow // nchunk,
                           (c + 1) * nrow // nchunk)
        return 0.0, -1
    # ---- stage 1: corrected fluxes update U* = U^n - dt div F into slot 1
    nterm = ndim - 1
    tslot = serial_full(max(nterm, 1), 0)
    tstride = serial_full(max(nterm, 1), 0)
    tcoef = serial_full(max(nterm, 1), 0.0)
    none_slot = serial_full(0, 0)
    none_coef = serial_full(0, 0.0)
    first_update = True
    for axis in range(3):
        if not active[axis]:
            continue
        t_i = 0
        for other in range(3):
            if other == axis or not active[other]:
                continue
            # 2D: the 1D flux of `other`; 3D: the flux of `other` corrected by the third axis
            tslot[t_i] = other if ndim == 2 else _corrected_slot(other, 3 - axis - other)
            tstride[t_i] = _stride(other, lay)
            tcoef[t_i] = -0.5 * dt / _spacing(other, sp)
            t_i += 1
        if nterm > 0:  # the corrections, added in place to the face states (their last use)
            rows = (ny + (2 if axis == 1 else 0)) * (nz + (2 if axis == 2 else 0))
            nchunk = min(rows, nthreads)
            for c in prange(nchunk):
                transverse_rows(ql[axis], qr[axis], fluxes, axis, tslot[:nterm], tstride[:nterm], tcoef[:nterm], lay,
                                c * rows // nchunk, (c + 1) * rows // nchunk)
        n, g, stride, d, na, ga, sa, ea, nb, gb, sb, eb = pencil_frame(axis, lay, sp, 0, 0)
        npen = na * nb
        nchunk = min(npen, nthreads)
        store = shearing and axis == 0
        for c in prange(nchunk):
            transverse_pencils(u, uh, axis, lay, sp, scheme, ql[axis], qr[axis], fluxes, none_slot, none_slot,
                               none_coef, 0, 0, -1, first_update, dt, bflux, store, c * npen // nchunk,
                               (c + 1) * npen // nchunk)
        first_update = False
    t_half = t + 0.5 * dt
    if shearing:
        plane_flux = correct_radial_fluxes(uh, bflux, dt / sp.dx, t_half, lay, sp, bc, nthreads)
        for k in range(nz):
            budget[k] += dt * plane_flux[k] * sp.dy * sp.dz
    y_source = serial_full(nrow, 0.0)
    rates = serial_full(nrow, 0.0)
    bads = serial_full(nrow, -1)
    nchunk = min(nrow, nthreads)
    for c in prange(nchunk):
        final_rows(u, uh, lay, sp, st, xc, zc, ext, use_ext, dt, scheme[3], y_source, rates, bads,
                   c * nrow // nchunk, (c + 1) * nrow // nchunk)
    y0 = budget_offsets(nx, ny, nz)[1]
    for r in range(nrow):  # row r = k ny + j
        budget[y0 + r] += dt * y_source[r] * sp.dx * sp.dy * sp.dz
    if oa_rate != 0.0 and ny > 1:
        ncol = nx * nz
        col_rates = serial_full(ncol, 0.0)
        col_bads = serial_full(ncol, -1)
        nchunk = min(ncol, nthreads)
        for c in prange(nchunk):
            remap_columns(u, dt, oa_rate, lay, sp, xc, scheme[0], scheme[1], scheme[3], col_rates, col_bads,
                          c * ncol // nchunk, (c + 1) * ncol // nchunk)
        return combine_rates(col_rates, col_bads)
    return combine_rates(rates, bads)
