"""Gas + particles: the coupled engine (thesis §4.2, eqs. 4.22-4.25; Bai & Stone 2010a).

Scheme
------
One step ``t^n -> t^{n+1} = t^n + h`` interleaves the particles with the two stages of the gas
integrator (VL2, Stone & Gardiner 2009: a predictor to ``t^n + h/2``, a corrector to
``t^{n+1}``):

1. drift ``x^{n+1/2} = x^n + (h/2) v^n``; the exchange step (particle boundaries,
   :mod:`dustygas.particles.boundaries`); sort into canonical order; weights; image records;
2. with back-reaction, deposit each species' density and momentum (positions ``x^{n+1/2}``,
   velocities ``v^n``);
3. gas predictor ``U^{n+1/2} = U^n + (h/2)[L(U^n) + S^{n-1/2} + S_terms]``, ``S^{n-1/2}``
   the drag source of the previous step's corrector; at the first step the drag at ``t^n``,
   ``S^0 = Σ_s (ρ_s V_s - ρ_s u^n)/T_s`` from the step-2 deposit (without it the first
   predictor lacks the drag, an O(h²) kick that starts an epicycle of the mixture: the NSH
   drift then oscillates about its equilibrium with amplitude 1e-5 .. 1e-4);
4. the local drag problem of every cell (:mod:`dustygas.particles.drag`): the gas velocity
   ``ũ(t)`` each species will see over the step, from ``U^n``, the gas's own acceleration
   ``(U^{n+1/2} - U^n)/(h/2)`` less the drag it received, and the dust deposit; through the
   grid-scale filter;
5. every particle gathers ``ũ`` and integrates its velocity exactly over the step with the
   held accelerations of its terms (:mod:`dustygas.particles.terms`; vertical gravity exactly,
   with the drag), deposits minus its drag impulse (through the filter), and drifts
   ``x^{n+1} = x^{n+1/2} + (h/2) v^{n+1}``; the exchange step;
6. gas corrector with the deposited source ``S^{n+1/2}`` (and the gas terms).

Momentum: the gas receives exactly minus the drag impulse ``Σ m_i Δv_drag,i`` of the
particles through weights that sum to one inside the domain, so the total momentum changes
only by the terms (the engine's history has their impulse) and the round-off of the sums.
Steady states: the NSH drift (thesis eq. 4.8) of uniform gas and a particle lattice is an
exact fixed point; a uniform dusty box relaxes at the exact rate for any step and stiffness.

Frames: particle velocities are stored like the gas's (full velocities, or relative to the
shear ``v + q Ω x ŷ`` under orbital advection). The drag (steps 2, 4, 5) is solved in the
velocities relative to the shear in either case, with the rotating frame of orbital advection
(:func:`~dustygas.particles.push.shear_frame_forces`): a particle drifting radially through
the shear keeps a constant ``v_y + q Ω x`` while its stored ``v_y`` changes in time, which a
step that holds the gas velocity and the forces fixed does not reproduce. The global pressure
gradient is either on the gas (``shearing_box.eta_vK``) or, opposite, on the particles (a
:class:`~dustygas.particles.terms.ConstantAcceleration`).

Time step: the gas's Courant step and the particles' ``cfl Δx_d / max|v_d|`` (a particle
moves less than a cell per step, which the sort-then-deposit order needs); the drag needs no
limit (``drag_cfl`` can impose one).

Accuracy at the benchmarked settings (64², one particle per cell; PPM-CS, HLLC, TSC through
the grid-scale filter): si-linA grows 0.36 % and si-linB 2.1 % too slowly (Youdin & Johansen
2007; Athena: 1.2 % and 17.7 %). What mattered for linB: the grid-scale filter (without it
-3.9 %: particles drifting through the mesh alias their noise onto grid-scale gas waves) and
the Colella & Sekora (2008) limiter (the classic CW84 limiter: -6.2 %).
"""

from __future__ import annotations

import math
from typing import Sequence

import numba
import numpy as np

