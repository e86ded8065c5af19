"""Neighbour finding: one interface for periodic and open boundaries.

A pair :math:`(a, b)` are neighbours when :math:`r_{ab} < R \\max(h_a, h_b)`, the condition under
which either of the kernels :math:`W(r_{ab}, h_a)` and :math:`W(r_{ab}, h_b)` of the symmetric SPH
sums (thesis eqs. 3.2-3.4) is non-zero. The finder returns, for every *query* particle, the
indices of its *source* neighbours in a padded ("ELLPACK") table ``index[a, :count[a]]``:
one row per particle, filled in parallel without atomics, deterministic for any thread count,
and read back-to-back by the density and force loops of the same step. Queries and sources may
be the same set (gas-gas, the particle itself excluded) or different sets (dust querying gas,
with their own smoothing lengths).

The search uses a uniform grid of cells no smaller than the largest interaction radius
(a numba cell list): particles are binned with a counting sort, sources are copied in cell
order so that the inner loop streams contiguous memory, and each query scans the
:math:`3^d` cells around its own. Periodic dimensions with at least three cells use a
per-cell image shift; thinner periodic dimensions use a single cell and the minimum-image
distance. The time per particle is independent of :math:`N` for quasi-uniform particle
distributions; for strongly clustered ones (global disks) the k-d tree of
:mod:`~dustygas.sph.kdtree` visits far fewer candidates, and :class:`NeighbourFinder` picks it
automatically when the smoothing lengths spread by more than a factor four.

Examples
--------
>>> import numpy as np
>>> box = Box.periodic_box(1, (0.0,), (1.0,))
>>> x = np.zeros((10, 3)); x[:, 0] = (np.arange(10) + 0.5) / 10
>>> nl = NeighbourFinder(box, radius=2.0).find(x, np.full(10, 0.12))
>>> sorted(nl.neighbours_of(0).tolist())  # two on each side, across the periodic boundary
[1, 2, 8, 9]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from ..errors import SimulationError
from .kdtree import build_tree, tree_search
from .pairs import candidate_buffers, minimum_image, scan_candidates
from .workshare import WORKERS, new_counter, next_chunk

__all__ = ["Box", "NeighbourList", "NeighbourFinder", "minimum_image"]

#: the cell search hands out contiguous chunks of cells (each allocates its candidate buffers once)
SEARCH_CHUNKS = 256


@dataclass(frozen=True)
class Box:
    """The domain: ``ndim`` dimensions, periodic ones wrapping on ``[lo, hi)``.

    Positions are always stored with three components; dimensions ``>= ndim`` are ignored.
    ``lo``/``hi`` of open dimensions are informative only.
    """

    ndim: int
    lo: tuple[float, float, float]
    hi: tuple[float, float, float]
    periodic: tuple[bool, bool, bool]

    @classmethod
    def periodic_box(cls, ndim: int, lo, hi) -> "Box":
        """A box periodic in its first ``ndim`` dimensions."""
        lo = tuple(float(v) for v in lo) + (0.0,) * (3 - len(lo))
        hi = tuple(float(v) for v in hi) + (0.0,) * (3 - len(hi))
        return cls(ndim, lo, hi, tuple(d < ndim for d in range(3)))

    @classmethod
    def open_box(cls, ndim: int) -> "Box":
        """No boundaries at all (e.g. a disk around a star)."""
        return cls(ndim, (0.0,) * 3, (0.0,) * 3, (False,) * 3)

    @property
    def length(self) -> np.ndarray:
        return np.array([h - l for l, h in zip(self.lo, self.hi)])

    def arrays(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(lo, length, periodic)`` as float64/float64/bool arrays of length 3 for kernels."""
        per = np.array([self.periodic[d] and d < self.ndim for d in range(3)], dtype=np.bool_)
        return np.array(self.lo, dtype=np.float64), self.length.astype(np.float64), per

    def wrap(self, pos: np.ndarray) -> None:
        """Put positions back into ``[lo, hi)`` along periodic dimensions (in place)."""
        lo, length, per = self.arrays()
        _wrap(pos, lo, length, per)


@njit(parallel=True, cache=True)
def _wrap(pos, lo, length, periodic):
    for i in prange(pos.shape[0]):
        for d in range(3):
            if periodic[d]:
                x = pos[i, d]
                if x < lo[d] or x >= lo[d] + length[d]:
                    x = lo[d] + (x - lo[d]) % length[d]
                    if x >= lo[d] + length[d]:  # (x - lo) % L can round up to L
                        x = lo[d]
                    pos[i, d] = x


