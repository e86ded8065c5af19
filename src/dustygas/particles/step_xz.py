"""The coupled step of a whole periodic x–z box in one compiled call.

:meth:`ParticleGridEngine.advance <dustygas.particles.coupling.ParticleGridEngine.advance>`
makes fourteen calls into compiled kernels a step from Python (the scheme of thesis §4.2,
eqs. 4.22-4.25; Bai & Stone 2010a). On a small box the Python around them is not small: in the
64² linA box a step takes about 1.3 ms on one thread and 0.73 ms on two, and the Python between
the calls cost 45-60 µs of it on either thread count, numba's dispatch of the calls (the
arguments' types checked and unboxed at every call) 5-25 µs more: the kernels in between leave
the interpreter's data out of the caches (the same Python repeated alone, its kernels replaced
by stubs, takes 10 µs), and it does not divide between threads.

:func:`coupled_step_xz` runs the whole scheme of :mod:`dustygas.particles.coupling` (drift and
exchange to the corrector and the end-of-step exchange) in one call for the case that most
small runs are: one block holding a whole 2D x–z box, periodic along x and z (no particle
leaves it, and the deposits read the periodic images in place), with the grid-scale filter, the
VL2 gas integrator, no gas terms and no mesh term, from the first step on (the first adds the
drag at ``t^n`` to the predictor, :func:`~dustygas.particles.push.explicit_drag_source`, where
later steps use the previous corrector's). It calls the same
kernels with the same arguments in the same order as the Python sequence, so the two give the
same state bit for bit (``tests/particles/test_step_xz.py``). The engine uses it where it
applies (:attr:`~dustygas.particles.coupling.ParticleGridEngine.compiled_step`); in the linA box
a step took 19-38 µs less on one thread and 23-37 µs less on two, whole runs 1-4 % less
(2026-12-06). The sequence is written twice, here and in the Python step: a change to one is a
change to the other, and the test compares them on every registered problem that takes the
compiled step. Until 2026-12-06 the first step went through the Python sequence: a new process
then loaded every kernel of the sequence from numba's cache at the first step and the compiled
step at the second, about 0.11 s each in the linA box (one load now).
"""

from __future__ import annotations

import numba
import numpy as np
from numba import njit

from .._numba_cache import load_for_arguments
from ..grid.integrator import advance_gas
from .boundaries import apply_boundaries
from .deposit import filter_field_xz, filter_pieces, pull_deposit
from .drag import step_coefficients
from .push import (cell_trajectories, copy_domain, dust_values, explicit_drag_source, kick, occupied_rows,
                   padded_rows)
from .store import sort_by_cell

__all__ = ["coupled_step_xz", "OneCallStep"]


