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

__all__ = ["HaloExchange"]


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

    def fill(self, u: np.ndarray) -> None:
        """Fill the ghost layers of ``u`` that neighbouring blocks own (collective)."""
        from mpi4py import MPI

        for axis, lo, hi, g, n in self.plan:
            dim = u.ndim - 1 - axis  # [..., z, y, x]
            def layers(a, b):
                index = [slice(None)] * u.ndim
                index[dim] = slice(a, b)
                return tuple(index)
            first, last = layers(g, 2 * g), layers(n, n + g)
            ghost_lo, ghost_hi = layers(0, g), layers(n + g, n + 2 * g)
            lo_rank = MPI.PROC_NULL if lo is None else lo
            hi_rank = MPI.PROC_NULL if hi is None else hi
            recv = np.empty_like(u[ghost_hi])
            # my first layers go down (the lower block's upper ghosts), the upper block's come up
            self.comm.Sendrecv(np.ascontiguousarray(u[first]), dest=lo_rank, sendtag=2 * axis,
                               recvbuf=recv, source=hi_rank, recvtag=2 * axis)
            if hi is not None:
                u[ghost_hi] = recv
            self.comm.Sendrecv(np.ascontiguousarray(u[last]), dest=hi_rank, sendtag=2 * axis + 1,
                               recvbuf=recv, source=lo_rank, recvtag=2 * axis + 1)
            if lo is not None:
                u[ghost_lo] = recv
