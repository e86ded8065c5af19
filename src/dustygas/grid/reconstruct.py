"""Reconstruction of face states along one pencil of cells.

All functions work on a pencil buffer ``w[var, s]`` of *primitive* variables (density and
velocities, normal component first) and write the left and right states of faces
``lo .. hi``: face ``f`` separates cells ``f - 1`` and ``f``, ``wl[var, f]`` is the state on its
left (the right edge of cell ``f - 1``), ``wr[var, f]`` the state on its right.

Methods
-------
donor
    Piecewise constant (first order): ``wl[f] = w[f-1]``, ``wr[f] = w[f]``. Used by the VL2
    predictor (Stone & Gardiner 2009, §2).
plm
    Piecewise linear (second order) with a slope limiter on the one-sided differences
    ``dl = w_c - w_{c-1}``, ``dr = w_{c+1} - w_c`` (zero slope where ``dl dr <= 0``):

    * ``minmod``: ``sign * min(|dl|, |dr|)``;
    * ``vanleer``: ``2 dl dr / (dl + dr)`` (van Leer 1974);
    * ``mc``: ``sign * min(2|dl|, 2|dr|, |dl + dr| / 2)`` (monotonised central, van Leer 1977).
ppm
    Piecewise parabolic (Colella & Woodward 1984, hereafter CW84): limited centred slopes
    (CW84 eqs. 1.7-1.8), fourth-order interface values (eq. 1.6 on a uniform mesh,
    ``a_{j+1/2} = (a_j + a_{j+1})/2 - (da_{j+1} - da_j)/6``), then the monotonicity
    constraints on each parabola (eq. 1.10). No characteristic tracing: in the VL2 corrector
    and in the Runge-Kutta stages the reconstructed state is already time-centred.
ppm-cs
    PPM with the extremum-preserving limiter of Colella & Sekora (2008, J. Comput. Phys. 227,
    7069; hereafter CS08): unlimited fourth-order interface values
    ``a_{j+1/2} = 7/12 (a_j + a_{j+1}) - 1/12 (a_{j-1} + a_{j+2})``, limited only where they
    leave ``[a_j, a_{j+1}]`` (CS08 eqs. 13-15); at an extremum of the data or of the parabola
    the curvature is limited by the neighbouring second differences (``C = 1.25``, CS08
    eqs. 16-20) instead of flattening the parabola, otherwise the CW84 overshoot rule. Smooth
    extrema keep their accuracy: third order (with a third-order time integrator) where
    CW84's flattening gives second.

The same limiter formulas serve the conservative remap of :mod:`dustygas.grid.remap`.
"""

from __future__ import annotations

from numba import njit

__all__ = [
    "DONOR", "PLM", "PPM", "PPM_CS", "RECONSTRUCTIONS", "STENCIL_DEPTH",
    "MINMOD", "VANLEER", "MC", "LIMITERS",
    "limited_slope", "cw84_slope", "cw84_face", "cw84_monotone", "cs08_unlimited_face", "cs08_face", "cs08_overshoot",
    "cs08_is_extremum", "cs08_parabola", "reconstruct_faces",
]

DONOR, PLM, PPM, PPM_CS = 0, 1, 2, 3
#: name -> code of the reconstruction methods
RECONSTRUCTIONS = {"donor": DONOR, "plm": PLM, "ppm": PPM, "ppm-cs": PPM_CS}
#: code -> ghost layers the faces of the first and last domain cells read (:func:`reconstruct_faces`)
STENCIL_DEPTH = {DONOR: 1, PLM: 2, PPM: 3, PPM_CS: 3}

MINMOD, VANLEER, MC = 0, 1, 2
#: name -> code of the PLM slope limiters
LIMITERS = {"minmod": MINMOD, "vanleer": VANLEER, "mc": MC}


