"""The halo exchange: ghost layers of a block from the blocks beside it.

For each split axis, in the order z, y, x of the serial ghost fill
(:func:`~dustygas.grid.boundaries.fill_ghosts`), a block sends its first ``g`` domain layers
to the neighbour below and its last ``g`` to the neighbour above, each layer over the full
padded extent of the other two axes, and receives their layers into its ghost zones; a
periodic axis wraps around (the periodic image is the first or last block), a physical end
has no neighbour and is left to the local fill. Because each axis's layers carry the ghosts
of the axes exchanged before it, edges and corners come out as the serial fill makes them,
and since every ghost is a copy, bit for bit.

The faces an exchange fills are marked :data:`~dustygas.grid.boundaries.NEIGHBOUR` in the
block's :class:`~dustygas.grid.boundaries.Boundaries`, so the compiled step's own fill leaves
them alone and fills only the physical faces (and the unsplit axes), after the exchange.
"""

from __future__ import annotations

import numpy as np

from .decomposition import Decomposition

__all__ = ["HaloExchange", "MessageBuffers", "exchange_both_ways"]


class MessageBuffers:
    """Message buffers kept between steps, one per key and shape (:meth:`get`).

    A slab of ghost layers of a 64^3 block is about 0.6 MB; allocated anew at every exchange, the
    freed memory went back to the system and was faulted in again, and a fill of 3 layers took
    0.73-0.88 ms against 0.22 ms with kept buffers (two ranks, 2026-12-03; the 588 kB message
    itself takes 60 us).
    """

    def __init__(self) -> None:
        self._kept: dict[tuple, np.ndarray] = {}

    def get(self, key: tuple, shape: tuple[int, ...]) -> np.ndarray:
        """The float64 buffer of ``key`` and ``shape`` (its contents are whatever was left in it)."""
        key = (*key, shape)
        if key not in self._kept:
            self._kept[key] = np.empty(shape)
        return self._kept[key]


def exchange_both_ways(comm, lower: int | None, upper: int | None, to_lower: np.ndarray | None,
                       to_upper: np.ndarray | None, tag: int) -> tuple[np.ndarray | None, np.ndarray | None]:
    """Send a float64 table to each neighbour and receive theirs, of any length, in one round.

    ``to_lower`` goes to rank ``lower`` and ``to_upper`` to rank ``upper`` (None: no neighbour
    there, nothing sent); each neighbour's table comes back flat (the caller knows its width),
    ``(from the lower, from the upper)``, None where there is no neighbour. The receive learns the
    length from the message itself (``MPI_Mprobe``), so the lengths are not exchanged first. With
    two blocks around a periodic axis ``lower == upper`` and the tags tell the messages apart.

    A table as raw doubles instead of a pickled tuple of arrays: on two ranks of this machine a
    pickled exchange of 1000 particles' attributes both ways took 168 us, of 16 particles 54 us
    (2026-12-04).
    """
    from mpi4py import MPI

    requests, sent = [], []
    for table, dest, my_tag in ((to_lower, lower, tag), (to_upper, upper, tag + 1)):
        if dest is not None:
            sent.append(np.ascontiguousarray(table, dtype=np.float64))  # held until the sends complete
            requests.append(comm.Isend(sent[-1], dest=dest, tag=my_tag))
    got = []
    for source, their_tag in ((lower, tag + 1), (upper, tag)):  # the lower sends its table "up", ...
        if source is None:
            got.append(None)
            continue
        status = MPI.Status()
        message = comm.Mprobe(source=source, tag=their_tag, status=status)
        table = np.empty(status.Get_count(MPI.DOUBLE))
        message.Recv(table)
        got.append(table)
    MPI.Request.Waitall(requests)
    return got[0], got[1]


class HaloExchange:
    """Ghost exchange of one rank's block (:meth:`fill`), for a ``(nvar, NZ, NY, NX)`` array.

    Parameters
    ----------
    comm
        The communicator (``MPI.COMM_WORLD`` or a duplicate).
    decomposition, rank
        The layout and this rank.
    ghosts
        Ghost layers per side in x, y, z.
    periodic
        Whether each axis wraps around (periodic or shear-periodic kinds).
    """

    def __init__(self, comm, decomposition: Decomposition, rank: int, ghosts: tuple[int, int, int],
                 periodic: tuple[bool, bool, bool]):
        self.comm = comm
        self._buffers = MessageBuffers()
        self.plan = []
        for axis in (2, 1, 0):
            if decomposition.dims[axis] == 1:
                continue
            lo = decomposition.neighbour(rank, axis, -1, periodic[axis])
            hi = decomposition.neighbour(rank, axis, +1, periodic[axis])
            self.plan.append((axis, lo, hi, ghosts[axis], decomposition.block_shape_of(rank)[axis]))

    def neighbour_faces(self) -> dict[str, bool]:
        """Which faces (``x_lo`` ... ``z_hi``) another block fills."""
        out = {}
        for axis, lo, hi, _, _ in self.plan:
            out["xyz"[axis] + "_lo"] = lo is not None
            out["xyz"[axis] + "_hi"] = hi is not None
        return out

    def fill(self, u: np.ndarray, depth: int | None = None) -> None:
        """Fill the ghost layers of ``u`` that neighbouring blocks own (collective): the ``depth``
        layers next to each inner face (default: all of them); the outer ones keep what they held."""
        from mpi4py import MPI

        for axis, lo, hi, g, n in self.plan:
            d = g if depth is None else min(int(depth), g)
            dim = u.ndim - 1 - axis  # [..., z, y, x]
            def layers(a, b):
                index = [slice(None)] * u.ndim
                index[dim] = slice(a, b)
                return tuple(index)
            first, last = layers(g, g + d), layers(n + g - d, n + g)
            ghost_lo, ghost_hi = layers(g - d, g), layers(n + g, n + g + d)
            lo_rank = MPI.PROC_NULL if lo is None else lo
            hi_rank = MPI.PROC_NULL if hi is None else hi
            # my first layers go down (the lower block's upper ghosts), my last ones up; both ways
            # in one round
            shape = u[first].shape
            down, up = self._buffers.get(("down", axis), shape), self._buffers.get(("up", axis), shape)
            from_hi, from_lo = self._buffers.get(("from_hi", axis), shape), self._buffers.get(("from_lo", axis), shape)
            requests = [self.comm.Irecv(from_hi, source=hi_rank, tag=2 * axis),
                        self.comm.Irecv(from_lo, source=lo_rank, tag=2 * axis + 1)]
            np.copyto(down, u[first])
            np.copyto(up, u[last])
            requests += [self.comm.Isend(down, dest=lo_rank, tag=2 * axis),
                         self.comm.Isend(up, dest=hi_rank, tag=2 * axis + 1)]
            MPI.Request.Waitall(requests)
            if hi is not None:
                u[ghost_hi] = from_hi
            if lo is not None:
                u[ghost_lo] = from_lo
