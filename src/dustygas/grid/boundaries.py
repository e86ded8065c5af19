"""Ghost zones: the one place of the grid engine that knows about neighbours.

Every stage of the integrator starts by calling :func:`fill_ghosts` on the state it reads;
the sweep kernels only ever read ghost cells, they never ask where the data came from. A new
kind of boundary (another MPI rank's data, a wall with inflow...) is a new code here and
nothing else changes.

Kinds, registered by name in :data:`BOUNDARY_KINDS` (each side of each axis has one):

periodic
    ghost = the cell one box length away.
shear-periodic
    (x only, both sides) the radial images of a shearing box slide in y by
    ``q Omega Lx t`` (:func:`~dustygas.grid.shearing_box.shear_offset`): each ghost column
    is the periodic column one box length away shifted conservatively by that offset
    (:func:`~dustygas.grid.remap.shift_column`: integer shift plus a reconstructed fractional
    one, as in Stone & Gardiner 2010, §3), and unless the velocity is stored relative to the
    shear, ``rho v_y`` gains ``+/- q Omega Lx rho`` on the inner/outer side.
outflow
    zero gradient: ghost = the last domain cell.
reflecting
    mirror image with the normal momentum reversed.
hydrostatic
    (z only, with vertical gravity) an open boundary for a stratified isothermal box: the
    velocity of the last domain cell is copied and the density continues the hydrostatic
    profile ``rho ~ exp(-z^2 / 2H^2)``, ``H = c_s / Omega``, so that the boundary does not pull
    the atmosphere down as zero-gradient ``outflow`` does, and a column at rest stays at rest.
    The vertical velocity is copied in both directions: a boundary that lets gas out but
    not in (``v_z`` set to zero when it points inwards) rectifies the vertical oscillations of
    a turbulent layer into a steady outflow (a settling dust layer in a box of ±0.15 H lost
    12 % of its gas in 3 Ω⁻¹ that way, 0.4 % with the symmetric copy).
neighbour
    (internal code only, set per face by :mod:`dustygas.parallel`) the face borders another
    block: its ghosts are left alone here, the halo exchange fills them before the stage.

Ghosts are filled axis by axis, z, y, then x, each over the full extent of the other two
axes, so edges and corners are right too (the particle module's TSC weights need them).

:func:`correct_radial_fluxes` makes a shear-periodic box conserve mass (and obey the
y-momentum budget) to round-off: the flux through the inner radial face is the same
physical flux as the one through the outer face one shear offset away, so both are replaced
by the average of their own value and the conservatively remapped value of the other side
(with the ``q Omega Lx`` shift of ``rho v_y``). The sums over each face then agree exactly:
``sum F_rho(in) = sum F_rho(out)`` and ``sum F_y(out) - sum F_y(in) = -q Omega Lx sum F_rho``.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from ..errors import SetupError
from .remap import shift_column
from .shearing_box import shear_offset

__all__ = [
    "PERIODIC", "SHEAR_PERIODIC", "OUTFLOW", "NEIGHBOUR", "REFLECTING", "HYDROSTATIC", "BOUNDARY_KINDS",
    "Boundaries", "make_boundaries", "fill_ghosts", "fill_band_ghosts", "ghost_lines", "fill_ghost_lines",
    "correct_radial_items", "correct_radial_fluxes", "fill_ghosts_threaded", "PARALLEL_REMAP_NY",
]

PERIODIC, SHEAR_PERIODIC, OUTFLOW, REFLECTING, HYDROSTATIC = 0, 1, 2, 3, 4
#: a face whose ghosts another block provides (not a name users choose)
NEIGHBOUR = 5
#: name -> code of the boundary kinds
BOUNDARY_KINDS = {"periodic": PERIODIC, "shear-periodic": SHEAR_PERIODIC, "outflow": OUTFLOW,
                  "reflecting": REFLECTING, "hydrostatic": HYDROSTATIC}

#: 2D x-y boxes with at least this many cells along y remap their radial ghosts and fluxes in
#: parallel (measured: ~3.5 ns per remapped value, ~2 us per parallel region)
PARALLEL_REMAP_NY = 100


class Boundaries(NamedTuple):
    """Boundary kind of each face and what the shear-periodic one needs."""

    x_lo: int
    x_hi: int
    y_lo: int
    y_hi: int
    z_lo: int
    z_hi: int
    q_omega_lx: float  # speed at which the radial images slide in y
    vy_jump: float  # q Omega Lx if the full v_y is stored, 0 under orbital advection
    remap_method: int  # reconstruction of the fractional shift
    remap_limiter: int
    half_inv_h2: float  # 1 / (2 H^2) = Omega^2 / (2 c_s^2) of the hydrostatic boundary
    #: where the block sits along z: the lower z of the whole box and the block's first cell
    #: (a block's hydrostatic ghosts take the heights of the whole mesh, bit for bit)
    z_origin: float = 0.0
    z_first: int = 0

    @property
    def shearing(self) -> bool:
        return self.x_lo == SHEAR_PERIODIC


def make_boundaries(
    kinds: tuple[str, str, str],
    active: tuple[bool, bool, bool],
    q_omega_lx: float = 0.0,
    vy_jump: float = 0.0,
    remap_method: int = 1,
    remap_limiter: int = 2,
    scale_height: float = 0.0,
) -> Boundaries:
    """Boundaries from one kind name per axis (both sides alike); inactive axes are ignored.

    >>> b = make_boundaries(("shear-periodic", "periodic", "outflow"), (True, True, False), 1.5, 1.5)
    >>> b.shearing, b.y_lo == PERIODIC
    (True, True)
    """
    codes = []
    for axis, (name, on) in enumerate(zip(kinds, active)):
        if name not in BOUNDARY_KINDS:
            raise SetupError(f"boundary '{name}' unknown: choose one of {', '.join(BOUNDARY_KINDS)}")
        code = BOUNDARY_KINDS[name] if on else PERIODIC
        if code == SHEAR_PERIODIC and axis != 0:
            raise SetupError("shear-periodic boundaries are radial: only the x axis can have them")
        if code == HYDROSTATIC and (axis != 2 or not scale_height > 0):
            raise SetupError("hydrostatic boundaries are vertical: z axis only, with vertical gravity on")
        codes += [code, code]
    half_inv_h2 = 0.5 / scale_height**2 if scale_height > 0 else 0.0
    return Boundaries(*codes, float(q_omega_lx), float(vy_jump), int(remap_method), int(remap_limiter), half_inv_h2)


@njit(cache=True, error_model="numpy")
def _source_index(kind: int, lower: bool, m: int, n: int, g: int) -> int:
    """Index (ghost-padded) of the cell a ghost copies; ``m`` counts outwards from the domain."""
    if lower:
        if kind == PERIODIC:
            return g - 1 - m + n
        if kind == OUTFLOW or kind == HYDROSTATIC:
            return g
        return g + m  # reflecting
    if kind == PERIODIC:
        return g + m
    if kind == OUTFLOW or kind == HYDROSTATIC:
        return g + n - 1
    return g + n - 1 - m  # reflecting


@njit(cache=True, error_model="numpy")
def _copy_ghosts(u, axis, n, g, kind_lo, kind_hi, l0, l1, i0=0, i1=-1):
    """Copy-type kinds (periodic, outflow, reflecting) along ``axis`` for lines ``l0 .. l1-1``
    (rows j for z, planes k for y and x), over the full extent of the other axes (for z and y:
    the columns ``i0 .. i1-1``, all if ``i1 < 0``). A side whose kind is ``NEIGHBOUR`` is left alone."""
    nyt, nxt = u.shape[2], u.shape[3]
    if i1 < 0:
        i1 = nxt
    flip = 1 + axis  # momentum component normal to this axis
    for side in range(2):
        kind = kind_lo if side == 0 else kind_hi
        if kind == NEIGHBOUR:
            continue
        for m in range(g):
            dst = g - 1 - m if side == 0 else g + n + m
            src = _source_index(kind, side == 0, m, n, g)
            for v in range(4):
                sign = -1.0 if (kind == REFLECTING and v == flip) else 1.0
                for line in range(l0, l1):
                    if axis == 0:  # short strided lines: index directly
                        for j in range(nyt):
                            u[v, line, j, dst] = sign * u[v, line, j, src]
                        continue
                    # views of a ghost row and its source row (indices from 0: no wraparound)
                    if axis == 2:
                        to, frm = u[v, dst, line, :], u[v, src, line, :]
                    else:
                        to, frm = u[v, line, dst, :], u[v, line, src, :]
                    for i in range(i0, i1):
                        to[i] = sign * frm[i]


@njit(cache=True, error_model="numpy")
def _hydrostatic_ghosts(u, lay, sp, bc, l0, l1, side0=0, side1=2, i0=0, i1=-1):
    """Open vertical boundaries of a stratified isothermal box, rows ``l0 .. l1-1``, sides
    ``side0 .. side1-1`` (0: lower), columns ``i0 .. i1-1`` (all if ``i1 < 0``) (a face
    that borders another block is left alone; heights ``z_origin + (z_first + k + 1/2) dz``
    of the whole mesh)."""
    nz, gz = lay.nz, lay.gz
    if i1 < 0:
        i1 = u.shape[3]
    for side in range(side0, side1):
        if (bc.z_lo if side == 0 else bc.z_hi) == NEIGHBOUR:
            continue
        src = gz if side == 0 else gz + nz - 1
        z_src = bc.z_origin + (bc.z_first + src - gz + 0.5) * sp.dz
        for m in range(gz):
            dst = gz - 1 - m if side == 0 else gz + nz + m
            z_dst = bc.z_origin + (bc.z_first + dst - gz + 0.5) * sp.dz
            factor = math.exp(-(z_dst * z_dst - z_src * z_src) * bc.half_inv_h2)
            for line in range(l0, l1):
                for v in range(3):
                    to, frm = u[v, dst, line, :], u[v, src, line, :]
                    for i in range(i0, i1):
                        to[i] = factor * frm[i]
                to, frm = u[3, dst, line, :], u[3, src, line, :]
                for i in range(i0, i1):
                    to[i] = factor * frm[i]


@njit(cache=True, error_model="numpy")
def _shear_ghosts(u, item, t, lay, sp, bc, col, out, work):
    """Radial ghosts of a shearing box: periodic in x, shifted in y (see :func:`ghost_lines`
    for the items: (side, plane) if y is inactive, else (side, variable, plane))."""
    nx, ny, g, gy = lay.nx, lay.ny, lay.gx, lay.gy
    nyt = u.shape[2]
    side = item % 2
    jump = bc.vy_jump if side == 0 else -bc.vy_jump
    if ny == 1:  # radial-vertical plane: no azimuthal shift, only the velocity jump
        k = item // 2
        for m in range(g):
            dst = g - 1 - m if side == 0 else g + nx + m
            src = g - 1 - m + nx if side == 0 else g + m
            u[0, k, 0, dst] = u[0, k, 0, src]
            u[1, k, 0, dst] = u[1, k, 0, src]
            u[2, k, 0, dst] = u[2, k, 0, src] + jump * u[0, k, 0, src]
            u[3, k, 0, dst] = u[3, k, 0, src]
        return
    v = (item // 2) % 4
    k = item // 8
    s = shear_offset(t, bc.q_omega_lx, sp.ly) / sp.dy
    shift = s if side == 0 else -s
    for m in range(g):
        dst = g - 1 - m if side == 0 else g + nx + m
        src = g - 1 - m + nx if side == 0 else g + m
        # the variable, and for rho v_y also rho (the velocity jump), remapped
        for slot in range(2 if v == 2 else 1):
            column = u[v if slot == 0 else 0, k, gy:gy + ny, src]
            for j in range(ny):
                col[j] = column[j]
            shift_column(col, ny, shift, bc.remap_method, bc.remap_limiter, out[slot], work)
        ghost = u[v, k, :, dst]
        for j in range(nyt):
            jj = (j - gy) % ny
            ghost[j] = out[0, jj] + jump * out[1, jj] if v == 2 else out[0, jj]


@njit(cache=True, error_model="numpy")
def ghost_lines(axis: int, lay, bc) -> int:
    """Number of independent work items of the ghost fill along ``axis`` (0 if inactive):
    rows j for z, planes k for y and x, and for shear-periodic x (side, plane) pairs when y
    is inactive, else (side, variable, plane) triples."""
    NY = lay.ny + 2 * lay.gy
    NZ = lay.nz + 2 * lay.gz
    if axis == 2:
        return NY if lay.gz > 0 else 0
    if axis == 1:
        return NZ if lay.gy > 0 else 0
    if lay.gx == 0:
        return 0
    if bc.x_lo != SHEAR_PERIODIC:
        return NZ
    return 2 * NZ if lay.ny == 1 else 8 * NZ


@njit(cache=True, error_model="numpy")
def fill_ghost_lines(u, axis, l0, l1, t, lay, sp, bc) -> None:
    """Items ``l0 .. l1-1`` (see :func:`ghost_lines`) of the ghost fill along ``axis``.

    All items of an axis are independent; the axes must be done in the order z, y, x.
    """
    if axis == 2:
        if bc.z_lo == HYDROSTATIC or bc.z_hi == HYDROSTATIC:
            _hydrostatic_ghosts(u, lay, sp, bc, l0, l1)
        else:
            _copy_ghosts(u, 2, lay.nz, lay.gz, bc.z_lo, bc.z_hi, l0, l1)
    elif axis == 1:
        _copy_ghosts(u, 1, lay.ny, lay.gy, bc.y_lo, bc.y_hi, l0, l1)
    elif bc.x_lo != SHEAR_PERIODIC:
        _copy_ghosts(u, 0, lay.nx, lay.gx, bc.x_lo, bc.x_hi, l0, l1)
    else:
        ny = lay.ny
        col = np.empty(ny)
        out = np.empty((2, ny))
        work = np.empty(4 * ny + 19)
        for item in range(l0, l1):
            _shear_ghosts(u, item, t, lay, sp, bc, col, out, work)


@njit(cache=True, error_model="numpy")
def fill_ghosts(u, t, lay, sp, bc) -> None:
    """Fill every ghost cell of the state ``u[4, NZ, NY, NX]`` at time ``t`` (see module doc).

    Axes in the order z, y, x, each over the full extent of the others (edges and corners).
    This is the serial version; the integrator spreads the items of each axis over threads
    for large (3D) blocks.
    """
    for back in range(3):
        axis = 2 - back
        fill_ghost_lines(u, axis, 0, ghost_lines(axis, lay, bc), t, lay, sp, bc)


@njit(cache=True, error_model="numpy")
def fill_band_ghosts(u, t, lay, sp, bc, k0, k1) -> None:
    """The ghosts that a band of domain planes ``k0 .. k1-1`` of a radial-vertical (x-z) box
    owns: the radial ghosts of its planes and, if it holds the first (last) plane, the vertical
    ghost planes below (above) it with their radial ghosts. Bands that cover the planes fill
    every ghost cell with the values of :func:`fill_ghosts`, each band reading only domain
    cells (the vertical copy takes the domain columns; the radial ghosts of a ghost plane are
    then filled from them, as :func:`fill_ghosts` overwrites what its vertical copy put there),
    so the bands can fill at the same time: the integrator fills each band's ghosts in the
    parallel region that sweeps the band. Requires ``ny == 1`` and radial faces that do not
    border another block.
    """
    nx, nz, gx, gz = lay.nx, lay.nz, lay.gx, lay.gz
    hydrostatic = bc.z_lo == HYDROSTATIC or bc.z_hi == HYDROSTATIC
    if gz > 0:
        for side in range(2):
            if (side == 0 and k0 > 0) or (side == 1 and k1 < nz):
                continue
            if hydrostatic:
                _hydrostatic_ghosts(u, lay, sp, bc, 0, 1, side, side + 1, gx, gx + nx)
            else:
                _copy_ghosts(u, 2, nz, gz, bc.z_lo if side == 0 else NEIGHBOUR,
                             bc.z_hi if side == 1 else NEIGHBOUR, 0, 1, gx, gx + nx)
    p0 = gz + k0 if k0 > 0 else 0
    p1 = gz + k1 if k1 < nz else nz + 2 * gz
    per_plane = ghost_lines(0, lay, bc) // (nz + 2 * gz)  # radial items a plane: 1, or 2 if shear-periodic
    fill_ghost_lines(u, 0, per_plane * p0, per_plane * p1, t, lay, sp, bc)


@njit(cache=True, error_model="numpy")
def correct_radial_items(u, bflux, dtdx, t, lay, sp, bc, i0, i1, plane_flux) -> None:
    """Average the radial-face fluxes of a shear-periodic box with their remapped images, for
    items ``i0 .. i1-1``: item ``4 k + v`` is variable v of plane k (all independent).

    Parameters
    ----------
    u
        State just updated with the uncorrected fluxes; its first and last radial domain
        cells are corrected in place.
    bflux
        ``(2, 4, nz, ny)`` fluxes through the inner (0) and outer (1) radial faces, as applied.
    dtdx
        The ``dt / dx`` the fluxes were applied with.
    plane_flux
        ``(nz,)`` output, written by the density items: each plane's ``sum_j F_rho`` through
        the radial boundary after the correction (outward positive, per unit face area).
    """
    nx, ny = lay.nx, lay.ny
    gx, gy, gz = lay.gx, lay.gy, lay.gz
    s = shear_offset(t, bc.q_omega_lx, sp.ly) / sp.dy if ny > 1 else 0.0
    img_in = np.empty((2, ny))  # image of the outer flux on the inner face (and of F_rho)
    img_out = np.empty((2, ny))
    work = np.empty(4 * ny + 19)
    for item in range(i0, i1):
        k = item // 4
        v = item % 4
        for slot in range(2 if v == 2 else 1):
            w = v if slot == 0 else 0
            if ny == 1:  # no azimuthal shift
                img_in[slot, 0] = bflux[1, w, k, 0]
                img_out[slot, 0] = bflux[0, w, k, 0]
            else:
                shift_column(bflux[1, w, k], ny, s, bc.remap_method, bc.remap_limiter, img_in[slot], work)
                shift_column(bflux[0, w, k], ny, -s, bc.remap_method, bc.remap_limiter, img_out[slot], work)
        inner = u[v, gz + k, gy:gy + ny, gx]
        outer = u[v, gz + k, gy:gy + ny, gx + nx - 1]
        f_in_line = bflux[0, v, k]
        f_out_line = bflux[1, v, k]
        plane = 0.0
        for j in range(ny):
            g_in = img_in[0, j]
            g_out = img_out[0, j]
            if v == 2:  # v_y is larger by q Omega Lx in the inner image
                g_in += bc.vy_jump * img_in[1, j]
                g_out -= bc.vy_jump * img_out[1, j]
            new_in = 0.5 * (f_in_line[j] + g_in)
            new_out = 0.5 * (f_out_line[j] + g_out)
            inner[j] += dtdx * (new_in - f_in_line[j])
            outer[j] -= dtdx * (new_out - f_out_line[j])
            plane += new_in
        if v == 0:
            plane_flux[k] = plane


@njit(inline="always")
def fill_ghosts_threaded(u, t, lay, sp, bc, nthreads) -> None:
    """:func:`fill_ghosts` with the items of each axis spread over ``nthreads`` chunks where it
    pays: in 3D, and for the remapped radial ghosts of a 2D x-y shearing box with at least
    :data:`PARALLEL_REMAP_NY` cells along y (otherwise a parallel region costs more than the
    fill: in a 2D x-z box an item is a few cells). Inlined, so that its loops are parallel
    regions of the integrator that calls it
    (:func:`~dustygas.grid.integrator.advance_gas`, :func:`~dustygas.grid.ctu.ctu_stage`);
    the items are independent, so the result does not depend on ``nthreads``.
    """
    shearing = bc.x_lo == SHEAR_PERIODIC
    for back in range(3):
        axis = 2 - back
        nlines = ghost_lines(axis, lay, bc)
        if nlines > 1 and ((lay.ny > 1 and lay.nz > 1) or (axis == 0 and shearing and lay.ny >= PARALLEL_REMAP_NY)):
            nchunk = min(nlines, nthreads)
            for c in prange(nchunk):
                fill_ghost_lines(u, axis, c * nlines // nchunk, (c + 1) * nlines // nchunk, t, lay, sp, bc)
        elif nlines > 0:
            fill_ghost_lines(u, axis, 0, nlines, t, lay, sp, bc)


@njit(inline="always")
def correct_radial_fluxes(u, bflux, dtdx, t, lay, sp, bc, nthreads) -> np.ndarray:
    """:func:`correct_radial_items` for every item (module docstring; Stone & Gardiner 2010,
    §3); returns ``sum_j F_rho`` through the radial boundary after the correction, per z plane
    (``(nz,)``; multiply by ``dt dy dz`` for the mass that crossed it).

    The items are spread over ``nthreads`` chunks in 3D and in 2D x-y boxes with at least
    :data:`PARALLEL_REMAP_NY` cells along y (inlined, like :func:`fill_ghosts_threaded`; in a 2D
    x-z box an item is one cell and a parallel region would cost more than the work); they
    are independent, so the result does not depend on ``nthreads``.
    """
    nz = lay.nz
    plane_flux = serial_full(nz, 0.0)  # not a parallel region of its own (dustygas.arrays)
    nitems = 4 * nz
    if (nz > 1 and lay.ny > 1) or lay.ny >= PARALLEL_REMAP_NY:
        nchunk = min(nitems, nthreads)
        for c in prange(nchunk):
            correct_radial_items(u, bflux, dtdx, t, lay, sp, bc, c * nitems // nchunk, (c + 1) * nitems // nchunk,
                                 plane_flux)
    else:
        correct_radial_items(u, bflux, dtdx, t, lay, sp, bc, 0, nitems, plane_flux)
    return plane_flux
