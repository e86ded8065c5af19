"""The drag integrator against exact solutions computed here independently (scipy's expm).

* :func:`relax`: ``v' = g + (u0 + a t - v)/t_s`` is linear with a forcing linear in time; its
  exact solution is the exponential of the augmented matrix. Exact to round-off for any h/t_s.
* :func:`oscillator_step`: the damped vertical oscillator with the same forcing, stiff to
  free (τ_s from 1e-6 to 1e4, through critical damping τ_s = 1/2).
* :func:`relaxation_rates`, :func:`cell_model`: the local drag problem of gas and N species,
  against the eigenvalues and the matrix exponential of the full (N+1)-velocity system.
"""

import numpy as np
import pytest
from numba import njit
from scipy.linalg import expm

from dustygas.particles.drag import cell_model, oscillator_step, relax, relaxation_rates
from dustygas.physics.drag import epstein_stopping_time, epstein_stopping_time_scalar


def exact_linear(v0, ts, h, u0, a, g):
    """v(h) of v' = g + (u0 + a t - v)/ts: state (v, t, 1)."""
    M = np.array([[-1 / ts, a / ts, g + u0 / ts], [0, 0, 1], [0, 0, 0]])
    return (expm(M * h) @ np.array([v0, 0.0, 1.0]))[0]


@pytest.mark.parametrize("ts", [1e-6, 1e-3, 0.1, 1.0, 1e3])
@pytest.mark.parametrize("h", [1e-4, 0.05, 0.7])
def test_relax_is_exact_for_any_step(ts, h):
    v0, u0, a, g = 0.3, -0.2, 0.7, -0.05
    got = relax(v0, ts, h, u0, a, g, 0.0)
    want = exact_linear(v0, ts, h, u0, a, g)
    assert got == pytest.approx(want, rel=1e-12, abs=1e-14)


def exact_oscillator(z0, v0, ts, w2, h, b0, b1):
    M = np.zeros((4, 4))
    M[0, 1] = 1.0
    M[1, 0], M[1, 1], M[1, 2], M[1, 3] = -w2, -1 / ts, b1, b0
    M[2, 3] = 1.0
    y = expm(M * h) @ np.array([z0, v0, 0.0, 1.0])
    return y[0], y[1]


@pytest.mark.parametrize("ts", [1e-6, 1e-3, 0.01, 0.4999999, 0.5, 0.5000001, 1.0, 100.0, 1e4])
@pytest.mark.parametrize("h", [1e-3, 0.3, 2.0])
def test_oscillator_step_is_exact_from_stiff_to_free(ts, h):
    """Tolerance 1e-12 of the solution's scale; 1e-10 where h/t_s > 1e5, at which scipy's expm of
    the reference itself loses 1e-11 (the worst case, t_s = 1e-6, h = 2, agrees with a 40-digit
    mpmath exponential to 1e-16)."""
    z0, v0, w2 = 0.07, -0.3, 1.0
    b0, b1 = 0.02 + 0.01 / ts, -0.5 / ts  # a gas velocity u0 + a t seen through the drag
    z, v = oscillator_step(z0, v0, ts, w2, h, b0, b1)
    ze, ve = exact_oscillator(z0, v0, ts, w2, h, b0, b1)
    scale = abs(z0) + abs(v0) * h + abs(ze) + abs(ve) * h
    tol = 1e-12 if h / ts < 1e5 else 1e-10
    assert abs(z - ze) < tol * scale and abs(v - ve) * h < tol * scale, (z, ze, v, ve)


def arrow_matrix(rho_g, rho_s, ts):
    """The drag-only system d/dt (u, V_1..V_N) = -A (u, V): A = M^{-1} D."""
    n = len(rho_s)
    A = np.zeros((n + 1, n + 1))
    for s in range(n):
        k = rho_s[s] / ts[s]
        A[0, 0] += k / rho_g
        A[0, s + 1] -= k / rho_g
        A[s + 1, s + 1] += 1 / ts[s]
        A[s + 1, 0] -= 1 / ts[s]
    return A


