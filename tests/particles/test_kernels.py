"""Assignment functions, the canonical sort, image records and the pull deposit (thesis eqs. 4.22-4.25).

Each test states the property it checks: partition of unity (every particle deposits exactly
its mass), reproduction of linear fields (the first moment), the second moment that sets the
smoothing (TSC: 1/4 cell² whatever the offset; compensated TSC: 0), a canonical order that
depends only on positions and ids, image records that keep the mass at shear-periodic and
mirror faces, and results that do not depend on the thread count (bit for bit, in
subprocesses with 1 and 2 numba threads).
"""

import numpy as np
import pytest

from _threads import assert_identical, results_at_threads

from dustygas.grid import Mesh
from dustygas.particles.density import deposit_density
from dustygas.particles.interp import KERNEL_REACH, KERNEL_WIDTH, KERNELS, TSC, TSC_C, axis_weights, cell_weights
from dustygas.particles.store import ParticleStore, sort_by_cell


def weights(s, order):
    r = axis_weights(s, order)
    return r[0], np.array(r[1:])


@pytest.mark.parametrize("kernel", list(KERNELS))
def test_partition_of_unity_and_linear_reproduction(kernel):
    order = KERNELS[kernel]
    R = KERNEL_REACH[order]
    out = np.zeros(2 * R + 1)
    for s in np.linspace(-0.499, 7.499, 997):
        i0, w = weights(s, order)
        cells = i0 + np.arange(5)
        assert w.sum() == pytest.approx(1.0, abs=1e-15)
        assert np.all(w[KERNEL_WIDTH[order]:] == 0.0)
        if kernel != "ngp":  # NGP does not reproduce linear fields
            assert w @ cells == pytest.approx(s, abs=2e-15)
        # the same weights around the containing cell
        c = cell_weights(s, order, R, out)
        assert c == int(np.floor(s + 0.5))
        assert out @ (c + np.arange(-R, R + 1)) == pytest.approx(w @ cells, abs=2e-15)


def test_second_moments_tsc_quarter_cell_and_compensated_zero():
    # TSC: sum w (j - s)^2 = 1/4 for every offset, i.e. the smoothing (1 - (k dx)^2 / 8) does not
    # depend on where the particle sits; the compensated kernel removes it
    for s in np.linspace(-0.5, 3.5, 401):
        i0, w = weights(s, TSC)
        assert w @ (i0 + np.arange(5) - s) ** 2 == pytest.approx(0.25, abs=1e-14)
        i0, w = weights(s, TSC_C)
        assert w @ (i0 + np.arange(5) - s) ** 2 == pytest.approx(0.0, abs=1e-14)


@pytest.mark.parametrize("kernel", ["cic", "tsc", "tsc-c"])
def test_moving_lattice_deposits_a_uniform_density(kernel):
    """A lattice of one particle per cell at any common offset deposits rho = m/V exactly (periodic)."""
    mesh = Mesh((16, 1, 12), (1.0, 1.0, 1.0))
    x = (np.arange(16) + 0.5) / 16 - 0.5
    z = (np.arange(12) + 0.5) / 12 - 0.5
    X, Z = np.meshgrid(x, z)
    for shift in (0.0, 0.123, 0.5, 0.77):
        pos = np.zeros((3, X.size))
        pos[0] = (X.ravel() + shift / 16 + 0.5) % 1.0 - 0.5
        pos[2] = (Z.ravel() - 0.31 * shift / 12 + 0.5) % 1.0 - 0.5
        rho = deposit_density(mesh, pos, np.full(X.size, 2.0 / 192), kernel)
        np.testing.assert_allclose(rho, 2.0, rtol=1e-13)


def test_mirror_faces_fold_the_stencil_back_into_the_domain():
    """Near outflow or reflecting faces the part of a stencil beyond the face is folded back:
    every particle still deposits exactly its mass (random particles, 3D)."""
    rng = np.random.default_rng(2)
    mesh = Mesh((6, 5, 7), (1.0, 1.0, 1.4))
    pos = np.array([rng.uniform(lo, lo + L, 300) for lo, L in zip(mesh.lower, mesh.size)])
    mass = rng.uniform(0.5, 1.5, 300)
    for kinds in (("periodic", "outflow", "reflecting"), ("outflow", "outflow", "outflow")):
        rho = deposit_density(mesh, pos, mass, "tsc", kinds)
        assert rho.sum() * mesh.cell_volume == pytest.approx(mass.sum(), rel=1e-14)
        assert rho.min() >= 0.0


