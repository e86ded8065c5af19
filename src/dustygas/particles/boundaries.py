"""Particle boundaries: the one place of the particle module that knows what lies beyond a face.

Kinds, per axis (both faces alike), in :data:`PARTICLE_BOUNDARIES`:

periodic
    a particle leaving through one face re-enters through the opposite one.
shear-periodic
    (x only; thesis §4.3.1; Hawley, Gammie & Balbus 1995) the radial images of the box slide
    along y: image ``n`` of a point ``(x, y)`` is ``(x + n L_x, y - n s_y)`` with
    ``s_y = q Ω L_x t`` (the convention of the gas ghost zones of
    :mod:`dustygas.grid.boundaries`), and its full azimuthal velocity is smaller by
    ``n q Ω L_x``. A particle found beyond the outer face (``n = +1``) re-enters at
    ``(x - L_x, y + s_y)`` with ``v_y + q Ω L_x``; velocities stored relative to the shear
    (orbital advection) do not jump.
outflow
    a particle that leaves is removed; its mass and momentum are added to the face's account
    (:func:`apply_boundaries` returns them, the engine's history records them).
reflecting
    a particle is mirrored back into the box with its normal velocity reversed.

Two operations use the kinds:

* :func:`apply_boundaries`, after every drift: the exchange step. Today it maps particles back
  into the single block; with several blocks, particles that cross into a neighbour leave here
  too, and the rest of the engine does not change.
* :func:`build_images`: *image records* for the deposits. A deposit is gathered by every domain
  cell from the particles of the cells within the kernel's reach
  (:mod:`dustygas.particles.deposit`); next to a face, some of those cells lie outside the
  domain, and hold images: for periodic axes the particles one box length away (shear-periodic:
  at their image position, with the y weights recomputed there), for the other kinds the
  mirror image of the particles inside, whose weights fold the part of the stencil beyond
  the face back into the domain -- so every particle deposits exactly its mass and momentum.
  Where every image would be a particle one box length away with its own weights
  (:func:`images_wrap`), the deposit reads those particles in place and no records are built.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np
from numba import njit, prange

from ..errors import SetupError
from ..grid.mesh import Layout, Spacing
from .interp import cell_weights

__all__ = ["PERIODIC", "SHEAR_PERIODIC", "OUTFLOW", "REFLECTING", "PARTICLE_BOUNDARIES", "ParticleBoundaries",
           "make_particle_boundaries", "apply_boundaries", "build_images", "images_wrap", "wrap_positions"]

PERIODIC, SHEAR_PERIODIC, OUTFLOW, REFLECTING = 0, 1, 2, 3
#: name -> code of the particle boundary kinds
PARTICLE_BOUNDARIES = {"periodic": PERIODIC, "shear-periodic": SHEAR_PERIODIC, "outflow": OUTFLOW,
                       "reflecting": REFLECTING}
#: gas boundary kind -> the particle kinds it admits
COMPATIBLE = {"periodic": ("periodic",), "shear-periodic": ("shear-periodic",),
              "outflow": ("outflow", "reflecting"), "hydrostatic": ("outflow", "reflecting"),
              "reflecting": ("reflecting", "outflow")}


class ParticleBoundaries(NamedTuple):
    """Kind of each axis (inactive axes: periodic) and the shear of the radial images."""

    x: int
    y: int
    z: int
    q_omega_lx: float  # speed at which the radial images slide along y
    jump: float  # q Omega Lx if full azimuthal velocities are stored, else 0
    #: faces (bit ``2 axis + side``, side 1: upper) that border another block: no images are
    #: built there, the neighbour's particles arrive as halo records (:mod:`dustygas.parallel`)
    neighbours: int = 0


def make_particle_boundaries(kinds: tuple[str, str, str], gas_kinds: tuple[str, str, str],
                             active: tuple[bool, bool, bool], q_omega_lx: float, jump: float,
                             keys: tuple[str, str, str] = ("x", "y", "z")) -> ParticleBoundaries:
    """Codes from names, checked against the gas boundaries of the same axes.

    ``keys`` name the configuration entries in the error messages.

    >>> make_particle_boundaries(("shear-periodic", "periodic", "outflow"),
    ...                          ("shear-periodic", "periodic", "hydrostatic"), (True, True, True), 0.3, 0.3).z
    2
    """
    codes = []
    for axis, (name, gas, on, key) in enumerate(zip(kinds, gas_kinds, active, keys)):
        if name not in PARTICLE_BOUNDARIES:
            raise SetupError(f"{key} = '{name}' unknown: choose one of {', '.join(PARTICLE_BOUNDARIES)}")
        if not on:
            codes.append(PERIODIC)
            continue
        allowed = COMPATIBLE.get(gas, ())
        if name not in allowed:
            raise SetupError(f"{key} = '{name}': with the gas boundary '{gas}' on the {'xyz'[axis]} axis particles "
                             f"can only be {' or '.join(allowed)}")
        codes.append(PARTICLE_BOUNDARIES[name])
    return ParticleBoundaries(*codes, float(q_omega_lx), float(jump))


def images_wrap(bounds: ParticleBoundaries, reach, shape: tuple[int, int, int]) -> bool:
    """Whether every image record would be a domain particle one box length away with its own
    weights: every axis the stencil reaches (``reach[a] > 0``) periodic, at least ``reach[a]``
    cells long and bordering no other block, and the radial images not sliding along y (a
    shear-periodic x only with ``ny = 1``). The deposit then reads those particles in place
    (:func:`~dustygas.particles.deposit.pull_deposit` with ``wrap``) and :func:`build_images`
    is not needed.
    """
    kinds = (bounds.x, bounds.y, bounds.z)
    for a in range(3):
        if reach[a] > 0 and (kinds[a] not in (PERIODIC, SHEAR_PERIODIC) or shape[a] < reach[a]):
            return False
    return bounds.neighbours == 0 and not (reach[0] > 0 and bounds.x == SHEAR_PERIODIC and shape[1] > 1)


@njit(cache=True, error_model="numpy")
def _periods(v: float, lo: float, length: float) -> int:
    """How many box lengths ``v`` lies beyond ``[lo, lo + length)`` (comparisons first)."""
    if v < lo:
        if v >= lo - length:
            return -1
    elif v < lo + length:
        return 0
    elif v < lo + 2.0 * length:
        return 1
    return int(math.floor((v - lo) / length))


@njit(cache=True, error_model="numpy")
def _reflect(v: float, lo: float, length: float):
    """Mirror ``v`` at the faces of ``[lo, lo + length)``; returns (new v, True if mirrored)."""
    if v < lo:
        return 2.0 * lo - v, True
    hi = lo + length
    if v >= hi:
        w = 2.0 * hi - v
        if w >= hi:  # exactly on the face
            w = math.nextafter(hi, lo)
        return w, True
    return v, False


@njit(cache=True, parallel=True, error_model="numpy")
def apply_boundaries(pos, vel, n, layout, spacing, bounds, y_shift, leaving, half_dt=0.0) -> int:
    """The exchange step for particles ``0 .. n-1`` after a drift (module docstring).

    ``y_shift``: the shear offset ``s_y`` at the time of the positions. Periodic, shear-periodic
    and reflecting particles are mapped back in place; a particle leaving through an outflow
    face gets ``leaving[p] = 1 + 2 axis + side`` (side 1: upper face), all others 0. Returns the
    number leaving (the caller accounts and removes them). ``half_dt != 0``: first the drift
    ``x += half_dt v`` along the active axes, in the same pass.
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    pb = ParticleBoundaries(*bounds)
    count = 0
    kinds = (pb.x, pb.y, pb.z)
    nn = (lay.nx, lay.ny, lay.nz)
    for p in prange(n):
        if half_dt != 0.0:
            for a in range(3):
                if nn[a] > 1:
                    pos[a, p] += half_dt * vel[a, p]
        flag = 0
        for a in range(3):
            if nn[a] == 1:
                continue
            lo = sp.x0 if a == 0 else (sp.y0 if a == 1 else sp.z0)
            length = sp.lx if a == 0 else (sp.ly if a == 1 else sp.lz)
            v = pos[a, p]
            kind = kinds[a]
            if kind == PERIODIC or kind == SHEAR_PERIODIC:
                m = _periods(v, lo, length)
                if m != 0:
                    pos[a, p] = v - m * length
                    if kind == SHEAR_PERIODIC:
                        if lay.ny > 1:  # x is done before y: the y wrap below sees the shifted y
                            pos[1, p] += m * y_shift
                        vel[1, p] += m * pb.jump
            elif kind == REFLECTING:
                w, hit = _reflect(v, lo, length)
                if hit:
                    pos[a, p] = w
                    vel[a, p] = -vel[a, p]
            elif flag == 0 and (v < lo or v >= lo + length):
                flag = 1 + 2 * a + (1 if v >= lo else 0)
        leaving[p] = flag
        if flag:
            count += 1
    return count


