"""Power-law disks, pressure support, viscous inflow and radial drift (thesis §3.2.2, §3.3.1)."""

import numpy as np
from scipy.integrate import quad
from scipy.optimize import minimize_scalar

from dustygas import units
from dustygas.physics import disk, nsh_velocities
from dustygas.physics.growth import drift_size, drift_size_midplane

ETA_FIG35 = 7.5e-3  # thesis Figure 3.5, eta of eq. 3.24
VRGAS_FIG35 = -3.75e-5  # v_r,gas / v_K of Figure 3.5


def _minus_vr(log_tau, v_r_gas):
    return float(-disk.radial_drift_velocity(10.0**log_tau, ETA_FIG35, 1.0, v_r_gas))


def test_drift_peaks_at_unit_stokes_number():
    """With v_r,gas = 0, -v_r = eta v_K tau/(1+tau^2) peaks at tau = 1 with eta v_K/2 exactly."""
    res = minimize_scalar(lambda x: -_minus_vr(x, 0.0), bounds=(-3, 3), method="bounded",
                          options={"xatol": 1e-8})
    assert abs(res.x) < 1e-3  # log10 tau_peak
    np.testing.assert_allclose(_minus_vr(0.0, 0.0), ETA_FIG35 / 2, rtol=1e-15)
    np.testing.assert_allclose(-res.fun, ETA_FIG35 / 2, rtol=1e-9)


def test_drift_peak_with_gas_inflow():
    """With a = -v_r,gas, b = eta: d/dtau[(a + b tau)/(1+tau^2)] = 0 gives b tau^2 + 2 a tau - b = 0,
    tau* = (sqrt(a^2+b^2) - a)/b = 0.99501 for Figure 3.5's numbers (log10 tau* = -0.00217)."""
    a, b = -VRGAS_FIG35, ETA_FIG35
    tau_star = (np.hypot(a, b) - a) / b
    res = minimize_scalar(lambda x: -_minus_vr(x, VRGAS_FIG35), bounds=(-3, 3), method="bounded",
                          options={"xatol": 1e-9})
    assert abs(res.x - np.log10(tau_star)) < 1e-6
    assert abs(np.log10(tau_star)) < 3e-3


def test_drift_limits():
    """tau << 1: v_r -> v_r,gas; tau >> 1: v_r -> -eta v_K / tau (thesis §3.3.1)."""
    v_K = 3e6
    small = disk.radial_drift_velocity(1e-10, ETA_FIG35, v_K, VRGAS_FIG35 * v_K)
    np.testing.assert_allclose(small, VRGAS_FIG35 * v_K, rtol=1e-6)
    # v_r tau/(-eta v_K) = 1 + (-v_r,gas/(eta v_K))/tau + O(tau^-2): 1 + 5e-3/tau here
    taus = np.array([1e10, 1e12])
    large = disk.radial_drift_velocity(taus, ETA_FIG35, v_K, VRGAS_FIG35 * v_K)
    np.testing.assert_allclose(large * taus / (-ETA_FIG35 * v_K), 1.0, rtol=1e-12)


def test_drift_equals_nsh_dust_velocity_at_zero_dust_loading():
    """eq. 3.23 with eta_3.24 = 2 eta_YJ is NSH's v_x = -2 tau/(1+tau^2) (eta_YJ v_K units), mu = 0."""
    taus = np.logspace(-4, 4, 41)
    np.testing.assert_allclose(disk.radial_drift_velocity(taus, 2.0), nsh_velocities(taus, 0.0).dust_vx,
                               rtol=1e-15, atol=0)


def _mmsn_like(p=1.0, q=0.5):
    return disk.PowerLawDisk(Sigma0=300.0, r0=units.au, p=p, T0=280.0, q=q, M_star=units.M_sun)


def test_pressure_exponent_from_profiles():
    """P = rho_mid c_s^2 of the disk object falls as r^-n with n = p + q/2 + 3/2."""
    for p, q in [(1.0, 0.5), (0.0, 0.5), (1.5, 0.75), (0.5, 1.0)]:
        d = _mmsn_like(p, q)
        r = np.array([3.0, 6.0]) * units.au
        P = d.midplane_density(r) * d.sound_speed(r) ** 2
        np.testing.assert_allclose(np.log(P[0] / P[1]) / np.log(2.0), p + q / 2 + 1.5, rtol=1e-12)
        assert d.pressure_exponent == p + q / 2 + 1.5


