"""Epstein and Stokes drag (thesis §2.1): hand-computed values, regime switch, conversions."""

import numpy as np

from dustygas.physics import drag
from dustygas.units import MEAN_MOLECULAR_WEIGHT, m_H, sigma_H2


def test_epstein_stopping_time_hand_computed():
    """s = 1 mm, rho_grain = 3 g/cm^3, rho_g = 1e-9 g/cm^3, c_s = 1e5 cm/s, gamma = 1:

    v_th = sqrt(8/pi) c_s = 1.5957691216e5 cm/s,
    t_s  = rho_grain s / (rho_g v_th) = 0.3 / (1e-9 * 1.5957691216e5) s
         = sqrt(pi/8) * 0.3 / 1e-4 s = 0.62665706866 * 3000 s = 1879.9712060 s.
    With gamma = 7/5: t_s = sqrt(7 pi/40) * 3000 s = 0.74147064 * 3000 s = 2224.4119 s.
    """
    t_s = drag.epstein_stopping_time(0.1, 3.0, 1e-9, 1e5)
    np.testing.assert_allclose(t_s, 1879.9712060, rtol=1e-10)
    np.testing.assert_allclose(drag.epstein_stopping_time(0.1, 3.0, 1e-9, 1e5, gamma=1.4), 2224.4119, rtol=1e-7)
    np.testing.assert_allclose(drag.thermal_speed(1e5), 1.5957691216e5, rtol=1e-10)


def test_epstein_K_and_mixture_stopping_time():
    """t_s = rho_d/K for one grain; rho_g rho_d/(K (rho_g+rho_d)) for the mixture (Laibe & Price 2011, the dustybox)."""
    s, rho_grain, rho_g, rho_d, c_s = 0.01, 2.6, 3e-10, 1e-10, 7e4
    K = drag.epstein_drag_coefficient(rho_g, rho_d, s, rho_grain, c_s)
    np.testing.assert_allclose(drag.epstein_stopping_time(s, rho_grain, rho_g, c_s), rho_d / K, rtol=1e-14)
    np.testing.assert_allclose(
        drag.epstein_stopping_time(s, rho_grain, rho_g, c_s, rho_d=rho_d),
        rho_g * rho_d / (K * (rho_g + rho_d)), rtol=1e-14,
    )
    # equal gas and dust densities halve the stopping time
    np.testing.assert_allclose(
        drag.epstein_stopping_time(s, rho_grain, rho_g, c_s, rho_d=rho_g),
        0.5 * drag.epstein_stopping_time(s, rho_grain, rho_g, c_s), rtol=1e-15,
    )


def test_stokes_number_and_inverse_size():
    Omega = 2e-8
    s = np.array([1e-4, 0.1, 10.0])
    taus = drag.stokes_number(drag.epstein_stopping_time(s, 2.6, 1e-10, 5e4), Omega)
    np.testing.assert_allclose(drag.epstein_grain_size(taus, 2.6, 1e-10, 5e4, Omega), s, rtol=1e-14)


def _regime_gas():
    rho_g, c_s = 1e-9, 1e5
    lam = drag.mean_free_path(rho_g)
    nu = drag.molecular_viscosity(rho_g, c_s)
    return rho_g, c_s, lam, nu


def test_mean_free_path_and_viscosity_definitions():
    """lambda = mu m_H/(rho_g sigma_H2) = 2.34 * 1.6737e-24 / (1e-9 * 2e-15) cm = 1.958 cm."""
    rho_g, c_s, lam, nu = _regime_gas()
    np.testing.assert_allclose(lam, MEAN_MOLECULAR_WEIGHT * m_H / (rho_g * sigma_H2), rtol=1e-15)
    np.testing.assert_allclose(lam, 1.958, rtol=1e-3)
    np.testing.assert_allclose(nu, 0.5 * lam * np.sqrt(8 / np.pi) * c_s, rtol=1e-15)