def test_relaxation_rates_are_the_eigenvalues_of_the_local_system():
    rng = np.random.default_rng(4)
    for n in (1, 2, 3, 7):
        for _ in range(20):
            ts = np.sort(10 ** rng.uniform(-4, 1, n))[::-1].copy()
            rho_s = 10 ** rng.uniform(-3, 2, n)
            mu = np.zeros(n)
            relaxation_rates(rho_s.copy(), ts, n, mu)
            ev = np.sort(np.linalg.eigvals(arrow_matrix(1.0, rho_s, ts)).real)
            np.testing.assert_allclose(mu, ev[1:], rtol=1e-10)
            assert abs(ev[0]) < 1e-8 * ev[-1]  # the centre of mass


@pytest.mark.parametrize("n", [1, 2, 4])
def test_cell_model_particle_follows_the_exact_local_solution(n):
    """A particle of species s with the species' mean velocity, updated with relax + R_s, lands
    exactly on V_s(h) of the full local system (drag, constant forcing); the gas's mean
    acceleration A is the mixture's."""
    rng = np.random.default_rng(11 + n)
    rho_g = 1.3
    rho_s = 10 ** rng.uniform(-2, 2, n)
    ts = 10 ** rng.uniform(-4, 0, n)
    u0 = rng.standard_normal(3)
    vs = rng.standard_normal((n, 3))
    fg = rng.standard_normal(3)
    fs = rng.standard_normal((n, 3))
    h = 0.02
    out_a = np.zeros(3)
    out_r = np.zeros((n, 3))
    cell_model(rho_g, u0, fg, n, rho_s, vs, fs, ts, h, out_a, out_r, np.zeros((6, n)), np.zeros(n, dtype=np.int64),
               np.zeros((n, 3)))
    np.testing.assert_allclose(out_a, (rho_g * fg + rho_s @ fs) / (rho_g + rho_s.sum()), rtol=1e-13)
    A = arrow_matrix(rho_g, rho_s, ts)
    for c in range(3):
        M = np.zeros((n + 2, n + 2))
        M[:n + 1, :n + 1] = -A
        M[:n + 1, n + 1] = np.r_[fg[c], fs[:, c]]
        y = expm(M * h) @ np.r_[u0[c], vs[:, c], 1.0]
        for s in range(n):
            v = relax(vs[s, c], ts[s], h, u0[c], out_a[c], fs[s, c], out_r[s, c])
            assert v == pytest.approx(y[1 + s], rel=1e-9, abs=1e-11 * np.abs(y).max()), (n, s, c)


