"""Gas + particles: the coupled engine (thesis §4.2, eqs. 4.22-4.25; Bai & Stone 2010a).

Scheme
------
One step ``t^n -> t^{n+1} = t^n + Δt`` interleaves the particles with the two stages of the
gas's VL2 integrator (Stone & Gardiner 2009), following the predictor-corrector structure of
Bai & Stone (2010a, §3) and made second order with *our* gas stages:

1. **particle predictor** (:func:`~dustygas.particles.push.particle_stage`): half drift
   ``x^{n+1/2} = x^n + (Δt/2) v^n``;
2. **gas predictor**: ``U^{n+1/2} = U^n + (Δt/2)[L_donor(U^n) + S^{n-1/2}]``, with the
   back-reaction ``S^{n-1/2}`` deposited by the previous corrector (step 3). The VL2 predictor
   only needs ``U^{n+1/2}`` to first order, and ``S^{n-1/2} = S(t^n) + O(Δt)`` changes it by
   ``O(Δt²)``, which enters ``U^{n+1}`` at ``O(Δt³)``: the step stays second order, costs one
   particle gather and deposit instead of two, and the source is the drag impulse actually
   exchanged, bounded however stiff the drag. The first step (and only it) computes
   ``S^0 = Σ_i W(x_i^0) m_i (v_i^0 - u^0(x_i^0)) / (t_s V_cell)`` explicitly;
Second order: the particle update is a drift-kick-drift (leapfrog) in position with a
time-centred (midpoint) kick, gathering the gas at the midpoint time and position; the gas
corrector, the only stage whose source enters ``U^{n+1}``, receives the time-centred drag
deposited at the time-centred positions. Momentum: the gas receives in the corrector exactly
minus the drag impulse ``Σ m_i Δv_{drag,i}`` the particles received, with weights that sum to
one, so ``Σ_cells ρu V + Σ_i m_i v_i`` changes only by the round-off of the sums (eq. 4.25)
-- the predictor's source only shapes ``U^{n+1/2}``. The source carried from one step to the
next is part of the checkpoint, so a restarted run is bit-identical. Steady states: with uniform gas and a
uniform particle lattice the NSH drift (thesis eq. 4.8) is an exact fixed point of every stage
(both drag integrators keep a steady drift exactly; TSC and CIC deposit a moving lattice
uniformly).

Frames: particle velocities are stored like the gas's (full velocities, or relative to the
shear ``v + q Ω x ŷ`` under orbital advection); the Coriolis/tidal terms are the gas's
(thesis eq. 4.2), ``(2Ω v_y + 2qΩ²x, -2Ω v_x)`` or ``(2Ω v'_y, -(2 - q)Ω v'_x)``. The global
pressure gradient is either on the gas (``shearing_box.eta_vK``) or, opposite, on the
particles (``acceleration = (-2 η v_K Ω, 0, 0)``).

Time step: the gas's Courant step, the particles' ``cfl Δx_d / max|v_d|`` (so that a particle
moves less than a cell per step, which the deposit scheme needs), and optionally a fraction of
the smallest stopping time. Two-way coupling of heavy (μ > 1), stiff (t_s ≪ Δt) dust needs the
last: the predictor's explicit source then overshoots.

What mattered for linB (Youdin & Johansen 2007; Athena misses it by -17.7 %)
-----------------------------------------------------------------------------
linB (ε = 0.2, K = 6, s = 0.0154862) grows 150 Ω⁻¹ through 459,000 steps at 64 cells per
wavelength, so anything that damps or pollutes a resolved wave shows. Measured at 64², one
particle per cell, t = 0 -> 150 (growth error, spread of the eight fields; 2026-11-22):

* shipped defaults (PPM-CS, HLLC, TSC through the grid-scale filter, semi-implicit drag):
  **-2.10 %**, fields within 0.012 %;
* without the grid-scale filter (``smooth=False``): -3.86 %, fields within 0.58 %. The
  particles drift through the mesh at the NSH speed and their deposit aliases the particle
  noise onto grid-scale gas waves that feed back on them: by t = 150 the dust density's
  grid-scale Fourier content (|m| > 8) is 1.4e-6, above the linB mode's 8.9e-7 (3.9e-13 with
  the filter);
* the classic Colella & Woodward (1984) PPM limiter instead of Colella & Sekora's (with the
  filter): -6.16 %, fields within 0.015 %: it clips the smooth extrema of the tiny gas wave.

linA (s = 0.419, 6 Ω⁻¹) is insensitive to these choices: -0.36 % with the defaults.
"""

