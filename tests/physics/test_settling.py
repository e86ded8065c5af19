"""Settling (thesis §4.1.4-4.1.5, eqs. 4.18-4.20)."""

import numpy as np

from dustygas.physics import (
    growth_settling_threshold,
    growth_to_settling_ratio,
    settling_time,
    steady_settling_velocity,
)

TAUS = np.array([1.0, 0.1, 0.01, 0.001])


def test_growth_settling_criterion_values():
    """Criterion 4.20, tau/(2 tau^2 + 1), at tau_s = 1, 0.1, 0.01, 0.001.

    Exact, by hand: 1/3, 0.1/1.02 = 0.0980392157, 0.01/1.0002 = 0.0099980004, 0.001/1.000002 =
    0.000999998 (to 1e-15).
    """
    got = growth_settling_threshold(TAUS)
    np.testing.assert_allclose(got, [1 / 3, 0.1 / 1.02, 0.01 / 1.0002, 0.001 / 1.000002], rtol=1e-15)


def test_settling_time_and_velocity_are_consistent():
    """eq. 4.19: v_z = H_g / t_settle with H_g = c_s/Omega; eq. 4.20 ratio is 1 at the threshold."""
    Omega, c_s = 2e-8, 5e4
    t_settle = settling_time(TAUS, Omega)
    np.testing.assert_allclose(t_settle, (2 * TAUS**2 + 1) / (TAUS * Omega), rtol=1e-15)
    np.testing.assert_allclose(steady_settling_velocity(TAUS, c_s), (c_s / Omega) / t_settle, rtol=1e-15)
    growth = growth_settling_threshold(TAUS) * Omega
    np.testing.assert_allclose(growth_to_settling_ratio(growth, TAUS, Omega), 1.0, rtol=1e-15)
    # t_settle is shortest, 2 sqrt(2)/Omega, at tau_s = 1/sqrt(2)
    taus = np.geomspace(1e-2, 1e2, 40001)
    i = np.argmin(settling_time(taus))
    np.testing.assert_allclose(taus[i], 1 / np.sqrt(2), rtol=2e-4)
    np.testing.assert_allclose(settling_time(1 / np.sqrt(2)), 2 * np.sqrt(2), rtol=1e-15)
