"""Exact Riemann solver against published values; the SPH Sod shock tube against it."""

import numpy as np
import pytest

from dustygas.physics.exact_riemann import RiemannSolution
from dustygas.problems.sph_sod import l1_errors

from ._run import advance_to, build


def test_exact_solver_toro_test1():
    """Toro (2009) Table 4.3, test 1 (Sod, gamma = 1.4): p* = 0.30313, u* = 0.92745,
    rho*_L = 0.42632, rho*_R = 0.26557 (to the 5 printed digits)."""
    s = RiemannSolution(1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 1.4)
    assert (round(s.p_star, 5), round(s.u_star, 5)) == (0.30313, 0.92745)
    assert (round(s.rho_star_left, 5), round(s.rho_star_right, 5)) == (0.42632, 0.26557)


def test_exact_solver_dustyshock_mixture():
    """Laibe & Price (2012), K -> infinity dusty shock as one gas, gamma = 5/3 (Toro 2009 exact solver):
    P* = 0.29395, u* = 0.59481, rho*_L = 0.95938, rho*_R = 0.45961, shock speed 1.30424."""
    s = RiemannSolution(2.0, 0.0, 1.0, 0.25, 0.0, 0.1, 5.0 / 3.0)
    got = [s.p_star, s.u_star, s.rho_star_left, s.rho_star_right, s.shock_speed_right]
    assert np.allclose(got, [0.29395, 0.59481, 0.95938, 0.45961, 1.30424], atol=5e-6)


def test_exact_solver_sampling_conserves_mass_and_momentum():
    """The sampled profile conserves mass and momentum across the waves: integral of rho and
    rho u over [-1, 1] at t = 0.2 equals the initial one to 1e-6 (fine midpoint quadrature)."""
    s = RiemannSolution(1.0, 0.0, 1.0, 0.125, 0.0, 0.1, 5.0 / 3.0)
    x = (np.arange(400000) + 0.5) / 200000 - 1.0
    rho, u, p = s(x / 0.2)
    dx = 2.0 / len(x)
    assert np.sum(rho) * dx == pytest.approx(1.0 + 0.125, abs=1e-6)
    # momentum changes by the pressure difference at the ends: (P_L - P_R) t
    assert np.sum(rho * u) * dx == pytest.approx((1.0 - 0.1) * 0.2, abs=1e-6)


@pytest.mark.parametrize("force,limit", [("price2012", 0.0055), ("gasoline2", 0.0055), ("gasoline2-wadsley", 0.0047)])
def test_sod_1d_l1_error(force, limit):
    """1D Sod, gamma = 5/3, 256 particles in -0.5 < x < 0 (Phantom's default resolution), cubic
    kernel, t = 0.2: mean |rho - rho_exact| over |x| < 0.5 is < 0.0055 (measured 0.0050 for both
    forms), velocity and pressure errors < 0.009 and < 0.006. (Phantom's 3D tube at 64 particles in
    -0.5 < x < 0: L1(rho) = 0.0075, ours in the same tube 0.0067 -- benchmarks/RESULTS.md.)"""
    extra = ["sph.force=gasoline2", "sph.gasoline2_f=wadsley"] if force == "gasoline2-wadsley" else [f"sph.force={force}"]
    prob, cfg, eng = build("sph-sod", "problem.nx=256", *extra)
    advance_to(eng, cfg.run.tlim)
    err = l1_errors(eng, prob.solution(cfg))
    assert err["rho"] < limit and err["vx"] < 0.009 and err["P"] < 0.006


def test_sod_1d_converges():
    """Halving the spacing (nx 128 -> 512) lowers the density L1 error by more than 2.5x (measured 2.8x)."""
    errs = []
    for nx in (128, 512):
        prob, cfg, eng = build("sph-sod", f"problem.nx={nx}")
        advance_to(eng, cfg.run.tlim)
        errs.append(l1_errors(eng, prob.solution(cfg))["rho"])
    assert errs[0] / errs[1] > 2.5


@pytest.mark.slow
def test_sod_3d_tube():
    """3D Sod in a close-packed tube (quintic kernel, 32 particles in -0.5 < x < 0, 8 rows across
    the low-density side): density L1 < 0.0135 (measured 0.0126; at 64 particles and Phantom's
    tube width 0.0067, against Phantom's 0.0075 -- benchmarks/RESULTS.md)."""
    prob, cfg, eng = build("sph-sod-3d", "problem.nx=32")
    advance_to(eng, cfg.run.tlim)
    assert l1_errors(eng, prob.solution(cfg))["rho"] < 0.0135


@pytest.mark.parametrize("switch", ["morris-monaghan", "cullen-dehnen"])
def test_viscosity_switches_on_the_shock(switch):
    """Both switches with alpha_min = 0: alpha peaks on the shock (within 0.05 of x = 0.40, the
    exact shock position at t = 0.2, measured peak 0.50 (MM) and 1.0 (CD)) and stays below 0.05
    in the undisturbed gas x < -0.6; the density L1 error stays < 0.0055."""
    prob, cfg, eng = build("sph-sod", "problem.nx=256", f"sph.switch={switch}", "sph.alpha_min=0.0")
    advance_to(eng, cfg.run.tlim)
    x, alpha = eng.particles.pos[:, 0], eng.particles.alpha
    shock = prob.solution(cfg).shock_speed_right * cfg.run.tlim
    central = np.abs(x) < 0.5
    peak = x[central][np.argmax(alpha[central])]
    assert abs(peak - shock) < 0.05 and alpha[central].max() > 0.45
    assert alpha[x < -0.6].max() < 0.05
    assert l1_errors(eng, prob.solution(cfg))["rho"] < 0.0055


@pytest.mark.slow
def test_sod_3d_matches_phantom_at_the_same_resolution():
    """Phantom's own shock-tube set-up (hexagonal-close-packed tube, 64 particles in
    -0.5 < x < 0, 24 x 24 rows across on the left, quintic kernel, gamma = 5/3, t = 0.2) run with
    Phantom v2026.0.1 on this machine gives L1(rho) = 0.00746, L1(v_x) = 0.01152, L1(P) = 0.00652
    (benchmarks/RESULTS.md). The same tube here must do at least as well (measured 0.00671, 0.00974,
    0.00585; 82,944 particles, about three minutes on one thread)."""
    prob, cfg, eng = build("sph-sod-3d", "problem.nx=64", "problem.layers=12")
    advance_to(eng, cfg.run.tlim)
    err = l1_errors(eng, prob.solution(cfg))
    assert err["rho"] < 0.00746 and err["vx"] < 0.01152 and err["P"] < 0.00652


@pytest.mark.parametrize("kernel,limit", [("quintic", 0.0047), ("wendland-c2", 0.0065), ("wendland-c4", 0.0056)])
def test_sod_1d_other_kernels(kernel, limit):
    """Every kernel runs the 1D Sod tube (nx = 256) to the exact solution: density L1 measured
    0.0044 (M6), 0.0060 (Wendland C2), 0.0052 (Wendland C4); limits ~8 % above."""
    prob, cfg, eng = build("sph-sod", "problem.nx=256", f"sph.kernel={kernel}")
    advance_to(eng, cfg.run.tlim)
    assert l1_errors(eng, prob.solution(cfg))["rho"] < limit