@njit(cache=True, error_model="numpy", inline="always")
def limited_slope(dl: float, dr: float, limiter: int) -> float:
    """Limited slope (per cell) from the one-sided differences ``dl``, ``dr``."""
    p = dl * dr
    if p <= 0.0:
        return 0.0
    if limiter == VANLEER:
        return 2.0 * p / (dl + dr)
    adl = abs(dl)
    adr = abs(dr)
    if limiter == MINMOD:
        s = min(adl, adr)
    else:  # MC
        s = min(2.0 * min(adl, adr), 0.5 * abs(dl + dr))
    return s if dl > 0.0 else -s


@njit(cache=True, error_model="numpy", inline="always")
def cw84_slope(wm: float, w0: float, wp: float) -> float:
    """CW84 eqs. 1.7-1.8: centred slope limited to twice the one-sided differences."""
    dl = w0 - wm
    dr = wp - w0
    if dl * dr <= 0.0:
        return 0.0
    dc = 0.5 * (dl + dr)
    s = min(abs(dc), 2.0 * min(abs(dl), abs(dr)))
    return s if dc > 0.0 else -s


@njit(cache=True, error_model="numpy", inline="always")
def cw84_monotone(a: float, al: float, ar: float) -> tuple[float, float]:
    """CW84 eq. 1.10: edge values ``(al, ar)`` of a parabola without new extrema in its cell."""
    if (ar - a) * (a - al) <= 0.0:
        return a, a
    da = ar - al
    a6 = 6.0 * (a - 0.5 * (al + ar))
    if da * a6 > da * da:
        al = 3.0 * a - 2.0 * ar
    elif -da * da > da * a6:
        ar = 3.0 * a - 2.0 * al
    return al, ar


CS08_C = 1.25  # CS08's bound on the limited curvature relative to its neighbours


@njit(cache=True, error_model="numpy", inline="always")
def _same_sign_min(d, d1, d2, d3) -> float:
    """``sign(d) min(|d|, C|d1|, C|d2|, C|d3|)`` if all four share a sign, else 0."""
    if d > 0.0 and d1 > 0.0 and d2 > 0.0 and d3 > 0.0:
        return min(d, CS08_C * min(d1, min(d2, d3)))
    if d < 0.0 and d1 < 0.0 and d2 < 0.0 and d3 < 0.0:
        return max(d, CS08_C * max(d1, max(d2, d3)))
    return 0.0


@njit(cache=True, error_model="numpy", inline="always")
def cs08_face(am: float, a0: float, ap: float, app: float) -> float:
    """CS08 interface value between cells 0 and p (neighbours m and pp), eqs. 13-15."""
    face = cs08_unlimited_face(am, a0, ap, app)
    if (face - a0) * (ap - face) < 0.0:
        d2 = 3.0 * (a0 - 2.0 * face + ap)
        d2l = am - 2.0 * a0 + ap
        d2r = a0 - 2.0 * ap + app
        face = 0.5 * (a0 + ap) - _same_sign_min(d2, d2l, d2r, d2) / 6.0
    return face


@njit(cache=True, error_model="numpy", inline="always")
def cs08_parabola(amm: float, am: float, a0: float, ap: float, app: float, al: float, ar: float) -> tuple[float, float]:
    """CS08 edge values of cell 0's parabola from its interface values ``al``, ``ar``."""
    if cs08_is_extremum(am, a0, ap, al, ar):
        d2 = 6.0 * (al + ar - 2.0 * a0)
        if d2 == 0.0:
            return a0, a0
        lim = _same_sign_min(d2, amm - 2.0 * am + a0, am - 2.0 * a0 + ap, a0 - 2.0 * ap + app)
        return a0 + (al - a0) * lim / d2, a0 + (ar - a0) * lim / d2
    if abs(ar - a0) >= 2.0 * abs(al - a0):
        ar = a0 - 2.0 * (al - a0)
    if abs(al - a0) >= 2.0 * abs(ar - a0):
        al = a0 - 2.0 * (ar - a0)
    return al, ar


