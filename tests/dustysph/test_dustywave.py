"""The dustywave (Laibe & Price 2011) at strong (K = 1000) and weak (K = 1) drag converges to the exact solution
for one- and two-fluid dust, and the two-fluid run reports when h < c_s t_s is violated."""

import numpy as np
import pytest

from dustygas.physics.exact import dusty_wave, dusty_wave_matrix
from dustygas.problems.dustywave import velocity_errors

from ._run import advance_to, build


def _errors(nx, *overrides):
    prob, cfg, eng = build("dustywave", f"problem.nx={nx}", *overrides)
    advance_to(eng, cfg.run.tlim)
    e = velocity_errors(eng, cfg)
    return e["gas"], e["dust"], eng


def test_exact_solution_modes_are_numbers_md_roots():
    """The matrix of the exact solution has the eigenvalues -i omega of Laibe & Price (2011)'s dispersion relation for Phantom's wave
    (rho_g = rho_d = c_s = lambda = 1, K = 1000): omega = +-4.44289 - 0.0049348 i and -1999.99 i; the
    exact solution starts from the initial state (to 1e-15)."""
    lam = np.linalg.eigvals(dusty_wave_matrix(2 * np.pi, K=1000.0, cs=1.0, rho_gas=1.0, rho_dust=1.0))
    omega = np.sort_complex(1j * lam)
    np.testing.assert_allclose(omega.real[[0, 3]], [-4.44289, 4.44289], atol=1e-5)
    np.testing.assert_allclose(omega.imag[[0, 3]], [-0.0049348, -0.0049348], atol=1e-7)
    assert np.isclose(sorted(omega.imag)[0], -1999.99, atol=0.01)
    x = np.linspace(-0.5, 0.5, 7)
    rg, rd, vg, vd = dusty_wave(x, 0.0, amplitude=1e-4, K=1000.0)
    np.testing.assert_allclose(vg, 1e-4 * np.sin(2 * np.pi * (x + 0.5)), atol=1e-19)
    np.testing.assert_allclose(rd, 1 + 1e-4 * np.sin(2 * np.pi * (x + 0.5)), atol=1e-15)


@pytest.mark.parametrize("K, errs_expected", [(1000.0, (0.071, 0.013, 0.0024)), (1.0, (0.034, 0.0086, 0.0022))])
def test_two_fluid_converges(K, errs_expected):
    """1D, t = 0.5, MC-reconstructed projected drag, explicit steps (dt <= 0.9 t_s at K = 1000): the RMS
    velocity errors of gas and dust, in units of A c_s, at 32, 64, 128 particles per wavelength are below
    the stated bounds (measured K = 1000: 7.0 %, 1.25 %, 0.23 %; K = 1: gas 3.4 %, 0.85 %, 0.21 %, dust
    0.57 %, 0.15 %, 0.039 %) and fall by more than 3.5 at every doubling."""
    errs = np.array([_errors(nx, f"dust.K={K}")[:2] for nx in (32, 64, 128)])
    assert np.all(errs[:, 0] < errs_expected), errs
    assert np.all(errs[:-1] / errs[1:] > 3.5), errs


@pytest.mark.parametrize("K, model, gas_at_128, dust_at_128",
                         [(1000.0, "full", 0.0016, 0.0016), (1.0, "full", 0.0024, 0.0007),
                          (1000.0, "terminal-velocity", 0.0005, 0.0031)])
def test_one_fluid_converges(K, model, gas_at_128, dust_at_128):
    """1D one-fluid, t = 0.5: full equations at K = 1000 (errors 2.4 %, 0.61 %, 0.15 % at 32, 64, 128)
    and K = 1 (gas 3.5 %, 0.90 %, 0.23 %); terminal-velocity approximation at K = 1000 (gas 2.2 %, 0.48 %,
    0.043 %). Errors fall with resolution (gas by > 3.5 per doubling); the terminal-velocity dust
    error levels off at O(t_s omega) ~ 0.3 % (the approximation, 0.29 % at 128, not the discretisation)."""
    errs = np.array([_errors(nx, "dust.method=one-fluid", f"dust.model={model}", f"dust.K={K}")[:2]
                     for nx in (32, 64, 128)])
    assert errs[-1, 0] < gas_at_128 and errs[-1, 1] < dust_at_128, errs
    assert np.all(errs[:-1, 0] / errs[1:, 0] > 3.5), errs
    assert np.all(errs[:-1, 1] > errs[1:, 1]), errs


def test_resolution_criterion_reported():
    """Laibe & Price (2012): two-fluid drag over-damps the wave unless h < c_s t_s. At K = 1000 with 64
    particles per wavelength h = 31 c_s t_s: every gas particle is flagged (drag_unresolved_fraction = 1,
    drag_resolution = 31.3) and exactly one warning line is produced; without reconstruction the error
    is 39 % (> 30 %), with it 1.25 %. At K = 1 (h = 0.031 c_s t_s) nothing is flagged or logged."""
    e_none, _, eng = _errors(64, "dust.reconstruction=none")
    e_mc, _, eng_mc = _errors(64)
    assert e_none > 0.30 and e_mc < 0.013
    for engine in (eng, eng_mc):
        h = engine.history()
        assert h["drag_unresolved_fraction"] == 1.0 and 30 < h["drag_resolution"] < 33, h
        msgs = engine.messages()
        assert len(msgs) == 1 and "h > c_s t_s" in msgs[0], msgs
        assert engine.messages() == []  # each line is handed out once
    _, _, eng_weak = _errors(64, "dust.K=1.0")
    assert eng_weak.history()["drag_unresolved_fraction"] == 0.0 and eng_weak.messages() == []
