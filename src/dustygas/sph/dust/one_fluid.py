"""One-fluid dust: mixture particles carrying a dust fraction (thesis §2.2 and §3.2).

Every SPH particle is a parcel of the dust-gas mixture: mass :math:`m`, total density
:math:`\\rho` (eq. 3.1), barycentric velocity, gas thermal energy :math:`u`, and the dust fraction
:math:`\\epsilon = \\rho_d/\\rho` (eq. 2.7). The gas pressure is that of the gas density
:math:`\\rho_g = (1-\\epsilon)\\rho` (:meth:`OneFluidDust.adjust_pressure`), the ordinary SPH force
then gives :math:`-\\nabla P/\\rho` (eq. 2.9c), and this module adds the dust terms of
:mod:`~dustygas.sph.dust.one_fluid_kernels`:

* ``model = "terminal-velocity"`` (thesis eqs. 2.10-2.11, Price & Laibe 2015): the relative
  velocity is not evolved; the dust fraction diffuses with the flux :math:`\\epsilon t_s\\nabla P`;
* ``model = "full"`` (thesis eq. 2.9, Laibe & Price 2014a,b): the relative velocity
  :math:`\\Delta\\mathbf v = \\mathbf v_d - \\mathbf v_g` (the thesis's :math:`\\mathbf w`) is evolved too,
  with explicit drag (:math:`\\Delta t \\le C_{\\rm drag} t_s`, eq. 2.15).

The dust exchange between neighbours is ``arithmetic`` (thesis eq. 3.4) or ``upwind`` (eqs.
3.15-3.17); the evolved variable is :math:`\\epsilon` or, for the terminal-velocity model,
:math:`S = \\sqrt{\\rho\\epsilon}` (Ballabio et al. 2018), which cannot become negative. Stopping
times come from a :class:`~dustygas.sph.dust.drag_law.DragLaw`; with Epstein drag each particle
may carry its own grain size, advected with the exchanged dust and grown or fragmented locally
(:mod:`~dustygas.sph.dust.grain_size`).

Time step (besides Courant and acceleration): the dust-fraction criterion ``c_eps`` -- the
diffusion limit :math:`\\Delta t \\le C_\\epsilon h^2/(\\epsilon t_s c_s^2)` of Price & Laibe (2015)
for the terminal-velocity model, and for both models
:math:`\\Delta t \\le C_\\epsilon\\,\\epsilon_a/\\sum_b|\\dot\\epsilon_{ab}|` so that no particle can give away
more dust than it holds in one step with the upwind exchange (whose outflow is proportional to
:math:`\\epsilon_a`; ``c_eps = 0`` switches both off, as in the thesis's CHANGA runs).

**Clamping** (thesis §3.2.4) is off unless asked for. With ``clamp = True`` a dust fraction that
leaves :math:`[\\epsilon_{\\rm floor}, \\epsilon_{\\rm ceiling}]` after a step is set to the bound; every
such event is counted and the dust mass it created or destroyed is summed (history columns
``clamp_events``, ``clamp_mass_created``, ``clamp_mass_destroyed``; a log line when it happens).
Without clamping a negative dust fraction is kept (and shows in ``min_dust_fraction``).

Total dust mass :math:`\\sum_a m_a\\epsilon_a` is conserved to round-off by the exchange (and
reported as ``dust_mass``); with :math:`S` the exchange conserves :math:`\\sum_a m_a S_a^2/\\rho_a` only in
the time-continuous limit (a step of :math:`S` changes :math:`S^2` by :math:`\\Delta t^2\\dot S^2` too) and the
compression term :math:`-\\tfrac12 S\\nabla\\cdot\\mathbf v` only as far as the summed density follows
:math:`\\nabla\\cdot\\mathbf v`: the price of a dust fraction that cannot become negative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import SetupError
from ..modules import SPHModule
from ..particles import GAS
from .drag_law import DragLaw
from .grain_size import GrainGrowth, advect_sizes, enforce_minimum_size
from .one_fluid_kernels import FULL, TERMINAL_VELOCITY, one_fluid_rates

__all__ = ["OneFluidOptions", "OneFluidDust", "ONE_FLUID_MODELS", "EXCHANGES", "VARIABLES"]

ONE_FLUID_MODELS = ("terminal-velocity", "full")
EXCHANGES = ("upwind", "arithmetic")
VARIABLES = ("dust-fraction", "sqrt-rho-eps")

# particles.extra names
EPS, SQRT, DEPS, DV, DDV, TS, SIZE, DSIZE = ("dust_fraction", "sqrt_rho_eps", "ddust_dt", "delta_v",
                                             "ddelta_v_dt", "stopping_time", "grain_size", "dgrain_size_dt")
IN, INS, OUT = "dust_inflow", "dust_inflow_size", "dust_outflow"
DRAG, HEAT = "drag_ddelta_v_dt", "drag_heating"


@dataclass(frozen=True)
class OneFluidOptions:
    """Choices of the one-fluid module (module docstring)."""

    model: str = "terminal-velocity"
    exchange: str = "upwind"
    variable: str = "dust-fraction"
    drag: DragLaw = field(default_factory=DragLaw)
    c_eps: float = 0.3
    c_drag: float = 0.9
    clamp: bool = False
    eps_floor: float = 0.0
    eps_ceiling: float = 1.0
    hold_gas: bool = False
    growth: GrainGrowth | None = None

    def __post_init__(self) -> None:
        checks = [
            (self.model in ONE_FLUID_MODELS, f"model must be one of {', '.join(ONE_FLUID_MODELS)}"),
            (self.exchange in EXCHANGES, f"exchange must be one of {', '.join(EXCHANGES)}"),
            (self.variable in VARIABLES, f"variable must be one of {', '.join(VARIABLES)}"),
            (not (self.variable == "sqrt-rho-eps" and (self.model == "full" or self.exchange == "upwind")),
             "the sqrt(rho eps) variable is implemented for the terminal-velocity model with the arithmetic "
             "exchange (Ballabio et al. 2018)"),
            (self.c_eps >= 0 and self.c_drag > 0, "need c_eps >= 0 and c_drag > 0"),
            (0.0 <= self.eps_floor < self.eps_ceiling <= 1.0, "need 0 <= eps_floor < eps_ceiling <= 1"),
            (self.growth is None or self.drag.kind == "epstein", "grain growth needs Epstein drag"),
        ]
        for ok, msg in checks:
            if not ok:
                raise SetupError(f"one-fluid dust: {msg}")


class OneFluidDust(SPHModule):
    """One-fluid dust on mixture particles (module docstring).

    Parameters
    ----------
    options
        :class:`OneFluidOptions`.
    dust_fraction
        Initial :math:`\\epsilon` per particle (or one value).
    delta_v
        Initial :math:`\\mathbf v_d - \\mathbf v_g` per particle, ``(N, 3)`` (full model; default zero).
    grain_size
        Initial grain radius per particle (Epstein drag; default ``options.drag.grain_size``).
    """

    name = "one_fluid"

    def __init__(self, options: OneFluidOptions, dust_fraction, delta_v=None, grain_size=None):
        self.options = options
        self._init = (dust_fraction, delta_v, grain_size)
        self.full = options.model == "full"
        self.sqrt_variable = options.variable == "sqrt-rho-eps"
        self.tracks_size = options.drag.needs_sizes
        self._pred: dict[str, np.ndarray] | None = None
        self._eps_eval: np.ndarray | None = None
        self.clamp_events = 0
        self.clamp_mass_created = 0.0
        self.clamp_mass_destroyed = 0.0
        self._last_clamp_log = -1
        self._messages: list[str] = []

    # ------------------------------------------------------------------ set-up
    def attach(self, engine) -> None:
        p = engine.particles
        n = len(p)
        if np.any(p.ptype != GAS):
            raise SetupError("one-fluid dust: every particle must be a mixture (gas-type) particle")
        eps0, dv0, s0 = self._init
        eps = np.array(np.broadcast_to(np.asarray(eps0, dtype=np.float64), (n,)))
        if np.any(eps < 0) or np.any(eps >= 1) or not np.all(np.isfinite(eps)):
            raise SetupError("one-fluid dust: initial dust fractions must lie in [0, 1)")
        ex = p.extra
        ex.setdefault(EPS, eps)
        ex.setdefault(DEPS, np.zeros(n))
        ex.setdefault(TS, np.zeros(n))
        for name in (IN, INS, OUT):
            ex.setdefault(name, np.zeros(n))
        if self.full:
            dv = np.zeros((n, 3)) if dv0 is None else np.array(np.broadcast_to(dv0, (n, 3)), dtype=np.float64)
            ex.setdefault(DV, dv)
            ex.setdefault(DDV, np.zeros((n, 3)))
            ex.setdefault(DRAG, np.zeros((n, 3)))
            ex.setdefault(HEAT, np.zeros(n))
        if self.tracks_size:
            s = np.full(n, self.options.drag.grain_size) if s0 is None else \
                np.array(np.broadcast_to(np.asarray(s0, dtype=np.float64), (n,)))
            if np.any(s <= 0):
                raise SetupError("one-fluid dust: grain sizes must be > 0")
            ex.setdefault(SIZE, s)
            ex.setdefault(DSIZE, np.zeros(n))
        engine.timestep_limits.append(self.timestep)

    # ------------------------------------------------------------------ evaluation
    def _field(self, engine, name: str) -> np.ndarray:
        if self._pred is not None and name in self._pred:
            return self._pred[name]
        return engine.particles.extra[name]

    def adjust_pressure(self, engine, gas, rho, u, P, cs) -> None:
        if self.sqrt_variable:
            if SQRT not in engine.particles.extra:  # first evaluation: S = sqrt(rho eps) from the initial eps
                engine.particles.extra[SQRT] = np.sqrt(rho * engine.particles.extra[EPS])
            S = self._field(engine, SQRT)
            eps = S * S / rho
        else:
            eps = self._field(engine, EPS)
        self._eps_eval = eps
        P *= 1.0 - eps  # gas pressure from rho_g = (1 - eps) rho; c_s is the gas sound speed

    def add_derivatives(self, engine, vel, u) -> None:
        p, o, k = engine.particles, self.options, engine.kernel
        ex = p.extra
        eps = self._eps_eval
        size = self._field(engine, SIZE) if self.tracks_size else np.zeros(1)
        ts = o.drag.one_fluid_stopping_time(engine.rho, eps, engine.cs, size if self.tracks_size else None)
        ex[TS] = ts
        if self.full:
            dv = self._field(engine, DV)
            Q = (1.0 - 2.0 * eps) * np.einsum("ij,ij->i", dv, dv)
            ddv = ex[DDV]
        else:
            dv, Q, ddv = np.zeros((1, 3)), np.zeros(1), np.zeros((1, 3))
        heat = engine.eos.evolves_energy
        nl = engine.last_neighbours
        _, length, per = engine._box_arrays
        sqrt_field = self._field(engine, SQRT) if self.sqrt_variable else np.zeros(1)
        one_fluid_rates(p.pos, vel, p.mass, p.h, engine.rho, engine.omega, engine.P, u, eps, sqrt_field, ts,
                        dv, Q, size, nl.index, nl.count, k.shape, k.norm, k.ndim, length, per,
                        FULL if self.full else TERMINAL_VELOCITY, o.exchange == "upwind", self.sqrt_variable,
                        heat, self.tracks_size, ex[DEPS], ddv, engine.acc, engine.dudt, ex[IN], ex[INS], ex[OUT])
        if self.sqrt_variable:
            ex[DEPS] -= 0.5 * sqrt_field * engine.divv  # -S div(v)/2
        if heat:
            engine.dudt /= 1.0 - eps  # the energy equations give (1 - eps) du/dt
        if self.full:
            np.divide(-dv, ts[:, None], out=ex[DRAG])  # drag (explicit)
            ddv += ex[DRAG]
            if heat:
                ex[HEAT] = eps * np.einsum("ij,ij->i", dv, dv) / ts  # also in dudt (from the pair pass)
        if self.tracks_size and o.growth is not None:
            ex[DSIZE] = o.growth.rate(size, eps * engine.rho, ts, engine.cs)
        if o.hold_gas:
            engine.acc[:] = 0.0

    # ------------------------------------------------------------------ time integration
    def _advance_fields(self, ex: dict, dt: float, out: dict) -> None:
        """``out[name] = ex[name] + dt * rate`` for every evolved field (sizes: eq. 3.14 and growth)."""
        o = self.options
        if self.tracks_size:
            s = advect_sizes(ex[SIZE], ex[EPS], ex[IN], ex[INS], ex[OUT], dt)
            if o.growth is not None:
                s = s + dt * ex[DSIZE]
                enforce_minimum_size(s, o.growth.min_size)
            out[SIZE] = s
        key = SQRT if self.sqrt_variable else EPS
        out[key] = ex[key] + dt * ex[DEPS]
        if self.full:
            out[DV] = ex[DV] + dt * ex[DDV]

    def predict(self, engine, dt: float) -> None:
        self._pred = {}
        self._advance_fields(engine.particles.extra, 0.5 * dt, self._pred)

    def kick(self, engine, dt: float, final: bool) -> None:
        ex = engine.particles.extra
        new: dict[str, np.ndarray] = {}
        self._advance_fields(ex, dt, new)
        for name, value in new.items():
            ex[name][...] = value
        if self.full and engine.eos.evolves_energy:
            # Drag heating = the work of the drag on the relative velocity over this kick, at the mean of
            # the old and new relative velocities: -eps (1 - eps) dt a_d . (dv_old + dv_new)/2 per unit
            # mass. When the drag acts alone (the dustybox) this is the exact loss of eps (1 - eps) |dv|^2/2;
            # the base kick already added dt * eps |dv|^2 / t_s (times 1 - eps).
            a_d = ex[DRAG]
            dv_mid = ex[DV] - 0.5 * dt * ex[DDV]
            eps = ex[EPS]
            engine.particles.u += -eps * dt * np.einsum("ij,ij->i", a_d, dv_mid) - dt * ex[HEAT]
        if not final:
            return
        self._pred = None
        if self.sqrt_variable:
            ex[EPS][...] = ex[SQRT] ** 2 / engine.rho
        if self.options.clamp:
            self._clamp(engine)

    def _clamp(self, engine) -> None:
        o, p = self.options, engine.particles
        ex = p.extra
        key = SQRT if self.sqrt_variable else EPS
        eps = ex[EPS]
        low, high = eps < o.eps_floor, eps > o.eps_ceiling
        n = int(low.sum() + high.sum())
        if n == 0:
            return
        created = float(np.sum(p.mass[low] * (o.eps_floor - eps[low])))
        destroyed = float(np.sum(p.mass[high] * (eps[high] - o.eps_ceiling)))
        eps[low] = o.eps_floor
        eps[high] = o.eps_ceiling
        if key == SQRT:
            ex[SQRT][...] = np.sqrt(eps * engine.rho)
        self.clamp_events += n
        self.clamp_mass_created += created
        self.clamp_mass_destroyed += destroyed
        if self._last_clamp_log < 0 or engine.cycle + 1 - self._last_clamp_log >= 100:
            self._last_clamp_log = engine.cycle + 1
            self._messages.append(
                f"dust-fraction clamp: {n} particles set to [{o.eps_floor:g}, {o.eps_ceiling:g}] at cycle "
                f"{engine.cycle + 1}; so far {self.clamp_events} events, dust mass created "
                f"{self.clamp_mass_created:.6g}, destroyed {self.clamp_mass_destroyed:.6g}")

    # ------------------------------------------------------------------ time step
    def timestep(self, engine) -> float:
        o, p = self.options, engine.particles
        ex = p.extra
        dt = math.inf
        if self.full:
            dt = min(dt, o.c_drag * float(np.min(ex[TS])))
        if o.c_eps > 0:
            eps = np.maximum(self.dust_fractions(engine), 0.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                out = ex[OUT]
                pos = out > 0
                if o.exchange == "upwind" and pos.any():  # outflow is proportional to eps_a: a finite limit
                    dt = min(dt, o.c_eps * float(np.min(eps[pos] / out[pos])))
                if not self.full:
                    d = eps * ex[TS] * engine.cs**2
                    big = d > 0
                    if big.any():
                        dt = min(dt, o.c_eps * float(np.min(p.h[big] ** 2 / d[big])))
        if self.tracks_size and o.growth is not None:
            dt = min(dt, o.growth.timestep(ex[SIZE], ex[DSIZE]))
        return dt

    # ------------------------------------------------------------------ diagnostics
    def dust_fractions(self, engine) -> np.ndarray:
        """Current :math:`\\epsilon` of every particle (:math:`S^2/\\rho` for the square-root variable)."""
        ex = engine.particles.extra
        return ex[SQRT] ** 2 / engine.rho if self.sqrt_variable else ex[EPS]

    def dust_mass(self, engine) -> float:
        """:math:`\\sum_a m_a\\epsilon_a`."""
        return float(np.sum(engine.particles.mass * self.dust_fractions(engine)))

    def history(self, engine, out: dict[str, float]) -> None:
        p = engine.particles
        eps = self.dust_fractions(engine)
        out["dust_mass"] = float(np.sum(p.mass * eps))
        out["min_dust_fraction"] = float(eps.min())
        out["max_dust_fraction"] = float(eps.max())
        if engine.eos.evolves_energy:
            etherm = float(np.sum(p.mass * (1.0 - eps) * p.u))
            out["total_energy"] += etherm - out["thermal_energy"]
            out["thermal_energy"] = etherm
        if self.full:
            dv = p.extra[DV]
            erel = 0.5 * float(np.sum(p.mass * eps * (1.0 - eps) * np.einsum("ij,ij->i", dv, dv)))
            out["relative_kinetic_energy"] = erel
            out["kinetic_energy"] += erel
            out["total_energy"] += erel
        if self.tracks_size:
            s = p.extra[SIZE]
            out["mean_grain_size"] = float(np.sum(p.mass * eps * s) / max(np.sum(p.mass * eps), 1e-300))
            out["min_grain_size"] = float(s.min())
        if self.options.clamp:
            out["clamp_events"] = float(self.clamp_events)
            out["clamp_mass_created"] = self.clamp_mass_created
            out["clamp_mass_destroyed"] = self.clamp_mass_destroyed

    def messages(self) -> list[str]:
        out, self._messages = self._messages, []
        return out

    def state(self) -> dict[str, Any]:
        return {"clamp_events": self.clamp_events, "clamp_mass_created": self.clamp_mass_created,
                "clamp_mass_destroyed": self.clamp_mass_destroyed, "last_clamp_log": self._last_clamp_log}

    def restore_state(self, state: dict[str, Any]) -> None:
        if state:
            self.clamp_events = int(state["clamp_events"])
            self.clamp_mass_created = float(state["clamp_mass_created"])
            self.clamp_mass_destroyed = float(state["clamp_mass_destroyed"])
            self._last_clamp_log = int(state["last_clamp_log"])