def wrap_positions(pos: np.ndarray, lower, size, shape) -> np.ndarray:
    """Positions ``(3, N)`` of a set-up moved by whole periods into the box ``[lower, lower + size)``
    along every active axis (numpy; the compiled exchange step does the same during a run).

    >>> wrap_positions(np.array([[1.25], [0.0], [0.0]]), (-0.5, 0.0, 0.0), (1.0, 1.0, 1.0), (8, 1, 1))[0].tolist()
    [0.25]
    """
    out = np.array(pos, dtype=np.float64)
    for a in range(3):
        if shape[a] > 1:
            out[a] = lower[a] + np.mod(out[a] - lower[a], size[a])
            out[a] = np.where(out[a] >= lower[a] + size[a], lower[a], out[a])
    return out


# --------------------------------------------------------------------------- image records
@njit(cache=True, error_model="numpy")
def _add_image(m, src, i, j, k, w_src, dvy, flip, img_src, img_cell, img_w, img_dvy):
    """Record ``m``: image of ``src`` in cell (i, j, k) with the weights ``w_src`` (3, W), its
    x, y or z weights reversed if ``flip`` is 0, 1, 2 (a mirror image)."""
    img_src[m] = src
    img_cell[m, 0] = i
    img_cell[m, 1] = j
    img_cell[m, 2] = k
    W = w_src.shape[1]
    for a in range(3):
        for s in range(W):
            img_w[m, a, s] = w_src[a, W - 1 - s] if a == flip else w_src[a, s]
    img_dvy[m] = dvy


