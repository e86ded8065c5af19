"""Conservative shift of a periodic column by a real number of cells.

Both the shear-periodic ghost zones (Hawley, Gammie & Balbus 1995; Stone & Gardiner 2010,
§3) and orbital advection (Masset 2000; Johnson, Guan & Gammie 2008) move a periodic
column of cell averages ``a_j`` by ``s`` cells along y. Write ``s = n + f`` with integer n and
``0 <= f < 1``; the integer part is a relabelling, the fractional part moves the amount

.. math::

    \\phi_{j+1/2} = \\frac1{\\Delta y}\\int_{y_{j+1/2} - f\\Delta y}^{y_{j+1/2}} a(y)\\,dy

of the reconstructed profile of cell j (same reconstruction as the scheme's) across its
right face, so that

.. math:: a^{new}_{j+n} = a_j - \\phi_{j+1/2} + \\phi_{j-1/2}.

The column sum is unchanged to round-off whatever the reconstruction. For a parabola with edge
values ``a_L, a_R`` and ``a_6 = 6(a - (a_L + a_R)/2)`` (CW84 eq. 1.5), the amount leaving through
the right face is ``f [a_R - f/2 (Δa - (1 - 2f/3) a_6)]`` with ``Δa = a_R - a_L`` (CW84 eq. 1.12);
a line with slope ``Δa`` gives ``f [a + (1 - f) Δa / 2]``.
"""

from __future__ import annotations

import math

from numba import njit

from .reconstruct import DONOR, PLM, PPM, cs08_face, cs08_parabola, cw84_monotone, cw84_slope, limited_slope

__all__ = ["shift_column"]


@njit(cache=True, error_model="numpy")
def shift_column(a, n: int, shift: float, method: int, limiter: int, out, work) -> None:
    """``out[j] = `` the periodic column ``a[0:n]`` moved by ``shift`` cells towards larger j.

    Parameters
    ----------
    a
        Cell averages; only ``a[0:n]`` is read (periodic).
    shift
        Displacement in cells (any real number).
    method, limiter
        Reconstruction codes of :mod:`dustygas.grid.reconstruct`.
    out
        Output, ``out[0:n]`` written.
    work
        Work array of length >= ``4 n + 19``.
    """
    whole = math.floor(shift)
    f = shift - whole
    m = int(whole) % n
    if f == 0.0 or n == 1:
        head, tail = out[m:], a[n - m:]
        for j in range(n - m):
            head[j] = a[j]
        for j in range(m):
            out[j] = tail[j]
        return
    # the column with three periodic ghosts per side: p[k] = a[(k - 3) mod n], k = 0 .. n + 5;
    # cell c = -1 .. n - 1 sits at p[c + 3], the transport through its right face is phi[c + 1]
    p = work[: n + 6]
    slope = work[n + 6: 2 * n + 12]
    face = work[2 * n + 12: 3 * n + 18]  # face[k]: between p[k - 1] and p[k]
    phi = work[3 * n + 18: 4 * n + 19]
    body = p[3:]
    for j in range(n):
        body[j] = a[j]
    if n >= 3:
        for j in range(3):
            p[j] = a[n - 3 + j]
            body[n + j] = a[j]
    else:
        for k in range(n + 6):
            p[k] = a[(k - 3) % n]
    # views so that loop indices start at 0 (see reconstruct.py)
    pm, p0, pp = p[1:], p[2:], p[3:]
    if method == DONOR:
        for j in range(n + 1):
            phi[j] = f * p0[j]
    elif method == PLM:
        for j in range(n + 1):
            phi[j] = f * (p0[j] + 0.5 * (1.0 - f) * limited_slope(p0[j] - pm[j], pp[j] - p0[j], limiter))
    else:
        if method == PPM:
            sl = slope[1:]
            for j in range(n + 4):  # slopes of p[1 .. n + 4]
                sl[j] = cw84_slope(p[j], pm[j], p0[j])
            fa = face[2:]
            s0 = slope[1:]
            s1 = slope[2:]
            for j in range(n + 3):  # faces 2 .. n + 4
                fa[j] = 0.5 * (pm[j] + p0[j]) - (s1[j] - s0[j]) / 6.0
        else:  # PPM_CS
            fa = face[2:]
            for j in range(n + 2):  # faces 2 .. n + 3
                fa[j] = cs08_face(p[j], pm[j], p0[j], pp[j])
        left = face[2:]
        right = face[3:]
        p1, p2 = p[4:], p[0:]
        for j in range(n + 1):  # cell at p[j + 2]
            a0 = p0[j]
            al, ar = left[j], right[j]
            if method == PPM:
                al, ar = cw84_monotone(a0, al, ar)
            else:
                al, ar = cs08_parabola(p2[j], pm[j], a0, pp[j], p1[j], al, ar)
            da = ar - al
            a6 = 6.0 * (a0 - 0.5 * (al + ar))
            phi[j] = f * (ar - 0.5 * f * (da - (1.0 - 2.0 * f / 3.0) * a6))
    head, right_face = out[m:], phi[1:]
    for j in range(n - m):
        head[j] = a[j] - right_face[j] + phi[j]
    tail_a, tail_l, tail_r = a[n - m:], phi[n - m:], phi[n - m + 1:]
    for j in range(m):
        out[j] = tail_a[j] - tail_r[j] + tail_l[j]
