"""Ghost cells of the cell fields other than the gas state: the fields the particles gather and deposit.

The gas state's ghosts follow its boundary kinds (:mod:`dustygas.grid.boundaries`); a particle-side
field needs only three rules, one per axis (:func:`field_ghost_kinds`): a copy one box length away, the
shear-periodic copy shifted along y, or a mirror image (every non-periodic kind: it keeps the sum of a
field under the symmetric grid-scale filter and folds a deposit back into the domain).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from .boundaries import PERIODIC, REFLECTING, _source_index
from .remap import shift_column

__all__ = ["FIELD_PERIODIC", "FIELD_SHEAR", "FIELD_MIRROR", "FIELD_NEIGHBOUR", "field_ghost_kinds", "field_ghost_pair",
           "z_source_row", "row_x_ghosts", "fill_field_ghosts"]

#: the x ghosts of a cell field (:func:`fill_field_ghosts`) are filled in parallel from this many values on
FIELD_PARALLEL_VALUES = 16384
#: the ghost rules (module docstring)
FIELD_PERIODIC, FIELD_SHEAR, FIELD_MIRROR = 0, 1, 2
#: a z face of a field whose ghosts another block provides (:mod:`dustygas.parallel`)
FIELD_NEIGHBOUR = 3


def field_ghost_kinds(kinds: tuple[str, str, str], active: tuple[bool, bool, bool]) -> np.ndarray:
    """Field ghost rule of each axis from the gas boundary kind names (inactive axes: periodic).

    >>> field_ghost_kinds(("shear-periodic", "periodic", "hydrostatic"), (True, True, True)).tolist()
    [1, 0, 2]
    """
    out = []
    for name, on in zip(kinds, active):
        if not on or name == "periodic":
            out.append(FIELD_PERIODIC)
        elif name == "shear-periodic":
            out.append(FIELD_SHEAR)
        else:
            out.append(FIELD_MIRROR)
    return np.array(out, dtype=np.int64)


@njit(cache=True, error_model="numpy")
def field_ghost_pair(kind, m, n, g):
    """Indices of the ``m``-th lower and upper ghost layers of a field and of the layers they copy
    (a mirror image like a reflecting wall, else periodic)."""
    src_kind = REFLECTING if kind == FIELD_MIRROR else PERIODIC
    return (g - 1 - m, g + n + m, _source_index(src_kind, True, m, n, g), _source_index(src_kind, False, m, n, g))


@njit(cache=True, error_model="numpy")
def z_source_row(k, nz, gz, kinds) -> int:
    """The padded z row whose cells the padded z row ``k`` of a field copies: ``k`` itself in the
    domain and beyond a face a neighbouring block fills (:data:`FIELD_NEIGHBOUR`), else the
    domain row of the face's rule (``kinds[2]``, or ``kinds[3]`` for the upper face if given)."""
    if gz <= k < gz + nz:
        return k
    lower = k < gz
    kind = kinds[2] if lower or kinds.shape[0] < 4 else kinds[3]
    if kind == FIELD_NEIGHBOUR:
        return k
    m = gz - 1 - k if lower else k - gz - nz
    lo, hi, slo, shi = field_ghost_pair(kind, m, nz, gz)
    return slo if lower else shi


@njit(cache=True, error_model="numpy")
def row_x_ghosts(row, nv, nx, gx, kind) -> None:
    """The x ghosts of the flattened padded row ``row`` (``(nx + 2 gx) nv`` values, ``nv`` per
    cell) from its domain cells, by a copy rule (periodic or mirror; a shear-periodic rule
    without y copies too)."""
    for m in range(gx):
        lo, hi, slo, shi = field_ghost_pair(kind, m, nx, gx)
        for v in range(nv):
            row[lo * nv + v] = row[slo * nv + v]
            row[hi * nv + v] = row[shi * nv + v]


