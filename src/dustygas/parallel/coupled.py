"""The particle–gas engine over MPI ranks, with the run-loop protocol of one box.

:func:`distribute` turns a :class:`~dustygas.particles.coupling.ParticleGridEngine` a problem
has built (on every rank, the whole box: the initial state does not depend on the
decomposition) into a :class:`DistributedParticleEngine`: the mesh is cut along z into one
block per rank (layout ``(1, 1, P)``: a shear-periodic box cannot split x or y yet, and the
particles' halo and migration are along z), every rank keeps the gas of its block and the
particles whose cells lie in it (:class:`~dustygas.parallel.particles.BlockParticleEngine`).

Outputs are those of the serial engine by construction: rank 0 keeps the engine the problem
built (``whole``), into which the blocks' gas and the particles are gathered -- the particles
in the serial store order, by their cell at the last sort and their id -- so its
:meth:`history`, :meth:`snapshot` and :meth:`checkpoint` (whose re-sorts change the order as
they do in a serial run) are the serial ones; when they sort the particles, every block sorts
its own, so that the next exchange step meets them in the serial order. The state is gathered
once per step, whatever the outputs asked for. The checkpoint is the serial one and restarts on
any rank count (with z cuts chosen again for its particles).

The budgets are bit-identical too. Those that are sums over the step's particles or cells --
the momentum the particle terms gave (``particle_terms_impulse_*``), the gas terms' impulse,
the gas's radial mass and y-momentum budgets -- are running totals per row of cells ``(k, j)``
(or z plane), each summed in a fixed order by the block that holds the row
(:func:`~dustygas.particles.push.kick`, :mod:`dustygas.grid.budget`); rank 0 gathers the rows
and sums them as the serial engine does. What left through a z face is added up by the end
block of that face alone, what left through an x or y face by rank 0 from every block's leaving
particles (each a correctly rounded sum, :func:`~dustygas.particles.coupling.add_lost`). The
checkpoint holds the rows of the whole box: a restart on another rank count, with other z cuts,
goes on adding to the same rows.

Phase-one limits: self-gravity (a mesh acceleration) and gas terms on mesh fields are refused
(a first step for self-gravity: gather the density to rank 0, solve, scatter the potential --
the blocks already hold the field rows the particles gather); the initial state is built whole on every rank.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import UserError
from ..particles.outputs import impulse_rows_from
from ..particles.store import ParticleStore
from ..particles.terms import GasMeshAcceleration, MeshAcceleration
from .decomposition import balanced_cuts
from .gas import DistributedGridEngine
from .particles import BlockGas, BlockParticleEngine, z_blocks

__all__ = ["DistributedParticleEngine", "distribute", "PARTICLE_WEIGHT"]

#: the modelled cost of a particle relative to a cell in one coupled step, which the z cuts
#: balance: in the 3D box (32³, one particle per cell, one thread) the per-particle passes (two
#: deposits, gather and kick, sort, stencil, exchange, images) took 22 ms per step and the gas
#: 20 ms (benchmarks/RESULTS.md, 2026-12-02 13:45), so one particle costs about one cell
PARTICLE_WEIGHT = 1.0


def distribute(serial, comm=None) -> "DistributedParticleEngine":
    """The decomposed engine of the whole-box engine ``serial`` (on every rank; collective)."""
    return DistributedParticleEngine(serial, comm)


class DistributedParticleEngine:
    """A :class:`~dustygas.particles.coupling.ParticleGridEngine` split over the ranks (module doc)."""

    work_label = "zone-cycles"
    distributed = True

    def __init__(self, serial, comm=None):
        if comm is None:
            from .comm import world

            comm = world()
        self.comm = comm
        self.rank, self.size = comm.Get_rank(), comm.Get_size()
        if any(isinstance(t, MeshAcceleration) for t in serial.particle_terms) or any(
                isinstance(t, GasMeshAcceleration) for t in serial.gas_terms):
            raise UserError("self-gravity (a mesh acceleration) does not run on several MPI ranks yet: "
                            "run this problem with one process")
        mesh = serial.gas.mesh
        if mesh.shape[2] == 1:
            raise UserError(f"mpi ranks={self.size}: particles split the z axis only, and this mesh has nz = 1")
        self.serial_options = (serial.gas.options, dict(serial.options, mode=None), serial._sp,
                               serial.geometry.boundaries[2] in ("periodic", "shear-periodic"))
        self.min_rows = max(mesh.nghost, serial._R + 2)
        self.whole = serial if self.rank == 0 else None
        self.mesh = mesh
        self.work_units = mesh.ncells
        self._version = 0
        self._gathered = -1
        self._loads: list[int] = []
        self._messages: list[str] = []
        arrays, attrs = serial.checkpoint()
        self._build(arrays, attrs)
        self.t, self.cycle = serial.t, serial.cycle

    # ------------------------------------------------------------------ distribution
    def _rows_of(self, pos: np.ndarray, cuts: np.ndarray) -> np.ndarray:
        """The block (of ``cuts``) of each particle at ``pos`` (3, N): :func:`~.particles.z_blocks`."""
        pos = np.ascontiguousarray(pos, dtype=np.float64)
        n = pos.shape[1]
        out = np.zeros(n, dtype=np.int64)
        sp = self.serial_options[2]
        z_blocks(pos, n, sp.z0, sp.dz, int(cuts[-1]), cuts, np.zeros(n, dtype=np.int64), out)
        return out

    def _cuts(self, pos: np.ndarray) -> np.ndarray:
        """Block rows that balance the modelled work of a step: a row costs its cells plus
        :data:`PARTICLE_WEIGHT` times its particles (:func:`~.decomposition.balanced_cuts`)."""
        nx, ny, nz = self.mesh.shape
        rows = self._rows_of(pos, np.arange(nz + 1, dtype=np.int64))
        count = np.bincount(rows[rows >= 0], minlength=nz)[:nz]
        return np.asarray(balanced_cuts(nx * ny + PARTICLE_WEIGHT * count, self.size, self.min_rows), dtype=np.int64)

    def _build(self, arrays: dict, attrs: dict) -> None:
        """The blocks (gas, particles, drag source, budgets) of the whole-box state ``arrays``,
        with z cuts chosen from its particles."""
        gas_options, options, _, periodic_z = self.serial_options
        pos = np.asarray(arrays["particles/pos"])
        self.cuts = self._cuts(pos)
        self.gas = DistributedGridEngine(self.mesh, comm=self.comm, layout=(1, 1, self.size),
                                         z_cuts=tuple(int(c) for c in self.cuts), **gas_options)
        dec = self.gas.decomposition
        self.block = dec.coords(self.rank)[2]
        ranks = [dec.rank_of((0, 0, b)) for b in range(self.size)]
        owner = self._rows_of(pos, self.cuts)
        mine = (owner == self.block) | ((owner == -2) & (self.rank == 0))
        self.local = BlockParticleEngine(BlockGas(self.gas), self._particles(arrays, mine), self.comm, self.cuts,
                                         self.block, ranks, periodic_z, **options)
        if self.rank == 0:
            self.gas.whole = self.whole.gas
        self._restore_blocks(arrays, attrs)
        loads = np.bincount(owner[owner >= 0], minlength=self.size)
        nx, ny, _ = self.mesh.shape
        work = np.diff(self.cuts) * nx * ny + PARTICLE_WEIGHT * loads
        self._messages.append(f"mpi: z rows {' '.join(str(int(c)) for c in self.cuts)}; particles per rank "
                              f"{' '.join(str(int(x)) for x in loads)} (max/mean {_ratio(loads):.3f}); modelled "
                              f"work max/mean {_ratio(work):.3f}")

    @staticmethod
    def _particles(arrays: dict, sel: np.ndarray) -> ParticleStore:
        try:
            parts = {k: np.asarray(arrays[f"particles/{k}"]) for k in ("pos", "vel", "species", "pid", "mass")}
        except KeyError as exc:
            raise UserError(f"checkpoint has no particle array {exc}") from None
        return ParticleStore(parts["pos"][:, sel], parts["vel"][:, sel], parts["species"][sel], parts["pid"][sel],
                             parts["mass"][sel])

    def _restore_blocks(self, arrays: dict, attrs: dict) -> None:
        """The block of the gas and of the drag source, and (rank 0) the budgets, of a whole-box state."""
        self.gas.restore({k: v for k, v in arrays.items() if not k.startswith("particles/")}, attrs)
        loc = self.local
        k0, k1 = int(self.cuts[self.block]), int(self.cuts[self.block + 1])
        loc._have_source = "particles/gas_source" in arrays
        if loc._have_source:
            loc._source[...] = np.asarray(arrays["particles/gas_source"])[:, k0:k1]
        first = self.rank == 0
        lost = np.asarray(arrays["particles/lost"]) if "particles/lost" in arrays else np.zeros((6, 4))
        loc.lost[...] = 0.0  # the x and y faces to rank 0, each z face to its block
        loc.lost[:4] = lost[:4] if first else 0.0
        loc.lost[4] = lost[4] if self.block == 0 else 0.0
        loc.lost[5] = lost[5] if self.block == self.size - 1 else 0.0
        ny = self.mesh.shape[1]
        rows = impulse_rows_from(arrays, self.mesh.shape[2] * ny)[k0 * ny:k1 * ny]  # the block's rows (k, j)
        loc.terms_rows[...] = rows[:, :3]
        loc.gas_terms_rows[...] = rows[:, 3:]

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        """Take this rank's share of a whole-box (serial) checkpoint, with z cuts balanced for its
        particles; rank 0's ``whole`` takes all of it."""
        self._build(arrays, attrs)
        if self.rank == 0:
            self.whole.restore(arrays, attrs)
        self._version += 1
        self._gathered = self._version  # rank 0's whole engine holds this state, in the checkpoint's order

    # ------------------------------------------------------------------ state
    @property
    def t(self) -> float:
        return self.local.t

    @t.setter
    def t(self, value: float) -> None:
        self.local.t = value
        if self.whole is not None:
            self.whole.t = value

    @property
    def cycle(self) -> int:
        return self.local.cycle

    @cycle.setter
    def cycle(self, value: int) -> None:
        self.local.cycle = value
        if self.whole is not None:
            self.whole.cycle = value

    # ------------------------------------------------------------------ stepping
    def agree(self, decisions: tuple) -> tuple:
        """The run loop's per-rank decisions combined over the ranks (collective)."""
        return self.gas.agree(decisions)

    def timestep(self) -> float:
        """The serial step: the gas's Courant rate and the particle speeds, maxima over all ranks."""
        from mpi4py import MPI

        g, loc = self.gas.local, self.local
        mine = np.array([g._rate, *loc._vmax, 1.0 if g._bad >= 0 else 0.0])
        top = np.empty_like(mine)
        self.comm.Allreduce(mine, top, op=MPI.MAX)
        if top[4] > 0:
            return self.gas.timestep()  # names the cell on its rank, stops every rank
        return loc._limit_step(g.cfl / top[0], top[1:4])

    def advance(self, dt: float) -> None:
        self.local.advance(dt)
        self._version += 1

    # ------------------------------------------------------------------ outputs
    def _gather(self) -> None:
        """The gas, the particles (in the serial store order) and the budgets into rank 0's
        whole-box engine, once per state (collective)."""
        if self._gathered == self._version:
            return
        self.gas._gather()
        loc = self.local
        p = loc.particles
        n = p.n
        part = (p.pos.copy(), p.vel.copy(), p.species.copy(), p.pid.copy(), p.mass.copy(), loc._gkey[:n].copy())
        parts = self.comm.gather(part, root=0)
        sums = self.comm.gather((self.block, loc.lost.copy(), loc.terms_rows.copy(), loc.gas_terms_rows.copy()),
                                root=0)
        self._loads = [int(x[3].shape[0]) for x in parts] if self.rank == 0 else []
        self._gathered = self._version
        if self.rank != 0:
            return
        w = self.whole
        pos, vel, species, pid, mass, gkey = (np.concatenate([x[i] for x in parts], axis=-1) for i in range(6))
        order = np.lexsort((pid, gkey))
        store = ParticleStore(np.zeros((3, 0)), np.zeros((3, 0)), 0, np.zeros(0, dtype=np.int64), 1.0,
                              capacity=max(order.shape[0], 1))
        store.append(pos[:, order], vel[:, order], species[order], pid[order], mass[order])
        w.particles = store
        if store.capacity > w._capacity:
            w._allocate(store.capacity)
        lost = np.zeros((6, 4))
        for s in sums:  # each face's entries are held by one rank, the others hold zeros
            lost += s[1]
        w.lost[...] = lost
        sums.sort(key=lambda s: s[0])  # block (z) order: the rows of the whole box
        w.terms_rows[...] = np.concatenate([s[2] for s in sums])
        w.gas_terms_rows[...] = np.concatenate([s[3] for s in sums])

    def _load_line(self) -> str:
        return (f"particles per rank: {' '.join(str(int(x)) for x in self._loads)} (max/mean "
                f"{_ratio(self._loads):.3f}; z rows {' '.join(str(int(c)) for c in self.cuts)})")

    def particle_load(self) -> tuple[list[int], float]:
        """Particles per rank and max/mean of the last gather (rank 0; collective gather first)."""
        self._gather()
        loads = self._loads
        mean = float(np.mean(loads)) if loads else 0.0
        return loads, (max(loads) / mean if mean > 0 else 1.0)

    def history(self) -> dict[str, float]:
        """The serial history of the gathered state (the same on every rank; collective)."""
        self._gather()
        if self.rank == 0:
            before = self.whole.sorts
            values = self.whole.history()
            resorted = self.whole.sorts != before
        values, resorted = self.comm.bcast((values, resorted) if self.rank == 0 else None, root=0)
        if resorted:  # the serial history sorted the particles (its dust density): so do the blocks
            self.local.resort()
        return values

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """The serial snapshot on rank 0; empty elsewhere (collective)."""
        self._gather()
        self.local.resort()  # the serial snapshot sorts the particles (its dust density)
        if self.rank != 0:
            return {}, {}
        self._messages.append(self._load_line())
        return self.whole.snapshot()

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """The serial checkpoint on rank 0 (restartable on any rank count); empty elsewhere (collective)."""
        self._gather()
        loc = self.local
        blocks = self.comm.gather(loc._source.copy() if loc._have_source else None, root=0)
        if self.rank != 0:
            return {}, {}
        w = self.whole
        w._have_source = loc._have_source
        if loc._have_source:
            w._source[...] = np.concatenate(blocks, axis=1)
        return w.checkpoint()

    def messages(self) -> list[str]:
        """Log lines since the last call (rank 0: the cuts and the particle load per rank)."""
        out, self._messages = self._messages, []
        return out if self.rank == 0 else []


def _ratio(values) -> float:
    """max/mean of ``values`` (1 if they are all 0)."""
    values = np.asarray(values, dtype=np.float64)
    mean = float(values.mean()) if values.size else 0.0
    return float(values.max()) / mean if mean > 0 else 1.0
