"""The column-block kernel of the y and z sweeps against the pencil kernel: equal bit for bit.

:func:`~dustygas.grid.sweep_columns.sweep_columns` reorders the loops of
:func:`~dustygas.grid.sweep.sweep_pencils` (columns innermost) and must give every cell the same
operations in the same order. Random states (density 0.5-1.5, velocities up to Mach 2, so
that every limiter branch and both signs of every wave speed occur), every reconstruction and
solver, 2D and 3D boxes with column counts that are not multiples of the block, pencil ranges
that end inside a row of pencils, and segments of pencils: the updated state, the Courant
rates, the first invalid cells and the stored boundary fluxes must be identical.
"""

from __future__ import annotations

import numpy as np
import pytest

from dustygas.grid.mesh import Mesh
from dustygas.grid.reconstruct import LIMITERS, RECONSTRUCTIONS
from dustygas.grid.riemann import RIEMANN_SOLVERS
from dustygas.grid.shearing_box import source_terms
from dustygas.grid.sweep import pencil_count, sweep_pencils
from dustygas.grid.sweep_columns import BLOCK, sweep_columns

CS = 0.7


def _state(mesh: Mesh, rng: np.random.Generator) -> np.ndarray:
    shape = (4, *mesh.array_shape)
    u = np.empty(shape)
    u[0] = rng.uniform(0.5, 1.5, shape[1:])
    u[1:] = u[0] * rng.uniform(-2.0 * CS, 2.0 * CS, (3, *shape[1:]))
    return u


def _both(mesh, axis, method, limiter, solver, p0, p1, c0, c1, seg, nseg, want_rate, store, seed):
    """Run both kernels from the same inputs; return their (dst, rates, bads, bflux)."""
    rng = np.random.default_rng(seed)
    lay, sp = mesh.layout, mesh.spacing
    src = _state(mesh, rng)
    dst0 = rng.normal(size=src.shape)
    scheme = (RECONSTRUCTIONS[method], LIMITERS[limiter], RIEMANN_SOLVERS[solver], CS)
    npen = pencil_count(axis, lay)
    n_axis = mesh.shape[axis]
    nb = mesh.shape[2] if axis == 1 else mesh.shape[1]
    out = []
    for kernel in ("pencils", "columns"):
        dst = dst0.copy()
        rates = np.zeros(npen * nseg)
        bads = np.full(npen * nseg, -7, dtype=np.int64)
        bflux = np.full((2, 4, nb, mesh.shape[0]), np.nan)
        if kernel == "pencils":
            sweep_pencils(src, dst, dst, axis, False, 1.0, 0.0, 0.013, lay, sp, scheme, source_terms(omega=1.0),
                          mesh.centers(0, ghosts=True), mesh.centers(2, ghosts=True), np.zeros((3, 1, 1, 1)), False,
                          bflux, store, np.zeros(npen), rates, bads, want_rate, False, p0, p1, c0, c1, seg, nseg)
        else:
            sweep_columns(src, dst, axis, 0.013, lay, sp, scheme, bflux, store, rates, bads, want_rate, False,
                          p0, p1, c0, c1, seg, nseg)
        out.append((dst, rates, bads, bflux))
    assert n_axis > 1
    return out


def _assert_identical(a, b) -> None:
    for x, y in zip(a, b):
        np.testing.assert_array_equal(x.view(np.int64) if x.dtype == np.float64 else x,
                                      y.view(np.int64) if y.dtype == np.float64 else y)


@pytest.mark.parametrize("solver", sorted(RIEMANN_SOLVERS))
@pytest.mark.parametrize("method,limiter", [("donor", "mc"), ("plm", "minmod"), ("plm", "vanleer"), ("plm", "mc"),
                                            ("ppm", "mc"), ("ppm-cs", "mc")])
def test_2d_z_sweep_identical(method, limiter, solver):
    mesh = Mesh((2 * BLOCK + 3, 1, 24), (1.0, 1.0, 1.3))  # two full blocks and one of 3 columns
    pencils, columns = _both(mesh, 2, method, limiter, solver, 0, mesh.shape[0], 0, 24, 0, 1, True, True, 1)
    _assert_identical(pencils, columns)
    assert np.all(np.isfinite(columns[3]))  # every boundary flux stored


@pytest.mark.parametrize("p0,p1", [(0, 19), (5, 14), (3, 4)])
def test_2d_pencil_ranges_inside_a_block(p0, p1):
    """A thread's range of pencils may start and end inside a block."""
    mesh = Mesh((19, 1, 16), (1.0, 1.0, 1.0))
    pencils, columns = _both(mesh, 2, "ppm-cs", "mc", "hllc", p0, p1, 0, 16, 0, 1, True, False, 2)
    _assert_identical(pencils, columns)


@pytest.mark.parametrize("axis", [1, 2])
@pytest.mark.parametrize("method", ["plm", "ppm-cs"])
def test_3d_sweeps_identical(axis, method):
    mesh = Mesh((11, 9, 10), (1.0, 1.2, 0.9))
    npen = pencil_count(axis, mesh.layout)
    # pencils 4 .. npen-3: ranges that cut rows of pencils at both ends
    pencils, columns = _both(mesh, axis, method, "mc", "hlle", 4, npen - 3, 0, mesh.shape[axis], 0, 1, True, True, 3)
    _assert_identical(pencils, columns)


@pytest.mark.parametrize("c0,c1,seg", [(0, 4, 0), (4, 7, 1), (7, 10, 2)])
def test_3d_z_segments_identical(c0, c1, seg):
    """The z sweep of a slab of z planes (3D runs split the z pencils into segments per thread)."""
    mesh = Mesh((11, 9, 10), (1.0, 1.2, 0.9))
    pencils, columns = _both(mesh, 2, "ppm-cs", "mc", "hllc", 0, 99, c0, c1, seg, 3, True, True, 4)
    _assert_identical(pencils, columns)
