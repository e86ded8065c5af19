"""Tree upkeep, neighbour search and scheduling of the active particles of a block sub-step.

Used by :mod:`~dustygas.sph.timesteps` (hierarchical individual time steps). The k-d tree of
:mod:`~dustygas.sph.kdtree` is built now and then and *refitted* in between (:func:`refit_tree`:
the node boxes and largest smoothing lengths are recomputed for the current positions, the
particle order is kept), so a sub-step with few active particles costs :math:`O(N)` cheap
operations plus work proportional to the active particles:

* :func:`schedule` -- the particles whose step (or external-force step) ends at this tick, in
  tree order, grouped by leaf;
* :func:`active_search` -- their neighbour rows among all particles, split by species;
* :func:`drift_and_accrete` -- the drift of every particle and the accretion by the star.

Every loop writes only its own rows or runs serially: deterministic for any thread count.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from .kdtree import leaves_in_reach
from .pairs import gather_candidates, minimum_image
from .workshare import WORKERS, new_counter, next_chunk

__all__ = ["DEAD", "refit_tree", "leaf_of_particles", "active_search", "schedule", "drift_and_accrete"]

#: type of an accreted particle waiting to be removed at the end of the block (never active, no neighbour)
DEAD = 99


# --------------------------------------------------------------------------- tree


@njit(parallel=True, cache=True)
def refit_tree(pos, h, order, start, end, child, leaves, lo, hi, hmax):
    """Recompute every node's bounding box and largest ``h`` bottom-up (children are stored after
    their parents, :func:`dustygas.sph.kdtree.build_tree`); the particle order is kept."""
    for il in prange(leaves.shape[0]):
        node = leaves[il]
        x0 = y0 = z0 = np.inf
        x1 = y1 = z1 = -np.inf
        hm = 0.0
        for k in range(start[node], end[node]):
            i = order[k]
            x0 = min(x0, pos[i, 0])
            x1 = max(x1, pos[i, 0])
            y0 = min(y0, pos[i, 1])
            y1 = max(y1, pos[i, 1])
            z0 = min(z0, pos[i, 2])
            z1 = max(z1, pos[i, 2])
            hm = max(hm, h[i])
        lo[node, 0], lo[node, 1], lo[node, 2] = x0, y0, z0
        hi[node, 0], hi[node, 1], hi[node, 2] = x1, y1, z1
        hmax[node] = hm
    for node in range(start.shape[0] - 1, -1, -1):
        c = child[node]
        if c < 0:
            continue
        for d in range(3):
            lo[node, d] = min(lo[c, d], lo[c + 1, d])
            hi[node, d] = max(hi[c, d], hi[c + 1, d])
        hmax[node] = max(hmax[c], hmax[c + 1])


@njit(cache=True)
def leaf_of_particles(order, start, end, child, n):
    """The leaf holding each particle, and the list of leaves."""
    leaf = np.empty(n, np.int64)
    nleaves = 0
    for node in range(start.shape[0]):
        if child[node] < 0:
            nleaves += 1
            for k in range(start[node], end[node]):
                leaf[order[k]] = node
    leaves = np.empty(nleaves, np.int64)
    j = 0
    for node in range(start.shape[0]):
        if child[node] < 0:
            leaves[j] = node
            j += 1
    return leaf, leaves


#: groups of at least this many active particles gather their candidates into contiguous arrays first
GATHER_MIN = 4
#: groups per chunk of the parallel search (handed out dynamically: :mod:`~dustygas.sph.workshare`; each
#: worker allocates its scratch arrays once)
SEARCH_CHUNK = 32


@njit(inline="always")
def _enter(b, tb, ta, same_index, o_s, room_s, ns, cross_index, o_c, room_c, nc):
    """Append neighbour ``b`` (of type ``tb``) to the same- or other-species row of a particle of type ``ta``."""
    if tb == ta:
        if ns < room_s:
            same_index[o_s + ns] = b
        ns += 1
    else:
        if nc < room_c:
            cross_index[o_c + nc] = b
        nc += 1
    return ns, nc


@njit(parallel=True, cache=True)
def active_search(pos, h_src, ptype, act, group, h_query, order, start, end, child, lo, hi, hmax, radius,
                  length, periodic, same_start, same_room, same_index, same_count, cross_start, cross_room,
                  cross_index, cross_count):
    """Neighbour rows of the active particles ``act`` among all (living) particles.

    ``group`` delimits runs of ``act`` that share a tree leaf (``act[group[g]:group[g+1]]``); each run
    walks the tree once with the bounding box of its particles; runs of at least ``GATHER_MIN``
    particles gather the candidates into contiguous arrays first (a vectorised distance test), smaller
    ones (most of them: the active particles of a sub-step are sparse) test the leaves' particles in
    place, in the same order. A particle ``b`` enters the row of slot ``i`` (particle ``a = act[i]``) when
    :math:`r_{ab} < R\\max(h^q_i, h_b)` (``h_query`` per slot, ``h_src`` per particle): into the
    same-species row ``same_index[same_start[i]:][:same_count[i]]``, or the other-species row
    ``cross_*``. A row has room for ``*_room[i]`` entries; the counts are the true numbers even when
    they exceed it (the caller then searches those slots again with more room).
    """
    r2 = radius * radius
    wrap = periodic[0] or periodic[1] or periodic[2]
    ngroups = group.shape[0] - 1
    nchunk = (ngroups + SEARCH_CHUNK - 1) // SEARCH_CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        c = next_chunk(counter)
        if c >= nchunk:
            continue  # no work left for this worker: no scratch either
        qlo = np.empty(3)
        qhi = np.empty(3)
        nodes = np.empty(64, np.int64)
        stack = np.empty(128, np.int64)
        cap = 0
        px = py = pz = ph2 = d2 = np.empty(0)
        pid = np.empty(0, np.int64)
        while c < nchunk:
            for g in range(c * SEARCH_CHUNK, min((c + 1) * SEARCH_CHUNK, ngroups)):
                s0, s1 = group[g], group[g + 1]
                for d in range(3):
                    qlo[d] = np.inf
                    qhi[d] = -np.inf
                qh = 0.0
                for i in range(s0, s1):
                    a = act[i]
                    for d in range(3):
                        qlo[d] = min(qlo[d], pos[a, d])
                        qhi[d] = max(qhi[d], pos[a, d])
                    qh = max(qh, h_query[i])
                m, nl = leaves_in_reach(qlo, qhi, qh, lo, hi, hmax, child, start, end, length, periodic, r2, nodes,
                                        stack)
                if nl > nodes.shape[0]:
                    nodes = np.empty(2 * nl, np.int64)
                    leaves_in_reach(qlo, qhi, qh, lo, hi, hmax, child, start, end, length, periodic, r2, nodes, stack)
                gathered = s1 - s0 >= GATHER_MIN
                if gathered:
                    if m > cap:
                        cap = 2 * m
                        px = np.empty(cap)
                        py = np.empty(cap)
                        pz = np.empty(cap)
                        ph2 = np.empty(cap)
                        d2 = np.empty(cap)
                        pid = np.empty(cap, np.int64)
                    gather_candidates(nodes, nl, start, end, order, pos, h_src, px, py, pz, ph2, pid)
                for i in range(s0, s1):
                    a = act[i]
                    xa, ya, za = pos[a, 0], pos[a, 1], pos[a, 2]
                    ha2 = h_query[i] * h_query[i]
                    ta = ptype[a]
                    ns = nc = 0
                    o_s, room_s = same_start[i], same_room[i]
                    o_c, room_c = cross_start[i], cross_room[i]
                    if not gathered:  # test the leaves' particles in place
                        for t in range(nl):
                            node = nodes[t]
                            for k in range(start[node], end[node]):
                                b = order[k]
                                dx = minimum_image(xa - pos[b, 0], length[0], periodic[0])
                                dy = minimum_image(ya - pos[b, 1], length[1], periodic[1])
                                dz = minimum_image(za - pos[b, 2], length[2], periodic[2])
                                hb = h_src[b]
                                if dx * dx + dy * dy + dz * dz - r2 * max(ha2, hb * hb) < 0.0 and b != a \
                                        and ptype[b] != DEAD:
                                    ns, nc = _enter(b, ptype[b], ta, same_index, o_s, room_s, ns, cross_index, o_c,
                                                    room_c, nc)
                    else:
                        if wrap:
                            for j in range(m):
                                dx = minimum_image(xa - px[j], length[0], periodic[0])
                                dy = minimum_image(ya - py[j], length[1], periodic[1])
                                dz = minimum_image(za - pz[j], length[2], periodic[2])
                                d2[j] = dx * dx + dy * dy + dz * dz - r2 * max(ha2, ph2[j])
                        else:
                            for j in range(m):  # vectorised: no branch
                                dx = xa - px[j]
                                dy = ya - py[j]
                                dz = za - pz[j]
                                d2[j] = dx * dx + dy * dy + dz * dz - r2 * max(ha2, ph2[j])
                        for j in range(m):
                            b = pid[j]
                            if d2[j] < 0.0 and b != a and ptype[b] != DEAD:
                                ns, nc = _enter(b, ptype[b], ta, same_index, o_s, room_s, ns, cross_index, o_c, room_c,
                                                nc)
                    same_count[i] = ns
                    cross_count[i] = nc
            c = next_chunk(counter)


@njit(cache=True)
def schedule(order, level, ext_level, wake, ptype, tick, log2_ticks):
    """The particles active at ``tick``, in tree order: those whose step ends there (``level``) or that
    were woken (``act``), and those whose external-force step ends there but not their step
    (``ext_only``). Dead particles are never active."""
    n = order.shape[0]
    act = np.empty(n, np.int64)
    ext = np.empty(n, np.int64)
    na = 0
    ne = 0
    one = np.int64(1)
    for k in range(n):
        a = order[k]
        if ptype[a] == DEAD:
            continue
        if wake[a] or tick & ((one << (log2_ticks - level[a])) - one) == 0:  # tick a multiple of the step
            act[na] = a
            na += 1
        elif tick & ((one << (log2_ticks - ext_level[a])) - one) == 0:
            ext[ne] = a
            ne += 1
    return act[:na], ext[:ne]


@njit(cache=True)
def drift_and_accrete(pos, vel, mass, ptype, dt, accretion_radius, accreted):
    """Drift every particle by ``dt``; particles that come within ``accretion_radius`` of the origin
    become ``DEAD`` and add their mass, momentum and angular momentum to ``accreted`` (7 numbers).
    Returns how many were accreted."""
    r2acc = accretion_radius * accretion_radius
    count = 0
    for a in range(pos.shape[0]):
        if ptype[a] == DEAD:
            continue
        x = pos[a, 0] + dt * vel[a, 0]
        y = pos[a, 1] + dt * vel[a, 1]
        z = pos[a, 2] + dt * vel[a, 2]
        pos[a, 0], pos[a, 1], pos[a, 2] = x, y, z
        if x * x + y * y + z * z < r2acc:
            m = mass[a]
            vx, vy, vz = vel[a, 0], vel[a, 1], vel[a, 2]
            accreted[0] += m
            accreted[1] += m * vx
            accreted[2] += m * vy
            accreted[3] += m * vz
            accreted[4] += m * (y * vz - z * vy)
            accreted[5] += m * (z * vx - x * vz)
            accreted[6] += m * (x * vy - y * vx)
            ptype[a] = DEAD
            count += 1
    return count