@pytest.mark.parametrize("rho_s, ts", [
    ([0.0, 6.6e-17, 0.0], [1e-3, 0.0316, 0.1]),  # one species present, far below round-off of the gas
    ([0.3, 1e-17, 2e-16], [1.0, 0.3, 0.1]),  # tiny species with roots just above their poles
    ([3.0, 1e-16, 0.0], [1.0, 0.3, 0.1]),  # (1 + eps_0)/T_0 > 1/T_1: a root just below the tiny one's pole
    ([0.2, 1e-9, 0.05], [1e-4, 1e-2, 1e-1]),
])
def test_cell_model_with_a_species_far_below_the_gas_density(rho_s, ts):
    """A cell at the edge of a particle's stencil holds 1e-17 of the gas density of a species
    (si3d-bs10b's first step): its drag mode lies within ~ε/T of its pole, where ``1 - μ T``
    computed from μ is round-off or 0 (an infinite mode vector, NaN gas). The responses are
    finite and a particle of every species, present or absent, lands on the exact local
    solution (expm of the system of the present species; a test particle for the absent ones):
    measured 1.3e-14 relative, tolerance 1e-13 (the first case gave NaN before the roots were
    sought as offsets from their poles)."""
    rng = np.random.default_rng(5)
    n = len(rho_s)
    rho_s, ts = np.array(rho_s), np.array(ts)
    rho_g, h = 0.9, 0.02
    u0, fg = rng.standard_normal(3), rng.standard_normal(3)
    vs, fs = rng.standard_normal((n, 3)), rng.standard_normal((n, 3))
    out_a, out_r = np.zeros(3), np.zeros((n, 3))
    cell_model(rho_g, u0, fg, n, rho_s, vs, fs, ts, h, out_a, out_r, np.zeros((6, n)), np.zeros(n, dtype=np.int64),
               np.zeros((n, 3)))
    assert np.all(np.isfinite(out_r))
    present = rho_s > 0
    A = arrow_matrix(rho_g, rho_s[present], ts[present])
    m = int(present.sum())
    for c in range(3):
        M = np.zeros((m + 2, m + 2))
        M[:m + 1, :m + 1] = -A
        M[:m + 1, m + 1] = np.r_[fg[c], fs[present, c]]
        y = expm(M * h) @ np.r_[u0[c], vs[present, c], 1.0]
        k = 0
        for s in range(n):
            v = relax(vs[s, c], ts[s], h, u0[c], out_a[c], fs[s, c], out_r[s, c])
            if present[s]:
                exact = y[1 + k]
                k += 1
            else:  # a test particle in the gas of the present species: the system plus its own row
                B = np.zeros((m + 3, m + 3))
                B[:m + 1, :m + 1] = -A
                B[m + 1, 0], B[m + 1, m + 1] = 1 / ts[s], -1 / ts[s]
                B[:m + 1, m + 2] = np.r_[fg[c], fs[present, c]]
                B[m + 1, m + 2] = fs[s, c]
                exact = (expm(B * h) @ np.r_[u0[c], vs[present, c], vs[s, c], 1.0])[m + 1]
            assert v == pytest.approx(exact, rel=1e-13), (s, c)


def test_stiff_heavy_dust_relaxes_at_the_exact_rate():
    """ε = 100, t_s = 1e-3: the relative velocity of the cell decays as exp(-(1+ε) h/t_s) per step:
    to 1e-9 relative while that is above 1e-6, else to the round-off of the velocities (1e-13 of
    the initial relative velocity); the mixture's momentum is unchanged."""
    rho_g, eps, ts = 1.0, 100.0, 1e-3
    for h in (2e-5, 1e-4, 1e-3):
        u0, V = np.array([0.0, 0.0, 0.0]), np.array([1.0, -0.5, 0.2])
        out_a, out_r = np.zeros(3), np.zeros((1, 3))
        cell_model(rho_g, u0, np.zeros(3), 1, np.array([eps]), V[None], np.zeros((1, 3)), np.array([ts]), h, out_a,
                   out_r, np.zeros((6, 1)), np.zeros(1, dtype=np.int64), np.zeros((1, 3)))
        v = np.array([relax(V[c], ts, h, u0[c], 0.0, 0.0, out_r[0, c]) for c in range(3)])
        u = u0 - eps * (v - V)  # the gas gets minus the particle's impulse
        ratio = (v - u) / (V - u0)
        exact = np.exp(-(1 + eps) * h / ts)
        if exact > 1e-6:
            np.testing.assert_allclose(ratio, exact, rtol=1e-9)
        else:
            np.testing.assert_allclose(ratio, exact, rtol=0, atol=1e-13)
        np.testing.assert_allclose(u + eps * v, u0 + eps * V, rtol=1e-14)


def test_compiled_epstein_stopping_time_agrees_with_the_numpy_one():
    rng = np.random.default_rng(7)
    for _ in range(50):
        s, rho_grain, rho_g, cs, gamma = 10 ** rng.uniform(-4, 2), rng.uniform(1, 4), 10 ** rng.uniform(-12, -6), \
            10 ** rng.uniform(4, 6), rng.uniform(1, 5 / 3)
        a = epstein_stopping_time_scalar(s, rho_grain, rho_g, cs, gamma)
        b = float(epstein_stopping_time(s, rho_grain, rho_g, cs, gamma))
        assert a == pytest.approx(b, rel=1e-15)