from ..errors import SetupError, SimulationError
from ..grid.field_ghosts import fill_field_ghosts, field_ghost_kinds
from ..grid.mesh import KernelTuple, Spacing
from ..physics.drag import epstein_grain_size
from .boundaries import apply_boundaries, build_images, images_wrap, make_particle_boundaries
from .density import deposit_density
from .deposit import filter_field, filter_field_xz, filter_pieces, pull_deposit, sort_images
from .drag import DRAG_LAWS, EPSTEIN, FIXED, MAX_SPECIES, N_COEF, Species, step_coefficients
from .interp import KERNEL_REACH, KERNELS
from .push import (PARTICLE_CHUNKS, cell_trajectories, copy_domain, dust_values, explicit_drag_source, kick,
                   shear_frame_forces, trajectory_columns)
from .outputs import CoupledOutputs
from .blocks import OneBlock
from .step_xz import OneCallStep
from .store import ParticleStore, sort_by_cell
from .terms import MeshAcceleration, RotatingFrame, add_row_impulse, force_table

__all__ = ["ParticleGridEngine", "DRAG_LAWS", "GAS_INTEGRATORS", "deposit_density"]

#: gas integrators the coupling supports: its drag is predicted and corrected with the two
#: stages of VL2 or CTU, both of which give U^{n+1/2} (Bai & Stone 2010a, §2.3); the
#: ``scheme.integrator`` of the particle problems offers these
GAS_INTEGRATORS = ("vl2", "ctu")


def add_lost(lost: np.ndarray, flags: np.ndarray, mass: np.ndarray, vel: np.ndarray, faces) -> None:
    """Add to ``lost[face]`` the mass and momentum ``[m, m v_x, m v_y, m v_z]`` of the particles
    leaving through each of ``faces`` (``flags[p] == face + 1``), each sum correctly rounded
    (:func:`math.fsum`): it does not depend on the particles' order, so a block holding the
    same leaving particles adds the same numbers (:mod:`dustygas.parallel`)."""
    n = flags.shape[0]
    for face in faces:
        sel = flags == face + 1
        if np.any(sel):
            m = mass[:n][sel]
            lost[face, 0] += math.fsum(m)
            for a in range(3):
                lost[face, 1 + a] += math.fsum(vel[a, :n][sel] * m)


