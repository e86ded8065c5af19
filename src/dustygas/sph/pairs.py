"""Pair geometry shared by the neighbour searches of :mod:`~dustygas.sph.neighbours` (cell list)
and :mod:`~dustygas.sph.kdtree` (k-d tree), and by the SPH sums that use their lists.

A pair :math:`(a, b)` are neighbours when :math:`r_{ab} < R\\max(h_a, h_b)` (the support of
either kernel of the symmetric SPH sums, thesis eqs. 3.2-3.4; Price 2012, J. Comput. Phys. 231,
759); separations along periodic dimensions are taken to the nearest image.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["minimum_image", "candidate_buffers", "gather_candidates", "scan_candidates", "store_neighbours"]


@njit(cache=True)
def minimum_image(dx: float, length: float, periodic: bool) -> float:
    """Separation ``dx`` mapped to the nearest periodic image (unchanged when not periodic)."""
    if periodic:
        if dx > 0.5 * length:
            return dx - length
        if dx < -0.5 * length:
            return dx + length
    return dx


@njit(inline="always")
def candidate_buffers(m):
    """Contiguous scratch arrays ``(x, y, z, h^2, index, d2)`` for ``m`` candidate neighbours."""
    return np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m, np.int64), np.empty(m)


@njit(inline="always")
def gather_candidates(nodes, nl, start, end, order, pos, h, px, py, pz, ph2, pid):
    """Copy the particles of the ``nl`` tree leaves ``nodes`` (positions, :math:`h^2`, indices) into the
    contiguous candidate arrays, in leaf order."""
    j = 0
    for t in range(nl):
        node = nodes[t]
        for k in range(start[node], end[node]):
            b = order[k]
            px[j] = pos[b, 0]
            py[j] = pos[b, 1]
            pz[j] = pos[b, 2]
            ph2[j] = h[b] * h[b]
            pid[j] = b
            j += 1


@njit(inline="always")
def scan_candidates(a, qpos, qh, m, px, py, pz, ph2, pid, d2, length, inv_l, r2, exclude_self, index, count,
                    overlap):
    """Test query ``a`` against the ``m`` gathered candidates and write its row of the list.

    Two vectorisable passes: ``d2 = r^2 - R^2 max(h_a, h_b)^2`` for every candidate (minimum image
    along the axes where ``inv_l = 1/L``, none where ``inv_l = 0``), then :func:`store_neighbours` keeps those with ``d2 < 0``.
    """
    xa, ya, za = qpos[a, 0], qpos[a, 1], qpos[a, 2]
    ha2 = qh[a] * qh[a]
    lx, ly, lz = length[0], length[1], length[2]  # scalars: the stores to d2 cannot alias them
    ilx, ily, ilz = inv_l[0], inv_l[1], inv_l[2]
    wrap_x, wrap_y, wrap_z = ilx != 0.0, ily != 0.0, ilz != 0.0  # loop-invariant branches
    for j in range(m):
        dx = xa - px[j]
        dy = ya - py[j]
        dz = za - pz[j]
        if wrap_x:
            dx -= lx * np.rint(dx * ilx)
        if wrap_y:
            dy -= ly * np.rint(dy * ily)
        if wrap_z:
            dz -= lz * np.rint(dz * ilz)
        d2[j] = (dx * dx + dy * dy + dz * dz) - r2 * max(ha2, ph2[j])
    store_neighbours(a, m, d2, pid, ph2, ha2, r2, exclude_self, index, count, overlap)


@njit(inline="always")
def store_neighbours(a, m, d2, pid, ph2, ha2, r2, exclude_self, index, count, overlap):
    """Write the candidates with d2 < 0 (inside max(h_a, h_b) * radius) into row a of the list.

    ``count[a]`` is the true number of neighbours even when it exceeds the row capacity (the caller
    then grows the list and searches again); ``overlap[a]`` records a neighbour at zero separation.
    """
    cap = index.shape[1]
    n = 0
    hit = -1
    for j in range(m):
        if d2[j] < 0.0:
            b = pid[j]
            if exclude_self and b == a:
                continue
            if d2[j] == -r2 * max(ha2, ph2[j]):
                hit = b  # zero separation
            if n < cap:
                index[a, n] = b
            n += 1
    count[a] = n
    overlap[a] = hit
