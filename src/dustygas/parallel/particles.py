"""The particle–gas engine on one block of a mesh split along z: migration, halo particles, field halos.

:class:`BlockParticleEngine` is the coupled engine of :mod:`dustygas.particles.coupling` on the
rows ``cuts[b] .. cuts[b+1]-1`` of the whole mesh (block ``b`` of a layout ``(1, 1, P)``). It
runs the serial step unchanged and fills in its hooks, so that every value a particle or a
cell of the block receives is the serial run's, bit for bit:

* the **exchange step** (:meth:`~BlockParticleEngine._exchange`): the particle boundaries of
  the whole box (periodic wraps, shear-periodic images, outflow, reflection), then every
  particle whose cell -- the serial sort's own arithmetic (:func:`z_blocks`) -- lies in another
  block leaves for it with every attribute (position, velocity, species, id, mass); it is never
  clamped into this block. A particle that would jump past the next block (impossible at a
  particle Courant number <= 1 and blocks of >= 3 cells) stops the run on every rank;
* **halo particles** (:meth:`~BlockParticleEngine._add_halo`): after the sort, each block sends
  its neighbours the records of its ``R`` boundary rows (``R`` the assignment kernel's reach):
  its particles there with their cells and weights, and its radial and azimuthal image records
  in those rows. They become image records of the receiving block, in its padded rows beyond
  the face, and the receiver holds their particles after its own (the store's tail) to compute
  what they deposit. :func:`~dustygas.particles.deposit.pull_deposit` sums every padded row's
  records in the order (cell, particle id), so a cell next to the face sums the same terms in
  the same order as the serial run, whose image and real records of those rows are the same;
* after the kick the neighbours' halo particles receive their drag deposits (the owner's);
* **field halos** (:meth:`~BlockParticleEngine._field_halo`): the trajectory field and the
  drag deposit are exchanged, unfiltered, in the ghost rows of the face (``R + 2`` and ``2``
  rows), before the ghosts of the other axes are filled and the grid-scale filter runs: its
  value at a row depends on the two rows on either side only;
* every particle message is a table of doubles exchanged with both neighbours in one round
  (:func:`~dustygas.parallel.halo.exchange_both_ways`; integers travel as their bits or exactly);
* the rows of the thin-layer optimisation (:func:`~dustygas.particles.push.occupied_rows`) and
  the checks of the sort are agreed by all ranks in one ``Allreduce`` per step.

The gas is a :class:`~dustygas.parallel.gas.DistributedGridEngine` whose stages run after
their halo exchange (:class:`BlockGas`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..errors import SetupError, SimulationError
from ..grid.field_ghosts import FIELD_NEIGHBOUR
from ..particles.boundaries import OUTFLOW, apply_boundaries
from ..particles.coupling import ParticleGridEngine, add_lost
from ..particles.interp import axis_cell
from ..particles.push import padded_rows
from ..particles.store import sort_by_cell
from .halo import exchange_both_ways

__all__ = ["BlockGas", "BlockParticleEngine", "migration_lists", "z_blocks"]

#: a row index beyond any mesh (no particle on a rank)
_FAR = 1 << 40


@njit(cache=True, error_model="numpy")
def z_blocks(pos, n, z0, dz, nz, cuts, leaving, out) -> None:
    """``out[p]``: the block ``b`` (``cuts[b] <= k < cuts[b+1]``) holding the z cell ``k`` of
    particle ``p`` of ``0 .. n-1`` -- :func:`~dustygas.particles.interp.axis_cell` of the whole
    mesh, as the sort finds it; -1 for a particle leaving the box (``leaving[p] != 0``), -2 for a
    position that is not finite (it stays, and the sort stops the run)."""
    iz = 1.0 / dz
    nb = cuts.shape[0] - 1
    for p in range(n):
        if leaving[p] != 0:
            out[p] = -1
            continue
        z = pos[2, p]
        if not np.isfinite(z):
            out[p] = -2
            continue
        k = axis_cell(z, z0, iz, 0, nz)
        b = 0
        while b < nb - 1 and k >= cuts[b + 1]:
            b += 1
        out[p] = b


#: the rows of a particle table (:meth:`BlockParticleEngine._pack`): integers travel as their
#: bits (the id, the sort key) or exactly (the species); the key row only in migration
_COLUMNS = ("x", "y", "z", "vx", "vy", "vz", "mass", "species", "pid", "key")
_KEY = 9


def _halo_parts(msg: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
    """The particle table (:data:`_COLUMNS` without the key) and the records table of a halo
    message (:meth:`BlockParticleEngine._halo_message`): rows cell x, y, z, source, dvy and the
    ``width`` weights."""
    k, r = int(msg[0]), int(msg[1])
    return msg[2:2 + _KEY * k].reshape(_KEY, k), msg[2 + _KEY * k:].reshape(5 + width, r)


def _unpack(table: np.ndarray) -> tuple:
    """``(pos, vel, species, pid, mass)`` of a particle table, as :meth:`ParticleStore.append` takes them."""
    return (table[0:3], table[3:6], table[7].astype(np.int32), np.ascontiguousarray(table[8]).view(np.int64),
            table[6])


@njit(cache=True, error_model="numpy")
def migration_lists(dest, n, block, lo, hi, moving, keep) -> tuple[int, int, int, int]:
    """Sort particles ``0 .. n-1`` by the block ``dest[p]`` their cell lies in (:func:`z_blocks`):
    ``moving[:n_down]`` the indices of those for the lower neighbour ``lo``, ``moving[n_down:
    n_down + n_up]`` those for the upper one ``hi`` (-1: no neighbour; with two blocks around a
    periodic axis ``lo == hi`` and all go "down"); ``keep[p]`` whether it stays (its own block, a
    non-finite position, or a stray that jumped past the neighbours: it stays, never clamped, and
    the check after the sort stops the run; a particle leaving the box, ``dest[p] == -1``, does
    not). Returns ``(n_down, n_up, first stray or -1, number not kept)``."""
    n_down = 0
    stray = -1
    gone = 0
    for p in range(n):
        d = dest[p]
        go = d >= 0 and d != block and d == lo
        keep[p] = not go and d != -1
        if not keep[p]:
            gone += 1
        if go:
            moving[n_down] = p
            n_down += 1
    n_up = 0
    for p in range(n):
        d = dest[p]
        if keep[p] and d >= 0 and d != block:
            if d == hi:
                keep[p] = False
                gone += 1
                moving[n_down + n_up] = p
                n_up += 1
            elif stray < 0:
                stray = p
    return n_down, n_up, stray, gone


class BlockGas:
    """The block's :class:`~dustygas.grid.engine.GridEngine` as the particle engine sees it:
    each stage runs after the halo exchange of its input
    (:meth:`~dustygas.parallel.gas.DistributedGridEngine.advance_stage`)."""

    def __init__(self, dist):
        self._dist = dist
        self._local = dist.local

    def __getattr__(self, name):
        return getattr(self._local, name)

    @property
    def t(self) -> float:
        return self._local.t

    @t.setter
    def t(self, value: float) -> None:
        self._local.t = value

    @property
    def cycle(self) -> int:
        return self._local.cycle

    @cycle.setter
    def cycle(self, value: int) -> None:
        self._local.cycle = value

    def advance_stage(self, stage: int, dt: float, ext=None, nthreads: int = 0) -> None:
        self._dist.advance_stage(stage, dt, ext, nthreads)


class BlockParticleEngine(ParticleGridEngine):
    """The coupled engine on block ``block`` of a z split (module docstring).

    Parameters
    ----------
    gas
        The block's gas (:class:`BlockGas`).
    particles
        The particles whose cells lie in the block.
    comm
        The communicator; rank of block ``b`` is ``ranks[b]``.
    cuts
        First row of every block along z, and the row count of the whole mesh (``P + 1``).
    block
        This block.
    ranks
        The rank of each block.
    periodic_z
        Whether the z axis wraps around (the first and last blocks are neighbours).
    **options
        The serial engine's arguments (:attr:`ParticleGridEngine.options`).
    """

    _whole_box = False  # the compiled whole-box step (particles.step_xz) is not for a block

    def __init__(self, gas, particles, comm, cuts, block: int, ranks, periodic_z: bool, **options):
        self.comm = comm
        self._cuts = np.asarray(cuts, dtype=np.int64)
        self._block = int(block)
        nb = len(cuts) - 1
        self._nz = int(cuts[-1])
        self._k0 = int(cuts[block])
        self._nzb = int(cuts[block + 1] - cuts[block])
        lo = block - 1 if block > 0 else (nb - 1 if periodic_z and nb > 1 else None)
        hi = block + 1 if block < nb - 1 else (0 if periodic_z and nb > 1 else None)
        self._lo_block, self._hi_block = lo, hi
        self._lo_rank = None if lo is None else int(ranks[lo])  # None: no neighbour on that side
        self._hi_rank = None if hi is None else int(ranks[hi])
        self._periodic_z = bool(periodic_z)
        self._gkey = np.zeros(0, dtype=np.int64)
        self._dest = np.zeros(0, dtype=np.int64)
        self._moving = np.zeros(0, dtype=np.int64)
        self._stray = -1
        self._bad_particle = -1
        self._k_range = (_FAR, -_FAR)
        self._plan: list = []
        super().__init__(gas, particles, **options)
        R = self._R
        if self._nzb < R + 2:
            raise SetupError(f"a block of {self._nzb} rows along z: the particles need >= {R + 2} "
                             f"(kernel {self.kernel}); use fewer MPI ranks")
        #: particles can leave through an x or y face (outflow): the leaving particles of every
        #: block are gathered to rank 0 at each exchange step, which sums them in one place
        self._open_xy = OUTFLOW in (self._pb.x, self._pb.y)
        bits = (16 if lo is not None else 0) | (32 if hi is not None else 0)
        self._pb = self._pb._replace(neighbours=bits)
        kz = int(self._field_kinds[2])
        self._field_kinds = np.array([self._field_kinds[0], self._field_kinds[1],
                                      FIELD_NEIGHBOUR if lo is not None else kz,
                                      FIELD_NEIGHBOUR if hi is not None else kz], dtype=np.int64)

    # ------------------------------------------------------------------ arrays
    def _allocate(self, capacity: int) -> None:
        """Per-particle work arrays; the sort's keys and weights and the global keys are kept."""
        old = [getattr(self, name, None) for name in ("_keys", "_wts")]
        super()._allocate(capacity)
        for new, was in zip((self._keys, self._wts), old):
            if was is not None:
                k = min(was.shape[0], capacity)
                new[:k] = was[:k]
        self._keep = np.zeros(capacity, dtype=np.bool_)
        for name in ("_gkey", "_dest", "_moving"):
            was = getattr(self, name)
            new = np.zeros(capacity, dtype=np.int64)
            new[:min(was.shape[0], capacity)] = was[:capacity]
            setattr(self, name, new)

    def _owners(self, pos: np.ndarray, n: int, leaving: np.ndarray) -> np.ndarray:
        sp = self._sp
        z_blocks(pos, n, sp.z0, sp.dz, self._nz, self._cuts, leaving, self._dest)
        return self._dest[:n]

    def _check_inside(self) -> None:
        """Every particle inside the box and in this block (set-up and restart)."""
        super()._check_inside()
        p = self.particles
        if p.n and self._nz > 1:
            if self._dest.shape[0] < p.capacity:
                self._dest = np.zeros(p.capacity, dtype=np.int64)
            owners = self._owners(p.buffers()[0], p.n, np.zeros(p.n, dtype=np.int64))
            if np.any(owners != self._block):
                raise SetupError(f"particles outside block {self._block} (rows {self._k0} .. "
                                 f"{self._k0 + self._nzb - 1}) given to it")

    # ------------------------------------------------------------------ exchange: boundaries, migration
    def _exchange(self, t: float, half_dt: float = 0.0) -> None:
        """The exchange step of the whole box, then the migration to the neighbouring blocks."""
        p = self.particles
        pos, vel, species, pid, mass = p.buffers()
        n = p.n
        shift = self.geometry.shear_offset(t)
        count = apply_boundaries(pos, vel, n, self._lay_t, self._sp_t, self._pb_t, shift, self._leaving, half_dt)
        flags = self._leaving[:n]
        if count:  # the z faces: the end blocks hold every particle that leaves through them
            add_lost(self.lost, flags, p.mass, p.vel, (4, 5))
        if self._open_xy:  # the x and y faces: every block's leaving particles, summed on rank 0
            sel = (flags >= 1) & (flags <= 4)
            m = p.mass[sel]
            leaving = self.comm.gather((flags[sel], m, p.vel[:, sel]), root=0)
            if self.comm.Get_rank() == 0:
                f, m, v = (np.concatenate([x[i] for x in leaving], axis=-1) for i in range(3))
                add_lost(self.lost, f, m, v, range(4))
        dest = self._owners(pos, n, self._leaving)
        lo = -1 if self._lo_block is None else self._lo_block
        hi = -1 if self._hi_block is None else self._hi_block
        n_down, n_up, stray, gone = migration_lists(dest, n, self._block, lo, hi, self._moving, self._keep)
        if stray >= 0:
            self._stray = int(pid[stray])
            self._stray_to = int(dest[stray])
        moving = self._moving
        outgoing = (self._pack(moving[:n_down], self._gkey), self._pack(moving[n_down:n_down + n_up], self._gkey))
        if gone:
            keep = self._keep[:n]
            self._gkey[:n - gone] = self._gkey[:n][keep]  # the keys go with their particles
            p.remove(keep)
        for got in self._both_ways(outgoing, tag=31):  # from the lower block first
            if got is not None and got.size:
                got = got.reshape(len(_COLUMNS), -1)
                start = p.n
                p.append(*_unpack(got))
                if p.capacity > self._capacity:
                    self._allocate(p.capacity)
                self._gkey[start:p.n] = got[_KEY].view(np.int64)

    def _both_ways(self, outgoing, tag: int) -> tuple:
        """``outgoing[0]`` to the lower neighbour, ``outgoing[1]`` to the upper one, theirs back
        flat (:func:`~dustygas.parallel.halo.exchange_both_ways`): ``(from the lower, from the
        upper)``, None where there is no neighbour."""
        return exchange_both_ways(self.comm, self._lo_rank, self._hi_rank, outgoing[0], outgoing[1], tag)

    def _pack(self, sel: np.ndarray, keys: np.ndarray | None = None) -> np.ndarray:
        """Every attribute of the particles ``sel`` (indices or a range), and ``keys[sel]`` if
        given, as a table of rows :data:`_COLUMNS` (:func:`_unpack`)."""
        p = self.particles
        pos, vel, species, pid, mass = p.buffers()
        table = np.empty((_KEY + (keys is not None), pos[0, sel].shape[0]))
        table[0:3] = pos[:, sel]
        table[3:6] = vel[:, sel]
        table[6] = mass[sel]
        table[7] = species[sel]
        table[8] = pid[sel].view(np.float64)
        if keys is not None:
            table[_KEY] = keys[sel].view(np.float64)
        return table

    def resort(self) -> None:
        """Sort the block's particles at their present positions, as the serial run's outputs
        sort all of them: the next exchange step then meets them in the serial order (the mass
        and momentum that leave through a z face are summed in it)."""
        p = self.particles
        if p.capacity > self._capacity:
            self._allocate(p.capacity)
        pos, vel, species, pid, mass = p.buffers()
        bad = sort_by_cell(pos, vel, species, pid, mass, p.n, self._lay_t, self._sp_t, self._off_t, self._keys,
                           self._order_work, self._ptr, self._cell_start, self._fwork, self._iwork, self._order, self._R,
                           self._wts)
        if bad < 0:  # else the next step's sort stops the run on every rank
            nx, ny, _ = self.geometry.shape
            self._gkey[:p.n] = self._keys[:p.n] + self._k0 * nx * ny

    # ------------------------------------------------------------------ after the sort
    def _stop_nonfinite(self, bad: int) -> None:
        self._bad_particle = bad
        self._agree()

    def _agree(self) -> None:
        """One ``Allreduce``: the z rows the particles occupy, and whether a sort failed or a
        particle strayed on any rank (then every rank stops)."""
        from mpi4py import MPI

        p = self.particles
        n = p.n
        nxy = self.geometry.shape[0] * self.geometry.shape[1]
        first, last = _FAR, -_FAR
        if self._bad_particle < 0 and n:
            first = int(self._keys[0]) // nxy + self._k0
            last = int(self._keys[n - 1]) // nxy + self._k0
        mine = np.array([-first, last, int(self._bad_particle >= 0), int(self._stray >= 0)], dtype=np.int64)
        total = np.empty_like(mine)
        self.comm.Allreduce(mine, total, op=MPI.MAX)
        if total[2] or total[3]:
            if self._bad_particle >= 0:
                bad, self._bad_particle = self._bad_particle, -1
                ParticleGridEngine._stop_nonfinite(self, bad)
            if self._stray >= 0:
                raise SimulationError(
                    f"particle pid={self._stray} moved from block {self._block} to block {self._stray_to} in half "
                    f"a step (more than a neighbouring block) at time={self.t:.6g} cycle={self.cycle}")
            raise SimulationError(f"invalid particle state on another rank at time={self.t:.6g} cycle={self.cycle}")
        self._k_range = (int(-total[0]), int(total[1]))

    def _wrap_images(self) -> bool:
        """Image records always: the neighbours' particles arrive as records too."""
        return False

    def _add_halo(self, m: int) -> int:
        """The neighbours' records of their boundary rows, as image records beyond the faces."""
        self._agree()
        p = self.particles
        n = p.n
        nx, ny, _ = self.geometry.shape
        self._gkey[:n] = self._keys[:n] + self._k0 * nx * ny
        R, nzb = self._R, self._nzb
        msgs, ranges = [None, None], [(0, 0), (0, 0)]
        if self._lo_block is not None:
            msgs[0], ranges[0] = self._halo_message(m, 0, R)
        if self._hi_block is not None:
            msgs[1], ranges[1] = self._halo_message(m, nzb - R, nzb)
        from_below, from_above = self._both_ways(msgs, tag=41)
        width = self._img_w.shape[1] * self._img_w.shape[2]
        got = [] if from_above is None else [(_halo_parts(from_above, width), nzb, "above")]
        if from_below is not None:
            got.append((_halo_parts(from_below, width), -self._block_rows_of(self._lo_block), "below"))
        nsrc = sum(parts.shape[1] for (parts, _), _, _ in got)
        nrec = sum(records.shape[1] for (_, records), _, _ in got)
        if n + nsrc > p.capacity:
            p.reserve(max(n + nsrc, 2 * p.capacity))
        if p.capacity > self._capacity:
            self._allocate(p.capacity)
        self._grow_images(m + nrec)
        pos, vel, species, pid, mass = p.buffers()
        slots = {"above": (0, 0), "below": (0, 0)}
        s0, r0 = n, m
        for (parts, records), shift, side in got:
            k, r = parts.shape[1], records.shape[1]
            pos[:, s0:s0 + k], vel[:, s0:s0 + k], species[s0:s0 + k], pid[s0:s0 + k], mass[s0:s0 + k] = \
                _unpack(parts)
            self._img_cell[r0:r0 + r] = records[0:3].T.astype(np.int64)
            self._img_cell[r0:r0 + r, 2] += shift
            self._img_src[r0:r0 + r] = records[3].astype(np.int64) + s0
            self._img_dvy[r0:r0 + r] = records[4]
            self._img_w[r0:r0 + r] = records[5:].T.reshape(r, *self._img_w.shape[1:])
            slots[side] = (s0, k)
            s0, r0 = s0 + k, r0 + r
        self._n_halo = s0 - n
        self._plan = [ranges, slots["above"], slots["below"]]
        return r0

    def _block_rows_of(self, b: int) -> int:
        return int(self._cuts[b + 1] - self._cuts[b])

    def _halo_message(self, m: int, k_a: int, k_b: int) -> tuple[np.ndarray, tuple[int, int]]:
        """The particles of rows ``k_a .. k_b-1`` and every record in those rows (cells with the
        row in this block's numbering, source index relative to the first particle), as one flat
        message (:func:`_halo_parts`), and the particles' index range."""
        nx, ny, _ = self.geometry.shape
        cs = self._cell_start
        a, b = int(cs[k_a * nx * ny]), int(cs[k_b * nx * ny])
        k = b - a
        sel = np.nonzero((self._img_cell[:m, 2] >= k_a) & (self._img_cell[:m, 2] < k_b))[0]
        r = k + sel.shape[0]
        width = self._img_w.shape[1] * self._img_w.shape[2]
        msg = np.empty(2 + _KEY * k + (5 + width) * r)
        msg[0], msg[1] = k, r
        msg[2:2 + _KEY * k] = self._pack(slice(a, b)).ravel()
        records = msg[2 + _KEY * k:].reshape(5 + width, r)
        keys = self._keys[a:b]
        records[0, :k], records[1, :k], records[2, :k] = keys % nx, (keys // nx) % ny, keys // (nx * ny)
        records[0:3, k:] = self._img_cell[sel].T
        records[3, :k] = np.arange(k)
        records[3, k:] = self._img_src[sel] - a
        records[4, :k] = 0.0
        records[4, k:] = self._img_dvy[sel]
        records[5:, :k] = self._wts[a:b].reshape(k, width).T
        records[5:, k:] = self._img_w[sel].reshape(-1, width).T
        return msg, (a, b)

    def _kicked(self, n: int) -> None:
        """The drag deposits of this block's boundary particles to the neighbours that hold them."""
        if not self._plan:
            return
        ranges, above, below = self._plan
        vals = self._values
        mine = [vals[a:b, :3] for a, b in ranges]
        got_below, got_above = self._both_ways(mine, tag=51)
        for got, (s0, k) in ((got_above, above), (got_below, below)):
            if got is not None and k:
                vals[s0:s0 + k, :3] = got.reshape(k, 3)

    # ------------------------------------------------------------------ rows and field halos
    def _occupied_rows(self, n: int, margin: int) -> tuple[int, int]:
        """:func:`~dustygas.particles.push.occupied_rows` of all the particles (agreed after the sort)."""
        first, last = self._k_range
        nz = self._nz
        if last < first:
            return 0, nz
        lo, hi = first - margin, last + 1 + margin
        if self._periodic_z and (lo < 0 or hi > nz):
            return 0, nz
        return max(lo, 0), min(hi, nz)

    def _block_rows(self, rows: tuple[int, int]) -> tuple[int, int]:
        return max(rows[0] - self._k0, 0), min(rows[1] - self._k0, self._nzb)

    def _padded_of(self, b: int, rows: tuple[int, int], gz: int) -> tuple[int, int]:
        """The serial padded rows of ``rows`` in block ``b``'s numbering, clipped to it."""
        k_lo, k_hi = padded_rows(rows, gz, self._nz)
        k0, top = int(self._cuts[b]), self._block_rows_of(b) + 2 * gz
        k_lo, k_hi = min(max(k_lo - k0, 0), top), min(max(k_hi - k0, 0), top)
        return k_lo, max(k_hi, k_lo)

    def _padded_rows(self, rows: tuple[int, int], gz: int) -> tuple[int, int]:
        return self._padded_of(self._block, rows, gz)

    def _field_halo(self, field: np.ndarray, gz: int) -> None:
        """The ``gz`` ghost rows of ``field`` at the block faces from the neighbours' first and
        last domain rows (unfiltered), where the fields are needed this step."""
        if gz == 0:
            return
        rows, nzb = self.field_rows, self._nzb
        lo, hi = self._lo_block, self._hi_block
        # the lower neighbour needs my first rows if its upper ghosts are in its padded range; I need
        # the upper neighbour's if mine are, and so on (every rank decides alike from the agreed rows)
        send_down = lo is not None and self._padded_of(lo, rows, gz)[1] > self._block_rows_of(lo) + gz
        recv_up = hi is not None and self._padded_of(self._block, rows, gz)[1] > nzb + gz
        send_up = hi is not None and self._padded_of(hi, rows, gz)[0] < gz
        recv_down = lo is not None and self._padded_of(self._block, rows, gz)[0] < gz
        # one round, straight from and into the field: its rows (axis 0) are contiguous slabs
        from mpi4py import MPI

        requests = []
        if recv_up:
            requests.append(self.comm.Irecv(field[nzb + gz:nzb + 2 * gz], source=self._hi_rank, tag=61))
        if recv_down:
            requests.append(self.comm.Irecv(field[:gz], source=self._lo_rank, tag=62))
        if send_down:
            requests.append(self.comm.Isend(field[gz:2 * gz], dest=self._lo_rank, tag=61))
        if send_up:
            requests.append(self.comm.Isend(field[nzb:nzb + gz], dest=self._hi_rank, tag=62))
        MPI.Request.Waitall(requests)
