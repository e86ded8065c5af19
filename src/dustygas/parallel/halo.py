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

__all__ = ["HaloExchange", "MessageBuffers"]


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
            send = self._buffers.get(("send", axis), u[first].shape)
            recv = self._buffers.get(("recv", axis), u[first].shape)
            # my first layers go down (the lower block's upper ghosts), the upper block's come up
            np.copyto(send, u[first])
            self.comm.Sendrecv(send, dest=lo_rank, sendtag=2 * axis, recvbuf=recv, source=hi_rank,
                               recvtag=2 * axis)
            if hi is not None:
                u[ghost_hi] = recv
            np.copyto(send, u[last])
            self.comm.Sendrecv(send, dest=hi_rank, sendtag=2 * axis + 1, recvbuf=recv, source=lo_rank,
                               recvtag=2 * axis + 1)
            if lo is not None:
                u[ghost_lo] = recv