@njit(cache=True, error_model="numpy", inline="always")
def cs08_unlimited_face(am: float, a0: float, ap: float, app: float) -> float:
    """CS08 eq. 13: the unlimited fourth-order interface value between cells 0 and p."""
    return (7.0 * (a0 + ap) - (am + app)) / 12.0


@njit(cache=True, error_model="numpy", inline="always")
def cs08_overshoot(a0: float, al: float, ar: float) -> tuple[float, float]:
    """The overshoot rule of :func:`cs08_parabola` (its last branch) as selects, which vectorise."""
    ar = a0 - 2.0 * (al - a0) if abs(ar - a0) >= 2.0 * abs(al - a0) else ar
    al = a0 - 2.0 * (ar - a0) if abs(al - a0) >= 2.0 * abs(ar - a0) else al
    return al, ar


@njit(cache=True, error_model="numpy", inline="always")
def cs08_is_extremum(am: float, a0: float, ap: float, al: float, ar: float) -> bool:
    """Whether :func:`cs08_parabola` takes its extremum branch in cell 0."""
    return (ar - a0) * (a0 - al) <= 0.0 or (a0 - am) * (ap - a0) <= 0.0


@njit(cache=True, error_model="numpy", inline="always")
def cw84_face(a0: float, ap: float, s0: float, sp: float) -> float:
    """CW84 eq. 1.6 on a uniform mesh: the interface value between cells 0 and p from their slopes."""
    return 0.5 * (a0 + ap) - (sp - s0) / 6.0


# The loops below index views that start at the first cell they need, one view per neighbour
# offset, with the loop index alone: numba then knows every index is non-negative and drops its
# negative-index wraparound handling, which otherwise costs a factor of four in these loops. The
# limiter functions above are inlined by numba itself (``inline="always"``): as calls LLVM kept
# them out of line, which made the PPM-CS loops about twice as slow (measured at 64 cells, same
# arithmetic, same bits).
#
# ``k`` is the distance between neighbouring cells in the buffer: 1 for one pencil, ``B`` for a
# block of ``B`` pencils stored cell-major (``w[var, s B + c]``: cell ``s`` of pencil ``c``,
# :mod:`dustygas.grid.sweep_columns`). A loop over ``m`` cells or faces of a pencil then runs over
# ``m k`` buffer entries, every pencil of the block at once.


@njit(cache=True, error_model="numpy")
def _ppm_cs(w, lo, hi, wl, wr, face, k):
    nface = (hi - lo + 3) * k  # faces lo-1 .. hi+1
    ncell = (hi - lo + 2) * k  # cells lo-1 .. hi
    f0 = face[(lo - 1) * k:]
    f1 = face[lo * k:]
    for v in range(w.shape[0]):
        a0 = w[v, (lo - 3) * k:]
        a1 = w[v, (lo - 2) * k:]
        a2 = w[v, (lo - 1) * k:]
        a3 = w[v, lo * k:]
        a4 = w[v, (lo + 1) * k:]
        # the unlimited fourth-order faces (a loop the compiler vectorises), then the rare ones
        # outside their neighbours limited: the same values as cs08_face everywhere
        for i in range(nface):  # face lo-1+i between cells a1 and a2
            f0[i] = cs08_unlimited_face(a0[i], a1[i], a2[i], a3[i])
        for i in range(nface):
            if (f0[i] - a1[i]) * (a2[i] - f0[i]) < 0.0:
                f0[i] = cs08_face(a0[i], a1[i], a2[i], a3[i])
        right = wr[v, (lo - 1) * k:]
        left = wl[v, lo * k:]
        # the overshoot rule of cs08_parabola as selects (vectorised), then its extremum branch
        # where it applies (the same values as cs08_parabola everywhere); cell lo-1+i is a2
        for i in range(ncell):
            right[i], left[i] = cs08_overshoot(a2[i], f0[i], f1[i])
        for i in range(ncell):
            if cs08_is_extremum(a1[i], a2[i], a3[i], f0[i], f1[i]):
                right[i], left[i] = cs08_parabola(a0[i], a1[i], a2[i], a3[i], a4[i], f0[i], f1[i])