class ParticleGridEngine(CoupledOutputs, OneBlock, OneCallStep):
    """A two-stage gas engine (VL2) with Lagrangian dust particles (module docstring).

    Parameters
    ----------
    gas
        The gas engine holding its initial state; its integrator must be ``vl2`` or ``ctu``.
    particles
        The particles (positions inside the box; velocities in the gas's frame).
    t_stop
        Stopping time of each species (code units). For ``"epstein"`` species it is the value
        at gas density ``rho_ref``; the local one is ``t_stop rho_ref / rho_g`` (thesis eq. 2.6).
    drag_law
        ``"fixed"`` or ``"epstein"`` per species (one string for all).
    kernel
        Assignment function ``"ngp"``, ``"cic"``, ``"tsc"``, ``"tsc-c"`` (gather and deposit alike).
    feedback
        Apply the back-reaction of the drag on the gas.
    particle_terms
        Accelerations of the particles (:mod:`dustygas.particles.terms`); default: the rotating
        frame of the gas engine (none without rotation).
    gas_terms
        Momentum sources on the gas besides the drag and the grid engine's own terms.
    boundaries
        Particle boundary kind per axis (``periodic``, ``shear-periodic``, ``outflow``,
        ``reflecting``); default: the gas's periodic kinds, ``outflow`` where the gas is open.
    boundary_keys
        Names of the configuration entries of ``boundaries``, for error messages.
    cfl
        Particle Courant number (default: the gas's); at most 1.
    drag_cfl
        If > 0, also limit ``Δt`` to ``drag_cfl`` times the smallest fixed stopping time.
    mode
        Integer mode numbers ``(m_x, m_y, m_z)`` whose Fourier amplitudes go into the history
        (``mode_<field>_re/_im`` for the fields of :data:`~dustygas.particles.diagnostics.MODE_FIELDS`).
    rho_ref
        Reference gas density of the Epstein law.
    smooth
        Gather and deposit through ``F * W``: the assignment function followed by the
        grid-scale filter ``F = 1 - δ⁴/16`` (:func:`~dustygas.particles.deposit.filter_field`).
    species_names
        Labels of the species for the history (default ``0, 1, ...``).
    """

    work_label = "zone-cycles"
    # the records the kernels take, each with its plain tuple (``_lay_t`` ...: dustygas.grid.mesh)
    _lay, _sp, _off, _pb = KernelTuple(), KernelTuple(), KernelTuple(), KernelTuple()
    species, _frame_forces = KernelTuple(), KernelTuple()

    def __init__(
        self,
        gas,
        particles: ParticleStore,
        t_stop: Sequence[float],
        drag_law: str | Sequence[str] = "fixed",
        kernel: str = "tsc",
        feedback: bool = True,
        particle_terms: Sequence | None = None,
        gas_terms: Sequence = (),
        boundaries: Sequence[str] | None = None,
        boundary_keys: tuple[str, str, str] = ("particles.boundary_x", "particles.boundary_y", "particles.boundary_z"),
        cfl: float | None = None,
        drag_cfl: float = 0.0,
        mode: Sequence[int] | None = None,
        rho_ref: float = 1.0,
        smooth: bool = True,
    ):
        if getattr(gas, "distributed", False):
            raise SetupError("a ParticleGridEngine takes the whole box's gas: decompose the coupled engine with "
                             "dustygas.parallel.coupled.distribute")
        if gas.scheme_names["integrator"] not in GAS_INTEGRATORS:
            raise SetupError(f"particles need the {' or '.join(GAS_INTEGRATORS)} gas integrator, "
                             f"not {gas.scheme_names['integrator']}")
        if kernel not in KERNELS:
            raise SetupError(f"particle kernel '{kernel}' unknown: choose one of {', '.join(KERNELS)}")
        t_stop = np.atleast_1d(np.asarray(t_stop, dtype=np.float64))
        if len(t_stop) > MAX_SPECIES:
            raise SetupError(f"{len(t_stop)} particle species: at most {MAX_SPECIES}")
        laws = [drag_law] * len(t_stop) if isinstance(drag_law, str) else list(drag_law)
        if len(laws) != len(t_stop) or any(law not in DRAG_LAWS for law in laws):
            raise SetupError(f"drag_law must be one of {', '.join(DRAG_LAWS)} per species ({len(t_stop)})")
        if not np.all(t_stop > 0) or not np.all(np.isfinite(t_stop)):
            raise SetupError("stopping times must be positive and finite")
        if particles.n and (particles.species.min() < 0 or particles.species.max() >= len(t_stop)):
            raise SetupError(f"particle species must be in 0 .. {len(t_stop) - 1}")
        #: the arguments this engine was built with (a decomposed run builds one per block from them)
        self.options = dict(t_stop=t_stop.copy(), drag_law=drag_law, kernel=kernel, feedback=feedback,
                            particle_terms=particle_terms, gas_terms=gas_terms, boundaries=boundaries,
                            boundary_keys=boundary_keys, cfl=cfl, drag_cfl=drag_cfl, mode=mode, rho_ref=rho_ref,
                            smooth=smooth)
        cfl = gas.cfl if cfl is None else float(cfl)
        if not 0 < cfl <= 1:
            raise SetupError(f"particle cfl={cfl}: must be in (0, 1] (a particle moves less than a cell per step)")
        geom = gas.geometry
        self.gas = gas
        self.particles = particles
        self.geometry = geom
        self.mesh = gas.mesh
        self.kernel = kernel
        self.feedback = bool(feedback)
        self.smooth = bool(smooth)
        self.cfl = cfl
        self.drag_cfl = float(drag_cfl)
        active = tuple(n > 1 for n in geom.shape)
        self._active = np.array(active, dtype=np.bool_)
        relative = geom.velocity_relative_to_shear
        if particle_terms is None:
            particle_terms = [RotatingFrame(geom.omega, geom.q, relative)] if geom.omega != 0.0 else []
        self.particle_terms = list(particle_terms)
        self.gas_terms = list(gas_terms)
        self.forces = force_table(self.particle_terms)
        if self.forces.gravity_z > 0 and not active[2]:
            raise SetupError("vertical gravity on the particles needs an active z axis (nz > 1)")
        self._mesh_term = next((t for t in self.particle_terms if isinstance(t, MeshAcceleration)), None)
        #: z rows [k_lo, k_hi) of the fields the particles gather this step (a mesh term may
        #: restrict its work to them)
        self.field_rows = (0, gas.geometry.shape[2])
        # species table
        codes = np.array([DRAG_LAWS[law] for law in laws], dtype=np.int64)
        grain = np.where(codes == EPSTEIN, epstein_grain_size(t_stop, 1.0, rho_ref, gas.cs, 1.0), 0.0)
        self.species = Species(codes, t_stop.copy(), np.ascontiguousarray(grain, dtype=np.float64), float(gas.cs))
        #: (species, stopping time) of each species with a fixed stopping time, and the cell size of each
        #: active axis: the per-step Python of the drag coefficients and the step limit reads these
        self._fixed_t_stop = tuple((s, float(t_stop[s])) for s in range(len(t_stop)) if codes[s] == FIXED)
        self._active_dx = tuple((a, float(geom.dx[a])) for a in range(3) if geom.shape[a] > 1)
        self.laws = laws
        self.nspecies = len(t_stop)
        # boundaries: the particles' own kinds, checked against the gas's
        if boundaries is None:
            boundaries = tuple(k if k in ("periodic", "shear-periodic") else "outflow" for k in geom.boundaries)
        q_omega_lx = geom.q * geom.omega * geom.box[0] if geom.shear_periodic else 0.0
        self.boundary_kinds = tuple(boundaries)
        self._pb = make_particle_boundaries(tuple(boundaries), geom.boundaries, active, q_omega_lx,
                                            0.0 if relative else geom.shear_velocity_jump, boundary_keys)
        # full velocities in a rotating box: the fields the particles gather hold u_y + q Omega x
        self._shear_rate = geom.q * geom.omega if not relative and geom.omega != 0.0 else 0.0
        #: the particle terms for the velocity relative to the shear, in which the drag is solved
        self._frame_forces = shear_frame_forces(self.forces, self._shear_rate)
        self._field_kinds = field_ghost_kinds(geom.boundaries, active)
        m = gas.mesh
        # the spacing of the whole mesh (origin, box) and the block's offsets: particle cells and
        # weights, cell centres and the periodic images are those of the whole box
        self._lay, self._sp, self._off = m.layout, Spacing(*m.dx, *m.origin, *m.size), m.offsets
        self._remap = gas.remap_codes
        # kernel, reach and field arrays
        self._order = KERNELS[kernel]
        R = KERNEL_REACH[self._order]
        self._R = R
        #: the rows beyond the particles' whose fields a step needs: the deposit reaches R rows beyond a
        #: particle's and the filter spreads it two more, which the z pass filters only 2 rows inside
        #: the range: R + 4 (R + 2 loses momentum near a thin layer)
        self._field_margin = R + (4 if self.smooth else 0)
        self._reach = np.array([R if a else 0 for a in active], dtype=np.int64)
        extra = 2 if self.smooth else 0
        self._gt = tuple(int((R + extra) if a else 0) for a in active)
        self._g2 = tuple(int(extra if a else 0) for a in active)
        nx, ny, nz = geom.shape
        self._ncell = nx * ny * nz
        self._inv_vol = 1.0 / m.cell_volume
        ntraj, self._c_rho, self._c_mesh = trajectory_columns(self.nspecies, bool(np.any(codes == EPSTEIN)),
                                                              self._mesh_term is not None)
        self._coef = np.zeros((self.nspecies, N_COEF))
        self._coef_dt = -1.0
        gx, gy, gz = self._gt
        self._traj = np.zeros((nz + 2 * gz, ny + 2 * gy, nx + 2 * gx, ntraj))
        gx2, gy2, gz2 = self._g2
        self._dep2 = np.zeros((nz + 2 * gz2, ny + 2 * gy2, nx + 2 * gx2, 3))
        #: a 2D x-z box filters out of place, into a second array per field (one parallel region)
        self._xz = self.smooth and active == (True, False, True)
        self._traj_out = np.zeros_like(self._traj) if self._xz else self._traj
        self._dep2_out = np.zeros_like(self._dep2) if self._xz else self._dep2
        #: the ghost widths of the deposit targets as the int64 arrays the kernels take
        self._ghost_arrays = {g: np.array(g, dtype=np.int64) for g in ((0, 0, 0), self._g2)}
        self._dep1 = np.zeros((nz, ny, nx, 4 * self.nspecies))
        self._rho_p = np.zeros((nz, ny, nx, self.nspecies))
        self._mesh_field = np.zeros((3, nz, ny, nx))
        #: the back-reaction source: written by the corrector, used by the next predictor
        self._source = np.zeros((3, nz, ny, nx))
        self._ext = np.zeros((3, nz, ny, nx))
        self._have_source = False
        self._cell_start = np.zeros(self._ncell + 1, dtype=np.int64)
        self._ptr = np.zeros(self._ncell, dtype=np.int64)
        nyr, nzr = ny + 2 * self._reach[1], nz + 2 * self._reach[2]
        self._img_row_start = np.zeros(nyr * nzr + 1, dtype=np.int64)
        self._img_capacity = 0
        #: the deposits read the periodic images in place (no image records: :func:`images_wrap`);
        #: then the record arrays stay empty (a large periodic box would hold a record per fourth particle)
        self._wrap = self._wrap_images()
        self._img_src, self._img_cell = np.zeros(0, dtype=np.int64), np.zeros((0, 3), dtype=np.int64)
        self._img_w, self._img_dvy = np.zeros((0, 3, 2 * R + 1)), np.zeros(0)
        self._vmax_work = np.zeros((PARTICLE_CHUNKS, 3))
        #: time integrals: [mass, p_x, p_y, p_z] that left through each face; per row of cells
        #: ``(k, j)`` (row ``k ny + j``), the momentum the particle terms gave its particles and
        #: the momentum the gas terms gave its gas (each row summed in a fixed order, so that
        #: the rows do not depend on the block that holds them: :attr:`terms_impulse`)
        self.lost = np.zeros((6, 4))
        self.terms_rows = np.zeros((nz * ny, 3))
        self.gas_terms_rows = np.zeros((nz * ny, 3))
        self._allocate(max(particles.capacity, 1))
        self._images = 0
        #: particles of neighbouring blocks held after the store's own (halo sources; 0 in one block)
        self._n_halo = 0
        #: sorts so far (the outputs sort too: a decomposed run repeats them on its blocks)
        self.sorts = 0
        #: whether the steps after the first run as one compiled call (:mod:`dustygas.particles.step_xz`)
        self.compiled_step = self._one_call_case()
        self.mode = None if mode is None else tuple(int(x) for x in mode)
        self._mode_setup()
        self._check_inside()
        self._vmax = np.max(np.abs(particles.vel), axis=1) if particles.n else np.zeros(3)
        self.work_units = self._ncell
        for term in self.particle_terms:
            if hasattr(term, "bind"):
                term.bind(self)

    # ------------------------------------------------------------------ set-up helpers
    def _allocate(self, capacity: int) -> None:
        W = 2 * self._R + 1
        self._keys = np.zeros(capacity, dtype=np.int64)
        self._order_work = np.zeros(capacity, dtype=np.int64)
        self._fwork = np.zeros((7, capacity))
        self._iwork = np.zeros((3, capacity), dtype=np.int64)
        self._wts = np.zeros((capacity, 3, W))
        self._values = np.zeros((capacity, 4))
        self._cols = np.zeros(capacity, dtype=np.int64)
        self._zero_cols = np.zeros(capacity, dtype=np.int64)
        self._leaving = np.zeros(capacity, dtype=np.int64)
        self._capacity = capacity
        self._one_call_args = None  # the compiled step's argument tables (step_xz) hold the old arrays
        if not self._wrap:
            self._grow_images(max(16, capacity // 4))

    def _grow_images(self, m: int) -> None:
        """Room for ``m`` image records (the present ones kept)."""
        if m <= self._img_capacity:
            return
        W = 2 * self._R + 1
        m = max(m, 2 * self._img_capacity)
        old = (self._img_src, self._img_cell, self._img_w, self._img_dvy)
        self._img_src = np.zeros(m, dtype=np.int64)
        self._img_cell = np.zeros((m, 3), dtype=np.int64)
        self._img_w = np.zeros((m, 3, W))
        self._img_dvy = np.zeros(m)
        for new, was in zip((self._img_src, self._img_cell, self._img_w, self._img_dvy), old):
            new[:was.shape[0]] = was
        self._img_capacity = m

    def _check_inside(self) -> None:
        """Every particle inside the box (set-up and restart)."""
        pos = self.particles.pos
        for axis in range(3):
            if self.geometry.shape[axis] == 1 or not pos.shape[1]:
                continue
            lo, length = self.mesh.origin[axis], self.geometry.box[axis]
            if pos[axis].min() < lo or pos[axis].max() >= lo + length:
                raise SetupError(f"particle positions along {'xyz'[axis]} must lie in [{lo:g}, {lo + length:g})")

    # ------------------------------------------------------------------ budgets
    @property
    def terms_impulse(self) -> np.ndarray:
        """The momentum ``(3,)`` the particle terms gave the particles: the correctly rounded
        sum of :attr:`terms_rows` (:func:`math.fsum`, which does not depend on their order)."""
        return np.array([math.fsum(col) for col in self.terms_rows.T])

    @property
    def gas_terms_impulse(self) -> np.ndarray:
        """The momentum ``(3,)`` the gas terms gave the gas (the sum of :attr:`gas_terms_rows`)."""
        return np.array([math.fsum(col) for col in self.gas_terms_rows.T])

    # ------------------------------------------------------------------ time
    @property
    def t(self) -> float:
        return self.gas.t

    @t.setter
    def t(self, value: float) -> None:
        self.gas.t = value

    @property
    def cycle(self) -> int:
        return self.gas.cycle

    @cycle.setter
    def cycle(self, value: int) -> None:
        self.gas.cycle = value

    def timestep(self) -> float:
        """Smallest of the gas Courant step, the particle Courant step and the drag limit."""
        return self._limit_step(self.gas.timestep(), self._vmax)

    def _limit_step(self, dt: float, vmax) -> float:
        """The gas step ``dt`` limited by the particles (largest speeds ``vmax`` per axis) and the drag."""
        rate = 0.0
        for a, d in self._active_dx:
            rate = max(rate, vmax[a] / d)
        if rate > 0:
            dt = min(dt, self.cfl / rate)
        if self.drag_cfl > 0 and self._fixed_t_stop:
            dt = min(dt, self.drag_cfl * min(ts for _, ts in self._fixed_t_stop))
        return dt

    # ------------------------------------------------------------------ the passes
    def _exchange(self, t: float, half_dt: float = 0.0) -> None:
        """The exchange step at time ``t`` (particle boundaries; removes outflowing particles),
        after a drift by ``half_dt`` if not 0."""
        p = self.particles
        pos, vel, species, pid, mass = p.buffers()
        shift = self.geometry.shear_offset(t)
        count = apply_boundaries(pos, vel, p.n, self._lay_t, self._sp_t, self._pb_t, shift, self._leaving, half_dt)
        if count:
            self._remove_leaving()

    def _remove_leaving(self) -> None:
        """Remove the particles the last exchange flagged as leaving, adding what they carry to :attr:`lost`."""
        p = self.particles
        flags = self._leaving[:p.n]
        add_lost(self.lost, flags, p.mass, p.vel, range(6))
        p.remove(flags == 0)

    def _prepare(self, t: float) -> None:
        """Sort, weights and image records of the particles as they are (positions at ``t``)."""
        p = self.particles
        self.sorts += 1
        if p.capacity > self._capacity:
            self._allocate(p.capacity)
        pos, vel, species, pid, mass = p.buffers()
        n = p.n
        bad = sort_by_cell(pos, vel, species, pid, mass, n, self._lay_t, self._sp_t, self._off_t, self._keys,
                           self._order_work, self._ptr, self._cell_start, self._fwork, self._iwork, self._order, self._R,
                           self._wts)
        if bad >= 0:
            self._stop_nonfinite(bad)  # raises (a block of a decomposed run first tells the others)
            return
        if self._wrap:
            self._images = 0
            return
        shift = self.geometry.shear_offset(t)
        args = (n, self._lay_t, self._sp_t, self._pb_t, self._reach, self._order, shift, self._keys, self._wts, pos,
                self._cell_start)
        while True:
            m = build_images(*args, self._img_src, self._img_cell, self._img_w, self._img_dvy)
            if m <= self._img_capacity:
                break
            self._grow_images(m)
        m = self._add_halo(m)
        pos, vel, species, pid, mass = p.buffers()
        sort_images(m, self._lay_t, self._reach, pid, self._img_src, self._img_cell, self._img_w, self._img_dvy,
                    self._img_row_start)
        self._images = m

    def _stop_nonfinite(self, bad: int) -> None:
        """Stop (:class:`~dustygas.errors.SimulationError`, naming the particle and the field):
        particle ``bad`` has a position or velocity that is not finite."""
        p = self.particles
        values = {f"{name}": float(p.pos[a, bad]) for a, name in enumerate("xyz")}
        values.update({f"v{name}": float(p.vel[a, bad]) for a, name in enumerate("xyz")})
        fields = [f"{k}={v:.6g}" for k, v in values.items() if not np.isfinite(v)]
        raise SimulationError(
            f"invalid particle state (particle pid={int(p.pid[bad])}, species {int(p.species[bad])}) at "
            f"time={self.t:.6g} cycle={self.cycle}: {', '.join(fields)}",
            state={"particle_pos": p.pos.copy(), "particle_vel": p.vel.copy(), "particle_pid": p.pid.copy()},
        )

    def _deposit(self, out, g, values, cols, nthreads: int = 0) -> None:
        """Pull-deposit ``values`` (N, nv) of the prepared particles into the domain of ``out``
        (its domain cells set to the deposit; its ghosts left alone), in ``nthreads`` chunks
        (0: numba's current thread count)."""
        pull_deposit(out, self._ghost_arrays[g], self._lay_t, self._reach, self._R, self._cell_start, self._keys,
                     self._wts, values, cols, self._img_row_start, self._img_cell, self._img_w, self._img_src,
                     nthreads or numba.get_num_threads(), True, self._wrap)

    def _fill_and_filter(self, field, out, g, t: float, rows: tuple[int, int], nthreads: int) -> np.ndarray:
        """Ghosts and the grid-scale filter of a particle-side field in the domain rows ``rows``
        (with the ghost rows beyond them where they reach a z face); returns the array that holds
        the result: ``out`` in a 2D x-z box (filtered out of place), else ``field`` itself."""
        shift = self.geometry.shear_offset(t) / self.geometry.dx[1] if self.geometry.shape[1] > 1 else 0.0
        k_lo, k_hi = self._padded_rows(rows, g[2])
        self._field_halo(field, g[2])
        if self._xz:  # the ghosts inside the filter's parallel region
            filter_field_xz(field, out, k_lo, k_hi, filter_pieces(nthreads), g[0], g[2], self._field_kinds)
            return out
        fill_field_ghosts(field, g[0], g[1], g[2], self._field_kinds, shift, *self._remap, k_lo, k_hi)
        if self.smooth:
            filter_field(field, self._active, k_lo, k_hi)
        return field

    def _step_coefficients(self, h: float) -> None:
        if h != self._coef_dt:
            for s, ts in self._fixed_t_stop:
                step_coefficients(ts, self.forces.gravity_z, h, self._coef[s])
            self._coef_dt = h

    def _stage_source(self, state: np.ndarray, t: float) -> np.ndarray:
        """The momentum source of a gas stage: the back-reaction plus the gas terms (``state`` at ``t``).
        Without gas terms the back-reaction array itself (the gas stages only read it)."""
        if not self.gas_terms:
            return self._source
        ext = self._ext
        ext[...] = self._source if self.feedback else 0.0
        self._gas_terms(state, t, ext)
        return ext

    def _gas_terms(self, state: np.ndarray, t: float, out: np.ndarray) -> None:
        if self.gas_terms:
            rho = state[(0,) + self.mesh.interior()]
            for term in self.gas_terms:
                term.add_source(self, rho, t, out)

    def advance(self, dt: float) -> None:
        """One coupled step (module docstring); one compiled call where it can
        (:attr:`compiled_step`, :mod:`dustygas.particles.step_xz`)."""
        if self.compiled_step:
            self._advance_one_call(dt)
            return
        gas, p = self.gas, self.particles
        h = dt
        t = gas.t
        nthreads = numba.get_num_threads()
        pos, vel, species, pid, mass = p.buffers()
        # 1. drift, exchange, sort, weights, images at x^{n+1/2}
        self._exchange(t + 0.5 * h, 0.5 * h)
        self._prepare(t + 0.5 * h)
        pos, vel, species, pid, mass = p.buffers()
        n = p.n
        # 2. the dust deposit of the local drag problem
        u_old = gas.stage_input(0)
        if self.feedback:
            back = 0.5 * h if self._active[0] else 0.0
            dust_values(pos, vel, species, mass, n + self._n_halo, self._inv_vol, True, self._shear_rate, back,
                        self._values, self._cols)
            self._deposit(self._dep1, (0, 0, 0), self._values, self._cols, nthreads)
            if not self._have_source:  # first step: the drag at t^n (a steady drift stays a fixed point)
                explicit_drag_source(u_old, self.mesh.ghosts, self._sp_t, self._off_t, self._shear_rate, self._dep1,
                                     self.nspecies, self.species_t, self._source)
        # 3. gas predictor
        use_ext = self.feedback or bool(self.gas_terms)
        ext = self._stage_source(u_old, t) if use_ext else None
        gas.advance_stage(0, h, ext, nthreads)
        u_half = gas.stage_input(1)
        t_half = t + 0.5 * h
        # 4. the trajectory field
        pred_dt = gas.stage_weight(0) * h
        rows = self._occupied_rows(n, self._field_margin)
        self.field_rows = rows
        mine = self._block_rows(rows)
        if self._mesh_term is not None:
            self._mesh_term.update(self, u_half[(0,) + self.mesh.interior()], t_half)
            self._mesh_field[...] = self._mesh_term.field
        if mine[1] > mine[0]:
            cell_trajectories(u_old, u_half, self.mesh.ghosts, self._source, pred_dt, h, self._lay_t, self._sp_t,
                              self._off_t, self._dep1, self.nspecies, self.species_t, self._frame_forces_t,
                              self._mesh_field, self._shear_rate, self.feedback, self._traj, self._gt, self._c_rho,
                              self._c_mesh, mine[0], mine[1])
        traj = self._fill_and_filter(self._traj, self._traj_out, self._gt, t_half, rows, nthreads)
        # 5. particles: gather, update, their drag source, second half drift
        self._step_coefficients(h)
        self._vmax = kick(pos, vel, species, mass, n, self._keys, self._wts, self._R, self._reach, self._lay_t,
                          self._sp_t, traj, self._gt, self._c_rho, self._c_mesh, self.species_t, self._coef,
                          self._frame_forces_t, self._shear_rate, h, self._inv_vol, self._active, self._values,
                          self.terms_rows, self._vmax_work, self._fwork)
        if self.feedback:
            self._kicked(n)
            self._deposit(self._dep2, self._g2, self._values[:, :3], self._zero_cols, nthreads)
            dep2 = self._fill_and_filter(self._dep2, self._dep2_out, self._g2, t_half, rows, nthreads)
            copy_domain(dep2, self._ghost_arrays[self._g2], self._source, 1.0)
            self._have_source = True
        # 6. gas corrector
        ext = None
        if use_ext:
            ext = self._stage_source(u_half, t_half)
            if self.gas_terms:
                add_row_impulse(ext, self._source, self.feedback, h * self.mesh.cell_volume, self.gas_terms_rows)
        gas.advance_stage(1, h, ext, nthreads)
        self._exchange(t + h)
