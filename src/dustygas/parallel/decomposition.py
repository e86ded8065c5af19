"""The Cartesian rank layout: which axes are split into how many equal blocks.

A mesh of ``(NX, NY, NZ)`` cells on ``P = px py pz`` ranks is cut into blocks of
``(NX/px, NY/py, NZ/pz)`` cells; rank ``r`` holds the block at Cartesian coordinates
``(cx, cy, cz)`` with ``r = (cx py + cy) pz + cz`` (MPI's row-major order, z fastest) and first
cell ``(cx NX/px, cy NY/py, cz NZ/pz)``. Every block of an active axis must hold at least the
ghost depth (:data:`~dustygas.grid.mesh.NGHOST` cells) so that one exchange with the nearest
neighbour fills its ghosts.

Phase-one limits, refused with a one-line error rather than run wrongly: the radial axis of a
shear-periodic box and the azimuthal axis of a box with shear-periodic boundaries or orbital
advection are not split (the sliding radial images, the radial flux correction and the
orbital-advection remap work on whole x-y planes). A box with hydrostatic z boundaries is split
in z like any other: its end blocks fill those ghosts with the heights of the whole mesh.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from ..errors import UserError
from ..grid.mesh import NGHOST, Mesh

__all__ = ["Decomposition", "BlockMesh", "choose_layout", "unsplittable_axes", "balanced_cuts", "check_cuts"]


def unsplittable_axes(boundaries: tuple[str, str, str], orbital_advection: bool,
                      active: tuple[bool, bool, bool]) -> dict[int, str]:
    """Axes this phase cannot split, each with the reason (for the error message).

    >>> sorted(unsplittable_axes(("shear-periodic", "periodic", "periodic"), False, (True, True, True)))
    [0, 1]
    >>> unsplittable_axes(("shear-periodic", "periodic", "periodic"), False, (True, False, True))
    {0: 'shear-periodic x boundaries'}
    """
    out: dict[int, str] = {}
    if boundaries[0] == "shear-periodic" and active[0]:
        out[0] = "shear-periodic x boundaries"
        if active[1]:
            out[1] = "shear-periodic x boundaries (the sliding images remap whole y columns)"
    if orbital_advection and active[1]:
        out[1] = "orbital advection (it remaps whole y columns)"
    return out


def choose_layout(shape: tuple[int, int, int], nranks: int, forbidden: dict[int, str] | None = None,
                  nghost: int = NGHOST) -> tuple[int, int, int]:
    """Ranks per axis ``(px, py, pz)`` for ``nranks``: every split axis divides evenly into
    blocks of at least ``nghost`` cells; of the layouts that do, the one with the smallest halo
    (ghost cells per block) wins, ties going to the layout that splits z, then y, first.

    Raises
    ------
    UserError
        No layout fits (too many ranks for the blocks, or a count that does not divide).

    >>> choose_layout((64, 64, 64), 2)
    (1, 1, 2)
    >>> choose_layout((64, 64, 1), 4)
    (1, 4, 1)
    """
    forbidden = forbidden or {}
    best, best_key = None, None
    for px, py, pz in itertools.product(range(1, nranks + 1), repeat=3):
        if px * py * pz != nranks:
            continue
        dims = (px, py, pz)
        if any(p > 1 and axis in forbidden for axis, p in enumerate(dims)):
            continue
        if any(n % p or (p > 1 and n // p < nghost) for n, p in zip(shape, dims)):
            continue
        local = [n // p for n, p in zip(shape, dims)]
        halo = sum(2 * nghost * np.prod([local[b] for b in range(3) if b != a])
                   for a in range(3) if dims[a] > 1)
        key = (halo, px, py)
        if best_key is None or key < best_key:
            best, best_key = dims, key
    if best is None:
        allowed = [a for a in range(3) if a not in forbidden]
        cells = " x ".join(str(n) for n in shape)
        why = "; ".join(f"{'xyz'[a]} not split ({r})" for a, r in forbidden.items() if shape[a] > 1)
        raise UserError(
            f"mpi ranks={nranks}: the {cells} mesh has no layout of {nranks} equal blocks of >= {nghost} cells "
            f"along {', '.join('xyz'[a] for a in allowed) or 'no axis'}" + (f" ({why})" if why else "")
        )
    return best


def check_layout(shape: tuple[int, int, int], dims: tuple[int, int, int], forbidden: dict[int, str] | None = None,
                 nghost: int = NGHOST) -> None:
    """Refuse a given layout ``dims`` that does not fit ``shape`` (one-line :class:`UserError`)."""
    forbidden = forbidden or {}
    for axis, (n, p) in enumerate(zip(shape, dims)):
        name = "xyz"[axis]
        if p < 1:
            raise UserError(f"mpi layout {dims}: ranks per axis must be >= 1")
        if p > 1 and axis in forbidden:
            raise UserError(f"mpi layout {dims}: cannot split {name} ({forbidden[axis]})")
        if n % p:
            raise UserError(f"mpi layout {dims}: n{name}={n} is not divisible by {p} ranks")
        if p > 1 and n // p < nghost:
            raise UserError(f"mpi layout {dims}: n{name}={n} on {p} ranks leaves {n // p} cells per block, "
                            f"fewer than the {nghost} ghost layers")


def check_cuts(nz: int, pz: int, cuts, nghost: int = NGHOST) -> None:
    """Refuse z cuts that are not ``pz + 1`` rising rows from 0 to ``nz`` with blocks of >= ``nghost`` rows."""
    cuts = [int(c) for c in cuts]
    if len(cuts) != pz + 1 or cuts[0] != 0 or cuts[-1] != nz or min(np.diff(cuts), default=nghost) < nghost:
        raise UserError(f"mpi z cuts {cuts}: need {pz + 1} rows rising from 0 to {nz} in steps of >= {nghost}")


def balanced_cuts(row_cost, nblocks: int, min_rows: int) -> tuple[int, ...]:
    """First rows of ``nblocks`` consecutive blocks of >= ``min_rows`` rows (and the row count)
    that minimise the largest block cost, the cost of a block being the sum of ``row_cost`` over
    its rows (dynamic programming over the cut rows; the first of equal optima).

    >>> balanced_cuts([1.0] * 12, 3, 3)
    (0, 4, 8, 12)
    >>> balanced_cuts([1, 1, 1, 1, 1, 9, 9, 1, 1, 1, 1, 1], 2, 3)
    (0, 6, 12)
    >>> balanced_cuts([1, 1, 1, 1, 1, 9, 9, 1, 1, 1, 1, 1], 4, 3)
    (0, 3, 6, 9, 12)
    """
    cost = np.asarray(row_cost, dtype=np.float64)
    nz = cost.shape[0]
    if nblocks * min_rows > nz:
        raise UserError(f"mpi ranks={nblocks}: {nz} rows along z hold no {nblocks} blocks of >= {min_rows} rows")
    prefix = np.concatenate([[0.0], np.cumsum(cost)])
    # best[b, e]: the least largest cost of b + 1 blocks covering rows 0 .. e-1; start[b, e] its last cut
    best = np.full((nblocks, nz + 1), np.inf)
    start = np.zeros((nblocks, nz + 1), dtype=np.int64)
    best[0, min_rows:] = prefix[min_rows:]
    for b in range(1, nblocks):
        for e in range((b + 1) * min_rows, nz + 1):
            s = np.arange(b * min_rows, e - min_rows + 1)
            worst = np.maximum(best[b - 1, s], prefix[e] - prefix[s])
            i = int(np.argmin(worst))
            best[b, e], start[b, e] = worst[i], s[i]
    cuts = [nz]
    for b in range(nblocks - 1, 0, -1):
        cuts.append(int(start[b, cuts[-1]]))
    return tuple([0] + cuts[::-1])


@dataclass(frozen=True)
class Decomposition:
    """A Cartesian layout ``dims = (px, py, pz)`` of the mesh ``shape`` (see module doc); the z
    blocks may be uneven: ``z_cuts`` (``pz + 1`` rows, from 0 to ``nz``) are their first rows.

    >>> d = Decomposition((64, 32, 16), (2, 1, 2))
    >>> d.nranks, d.block_shape, d.coords(3), d.offset(3)
    (4, (32, 32, 8), (1, 0, 1), (32, 0, 8))
    >>> Decomposition((8, 8, 16), (1, 1, 3), z_cuts=(0, 6, 10, 16)).block_shape_of(1)
    (8, 8, 4)
    """

    shape: tuple[int, int, int]
    dims: tuple[int, int, int]
    z_cuts: tuple[int, ...] | None = None

    @property
    def cuts(self) -> tuple[int, ...]:
        """First row of every z block, and ``nz``."""
        if self.z_cuts is not None:
            return tuple(int(c) for c in self.z_cuts)
        pz, nz = self.dims[2], self.shape[2]
        return tuple(b * (nz // pz) for b in range(pz + 1))

    def block_shape_of(self, rank: int) -> tuple[int, int, int]:
        """Cells of the block of ``rank``."""
        bx, by, _ = self.block_shape
        cz = self.coords(rank)[2]
        cuts = self.cuts
        return (bx, by, cuts[cz + 1] - cuts[cz])

    @property
    def nranks(self) -> int:
        return int(np.prod(self.dims))

    @property
    def block_shape(self) -> tuple[int, int, int]:
        return tuple(n // p for n, p in zip(self.shape, self.dims))  # type: ignore[return-value]

    def coords(self, rank: int) -> tuple[int, int, int]:
        px, py, pz = self.dims
        return (rank // (py * pz), (rank // pz) % py, rank % pz)

    def rank_of(self, coords: tuple[int, int, int]) -> int:
        _, py, pz = self.dims
        cx, cy, cz = coords
        return (cx * py + cy) * pz + cz

    def offset(self, rank: int) -> tuple[int, int, int]:
        """First global cell ``(i0, j0, k0)`` of the rank's block."""
        cx, cy, cz = self.coords(rank)
        bx, by, _ = self.block_shape
        return (cx * bx, cy * by, self.cuts[cz])

    def neighbour(self, rank: int, axis: int, step: int, periodic: bool) -> int | None:
        """Rank of the block ``step`` (+1 or -1) along ``axis``; None past a non-periodic end."""
        c = list(self.coords(rank))
        c[axis] += step
        if not 0 <= c[axis] < self.dims[axis]:
            if not periodic:
                return None
            c[axis] %= self.dims[axis]
        return self.rank_of(tuple(c))  # type: ignore[arg-type]

    def block_slices(self, rank: int) -> tuple[slice, slice, slice]:
        """Index ``[k, j, i]`` of the rank's block in a global ``(NZ, NY, NX)`` domain array."""
        (i0, j0, k0), (bx, by, bz) = self.offset(rank), self.block_shape_of(rank)
        return (slice(k0, k0 + bz), slice(j0, j0 + by), slice(i0, i0 + bx))


