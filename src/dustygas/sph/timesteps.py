"""Hierarchical (block) individual time steps with pairwise kicks: exactly momentum-conserving SPH for disks.

Orbital periods across a disk from 5 to 200 au differ by :math:`40^{3/2} \\approx 250`, so one global
step wastes most of the work on the outer disk. As in GASOLINE and Phantom (Price et al. 2018,
Sect. 2.3.4) each particle :math:`a` takes steps :math:`\\Delta t_a = \\Delta t_{\\rm block}/2^{k_a}`
on a binary hierarchy of *levels* :math:`k_a`; the block ends when every particle is
synchronised. Between sub-steps **all** particles drift; a particle is *active* at the times that are
multiples of its step, where its density and forces are evaluated.

**Pairwise kicks.** Each pair interaction (pressure, viscosity, drag) is integrated with its own
kick-drift-kick step, the *pair step* :math:`\\tau_{ab} = \\min(\\Delta t_a, \\Delta t_b)`: at every
sub-step that ends one of its steps (i.e. where the faster particle of the pair is active), the
pair force :math:`\\mathbf f_{ab}` is evaluated once and applied to *both* particles, as the closing
half kick :math:`\\tau^{\\rm old}_{ab}/2` of the step that ends and the opening half kick
:math:`\\tau^{\\rm new}_{ab}/2` of the next, :math:`m_a\\Delta\\mathbf v_a = -m_b\\Delta\\mathbf v_b`. External
forces kick each particle with its own steps. With the global drift this is the nested
(RESPA-like) splitting :math:`K_{\\rm slow}(\\tau/2)[K_{\\rm fast}(\\tau/4)D(\\tau/2)K_{\\rm fast}(\\tau/4)]^2K_{\\rm slow}(\\tau/2)`:
second order and time-symmetric, and since every pair term is central and applied antisymmetrically,
linear and angular momentum are conserved to round-off (the star's force is central: angular
momentum about it), which the usual scheme -- each particle kicked with its own step by a force
that its slower neighbours receive at other times -- does not do. An inactive neighbour of an active
particle is kicked by its share of their pair; its own density, pressure and smoothing length are
those of its last evaluation, exactly as both sides of the pair see them.

**Drag.** The drag between a dust particle and a gas particle is one more pair term: its pair
step is the smaller of the two, so a strongly coupled dust particle, limited by
:math:`\\Delta t \\le C_{\\rm drag} t_s` (thesis eq. 2.15), takes short steps and kicks its gas
neighbours at that cadence, but the gas keeps its own (Courant and force) steps.

**Levels.** At each activation the criteria (thesis eqs. 2.13-2.15; Courant with the largest pair
signal speed, acceleration, drag) give a wanted step; the particle moves to a faster level at once,
to a slower one only by one level and only where the current time is a multiple of the slower step
(Makino 1991). At the end of a block every particle is active: the next block length is the largest
wanted step (at most ``dt_max``) and every level is chosen afresh. The velocities held between
run-loop steps are the synchronised ones (closing kicks applied); the opening kicks of the next
block are kept in a *pending* array, part of the checkpoint, so a restart is bit-identical.

**Costs.** A sub-step costs :math:`O(|S|)` for the active set :math:`S` plus an :math:`O(N)` drift and
refit of the k-d tree (:mod:`~dustygas.sph.active`); the tree is rebuilt from scratch when at least
``rebuild_fraction`` of the particles are active. ``work_units`` counts the particle updates (active
particles summed over sub-steps) of the last block, the figure Phantom reports as well.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numba
import numpy as np

from ..errors import SetupError, SimulationError
from .active import (NPACK, active_densities, active_drag, active_hydro, active_search, kick_active, kick_passive,
                     leaf_of_particles, limit_levels, pack_hydro, refit_tree, reverse_rows)
from .density import H_NEEDS_NEIGHBOURS, H_NOT_CONVERGED
from .dust.two_fluid import TwoFluidOptions
from .dust.two_fluid_kernels import pack
from .engine import PARALLEL_CHUNK, SPHOptions
from .eos import EquationOfState, pressure_sound_speed
from .external import ExternalForces
from .forces import FORCE_FORMS
from .kdtree import build_tree
from .kernels import get_kernel
from .neighbours import Box
from .particles import DUST, GAS, ParticleSet, count_invalid

__all__ = ["BlockStepOptions", "BlockStepEngine", "TICKS_LOG2"]

#: a block is 2**TICKS_LOG2 ticks; a particle on level k steps every 2**(TICKS_LOG2 - k) ticks
TICKS_LOG2 = 40
_FIELDS = ("rho", "omega", "P", "cs", "divv", "curlv", "vsig", "tmin", "dt_want", "phi")
_VECTORS = ("acc", "v_sync", "pending")


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


class BlockStepEngine:
    """Gas and (optionally) two-fluid dust particles under SPH, drag and external forces, advanced with
    block individual time steps and pairwise kicks (module docstring).

    Parameters
    ----------
    particles, box, eos, options, external
        As for :class:`~dustygas.sph.SPHEngine`; the equation of state must be (locally) isothermal
        and the viscosity constant (``switch = "none"``).
    drag
        Two-fluid drag between the ``DUST`` and ``GAS`` particles (explicit, no reconstruction).
    grain_size
        Grain radii of the dust particles (Epstein drag), one per particle or a scalar.
    steps
        :class:`BlockStepOptions`.
    diagnostics
        Callables ``f(engine, row)`` adding entries to every history row.
    """

    work_label = "particle-updates"

    def __init__(self, particles: ParticleSet, box: Box, eos: EquationOfState, options: SPHOptions = SPHOptions(),
                 external: ExternalForces = ExternalForces(), drag: TwoFluidOptions | None = None, grain_size=None,
                 steps: BlockStepOptions = BlockStepOptions(), diagnostics: tuple = ()):
        if eos.evolves_energy:
            raise SetupError("individual time steps: only (locally) isothermal gas is supported")
        if options.switch != "none":
            raise SetupError("individual time steps: use sph.switch = none (constant artificial viscosity)")
        if options.force == "gasoline2" and options.gasoline2_f != "gradh":
            raise SetupError("individual time steps: the GASOLINE2 force needs gasoline2_f = gradh")
        if drag is not None and (drag.reconstruction != "none" or drag.integration != "explicit"):
            raise SetupError("individual time steps: two-fluid drag must be explicit without reconstruction "
                             "(dust.reconstruction = none, dust.integration = explicit)")
        self.particles = particles
        self.box = box
        self.eos = eos
        self.options = options
        self.external = external
        self.drag = drag
        self.steps = steps
        self.diagnostics = tuple(diagnostics)
        self.kernel = get_kernel(options.kernel, box.ndim)
        self.hfact = options.hfact or self.kernel.default_hfact
        self._box_arrays = box.arrays()
        self.t = 0.0
        self.cycle = 0
        self.accreted_mass = 0.0
        self.accreted_momentum = np.zeros(3)
        self.accreted_angular_momentum = np.zeros(3)
        self.updates = len(particles)  # particle updates of the last block
        self.total_updates = 0
        self.substeps = 0  # sub-steps of the last block
        self.dt_block = 0.0
        self.started = False
        self._check(grain_size)
        box.wrap(particles.pos)
        n = len(particles)
        for name in _FIELDS:
            setattr(self, name, np.zeros(n))
        for name in _VECTORS:
            setattr(self, name, np.zeros((n, 3)))
        self.omega[:] = 1.0
        self.tmin[:] = math.inf
        self.level = np.zeros(n, np.int64)
        self.last_tick = np.zeros(n, np.int64)
        self._wake = np.zeros(n, np.bool_)
        self._packed = np.zeros((n, NPACK))
        self._n_same = np.full(n, 64, np.int64)  # last neighbour counts: room in the next search
        self._n_cross = np.zeros(n, np.int64)

    # ------------------------------------------------------------------ set-up
    def _check(self, grain_size) -> None:
        p = self.particles
        for name in ("pos", "vel", "mass", "h", "alpha"):
            arr = getattr(p, name)
            if not np.all(np.isfinite(arr)):
                raise SetupError(f"initial {name} of particle {int(np.argwhere(~np.isfinite(arr))[0][0])} is not finite")
        if np.any(p.mass <= 0) or np.any(p.h <= 0):
            raise SetupError("particles need positive masses and smoothing lengths")
        dust = p.ptype == DUST
        if dust.any() and self.drag is None:
            raise SetupError("dust particles need a drag law (drag=TwoFluidOptions(...))")
        if self.drag is not None and self.drag.drag.needs_sizes:
            s = self.drag.drag.grain_size if grain_size is None else grain_size
            p.extra.setdefault("grain_size", np.array(np.broadcast_to(np.asarray(s, np.float64), (len(p),))))
        if not np.isin(p.ptype, (GAS, DUST)).all():
            raise SetupError("individual time steps: particles must be gas or dust")

    @property
    def work_units(self) -> int:
        return int(self.updates)

    @property
    def n_levels(self) -> int:
        return int(self.level.max(initial=0)) + 1

    # ------------------------------------------------------------------ tree
    def _build_tree(self, h_src) -> None:
        p = self.particles
        self._tree = build_tree(p.pos, h_src, self.box.ndim, 12)
        order, start, end, child = self._tree[:4]
        self._leaf_of, self._leaves = leaf_of_particles(order, start, end, child, len(p))

    def _refit(self, h_src) -> None:
        order, start, end, child, lo, hi, hmax = self._tree
        refit_tree(self.particles.pos, h_src, order, start, end, child, self._leaves, lo, hi, hmax)

    def _search(self, act, h_query, h_src):
        """Rows of the active particles (``act`` in tree order) among all particles: flat buffers with
        room for 1.25 times each particle's last count (slots that overflow are searched again)."""
        p, k = self.particles, self.kernel
        order, start, end, child, lo, hi, hmax = self._tree
        _, length, per = self._box_arrays
        rows = []
        room = [self._room(self._n_same[act]), self._room(self._n_cross[act])]
        todo = np.arange(act.size)
        starts = [np.zeros(act.size, np.int64), np.zeros(act.size, np.int64)]
        counts = [np.zeros(act.size, np.int64), np.zeros(act.size, np.int64)]
        buffers = [np.empty(0, np.int64), np.empty(0, np.int64)]
        while todo.size:
            sub = act[todo]
            leaf = self._leaf_of[sub]
            group = np.flatnonzero(np.r_[True, leaf[1:] != leaf[:-1], True]).astype(np.int64)
            st, bufs, cn = [], [], []
            for j in range(2):
                r = room[j][todo]
                st.append(np.concatenate([[0], np.cumsum(r)[:-1]]).astype(np.int64) + buffers[j].size)
                bufs.append(np.empty(int(r.sum()), np.int64))
                cn.append(np.empty(todo.size, np.int64))
            active_search(p.pos, h_src, p.ptype, sub, group, h_query[todo], order, start, end, child, lo, hi, hmax,
                          k.radius, length, per, st[0] - buffers[0].size, room[0][todo], bufs[0], cn[0],
                          st[1] - buffers[1].size, room[1][todo], bufs[1], cn[1])
            for j in range(2):
                buffers[j] = np.concatenate([buffers[j], bufs[j]])
                starts[j][todo] = st[j]
                counts[j][todo] = cn[j]
            over = (cn[0] > room[0][todo]) | (cn[1] > room[1][todo])
            for j in range(2):
                room[j][todo] = np.maximum(room[j][todo], cn[j])
            todo = todo[over]
        self._n_same[act], self._n_cross[act] = counts[0], counts[1]
        return starts[0], buffers[0], counts[0], starts[1], buffers[1], counts[1]

    @staticmethod
    def _room(last):
        return (last + last // 4 + 8).astype(np.int64)

    # ------------------------------------------------------------------ one sub-step
    def _active_order(self, active_mask) -> np.ndarray:
        order = self._tree[0]
        return order[active_mask[order]]

    def _evaluate(self, act: np.ndarray, tick: int, tick_dt: float, rebuild: bool):
        """Densities and forces of the active particles at the current positions: returns the rows,
        the per-entry pair forces and the per-slot total and external accelerations."""
        p, o, k = self.particles, self.options, self.kernel
        _, length, per = self._box_arrays
        # predicted smoothing lengths (dh/dt = h div v / d) of the active particles, per particle
        h_pred = p.h.copy()
        elapsed = (tick - self.last_tick[act]) * tick_dt
        h_pred[act] *= np.exp(np.clip(elapsed * self.divv[act] / k.ndim, -0.5, 0.5))
        h_src = p.h.copy()
        h_src[act] = h_pred[act] * (1.0 + o.neighbour_buffer)
        if rebuild:
            self._build_tree(h_src)
            mask = np.zeros(len(p), np.bool_)
            mask[act] = True
            act = self._active_order(mask)
        else:
            self._refit(h_src)
        h_guess = h_pred[act]
        h_query = h_src[act]
        status = None
        for attempt in range(8):
            if attempt:
                h_src[act] = h_query
                self._refit(h_src)
            same_o, same_i, same_n, cross_o, cross_i, cross_n = self._search(act, h_query, h_src)
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
        gas = act[p.ptype[act] == GAS]
        if gas.size:
            P, cs = np.empty(gas.size), np.empty(gas.size)
            e = self.eos
            pressure_sound_speed(e.kind, e.cs0, e.gamma, e.r0, e.q, self.rho[gas], p.u[gas], p.pos[gas], P, cs)
            self.P[gas], self.cs[gas] = P, cs
        slot = np.full(len(p), -1, np.int64)
        slot[act] = np.arange(act.size)
        passive, ptr, e_slot, e_pos, e_kind = reverse_rows(act, slot, p.ptype, same_o, same_i, same_n, cross_o, cross_i,
                                                           cross_n, len(p))
        rows = np.concatenate([act, passive])
        elapsed = (tick - self.last_tick[rows]) * tick_dt
        vel_pred = self.v_sync[rows] + elapsed[:, None] * self.acc[rows]
        n = act.size
        acc = np.zeros((n, 3))
        pair_s = np.zeros(same_i.shape)
        if gas.size:
            pack_hydro(rows, p.pos, vel_pred, p.mass, p.h, self.rho, self.omega, self.P, self.cs, p.alpha, k.norm,
                       k.ndim, FORCE_FORMS[o.force], self._packed)
            divv, curlv, vsig = np.empty(n), np.empty(n), np.empty(n)
            active_hydro(act, p.ptype, self._packed, same_o, same_i, same_n, k.shape, k.radius, length, per,
                         FORCE_FORMS[o.force], o.beta, pair_s, acc, divv, curlv, vsig)
            self.divv[act], self.curlv[act], self.vsig[act] = divv, curlv, vsig
        pair_f = np.zeros(cross_i.shape + (3,))
        if self.drag is not None:
            acc_d = np.empty((n, 3))
            tmin = np.empty(n)
            table = self._drag_table(rows, vel_pred)
            d = self.drag
            c0 = d.drag.pair_factors(np.ones(1), np.ones(1), np.ones(1))[2]
            active_drag(act, p.ptype, table, cross_o, cross_i, cross_n, k.shape, k.ndim, length, per, c0,
                        d.form == "projected", d.drag_kernel == "gas", pair_f, acc_d, tmin)
            acc += acc_d
            self.tmin[act] = tmin
        acc_ext = np.zeros((n, 3))
        if self.external.active:
            phi = np.empty(n)
            self.external.add(p.pos[act], acc_ext, phi)
            self.phi[act] = phi
        acc += acc_ext
        if count_invalid(acc, acc, np.zeros(n), p.ptype[act], False):
            bad = act[~np.isfinite(acc).all(axis=1)]
            raise SimulationError(f"non-finite acceleration for {bad.size} particles at time={self.t:.6g}",
                                  state={"particles": bad, "position": p.pos[bad]})
        self.acc[act] = acc
        self.dt_want[act] = self._wanted_steps(act, acc)
        return (act, same_o, same_i, same_n, pair_s, cross_o, cross_i, cross_n, pair_f, acc_ext, passive, ptr, e_slot,
                e_pos, e_kind)

    def _drag_table(self, rows, vel_pred) -> np.ndarray:
        """The drag pair table (:func:`dustygas.sph.dust.two_fluid_kernels.drag_pair`) with current rows."""
        p, k = self.particles, self.kernel
        n = len(p)
        if getattr(self, "_dtable", None) is None or self._dtable.shape[0] != n:
            self._dtable = np.zeros((n, 11))
        law = self.drag.drag
        g = rows[p.ptype[rows] == GAS]
        d = rows[p.ptype[rows] == DUST]
        size = p.extra["grain_size"][d] if law.needs_sizes else None
        kg, kd, _ = law.pair_factors(self.rho[g], self.cs[g], self.rho[d], size)
        cnorm = k.norm_drag if self.drag.form == "projected" else k.norm
        hinv = 1.0 / p.h[rows]
        kk = np.empty(rows.size)
        is_gas = p.ptype[rows] == GAS
        kk[is_gas], kk[~is_gas] = kg, kd
        self._dtable[rows] = pack(p.pos[rows], vel_pred, p.mass[rows], hinv, cnorm * hinv**k.ndim, self.rho[rows], kk)
        return self._dtable

    def _wanted_steps(self, act, acc) -> np.ndarray:
        """Largest stable step of each active particle: Courant (gas, thesis eq. 2.13), acceleration
        (eq. 2.14) and explicit drag (dust, eq. 2.15)."""
        p, o = self.particles, self.options
        if o.fixed_dt > 0:
            return np.full(act.size, o.fixed_dt)
        h = p.h[act]
        amag = np.sqrt(np.einsum("ij,ij->i", acc, acc))
        with np.errstate(divide="ignore"):
            dt = o.c_force * np.sqrt(h / amag)
            gas = p.ptype[act] == GAS
            dt = np.where(gas, np.minimum(dt, o.c_cour * h / np.where(gas, self.vsig[act], 1.0)), dt)
            if self.drag is not None:
                dt = np.where(gas, dt, np.minimum(dt, self.drag.c_drag * self.tmin[act]))
        return dt

    # ------------------------------------------------------------------ levels and kicks
    def _levels_for(self, dt_block: float, dt_want: np.ndarray) -> np.ndarray:
        with np.errstate(divide="ignore"):
            k = np.ceil(np.log2(dt_block / dt_want) - 1e-12)
        k = np.maximum(k, 0.0)
        if not np.all(k <= self.steps.max_level):
            raise SimulationError(f"a particle needs a step below dt_block/2^{self.steps.max_level} at time="
                                  f"{self.t:.6g} (smallest wanted step {float(dt_want.min()):.4g})")
        return k.astype(np.int64)

    def _plan_block(self) -> None:
        """Levels of every particle for the next block (all synchronised) from their wanted steps."""
        want = self.dt_want
        if not np.all(want > 0):
            raise SimulationError(f"non-positive time step at time={self.t:.6g}")
        if self.steps.individual:
            dt = float(want[np.isfinite(want)].max(initial=0.0)) if np.isfinite(want).any() else 0.0
            if self.steps.dt_max > 0:
                dt = min(dt, self.steps.dt_max) if dt > 0 else self.steps.dt_max
            self.level = self._levels_for(dt, want)
        else:
            dt = float(want.min())
            if self.steps.dt_max > 0:
                dt = min(dt, self.steps.dt_max)
            self.level = np.zeros(len(want), np.int64)
        if not (dt > 0 and math.isfinite(dt)):
            raise SimulationError(f"invalid block length {dt!r} at time={self.t:.6g}")
        self.dt_block = dt

    def _rebin(self, ev, tick: int) -> None:
        """New levels of the active particles in the middle of a block (module docstring): faster at
        once, slower by one level, never off the hierarchy (the current time a multiple of the step),
        then the limiter, which also marks slow neighbours to be woken."""
        act = ev[0]
        old = self.level[act]
        want = self._levels_for(self.dt_block, self.dt_want[act]) if self.steps.individual else old
        aligned = TICKS_LOG2 - int(np.log2(tick & -tick)) if tick else 0
        new = np.where(want >= old, want, np.maximum(want, old - 1))
        self.level[act] = np.maximum(new, aligned)
        self._limit(ev)

    def _limit(self, ev) -> None:
        if self.steps.limiter < 0 or not self.steps.individual:
            return
        act, same_o, same_i, same_n = ev[:4]
        slot = np.full(len(self.particles), -1, np.int64)
        slot[act] = np.arange(act.size)
        limit_levels(act, self.particles.ptype, self.level, same_o, same_i, same_n, slot, self.steps.limiter,
                     self._wake)

    def _kick(self, ev, tau_new, final: bool, tick: int = 0, tick_dt: float = 0.0) -> None:
        act, same_o, same_i, same_n, pair_s, cross_o, cross_i, cross_n, pair_f, acc_ext, passive, ptr, e_slot, e_pos, \
            e_kind = ev
        p = self.particles
        _, length, per = self._box_arrays
        close = np.empty((act.size, 3))
        open_ = np.empty((act.size, 3))
        kick_active(act, p.ptype, p.pos, p.mass, self._tau, tau_new, self.last_tick, tick, tick_dt, same_o, same_i,
                    same_n, pair_s, cross_o, cross_i, cross_n, pair_f, acc_ext, length, per, close, open_)
        if passive.size:
            kick_passive(passive, ptr, e_slot, e_pos, e_kind, act, p.pos, p.mass, self._tau, tau_new, self.last_tick,
                         tick, tick_dt, pair_s, pair_f, length, per, p.vel)
        p.vel[act] += close
        self.v_sync[act] = p.vel[act]
        if final:
            self.pending[act] = open_
        else:
            p.vel[act] += open_

    # ------------------------------------------------------------------ run-loop protocol
    def _start(self) -> None:
        """First evaluation of a fresh run: everything active, no closing kicks."""
        n = len(self.particles)
        self._tau = np.zeros(n)
        self.v_sync = self.particles.vel.copy()
        act = np.arange(n)
        with numba.parallel_chunksize(PARALLEL_CHUNK):
            ev = self._evaluate(act, 0, 0.0, rebuild=True)
            self._plan_block()
            self._limit(ev)
            tau_new = self.dt_block * np.ldexp(1.0, -self.level)
            self._kick(ev, tau_new, final=True)
        self.last_tick[:] = 0
        self.started = True

    def reset(self) -> None:
        """Forget the planned block: the next call evaluates every force afresh (after the set-up
        changed positions or velocities)."""
        self.started = False
        self.pending[:] = 0.0

    def timestep(self) -> float:
        """Length of the next block (its levels are planned at the end of the previous one)."""
        if not self.started:
            self._start()
        return self.dt_block

    def advance(self, dt: float) -> None:
        """One block of length ``dt`` (the planned one, or shorter at the end of a run)."""
        if not self.started:
            self._start()
        with numba.parallel_chunksize(PARALLEL_CHUNK):
            self._advance(dt)

    def _advance(self, dt: float) -> None:
        p = self.particles
        if abs(dt - self.dt_block) > 1e-12 * self.dt_block:
            if not dt > 0:
                raise SimulationError(f"invalid step {dt!r}")
            self.pending[:] = 0.0  # re-plan for the shorter block: a fresh evaluation at this state
            self.dt_block = dt
            self.level = self._levels_for(dt, self.dt_want) if self.steps.individual else np.zeros(len(p), np.int64)
            self._tau = np.zeros(len(p))
            ev = self._evaluate(np.arange(len(p)), 0, 0.0, rebuild=True)
            self._limit(ev)
            self._kick(ev, dt * np.ldexp(1.0, -self.level), final=True)
        o = self.options
        self._build_tree(p.h)
        if o.reorder_every and self.cycle % o.reorder_every == 0:  # store particles in tree order
            order = self._tree[0]
            self._reorder(order)
            self._tree = (np.arange(len(order)),) + self._tree[1:]
            self._leaf_of = self._leaf_of[order]
            p = self.particles
        p.vel += self.pending
        self.pending[:] = 0.0
        top = np.int64(1) << TICKS_LOG2
        tick_dt = self.dt_block / float(top)
        self._tau = self.dt_block * np.ldexp(1.0, -self.level)
        self.last_tick[:] = 0
        tick = np.int64(0)
        updates = 0
        substeps = 0
        while tick < top:
            kmax = int(self.level.max())
            dtick = np.int64(1) << (TICKS_LOG2 - kmax)
            p.pos += (dtick * tick_dt) * p.vel
            tick += dtick
            substeps += 1
            final = tick == top
            accreted = self._accrete()
            p = self.particles
            active = ((tick % (np.int64(1) << (TICKS_LOG2 - self.level))) == 0) | self._wake
            self._wake[:] = False
            act = np.flatnonzero(active)
            rebuild = final or accreted or act.size >= self.steps.rebuild_fraction * len(p)
            if not rebuild:
                act = self._active_order(active)
            ev = self._evaluate(act, int(tick), tick_dt, rebuild)
            act = ev[0]
            updates += act.size
            if final:
                self.t += dt
                self._plan_block()
                self._limit(ev)
                tau_new = self.dt_block * np.ldexp(1.0, -self.level)
            else:
                self._rebin(ev, int(tick))
                tau_new = self._tau.copy()
                tau_new[act] = self.dt_block * np.ldexp(1.0, -self.level[act])
            self._kick(ev, tau_new, final, int(tick), tick_dt)
            self._tau = tau_new
            self.last_tick[act] = tick
        self.last_tick[:] = 0
        self.cycle += 1
        self.updates = updates
        self.substeps = substeps
        self.total_updates += updates
        self._check_state()

    def _check_state(self) -> None:
        p = self.particles
        if count_invalid(p.pos, p.vel, np.zeros(len(p)), p.ptype, False):
            bad = np.flatnonzero(~np.isfinite(p.pos).all(axis=1) | ~np.isfinite(p.vel).all(axis=1))
            raise SimulationError(f"non-finite position/velocity for {bad.size} particles at time={self.t:.6g} "
                                  f"cycle={self.cycle} (first: particle {int(bad[0])})",
                                  state={"particles": bad, "position": p.pos[bad], "velocity": p.vel[bad]})

    def _per_particle(self) -> list[str]:
        return list(_FIELDS) + list(_VECTORS) + ["level", "last_tick", "_tau", "_n_same", "_n_cross", "_wake"]

    def _reorder(self, order: np.ndarray) -> None:
        self.particles = self.particles.take(order)
        for name in self._per_particle():
            setattr(self, name, np.ascontiguousarray(getattr(self, name)[order]))

    def _accrete(self) -> bool:
        """Remove the particles inside the accretion radius (checked at every sub-step); their mass,
        momentum and angular momentum go to the star. Their pairs were opened for both particles and
        are never closed, so momentum stays conserved."""
        ext = self.external
        gone = ext.accreted(self.particles.pos)
        if not gone.size:
            return False
        p = self.particles
        m = p.mass[gone]
        self.accreted_mass += float(m.sum())
        self.accreted_momentum += (m[:, None] * p.vel[gone]).sum(axis=0)
        self.accreted_angular_momentum += (m[:, None] * np.cross(p.pos[gone], p.vel[gone])).sum(axis=0)
        keep = np.setdiff1d(np.arange(len(p)), gone)
        self._reorder(keep)
        self._packed = np.zeros((len(keep), NPACK))
        self._dtable = None
        return True

    def history(self) -> dict[str, float]:
        """Mass, momentum, angular momentum (about the star) and energies, accreted shares included, and
        the cost of the last block."""
        if not self.started:
            self._start()
        p = self.particles
        m = p.mass
        mom = (m[:, None] * p.vel).sum(axis=0) + self.accreted_momentum
        ang = (m[:, None] * np.cross(p.pos, p.vel)).sum(axis=0) + self.accreted_angular_momentum
        ekin = 0.5 * float(np.sum(m * np.einsum("ij,ij->i", p.vel, p.vel)))
        epot = float(np.sum(m * self.phi)) if self.external.active else 0.0
        out = {"mass": float(m.sum()) + self.accreted_mass, "n_particles": float(len(p))}
        for i, ax in enumerate("xyz"):
            out[f"momentum_{ax}"] = float(mom[i])
            out[f"angular_momentum_{ax}"] = float(ang[i])
        out.update(kinetic_energy=ekin, potential_energy=epot, total_energy=ekin + epot,
                   block_dt=self.dt_block, levels=float(self.n_levels), substeps=float(self.substeps),
                   updates=float(self.updates), total_updates=float(self.total_updates))
        for f in self.diagnostics:
            f(self, out)
        return out

    def _attrs(self) -> dict[str, Any]:
        return {"ndim": self.box.ndim, "box_lo": list(self.box.lo), "box_hi": list(self.box.hi),
                "periodic": [int(v) for v in self.box.periodic], "kernel": self.kernel.name,
                "hfact": self.hfact, "eos_kind": self.eos.kind, "gamma": self.eos.gamma}

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        if not self.started:
            self._start()
        p = self.particles
        arrays = {"pos": p.pos, "vel": p.vel, "mass": p.mass, "h": p.h, "rho": self.rho, "u": p.u, "P": self.P,
                  "alpha": p.alpha, "pid": p.pid, "ptype": p.ptype, "level": self.level}
        arrays.update({f"extra/{k}": v for k, v in p.extra.items()})
        return {k: np.array(v) for k, v in arrays.items()}, self._attrs()

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays = {f"particles/{k}": np.array(v) for k, v in self.particles.arrays().items()}
        names = self._per_particle() if self.started else list(_FIELDS) + list(_VECTORS) + ["level", "last_tick"]
        arrays.update({f"block/{name}": np.array(getattr(self, name)) for name in names})
        arrays["accreted_momentum"] = self.accreted_momentum.copy()
        arrays["accreted_angular_momentum"] = self.accreted_angular_momentum.copy()
        attrs = {**self._attrs(), "accreted_mass": self.accreted_mass, "started": int(self.started),
                 "dt_block": self.dt_block, "updates": self.updates, "total_updates": self.total_updates,
                 "substeps": self.substeps, "options": str(asdict(self.options)), "steps": str(asdict(self.steps))}
        return arrays, attrs

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        self.particles = ParticleSet.from_arrays(
            {k[len("particles/"):]: v for k, v in arrays.items() if k.startswith("particles/")})
        for key, value in arrays.items():
            if key.startswith("block/"):
                setattr(self, key[len("block/"):], np.array(value))
        self.accreted_momentum = np.array(arrays["accreted_momentum"])
        self.accreted_angular_momentum = np.array(arrays["accreted_angular_momentum"])
        self.accreted_mass = float(attrs["accreted_mass"])
        self.started = bool(attrs["started"])
        self.dt_block = float(attrs["dt_block"])
        self.updates, self.total_updates = int(attrs["updates"]), int(attrs["total_updates"])
        self.substeps = int(attrs["substeps"])
        self._packed = np.zeros((len(self.particles), NPACK))
        self._dtable = None
