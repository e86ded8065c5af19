"""The compiled Hessenberg-QR eigenvalues against LAPACK and against extended precision.

Tolerance. Both solvers are backward stable: each returns the exact eigenvalues of a matrix
within a few ε‖A‖ of the input. The operators here carry sound waves (|λ| ~ c_s|k| up to
~1e4) and drag rates (up to μ/τ_s ~ 1e5) next to growth rates ~1e-6, so an eigenvalue far
below ‖A‖ is only determined to ~ε‖A‖ by *any* double-precision method. The comparison
is therefore |λ − λ_LAPACK| ≤ 1e-10 |λ| + 1e4 ε ‖A‖_F for every eigenvalue (and the same for
the maximal growth rate): relative 1e-10 wherever the eigenvalue is resolved, the common
backward-error floor elsewhere. Independently of LAPACK, every eigenvalue is checked to have a backward error below
100 ε‖A‖_F (smallest singular value of A − λI).
"""

import numpy as np
from scipy.optimize import linear_sum_assignment

from dustygas.linear import StreamingParams, growth_rate, operator_matrix
from dustygas.linear.eigensolver import eigvals_batch

EPS = np.finfo(float).eps


def random_operators(n, seed, species=1):
    rng = np.random.default_rng(seed)
    drags = ("consistent", "yj07", "epstein")
    out = []
    for i in range(n):
        taus = list(10 ** rng.uniform(-3, 1, species))
        mu = list(10 ** rng.uniform(-2, 2, species))
        p = StreamingParams(
            taus=taus if species > 1 else taus[0], mu=mu if species > 1 else mu[0],
            kx=float(10 ** rng.uniform(-1, 3) * rng.choice([-1, 1])),
            kz=float(10 ** rng.uniform(-1, 3) * rng.choice([-1, 1])),
            Pi=(0.05, 0.0, 0.1)[i % 3], drag=drags[(i // 3) % 3], vz=float(rng.normal()) * (i % 2))
        out.append(p)
    return out


def _check(mats):
    worst_rel = 0.0
    for A in mats:
        ours = eigvals_batch(A[None])[0]
        ref = np.linalg.eigvals(A)
        C = np.abs(ours[:, None] - ref[None, :])
        r, c = linear_sum_assignment(C)
        floor = 1e4 * EPS * np.linalg.norm(A)
        tol = 1e-10 * np.abs(ref[c]) + floor
        assert np.all(C[r, c] <= tol), (C[r, c], tol)
        s, s_ref = ours.real.max(), ref.real.max()
        assert abs(s - s_ref) <= 1e-10 * abs(s_ref) + floor
        resolved = np.abs(ref[c]) >= 1e-2 * np.linalg.norm(A)
        if resolved.any():
            worst_rel = max(worst_rel, float(np.max(C[r, c][resolved] / np.abs(ref[c][resolved]))))
    return worst_rel


def test_against_lapack_single_species_3000_operators():
    """3000 operators: 8×8 compressible and 6×6 incompressible, three drags, with/without drift."""
    mats = [operator_matrix(p) for p in random_operators(3000, seed=1)]
    assert {m.shape[0] for m in mats} == {6, 8}
    worst = _check(mats)
    assert worst <= 1e-10  # eigenvalues with |λ| >= 0.01 ‖A‖_F: relative agreement


def test_against_lapack_two_species():
    _check([operator_matrix(p) for p in random_operators(300, seed=2, species=2)])


def test_against_lapack_random_dense_matrices():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(500, 8, 8)) + 1j * rng.normal(size=(500, 8, 8))
    _check(list(A))


def test_growth_rate_kernel_equals_lapack_on_operators():
    """The vectorised fast path (build + QR in one kernel) against LAPACK on the same points."""
    ps = random_operators(600, seed=4)
    ps = [p for p in ps if not p.incompressible]
    s = growth_rate(taus=[p.taus for p in ps], mu=[p.mu for p in ps], kx=[p.kx for p in ps], kz=[p.kz for p in ps],
                    Pi=[p.Pi for p in ps], drag="consistent",
                    vz=[p.vz_array[0] for p in ps])
    for si, p in zip(s, ps):
        q = StreamingParams(taus=p.taus, mu=p.mu, kx=p.kx, kz=p.kz, Pi=p.Pi, drag="consistent", vz=p.vz)
        A = operator_matrix(q)
        ref = np.linalg.eigvals(A).real.max()
        assert abs(si - ref) <= 1e-10 * abs(ref) + 1e4 * EPS * np.linalg.norm(A)


def test_every_eigenvalue_has_a_tiny_backward_error():
    """σ_min(A − λI) ≤ 100 ε ‖A‖_F: each λ is exactly an eigenvalue of a matrix within 100 ε‖A‖."""
    for p in random_operators(300, seed=5):
        A = operator_matrix(p)
        n = A.shape[0]
        for lam in eigvals_batch(A[None])[0]:
            smin = np.linalg.svd(A - lam * np.eye(n), compute_uv=False)[-1]
            assert smin <= 100 * EPS * np.linalg.norm(A)
