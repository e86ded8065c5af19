"""Nakagawa-Sekiya-Hayashi drift (thesis eq. 4.8): published values and steady-state residuals."""

import numpy as np
import pytest

from dustygas.physics import nsh_velocities, nsh_velocities_multi

# Nakagawa, Sekiya & Hayashi (1986) at Youdin & Johansen (2007)'s linA/linB parameters, worked out to 8 decimals
# (units eta v_K; D = (1+eps)^2 + tau^2, U = (2 eps tau, -(1+eps+tau^2))/D, W = (-2 tau, -(1+eps))/D)
PUBLISHED = {
    "linA": (0.1, 3.0, (+0.03747658, -0.25046846), (-0.01249219, -0.24984385)),
    "linB": (0.1, 0.2, (+0.02758621, -0.83448276), (-0.13793103, -0.82758621)),
}


@pytest.mark.parametrize("case", sorted(PUBLISHED))
def test_nsh_matches_published_linA_linB(case):
    """Printed to 8 decimals, so the exact values lie within 5e-9 of them (< 1e-8)."""
    taus, mu, gas, dust = PUBLISHED[case]
    eq = nsh_velocities(taus, mu)
    got = [float(eq.gas_vx), float(eq.gas_vy), float(eq.dust_vx), float(eq.dust_vy)]
    np.testing.assert_allclose(got, [*gas, *dust], rtol=0, atol=5e-9)


def test_n_species_reduces_to_one_species():
    taus = np.array([1e-3, 0.1, 1.0, 10.0])
    mus = np.array([0.01, 3.0, 0.2, 1.0])
    one = nsh_velocities(taus, mus)
    for j in range(taus.size):
        multi = nsh_velocities_multi([taus[j]], [mus[j]])
        np.testing.assert_allclose(multi.gas_vx, one.gas_vx[j], rtol=1e-14)
        np.testing.assert_allclose(multi.gas_vy, one.gas_vy[j], rtol=1e-14)
        np.testing.assert_allclose(multi.dust_vx[0], one.dust_vx[j], rtol=1e-14)
        np.testing.assert_allclose(multi.dust_vy[0], one.dust_vy[j], rtol=1e-14)
    # a species split into two identical halves is the same physical system
    split = nsh_velocities_multi([0.1, 0.1], [1.5, 1.5])
    np.testing.assert_allclose(split.dust_vx, nsh_velocities(0.1, 3.0).dust_vx, rtol=1e-14)
    np.testing.assert_allclose(split.gas_vy, nsh_velocities(0.1, 3.0).gas_vy, rtol=1e-14)


def _momentum_residuals(taus, mus, eq):
    """Steady shearing-sheet momentum equations, Omega = 1, velocities in eta*v_K.

    Gas:  0 = 2 u_y + 2 + sum_j mu_j (v_xj - u_x)/tau_j,   0 = -u_x/2 + sum_j mu_j (v_yj - u_y)/tau_j
    Dust: 0 = 2 v_yj - (v_xj - u_x)/tau_j,                 0 = -v_xj/2 - (v_yj - u_y)/tau_j
    (Coriolis + tidal shear give 2 u_y and -u_x/2 for velocities relative to -3/2 x y-hat;
    the global pressure gradient is the force 2 eta v_K Omega on the gas, thesis eq. 4.2b.)
    Each residual is divided by the size of its equation's terms, with a difference such as
    v_xj - u_x counted as |v_xj| + |u_x| (a backward-error residual: at tau_j = 1e-3 the drag
    terms are differences of nearly equal O(1) velocities divided by 1e-3).
    """
    ux, uy, vx, vy = eq.gas_vx, eq.gas_vy, eq.dust_vx, eq.dust_vy
    a = np.abs
    equations = [  # (sum of terms, scale)
        (2 * uy + 2 + np.sum(mus * (vx - ux) / taus), 2 * a(uy) + 2 + np.sum(mus * (a(vx) + a(ux)) / taus)),
        (-ux / 2 + np.sum(mus * (vy - uy) / taus), a(ux) / 2 + np.sum(mus * (a(vy) + a(uy)) / taus)),
        *[(2 * vy[j] - (vx[j] - ux) / taus[j], 2 * a(vy[j]) + (a(vx[j]) + a(ux)) / taus[j]) for j in range(taus.size)],
        *[(-vx[j] / 2 - (vy[j] - uy) / taus[j], a(vx[j]) / 2 + (a(vy[j]) + a(uy)) / taus[j]) for j in range(taus.size)],
    ]
    return np.array([value / scale for value, scale in equations])


def test_n_species_steady_state_residuals_vanish():
    """tau_j from 1e-3 to 10, mu_j from 0.01 to 3: relative residuals < 1e-14."""
    rng = np.random.default_rng(1)
    for n in (1, 2, 7):
        taus = 10 ** rng.uniform(-3, 1, n)
        mus = 10 ** rng.uniform(-2, 0.5, n)
        eq = nsh_velocities_multi(taus, mus)
        res = _momentum_residuals(taus, mus, eq)
        assert np.max(np.abs(res)) < 1e-14, (n, res)


def test_momentum_residuals_detect_wrong_solution():
    """The residual check is not vacuous: perturbing the solution by 1e-10 is seen."""
    taus, mus = np.array([0.1, 1.0]), np.array([0.5, 0.3])
    eq = nsh_velocities_multi(taus, mus)
    bad = eq._replace(gas_vy=eq.gas_vy + 1e-10)
    assert np.max(np.abs(_momentum_residuals(taus, mus, bad))) > 1e-11
