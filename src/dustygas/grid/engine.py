"""The grid engine: isothermal Godunov gas on one block, driven by the run loop.

:class:`GridEngine` owns the state (``states[0]`` is the conserved ``(rho, rho v_x, rho v_y,
rho v_z)`` with ghost zones; further slots are integrator scratch), implements the run-loop
protocol of :mod:`dustygas.runner`, and exposes the small :class:`GridGeometry` interface the
particle module uses instead of grid internals.

Memory: ``4 x 8 = 32`` bytes per cell and state slot, so VL2 and RK2 hold 64 bytes per cell
(plus ghost zones), RK3 96; per-thread pencil buffers are a few kB.

Velocities in the state are the full velocities of the rotating frame unless orbital
advection is on, in which case they are relative to the background shear
(``v'_y = v_y + q Omega x``); :meth:`GridEngine.primitive` and the snapshots always return
the full velocity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Callable

import numba
import numpy as np

from .._numba_cache import load_for_arguments
from ..errors import SetupError, SimulationError, UserError
from .boundaries import BOUNDARY_KINDS, PERIODIC, SHEAR_PERIODIC, fill_ghosts, make_boundaries
from .budget import budget_offsets, budget_rows_from, budget_totals
from .ctu import ctu_stage, ctu_work
from .diagnostics import domain_sums, max_signal_rate
from .integrator import INTEGRATORS, advance_gas, courant_limit, integrator_tables
from .mesh import KernelTuple, Mesh
from .reconstruct import LIMITERS, RECONSTRUCTIONS, STENCIL_DEPTH
from .riemann import RIEMANN_SOLVERS
from .shearing_box import (periodic_tidal_lever, periodic_tidal_potential, shear_offset, shear_velocity_jump,
                           source_terms)

__all__ = ["GridEngine", "GridGeometry"]

#: callback of :meth:`GridEngine.advance_with_sources`: (stage, state read, stage time, stage dt) -> S_ext or None
SourceHook = Callable[[int, np.ndarray, float, float], "np.ndarray | None"]


@dataclass(frozen=True)
class GridGeometry:
    """What a particle module needs to know about the mesh and the frame.

    Attributes
    ----------
    shape
        Domain cells ``(nx, ny, nz)``; 1 marks an inactive axis.
    nghost
        Ghost cells per side ``(gx, gy, gz)``; domain cell ``(i, j, k)`` is array element
        ``[k + gz, j + gy, i + gx]`` of each variable.
    lower, dx, box
        Lower corner of the domain, cell sizes and box lengths (inactive axes: 0, 1, 1).
    q, omega
        Shear parameter and frame rotation.
    shear_periodic
        Whether the radial boundaries slide (particles crossing x change y by the offset).
    velocity_relative_to_shear
        True under orbital advection: stored gas velocities are ``v + q Omega x y^``.
    boundaries
        Boundary kind name of each axis (:data:`~dustygas.grid.boundaries.BOUNDARY_KINDS`).
    """

    shape: tuple[int, int, int]
    nghost: tuple[int, int, int]
    lower: tuple[float, float, float]
    dx: tuple[float, float, float]
    box: tuple[float, float, float]
    q: float
    omega: float
    shear_periodic: bool
    velocity_relative_to_shear: bool
    boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic")

    def shear_offset(self, t: float) -> float:
        """Azimuthal offset ``q Omega Lx t mod Ly`` of the outer radial image at time ``t``."""
        if not self.shear_periodic or self.shape[1] == 1:
            return 0.0
        return float(shear_offset(t, self.q * self.omega * self.box[0], self.box[1]))

    @property
    def shear_velocity_jump(self) -> float:
        """``q Omega Lx`` (0 without shear-periodic boundaries): v_y of the inner image minus the outer."""
        return self.q * self.omega * self.box[0] if self.shear_periodic else 0.0


class GridEngine:
    """Isothermal gas on a uniform mesh, optionally in a shearing box.

    Parameters
    ----------
    mesh
        The block of cells.
    cs
        Isothermal sound speed.
    integrator, reconstruction, limiter, riemann
        Names from :data:`~dustygas.grid.integrator.INTEGRATORS`,
        :data:`~dustygas.grid.reconstruct.RECONSTRUCTIONS`,
        :data:`~dustygas.grid.reconstruct.LIMITERS`,
        :data:`~dustygas.grid.riemann.RIEMANN_SOLVERS`.
    cfl
        Courant number (see :func:`~dustygas.grid.diagnostics.max_signal_rate`).
    boundaries
        Kind name per axis (:data:`~dustygas.grid.boundaries.BOUNDARY_KINDS`).
    omega, q, orbital_advection, vertical_gravity, eta_vK
        Shearing box (:func:`~dustygas.grid.shearing_box.source_terms`); ``omega = 0``: none.
        Vertical gravity in a box periodic in z derives from the periodic, smoothed potential
        :meth:`tidal_potential` (Athena's stratified boxes, Bai & Stone 2010b).

    Examples
    --------
    >>> eng = GridEngine(Mesh((32, 1, 1), (1.0, 1.0, 1.0)))
    >>> eng.set_primitive(rho=1.0)
    >>> eng.advance(eng.timestep()); eng.cycle, round(eng.history()["mass"], 12)
    (1, 1.0)
    """

    work_label = "zone-cycles"
    # the records the stages take, each with its plain tuple (``_layout_t`` ...: dustygas.grid.mesh)
    _layout, _spacing, _sources, _bc = KernelTuple(), KernelTuple(), KernelTuple(), KernelTuple()

    def __init__(
        self,
        mesh: Mesh,
        cs: float = 1.0,
        integrator: str = "vl2",
        reconstruction: str = "plm",
        limiter: str = "mc",
        riemann: str = "hlle",
        cfl: float = 0.4,
        boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic"),
        omega: float = 0.0,
        q: float = 1.5,
        orbital_advection: bool = False,
        vertical_gravity: bool = False,
        eta_vK: float = 0.0,
    ):
        for name, value, table in (("integrator", integrator, INTEGRATORS),
                                   ("reconstruction", reconstruction, RECONSTRUCTIONS),
                                   ("limiter", limiter, LIMITERS), ("riemann", riemann, RIEMANN_SOLVERS)):
            if value not in table:
                raise SetupError(f"{name} '{value}' unknown: choose one of {', '.join(table)}")
        if not cs > 0:
            raise SetupError(f"sound speed cs={cs}: must be positive")
        limit = courant_limit(mesh.ndim, integrator)
        if not 0 < cfl <= limit:
            raise SetupError(f"cfl={cfl}: {integrator} in {mesh.ndim}D is stable for 0 < cfl <= {limit:g}")
        for n, g, axis in zip(mesh.shape, mesh.ghosts, "xyz"):
            if 1 < n < g:
                raise SetupError(f"n{axis}={n}: an active axis needs at least {g} cells")
        #: the arguments besides the mesh (a decomposed run builds a block engine from them)
        self.options = dict(cs=cs, integrator=integrator, reconstruction=reconstruction, limiter=limiter,
                            riemann=riemann, cfl=cfl, boundaries=tuple(boundaries), omega=omega, q=q,
                            orbital_advection=orbital_advection, vertical_gravity=vertical_gravity, eta_vK=eta_vK)
        shear = boundaries[0] == "shear-periodic" and mesh.active[0]
        if orbital_advection and omega == 0.0:
            raise SetupError("orbital advection needs a rotating frame (omega != 0)")
        self.mesh = mesh
        self.cs = float(cs)
        self.cfl = float(cfl)
        self.scheme_names = dict(integrator=integrator, reconstruction=reconstruction, limiter=limiter, riemann=riemann)
        self.omega, self.q = float(omega), float(q)
        # velocities relative to the shear; the remap itself only acts if y is active
        self.orbital_advection = bool(orbital_advection)
        self.shear_periodic = shear
        self.boundary_kinds = tuple(boundaries)
        recon = RECONSTRUCTIONS[reconstruction]
        lim = LIMITERS[limiter]
        self._scheme = (recon, lim, RIEMANN_SOLVERS[riemann], self.cs)
        self._ints, self._reals = integrator_tables(integrator)
        self._layout = mesh.layout
        self._spacing = mesh.spacing
        self._sources = source_terms(omega, q, self.orbital_advection, vertical_gravity, eta_vK)
        lx = mesh.size[0]
        self._bc = make_boundaries(
            tuple(boundaries), mesh.active, q * omega * lx,
            shear_velocity_jump(q, omega, lx, self.orbital_advection), recon, lim,
            scale_height=cs / omega if vertical_gravity and omega > 0 else 0.0,
        )._replace(z_origin=float(mesh.origin[2]), z_first=int(mesh.offsets.k0))
        self._oa_rate = q * omega if self.orbital_advection and mesh.active[1] else 0.0
        # v_y(full) = v_y(stored) - to_full x ;  v_y(relative to shear) = v_y(stored) + to_relative x
        self._to_full = q * omega if self.orbital_advection else 0.0
        self._to_relative = 0.0 if self.orbital_advection else q * omega
        self._xc = mesh.centers(0, ghosts=True)
        # the lever of the vertical gravity -Omega^2 zeta: z, or in a box periodic in z the
        # folded and smoothed lever of a periodic potential (kernels read zc only for gravity)
        self._periodic_gravity = (vertical_gravity and mesh.active[2]
                                  and BOUNDARY_KINDS[boundaries[2]] in (PERIODIC, SHEAR_PERIODIC))
        self._zc = mesh.centers(2, ghosts=True)
        if self._periodic_gravity:
            self._zc = periodic_tidal_lever(self._zc, **self._periodic_box())
        nz, ny, nx = mesh.array_shape
        self.states = np.zeros((INTEGRATORS[integrator], 4, nz, ny, nx))
        #: the state each stage reads (views of ``states``, made once: a step asks for them twice)
        self._stage_inputs = tuple(self.states[int(i)] for i in self._ints[:, 0])
        self._nstage = int(self._ints.shape[0])
        self._bflux = np.zeros((2, 4, mesh.shape[2], mesh.shape[1]))
        if integrator == "ctu" and mesh.active[2] and BOUNDARY_KINDS[boundaries[2]] not in (PERIODIC, SHEAR_PERIODIC):
            # the CTU stage does not record the mass fluxes of open z faces (budget[2:4])
            raise UserError(f"scheme.integrator = 'ctu' needs a periodic z boundary, not '{boundaries[2]}' (use vl2)")
        self._ctu = ctu_work(mesh.array_shape, mesh.ndim) if integrator == "ctu" else None
        self._wrap = tuple(BOUNDARY_KINDS[k] in (PERIODIC, SHEAR_PERIODIC) for k in boundaries)
        self._zflux = np.zeros((2, 4, mesh.shape[1], mesh.shape[0]))
        self._no_ext = np.zeros((3, 1, 1, 1))
        #: the time integrals of :mod:`dustygas.grid.budget` per unit (z plane, row of cells,
        #: face cell), which the stages add to; :attr:`budget` has their totals
        self.budget_rows = np.zeros(budget_offsets(*mesh.shape)[0])
        self.t = 0.0
        self.cycle = 0
        self.work_units = mesh.ncells
        self._update_rate()  # an unset (zero) density is flagged until set_primitive

    # ------------------------------------------------------------------ state access
    @property
    def budget(self) -> np.ndarray:
        """The time integrals [mass through the radial boundary, y-momentum from the source
        terms, mass out through the lower and the upper z face]: the sums of :attr:`budget_rows`
        (:func:`~dustygas.grid.budget.budget_totals`)."""
        return budget_totals(self.budget_rows, self.mesh.shape)

    @property
    def state(self) -> np.ndarray:
        """Conserved variables ``(4, NZ, NY, NX)`` with ghost zones (slot 0 of :attr:`states`)."""
        return self.states[0]

    @property
    def half_state(self) -> np.ndarray:
        """Slot 1: after a VL2 step, the half-step state ``U^{n+1/2}`` read by the corrector."""
        return self.states[1]

    @property
    def geometry(self) -> GridGeometry:
        m = self.mesh
        return GridGeometry(m.shape, m.ghosts, m.lower, m.dx, m.size, self.q, self.omega,
                            self.shear_periodic, self.orbital_advection, self.boundary_kinds)

    def set_primitive(self, rho: Any = 1.0, vx: Any = 0.0, vy: Any = 0.0, vz: Any = 0.0) -> None:
        """Set the domain from density and the *full* velocity (broadcast to ``(nz, ny, nx)``)."""
        shape = tuple(reversed(self.mesh.shape))
        rho = np.broadcast_to(np.asarray(rho, dtype=np.float64), shape)
        if not np.all(rho > 0) or not np.all(np.isfinite(rho)):
            raise SetupError("initial density must be positive and finite everywhere")
        x = self.mesh.centers(0)[None, None, :]
        vy = np.broadcast_to(np.asarray(vy, dtype=np.float64), shape) + self._to_full * x
        inner = (slice(None),) + self.mesh.interior()
        u = self.states[0][inner]
        for var, vel in ((1, vx), (2, vy), (3, vz)):
            u[var] = rho * np.broadcast_to(np.asarray(vel, dtype=np.float64), shape)
        u[0] = rho
        self._update_rate()

    def primitive(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Domain density and full velocities, each ``(nz, ny, nx)``."""
        u = self.states[0][(slice(None),) + self.mesh.interior()]
        rho = u[0].copy()
        x = self.mesh.centers(0)[None, None, :]
        return rho, u[1] / rho, u[2] / rho - self._to_full * x, u[3] / rho

    def fill_ghosts(self, u: np.ndarray | None = None, t: float | None = None) -> np.ndarray:
        """Fill the ghost zones (edges and corners too) of ``u`` (default: the state) at ``t``."""
        u = self.states[0] if u is None else u
        fill_ghosts(u, self.t if t is None else t, self._layout, self._spacing, self._bc)
        return u

    # ------------------------------------------------------------------ run-loop protocol
    def _update_rate(self) -> None:
        rate, bad = max_signal_rate(self.states[0], self._layout, self._spacing, self.cs)
        self._check(rate, bad)

    def _check(self, rate: float, bad: int) -> None:
        self._rate = rate
        self._bad = bad

    def _periodic_box(self) -> dict[str, float]:
        """The global z extent and the smoothing length (the ghost depth) of the periodic potential."""
        m = self.mesh
        return dict(z_lo=float(m.origin[2]), lz=float(m.size[2]), smoothing=m.nghost * float(m.dx[2]))

    def tidal_potential(self, z: np.ndarray) -> np.ndarray:
        """The vertical tidal potential per ``Omega^2`` that the gas feels, 0 at ``z = 0``: ``z^2/2``,
        or in a box periodic in z :func:`~dustygas.grid.shearing_box.periodic_tidal_potential`
        (the isothermal column at rest is ``rho_0 exp(-Omega^2 phi / c_s^2)``)."""
        z = np.asarray(z, dtype=np.float64)
        return periodic_tidal_potential(z, **self._periodic_box()) if self._periodic_gravity else 0.5 * z * z

    def timestep(self) -> float:
        """``cfl / max_d((|v_d| + c_s)/dx_d)`` of the current state (thesis eqs. 2.12-2.13)."""
        if self._bad >= 0:
            nx, ny, _ = self.mesh.shape
            i, j, k = self._bad % nx, (self._bad // nx) % ny, self._bad // (nx * ny)
            rho, vx, vy, vz = self.primitive()
            cell = {"rho": rho[k, j, i], "vx": vx[k, j, i], "vy": vy[k, j, i], "vz": vz[k, j, i]}
            bad = [f"{n}={v:.6g}" for n, v in cell.items() if not np.isfinite(v) or (n == "rho" and v <= 0)]
            raise SimulationError(
                f"invalid gas state in cell (i={i}, j={j}, k={k}) at time={self.t:.6g} cycle={self.cycle}: "
                + ", ".join(bad or [f"{n}={v:.6g}" for n, v in cell.items()]),
                state={"rho": rho, "vx": vx, "vy": vy, "vz": vz},
            )
        return self.cfl / self._rate

    def advance(self, dt: float) -> None:
        """One step of the configured integrator (fused: one call into compiled code)."""
        if self._ctu is not None:
            self.advance_stage(0, dt)
            self.advance_stage(1, dt)
            return
        rate, bad = advance_gas(*self._step_arguments(dt))
        self.finish_step(dt, rate, bad)

    def _step_arguments(self, dt: float) -> tuple:
        """The arguments of :func:`~dustygas.grid.integrator.advance_gas` for a whole step ``dt``."""
        return (self.states, self._ints, self._reals, 0, self._ints.shape[0], True, dt, self.t, self._layout_t,
                self._spacing_t, self._scheme, self._sources_t, self._bc_t, self._xc, self._zc, self._oa_rate,
                self._no_ext, False, self._bflux, self._zflux, self.budget_rows, numba.get_num_threads())

    def load_kernels(self) -> None:
        """Have numba load :meth:`advance`'s compiled step from its cache (or compile it) now,
        for the types of this engine's arguments, instead of at the first step (the run loop
        calls it before its clock starts: 0.07 s for a 256² shearing box, 2026-12-07). Nothing
        is run and the state is not touched."""
        if self._ctu is None:
            load_for_arguments(advance_gas, self._step_arguments(0.0))

    @property
    def stage_count(self) -> int:
        """Number of stages of the integrator (2 for VL2)."""
        return int(self._ints.shape[0])

    def stage_time_fraction(self, stage: int) -> float:
        """Time of ``stage`` as a fraction of the step (VL2: 0, then 1/2)."""
        return float(self._reals[stage, 3])

    def stage_weight(self, stage: int) -> float:
        """The stage's step factor: it advances by ``stage_weight * dt`` from its base (VL2: 1/2, 1)."""
        return float(self._reals[stage, 2])

    @property
    def remap_codes(self) -> tuple[int, int]:
        """Reconstruction and limiter codes of the scheme (for conservative shifts of other fields)."""
        return int(self._scheme[0]), int(self._scheme[1])

    def stage_ghost_depth(self, stage: int) -> int:
        """Ghost layers per side that ``stage`` reads of its input: the reconstruction stencil of
        the stage (VL2's donor-cell predictor: 1; PLM: 2; PPM: 3), all of them for CTU (its
        transverse predictor reaches further). A decomposed run exchanges only these."""
        if self._ctu is not None:
            return max(self.mesh.ghosts)
        method = int(self._ints[stage, 3])
        return STENCIL_DEPTH[int(self._scheme[0]) if method < 0 else method]

    def stage_input(self, stage: int) -> np.ndarray:
        """The state ``(4, NZ, NY, NX)`` that ``stage`` reads (for VL2: ``U^n``, then ``U^{n+1/2}``)."""
        return self._stage_inputs[stage]

    def advance_stage(self, stage: int, dt: float, ext: np.ndarray | None = None, nthreads: int = 0) -> None:
        """Stage ``stage`` of the step from :attr:`t` to ``t + dt``, with the external momentum
        source ``ext`` ``(3, nz, ny, nx)`` (momentum per unit volume and time; C-contiguous
        float64) or None.

        Call the stages in order ``0 .. stage_count - 1`` with the same ``dt``; the last one
        finishes the step (orbital advection, Courant rate, ``t += dt``, ``cycle += 1``). The
        stage fills the ghost zones of its input itself. The stages with ``ext=None`` are
        bit-identical to :meth:`advance`. See :mod:`dustygas.grid.integrator` for the VL2
        coupling recipe of the particles. ``nthreads``: the number of chunks of the parallel
        loops (0: numba's current thread count; results do not depend on it).
        """
        nstage = self._nstage
        nthreads = nthreads or numba.get_num_threads()
        use = ext is not None
        if self._ctu is not None:
            w = self._ctu
            rate, bad = ctu_stage(
                self.states, stage, dt, self.t, self._layout_t, self._spacing_t, self._scheme, self._sources_t,
                self._bc_t, self._xc, self._zc, self._oa_rate, ext if use else self._no_ext, use, self._wrap, w.ql,
                w.qr, w.fluxes, self._bflux, self.budget_rows, nthreads,
            )
        else:
            rate, bad = advance_gas(
                self.states, self._ints, self._reals, stage, stage + 1, stage == nstage - 1, dt, self.t,
                self._layout_t, self._spacing_t, self._scheme, self._sources_t, self._bc_t, self._xc, self._zc,
                self._oa_rate, ext if use else self._no_ext, use, self._bflux, self._zflux, self.budget_rows, nthreads,
            )
        if stage == nstage - 1:
            self.finish_step(dt, rate, bad)

    def two_stage_arguments(self) -> tuple | None:
        """The arguments of :func:`~dustygas.grid.integrator.advance_gas` that do not change from
        step to step (``states, ints, reals, layout, spacing, scheme, terms, bounds, xc, zc,
        oa_rate, no_ext, bflux, zflux, budget``) and the states the two stages read, for a caller
        that runs both VL2 stages inside one compiled function
        (:func:`~dustygas.particles.step_xz.coupled_step_xz`) and then :meth:`finish_step`; None
        for an integrator whose stages are not :func:`advance_gas`'s (CTU)."""
        if self._ctu is not None or self._nstage != 2:
            return None
        return (self.states, self._ints, self._reals, self._layout_t, self._spacing_t, self._scheme, self._sources_t,
                self._bc_t, self._xc, self._zc, self._oa_rate, self._no_ext, self._bflux, self._zflux,
                self.budget_rows, *self._stage_inputs)

    def finish_step(self, dt: float, rate: float, bad: int) -> None:
        """After the last stage of a step of ``dt``: its Courant ``rate`` and first ``bad`` cell
        (checked at the next :meth:`timestep`), the time and the cycle."""
        self._check(rate, bad)
        self.t += dt
        self.cycle += 1

    def advance_with_sources(self, dt: float, hook: SourceHook) -> None:
        """One step calling ``hook(stage, U_read, t_stage, dt_stage)`` before each stage.

        ``U_read`` is the state the stage reads, with ghost zones filled at ``t_stage``; the
        hook returns the external momentum source ``(3, nz, ny, nx)`` of that stage (momentum
        per unit volume and time) or None. With a hook returning None this is bit-identical
        to :meth:`advance`. See :mod:`dustygas.grid.integrator` for the VL2 coupling recipe.
        """
        reals = self._reals
        want = (3,) + tuple(reversed(self.mesh.shape))
        for s in range(self.stage_count):
            src = self.stage_input(s)
            t_stage = self.t + reals[s, 3] * dt
            fill_ghosts(src, t_stage, self._layout, self._spacing, self._bc)
            ext = hook(s, src, t_stage, reals[s, 2] * dt)
            if ext is not None:
                ext = np.ascontiguousarray(ext, dtype=np.float64)
                if ext.shape != want:
                    raise ValueError(f"momentum source has shape {ext.shape}, expected {want}")
            self.advance_stage(s, dt, ext)

    def history(self) -> dict[str, float]:
        """Totals over the box (per unit length of inactive axes)."""
        s = domain_sums(self.states[0], self._layout, self._xc, self._to_full, self._to_relative)
        dv = self.mesh.cell_volume
        out = {
            "mass": s[0] * dv,
            "momentum_x": s[1] * dv,
            "momentum_y": s[2] * dv,
            "momentum_z": s[3] * dv,
            "kinetic_energy": s[4] * dv,
            "rho_max": s[5],
            "rho_min": s[6],
        }
        budget = self.budget
        if self.shear_periodic or self._sources.active:
            out["radial_boundary_mass"] = float(budget[0])
            out["momentum_y_source"] = float(budget[1])
        if self.mesh.active[2] and self._bc.z_lo != PERIODIC:
            out["gas_mass_lost_z_lower"] = float(budget[2])
            out["gas_mass_lost_z_upper"] = float(budget[3])
            out["gas_mass_lost"] = float(budget[2] + budget[3])
        return {k: float(v) for k, v in out.items()}

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        rho, vx, vy, vz = self.primitive()
        m = self.mesh
        arrays = {"rho": rho, "vx": vx, "vy": vy, "vz": vz,
                  "x": m.centers(0), "y": m.centers(1), "z": m.centers(2)}
        attrs = {"cs": self.cs, "omega": self.omega, "q": self.q, "lx": m.size[0], "ly": m.size[1], "lz": m.size[2],
                 "shear_offset": self.geometry.shear_offset(self.t),
                 "orbital_advection": self.orbital_advection, **self.scheme_names}
        return arrays, attrs

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        inner = (slice(None),) + self.mesh.interior()
        return {"conserved": self.states[0][inner].copy(), "budget": self.budget,
                "budget_rows": self.budget_rows.copy()}, {}

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        inner = (slice(None),) + self.mesh.interior()
        u = np.asarray(arrays["conserved"])
        if u.shape != self.states[0][inner].shape:
            raise UserError(f"checkpoint holds a state of shape {u.shape}, the configuration a {self.states[0][inner].shape}")
        self.states[0][inner] = u
        self.budget_rows[:] = budget_rows_from(arrays, self.mesh.shape)
        self._update_rate()