@njit(cache=True, error_model="numpy")
def coupled_step_xz(h, back, pred_dt, half_shift, end_shift, n, nthreads, feedback, first, switches, particles,
                    layout, sorting, images, drag, fields, gas, gas_t):
    """One coupled step of a whole periodic x–z box.

    Parameters
    ----------
    h, back, pred_dt
        The step, the half step the dust deposit moves the particles back by (``h/2``) and the
        predictor's step (``h/2``), as the Python step computes them.
    half_shift, end_shift
        The shear offsets at ``t + h/2`` and ``t + h`` (the exchanges).
    n, nthreads, feedback
        The particle count, the chunks of the parallel loops and whether the dust drags the gas.
    first
        Whether the predictor takes the drag at ``t^n`` (the first step of a run with
        ``feedback``: no corrector has left its source yet).
    switches
        ``(True, False, 0, 1, 2)``: the flags and stage numbers the kernels take, as values that
        arrive at run time. Written here as constants, they would be typed as literals, and each
        kernel they reach would be compiled again for them (the gas stages and the deposit: 95 s
        on a first run).
    particles
        ``(pos, vel, species, pid, mass)``, the store's whole buffers.
    layout
        ``(layout, spacing, offsets, bounds, R, reach, dims, field_kinds, ghosts, inv_vol,
        shear_rate, leaving)``: the mesh and particle tables of the engine; ``dims`` ``(nx, ny,
        nz)``.
    sorting
        ``(keys, order_work, ptr, cell_start, fwork, iwork, order, wts)``.
    images
        ``(img_row_start, img_cell, img_w, img_src)`` (empty: the deposits wrap in place).
    drag
        ``(nspecies, species_table, frame_forces, coef, c_rho, c_mesh, mesh_field, cols,
        zero_cols, active, fixed_species, fixed_t_stop, gravity_z)``: ``coef`` receives the step
        coefficients of the species ``fixed_species`` of fixed stopping times ``fixed_t_stop``.
    fields
        ``(values, dep1, ghost1, source, traj, traj_out, gt, dep2, dep2_out, ghost2, g2,
        terms_rows, vmax_work, margin)``.
    gas
        The fixed arguments of :func:`~dustygas.grid.integrator.advance_gas`
        (:meth:`~dustygas.grid.engine.GridEngine.two_stage_arguments`, which ends with the states
        ``u_old`` and ``u_half`` the stages read).
    gas_t
        The gas time at the start of the step.

    Returns
    -------
    ``(bad, k_lo, k_hi, vmax, rate, bad_gas)``: ``bad >= 0`` names a particle with a non-finite
    state found by the sort (the step stops there), ``[k_lo, k_hi)`` the rows of the fields the
    particles needed, ``vmax`` the kick's largest speeds, ``rate`` and ``bad_gas`` the
    corrector's Courant rate and bad cell. No particle leaves a box periodic along both active
    axes, so the exchanges' counts are not returned.
    """
    yes, no, stage0, stage1, stage2 = switches
    pos, vel, species, pid, mass = particles
    lay, sp, off, bounds, R, reach, dims, kinds, ghosts, inv_vol, shear_rate, leaving = layout
    keys, order_work, ptr, cell_start, fwork, iwork, order, wts = sorting
    img_row_start, img_cell, img_w, img_src = images
    (nspecies, species_table, frame_forces, coef, c_rho, c_mesh, mesh_field, cols, zero_cols, active, fixed_species,
     fixed_t_stop, gravity_z) = drag
    values, dep1, ghost1, source, traj, traj_out, gt, dep2, dep2_out, ghost2, g2, terms_rows, vmax_work, margin = fields
    (states, ints, reals, gas_layout, gas_spacing, scheme, terms, gas_bounds, xc, zc, oa_rate, no_ext, bflux, zflux,
     budget, u_old, u_half) = gas
    # 1. drift, exchange, sort, weights (the images are read in place)
    apply_boundaries(pos, vel, n, lay, sp, bounds, half_shift, leaving, back)
    bad = sort_by_cell(pos, vel, species, pid, mass, n, lay, sp, off, keys, order_work, ptr, cell_start, fwork, iwork,
                       order, R, wts)
    if bad >= 0:
        return bad, 0, 0, (0.0, 0.0, 0.0), 0.0, -1
    # 2. the dust deposit of the local drag problem
    if feedback:
        dust_values(pos, vel, species, mass, n, inv_vol, yes, shear_rate, back, values, cols)
        pull_deposit(dep1, ghost1, lay, reach, R, cell_start, keys, wts, values, cols, img_row_start, img_cell, img_w,
                     img_src, nthreads, yes, yes)
        if first:
            explicit_drag_source(u_old, ghosts, sp, off, shear_rate, dep1, nspecies, species_table, source)
    ext = source if feedback else no_ext
    # 3. gas predictor
    advance_gas(states, ints, reals, stage0, stage1, no, h, gas_t, gas_layout, gas_spacing, scheme, terms, gas_bounds,
                xc, zc, oa_rate, ext, feedback, bflux, zflux, budget, nthreads)
    # 4. the trajectory field, filtered
    rows = occupied_rows(keys, n, dims[0], dims[1], dims[2], margin, kinds[2] == 0)
    if rows[1] > rows[0]:
        cell_trajectories(u_old, u_half, ghosts, source, pred_dt, h, lay, sp, off, dep1, nspecies, species_table,
                          frame_forces, mesh_field, shear_rate, feedback, traj, gt, c_rho, c_mesh, rows[0], rows[1])
    npiece = filter_pieces(nthreads)
    k_lo, k_hi = padded_rows(rows, gt[2], dims[2])
    filter_field_xz(traj, traj_out, k_lo, k_hi, npiece, gt[0], gt[2], kinds)
    # 5. particles: gather, update, drag source, second half drift
    for i in range(len(fixed_species)):
        step_coefficients(fixed_t_stop[i], gravity_z, h, coef[fixed_species[i]])
    vmax = kick(pos, vel, species, mass, n, keys, wts, R, reach, lay, sp, traj_out, gt, c_rho, c_mesh, species_table,
                coef, frame_forces, shear_rate, h, inv_vol, active, values, terms_rows, vmax_work, fwork)
    if feedback:
        pull_deposit(dep2, ghost2, lay, reach, R, cell_start, keys, wts, values[:, :3], zero_cols, img_row_start,
                     img_cell, img_w, img_src, nthreads, yes, yes)
        k_lo, k_hi = padded_rows(rows, g2[2], dims[2])
        filter_field_xz(dep2, dep2_out, k_lo, k_hi, npiece, g2[0], g2[2], kinds)
        copy_domain(dep2_out, ghost2, source, 1.0)
    # 6. gas corrector, then the exchange at t + h
    rate, bad_gas = advance_gas(states, ints, reals, stage1, stage2, yes, h, gas_t, gas_layout, gas_spacing, scheme,
                                terms, gas_bounds, xc, zc, oa_rate, ext, feedback, bflux, zflux, budget, nthreads)
    apply_boundaries(pos, vel, n, lay, sp, bounds, end_shift, leaving, 0.0)
    return -1, rows[0], rows[1], vmax, rate, bad_gas