@dataclass(frozen=True)
class BlockMesh(Mesh):
    """One block of a global :class:`~dustygas.grid.mesh.Mesh`.

    ``shape`` is the block's cell count, ``size`` the *global* box lengths (the kernels read
    them as the box: the shear offset, the radial velocity jump), ``global_shape`` and
    ``offset`` place the block. Cell sizes and cell centres are computed exactly as the
    global mesh computes them (``lower + (i0 + i + 1/2) dx``), so that a block's coordinates
    are bit-identical to the serial run's.

    >>> m = BlockMesh((16, 8, 1), (1.0, 1.0, 1.0), global_shape=(32, 8, 1), offset=(16, 0, 0))
    >>> float(m.centers(0)[0]) == float(Mesh((32, 8, 1), (1.0, 1.0, 1.0)).centers(0)[16])
    True
    """

    global_shape: tuple[int, int, int] = (1, 1, 1)
    offset: tuple[int, int, int] = (0, 0, 0)

    @property
    def global_mesh(self) -> Mesh:
        return Mesh(self.global_shape, self.size, self.nghost)

    @property
    def dx(self) -> tuple[float, float, float]:
        return self.global_mesh.dx

    @property
    def lower(self) -> tuple[float, float, float]:
        """Lower corner of the block (the global corner plus the offset)."""
        g = self.global_mesh
        return tuple(lo + i0 * d if n > 1 else 0.0
                     for lo, i0, d, n in zip(g.lower, self.offset, g.dx, self.shape))  # type: ignore[return-value]

    @property
    def origin(self) -> tuple[float, float, float]:
        """Lower corner of the whole mesh."""
        return self.global_mesh.lower

    @property
    def offsets(self):
        from ..grid.mesh import Offsets

        return Offsets(*self.offset, *self.global_shape)

    def centers(self, axis: int, ghosts: bool = False) -> np.ndarray:
        g = self.global_mesh
        n, gh = self.shape[axis], self.ghosts[axis]
        idx = np.arange(-gh, n + gh) if ghosts else np.arange(n)
        return g.lower[axis] + (self.offset[axis] + idx + 0.5) * g.dx[axis]

    @property
    def ncells(self) -> int:
        return int(np.prod(self.shape))


def block_mesh(mesh: Mesh, decomposition: Decomposition, rank: int) -> BlockMesh:
    """The block of ``mesh`` that ``rank`` holds."""
    return BlockMesh(decomposition.block_shape_of(rank), mesh.size, mesh.nghost, global_shape=mesh.shape,
                     offset=decomposition.offset(rank))
