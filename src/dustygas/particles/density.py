"""The particles' mass density on a mesh without a gas engine (set-ups, analyses and tests).

The same assignment functions, particle boundaries and race-free pull deposit as the coupled
engine (:mod:`dustygas.particles.coupling`; thesis eq. 4.24, Hockney & Eastwood 1981, §5-3):
a set-up's density and an analysis's clump masses are what the engine would deposit.
"""

from __future__ import annotations

import numba
import numpy as np

from .boundaries import ParticleBoundaries, build_images, images_wrap, make_particle_boundaries
from .deposit import pull_deposit, sort_images
from .interp import KERNEL_REACH, KERNELS
from .store import ParticleStore, sort_by_cell

__all__ = ["deposit_density"]


def deposit_density(mesh, pos: np.ndarray, mass, kernel: str = "tsc",
                    boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic"),
                    shear_offset: float = 0.0, wrap: bool | None = None) -> np.ndarray:
    """Mass density ``(nz, ny, nx)`` of particles at ``pos`` (3, N) on ``mesh`` with ``kernel``
    (for set-ups, analyses and tests: the deposit the engine uses, without a gas engine; a
    ``shear-periodic`` x puts the radial images ``shear_offset`` along y).

    ``wrap``: read the periodic images in place (None: wherever the boundaries allow,
    :func:`~dustygas.particles.boundaries.images_wrap`, as the engine does); False builds the
    image records, as a decomposed run does. Both give the same bits."""
    pos = np.asarray(pos, dtype=np.float64)
    n = pos.shape[1]
    store = ParticleStore.create(pos, np.zeros((3, n)), 0, mass)
    active = tuple(s > 1 for s in mesh.shape)
    gas_kinds = tuple(b if b in ("periodic", "shear-periodic") else "outflow" for b in boundaries)
    pb = tuple(make_particle_boundaries(tuple(boundaries), gas_kinds, active, 0.0, 0.0))  # plain (grid.mesh)
    order = KERNELS[kernel]
    R = KERNEL_REACH[order]
    reach = np.array([R if a else 0 for a in active], dtype=np.int64)
    lay, sp, off = tuple(mesh.layout), tuple(mesh.spacing), tuple(mesh.offsets)
    nx, ny, nz = mesh.shape
    ncell = nx * ny * nz
    keys = np.zeros(n, dtype=np.int64)
    cell_start = np.zeros(ncell + 1, dtype=np.int64)
    p_, v_, s_, i_, m_ = store.buffers()
    wts = np.zeros((n, 3, 2 * R + 1))
    sort_by_cell(p_, v_, s_, i_, m_, n, lay, sp, off, keys, np.zeros(n, dtype=np.int64), np.zeros(ncell, dtype=np.int64),
                 cell_start, np.zeros((7, n)), np.zeros((3, n), dtype=np.int64), order, R, wts)
    values = (m_[:n] / mesh.cell_volume).reshape(n, 1).copy()
    cols = np.zeros(n, dtype=np.int64)
    out = np.zeros((nz, ny, nx, 1))
    g = np.zeros(3, dtype=np.int64)
    allowed = images_wrap(ParticleBoundaries(*pb), reach, (nx, ny, nz))
    if wrap and not allowed:
        raise ValueError(f"wrap=True: the images of the boundaries {tuple(boundaries)} on a {nx}x{ny}x{nz} mesh "
                         f"are not the particles one box length away (images_wrap)")
    if wrap is None:
        wrap = allowed
    if wrap:  # the periodic images read in place: no records
        row_start = np.zeros(1, dtype=np.int64)
        img_src, img_cell = np.zeros(0, dtype=np.int64), np.zeros((0, 3), dtype=np.int64)
        img_w = np.zeros((0, 3, 2 * R + 1))
    else:
        args = (n, lay, sp, pb, reach, order, float(shear_offset), keys, wts, p_, cell_start)
        cap = max(16, n // 2)
        while True:
            img_src, img_cell = np.zeros(cap, dtype=np.int64), np.zeros((cap, 3), dtype=np.int64)
            img_w, img_dvy = np.zeros((cap, 3, 2 * R + 1)), np.zeros(cap)
            m = build_images(*args, img_src, img_cell, img_w, img_dvy)
            if m <= cap:
                break
            cap = 2 * m
        row_start = np.zeros((ny + 2 * reach[1]) * (nz + 2 * reach[2]) + 1, dtype=np.int64)
        sort_images(m, lay, reach, i_, img_src, img_cell, img_w, img_dvy, row_start)
    pull_deposit(out, g, lay, reach, R, cell_start, keys, wts, values, cols, row_start, img_cell, img_w, img_src,
                 numba.get_num_threads(), False, wrap)
    return out[..., 0]