@dataclass
class NeighbourList:
    """Neighbours of each query particle: ``index[a, :count[a]]`` (source indices)."""

    index: np.ndarray  # (n_query, capacity) int32
    count: np.ndarray  # (n_query,) int32
    search_h: np.ndarray  # smoothing lengths the list is complete for (r < R max(h_a, h_b))
    cell_order: np.ndarray  # query indices sorted by cell (a spatially coherent order)

    def neighbours_of(self, a: int) -> np.ndarray:
        return self.index[a, : self.count[a]]

    @property
    def total(self) -> int:
        return int(self.count.sum())


# --------------------------------------------------------------------------- numba core


@njit(cache=True)
def _cell_coord(x, origin, inv_size, n, periodic):
    c = int(math.floor((x - origin) * inv_size))
    if periodic:
        c = c % n
    elif c < 0:
        c = 0
    elif c >= n:
        c = n - 1
    return c


@njit(cache=True)
def _bin(pos, origin, inv_size, ncell, periodic):
    """Counting sort of particles into cells: (cell start offsets, particle order)."""
    n = pos.shape[0]
    nx, ny, nz = ncell[0], ncell[1], ncell[2]
    cell = np.empty(n, np.int64)
    start = np.zeros(nx * ny * nz + 1, np.int64)
    for i in range(n):
        cx = _cell_coord(pos[i, 0], origin[0], inv_size[0], nx, periodic[0])
        cy = _cell_coord(pos[i, 1], origin[1], inv_size[1], ny, periodic[1])
        cz = _cell_coord(pos[i, 2], origin[2], inv_size[2], nz, periodic[2])
        c = (cz * ny + cy) * nx + cx
        cell[i] = c
        start[c + 1] += 1
    for c in range(nx * ny * nz):
        start[c + 1] += start[c]
    fill = start[:-1].copy()
    order = np.empty(n, np.int64)
    for i in range(n):
        c = cell[i]
        order[fill[c]] = i
        fill[c] += 1
    return start, order


@njit(cache=True)
def _range(c, n, periodic):
    """First and last cell offsets to scan along one dimension."""
    if n == 1:
        return 0, 0
    if periodic:
        return -1, 1
    lo = -1 if c > 0 else 0
    hi = 1 if c < n - 1 else 0
    return lo, hi


@njit(inline="always")
def _image_cell(k, n, length):
    """Neighbour cell ``k`` (one beyond either end at most) wrapped into ``[0, n)``, and the shift
    that carries its particles to the image next to the query cell."""
    if k < 0:
        return k + n, -length
    if k >= n:
        return k - n, length
    return k, 0.0


@njit(parallel=True, cache=True)
def _search(qpos, qh, qstart, qorder, spos, sh, sstart, sorder, ncell, length, periodic, radius,
            exclude_self, index, count, overlap):
    """For each cell: gather the candidates of the 3^d surrounding cells once (periodic shifts
    applied), then test every query of the cell against them in two vectorisable passes."""
    nx, ny, nz = ncell[0], ncell[1], ncell[2]
    # minimum image needed along periodic dimensions held in a single cell
    inv_l = serial_full(3, 0.0)
    for d, n in enumerate((nx, ny, nz)):
        if periodic[d] and n == 1:
            inv_l[d] = 1.0 / length[d]
    r2 = radius * radius
    ncells = nx * ny * nz
    nchunk = min(ncells, SEARCH_CHUNKS)
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        t = next_chunk(counter)
        while t < nchunk:
            _search_cells(t * ncells // nchunk, (t + 1) * ncells // nchunk, qpos, qh, qstart, qorder, spos, sh,
                          sstart, sorder, nx, ny, nz, length, periodic, inv_l, r2, exclude_self, index, count,
                          overlap)
            t = next_chunk(counter)


