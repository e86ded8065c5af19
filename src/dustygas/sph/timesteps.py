"""Hierarchical (block) individual time steps with pairwise kicks: exactly momentum-conserving SPH for disks.

Orbital periods across a disk from 5 to 200 au differ by :math:`40^{3/2} \\approx 250`, so one global
step wastes most of the work on the outer disk. As in GASOLINE and Phantom (Price et al. 2018,
Sect. 2.3.4) each particle :math:`a` takes steps :math:`\\Delta t_a = \\Delta t_{\\rm block}/2^{k_a}` on a
binary hierarchy of *levels* :math:`k_a`; the block ends when every particle is synchronised.
Between sub-steps **all** particles drift; a particle is *active* at the times that are multiples of
its step, where its density and forces are evaluated.

**Pairwise kicks.** Each pair interaction (pressure, viscosity, drag) is integrated with its own
kick-drift-kick step, the *pair step* :math:`\\tau_{ab} = \\min(\\Delta t_a, \\Delta t_b)`: at every
sub-step where one of the pair is active, the pair force :math:`\\mathbf f_{ab}` is evaluated once
and applied to *both* particles, closing the pair's last step (the time elapsed since the pair was
last evaluated minus the half step it was then opened with) and opening the next with half the new
pair step, :math:`m_a\\Delta\\mathbf v_a = -m_b\\Delta\\mathbf v_b`. With the global drift this is the
nested (RESPA-like) splitting :math:`K_{\\rm slow}(\\tau/2)[K_{\\rm fast}(\\tau/4)D(\\tau/2)K_{\\rm fast}(\\tau/4)]^2K_{\\rm slow}(\\tau/2)`:
second order and time-symmetric, and since every pair term is central and applied
antisymmetrically, linear and angular momentum are conserved to round-off (about the star, whose
force is central) -- which the usual scheme, each particle kicked with its own step by a force
its slower neighbours feel at other times, does not do. An inactive neighbour of an active particle
is kicked by its share of their pair; its own density, pressure and smoothing length are those of
its last evaluation, exactly as both sides of the pair see them.

**External force.** The star's gravity is a one-particle term, cheap to evaluate, so each
particle has a second, faster level for it, set by :math:`C_{\\rm force}\\sqrt{h/|\\mathbf a_{\\rm ext}|}`
(Phantom likewise sub-cycles external forces), while its SPH level follows the SPH criteria only:
Courant with the largest pair signal speed (thesis eq. 2.13) and the SPH and drag accelerations
(eq. 2.14).

**Drag.** The drag between a dust particle and a gas particle is one more pair term: its pair step
is the smaller of the two, so a strongly coupled dust particle, limited by
:math:`\\Delta t \\le C_{\\rm drag} t_s` (eq. 2.15), takes short steps and kicks its gas neighbours at
that cadence, but the gas keeps its own steps.

**Levels.** At each activation a particle moves to a faster level at once and to a slower one by one
level at a time (Makino 1991); it is next active at the next multiple of its step, so a step that
begins between two multiples (after a wake-up or a slow-down) is shortened to the next one, and the
particles of a level are active together with every faster one. The limiter of Saitoh & Makino
(2009) keeps neighbouring gas particles within ``limiter`` levels: slower neighbours of an active
particle are *woken* at the next sub-step (their step ends early; the elapsed-time closing above
keeps every pair consistent). At the end of a block every particle is active: the next block length
is the largest wanted step (at most ``dt_max``) and every level is chosen afresh. The velocities held
between run-loop steps are the synchronised ones; the opening kicks of the next block are kept in a
*pending* array, part of the checkpoint, so a restart is bit-identical. Particles that come within
the star's accretion radius are accreted at once (mass, momentum and angular momentum go to the
star; their pairs were opened for both particles and are never closed) and removed at the end of
the block.

**Costs.** A sub-step costs :math:`O(|S|)` for the active set :math:`S` plus an :math:`O(N)` drift,
schedule and refit of the k-d tree (:mod:`~dustygas.sph.active_search`); the tree is rebuilt
from scratch when at least ``rebuild_fraction`` of the particles are active. ``work_units`` counts
the particle updates (active particles summed over sub-steps) of the last block, the figure Phantom
reports as well.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import SetupError, SimulationError
from .active import (active_densities, active_hydro, kick_active, kick_external, kick_passive, limit_levels,
                     pack_hydro, reverse_rows)
from .active_search import DEAD, active_search, drift_and_accrete, leaf_of_particles, refit_tree, schedule
from .block_physics import BlockPhysics
from .block_state import BlockState
from .density import H_NEEDS_NEIGHBOURS, H_NOT_CONVERGED
from .dust.grain_size import GrainGrowth, enforce_minimum_size
from .dust.two_fluid import TwoFluidOptions
from .engine import SPHOptions
from .eos import EquationOfState, pressure_sound_speed
from .external import ExternalForces
from .forces import FORCE_FORMS
from .kdtree import build_tree
from .kernels import get_kernel
from .neighbours import Box
from .particles import DUST, GAS, ParticleSet

__all__ = ["BlockStepOptions", "BlockStepEngine", "TICKS_LOG2"]

#: a block is 2**TICKS_LOG2 ticks; a particle on level k steps every 2**(TICKS_LOG2 - k) ticks
TICKS_LOG2 = 40


@dataclass(frozen=True)
class BlockStepOptions:
    """Choices of the block time stepping (module docstring).

    Attributes
    ----------
    individual
        Individual (hierarchical) steps; ``False``: every particle takes the smallest step.
    max_level
        Deepest level: at most :math:`2^{\\rm max\\_level}` sub-steps per block.
    dt_max
        Longest block (0: no limit).
    rebuild_fraction
        Rebuild the k-d tree from scratch at sub-steps with at least this fraction of the
        particles active (otherwise refit its boxes).
    limiter
        Neighbouring gas particles' levels differ by at most this much (Saitoh & Makino 2009);
        slower neighbours of an active particle are woken (negative: no limiter).
    """

    individual: bool = True
    max_level: int = 24
    dt_max: float = 0.0
    rebuild_fraction: float = 0.25
    limiter: int = 2

    def __post_init__(self) -> None:
        if not (1 <= self.max_level <= TICKS_LOG2):
            raise SetupError(f"time steps: max_level must be in [1, {TICKS_LOG2}], not {self.max_level}")
        if not (self.dt_max >= 0.0 and 0.0 < self.rebuild_fraction <= 1.0):
            raise SetupError("time steps: need dt_max >= 0 and 0 < rebuild_fraction <= 1")


class BlockStepEngine(BlockState, BlockPhysics):
    """Gas and (optionally) two-fluid dust particles under SPH, drag and external forces, advanced with
    block individual time steps and pairwise kicks (module docstring).

    Parameters
    ----------
    particles, box, eos, options, external
        As for :class:`~dustygas.sph.SPHEngine`; the equation of state must be (locally) isothermal
        and the viscosity constant (``switch = "none"``).
    drag
        Two-fluid drag between the ``DUST`` and ``GAS`` particles (explicit, no reconstruction).
    growth
        Local growth and fragmentation of the dust particles' grains (thesis eqs. 3.6-3.7; Epstein
        drag): :math:`ds/dt` from the dust density and the gas density and sound speed interpolated at
        each dust particle, with its own orbital frequency, integrated like a velocity (closing and
        opening half steps at each activation) and limiting the step to :math:`C_{\\rm size}\\,s/|ds/dt|`.
    steps
        :class:`BlockStepOptions`.
    diagnostics
        Callables ``f(engine, row)`` adding entries to every history row.
    """

    work_label = "particle-updates"

    def __init__(self, particles: ParticleSet, box: Box, eos: EquationOfState, options: SPHOptions = SPHOptions(),
                 external: ExternalForces = ExternalForces(), drag: TwoFluidOptions | None = None,
                 growth: GrainGrowth | None = None, steps: BlockStepOptions = BlockStepOptions(),
                 diagnostics: tuple = ()):
        if eos.evolves_energy:
            raise SetupError("individual time steps: only (locally) isothermal gas is supported")
        if options.switch != "none":
            raise SetupError("individual time steps: use sph.switch = none (constant artificial viscosity)")
        if options.force == "gasoline2" and options.gasoline2_f != "gradh":
            raise SetupError("individual time steps: the GASOLINE2 force needs gasoline2_f = gradh")
        if drag is not None and drag.reconstruction not in ("none", "gas"):
            raise SetupError("individual time steps: dust.reconstruction must be none or gas")
        if growth is not None and (drag is None or not drag.drag.needs_sizes or not external.star_gm):
            raise SetupError("grain growth needs Epstein drag (grain sizes) and a star (orbital frequencies)")
        self.box, self.eos, self.options, self.external, self.drag = box, eos, options, external, drag
        self.growth = growth
        self.steps = steps
        self.diagnostics = tuple(diagnostics)
        self.kernel = get_kernel(options.kernel, box.ndim)
        self.hfact = options.hfact or self.kernel.default_hfact
        self._box_arrays = box.arrays()
        self._gradients = drag is not None and drag.reconstruction == "gas"  # the velocity gradients' only reader
        self._check(particles)
        box.wrap(particles.pos)
        self._init_state(particles)

    def _check(self, p: ParticleSet) -> None:
        for name in ("pos", "vel", "mass", "h", "alpha"):
            arr = getattr(p, name)
            if not np.all(np.isfinite(arr)):
                raise SetupError(f"initial {name} of particle {int(np.argwhere(~np.isfinite(arr))[0][0])} is not finite")
        if np.any(p.mass <= 0) or np.any(p.h <= 0):
            raise SetupError("particles need positive masses and smoothing lengths")
        if not np.isin(p.ptype, (GAS, DUST)).all():
            raise SetupError("individual time steps: particles must be gas or dust")
        if (p.ptype == DUST).any() and self.drag is None:
            raise SetupError("dust particles need a drag law (drag=TwoFluidOptions(...))")
        if self.drag is not None and self.drag.drag.needs_sizes and "grain_size" not in p.extra:
            p.extra["grain_size"] = np.full(len(p), self.drag.drag.grain_size)

    # ------------------------------------------------------------------ tree and search
    def _build_tree(self) -> None:
        p = self.particles
        self._tree = build_tree(p.pos, self._h_src, self.box.ndim, 12)
        order, start, end, child = self._tree[:4]
        self._leaf_of, self._leaves = leaf_of_particles(order, start, end, child, len(p))

    def _refit(self) -> None:
        order, start, end, child, lo, hi, hmax = self._tree
        refit_tree(self.particles.pos, self._h_src, order, start, end, child, self._leaves, lo, hi, hmax)

    def _search(self, act, h_query):
        """Rows of the active particles (``act`` in tree order): flat buffers with room for 1.25 times
        each particle's last count (slots that overflow are searched again)."""
        p, k = self.particles, self.kernel
        order, start, end, child, lo, hi, hmax = self._tree
        _, length, per = self._box_arrays
        room = [self._room(self._n_same[act]), self._room(self._n_cross[act])]
        todo = np.arange(act.size)
        starts = [np.zeros(act.size, np.int64), np.zeros(act.size, np.int64)]
        counts = [np.zeros(act.size, np.int64), np.zeros(act.size, np.int64)]
        buffers = [np.empty(0, np.int64), np.empty(0, np.int64)]
        while todo.size:
            sub = act[todo]
            leaf = self._leaf_of[sub]
            group = np.flatnonzero(np.r_[True, leaf[1:] != leaf[:-1], True])
            local, bufs, cn = [], [], []
            for j in range(2):
                r = room[j][todo]
                local.append(np.cumsum(r) - r)
                bufs.append(np.empty(int(r.sum()), np.int64))
                cn.append(np.empty(todo.size, np.int64))
            active_search(p.pos, self._h_src, p.ptype, sub, group, h_query[todo], order, start, end, child, lo, hi,
                          hmax, k.radius, length, per, local[0], room[0][todo], bufs[0], cn[0], local[1],
                          room[1][todo], bufs[1], cn[1])
            for j in range(2):
                starts[j][todo] = local[j] + buffers[j].size
                buffers[j] = np.concatenate([buffers[j], bufs[j]]) if buffers[j].size else bufs[j]
                counts[j][todo] = cn[j]
            over = (cn[0] > room[0][todo]) | (cn[1] > room[1][todo])
            for j in range(2):
                room[j][todo] = np.maximum(room[j][todo], cn[j])
            todo = todo[over]
        self._n_same[act], self._n_cross[act] = counts[0], counts[1]
        return starts[0], buffers[0], counts[0], starts[1], buffers[1], counts[1]

    @staticmethod
    def _room(last):
        return last + last // 4 + 8

    # ------------------------------------------------------------------ one evaluation
    def _evaluate(self, act: np.ndarray, tick: int, tick_dt: float, rebuild: bool):
        """Densities and forces of the active particles at the current positions; returns the rows,
        the per-entry pair forces and the per-slot external accelerations (for the kicks)."""
        p, o, k = self.particles, self.options, self.kernel
        _, length, per = self._box_arrays
        elapsed = (tick - self.last_tick[act]) * tick_dt
        h_guess = p.h[act] * np.exp(np.clip(elapsed * self.divv[act] / k.ndim, -0.5, 0.5))
        self._h_src[act] = h_guess * (1.0 + o.neighbour_buffer)
        if rebuild:
            self._build_tree()
            mask = np.zeros(len(p), np.bool_)
            mask[act] = True
            act = self._tree[0][mask[self._tree[0]]]
            h_guess = self._h_src[act] / (1.0 + o.neighbour_buffer)
        else:
            self._refit()
        h_query = self._h_src[act]
        for attempt in range(8):
            if attempt:
                self._h_src[act] = h_query
                self._refit()
            same_o, same_i, same_n, cross_o, cross_i, cross_n = self._search(act, h_query)
            n = act.size
            h_new, rho, omega = np.empty(n), np.empty(n), np.empty(n)
            status, iters = np.empty(n, np.int8), np.empty(n, np.int32)
            active_densities(act, p.pos, p.mass, h_guess, h_query, same_o, same_i, same_n, k.shape, k.norm, k.ndim,
                             self.hfact, length, per, o.h_tolerance, o.h_max_iterations, h_new, rho, omega,
                             status, iters)
            grow = status == H_NEEDS_NEIGHBOURS
            if not grow.any():
                break
            h_query = np.where(grow, 1.5 * h_query, h_query)
            h_guess = h_new  # the last iterates: the roots, or the edge of the list for ``grow``
        else:
            bad = act[grow]
            raise SimulationError(f"smoothing-length iteration failed for {bad.size} particles at time={self.t:.6g} "
                                  f"(first: particle {int(bad[0])})", state={"particles": bad, "position": p.pos[bad]})
        if (status == H_NOT_CONVERGED).any():
            bad = act[status == H_NOT_CONVERGED]
            raise SimulationError(f"smoothing-length iteration did not converge for {bad.size} particles at "
                                  f"time={self.t:.6g} (first: particle {int(bad[0])})",
                                  state={"particles": bad, "position": p.pos[bad]})
        p.h[act], self.rho[act], self.omega[act] = h_new, rho, omega
        self._h_src[act] = h_new
        gas = act[p.ptype[act] == GAS]
        if gas.size:
            P, cs = np.empty(gas.size), np.empty(gas.size)
            e = self.eos
            pressure_sound_speed(e.kind, e.cs0, e.gamma, e.r0, e.q, self.rho[gas], p.u[gas], p.pos[gas], P, cs)
            self.P[gas], self.cs[gas] = P, cs
        self._slot[act] = np.arange(act.size)
        passive, ptr, e_slot, e_pos, e_kind = reverse_rows(act, self._slot, p.ptype, same_o, same_i, same_n, cross_o,
                                                           cross_i, cross_n)
        rows = np.concatenate([act, passive])
        elapsed = ((tick - self.last_tick[rows]) * tick_dt)[:, None]
        if self._implicit:  # stiff drag: predict with the other forces; dust as it is (kicked by every pair)
            vel_pred = self.v_sync[rows] + elapsed * self.acc_other[rows]
            dust_rows = p.ptype[rows] == DUST
            vel_pred[dust_rows] = p.vel[rows[dust_rows]]
        else:
            vel_pred = self.v_sync[rows] + elapsed * self.acc[rows]
        acc = np.zeros((n, 3))
        pair_s = np.zeros(same_i.size)
        if gas.size:
            pack_hydro(rows, p.pos, vel_pred, p.mass, p.h, self.rho, self.omega, self.P, self.cs, p.alpha, p.u,
                       k.norm, k.ndim, FORCE_FORMS[o.force], self._packed)
            divv, curlv, vsig, grad = np.empty(n), np.empty(n), np.empty(n), np.empty((n, 9))
            active_hydro(act, p.ptype, self._packed, same_o, same_i, same_n, k.shape, k.radius, length, per,
                         FORCE_FORMS[o.force], o.beta, self._gradients, pair_s, acc, divv, curlv, vsig, grad)
            self.divv[act], self.curlv[act], self.vsig[act], self.grad_v[act] = divv, curlv, vsig, grad
        acc_ext = self._external(act)
        self.acc_other[act] = acc + acc_ext
        ev = (act, same_o, same_i, same_n, pair_s, cross_o, cross_i, cross_n, np.zeros((cross_i.size, 3)), acc_ext,
              passive, ptr, e_slot, e_pos, e_kind)
        self._rows = (rows, vel_pred)
        if self.drag is not None and not self._implicit:
            acc += self._drag(ev, None)
        if self.growth is not None:
            self._grow(act, cross_o, cross_i, cross_n)
        if not np.isfinite(acc).all():
            bad = act[~np.isfinite(acc).all(axis=1)]
            raise SimulationError(f"non-finite acceleration for {bad.size} particles at time={self.t:.6g}",
                                  state={"particles": bad, "position": p.pos[bad]})
        self.dt_want[act] = self._wanted_steps(act, acc)
        if self.growth is not None:
            d = act[p.ptype[act] == DUST]
            self.dt_want[d] = np.minimum(self.dt_want[d], self.growth.timesteps(p.extra["grain_size"][d],
                                                                                 self._size_rate[d]))
        self.acc[act] = acc + acc_ext
        self._slot[act] = -1
        return ev

    # ------------------------------------------------------------------ levels and kicks
    def _levels_for(self, dt_want: np.ndarray) -> np.ndarray:
        with np.errstate(divide="ignore"):
            k = np.maximum(np.ceil(np.log2(self.dt_block / dt_want) - 1e-12), 0.0)
        if not np.all(k <= self.steps.max_level):
            raise SimulationError(f"a particle needs a step below dt_block/2^{self.steps.max_level} at time="
                                  f"{self.t:.6g} (smallest wanted step {float(dt_want.min()):.4g})")
        return k.astype(np.int64)

    def _plan_block(self, ev) -> None:
        """Block length and the levels of every particle (all synchronised) from their wanted steps."""
        want, want_ext = self.dt_want, self.dt_want_ext
        if not (np.all(want > 0) and np.all(want_ext > 0)):
            raise SimulationError(f"non-positive time step at time={self.t:.6g}")
        if self.steps.individual:
            finite = want[np.isfinite(want)]
            dt = float(finite.max()) if finite.size else math.inf
        else:
            dt = float(min(want.min(), want_ext.min()))
        if self.steps.dt_max > 0:
            dt = min(dt, self.steps.dt_max)
        if not (dt > 0 and math.isfinite(dt)):
            raise SimulationError(f"invalid block length {dt!r} at time={self.t:.6g} (set steps.dt_max)")
        self.dt_block = dt
        self._set_levels(ev)

    def _set_levels(self, ev) -> None:
        """Levels of every particle for a block of length ``dt_block`` (all synchronised)."""
        if self.steps.individual:
            self.level = self._levels_for(self.dt_want)
            self._limit(ev)
            self.ext_level = np.maximum(self.level, self._levels_for(self.dt_want_ext))
        else:
            self.level = np.zeros(len(self.particles), np.int64)
            self.ext_level = self.level.copy()

    @staticmethod
    def _next_level(old, want):
        """Faster at once, slower by one level at a time."""
        return np.where(want >= old, want, np.maximum(want, old - 1))

    def _until_next(self, level, tick: int, final: bool) -> np.ndarray:
        """Time from ``tick`` to the next activation on ``level``: the next multiple of the level's step
        (a full step when ``tick`` is one already; less for a particle woken early, or moved to a slower
        level, between two of its multiples)."""
        if final:
            tick = 0
        span = np.int64(1) << (TICKS_LOG2 - level)
        return ((tick // span + 1) * span - tick) * (self.dt_block / float(np.int64(1) << TICKS_LOG2))

    def _rebin(self, ev, ext_only, tick: int) -> None:
        """New levels of the particles active at ``tick`` (SPH, then external-force levels)."""
        if not self.steps.individual:
            return
        act = ev[0]
        if act.size:
            self.level[act] = self._next_level(self.level[act], self._levels_for(self.dt_want[act]))
            self._limit(ev)
        both = np.concatenate([act, ext_only])
        new = self._next_level(self.ext_level[both], self._levels_for(self.dt_want_ext[both]))
        self.ext_level[both] = np.maximum(new, self.level[both])

    def _limit(self, ev) -> None:
        if self.steps.limiter < 0 or not self.steps.individual:
            return
        act, same_o, same_i, same_n = ev[:4]
        self._slot[act] = np.arange(act.size)
        limit_levels(act, self.particles.ptype, self.level, same_o, same_i, same_n, self._slot, self.steps.limiter,
                     self._wake)
        self._slot[act] = -1

    def _kick(self, ev, ext_only, acc_ext_only, tick: int, tick_dt: float, final: bool) -> None:
        act, same_o, same_i, same_n, pair_s, cross_o, cross_i, cross_n, pair_f, acc_ext, passive, ptr, e_slot, \
            e_pos, e_kind = ev
        p = self.particles
        _, length, per = self._box_arrays
        tau_new = self._tau.copy()
        tau_new[act] = self._until_next(self.level[act], tick, final)
        if self._implicit:  # the drag averaged over the coming pair steps, now that they are known
            self.acc[act] += self._drag(ev, tau_new)
        both = np.concatenate([act, ext_only])
        ext_new = self._tau_ext.copy()
        ext_new[both] = self._until_next(self.ext_level[both], tick, final)
        close = np.empty((act.size, 3))
        open_ = np.empty((act.size, 3))
        kick_active(act, p.ptype, p.pos, p.mass, self._tau, tau_new, self.last_tick, tick, tick_dt, same_o, same_i,
                    same_n, pair_s, cross_o, cross_i, cross_n, pair_f, acc_ext, self._tau_ext, ext_new, self.last_ext,
                    length, per, close, open_)
        if passive.size:
            kick_passive(passive, ptr, e_slot, e_pos, e_kind, act, p.pos, p.mass, self._tau, tau_new, self.last_tick,
                         tick, tick_dt, pair_s, pair_f, length, per, p.vel)
        if ext_only.size:
            kick_external(ext_only, acc_ext_only, self._tau_ext, ext_new, self.last_ext, tick, tick_dt, p.vel)
        if self.growth is not None:  # grain sizes, integrated like the velocities
            d = act[p.ptype[act] == DUST]
            size = p.extra["grain_size"]
            size[d] += ((tick - self.last_tick[d]) * tick_dt - 0.5 * self._tau[d]) * self._size_rate[d]
            opening = 0.5 * tau_new[d] * self._size_rate[d]
            if final:
                self._pending_size[d] = opening
            else:
                size[d] += opening
            enforce_minimum_size(size, self.growth.min_size)
        p.vel[act] += close
        self.v_sync[act] = p.vel[act]
        if final:
            self.pending[act] = open_
        else:
            p.vel[act] += open_
        self._tau, self._tau_ext = tau_new, ext_new
        self.last_tick[act] = tick
        self.last_ext[both] = tick

    # ------------------------------------------------------------------ run-loop protocol
    def _evaluate_all(self, dt: float | None = None) -> None:
        """Everything active at a synchronised state with no step to close (a fresh start, or a block of
        length ``dt`` other than the planned one): forces, levels and the pending opening kicks."""
        n = len(self.particles)
        self._tau[:] = 0.0
        self._tau_ext[:] = 0.0
        self.last_tick[:] = 0
        self.last_ext[:] = 0
        self.pending[:] = 0.0
        self._pending_size[:] = 0.0
        self.v_sync = self.particles.vel.copy()
        self._h_src = self.particles.h.copy()
        ev = self._evaluate(np.arange(n), 0, 0.0, rebuild=True)
        if dt is None:
            self._plan_block(ev)
        else:
            self.dt_block = dt
            self._set_levels(ev)
        self._kick(ev, np.empty(0, np.int64), np.zeros((0, 3)), 0, 0.0, final=True)
        self.last_tick[:] = 0
        self.last_ext[:] = 0
        self.started = True

    def reset(self) -> None:
        """Forget the planned block: the next call evaluates every force afresh (after the set-up
        changed positions or velocities)."""
        self.started = False
        self.pending[:] = 0.0

    def timestep(self) -> float:
        """Length of the next block (planned at the end of the previous one)."""
        if not self.started:
            self._evaluate_all()
        return self.dt_block

    def advance(self, dt: float) -> None:
        """One block of length ``dt`` (the planned one, or shorter at the end of a run)."""
        if not dt > 0:
            raise SimulationError(f"invalid step {dt!r} at time={self.t:.6g}")
        if not self.started:
            self._evaluate_all()
        if abs(dt - self.dt_block) > 1e-12 * self.dt_block:
            self._evaluate_all(dt)
        self._advance(dt)

    def _advance(self, dt: float) -> None:
        o = self.options
        self._h_src = self.particles.h.copy()
        self._build_tree()
        if o.reorder_every and self.cycle % o.reorder_every == 0:  # store the particles in tree order
            order = self._tree[0]
            self._reorder(order)
            self._tree = (np.arange(len(order)),) + self._tree[1:]
            self._leaf_of = self._leaf_of[order]
        p = self.particles
        p.vel += self.pending
        self.pending[:] = 0.0
        if self.growth is not None:
            p.extra["grain_size"] += self._pending_size
            enforce_minimum_size(p.extra["grain_size"], self.growth.min_size)
            self._pending_size[:] = 0.0
        top = np.int64(1) << TICKS_LOG2
        tick_dt = self.dt_block / float(top)
        tick = np.int64(0)
        updates = substeps = 0
        racc = self.external.accretion_radius if self.external.star_gm else 0.0
        while tick < top:
            kmax = int(self.ext_level[p.ptype != DEAD].max())
            span = np.int64(1) << (TICKS_LOG2 - kmax)
            dtick = (tick // span + 1) * span - tick  # to the next activation of the finest level
            drift_and_accrete(p.pos, p.vel, p.mass, p.ptype, float(dtick * tick_dt), racc, self._accreted)
            tick += dtick
            substeps += 1
            final = tick == top
            if final:
                self._remove_dead()
                p = self.particles
                self._h_src = p.h.copy()
            act, ext_only = schedule(self._tree[0] if not final else np.arange(len(p)), self.level, self.ext_level,
                                     self._wake, p.ptype, tick, TICKS_LOG2)
            self._wake[:] = False
            acc_ext_only = self._external(ext_only)
            if act.size == 0:  # only external-force steps end here
                self._rebin((act,), ext_only, int(tick))
                self._kick_external_only(ext_only, acc_ext_only, int(tick), tick_dt)
                continue
            rebuild = final or act.size >= self.steps.rebuild_fraction * len(p)
            ev = self._evaluate(act, int(tick), tick_dt, rebuild)
            act = ev[0]
            updates += act.size
            if final:
                self.t += dt
                self._plan_block(ev)
            else:
                self._rebin(ev, ext_only, int(tick))
            self._kick(ev, ext_only, acc_ext_only, int(tick), tick_dt, final)
        self.last_tick[:] = 0
        self.last_ext[:] = 0
        self.cycle += 1
        self.updates = updates
        self.substeps = substeps
        self.total_updates += updates
        self._check_state()

    def _kick_external_only(self, ext_only, acc_ext_only, tick: int, tick_dt: float) -> None:
        ext_new = self._tau_ext.copy()
        ext_new[ext_only] = self._until_next(self.ext_level[ext_only], tick, False)
        kick_external(ext_only, acc_ext_only, self._tau_ext, ext_new, self.last_ext, tick, tick_dt, self.particles.vel)
        self._tau_ext = ext_new
        self.last_ext[ext_only] = tick