@njit(cache=True, parallel=True, error_model="numpy")
def fill_field_ghosts(f, gx, gy, gz, kinds, shift, remap_method, remap_limiter, k_lo, k_hi) -> None:
    """Fill the ghost cells of a cell field ``f[NZ, NY, NX, nvar]`` (``g*`` ghost layers per side).

    ``kinds``: :data:`FIELD_PERIODIC`, :data:`FIELD_SHEAR` (x only) or :data:`FIELD_MIRROR` per
    axis; a fourth entry, if given, is the kind of the upper z face (then ``kinds[2]`` that of
    the lower one), and a z face of kind :data:`FIELD_NEIGHBOUR` is left alone (a block's
    neighbour fills it). A shear-periodic ghost column is the periodic column shifted conservatively by
    ``+shift`` cells along y on the inner side and ``-shift`` on the outer (the convention of
    the gas ghosts, :mod:`dustygas.grid.boundaries`; ``shift`` = shear offset / dy), without a velocity jump: fields that
    hold the azimuthal gas velocity store it relative to the background shear. Axes z, y, x in
    this order, each over the full extent of the others (edges and corners). The y and x
    ghosts are filled only in the padded z rows ``k_lo .. k_hi-1`` (all: ``0, NZ``).
    """
    NZ, NY, NX, nvar = f.shape
    nz, ny, nx = NZ - 2 * gz, NY - 2 * gy, NX - 2 * gx
    for k in range(NZ):  # the z ghost rows (z_source_row: k itself for the others)
        src = z_source_row(k, nz, gz, kinds)
        if src != k:
            f[k] = f[src]
    for m in range(gy):
        lo, hi, slo, shi = field_ghost_pair(kinds[1], m, ny, gy)
        for k in range(k_lo, k_hi):
            f[k, lo] = f[k, slo]
            f[k, hi] = f[k, shi]
    if gx > 0:  # rows in parallel: a ghost column copies (or remaps) domain columns of its row only
        shear = kinds[0] == FIELD_SHEAR and ny > 1
        nk = k_hi - k_lo
        if shear or nk * NY * nvar * gx >= FIELD_PARALLEL_VALUES:
            nchunk = min(nk, 64)
            for c in prange(nchunk):
                _field_x_ghost_rows(f, gx, gy, kinds[0], shear, shift, remap_method, remap_limiter,
                                    k_lo + c * nk // nchunk, k_lo + (c + 1) * nk // nchunk)
        elif nk > 0:  # a few values per row (2D x-z): a parallel region would cost more than the copies
            _field_x_ghost_rows(f, gx, gy, kinds[0], shear, shift, remap_method, remap_limiter, k_lo, k_hi)


@njit(cache=True, error_model="numpy")
def _field_x_ghost_rows(f, gx, gy, kind, shear, shift, remap_method, remap_limiter, k0, k1) -> None:
    """The x ghosts of :func:`fill_field_ghosts` in the padded z rows ``k0 .. k1-1``."""
    NZ, NY, NX, nvar = f.shape
    ny, nx = NY - 2 * gy, NX - 2 * gx
    col = np.empty(ny)
    out = np.empty(ny)
    work = np.empty(4 * ny + 19)
    for k in range(k0, k1):
        if not shear:
            for j in range(NY):
                row_x_ghosts(f[k, j].reshape(NX * nvar), nvar, nx, gx, kind)
            continue
        for m in range(gx):
            lo, hi, slo, shi = field_ghost_pair(kind, m, nx, gx)
            for side in range(2):
                dst = lo if side == 0 else hi
                src = slo if side == 0 else shi
                s = shift if side == 0 else -shift
                for v in range(nvar):
                    for j in range(ny):
                        col[j] = f[k, gy + j, src, v]
                    shift_column(col, ny, s, remap_method, remap_limiter, out, work)
                    for j in range(NY):
                        f[k, j, dst, v] = out[(j - gy) % ny]