@njit(inline="always")
def _search_cells(c0, c1, qpos, qh, qstart, qorder, spos, sh, sstart, sorder, nx, ny, nz, length, periodic, inv_l, r2,
                  exclude_self, index, count, overlap):
    """The rows of the queries in cells ``c0 .. c1 - 1`` (:func:`_search`)."""
    longest = 0  # one set of candidate buffers per chunk of cells: no allocation per cell
    for c in range(c0, c1):
        if qstart[c] != qstart[c + 1]:
            longest = max(longest, _candidate_count(c, nx, ny, nz, periodic, sstart))
    px, py, pz, ph2, pid, d2 = candidate_buffers(longest)
    for c in range(c0, c1):
        if qstart[c] == qstart[c + 1]:
            continue
        cx = c % nx
        cy = (c // nx) % ny
        cz = c // (nx * ny)
        xlo, xhi = _range(cx, nx, periodic[0])
        ylo, yhi = _range(cy, ny, periodic[1])
        zlo, zhi = _range(cz, nz, periodic[2])
        j = 0
        for oz in range(zlo, zhi + 1):
            kz, sz = _image_cell(cz + oz, nz, length[2])
            for oy in range(ylo, yhi + 1):
                ky, sy = _image_cell(cy + oy, ny, length[1])
                for ox in range(xlo, xhi + 1):
                    kx, sx = _image_cell(cx + ox, nx, length[0])
                    k = (kz * ny + ky) * nx + kx
                    for i in range(sstart[k], sstart[k + 1]):
                        px[j] = spos[i, 0] + sx
                        py[j] = spos[i, 1] + sy
                        pz[j] = spos[i, 2] + sz
                        ph2[j] = sh[i] * sh[i]
                        pid[j] = sorder[i]
                        j += 1
        for iq in range(qstart[c], qstart[c + 1]):
            scan_candidates(qorder[iq], qpos, qh, j, px, py, pz, ph2, pid, d2, length, inv_l, r2, exclude_self,
                            index, count, overlap)


@njit(inline="always")
def _candidate_count(c, nx, ny, nz, periodic, sstart):
    """Number of sources in the 3^d cells around cell ``c``."""
    cx = c % nx
    cy = (c // nx) % ny
    cz = c // (nx * ny)
    xlo, xhi = _range(cx, nx, periodic[0])
    ylo, yhi = _range(cy, ny, periodic[1])
    zlo, zhi = _range(cz, nz, periodic[2])
    m = 0
    for oz in range(zlo, zhi + 1):
        kz = (cz + oz) % nz
        for oy in range(ylo, yhi + 1):
            ky = (cy + oy) % ny
            for ox in range(xlo, xhi + 1):
                kx = (cx + ox) % nx
                k = (kz * ny + ky) * nx + kx
                m += sstart[k + 1] - sstart[k]
    return m


@njit(parallel=True, cache=True)
def _gather_sorted(pos, h, order, spos, sh):
    for k in prange(order.shape[0]):
        i = order[k]
        spos[k, 0] = pos[i, 0]
        spos[k, 1] = pos[i, 1]
        spos[k, 2] = pos[i, 2]
        sh[k] = h[i]


# --------------------------------------------------------------------------- interface


class NeighbourFinder:
    """Neighbour search for kernels of support ``radius`` (in units of h) in ``box``.

    Parameters
    ----------
    box
        Domain and boundary conditions.
    radius
        Kernel support radius :math:`R` (2 for M4 and the Wendlands, 3 for M6).
    method
        ``cells`` (uniform cell list), ``tree`` (:mod:`~dustygas.sph.kdtree`) or ``auto``
        (:meth:`choose`, per call).
    leaf_size
        Particles per leaf of the tree.
    """

    def __init__(self, box: Box, radius: float, method: str = "auto", leaf_size: int = 12):
        if method not in ("auto", "cells", "tree"):
            raise ValueError(f"unknown neighbour-search method {method!r}; choose auto, cells or tree")
        self.box = box
        self.radius = float(radius)
        self.method = method
        self.leaf_size = int(leaf_size)
        self._capacity = 32

    def choose(self, h: np.ndarray) -> str:
        """``cells`` for quasi-uniform smoothing lengths, ``tree`` when the largest h exceeds four
        times the median (a cell list sized for the largest h would scan far too many particles)."""
        if self.method != "auto":
            return self.method
        if h.size == 0:
            return "cells"
        return "tree" if float(h.max()) > 4.0 * float(np.median(h)) else "cells"

    def _grid(self, pos_list, hmax):
        lo, length, per = self.box.arrays()
        size = self.radius * hmax
        origin = np.zeros(3)
        extent = np.ones(3)
        ncell = np.ones(3, np.int64)
        for d in range(self.box.ndim):
            if per[d]:
                if size > 0.5 * length[d]:
                    raise SimulationError(
                        f"kernel support {size:.4g} exceeds half the periodic box length {length[d]:.4g} "
                        f"along axis {d}: too few particles across the box for this h_fact"
                    )
                origin[d], extent[d] = lo[d], length[d]
                n = int(length[d] // size) if size > 0 else 1
                ncell[d] = n if n >= 3 else 1
            else:
                xmin = min(float(p[:, d].min()) for p in pos_list)
                xmax = max(float(p[:, d].max()) for p in pos_list)
                origin[d] = xmin
                extent[d] = max(xmax - xmin, 1e-300)
                ncell[d] = max(1, int(extent[d] // size)) if size > 0 else 1
        npart = max(len(p) for p in pos_list)
        limit = max(8 * npart, 64)
        while int(np.prod(ncell)) > limit:  # sparse open domains: coarser cells
            for d in range(self.box.ndim):
                if not per[d]:
                    ncell[d] = max(1, ncell[d] // 2)
            if all(per[d] or ncell[d] == 1 for d in range(self.box.ndim)):
                break
        inv_size = ncell / extent
        return origin, inv_size, ncell, length, per

    def spatial_order(self, pos: np.ndarray, h: np.ndarray) -> np.ndarray:
        """A permutation listing particles cell by cell (or leaf by leaf): storing them in this
        order keeps neighbours close in memory."""
        if self.choose(h) == "tree":
            return build_tree(pos, h, self.box.ndim, self.leaf_size)[0]
        origin, inv_size, ncell, _, per = self._grid([pos], float(h.max(initial=0.0)))
        return _bin(pos, origin, inv_size, ncell, per)[1]

    def find(self, pos: np.ndarray, h: np.ndarray, query_pos: np.ndarray | None = None,
             query_h: np.ndarray | None = None, allow_overlap: bool = False) -> NeighbourList:
        """Neighbours of every query particle among the sources ``(pos, h)``.

        Without ``query_pos`` the sources query themselves (self excluded). Raises
        :class:`SimulationError` if two particles sit at exactly the same position, unless
        ``allow_overlap`` (particles of different species, e.g. a dust particle on top of a gas
        particle, may coincide: their pair terms vanish).
        """
        same = query_pos is None
        qpos = pos if same else query_pos
        qh = h if same else query_h
        if self.choose(h if same else np.concatenate([h, qh])) == "tree":
            return self._find_tree(pos, h, qpos, qh, same, allow_overlap)
        hmax = float(max(h.max(initial=0.0), qh.max(initial=0.0)))
        origin, inv_size, ncell, length, per = self._grid([pos] if same else [pos, qpos], hmax)
        start, sorder = _bin(pos, origin, inv_size, ncell, per)
        qstart, qorder = (start, sorder) if same else _bin(qpos, origin, inv_size, ncell, per)
        spos = np.empty_like(pos)
        sh = np.empty_like(h)
        _gather_sorted(pos, h, sorder, spos, sh)
        nq = qpos.shape[0]
        count = np.zeros(nq, np.int32)
        overlap = np.empty(nq, np.int64)
        while True:
            index = np.empty((nq, self._capacity), np.int32)
            _search(qpos, qh, qstart, qorder, spos, sh, start, sorder, ncell, length, per, self.radius, same,
                    index, count, overlap)
            need = int(count.max(initial=0))
            if need <= self._capacity:
                break
            self._capacity = int(need * 1.25) + 8
        return self._finish(index, count, overlap, qpos, qh, qorder, allow_overlap)

    def _find_tree(self, pos, h, qpos, qh, same, allow_overlap=False) -> NeighbourList:
        lo, length, per = self.box.arrays()
        for d in range(self.box.ndim):
            if per[d] and self.radius * max(h.max(initial=0.0), qh.max(initial=0.0)) > 0.5 * length[d]:
                raise SimulationError(f"kernel support exceeds half the periodic box length along axis {d}")
        stree = build_tree(pos, h, self.box.ndim, self.leaf_size)
        qtree = stree if same else build_tree(qpos, qh, self.box.ndim, self.leaf_size)
        nq = qpos.shape[0]
        count = np.zeros(nq, np.int32)
        overlap = np.empty(nq, np.int64)
        while True:
            index = np.empty((nq, self._capacity), np.int32)
            tree_search(qpos, qh, qtree, pos, h, stree, length, per, self.radius, same, index, count, overlap)
            need = int(count.max(initial=0))
            if need <= self._capacity:
                break
            self._capacity = int(need * 1.25) + 8
        return self._finish(index, count, overlap, qpos, qh, qtree[0], allow_overlap)

    @staticmethod
    def _finish(index, count, overlap, qpos, qh, order, allow_overlap=False) -> NeighbourList:
        bad = np.flatnonzero(overlap >= 0) if not allow_overlap else np.empty(0, np.int64)
        if bad.size:
            a = int(bad[0])
            raise SimulationError(
                f"{bad.size} particles sit exactly on top of another (first: {a} and {int(overlap[a])})",
                state={"overlapping": bad, "partner": overlap[bad], "position": qpos[bad]},
            )
        return NeighbourList(index, count, np.array(qh, copy=True), order)