@njit(cache=True, error_model="numpy")
def _donor(w, lo, hi, wl, wr, k):
    nface = (hi - lo + 1) * k
    for v in range(w.shape[0]):
        am = w[v, (lo - 1) * k:]
        a0 = w[v, lo * k:]
        left = wl[v, lo * k:]
        right = wr[v, lo * k:]
        for i in range(nface):
            left[i] = am[i]
            right[i] = a0[i]


@njit(cache=True, error_model="numpy")
def _plm(w, lo, hi, limiter, wl, wr, k):
    ncell = (hi - lo + 2) * k  # cells lo-1 .. hi
    for v in range(w.shape[0]):
        am = w[v, (lo - 2) * k:]
        a0 = w[v, (lo - 1) * k:]
        ap = w[v, lo * k:]
        left = wl[v, lo * k:]
        right = wr[v, (lo - 1) * k:]
        for i in range(ncell):
            s = 0.5 * limited_slope(a0[i] - am[i], ap[i] - a0[i], limiter)
            left[i] = a0[i] + s
            right[i] = a0[i] - s


@njit(cache=True, error_model="numpy")
def _ppm(w, lo, hi, wl, wr, slope, face, k):
    nslope = (hi - lo + 4) * k  # cells lo-2 .. hi+1
    nface = (hi - lo + 3) * k  # faces lo-1 .. hi+1
    ncell = (hi - lo + 2) * k  # cells lo-1 .. hi
    s0 = slope[(lo - 2) * k:]
    s1 = slope[(lo - 1) * k:]
    f0 = face[(lo - 1) * k:]
    f1 = face[lo * k:]
    for v in range(w.shape[0]):
        a0 = w[v, (lo - 3) * k:]
        a1 = w[v, (lo - 2) * k:]
        a2 = w[v, (lo - 1) * k:]
        for i in range(nslope):  # cell lo-2+i is a1
            s0[i] = cw84_slope(a0[i], a1[i], a2[i])
        for i in range(nface):  # face lo-1+i between cells lo-2+i (a1) and lo-1+i (a2)
            f0[i] = cw84_face(a1[i], a2[i], s0[i], s1[i])
        right = wr[v, (lo - 1) * k:]
        left = wl[v, lo * k:]
        for i in range(ncell):  # cell lo-1+i is a2
            right[i], left[i] = cw84_monotone(a2[i], f0[i], f1[i])


@njit(cache=True, error_model="numpy")
def reconstruct_faces(w, lo, hi, method, limiter, wl, wr, scratch, k=1):
    """Left/right states ``wl[:, f]``, ``wr[:, f]`` at faces ``f = lo .. hi`` of a pencil.

    Parameters
    ----------
    w
        Primitive variables ``(nvar, N)`` along the pencil, ghost cells included; needs
        ``lo - 1 .. hi`` (donor), ``lo - 2 .. hi + 1`` (plm) or ``lo - 3 .. hi + 2`` (ppm, ppm-cs).
    method, limiter
        Codes from :data:`RECONSTRUCTIONS` and :data:`LIMITERS`.
    wl, wr
        Output ``(nvar, N + 1)``.
    scratch
        Work array ``(2, N + 1)`` (PPM slopes and interface values).
    k
        Neighbouring cells are ``k`` entries apart: ``k`` pencils stored cell-major (cell ``s``
        of pencil ``c`` at ``s k + c``; arrays ``(nvar, N k)`` and ``(nvar, (N + 1) k)``) are
        reconstructed together, face ``f`` of pencil ``c`` written at ``f k + c``.
    """
    if method == DONOR:
        _donor(w, lo, hi, wl, wr, k)
    elif method == PLM:
        _plm(w, lo, hi, limiter, wl, wr, k)
    elif method == PPM:
        _ppm(w, lo, hi, wl, wr, scratch[0], scratch[1], k)
    else:
        _ppm_cs(w, lo, hi, wl, wr, scratch[0], k)
