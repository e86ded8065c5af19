"""Assignment functions, the shared stencil, the sort and the deposit (thesis eqs. 4.22-4.25).

Each test states the property of the exact weights it checks: partition of unity (every
particle deposits exactly its mass), reproduction of linear fields (the first moment), the
second moment that sets the smoothing (TSC: 1/4 cell² whatever the offset; compensated TSC:
0), and the deposit's independence of the thread count (bit for bit).
"""

import numpy as np
import pytest

from _threads import assert_identical, results_at_threads

from dustygas.particles.deposit import chunk_bounds
from dustygas.particles.interp import KERNEL_WIDTH, KERNELS, TSC, TSC_C, Cells, axis_weights
from dustygas.particles.push import deposit_density
from dustygas.particles.store import cell_keys, counting_sort, slab_starts


def weights(s, order):
    r = axis_weights(s, order)
    return r[0], np.array(r[1:])


@pytest.mark.parametrize("kernel", list(KERNELS))
def test_partition_of_unity_and_linear_reproduction(kernel):
    order = KERNELS[kernel]
    for s in np.linspace(-0.999, 7.999, 997):
        i0, w = weights(s, order)
        cells = i0 + np.arange(5)
        assert w.sum() == pytest.approx(1.0, abs=1e-15)
        assert np.all(w[KERNEL_WIDTH[order]:] == 0.0)
        if kernel != "ngp":  # NGP does not reproduce linear fields
            assert w @ cells == pytest.approx(s, abs=2e-15)


def test_second_moments_tsc_quarter_cell_and_compensated_zero():
    # TSC: sum w (j - s)^2 = 1/4 for every offset, i.e. the smoothing (1 - (k dx)^2 / 8) does not
    # depend on where the particle sits; the compensated kernel removes it
    for s in np.linspace(-0.5, 3.5, 401):
        i0, w = weights(s, TSC)
        assert w @ (i0 + np.arange(5) - s) ** 2 == pytest.approx(0.25, abs=1e-14)
        i0, w = weights(s, TSC_C)
        assert w @ (i0 + np.arange(5) - s) ** 2 == pytest.approx(0.0, abs=1e-14)


def _cells(nx, ny, nz, lx=1.0, ly=1.0, lz=1.0, shear=False, jump=0.0, rate=0.0):
    dx, dy, dz = lx / nx, (ly / ny if ny > 1 else 1.0), (lz / nz if nz > 1 else 1.0)
    return Cells(nx, ny, nz, 0, 0, 0, dx, dy, dz, -lx / 2, -ly / 2 if ny > 1 else 0.0, -lz / 2 if nz > 1 else 0.0,
                 lx, ly if ny > 1 else 1.0, lz if nz > 1 else 1.0, shear, jump, rate)


@pytest.mark.parametrize("kernel", ["cic", "tsc", "tsc-c"])
def test_moving_lattice_deposits_a_uniform_density(kernel):
    """A lattice of one particle per cell at any common offset deposits rho = m/V exactly."""
    c = _cells(16, 1, 12)
    x = (np.arange(16) + 0.5) / 16 - 0.5
    z = (np.arange(12) + 0.5) / 12 - 0.5
    X, Z = np.meshgrid(x, z)
    for shift in (0.0, 0.123, 0.5, 0.77):
        pos = np.zeros((3, X.size))
        pos[0] = (X.ravel() + shift / 16 + 0.5) % 1.0 - 0.5
        pos[2] = (Z.ravel() - 0.31 * shift / 12 + 0.5) % 1.0 - 0.5
        rho = deposit_density(pos, np.full(X.size, 2.0 / 192), c, KERNELS[kernel], 0.0)
        np.testing.assert_allclose(rho, 2.0, rtol=1e-13)


