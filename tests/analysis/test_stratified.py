"""The analyses of stratified particle runs on planted data with known answers.

* A surface density ``1 + 0.1 cos(k·x)`` with ``k = 2π (3/L_x, 2/L_y)`` puts the FFT peak in
  exactly that bin, at ``θ_k = arctan(k_y/k_x)``, with amplitude 0.05 (half the mode's).
* Cell densities at the quantiles of an exponential distribution (mean 1): the mass fraction
  above ``ρ`` is ``(1 + ρ) e^{-ρ}``, to 1e-3 (measured 2.5e-5 with 2e4 cells).
* A Gaussian layer of σ = 0.02 H at the quantiles: ``H_p`` to 1 % (measured 1e-4); the same
  through the si3d set-up and the engine's history (49,152 random particles: 0.3 %).
"""

import math

import numpy as np
import pytest
from scipy.special import ndtri

from dustygas.analysis.stratified import density_cdf, dominant_wavevector, fourier_power, scale_height, surface_density
from dustygas.problems import get_problem


def test_planted_mode_lands_in_its_fft_bin_at_its_angle():
    nx, ny, lx, ly = 32, 24, 0.2, 0.3
    x = (np.arange(nx) + 0.5) * lx / nx - lx / 2
    y = (np.arange(ny) + 0.5) * ly / ny - ly / 2
    kx, ky = 2 * np.pi * 3 / lx, 2 * np.pi * 2 / ly
    sigma = 1.0 + 0.1 * np.cos(kx * x[None, :] + ky * y[:, None] + 0.3)
    rho = np.repeat(sigma[None] / 0.3, 3, axis=0)  # three layers of dz = 0.1: Sigma back
    s = surface_density(rho, 0.1)
    np.testing.assert_allclose(s, sigma, rtol=1e-14)
    amp, kxs, kys = fourier_power(s, lx, ly)
    got = dominant_wavevector(amp, kxs, kys)
    assert got[0] == pytest.approx(kx, rel=1e-12) and got[1] == pytest.approx(ky, rel=1e-12)
    assert got[2] == pytest.approx(math.degrees(math.atan(ky / kx)), abs=1e-9)
    assert amp.max() == pytest.approx(0.05, rel=1e-12)
    # an axisymmetric mode (stripes along y) has theta_k = 0
    flat = 1.0 + 0.1 * np.cos(kx * x)[None, :] * np.ones((ny, 1))
    assert dominant_wavevector(*fourier_power(flat, lx, ly))[2] == 0.0


def test_density_cdf_of_a_known_distribution():
    n = 20000
    rho = -np.log(1.0 - (np.arange(n) + 0.5) / n)  # quantiles of the exponential distribution
    thresholds = np.array([0.1, 0.5, 1.0, 2.0, 4.0])
    _, frac = density_cdf(rho.reshape(20, 1000), thresholds)
    np.testing.assert_allclose(frac, (1 + thresholds) * np.exp(-thresholds), atol=1e-3)


def test_gaussian_layer_gives_its_scale_height():
    n = 20000
    z = 0.02 * ndtri((np.arange(n) + 0.5) / n)
    assert scale_height(z) == pytest.approx(0.02, rel=0.01)
    prob = get_problem("si3d")
    eng = prob.build(prob.config())
    h = eng.history()
    assert h["species_0_scale_height"] == pytest.approx(0.02, rel=0.01)
    assert h["species_0_mass"] == pytest.approx(0.03 * math.sqrt(2 * math.pi) * 0.2 * 0.2, rel=1e-12)


def _write(path, columns):
    names = list(columns)
    rows = np.column_stack([np.asarray(columns[k], dtype=float) for k in names])
    path.write_text("# planted\n" + ",".join(names) + "\n" + "\n".join(",".join(repr(float(v)) for v in r) for r in rows) + "\n")


def test_saturation_checks_on_planted_series(tmp_path):
    """The si3d figures' checks: the window is the last 10 orbits (5-15 of a 15-orbit run);
    filaments 12x the midplane mean pass and 8x fail; non-axisymmetric FFT peaks >= 4x shot noise in 3 of 5
    window snapshots pass and 2 of 5 (one at 3.9x) fail; a layer steady over orbits 10-20 of a 20-orbit run passes,
    one thinning by half fails, and the same thinning in a 15-orbit run is not judged."""
    from dustygas.reproduce.si3d_checks import fig1_10_checks, fig1_13_checks, fig4_10_checks, window_start

    assert (window_start(15.0), window_start(30.0), window_start(6.0)) == (5.0, 20.0, 2.0)
    t = np.linspace(0.0, 15.0, 151)
    early = t < 5.0  # outside the window: a spike there must not count
    for peak, passes in ((12.0, True), (8.0, False)):
        rho_max = np.where(early, 50.0, 2.0 + (peak - 2.0) * (t == 10.0))
        _write(tmp_path / "fig1_10.csv", {"t_orbits": t, "rho_p_max": rho_max, "rho_p_midplane": np.ones_like(t)})
        (check,) = fig1_10_checks(tmp_path)
        assert check.value == pytest.approx(peak, rel=1e-12) and check.passed is passes
    ts = np.array([0.0, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0])  # the window holds the last five
    for peak, passes in (([9, 9, 1, 5, 5, 5, 1], True), ([5, 5, 5, 1, 1, 3.9, 5], False)):
        _write(tmp_path / "fig4_10.csv", {"t_orbits": ts, "kx": np.full(7, 31.4), "ky": np.zeros(7),
                                          "theta_k": np.zeros(7), "sigma_max_over_mean": np.ones(7),
                                          "nonaxisymmetric_over_noise": np.array(peak, dtype=float)})
        (check,) = fig4_10_checks(tmp_path)
        assert check.value == pytest.approx(np.mean(np.array(peak[2:]) >= 4.0)) and check.passed is passes
    # the steady layer is judged over orbits 10-20 of a 20-orbit run
    t20 = np.linspace(0.0, 20.0, 201)
    steady = np.where(t20 < 10.0, 0.05, 0.01 * (1 + 0.1 * np.sin(3 * t20)))
    thinning = np.where(t20 < 15.0, 0.02, 0.01)
    for hp, passes in ((steady, True), (thinning, False)):
        _write(tmp_path / "fig1_13.csv", {"t_orbits": t20, "Hp_0": hp})
        (check,) = fig1_13_checks(tmp_path)
        assert check.judged and check.passed is passes
    assert check.value == pytest.approx(0.5, rel=1e-12)
    # a 15-orbit run (window from 5 orbits) is too short: not judged, neither passed nor failed
    _write(tmp_path / "fig1_13.csv", {"t_orbits": t, "Hp_0": np.where(t < 10.0, 0.02, 0.01)})
    (check,) = fig1_13_checks(tmp_path)
    assert not check.judged and not check.passed and check.value == pytest.approx(0.5, rel=1e-12)
    assert "not judged (the window starts at 5 orbits" in check.describe()
