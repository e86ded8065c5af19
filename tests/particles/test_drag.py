"""The drag integrators against the exact solution of one particle in uniform gas.

For fixed gas velocity u and force F the particle velocity obeys the linear ODE
``dv/dt = F + C v - (v - u)/t_s`` (Coriolis matrix C = [[0, c_x], [-c_y, 0]]); its exact
solution is computed here independently with the matrix exponential of scipy. The
exponential integrator must reproduce it to round-off for any step; the semi-implicit one
(Bai & Stone 2010a) is second order, exact for the steady drift, and bounded for h >> t_s.
"""

import numpy as np
import pytest
from numba import njit
from scipy.linalg import expm

from dustygas.particles.drag import EXPONENTIAL, SEMI_IMPLICIT, kick
from dustygas.physics.drag import epstein_stopping_time, epstein_stopping_time_scalar

CX, CY = 2.0, 0.5  # Omega = 1, q = 3/2, velocities relative to the shear
U = np.array([0.03, -0.2, 0.01])
F = np.array([-0.1, 0.02, 0.05])


@njit(cache=False)
def _run(method, v0, u, f, cx, cy, ts, h, n):
    vx, vy, vz = v0[0], v0[1], v0[2]
    imp = np.zeros(3)
    for _ in range(n):
        vx, vy, vz, dx, dy, dz = kick(method, vx, vy, vz, u[0], u[1], u[2], f[0], f[1], f[2], cx, cy, ts, h)
        imp[0] += dx
        imp[1] += dy
        imp[2] += dz
    return np.array([vx, vy, vz]), imp


def exact(v0, t, ts):
    A = np.array([[-1 / ts, CX, 0], [-CY, -1 / ts, 0], [0, 0, -1 / ts]])
    b = F + U / ts
    M = np.zeros((4, 4))
    M[:3, :3] = A
    M[:3, 3] = b
    return (expm(M * t) @ np.r_[v0, 1.0])[:3]


def exact_drag_impulse(v0, t, ts):
    """-(1/t_s) ∫ (v - u) dt on the exact solution: with y = (v, 1), y' = M y, the integral
    ∫_0^t y ds = [∫_0^t exp(M s) ds] y_0 is the top-right block of exp([[M, I], [0, 0]] t)."""
    A = np.array([[-1 / ts, CX, 0], [-CY, -1 / ts, 0], [0, 0, -1 / ts]])
    M = np.zeros((4, 4))
    M[:3, :3] = A
    M[:3, 3] = F + U / ts
    B = np.zeros((8, 8))
    B[:4, :4] = M
    B[:4, 4:] = np.eye(4)
    integral = (expm(B * t)[:4, 4:] @ np.r_[v0, 1.0])[:3]
    return -(integral - U * t) / ts


@pytest.mark.parametrize("ts", [1e-3, 0.1, 1.0, 10.0])
@pytest.mark.parametrize("h", [1e-3, 0.05, 0.7])
def test_exponential_is_exact_for_fixed_gas(ts, h):
    v0 = np.array([0.3, -0.1, 0.2])
    n = 7
    v, imp = _run(EXPONENTIAL, v0, U, F, CX, CY, ts, h, n)
    np.testing.assert_allclose(v, exact(v0, n * h, ts), rtol=1e-12, atol=1e-13)
    # the drag part of the velocity change: total change minus forces and Coriolis
    np.testing.assert_allclose(imp, exact_drag_impulse(v0, n * h, ts), rtol=1e-11, atol=1e-13)


def test_semi_implicit_is_second_order_and_keeps_the_steady_drift():
    v0 = np.array([0.3, -0.1, 0.2])
    ts, t = 0.3, 2.0
    errors = []
    for n in (50, 100, 200, 400):
        v, _ = _run(SEMI_IMPLICIT, v0, U, F, CX, CY, ts, t / n, n)
        errors.append(np.abs(v - exact(v0, t, ts)).max())
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(np.abs(orders - 2.0) < 0.02), orders
    assert errors[0] < 2e-4  # measured 7.2e-5
    # the terminal (NSH-like) velocity is a fixed point: v_inf solves 0 = F + C v - (v - u)/t_s
    A = np.array([[-1 / ts, CX, 0], [-CY, -1 / ts, 0], [0, 0, -1 / ts]])
    vinf = -np.linalg.solve(A, F + U / ts)
    for method in (SEMI_IMPLICIT, EXPONENTIAL):
        v, imp = _run(method, vinf, U, F, CX, CY, ts, 0.37, 10)
        np.testing.assert_allclose(v, vinf, rtol=1e-14, atol=1e-15)


def test_stiff_drag_is_stable():
    """h = 1000 t_s: the exponential lands on the terminal velocity, the semi-implicit one stays
    bounded (its relative velocity flips sign each step, amplification (1-500)/(1+500))."""
    v0 = np.array([1.0, -1.0, 0.5])
    ts, h = 1e-3, 1.0
    A = np.array([[-1 / ts, CX, 0], [-CY, -1 / ts, 0], [0, 0, -1 / ts]])
    vinf = -np.linalg.solve(A, F + U / ts)
    v, _ = _run(EXPONENTIAL, v0, U, F, CX, CY, ts, h, 1)
    np.testing.assert_allclose(v, vinf, rtol=1e-12)
    v, _ = _run(SEMI_IMPLICIT, v0, U, F, CX, CY, ts, h, 1000)
    assert np.abs(v - vinf).max() <= np.abs(v0 - vinf).max()


def test_compiled_epstein_stopping_time_agrees_with_the_numpy_one():
    rng = np.random.default_rng(7)
    for _ in range(50):
        s, rho_grain, rho_g, cs, gamma = 10 ** rng.uniform(-4, 2), rng.uniform(1, 4), 10 ** rng.uniform(-12, -6), \
            10 ** rng.uniform(4, 6), rng.uniform(1, 5 / 3)
        a = epstein_stopping_time_scalar(s, rho_grain, rho_g, cs, gamma)
        b = float(epstein_stopping_time(s, rho_grain, rho_g, cs, gamma))
        assert a == pytest.approx(b, rel=1e-15)
