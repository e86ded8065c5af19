"""The SPH engine: particles + options + one derivative evaluation + the leapfrog, for the run loop.

:class:`SPHEngine` implements the engine protocol of :mod:`dustygas.runner` (``timestep``,
``advance``, ``history``, ``snapshot``, ``checkpoint``, ``restore``; ``work_units`` = number of
particles, ``work_label`` = ``"particle-updates"``). One derivative evaluation is

1. neighbour search with the predicted smoothing lengths times ``1 + neighbour_buffer``
   (:mod:`~dustygas.sph.neighbours`), one table reused for everything below;
2. smoothing lengths and densities (thesis eq. 3.1; :mod:`~dustygas.sph.density`), the search
   repeated only for particles whose :math:`h` outgrew the table;
3. pressures and sound speeds (:mod:`~dustygas.sph.eos`);
4. pressure force, artificial viscosity and conductivity, energy equation, :math:`\\nabla\\cdot v`
   and signal speeds in one pass over the pairs (thesis eqs. 3.2-3.3; :mod:`~dustygas.sph.forces`);
5. external forces and the viscosity switch,

followed by checks that stop the run with a :class:`~dustygas.errors.SimulationError` (and the
offending particles, which the run loop dumps to ``crash.h5``) on overlapping particles, a
smoothing-length iteration that fails, or non-finite or negative states.

Examples
--------
>>> import numpy as np
>>> from dustygas.sph import Box, EquationOfState, ParticleSet, SPHEngine
>>> x = (np.arange(64) + 0.5) / 64
>>> p = ParticleSet.create(x[:, None], mass=1 / 64, h=1.2 / 64)
>>> eng = SPHEngine(p, Box.periodic_box(1, (0.0,), (1.0,)), EquationOfState.isothermal(1.0))
>>> eng.update_derivatives()
>>> round(float(eng.rho[0] * eng.particles.h[0] / eng.particles.mass[0]), 12)  # rho h = m h_fact
1.2
>>> float(abs(eng.acc).max()) < 1e-12  # a uniform lattice is in equilibrium
True
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ..errors import SetupError, SimulationError
from ..physics.timestep import acceleration_timestep, courant_timestep, min_timestep
from .density import H_NEEDS_NEIGHBOURS, H_NOT_CONVERGED, gasoline2_correction, solve_smoothing_lengths
from .eos import EquationOfState, pressure_sound_speed
from .external import ExternalForces
from .forces import FORCE_FORMS, GASOLINE2, hydro_forces, pack_particles, packed_table
from .integrator import drift_and_predict, kick
from .kernels import KERNEL_NAMES, get_kernel
from .neighbours import Box, NeighbourFinder
from .modules import SPHModule
from .particles import GAS, ParticleSet, count_invalid
from .viscosity import cullen_dehnen_alpha, morris_monaghan_rate

__all__ = ["SPHOptions", "SPHEngine", "snapshot_attrs"]

_DERIVED = ("rho", "omega", "P", "cs", "acc", "dudt", "divv", "curlv", "vsig", "dalpha", "phi", "fcorr")


def snapshot_attrs(engine) -> dict[str, Any]:
    """The attributes every SPH snapshot and checkpoint carries: the box (``ndim``, ``box_lo``,
    ``box_hi``, ``periodic``), the kernel, ``hfact`` and the equation of state of ``engine`` (an
    :class:`SPHEngine` or a :class:`~dustygas.sph.timesteps.BlockStepEngine`)."""
    box, eos = engine.box, engine.eos
    return {"ndim": box.ndim, "box_lo": list(box.lo), "box_hi": list(box.hi),
            "periodic": [int(v) for v in box.periodic], "kernel": engine.kernel.name,
            "hfact": engine.hfact, "eos_kind": eos.kind, "gamma": eos.gamma}


@dataclass(frozen=True)
class SPHOptions:
    """Numerical choices of the SPH engine.

    Attributes
    ----------
    kernel
        ``cubic``, ``quintic``, ``wendland-c2`` or ``wendland-c4``.
    hfact
        :math:`h_{\\rm fact}` in :math:`\\rho h^d = m h_{\\rm fact}^d` (0: the kernel's usual value).
    force
        ``price2012`` (variational grad-h form) or ``gasoline2`` (thesis eqs. 3.2-3.3).
    gasoline2_f
        :math:`f_a` of the GASOLINE2 form: ``gradh`` (:math:`1/\\Omega_a`) or ``wadsley``.
    alpha, alpha_min, alpha_max, beta
        Artificial viscosity: initial (or constant) :math:`\\alpha`, switch bounds, :math:`\\beta`.
    switch
        ``none`` (constant :math:`\\alpha`), ``morris-monaghan`` or ``cullen-dehnen``
        (:mod:`~dustygas.sph.viscosity`).
    switch_decay
        :math:`\\sigma` of the switch's decay time :math:`h/(\\sigma c_s)`.
    alpha_u
        Artificial conductivity coefficient (adiabatic gas only; 0: off).
    c_cour, c_force
        Courant and acceleration time-step factors (thesis eqs. 2.13-2.14).
    h_tolerance, h_max_iterations
        Relative tolerance and iteration limit of the smoothing-length iteration.
    neighbour_buffer
        Relative margin on :math:`h` with which neighbour tables are built.
    neighbour_search
        ``auto``, ``cells`` or ``tree`` (:class:`~dustygas.sph.neighbours.NeighbourFinder`).
    reorder_every
        Every this many steps store the particles in spatial order (cell by cell), so that
        neighbours stay close in memory as the flow mixes them (0: never).
    fixed_dt
        Use this time step instead of the criteria (0: adaptive).
    """

    kernel: str = "cubic"
    hfact: float = 0.0
    force: str = "price2012"
    gasoline2_f: str = "gradh"
    alpha: float = 1.0
    alpha_min: float = 0.1
    alpha_max: float = 1.0
    beta: float = 2.0
    switch: str = "morris-monaghan"
    switch_decay: float = 0.1
    alpha_u: float = 1.0
    c_cour: float = 0.3
    c_force: float = 0.25
    h_tolerance: float = 1e-4
    h_max_iterations: int = 30
    neighbour_buffer: float = 0.02
    neighbour_search: str = "auto"
    reorder_every: int = 20
    fixed_dt: float = 0.0

    def __post_init__(self) -> None:
        checks = [
            (self.kernel in KERNEL_NAMES, f"kernel must be one of {', '.join(KERNEL_NAMES)}"),
            (self.force in FORCE_FORMS, f"force must be one of {', '.join(FORCE_FORMS)}"),
            (self.gasoline2_f in ("gradh", "wadsley"), "gasoline2_f must be gradh or wadsley"),
            (self.switch in ("none", "morris-monaghan", "cullen-dehnen"),
             "switch must be none, morris-monaghan or cullen-dehnen"),
            (self.neighbour_search in ("auto", "cells", "tree"), "neighbour_search must be auto, cells or tree"),
            (self.hfact >= 0 and self.h_tolerance > 0 and self.neighbour_buffer >= 0, "hfact, h_tolerance, "
             "neighbour_buffer must be positive"),
            (0 <= self.alpha_min <= self.alpha_max, "need 0 <= alpha_min <= alpha_max"),
        ]
        for ok, msg in checks:
            if not ok:
                raise SetupError(f"SPH options: {msg}")


class SPHEngine:
    """Gas (and test) particles under SPH forces and external forces (see module docstring).

    ``modules`` are :class:`~dustygas.sph.modules.SPHModule` objects adding physics (dust,
    grain growth) at fixed points of the step; they are called in the order given.
    """

    work_label = "particle-updates"

    def __init__(self, particles: ParticleSet, box: Box, eos: EquationOfState,
                 options: SPHOptions = SPHOptions(), external: ExternalForces = ExternalForces(),
                 modules: tuple[SPHModule, ...] = ()):
        self.particles = particles
        self.box = box
        self.eos = eos
        self.options = options
        self.external = external
        self.kernel = get_kernel(options.kernel, box.ndim)
        self.hfact = options.hfact or self.kernel.default_hfact
        self.finder = NeighbourFinder(box, self.kernel.radius, method=options.neighbour_search)
        self._box_arrays = box.arrays()
        self.t = 0.0
        self.cycle = 0
        self.accreted_mass = 0.0
        self.accreted_momentum = np.zeros(3)
        self.accreted_angular_momentum = np.zeros(3)
        self.last_neighbours = None
        self.h_iterations = 0
        self.extra_searches = 0  # neighbour searches repeated because some h outgrew its table
        #: further time-step limits, each ``f(engine) -> dt`` (e.g. the drag limit of thesis eq. 2.15,
        #: :func:`dustygas.physics.timestep.drag_timestep`, added by the dust modules)
        self.timestep_limits: list = []
        self.modules: tuple[SPHModule, ...] = tuple(modules)
        self._check_setup()
        box.wrap(particles.pos)
        self._allocate(len(particles))
        self._valid = False
        for module in self.modules:
            module.attach(self)

    # ------------------------------------------------------------------ set-up
    def _check_setup(self) -> None:
        p = self.particles
        for name in ("pos", "vel", "mass", "h", "u", "alpha"):
            arr = getattr(p, name)
            if not np.all(np.isfinite(arr)):
                raise SetupError(f"initial {name} of particle {int(np.argwhere(~np.isfinite(arr))[0][0])} is not finite")
        if np.any(p.mass <= 0):
            raise SetupError(f"particle {int(np.argmax(p.mass <= 0))} has mass <= 0")
        gas = p.ptype == GAS
        if np.any(p.h[gas] <= 0):
            raise SetupError("gas particles need positive initial smoothing lengths")
        if self.eos.evolves_energy and np.any(p.u[gas] <= 0):
            raise SetupError("adiabatic gas needs positive thermal energies u")

    def _allocate(self, n: int) -> None:
        for name in _DERIVED:
            setattr(self, name, np.zeros((n, 3)) if name == "acc" else np.zeros(n))
        self.omega[:] = 1.0
        self.fcorr[:] = 1.0

    @property
    def work_units(self) -> int:
        return len(self.particles)

    @property
    def evolves_alpha(self) -> bool:
        return self.options.switch == "morris-monaghan"

    # ------------------------------------------------------------------ derivatives
    def _smoothing_lengths(self, pos, mass, h, rho, omega):
        o, k = self.options, self.kernel
        _, length, per = self._box_arrays
        h_search = h * (1.0 + o.neighbour_buffer)
        n = len(h)
        status = np.zeros(n, np.int8)
        iterations = np.zeros(n, np.int32)
        for attempt in range(8):
            nl = self.finder.find(pos, h_search)
            solve_smoothing_lengths(pos, mass, h, nl.index, nl.count, h_search, k.shape, k.norm, k.radius,
                                    k.ndim, self.hfact, length, per, o.h_tolerance, o.h_max_iterations,
                                    rho, omega, status, iterations)
            grow = status == H_NEEDS_NEIGHBOURS
            if not grow.any():
                break
            self.extra_searches += 1
            h_search = np.where(grow, 1.5 * h_search, h_search)
        else:
            bad = np.flatnonzero(grow)
            raise SimulationError(
                f"smoothing-length iteration failed: {bad.size} particles find too few neighbours even at "
                f"h = {h_search[bad[0]]:.4g} (first: particle {int(bad[0])})",
                state={"particles": bad, "h": h[bad], "position": pos[bad]},
            )
        bad = np.flatnonzero(status == H_NOT_CONVERGED)
        if bad.size:
            raise SimulationError(
                f"smoothing-length iteration did not converge in {o.h_max_iterations} iterations for "
                f"{bad.size} particles (first: particle {int(bad[0])} at h = {h[bad[0]]:.4g})",
                state={"particles": bad, "h": h[bad], "position": pos[bad]},
            )
        self.h_iterations = int(iterations.max(initial=0))
        return nl

    def _check_state(self, vel, u) -> None:
        p = self.particles
        if count_invalid(p.pos, vel, u, p.ptype, self.eos.evolves_energy) == 0:
            return
        bad = ~np.isfinite(p.pos).all(axis=1) | ~np.isfinite(vel).all(axis=1)
        if self.eos.evolves_energy:
            bad |= ~(u > 0) & (p.ptype == GAS)
        if bad.any():
            idx = np.flatnonzero(bad)
            what = "non-finite position/velocity" if not np.isfinite(p.pos[idx[0]]).all() or \
                not np.isfinite(vel[idx[0]]).all() else "non-positive or non-finite thermal energy"
            raise SimulationError(
                f"{what} for {idx.size} particles at time={self.t:.6g} cycle={self.cycle} "
                f"(first: particle {int(idx[0])})",
                state={"particles": idx, "position": p.pos[idx], "velocity": vel[idx], "u": u[idx]},
            )

    def update_derivatives(self, vel: np.ndarray | None = None, u: np.ndarray | None = None,
                           alpha: np.ndarray | None = None) -> None:
        """Recompute h, densities, pressures and all time derivatives at the current positions."""
        p, o, k = self.particles, self.options, self.kernel
        vel = p.vel if vel is None else vel
        u = p.u if u is None else u
        alpha = p.alpha if alpha is None else alpha
        self._check_state(vel, u)
        _, length, per = self._box_arrays
        gas = np.flatnonzero(p.ptype == GAS)
        all_gas = gas.size == len(p)
        self.acc[:] = 0.0
        if gas.size:
            sel = (lambda a: a) if all_gas else (lambda a: np.ascontiguousarray(a[gas]))
            pos_g, mass_g, vel_g, u_g, alpha_g = sel(p.pos), sel(p.mass), sel(vel), sel(u), sel(alpha)
            h_g = p.h if all_gas else sel(p.h)
            out = {name: getattr(self, name) if all_gas else sel(getattr(self, name)) for name in _DERIVED}
            nl = self._smoothing_lengths(pos_g, mass_g, h_g, out["rho"], out["omega"])
            pressure_sound_speed(self.eos.kind, self.eos.cs0, self.eos.gamma, self.eos.r0, self.eos.q,
                                 out["rho"], u_g, pos_g, out["P"], out["cs"])
            for module in self.modules:
                module.adjust_pressure(self, None if all_gas else gas, out["rho"], u_g, out["P"], out["cs"])
            form = FORCE_FORMS[o.force]
            if form == GASOLINE2:
                if o.gasoline2_f == "wadsley":
                    gasoline2_correction(pos_g, mass_g, h_g, out["rho"], nl.index, nl.count, k.shape,
                                         k.radius, length, per, out["fcorr"])
                else:
                    np.divide(1.0, out["omega"], out=out["fcorr"])
            packed = packed_table(len(gas))
            pack_particles(pos_g, vel_g, mass_g, h_g, out["rho"], out["omega"], out["P"], out["cs"],
                           alpha_g, u_g, out["fcorr"], k.norm, k.ndim, form, packed)
            hydro_forces(packed, nl.index, nl.count, k.shape, k.radius, length, per, form, o.beta, o.alpha_u,
                         self.eos.evolves_energy, out["acc"], out["dudt"], out["divv"], out["curlv"], out["vsig"])
            if self.evolves_alpha:
                morris_monaghan_rate(alpha_g, out["divv"], h_g, out["cs"], o.alpha_min, o.alpha_max,
                                     o.switch_decay, out["dalpha"])
            if not all_gas:
                p.h[gas] = h_g
                for name in _DERIVED:
                    getattr(self, name)[gas] = out[name]
            self.last_neighbours = nl
        if self.external.active:
            self.external.add(p.pos, self.acc, self.phi)
        for module in self.modules:
            module.add_derivatives(self, vel, u)
        if count_invalid(self.acc, self.acc, self.dudt, p.ptype, False) == 0:
            self._valid = True
            return
        bad = ~np.isfinite(self.acc).all(axis=1) | ~np.isfinite(self.dudt)
        if bad.any():
            idx = np.flatnonzero(bad)
            raise SimulationError(
                f"non-finite acceleration or du/dt for {idx.size} particles at time={self.t:.6g} "
                f"cycle={self.cycle} (first: particle {int(idx[0])})",
                state={"particles": idx, "position": p.pos[idx], "acc": self.acc[idx], "rho": self.rho[idx]},
            )
        self._valid = True

    def _ensure(self) -> None:
        if not self._valid:
            self.update_derivatives()

    # ------------------------------------------------------------------ run-loop protocol
    def timestep(self) -> float:
        """Largest stable step: Courant (eq. 2.13, :math:`C_{\\rm cour} h_a/v_{{\\rm sig},a}` with the
        largest pair signal speed of each particle) and acceleration (eq. 2.14) criteria of
        :mod:`dustygas.physics.timestep`, and any :attr:`timestep_limits` (eq. 2.15 for drag)."""
        self._ensure()
        if self.options.fixed_dt > 0:
            return self.options.fixed_dt
        h, o = self.particles.h, self.options
        return min_timestep(courant_timestep(h, self.vsig, o.c_cour),
                            acceleration_timestep(h, self.acc, o.c_force, axis=1),
                            *(limit(self) for limit in self.timestep_limits))

    def advance(self, dt: float) -> None:
        """One kick-drift-kick step of length ``dt`` (:mod:`dustygas.sph.integrator`)."""
        o = self.options
        if o.reorder_every and self.cycle % o.reorder_every == 0:
            self.reorder(self.finder.spatial_order(self.particles.pos, self.particles.h))
        self._ensure()
        p = self.particles
        lo, length, per = self._box_arrays
        eu, ea = self.eos.evolves_energy, self.evolves_alpha
        kick(p.vel, self.acc, p.u, self.dudt, p.alpha, self.dalpha, 0.5 * dt, eu, ea, o.alpha_min, o.alpha_max)
        for module in self.modules:
            module.kick(self, 0.5 * dt, False)
        vel_pred = np.empty_like(p.vel)
        u_pred = np.empty_like(p.u)
        alpha_pred = np.empty_like(p.alpha)
        drift_and_predict(p.pos, p.vel, self.acc, p.u, self.dudt, p.alpha, self.dalpha, p.h, self.divv, dt,
                          self.box.ndim, lo, length, per, eu, ea, o.alpha_min, o.alpha_max,
                          vel_pred, u_pred, alpha_pred)
        gone = self.external.accreted(p.pos)
        if gone.size:
            keep = np.setdiff1d(np.arange(len(p)), gone)
            self._accrete(gone)
            p = self.particles
            vel_pred, u_pred, alpha_pred = vel_pred[keep], u_pred[keep], alpha_pred[keep]
        for module in self.modules:
            module.predict(self, dt)
        divv_old = self.divv.copy() if o.switch == "cullen-dehnen" else None  # (after any accretion)
        self.update_derivatives(vel_pred, u_pred, alpha_pred)
        kick(p.vel, self.acc, p.u, self.dudt, p.alpha, self.dalpha, 0.5 * dt, eu, ea, o.alpha_min, o.alpha_max)
        for module in self.modules:
            module.kick(self, 0.5 * dt, True)
        if divv_old is not None:
            gas = p.ptype == GAS
            cullen_dehnen_alpha(p.alpha, np.where(gas, self.divv, 0.0), np.where(gas, divv_old, 0.0),
                                self.curlv, p.h, self.cs, dt, o.alpha_min, o.alpha_max, o.switch_decay)
        self.t += dt
        self.cycle += 1

    def reorder(self, order: np.ndarray) -> None:
        """Store the particles (and everything derived from them) in the order ``order``."""
        self.particles = self.particles.take(order)
        for name in _DERIVED:
            setattr(self, name, np.ascontiguousarray(getattr(self, name)[order]))

    def _accrete(self, gone: np.ndarray) -> None:
        p = self.particles
        m = p.mass[gone]
        self.accreted_mass += float(m.sum())
        self.accreted_momentum += (m[:, None] * p.vel[gone]).sum(axis=0)
        self.accreted_angular_momentum += (m[:, None] * np.cross(p.pos[gone], p.vel[gone])).sum(axis=0)
        keep = np.setdiff1d(np.arange(len(p)), gone)
        self.particles = p.take(keep)
        for name in _DERIVED:
            setattr(self, name, np.ascontiguousarray(getattr(self, name)[keep]))

    def history(self) -> dict[str, float]:
        """Mass, momentum, angular momentum (about the origin) and energies, star's share included."""
        self._ensure()
        p = self.particles
        m = p.mass
        mom = (m[:, None] * p.vel).sum(axis=0) + self.accreted_momentum
        ang = (m[:, None] * np.cross(p.pos, p.vel)).sum(axis=0) + self.accreted_angular_momentum
        ekin = 0.5 * float(np.sum(m * np.einsum("ij,ij->i", p.vel, p.vel)))
        etherm = float(np.sum(m * p.u)) if self.eos.evolves_energy else 0.0
        epot = float(np.sum(m * self.phi)) if self.external.active else 0.0
        out = {"mass": float(m.sum()) + self.accreted_mass, "n_particles": float(len(p))}
        for i, ax in enumerate("xyz"):
            out[f"momentum_{ax}"] = float(mom[i])
            out[f"angular_momentum_{ax}"] = float(ang[i])
        out.update(kinetic_energy=ekin, thermal_energy=etherm, potential_energy=epot,
                   total_energy=ekin + etherm + epot)
        for module in self.modules:
            module.history(self, out)
        return out

    def messages(self) -> list[str]:
        """Log lines of the modules (warnings, events) since the last call; the run loop logs them."""
        return [line for module in self.modules for line in module.messages()]

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        self._ensure()
        p = self.particles
        arrays = {"pos": p.pos, "vel": p.vel, "mass": p.mass, "h": p.h, "rho": self.rho, "u": p.u,
                  "P": self.P, "alpha": p.alpha, "pid": p.pid, "ptype": p.ptype}
        arrays.update({f"extra/{k}": v for k, v in p.extra.items()})
        return {k: np.array(v) for k, v in arrays.items()}, snapshot_attrs(self)

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays = {f"particles/{k}": np.array(v) for k, v in self.particles.arrays().items()}
        arrays.update({f"derived/{name}": np.array(getattr(self, name)) for name in _DERIVED})
        arrays["accreted_momentum"] = self.accreted_momentum.copy()
        arrays["accreted_angular_momentum"] = self.accreted_angular_momentum.copy()
        attrs = {**snapshot_attrs(self), "accreted_mass": self.accreted_mass, "derivatives_valid": int(self._valid),
                 "options": str(asdict(self.options))}
        for module in self.modules:
            attrs.update({f"module_{module.name}_{k}": v for k, v in module.state().items()})
        return arrays, attrs

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        self.particles = ParticleSet.from_arrays(
            {k[len("particles/"):]: v for k, v in arrays.items() if k.startswith("particles/")})
        for name in _DERIVED:
            setattr(self, name, np.array(arrays[f"derived/{name}"]))
        self.accreted_momentum = np.array(arrays["accreted_momentum"])
        self.accreted_angular_momentum = np.array(arrays["accreted_angular_momentum"])
        self.accreted_mass = float(attrs["accreted_mass"])
        self._valid = bool(attrs["derivatives_valid"])
        for module in self.modules:
            prefix = f"module_{module.name}_"
            module.restore_state({k[len(prefix):]: v for k, v in attrs.items() if k.startswith(prefix)})

    # ------------------------------------------------------------------ convenience
    def mean_neighbours(self) -> float:
        """Mean number of neighbours within the kernel support at the last evaluation."""
        nl = self.last_neighbours
        return math.nan if nl is None else float(nl.count.mean())