def test_epstein_stokes_switch_is_continuous_for_small_Re():
    """At s = 9 lambda/4 with Re < 1 the two laws agree: 2 rho_gr s^2/(9 nu rho_g) = rho_gr s/(rho_g v_th)."""
    rho_g, c_s, lam, nu = _regime_gas()
    s_switch = 2.25 * lam
    dv = 1.0  # cm/s
    assert drag.reynolds_number(s_switch, dv, nu) < 1.0
    stokes = drag.stokes_stopping_time(s_switch, 2.6, rho_g, dv, nu)
    epstein = drag.epstein_stopping_time(s_switch, 2.6, rho_g, c_s)
    np.testing.assert_allclose(stokes, epstein, rtol=1e-13)
    below, above = drag.stopping_time(s_switch * np.array([1 - 1e-9, 1 + 1e-9]), 2.6, rho_g, c_s, dv)
    assert abs(above / below - 1.0) < 1e-8  # t_s ~ s on one side, s^2 on the other: jump ~ 3e-9
    # well inside each regime the right law is used
    small, large = drag.stopping_time(np.array([0.01 * lam, 100 * lam]), 2.6, rho_g, c_s, dv)
    np.testing.assert_allclose(small, drag.epstein_stopping_time(0.01 * lam, 2.6, rho_g, c_s), rtol=1e-15)
    np.testing.assert_allclose(large, drag.stokes_stopping_time(100 * lam, 2.6, rho_g, dv, nu), rtol=1e-15)
    assert large > 2 * drag.epstein_stopping_time(100 * lam, 2.6, rho_g, c_s)  # Stokes drag is weaker


def test_stokes_branches_at_Re_1_and_800():
    """C_D is continuous at Re = 1 (24/Re = 24 Re^-0.6 = 24) but jumps at Re = 800:
    24 * 800**-0.6 = 0.4348678, so 0.44 is 1.1802 per cent higher. t_s follows C_D."""
    eps = 1e-12
    cd = drag.stokes_drag_coefficient
    assert abs(cd(1 - eps) / cd(1.0) - 1) < 1e-10
    assert abs(cd(1 + eps) / cd(1.0) - 1) < 1e-10
    np.testing.assert_allclose(cd(800 * (1 - eps)), 0.4348678, rtol=1e-7)
    np.testing.assert_allclose(cd(800.0) / cd(800 * (1 - eps)) - 1, 0.011801752, rtol=1e-6)
    # the stopping time through the branches: Re set by delta_v at fixed size
    rho_g, c_s, lam, nu = _regime_gas()
    s = 50 * lam
    dv_for = lambda Re: Re * nu / (2 * s)  # noqa: E731
    t = drag.stokes_stopping_time(s, 2.6, rho_g, dv_for(np.array([1 - eps, 1 + eps])), nu)
    assert abs(t[1] / t[0] - 1) < 1e-10
    t = drag.stokes_stopping_time(s, 2.6, rho_g, dv_for(np.array([800 * (1 - eps), 800.0])), nu)
    np.testing.assert_allclose(t[0] / t[1] - 1, 0.011801752, rtol=1e-6)
    # Re < 1: independent of delta_v; Re > 800: t_s proportional to 1/delta_v
    lin = drag.stokes_stopping_time(s, 2.6, rho_g, dv_for(np.array([0.0, 1e-3, 0.5])), nu)
    np.testing.assert_allclose(lin, lin[0], rtol=1e-15)
    quad = drag.stokes_stopping_time(s, 2.6, rho_g, dv_for(np.array([1e3, 2e3])), nu)
    np.testing.assert_allclose(quad[0] / quad[1], 2.0, rtol=1e-14)


def test_dust_fraction_and_ratio_conversions():
    """eps = rho_d/(rho_d+rho_g) (2.7), mu = rho_d/rho_g (2.8): eps = mu/(1+mu), mu = eps/(1-eps)."""
    rho_d = np.array([0.0, 0.01, 1.0, 3.0])
    rho_g = np.array([1.0, 1.0, 1.0, 0.5])
    mu = drag.dust_to_gas_ratio(rho_d, rho_g)
    eps = drag.dust_fraction(rho_d, rho_g)
    np.testing.assert_allclose(mu, [0.0, 0.01, 1.0, 6.0], rtol=1e-15)
    np.testing.assert_allclose(eps, [0.0, 0.01 / 1.01, 0.5, 6.0 / 7.0], rtol=1e-15)
    np.testing.assert_allclose(drag.ratio_to_fraction(mu), eps, rtol=1e-15)
    np.testing.assert_allclose(drag.fraction_to_ratio(eps), mu, rtol=1e-14)