@pytest.mark.parametrize(("shape", "kinds", "kernel"), [
    ((8, 1, 6), ("periodic", "periodic", "periodic"), "cic"),
    ((8, 1, 6), ("shear-periodic", "periodic", "periodic"), "tsc"),
    ((7, 5, 4), ("periodic", "periodic", "periodic"), "tsc"),
    ((2, 1, 3), ("periodic", "periodic", "periodic"), "tsc-c"),  # boxes as short as the reach (2)
    ((5, 1, 1), ("periodic", "periodic", "periodic"), "tsc-c"),
])
def test_periodic_images_read_in_place_are_the_image_records_bit_for_bit(shape, kinds, kernel):
    """Where every image is a particle one box length away with its own weights, the deposit reads
    those particles in place of image records (``wrap``): the same records in the same order, so
    the same density to the last bit; and every particle deposits exactly its mass (random
    particles, several in some cells, one exactly on a face)."""
    rng = np.random.default_rng(7)
    mesh = Mesh(shape, (1.0, 0.8, 1.3))
    n = 40 * int(np.prod(shape))
    pos = np.array([rng.uniform(lo, lo + L, n) if s > 1 else np.zeros(n)
                    for lo, L, s in zip(mesh.lower, mesh.size, shape)])
    pos[:, :n // 4] = pos[:, n // 4:n // 2]  # pairs in the same place: the order within a cell is by id
    pos[0, 0] = mesh.lower[0]
    mass = rng.uniform(0.5, 1.5, n)
    in_place = deposit_density(mesh, pos, mass, kernel, kinds, wrap=True)
    records = deposit_density(mesh, pos, mass, kernel, kinds, wrap=False)
    assert np.array_equal(in_place, records)
    assert in_place.sum() * mesh.cell_volume == pytest.approx(mass.sum(), rel=1e-14)
    assert np.array_equal(deposit_density(mesh, pos, mass, kernel, kinds), in_place)  # the default reads in place


def test_periodic_images_in_place_only_where_they_are_copies():
    """Outflow or reflecting faces and radial images that slide along y need image records: the
    deposit refuses to read those in place."""
    from dustygas.particles.boundaries import images_wrap, make_particle_boundaries

    def wraps(kinds, shape, reach=2):
        active = tuple(s > 1 for s in shape)
        gas = tuple(k if k != "reflecting" else "outflow" for k in kinds)
        pb = make_particle_boundaries(kinds, gas, active, 0.3, 0.3)
        return images_wrap(pb, [reach if a else 0 for a in active], shape)

    assert wraps(("shear-periodic", "periodic", "periodic"), (8, 1, 8))
    assert not wraps(("shear-periodic", "periodic", "periodic"), (8, 4, 8))  # the images slide along y
    assert not wraps(("periodic", "periodic", "outflow"), (8, 1, 8))
    assert not wraps(("periodic", "periodic", "reflecting"), (8, 1, 8))
    assert not wraps(("periodic", "periodic", "periodic"), (8, 1, 1), reach=9)  # shorter than the reach
    mesh = Mesh((6, 1, 6), (1.0, 1.0, 1.0))
    with pytest.raises(ValueError, match="wrap=True"):
        deposit_density(mesh, np.zeros((3, 1)), np.ones(1), "tsc", ("periodic", "periodic", "outflow"), wrap=True)


@pytest.mark.parametrize(("problem", "sets"), [
    ("si-linA", ["grid.nx=16", "grid.nz=16"]),
    ("si3d", ["grid.nx=16", "grid.ny=1", "grid.nz=24"]),
])
def test_coupled_step_with_periodic_images_in_place_matches_image_records(problem, sets):
    """The coupled engine reads periodic images in place (a shear-periodic x-z box, and a
    stratified x-z box with periodic z): 12 steps give the same gas and particles, bit for bit,
    as with image records."""
    from dustygas.problems import get_problem

    prob = get_problem(problem)
    runs = []
    for wrap in (True, False):
        eng = prob.build(prob.config(overrides=sets))
        assert eng._wrap
        eng._wrap = wrap
        for _ in range(12):
            eng.advance(eng.timestep())
        runs.append((eng.gas.states[0].copy(), eng.particles.pos.copy(), eng.particles.vel.copy()))
    for a, b in zip(*runs):
        assert np.array_equal(a, b)


def test_canonical_order_depends_only_on_positions_and_ids():
    """Sorted by cell, then by id, whatever the order the particles came in."""
    rng = np.random.default_rng(3)
    n = 500
    mesh = Mesh((6, 1, 5), (1.0, 1.0, 1.0))
    pos = np.zeros((3, n))
    pos[0] = rng.uniform(-0.5, 0.5, n)
    pos[2] = rng.uniform(-0.5, 0.5, n)
    # two particles per position pair share cells: ids decide
    results = []
    for perm in (np.arange(n), rng.permutation(n)):
        store = ParticleStore(pos[:, perm], rng.standard_normal((3, n)) * 0 + pos[:, perm], (perm % 3), perm,
                              1.0 + perm)
        p, v, s, i, m = store.buffers()
        keys = np.zeros(n, dtype=np.int64)
        start = np.zeros(31, dtype=np.int64)
        wts = np.zeros((n, 3, 3))
        bad = sort_by_cell(p, v, s, i, m, n, mesh.layout, mesh.spacing, mesh.offsets, keys, np.zeros(n, dtype=np.int64),
                           np.zeros(30, dtype=np.int64), start, np.zeros((7, n)), np.zeros((3, n), dtype=np.int64),
                           KERNELS["tsc"], 1, wts)
        assert bad == -1
        # the TSC weights of the sorted particles along x (6 cells on [-0.5, 0.5)): each sums to one
        np.testing.assert_allclose(wts[:n, 0].sum(axis=1), 1.0, rtol=0, atol=1e-15)
        np.testing.assert_array_equal(wts[:n, 1], np.tile([0.0, 1.0, 0.0], (n, 1)))  # y inactive
        cell = np.floor((store.pos[2] + 0.5) * 5).astype(int) * 6 + np.floor((store.pos[0] + 0.5) * 6).astype(int)
        np.testing.assert_array_equal(keys[:n], cell)
        assert np.all(np.diff(cell) >= 0)
        same = np.diff(cell) == 0
        assert np.all(np.diff(store.pid)[same] > 0)
        np.testing.assert_array_equal(start[:-1], [np.count_nonzero(cell < c) for c in range(30)])
        np.testing.assert_array_equal(store.vel, store.pos)  # every array moved with the particle
        np.testing.assert_array_equal(store.mass, 1.0 + store.pid)
        results.append(store.pid.copy())
    np.testing.assert_array_equal(*results)


def test_store_grows_and_removes_in_order():
    store = ParticleStore.create(np.zeros((3, 3)), np.zeros((3, 3)), 0, 1.0)
    store.append(np.ones((3, 5)), np.ones((3, 5)), 1, np.arange(3, 8), 2.0)
    assert store.n == 8 and store.capacity >= 8
    store.remove(store.pid % 2 == 0)
    np.testing.assert_array_equal(store.pid, [0, 2, 4, 6])
    np.testing.assert_array_equal(store.mass, [1.0, 1.0, 2.0, 2.0])


def thread_case(problem: str, sets: list[str]) -> dict:
    """12 steps of ``problem`` with scrambled particle velocities (so particles change cells)."""
    from dustygas.problems import get_problem

    prob = get_problem(problem)
    eng = prob.build(prob.config(overrides=sets))
    rng = np.random.default_rng(0)
    eng.particles.vel[...] += 0.01 * rng.standard_normal(eng.particles.vel.shape)
    for _ in range(12):
        eng.advance(eng.timestep())
    return {"gas": eng.gas.state, "pos": eng.particles.pos, "vel": eng.particles.vel, "pid": eng.particles.pid,
            "rho_p": eng.dust_density()}


def test_coupled_3d_shearing_box_does_not_depend_on_the_thread_count(tmp_path):
    """Sorts, images, deposits and every pass are bit-identical on 1 and 2 threads (a 3D
    shear-periodic stratified box with outflowing z and back-reaction, each thread count in its
    own interpreter)."""
    sets = ["grid.nx=8", "grid.ny=8", "grid.nz=12", "problem.Hp=0.03"]
    assert_identical(results_at_threads("particles.test_kernels:thread_case", tmp_path, problem="si3d", sets=sets))


@pytest.mark.parametrize(("integrator", "cfl"), [("ctu", 0.8), ("vl2", 0.4)])
def test_coupled_2d_xz_box_does_not_depend_on_the_thread_count(tmp_path, integrator, cfl):
    """The same in a 2D x-z box (si-linA, 16², CTU and VL2 gas steps): its grid-scale filter runs
    out of place over pieces of the rows and its deposits over chunks of rows, both as many as
    threads; the VL2 stage sweeps each axis in a parallel region of its own, its pencils split in
    as many chunks as threads."""
    sets = ["grid.nx=16", "grid.nz=16", f"scheme.integrator={integrator}", f"scheme.cfl={cfl}"]
    assert_identical(results_at_threads("particles.test_kernels:thread_case", tmp_path, problem="si-linA", sets=sets))


@pytest.mark.parametrize("npiece", [1, 2, 3, 7])
@pytest.mark.parametrize("rows", [(0, 40), (5, 31), (11, 17)])
@pytest.mark.parametrize("kinds", [(0, 0, 0), (2, 0, 2), (1, 0, 0, 3), (0, 0, 3, 2)],
                         ids=["periodic", "mirror", "shear-x-neighbour-top", "neighbour-bottom-mirror-top"])
def test_xz_filter_equals_the_ghost_fill_and_the_generic_filter_for_any_split(npiece, rows, kinds):
    """The 2D x-z filter of the coupled step fills the field's ghosts itself (each piece its own
    rows, a neighbour's rows from a private copy) and filters out of place: ``out`` holds bit for
    bit what the generic ghost fill followed by the generic in-place filter leave in the field,
    for any split of the rows, for full and partial row windows and every ghost rule (periodic,
    mirror, a face a neighbouring block fills), and the field keeps its domain cells and gets the
    generic ghosts. Outside the window only the domain columns are compared: the generic fill
    copies whole z ghost rows there, stale x ghosts included, which nothing reads."""
    from dustygas.grid.field_ghosts import fill_field_ghosts
    from dustygas.particles.deposit import filter_field, filter_field_xz

    rng = np.random.default_rng(7)
    gx = gz = 4
    f = rng.random((40, 1, 36, 9))
    k_lo, k_hi = rows
    kinds = np.array(kinds, dtype=np.int64)
    reference = f.copy()
    fill_field_ghosts(reference, gx, 0, gz, kinds, 0.0, 0, 0, k_lo, k_hi)
    filled = reference.copy()
    filter_field(reference, np.array([True, False, True]), k_lo, k_hi)
    out = np.full_like(f, np.nan)
    filter_field_xz(f, out, k_lo, k_hi, npiece, gx, gz, kinds)
    window = slice(k_lo, k_hi)
    assert np.array_equal(out[window], reference[window])
    assert np.array_equal(out[:, :, gx:-gx], reference[:, :, gx:-gx])
    assert np.array_equal(f[window], filled[window])
    assert np.array_equal(f[:, :, gx:-gx], filled[:, :, gx:-gx])


@pytest.mark.parametrize(("problem", "sets"), [
    ("si-linA", ["grid.nx=16", "grid.nz=16"]),
    ("si3d", ["grid.nx=8", "grid.ny=8", "grid.nz=16", "problem.gas_boundary_z=outflow"]),
])
def test_image_records_count_every_image_and_survive_short_arrays(problem, sets):
    """Without shear the number of image records is the analytic one: a particle within the reach
    of ``a_d`` faces along axis d has ``prod_d (1 + a_d) - 1`` images (images of images at edges
    and corners); in the shearing box the radial images slide along y, and with them the y faces
    they are near, so there only the next property is checked. Called with arrays too short, the
    build returns a larger number; the caller grows the arrays to it and calls again
    (:meth:`~dustygas.particles.coupling.ParticleGridEngine._prepare`), and gets the same records
    as with long arrays, bit for bit."""
    from dustygas.particles.boundaries import build_images
    from dustygas.problems import get_problem

    prob = get_problem(problem)
    eng = prob.build(prob.config(overrides=sets))
    eng.advance(eng.timestep())
    eng._prepare(eng.t)
    n = eng.particles.n
    args = (n, eng._lay, eng._sp, eng._pb, eng._reach, eng._order, eng.geometry.shear_offset(eng.t), eng._keys,
            eng._wts, eng.particles.buffers()[0], eng._cell_start)
    W = eng._wts.shape[2]

    def records(cap):
        arrays = (np.zeros(cap, dtype=np.int64), np.zeros((cap, 3), dtype=np.int64), np.zeros((cap, 3, W)),
                  np.zeros(cap))
        m = build_images(*args, *arrays)
        return m, tuple(a[:m] for a in arrays)

    m, reference = records(8 * n)
    keys = eng._keys[:n]
    nx, ny, _ = eng.mesh.shape
    cells = np.stack([keys % nx, (keys // nx) % ny, keys // (nx * ny)])
    expected = np.ones(n, dtype=np.int64)
    for axis, (size, reach) in enumerate(zip(eng.mesh.shape, eng._reach)):
        if size > 1 and reach > 0:
            expected *= 1 + (cells[axis] < reach) + (cells[axis] >= size - reach)
    if not eng.geometry.shear_periodic:
        assert m == int(np.sum(expected - 1)) > 0
    m_short, _ = records(m // 3)
    assert m // 3 < m_short <= m
    m_again, again = records(m_short)
    while m_again > m_short:  # the caller's protocol
        m_short = m_again
        m_again, again = records(m_short)
    assert m_again == m
    for a, b in zip(again, reference):
        assert np.array_equal(a, b)