@njit(cache=True, error_model="numpy")
def _images_along(axis, m0, m1, n, lay, sp, pb, reach, order, y_shift, keys, wts, pos, cell_start,
                  img_src, img_cell, img_w, img_dvy) -> int:
    """Images across the two faces of ``axis`` of the reals and of the records ``m0 .. m1-1``;
    written from ``m1`` on while they fit. Returns the new number of records (more than the
    arrays hold: not all were written)."""
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    nn = nx if axis == 0 else (ny if axis == 1 else nz)
    R = reach[axis]
    cap = img_src.shape[0]
    if nn == 1 or R == 0 or m1 > cap:
        return m1
    kind = pb.x if axis == 0 else (pb.y if axis == 1 else pb.z)
    periodic = kind == PERIODIC or kind == SHEAR_PERIODIC
    shear = kind == SHEAR_PERIODIC and ny > 1  # the images slide along y
    m = m1
    W = wts.shape[2]
    wtmp = np.empty((3, W))
    ybuf = np.empty(W)
    # the real particles in the slabs within R of either face, then the earlier images
    nslab = 2 * R if 2 * R <= nn else nn
    other = (ny * nz) if axis == 0 else ((nx * nz) if axis == 1 else (nx * ny))
    for t in range(nslab * other + (m1 - m0)):
        if t < nslab * other:
            sl = t // other
            q = t % other
            s_idx = sl if sl < R or nslab == nn else nn - 2 * R + sl  # (a box shorter than 2R: every slab)
            if axis == 0:
                c = (q // ny * ny + q % ny) * nx + s_idx
            elif axis == 1:
                c = ((q // nx) * ny + s_idx) * nx + q % nx
            else:
                c = (s_idx * ny + q // nx) * nx + q % nx
            first, last = cell_start[c], cell_start[c + 1]
            is_real = True
        else:
            first = m0 + t - nslab * other
            last = first + 1
            is_real = False
        for r in range(first, last):
            if is_real:
                src = r
                key = keys[r]
                i, j, k = key % nx, (key // nx) % ny, key // (nx * ny)
                for a in range(3):
                    for s in range(W):
                        wtmp[a, s] = wts[r, a, s]
                dvy0 = 0.0
            else:
                src = img_src[r]
                i, j, k = img_cell[r, 0], img_cell[r, 1], img_cell[r, 2]
                for a in range(3):
                    for s in range(W):
                        wtmp[a, s] = img_w[r, a, s]
                dvy0 = img_dvy[r]
            c_ax = i if axis == 0 else (j if axis == 1 else k)
            for side in range(2):
                near = c_ax < R if side == 0 else c_ax >= nn - R
                if not near or (pb.neighbours >> (2 * axis + side)) & 1:
                    continue
                if periodic:
                    new = c_ax + nn if side == 0 else c_ax - nn
                    flip = -1
                else:
                    new = -1 - c_ax if side == 0 else 2 * nn - 1 - c_ax
                    flip = axis
                ii, jj, kk = i, j, k
                if axis == 0:
                    ii = new
                elif axis == 1:
                    jj = new
                else:
                    kk = new
                dvy = dvy0
                if m < cap:
                    # a particle near the inner face has its image beyond the outer one: n = sgn,
                    # at y - n s_y with v_y - n q Omega Lx
                    sgn = 1.0 if side == 0 else -1.0
                    if kind == SHEAR_PERIODIC:
                        dvy = dvy0 - sgn * pb.jump
                    if shear:
                        y = pos[1, src] - sgn * y_shift
                        sy = (y - sp.y0) / sp.dy - 0.5
                        sy -= ny * math.floor((sy + 0.5) / ny)  # into [-1/2, ny - 1/2): a cell of the box
                        jj = cell_weights(sy, order, reach[1], ybuf)
                    _add_image(m, src, ii, jj, kk, wtmp, dvy, flip, img_src, img_cell, img_w, img_dvy)
                    if shear:
                        for s in range(W):
                            img_w[m, 1, s] = ybuf[s]
                m += 1
    return m


@njit(cache=True, error_model="numpy")
def build_images(n, layout, spacing, bounds, reach, order, y_shift, keys, wts, pos, cell_start, img_src, img_cell,
                 img_w, img_dvy) -> int:
    """Image records of the sorted particles ``0 .. n-1`` (module docstring): along x, then y
    (of the particles and the x images), then z (of all). Returns their number; if it exceeds
    the length of the arrays, not all were written (nor counted): grow them and call again.

    ``reach[a]``: cells the stencil reaches along axis a (0 if inactive); ``keys`` the
    particles' domain cells; ``wts`` ``(N, 3, W)`` their weights; ``y_shift`` the shear
    offset at the time of the positions.
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    pb = ParticleBoundaries(*bounds)
    m = _images_along(0, 0, 0, n, lay, sp, pb, reach, order, y_shift, keys, wts, pos, cell_start,
                      img_src, img_cell, img_w, img_dvy)
    m = _images_along(1, 0, m, n, lay, sp, pb, reach, order, y_shift, keys, wts, pos, cell_start,
                      img_src, img_cell, img_w, img_dvy)
    return _images_along(2, 0, m, n, lay, sp, pb, reach, order, y_shift, keys, wts, pos, cell_start,
                         img_src, img_cell, img_w, img_dvy)