from __future__ import annotations

from typing import Any, Sequence

import numba
import numpy as np

from ..errors import SetupError, UserError
from ..physics.drag import epstein_grain_size
from .deposit import chunk_bounds
from .diagnostics import MODE_FIELDS, gas_mode, particle_mode
from .drag import DRAG_INTEGRATORS
from .interp import KERNEL_REACH, KERNELS, Cells
from .push import CORRECT, EPSTEIN, FIXED, PREDICT, Forces, Species, deposit_density, particle_stage
from .store import ParticleStore, cell_keys, counting_sort, slab_axis, slab_starts

__all__ = ["ParticleGridEngine", "DRAG_LAWS", "GAS_INTEGRATORS"]

#: name -> code of the stopping-time laws
DRAG_LAWS = {"fixed": FIXED, "epstein": EPSTEIN}

#: gas integrators the coupling supports: its drag is predicted and corrected with VL2's two
#: stages (Bai & Stone 2010a, §2.3); the ``scheme.integrator`` of the particle problems offers these
GAS_INTEGRATORS = ("vl2",)


class ParticleGridEngine:
    """A :class:`~dustygas.grid.GridEngine` (VL2) with Lagrangian dust particles.

    Parameters
    ----------
    gas
        The gas engine holding its initial state; its integrator must be ``vl2``.
    particles
        The particles (positions inside the box; velocities in the gas's frame).
    t_stop
        Stopping time of each species (code units). For ``"epstein"`` species it is the value
        at gas density ``rho_ref``; the local one is ``t_stop rho_ref / rho_g`` (thesis eq. 2.6).
    drag_law
        ``"fixed"`` or ``"epstein"`` per species (one string for all).
    kernel
        Assignment function ``"ngp"``, ``"cic"``, ``"tsc"`` (gather and deposit alike).
    integrator
        Drag integrator, ``"semi-implicit"`` (Bai & Stone 2010a) or ``"exponential"``.
    feedback
        Apply the back-reaction of the drag on the gas.
    acceleration
        Constant acceleration of every particle (e.g. ``(-2 η v_K Ω, 0, 0)``: the pressure
        gradient in the particle frame; a settling acceleration along z).
    vertical_gravity
        ``-Ω² z`` on the particles.
    gas_acceleration_z
        Constant vertical acceleration of the gas (per unit gas mass).
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
        grid-scale filter ``F = 1 - δ⁴/16`` (:func:`~dustygas.particles.deposit.filter_lines`),
        which removes the Nyquist scale and leaves resolved waves alone (``1 - (kΔx)⁴/16``).
        Without it, particles drifting through the mesh drive an aliasing instability at the
        grid scale (module docstring).
    """

    work_label = "zone-cycles"

    def __init__(
        self,
        gas,
        particles: ParticleStore,
        t_stop: Sequence[float],
        drag_law: str | Sequence[str] = "fixed",
        kernel: str = "tsc",
        integrator: str = "semi-implicit",
        feedback: bool = True,
        acceleration: Sequence[float] = (0.0, 0.0, 0.0),
        vertical_gravity: bool = False,
        gas_acceleration_z: float = 0.0,
        cfl: float | None = None,
        drag_cfl: float = 0.0,
        mode: Sequence[int] | None = None,
        rho_ref: float = 1.0,
        smooth: bool = True,
    ):
        if gas.scheme_names["integrator"] not in GAS_INTEGRATORS:
            raise SetupError(f"particles need the vl2 gas integrator, not {gas.scheme_names['integrator']}")
        if kernel not in KERNELS:
            raise SetupError(f"particle kernel '{kernel}' unknown: choose one of {', '.join(KERNELS)}")
        if integrator not in DRAG_INTEGRATORS:
            raise SetupError(f"drag integrator '{integrator}' unknown: choose one of {', '.join(DRAG_INTEGRATORS)}")
        t_stop = np.atleast_1d(np.asarray(t_stop, dtype=np.float64))
        laws = [drag_law] * len(t_stop) if isinstance(drag_law, str) else list(drag_law)
        if len(laws) != len(t_stop) or any(law not in DRAG_LAWS for law in laws):
            raise SetupError(f"drag_law must be one of {', '.join(DRAG_LAWS)} per species ({len(t_stop)})")
        if not np.all(t_stop > 0) or not np.all(np.isfinite(t_stop)):
            raise SetupError("stopping times must be positive and finite")
        if particles.n and (particles.species.min() < 0 or particles.species.max() >= len(t_stop)):
            raise SetupError(f"particle species must be in 0 .. {len(t_stop) - 1}")
        cfl = gas.cfl if cfl is None else float(cfl)
        if not 0 < cfl <= 1:
            raise SetupError(f"particle cfl={cfl}: must be in (0, 1] (a particle moves less than a cell per step)")
        geom = gas.geometry
        for axis, (kind, n) in enumerate(zip(geom.boundaries, geom.shape)):
            if n > 1 and kind not in ("periodic", "shear-periodic"):
                raise SetupError(f"particles need periodic or shear-periodic boundaries; the {'xyz'[axis]} axis is "
                                 f"'{kind}'")
        self.gas = gas
        self.particles = particles
        self.geometry = geom
        self.kernel, self.integrator = kernel, integrator
        self.feedback = bool(feedback)
        self.smooth = bool(smooth)
        self.cfl = cfl
        self.drag_cfl = float(drag_cfl)
        q, omega = geom.q, geom.omega
        relative = geom.velocity_relative_to_shear
        self._shear_y = 0.0 if relative else q * omega  # v_y + shear_y x: velocity relative to the shear
        self.forces = Forces(
            coriolis_x=2.0 * omega,
            coriolis_y=(2.0 - q) * omega if relative else 2.0 * omega,
            tidal_x=0.0 if relative else 2.0 * q * omega**2,
            gravity_z=omega**2 if vertical_gravity else 0.0,
            ax=float(acceleration[0]), ay=float(acceleration[1]), az=float(acceleration[2]),
        )
        self.gas_acceleration_z = float(gas_acceleration_z)
        codes = np.array([DRAG_LAWS[law] for law in laws], dtype=np.int64)
        grain = np.where(codes == EPSTEIN, epstein_grain_size(t_stop, 1.0, rho_ref, gas.cs, 1.0), 0.0)
        self.species = Species(codes, t_stop.copy(), np.ascontiguousarray(grain, dtype=np.float64), float(gas.cs))
        self.laws = laws
        nx, ny, nz = geom.shape
        gx, gy, gz = geom.nghost
        self.cells = Cells(nx, ny, nz, gx, gy, gz, *geom.dx, *geom.lower, *geom.box, bool(geom.shear_periodic),
                           0.0 if relative else geom.shear_velocity_jump, geom.shear_velocity_jump)
        self._order = KERNELS[kernel]
        self._method = DRAG_INTEGRATORS[integrator]
        self._axis = slab_axis(geom.shape)
        self._nslab = geom.shape[self._axis]
        self._bounds = chunk_bounds(self._nslab, KERNEL_REACH[self._order])
        ncell = nx * ny * nz
        self._fields = np.empty((4, ncell))
        self._work = np.empty((4, ncell))
        #: the back-reaction source: written by the corrector, used by the next predictor
        self._source = np.zeros((3, nz, ny, nx))
        self._have_source = False
        self._starts = np.zeros(self._nslab + 1, dtype=np.int64)
        self._vmax_work = np.zeros((len(self._bounds) - 1, 3))
        self._allocate(particles.n)
        self._use_ext = self.feedback or self.gas_acceleration_z != 0.0
        self.mode = None if mode is None else tuple(int(m) for m in mode)
        self._mode_setup()
        self._resort()
        self.work_units = ncell

    # ------------------------------------------------------------------ set-up helpers
    def _allocate(self, n: int) -> None:
        self._keys = np.zeros(n, dtype=np.int64)
        self._order_work = np.zeros(n, dtype=np.int64)

    def _resort(self) -> None:
        """Sort by cell, recompute the slab starts and the largest speeds."""
        p = self.particles
        self._wrap_all()
        cell_keys(p.pos, self.cells, self._axis, self._keys)
        counting_sort(self._keys, self.cells.nx * self.cells.ny * self.cells.nz, p.pos, p.vel, p.species, p.pid,
                      p.mass, self._order_work)
        ncell = self.cells.nx * self.cells.ny * self.cells.nz
        slab_starts(self._keys, ncell // self._nslab, self._nslab, self._starts)
        self._vmax = np.max(np.abs(p.vel), axis=1) if p.n else np.zeros(3)

    def _wrap_all(self) -> None:
        """Check that every particle is inside the box (set-up and restart)."""
        pos = self.particles.pos
        for axis in range(3):
            if self.geometry.shape[axis] == 1:
                continue
            lo, length = self.geometry.lower[axis], self.geometry.box[axis]
            if pos.shape[1] and (pos[axis].min() < lo or pos[axis].max() >= lo + length):
                raise SetupError(f"particle positions along {'xyz'[axis]} must lie in [{lo:g}, {lo + length:g})")

    def _mode_setup(self) -> None:
        if self.mode is None:
            return
        geom = self.geometry
        k = np.array([2 * np.pi * m / length if n > 1 else 0.0 for m, length, n in zip(self.mode, geom.box, geom.shape)])
        if not np.any(k):
            raise SetupError(f"mode {self.mode}: give a non-zero mode number along an active axis")
        self._k = k
        m = self.gas.mesh
        x, y, z = m.meshgrid()
        self._phase = np.exp(-1j * (k[0] * x + k[1] * y + k[2] * z)) * np.ones(tuple(reversed(m.shape)))
        self._cell_factor = float(np.prod([np.sinc(kd * d / (2 * np.pi)) for kd, d in zip(k, geom.dx)]))
        self._xc = x

    def _init_source(self, u: np.ndarray) -> None:
        """The source without feedback: the constant acceleration of the gas, ``rho gas_az``."""
        c = self.cells
        rho = u[0, c.gz:c.gz + c.nz, c.gy:c.gy + c.ny, c.gx:c.gx + c.nx]
        self._source[:2] = 0.0
        self._source[2] = rho * self.gas_acceleration_z

    # ------------------------------------------------------------------ time and stepping
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
        dt = self.gas.timestep()
        c = self.cells
        rate = 0.0
        for n, d, v in zip((c.nx, c.ny, c.nz), (c.dx, c.dy, c.dz), self._vmax):
            if n > 1:
                rate = max(rate, v / d)
        if rate > 0:
            dt = min(dt, self.cfl / rate)
        if self.drag_cfl > 0:
            fixed = self.species.t_stop[self.species.law == FIXED]
            if fixed.size:
                dt = min(dt, self.drag_cfl * float(fixed.min()))
        return dt

    def advance(self, dt: float) -> None:
        """One coupled step (module docstring): two particle stages, two gas stages."""
        gas, p, c = self.gas, self.particles, self.cells
        geom = self.geometry
        t = gas.t
        s0, s_half, s1 = geom.shear_offset(t), geom.shear_offset(t + 0.5 * dt), geom.shear_offset(t + dt)
        src = self._source
        args = (p.pos, p.vel, p.species, p.pid, p.mass)
        explicit = self.feedback and not self._have_source  # the first step: S^0 from the drag at t^0
        particle_stage(PREDICT, *args, gas.stage_input(0), c, self._order, self.species, self.forces, self._method,
                       explicit, self.gas_acceleration_z, dt, s0, s_half, self._fields, src.reshape(3, -1),
                       self._starts, self._bounds, self._keys, self._axis, self._order_work, self._vmax_work,
                       self.smooth, self._work)
        if self._use_ext and not self._have_source and not explicit:  # no feedback: only rho gas_az
            self._init_source(gas.stage_input(0))
        gas.advance_stage(0, dt, src if self._use_ext else None)
        vx, vy, vz, _ = particle_stage(CORRECT, *args, gas.stage_input(1), c, self._order, self.species, self.forces,
                                       self._method, self.feedback, self.gas_acceleration_z, dt, s_half, s1,
                                       self._fields, src.reshape(3, -1), self._starts, self._bounds, self._keys,
                                       self._axis, self._order_work, self._vmax_work, self.smooth, self._work)
        self._have_source = True
        self._vmax = (vx, vy, vz)
        gas.advance_stage(1, dt, src if self._use_ext else None)

    # ------------------------------------------------------------------ outputs
    def particle_momentum(self) -> np.ndarray:
        """``Σ m v`` of the particles with the full azimuthal velocity (3,)."""
        p = self.particles
        mom = p.momentum()
        if self.geometry.velocity_relative_to_shear:
            mom[1] -= self.geometry.q * self.geometry.omega * float(p.mass @ p.pos[0])
        return mom

    def mode_amplitudes(self) -> np.ndarray:
        """Complex amplitudes of :data:`~dustygas.particles.diagnostics.MODE_FIELDS` for :attr:`mode`."""
        rho, vx, vy, vz = self.gas.primitive()
        qo = self.geometry.q * self.geometry.omega
        gas = gas_mode(rho, (vx, vy + qo * self._xc, vz), self._phase, self._cell_factor)
        dust = np.empty(4, dtype=np.complex128)
        p = self.particles
        particle_mode(p.pos, p.vel, p.mass, self._k[0], self._k[1], self._k[2], self._shear_y, dust)
        return np.concatenate([gas, dust])

    def history(self) -> dict[str, float]:
        out = self.gas.history()
        pm = self.particle_momentum()
        p = self.particles
        out["particle_mass"] = float(p.mass.sum())
        for a, name in enumerate("xyz"):
            out[f"particle_momentum_{name}"] = float(pm[a])
            out[f"total_momentum_{name}"] = out[f"momentum_{name}"] + float(pm[a])
        if self.mode is not None:
            for name, value in zip(MODE_FIELDS, self.mode_amplitudes()):
                out[f"mode_{name}_re"] = float(value.real)
                out[f"mode_{name}_im"] = float(value.imag)
        return out

    def dust_density(self) -> np.ndarray:
        """Particle mass density on the mesh ``(nz, ny, nx)`` with the run's kernel."""
        c = self.cells
        out = deposit_density(self.particles.pos, self.particles.mass, c, self._order, self.geometry.shear_offset(self.t))
        return out.reshape(c.nz, c.ny, c.nx)

    def _attrs(self) -> dict[str, Any]:
        attrs = {"particle_kernel": self.kernel, "drag_integrator": self.integrator, "feedback": self.feedback,
                 "particle_smoothing": self.smooth,
                 "t_stop": self.species.t_stop.tolist(), "drag_law": list(self.laws)}
        if self.mode is not None:
            attrs["mode"] = list(self.mode)
            attrs["mode_k"] = self._k.tolist()
        return attrs

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays, attrs = self.gas.snapshot()
        arrays["rho_p"] = self.dust_density()
        for name, value in self.particles.arrays().items():
            arrays[f"particles/{name}"] = value
        return arrays, {**attrs, **self._attrs()}

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays, attrs = self.gas.checkpoint()
        for name, value in self.particles.arrays().items():
            arrays[f"particles/{name}"] = value
        if self._have_source:
            arrays["particles/gas_source"] = self._source.copy()
        return arrays, attrs

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        self.gas.restore({k: v for k, v in arrays.items() if not k.startswith("particles/")}, attrs)
        try:
            parts = {k: np.asarray(arrays[f"particles/{k}"]) for k in ("pos", "vel", "species", "pid", "mass")}
        except KeyError as exc:
            raise UserError(f"checkpoint has no particle array {exc}") from None
        self.particles = ParticleStore(**parts)
        self._allocate(self.particles.n)
        self._resort()
        self._have_source = "particles/gas_source" in arrays
        if self._have_source:
            self._source[...] = arrays["particles/gas_source"]