def test_gas_rotation_from_radial_force_balance():
    """v_theta^2 = v_K^2 + (r/rho) dP/dr (finite differences) equals v_K sqrt(1 - eta) (3.24-3.25);
    1 - v_theta/v_K = eta_YJ + eta_YJ^2/2 + O(eta^3) with eta_YJ = eta/2 (Nakagawa/YJ07 convention)."""
    d = _mmsn_like()
    r = 5.0 * units.au
    h = 1e-5 * r
    P = lambda x: d.midplane_density(x) * d.sound_speed(x) ** 2  # noqa: E731
    dPdr = (P(r + h) - P(r - h)) / (2 * h)
    v_K = d.v_kepler(r)
    v_theta = np.sqrt(v_K**2 + r / d.midplane_density(r) * dPdr)
    eta = d.eta(r)
    np.testing.assert_allclose(disk.gas_azimuthal_velocity(v_K, eta), v_theta, rtol=1e-10)
    eta_yj = disk.eta_nakagawa(d.pressure_exponent, d.sound_speed(r), v_K)
    np.testing.assert_allclose(eta_yj, eta / 2, rtol=1e-15)
    assert abs((1 - v_theta / v_K) - eta_yj - eta_yj**2 / 2) < 2 * eta_yj**3


def test_midplane_drift_size_consistent_with_general_definition():
    """s_drift = rho_g c_s/(rho_grain Omega) with rho_g = Sigma/(sqrt(2 pi) H), H = c_s/Omega,
    is Sigma/(sqrt(2 pi) rho_grain) at every radius and temperature (thesis 3.9 -> 3.10)."""
    for q in (0.0, 0.5, 1.0):
        d = _mmsn_like(1.0, q)
        r = np.geomspace(0.3, 300, 7) * units.au
        general = drift_size(d.midplane_density(r), d.sound_speed(r), d.omega(r), 2.6)
        np.testing.assert_allclose(general, drift_size_midplane(d.sigma(r), 2.6), rtol=1e-14)


def test_viscous_inflow_finite_difference_matches_power_law():
    """eq. 3.22 on a log grid of 4001 points vs -3 (beta - p + 1/2) nu / r, beta = 3/2 - q.
    p = 1, q = 1/2 is the steady accretion flow -3 nu/(2 r). Second-order differences (one-sided
    at the two end points): < 2e-6."""
    r = np.geomspace(1.0, 100.0, 4001) * units.au
    for p, q in [(1.0, 0.5), (0.0, 0.5), (1.5, 1.0)]:
        d = _mmsn_like(p, q)
        nu = disk.alpha_viscosity(1e-3, d.sound_speed(r), d.scale_height(r))
        numeric = disk.viscous_radial_velocity(r, d.sigma(r), nu)
        exact = disk.viscous_radial_velocity_power_law(r, nu, p, 1.5 - q)
        np.testing.assert_allclose(numeric, exact, rtol=2e-6)
    d = _mmsn_like(1.0, 0.5)
    nu = disk.alpha_viscosity(1e-3, d.sound_speed(r), d.scale_height(r))
    np.testing.assert_allclose(disk.viscous_radial_velocity_power_law(r, nu, 1.0, 1.0), -1.5 * nu / r, rtol=1e-15)


def test_surface_density_normalisation_gives_disk_mass():
    M, r_in, r_out, r0 = 0.01 * units.M_sun, 4 * units.au, 120 * units.au, units.au
    for p in (0.0, 1.0, 2.0):
        Sigma0 = disk.surface_density_normalisation(M, r_in, r_out, r0, p)
        mass, _ = quad(lambda r: 2 * np.pi * r * disk.surface_density(r, Sigma0, r0, p), r_in, r_out)
        np.testing.assert_allclose(mass, M, rtol=1e-10)


def test_kepler_and_sound_speed_at_one_au():
    """v_K(1 au, 1 M_sun) = 29.78 km/s; c_s(280 K, mu = 2.34) = sqrt(1.380649e-16 * 280 /
    (2.34 * 1.6737e-24)) cm/s = sqrt(9.8706e9) cm/s = 0.99351 km/s."""
    np.testing.assert_allclose(disk.keplerian_velocity(units.au, units.M_sun), 2.9785e6, rtol=1e-4)
    np.testing.assert_allclose(disk.isothermal_sound_speed(280.0), 0.99351e5, rtol=1e-5)
    np.testing.assert_allclose(disk.temperature_from_sound_speed(disk.isothermal_sound_speed(280.0)), 280.0, rtol=1e-14)
    d = disk.PowerLawDisk.from_aspect_ratio(1.0, units.au, 0.0, 0.05, 100 * units.au, 0.5, units.M_sun)
    r = 100 * units.au
    np.testing.assert_allclose(d.scale_height(r) / r, 0.05, rtol=1e-13)
    # code units: G = 1, Omega(1 au) = 1
    u = units.DISK_UNITS
    np.testing.assert_allclose(disk.keplerian_angular_velocity(1.0, 1.0, G=u.G), 1.0, rtol=1e-12)
    np.testing.assert_allclose(disk.keplerian_angular_velocity(units.au, units.M_sun) * u.time, 1.0, rtol=1e-12)
