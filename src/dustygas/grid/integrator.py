"""Time integrators: VL2 (Stone & Gardiner 2009) and the SSP Runge-Kutta methods.

Every integrator is a short table of *stages*; stage ``s`` reads the state ``src``, fills its
ghost zones at the stage time, and writes

.. math::

    U_{dst} = a\\,U_{base} + b\\,U_{src} + f\\,\\Delta t\\,L(U_{src}), \\qquad
    L(U) = -\\nabla\\cdot F(U) + S(U) + S_{ext}

(:func:`~dustygas.grid.sweep.sweep`), then corrects the radial fluxes of a shear-periodic
box. ``U`` is slot 0 of the ``states`` array; slots 1, 2 are scratch states.

====== ================================================ ===================================
name    stages ``(src -> dst: a, b, f, time)``             reference
====== ================================================ ===================================
vl2     ``U -> U1: 1, 0, 1/2, t`` with *donor-cell* fluxes;  Stone & Gardiner (2009), §2
        ``U1 -> U: 1, 0, 1, t + dt/2``
rk2     ``U -> U1: 1, 0, 1, t``; ``U1 -> U: 1/2, 1/2, 1/2, t + dt``   Shu & Osher (1988)
rk3     ``U -> U1: 1, 0, 1, t``; ``U1 -> U2: 3/4, 1/4, 1/4, t + dt``;  Shu & Osher (1988)
        ``U2 -> U: 1/3, 2/3, 2/3, t + dt/2``
====== ================================================ ===================================

VL2 is second order and stable to Courant number 0.5 in 2D and 3D; it is the integrator of
Athena's particle-gas runs (Bai & Stone 2010a). RK3 is third order in time, so that PPM
reaches its spatial order on smooth problems; it costs three full stages per step.

Hook for the particles
----------------------
A drag back-reaction enters as the external momentum source ``S_ext`` of a stage, a
``(3, nz, ny, nx)`` array of momentum per unit volume and time on the domain cells, added with
the stage's weight ``f dt`` in the first sweep. For VL2 (Bai & Stone 2010a, §2.3):

* *predictor* (stage 0, to ``t + dt/2``): the particles gather the gas state ``U^n`` (slot 0,
  ghosts filled at ``t``) and deposit the back-reaction of their state at ``t``;
* *corrector* (stage 1, to ``t + dt``): the particles gather the half-step gas ``U^{n+1/2}``
  (slot 1, ghosts filled at ``t + dt/2``) -- the gas velocity at the half step -- and deposit
  the back-reaction of their time-centred drag.

:meth:`~dustygas.grid.engine.GridEngine.advance_stage` runs one stage with a given ``S_ext``
(the particle engine calls it twice per step, computing each source in between);
:meth:`~dustygas.grid.engine.GridEngine.advance_with_sources` calls a function at the start of
each stage with the stage index, the state it reads and the stage time, and uses the array it
returns as ``S_ext``. Orbital advection remaps the gas after the last stage; the budget
accumulators of the shearing box do not include ``S_ext``.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from .boundaries import (NEIGHBOUR, PERIODIC, SHEAR_PERIODIC, Boundaries, correct_radial_fluxes, correct_radial_items,
                         fill_band_ghosts, fill_ghosts_threaded)
from .budget import budget_offsets
from .diagnostics import cell_rate, combine_rates, fold_rate
from .mesh import Layout, Spacing
from .orbital_advection import remap_columns
from .reconstruct import DONOR
from .shearing_box import SourceTerms
from .sweep import pencil_count, sweep_pencils
from .sweep_columns import sweep_columns

__all__ = ["INTEGRATORS", "courant_limit", "integrator_tables", "advance_gas"]

#: name -> number of state slots it needs
INTEGRATORS = {"vl2": 2, "rk2": 2, "rk3": 3, "ctu": 2}

KEEP = -1  # reconstruction column: use the scheme's reconstruction



def courant_limit(ndim: int, integrator: str = "vl2") -> float:
    """Largest Courant number per axis the engine accepts in ``ndim`` dimensions.

    The step is ``Δt = C / max_d((|v_d| + c_s)/Δx_d)`` (thesis eqs. 2.12-2.13). In an unsplit
    update without transverse corrections (``vl2``, ``rk2``, ``rk3``) the Courant numbers of
    the axes add up for a wave along the diagonal, and the engine keeps their sum at most 1:
    ``C <= 1/ndim``, i.e. 1 in 1D, 1/2 in 2D, 1/3 in 3D (Stone & Gardiner 2009 quote 0.5 for
    their VL+CT in 3D; with this VL2, a diagonal sound wave in 3D grows without bound at
    ``C = 0.38``). Corner transport upwind (``ctu``: Colella 1990 in 2D, the twelve-solve
    version of Saltzman 1994 in 3D, :mod:`dustygas.grid.ctu`) brings the corner cells into
    the stencil and is stable for ``C <= 1`` in any dimension. The ``scheme.cfl`` parameter
    shows and checks the same bound (:data:`dustygas.grid.params.SCHEME`).

    >>> courant_limit(1), courant_limit(2), round(courant_limit(3), 6)
    (1.0, 0.5, 0.333333)
    >>> courant_limit(2, "ctu"), courant_limit(3, "ctu")
    (1.0, 1.0)
    """
    return 1.0 if integrator == "ctu" else 1.0 / ndim


def integrator_tables(name: str) -> tuple[np.ndarray, np.ndarray]:
    """Stage tables ``(ints, reals)`` of an integrator.

    ``ints[s] = (src, dst, base, reconstruction or -1)``,
    ``reals[s] = (a, b, f, time fraction, weight in the step's net update)``.

    >>> ints, reals = integrator_tables("rk3")
    >>> float(reals[:, 4].sum())
    1.0
    """
    if name == "vl2":
        ints = [(0, 1, 0, DONOR), (1, 0, 0, KEEP)]
        reals = [(1.0, 0.0, 0.5, 0.0, 0.0), (1.0, 0.0, 1.0, 0.5, 1.0)]
    elif name == "ctu":  # predictor to U^{n+1/2} (slot 1), then the update (dustygas.grid.ctu)
        ints = [(0, 1, 0, KEEP), (1, 0, 0, KEEP)]
        reals = [(1.0, 0.0, 0.5, 0.0, 0.0), (1.0, 0.0, 1.0, 0.5, 1.0)]
    elif name == "rk2":
        ints = [(0, 1, 0, KEEP), (1, 0, 0, KEEP)]
        reals = [(1.0, 0.0, 1.0, 0.0, 0.5), (0.5, 0.5, 0.5, 1.0, 0.5)]
    elif name == "rk3":
        ints = [(0, 1, 0, KEEP), (1, 2, 0, KEEP), (2, 0, 0, KEEP)]
        reals = [
            (1.0, 0.0, 1.0, 0.0, 1.0 / 6.0),
            (0.75, 0.25, 0.25, 1.0, 1.0 / 6.0),
            (1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.5, 2.0 / 3.0),
        ]
    else:
        raise ValueError(f"unknown integrator {name!r}")
    return np.array(ints, dtype=np.int64), np.array(reals, dtype=np.float64)


@njit(cache=True, parallel=True, error_model="numpy")
def advance_gas(states, ints, reals, s_lo, s_hi, finish, dt, t, layout, spacing, scheme, terms, bounds, xc, zc, oa_rate,
                ext, use_ext, bflux, zflux, budget, nthreads) -> tuple[float, int]:
    """Stages ``s_lo .. s_hi-1`` of the step from ``t`` to ``t + dt``, then (if ``finish``)
    orbital advection and the Courant rate of the new state.

    Each stage: ghost fill of its input at the stage time; one parallel sweep per active
    axis (the first adds the sources and ``ext`` if ``use_ext``); the shear-periodic flux
    correction; the budget. ``budget`` is the flat array of :mod:`dustygas.grid.budget`: per z
    plane the mass through the radial boundary, per row ``(k, j)`` the y-momentum given by the
    rotating-frame source terms (summed along the first sweep's pencil), per face cell the mass
    that left through the lower and upper z faces of a box that is not periodic in z (the mass
    fluxes of the boundary faces, stored by the z sweep in ``zflux``, ``(2, 4, ny, nx)``), each
    weighted with the stage's share of the step. ``oa_rate`` is ``q Omega`` under orbital advection
    (0: off). ``nthreads`` is the number of chunks the pencils are split into (results do not
    depend on it; numba cannot cache a function that asks for it itself): in 3D, slabs of z
    planes, each running every sweep of the stage in its planes (the z pencils in segments); in
    a 2D x-z box, bands of rows, each filling the ghosts it owns
    (:func:`~dustygas.grid.boundaries.fill_band_ghosts`), sweeping x and z and correcting the
    radial fluxes of its rows: one parallel region per stage; in other 2D boxes, one parallel
    region per sweep, each splitting its pencils.

    Returns
    -------
    rate, bad
        :func:`~dustygas.grid.diagnostics.row_signal_rate` over the new state (0, -1 if
        ``finish`` is False).
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    st = SourceTerms(*terms)
    bc = Boundaries(*bounds)
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    dvol = sp.dx * sp.dy * sp.dz
    shearing = bc.x_lo == SHEAR_PERIODIC
    remap = oa_rate != 0.0 and ny > 1
    open_z = nz > 1 and bc.z_lo != PERIODIC
    last_axis = 2 if nz > 1 else (1 if ny > 1 else 0)
    # the Courant rate of the new state: per pencil of the step's last sweep (or per column of
    # the orbital-advection remap), plus the radial edge cells after their flux correction
    first_axis = 0 if nx > 1 else (1 if ny > 1 else 2)
    # z slabs in 3D: each thread runs every sweep of its slab of z planes (the z pencils in
    # segments): one parallel region per stage, and the cells a thread writes are the same in every
    # sweep (and in the particle kernels, which split rows too). In 2D, where a z plane is one row,
    # an x-z box runs in bands of rows (below), other boxes one parallel region per sweep
    nslab = min(nz, nthreads) if nx > 1 and ny > 1 and nz > 1 else 1
    # in 2D the y or z sweep after the x sweep runs on blocks of columns (sweep_columns), each
    # thread over every column in a band of rows (segments along the sweep's axis): the same rows
    # as its x pencils, so that a thread writes the same memory pages in both sweeps. Split by
    # columns instead, two threads writing alternate parts of every row gained 1.18-1.38x in the
    # z sweep of a 64^2 box against 1.80 by rows (the same code; 1.84-1.88 when each thread wrote
    # an array of its own: the cost is in sharing the pages, not the cache lines). The pencil
    # kernel split by rows gained 1.58 there, by columns 1.60 (2026-12-05, benchmarks/RESULTS.md)
    n_last = nx if last_axis == 0 else (ny if last_axis == 1 else nz)
    nband = min(n_last, nthreads) if nslab == 1 and last_axis > 0 and nx > 1 else 1
    # a radial-vertical (x-z) box: one parallel region per stage, each thread filling the ghosts
    # of its band of rows (fill_band_ghosts), then sweeping x and z over it and correcting its
    # radial fluxes. Every sweep reads src and writes only its own cells of dst, so the bands need
    # no barrier between the sweeps (two regions and a serial ghost fill before, 2026-12-05)
    banded = nslab == 1 and ny == 1 and nx > 1 and nz > 1 and bc.x_lo != NEIGHBOUR and bc.x_hi != NEIGHBOUR
    nrate = nx * nz if remap else pencil_count(last_axis, lay) * max(nslab, nband)
    _, y0, zl0, zu0 = budget_offsets(nx, ny, nz)
    rates = serial_full(nrate, 0.0)  # (small arrays: serial, see dustygas.arrays)
    bads = serial_full(nrate, -1)
    for s in range(s_lo, s_hi):
        src = states[ints[s, 0]]
        dst = states[ints[s, 1]]
        base = states[ints[s, 2]]
        a = reals[s, 0]
        b = reals[s, 1]
        dt_stage = reals[s, 2] * dt
        t_stage = t + reals[s, 3] * dt
        weight = reals[s, 4]
        method = scheme[0] if ints[s, 3] < 0 else ints[s, 3]
        sch = (method, scheme[1], scheme[2], scheme[3])
        # 1. ghost zones of the input state (in parallel where there is enough work)
        banded_stage = banded and ints[s, 0] != ints[s, 1]
        if not banded_stage:
            fill_ghosts_threaded(src, t_stage, lay, sp, bc, nthreads)
        # 2. one sweep per active axis; the first one writes base, sources and ext
        y_source = serial_full(pencil_count(first_axis, lay), 0.0)
        last_stage = finish and s == s_hi - 1 and not remap
        correct = shearing and weight != 0.0
        plane_flux = serial_full(nz, 0.0)
        if banded_stage:
            for c in prange(nband):
                k0, k1 = c * nz // nband, (c + 1) * nz // nband
                fill_band_ghosts(src, t_stage, lay, sp, bc, k0, k1)
                sweep_pencils(src, dst, base, 0, True, a, b, dt_stage, lay, sp, sch, st, xc, zc, ext, use_ext, bflux,
                              shearing, y_source, rates, bads, False, shearing, k0, k1, 0, nx, 0, 1)
                sweep_columns(src, dst, 2, dt_stage, lay, sp, sch, zflux, open_z, rates, bads, last_stage, shearing,
                              0, nx, k0, k1, c, nband)
                if correct:
                    correct_radial_items(dst, bflux, dt_stage / sp.dx, t_stage, lay, sp, bc, 4 * k0, 4 * k1,
                                         plane_flux)
            first = False
        elif nslab > 1:
            for c in prange(nslab):
                k0, k1 = c * nz // nslab, (c + 1) * nz // nslab
                first = True
                for axis in range(3):
                    n_axis = nx if axis == 0 else (ny if axis == 1 else nz)
                    if n_axis == 1:
                        continue
                    store = (shearing and axis == 0) or (open_z and axis == 2)
                    faces = zflux if axis == 2 else bflux
                    want_rate = last_stage and axis == last_axis
                    if axis == 0:  # the x pencils of planes k0 .. k1-1 (the first sweep): p = j + ny k
                        sweep_pencils(src, dst, base, axis, first, a, b, dt_stage, lay, sp, sch, st, xc, zc, ext,
                                      use_ext, faces, store, y_source, rates, bads, want_rate, shearing,
                                      k0 * ny, k1 * ny, 0, n_axis, 0, 1)
                    elif axis == 1:  # the y pencils of planes k0 .. k1-1, in column blocks: p = i + nx k
                        sweep_columns(src, dst, axis, dt_stage, lay, sp, sch, faces, store, rates, bads, want_rate,
                                      shearing, k0 * nx, k1 * nx, 0, n_axis, 0, 1)
                    else:  # every z pencil in the slab's cells, in column blocks
                        sweep_columns(src, dst, axis, dt_stage, lay, sp, sch, faces, store, rates, bads, want_rate,
                                      shearing, 0, nx * ny, k0, k1, c, nslab)
                    first = False
        else:
            first = True
            for axis in range(3):
                n_axis = nx if axis == 0 else (ny if axis == 1 else nz)
                if n_axis == 1:
                    continue
                npen = pencil_count(axis, lay)
                nchunk = min(npen, nthreads)
                store = (shearing and axis == 0) or (open_z and axis == 2)
                faces = zflux if axis == 2 else bflux
                want_rate = last_stage and axis == last_axis
                if axis > 0 and nx > 1:  # blocks of columns, in bands of rows (above)
                    nb = min(n_axis, nthreads)
                    for c in prange(nb):
                        sweep_columns(src, dst, axis, dt_stage, lay, sp, sch, faces, store, rates, bads, want_rate,
                                      shearing, 0, npen, c * n_axis // nb, (c + 1) * n_axis // nb, c, nb)
                else:
                    for c in prange(nchunk):
                        sweep_pencils(src, dst, base, axis, first, a, b, dt_stage, lay, sp, sch, st, xc, zc, ext,
                                      use_ext, faces, store, y_source, rates, bads, want_rate, shearing,
                                      c * npen // nchunk, (c + 1) * npen // nchunk, 0, n_axis, 0, 1)
                first = False
        # 3. radial fluxes of a shearing box (not for a stage whose fluxes do not enter the
        #    step's net update, like the VL2 predictor: conservation needs only the others)
        if correct:
            if not banded_stage:
                plane_flux = correct_radial_fluxes(dst, bflux, dt_stage / sp.dx, t_stage, lay, sp, bc, nthreads)
            for k in range(nz):
                budget[k] += weight * dt * plane_flux[k] * sp.dy * sp.dz
        if open_z and weight != 0.0:  # mass flux F_z of the two faces: out is -F at the bottom, +F at the top
            for j in range(ny):
                for i in range(nx):
                    budget[zl0 + j * nx + i] += weight * dt * -zflux[0, 0, j, i] * sp.dx * sp.dy
                    budget[zu0 + j * nx + i] += weight * dt * zflux[1, 0, j, i] * sp.dx * sp.dy
        if weight != 0.0:  # pencil p of an x sweep is row (k, j); of a y sweep (no x), row (k, 0)
            row_step = 1 if first_axis == 0 else ny
            for p in range(y_source.shape[0]):
                budget[y0 + p * row_step] += weight * dt * y_source[p] * dvol
    if not finish:
        return 0.0, -1
    u = states[0]
    if remap:
        ncol = nx * nz
        nchunk = min(ncol, nthreads)
        for c in prange(nchunk):
            remap_columns(u, dt, oa_rate, lay, sp, xc, scheme[0], scheme[1], scheme[3], rates, bads, c * ncol // nchunk,
                          (c + 1) * ncol // nchunk)
        return combine_rates(rates, bads)
    rate, bad = combine_rates(rates, bads)
    if shearing:  # the radial edge cells, left out by the last sweep
        for k in range(nz):
            for j in range(ny):
                for i in (0, nx - 1):
                    kk, jj, ii = lay.gz + k, lay.gy + j, lay.gx + i
                    r = cell_rate(u[0, kk, jj, ii], u[1, kk, jj, ii], u[2, kk, jj, ii], u[3, kk, jj, ii], lay, sp,
                                  scheme[3])
                    rate, bad = fold_rate(r, (k * ny + j) * nx + i, rate, bad)
    return rate, bad
