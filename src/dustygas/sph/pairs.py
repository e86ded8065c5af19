"""Pair geometry shared by the neighbour searches of :mod:`~dustygas.sph.neighbours` (cell list)
and :mod:`~dustygas.sph.kdtree` (k-d tree), and by the SPH sums that use their lists.

A pair :math:`(a, b)` are neighbours when :math:`r_{ab} < R\\max(h_a, h_b)` (the support of
either kernel of the symmetric SPH sums, thesis eqs. 3.2-3.4; Price 2012, J. Comput. Phys. 231,
759); separations along periodic dimensions are taken to the nearest image.
"""

from __future__ import annotations

from numba import njit

__all__ = ["minimum_image", "store_neighbours"]


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