class OneCallStep:
    """The engine's side of :func:`coupled_step_xz` (a mixin of the coupled engine).

    :attr:`compiled_step` says whether the steps run as one compiled call; the
    engine sets it where the case applies (module docstring), and setting it to False runs
    every step through the Python sequence (the same kernels, the same state).
    """

    compiled_step: bool = False

    def _one_call_case(self) -> bool:
        """Whether the engine is the case :func:`coupled_step_xz` runs (module docstring)."""
        return (self._whole_box and self._xz and self._wrap and not self.gas_terms and self._mesh_term is None
                and getattr(self.gas, "two_stage_arguments", lambda: None)() is not None)

    def _one_call_tables(self) -> tuple:
        """The arguments of :func:`coupled_step_xz` that change only when the particle arrays are
        reallocated (made again after :meth:`_allocate`), and the gas's, which never change."""
        layout = (self._lay_t, self._sp_t, self._off_t, self._pb_t, self._R, self._reach, self.geometry.shape,
                  self._field_kinds, self.mesh.ghosts, self._inv_vol, self._shear_rate, self._leaving)
        sorting = (self._keys, self._order_work, self._ptr, self._cell_start, self._fwork, self._iwork, self._order,
                   self._wts)
        images = (self._img_row_start, self._img_cell, self._img_w, self._img_src)
        fixed = self._fixed_t_stop
        drag = (self.nspecies, self.species_t, self._frame_forces_t, self._coef, self._c_rho, self._c_mesh,
                self._mesh_field, self._cols, self._zero_cols, self._active,
                np.array([s for s, _ in fixed], dtype=np.int64), np.array([ts for _, ts in fixed], dtype=np.float64),
                float(self.forces.gravity_z))
        fields = (self._values, self._dep1, self._ghost_arrays[(0, 0, 0)], self._source, self._traj, self._traj_out,
                  self._gt, self._dep2, self._dep2_out, self._ghost_arrays[self._g2], self._g2, self.terms_rows,
                  self._vmax_work, self._field_margin)
        return layout, sorting, images, drag, fields, self.gas.two_stage_arguments()  # the gas's arrays are made once

    def _one_call_arguments(self, h: float) -> tuple:
        """The arguments of :func:`coupled_step_xz` for a step ``h`` from the engine's state."""
        gas, p = self.gas, self.particles
        if p.capacity > self._capacity:
            self._allocate(p.capacity)
        if self._one_call_args is None:
            self._one_call_args = self._one_call_tables()
        layout, sorting, images, drag, fields, gas_arrays = self._one_call_args
        shift = self.geometry.shear_offset
        t = gas.t
        return (h, 0.5 * h, gas.stage_weight(0) * h, shift(t + 0.5 * h), shift(t + h), p.n, numba.get_num_threads(),
                self.feedback, self.feedback and not self._have_source, (True, False, 0, 1, 2), p.buffers(), layout,
                sorting, images, drag, fields, gas_arrays, t)

    def load_kernels(self) -> None:
        """Have numba load the compiled step from its cache (or compile it) now, for the types of
        this engine's arguments, instead of at the first step.

        The run loop calls it before its clock starts: the load (about 0.1 s for si-linA,
        2026-12-07) is start-up, the same on any thread count, and the loop's wall time and
        throughput are the steps'. Nothing is run and the state is not touched.
        """
        if self.compiled_step:
            load_for_arguments(coupled_step_xz, self._one_call_arguments(0.0))

    def _advance_one_call(self, dt: float) -> None:
        """:meth:`advance` through :func:`coupled_step_xz`."""
        self.sorts += 1
        bad, k_lo, k_hi, vmax, rate, bad_gas = coupled_step_xz(*self._one_call_arguments(dt))
        self._coef_dt = dt
        if bad >= 0:
            self._stop_nonfinite(bad)  # raises
        self._have_source = self._have_source or self.feedback
        self._images = 0
        self.field_rows = (k_lo, k_hi)
        self._vmax = vmax
        self.gas.finish_step(dt, rate, bad_gas)
