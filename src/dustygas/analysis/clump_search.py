"""Neighbour search of the clump finder: particles sorted by mesh cell, spheres across sheared images.

:class:`SearchBox` sorts the particles by the cell of the deposit mesh once (a compiled counting
sort, ``O(N)``) and answers "which particles lie within ``r`` of this point" by visiting the cells
the sphere overlaps (:func:`_ball`), y and z periodic, and the radial images of the point queried
explicitly: the image ``n`` of a particle at ``(x, y)`` is at ``(x + nL_x, y - ns)`` and moves
``nqΩL_x`` slower in y (:mod:`dustygas.particles.boundaries`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["SearchBox"]


@njit(cache=True)
def _cell_list(pos, lower, dx, cells):
    """Particles sorted by mesh cell: ``(starts, order)`` with cell ``c`` holding
    ``order[starts[c]:starts[c + 1]]`` (a stable counting sort)."""
    nx, ny, nz = cells
    n = pos.shape[1]
    key = np.empty(n, dtype=np.int64)
    counts = np.zeros(nx * ny * nz + 1, dtype=np.int64)
    for p in range(n):
        i = min(max(int((pos[0, p] - lower[0]) / dx[0]), 0), nx - 1)
        j = min(max(int((pos[1, p] - lower[1]) / dx[1]), 0), ny - 1)
        k = min(max(int((pos[2, p] - lower[2]) / dx[2]), 0), nz - 1)
        key[p] = (k * ny + j) * nx + i
        counts[key[p] + 1] += 1
    starts = np.cumsum(counts)
    fill = starts[:-1].copy()
    order = np.empty(n, dtype=np.int64)
    for p in range(n):
        order[fill[key[p]]] = p
        fill[key[p]] += 1
    return starts, order


@njit(cache=True)
def _axis_range(lo, hi, origin, d, n, periodic):
    a = int(np.floor((lo - origin) / d))
    b = int(np.floor((hi - origin) / d))
    if periodic:
        if b - a + 1 >= n:
            return 0, n - 1
        return a, b
    return max(a, 0), min(b, n - 1)


@njit(cache=True)
def _ball(pos, starts, order, q, radius, lower, dx, cells, length, periodic_z):
    """Indices of the particles within ``radius`` of ``q``: y periodic (nearest image), z periodic
    if ``periodic_z``, x not (the caller queries the radial images)."""
    nx, ny, nz = cells
    i0, i1 = _axis_range(q[0] - radius, q[0] + radius, lower[0], dx[0], nx, False)
    j0, j1 = _axis_range(q[1] - radius, q[1] + radius, lower[1], dx[1], ny, True)
    k0, k1 = _axis_range(q[2] - radius, q[2] + radius, lower[2], dx[2], nz, periodic_z)
    r2 = radius * radius
    out = np.empty(0, dtype=np.int64)
    for sweep in range(2):  # count, then fill
        m = 0
        for k in range(k0, k1 + 1):
            kk = k % nz
            for j in range(j0, j1 + 1):
                jj = j % ny
                for i in range(i0, i1 + 1):
                    c = (kk * ny + jj) * nx + i
                    for a in range(starts[c], starts[c + 1]):
                        p = order[a]
                        d0 = pos[0, p] - q[0]
                        d1 = pos[1, p] - q[1]
                        d1 -= length[1] * np.floor(d1 / length[1] + 0.5)
                        d2 = pos[2, p] - q[2]
                        if periodic_z:
                            d2 -= length[2] * np.floor(d2 / length[2] + 0.5)
                        if d0 * d0 + d1 * d1 + d2 * d2 < r2:
                            if sweep == 1:
                                out[m] = p
                            m += 1
        if sweep == 0:
            out = np.empty(m, dtype=np.int64)
    return out


class SearchBox:
    """Geometry of the search: box, shear and the particles sorted by mesh cell."""

    def __init__(self, pos, box, cells, shear_offset, shear, periodic_z, q_omega_lx):
        self.lx, self.ly, self.lz = box
        self.s = float(shear_offset) if shear else 0.0
        self.shear = shear
        self.periodic_z = periodic_z
        self.jump = q_omega_lx if shear else 0.0
        self._cells = np.array(cells, dtype=np.int64)
        self._lower = np.array([-0.5 * v for v in box])
        self._dx = np.array([v / c for v, c in zip(box, cells)])
        self._length = np.array(box, dtype=np.float64)
        self._starts, self._order = _cell_list(pos, self._lower, self._dx, self._cells)

    def wrap(self, c):
        """A centre moved into the box (radially through the sheared images)."""
        x, y, z = c
        n = np.floor((x + 0.5 * self.lx) / self.lx)
        x -= n * self.lx
        y += n * self.s
        y = (y + 0.5 * self.ly) % self.ly - 0.5 * self.ly
        if self.periodic_z:
            z = (z + 0.5 * self.lz) % self.lz - 0.5 * self.lz
        return np.array([x, y, z])

    def separation(self, a, b):
        """Offsets ``a - b`` (``(3,)`` or ``(3, n)``) between points of the box, nearest images
        (sheared radially)."""
        d = np.asarray(a, dtype=np.float64) - np.asarray(b, dtype=np.float64)
        n = np.round(d[0] / self.lx)
        d[0] -= n * self.lx
        d[1] += n * self.s
        d[1] -= self.ly * np.round(d[1] / self.ly)
        if self.periodic_z:
            d[2] -= self.lz * np.round(d[2] / self.lz)
        return d

    def within(self, c, radius, pos, vel):
        """Indices, offsets from ``c`` (3, n) and image velocities (3, n) of the particles within
        ``radius`` of the centre ``c`` (in the box), radial images included."""
        idx, rel, v = [], [], []
        for image in (0, -1, 1):  # the particle's image x + image Lx, y - image s
            if image and abs(c[0] - image * self.lx) > 0.5 * self.lx + radius:
                continue  # the sphere does not reach that radial face
            q = np.array([c[0] - image * self.lx, c[1] + image * self.s, c[2]])
            found = _ball(pos, self._starts, self._order, q, radius, self._lower, self._dx, self._cells,
                          self._length, self.periodic_z)
            if found.size == 0:
                continue
            d = np.empty((3, found.size))
            d[0] = pos[0, found] + image * self.lx - c[0]
            d[1] = pos[1, found] - image * self.s - c[1]
            d[1] -= self.ly * np.round(d[1] / self.ly)
            d[2] = pos[2, found] - c[2]
            if self.periodic_z:
                d[2] -= self.lz * np.round(d[2] / self.lz)
            w = vel[:, found].copy()
            w[1] -= image * self.jump
            idx.append(found)
            rel.append(d)
            v.append(w)
        if not idx:
            return np.zeros(0, dtype=np.int64), np.zeros((3, 0)), np.zeros((3, 0))
        several = len(idx) > 1
        idx = np.concatenate(idx)
        # a particle reached through two images of a large sphere is kept once (the nearest)
        rel, v = np.concatenate(rel, axis=1), np.concatenate(v, axis=1)
        if several and np.unique(idx).size != idx.size:
            r2 = (rel**2).sum(axis=0)
            order = np.lexsort((r2, idx))
            keep = order[np.r_[True, idx[order][1:] != idx[order][:-1]]]
            idx, rel, v = idx[keep], rel[:, keep], v[:, keep]
        return idx, rel, v
