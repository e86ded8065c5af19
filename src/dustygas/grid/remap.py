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
def shift_column(a, n: int, shift: float, method: int, limiter: int, out, phi) -> None:
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
    phi
        Work array of length >= n (face transports).
    """
    whole = math.floor(shift)
    f = shift - whole
    m = int(whole) % n
    if f == 0.0 or n == 1:
        for j in range(n):
            out[(j + m) % n] = a[j]
        return
    for j in range(n):
        a0 = a[j]
        am = a[j - 1] if j > 0 else a[n - 1]
        ap = a[j + 1] if j < n - 1 else a[0]
        if method == DONOR:
            phi[j] = f * a0
        elif method == PLM:
            phi[j] = f * (a0 + 0.5 * (1.0 - f) * limited_slope(a0 - am, ap - a0, limiter))
        else:
            amm = a[(j - 2) % n]
            app = a[(j + 2) % n]
            if method == PPM:
                sm = cw84_slope(amm, am, a0)
                s0 = cw84_slope(am, a0, ap)
                sp = cw84_slope(a0, ap, app)
                al = 0.5 * (am + a0) - (s0 - sm) / 6.0
                ar = 0.5 * (a0 + ap) - (sp - s0) / 6.0
                al, ar = cw84_monotone(a0, al, ar)
            else:  # PPM_CS
                al = cs08_face(amm, am, a0, ap)
                ar = cs08_face(am, a0, ap, app)
                al, ar = cs08_parabola(amm, am, a0, ap, app, al, ar)
            da = ar - al
            a6 = 6.0 * (a0 - 0.5 * (al + ar))
            phi[j] = f * (ar - 0.5 * f * (da - (1.0 - 2.0 * f / 3.0) * a6))
    for j in range(n):
        left = phi[j - 1] if j > 0 else phi[n - 1]
        out[(j + m) % n] = a[j] - phi[j] + left