def test_shear_periodic_stencil_uses_the_images_and_keeps_the_mass():
    """Near a radial face of a shear-periodic x-y box, the columns across the face take the y
    weights of the particle's image, ``y -/+ s_y``: the deposit sums to the particle's mass and
    lands where the image is (checked against a particle placed at the image position)."""
    c = _cells(8, 10, 1, shear=True, jump=0.0, rate=1.5)
    s_y = 0.37  # shear offset
    m = 1.0
    vol = c.dx * c.dy
    # a particle just inside the outer face: the cell beyond it is column 0 of the box at y + s_y
    p = np.array([[0.5 - 0.2 * c.dx], [0.05], [0.0]])
    rho = deposit_density(p, np.array([m]), c, TSC, s_y).reshape(10, 8)
    assert rho.sum() * vol == pytest.approx(m, rel=1e-14)
    # its image at x - Lx, y + s_y deposits the same amount into column 0 (the part across the face)
    image = np.array([[p[0, 0] - 1.0], [p[1, 0] + s_y - 1.0], [0.0]])
    wx_img = axis_weights((image[0, 0] + 0.5) / c.dx - 0.5, TSC)
    _, wy = weights((image[1, 0] + 0.5) / c.dy - 0.5, TSC)
    i0, wx = wx_img[0], np.array(wx_img[1:])
    j0 = weights((image[1, 0] + 0.5) / c.dy - 0.5, TSC)[0]
    col0 = np.zeros(10)
    for a in range(3):
        if i0 + a == 0:
            for b in range(3):
                col0[(j0 + b) % 10] += wx[a] * wy[b] * m / vol
    np.testing.assert_allclose(rho[:, 0], col0, rtol=1e-13, atol=1e-13)


def test_counting_sort_is_stable_and_slab_starts_are_right():
    rng = np.random.default_rng(3)
    n = 500
    c = _cells(6, 1, 5)
    pos = np.zeros((3, n))
    pos[0] = rng.uniform(-0.5, 0.5, n)
    pos[2] = rng.uniform(-0.5, 0.5, n)
    vel = rng.standard_normal((3, n))
    pid = np.arange(n, dtype=np.int64)
    species = (pid % 3).astype(np.int32)
    mass = rng.uniform(1, 2, n)
    keys = np.zeros(n, dtype=np.int64)
    cell_keys(pos, c, 2, keys)
    expect = np.argsort(keys, kind="stable")
    before = (pos.copy(), vel.copy(), mass.copy())
    assert counting_sort(keys, 30, pos, vel, species, pid, mass, np.zeros(n, dtype=np.int64))
    np.testing.assert_array_equal(pid, expect)
    np.testing.assert_array_equal(pos, before[0][:, expect])
    np.testing.assert_array_equal(vel, before[1][:, expect])
    np.testing.assert_array_equal(mass, before[2][expect])
    np.testing.assert_array_equal(species, expect % 3)
    assert not counting_sort(keys, 30, pos, vel, species, pid, mass, np.zeros(n, dtype=np.int64))  # sorted now
    starts = np.zeros(6, dtype=np.int64)
    slab_starts(keys, 6, 5, starts)
    slab = np.floor((pos[2] + 0.5) * 5).astype(int)
    np.testing.assert_array_equal(starts[:-1], [np.count_nonzero(slab < s) for s in range(5)])
    assert starts[-1] == n


def test_chunks_two_apart_never_share_a_slab():
    for nslab in range(1, 80):
        for reach in (0, 1, 2):
            b = chunk_bounds(nslab, reach)
            assert b[0] == 0 and b[-1] == nslab and np.all(np.diff(b) > 0)
            m = len(b) - 1
            if m > 1:
                assert m % 2 == 0 and np.all(np.diff(b) >= 2 * (1 + reach))


def thread_case() -> dict:
    """30 steps of a 16² si-linear box with scrambled particle velocities (so sorts happen)."""
    from dustygas.problems import get_problem

    prob = get_problem("si-linear")
    cfg = prob.config(overrides=["grid.nx=16", "grid.nz=16", "problem.amplitude=0.02"])
    eng = prob.build(cfg)
    rng = np.random.default_rng(0)
    eng.particles.vel += 0.01 * rng.standard_normal(eng.particles.vel.shape)
    pos0 = eng.particles.pos[:, np.argsort(eng.particles.pid)].copy()
    for _ in range(30):
        eng.advance(eng.timestep())
    return {"gas": eng.gas.state, "pos": eng.particles.pos, "vel": eng.particles.vel, "pid": eng.particles.pid,
            "pos0": pos0, "dx": eng.gas.mesh.dx[0]}


def test_coupled_run_does_not_depend_on_the_thread_count(tmp_path):
    """Deposits, sorts and every stage are bit-identical on 1 and 2 threads (each in its own
    interpreter); the scrambled particles did change cells on the way."""
    results = results_at_threads("particles.test_kernels:thread_case", tmp_path)
    assert_identical(results)
    r = results[0]
    moved = np.abs(r["pos"][:, np.argsort(r["pid"])] - r["pos0"])[0]
    assert moved.max() > 0.1 * r["dx"], moved.max() / r["dx"]