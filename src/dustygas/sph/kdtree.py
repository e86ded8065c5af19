"""A k-d tree neighbour search for strongly clustered particles (disks, collapsing clouds).

The uniform cell list of :mod:`~dustygas.sph.neighbours` sizes every cell for the largest
smoothing length, which is wasteful when :math:`h` spans orders of magnitude. Here particles are
split recursively at the median of the longest side of their bounding box into leaves of at most
``leaf_size``; every node stores its bounding box and the largest :math:`h` below it. For each
leaf the tree is walked once, opening only nodes whose box comes closer to the leaf's box than
:math:`R\\max(h^{\\rm leaf}_{\\max}, h^{\\rm node}_{\\max})` (periodic boxes by minimum image); the
particles of the leaves reached are then tested pair by pair with the exact criterion
:math:`r_{ab} < R\\max(h_a, h_b)`. Leaves are processed in parallel, each writing only its own
particles' rows, so the table is deterministic. The output is the same
:class:`~dustygas.sph.neighbours.NeighbourList` as the cell list's (rows in a different order).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from .pairs import candidate_buffers, gather_candidates, minimum_image, scan_candidates
from .workshare import WORKERS, new_counter, next_chunk

__all__ = ["build_tree", "tree_search"]

#: query leaves per chunk of the parallel search (about 100 particles)
LEAF_CHUNK = 8


@njit(cache=True)
def _select(idx, key, lo, hi, k):
    """Reorder ``idx[lo:hi]`` so that ``key[idx[k]]`` is the k-th smallest (Hoare's quickselect)."""
    while hi - lo > 1:
        pivot = key[idx[(lo + hi) // 2]]
        i, j = lo, hi - 1
        while i <= j:
            while key[idx[i]] < pivot:
                i += 1
            while key[idx[j]] > pivot:
                j -= 1
            if i <= j:
                idx[i], idx[j] = idx[j], idx[i]
                i += 1
                j -= 1
        if k <= j:
            hi = j + 1
        elif k >= i:
            lo = i
        else:
            return


@njit(cache=True)
def build_tree(pos, h, ndim, leaf_size):
    """Nodes ``(start, end, child, lo, hi, hmax)`` over the permutation ``order`` of the particles;
    ``child[i]`` is the first of two consecutive children (-1 for a leaf)."""
    n = pos.shape[0]
    max_nodes = 2 * (n // max(leaf_size // 2, 1) + 1) + 1
    start = np.empty(max_nodes, np.int64)
    end = np.empty(max_nodes, np.int64)
    child = np.full(max_nodes, -1, np.int64)
    lo = np.empty((max_nodes, 3))
    hi = np.empty((max_nodes, 3))
    hmax = np.empty(max_nodes)
    order = np.arange(n)
    key = np.empty(n)
    start[0] = 0
    end[0] = n
    count = 1
    stack = np.empty(128, np.int64)
    top = 0
    stack[top] = 0
    top += 1
    while top > 0:
        top -= 1
        node = stack[top]
        s, e = start[node], end[node]
        for d in range(3):
            lo[node, d] = np.inf
            hi[node, d] = -np.inf
        hm = 0.0
        for k in range(s, e):
            i = order[k]
            for d in range(3):
                lo[node, d] = min(lo[node, d], pos[i, d])
                hi[node, d] = max(hi[node, d], pos[i, d])
            hm = max(hm, h[i])
        hmax[node] = hm
        if e - s <= leaf_size:
            continue
        axis = 0
        for d in range(1, ndim):
            if hi[node, d] - lo[node, d] > hi[node, axis] - lo[node, axis]:
                axis = d
        for k in range(s, e):
            key[order[k]] = pos[order[k], axis]
        mid = (s + e) // 2
        _select(order, key, s, e, mid)
        child[node] = count
        start[count], end[count] = s, mid
        start[count + 1], end[count + 1] = mid, e
        stack[top] = count
        stack[top + 1] = count + 1
        top += 2
        count += 2
    return order, start[:count], end[:count], child[:count], lo[:count], hi[:count], hmax[:count]


@njit(inline="always")
def node_gap2(qlo, qhi, lo, hi, node, length, periodic):
    """Squared distance between the query box ``[qlo, qhi]`` and the box ``[lo[node], hi[node]]`` of a
    tree node: the gap between the boxes along each axis (0 where they overlap), minimum image along
    periodic axes."""
    g2 = 0.0
    for d in range(3):
        ca = 0.5 * (qlo[d] + qhi[d])
        cb = 0.5 * (lo[node, d] + hi[node, d])
        sep = abs(minimum_image(ca - cb, length[d], periodic[d]))
        gap = sep - 0.5 * (qhi[d] - qlo[d]) - 0.5 * (hi[node, d] - lo[node, d])
        if gap > 0.0:
            g2 += gap * gap
    return g2


@njit(cache=True)
def leaves_in_reach(qlo, qhi, qh, lo, hi, hmax, child, start, end, length, periodic, r2, out, stack):
    """The leaves of a tree that particles of the query box ``[qlo, qhi]`` may reach.

    A node is opened unless its box stays farther from the query box than
    :math:`R\\max(h_q, h^{\\rm node}_{\\max})` (``r2`` = :math:`R^2`, ``qh`` = :math:`h_q` the largest
    query smoothing length), so every pair with :math:`r_{ab} < R\\max(h_a, h_b)` lies in the
    leaves found. ``(lo, hi, hmax, child, start, end)`` are the node arrays of :func:`build_tree`
    (or refitted ones). The leaves are written to ``out`` while there is room (call again with a
    larger ``out`` when the returned count exceeds it); ``stack`` is scratch for 128 nodes. Returns
    the number of particles the leaves hold and the number of leaves.
    """
    stack[0] = 0
    top = 1
    total = 0
    nl = 0
    while top > 0:
        top -= 1
        node = stack[top]
        reach = max(qh, hmax[node])
        if node_gap2(qlo, qhi, lo, hi, node, length, periodic) >= r2 * reach * reach:
            continue
        c = child[node]
        if c >= 0:
            stack[top] = c
            stack[top + 1] = c + 1
            top += 2
            continue
        if nl < out.shape[0]:
            out[nl] = node
        nl += 1
        total += end[node] - start[node]
    return total, nl


@njit(parallel=True, cache=True)
def tree_search(qpos, qh, qtree, spos, sh, stree, length, periodic, radius, exclude_self, index, count, overlap):
    """Neighbour rows of the queries (tree ``qtree``) among the sources (tree ``stree``): per query
    leaf, the particles of the source leaves in reach are gathered into contiguous arrays once and
    tested against each query particle in two vectorisable passes (as in the cell list)."""
    qorder, qstart, qend, qchild, qlo, qhi, qhmax = qtree
    sorder, sstart, send, schild, slo, shi, shmax = stree
    r2 = radius * radius
    inv_l = serial_full(3, 0.0)
    for d in range(3):
        if periodic[d]:
            inv_l[d] = 1.0 / length[d]
    leaves = np.flatnonzero(qchild == -1)
    n_items = leaves.shape[0]
    n_chunks = (n_items + LEAF_CHUNK - 1) // LEAF_CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for il in range(chunk * LEAF_CHUNK, min(n_items, (chunk + 1) * LEAF_CHUNK)):
                leaf = leaves[il]
                stack = np.empty(128, np.int64)
                nodes = np.empty(64, np.int64)
                m, nl = leaves_in_reach(qlo[leaf], qhi[leaf], qhmax[leaf], slo, shi, shmax, schild, sstart, send,
                                        length, periodic, r2, nodes, stack)
                if nl > nodes.shape[0]:
                    nodes = np.empty(nl, np.int64)
                    leaves_in_reach(qlo[leaf], qhi[leaf], qhmax[leaf], slo, shi, shmax, schild, sstart, send,
                                    length, periodic, r2, nodes, stack)
                px, py, pz, ph2, pid, d2 = candidate_buffers(m)
                gather_candidates(nodes, nl, sstart, send, sorder, spos, sh, px, py, pz, ph2, pid)
                for k in range(qstart[leaf], qend[leaf]):
                    scan_candidates(qorder[k], qpos, qh, m, px, py, pz, ph2, pid, d2, length, inv_l, r2, exclude_self,
                                    index, count, overlap)
            chunk = next_chunk(counter)
