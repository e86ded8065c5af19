"""The growth box follows Vericel et al. (2021) to 5e-4 for growth and fragmentation; sizes
never go negative near the minimum size; advection of sizes with the exchanged dust (eqs. 3.11-3.14)."""

import numpy as np
import pytest

from dustygas.physics import drag
from dustygas.problems.growth_box import stokes_numbers
from dustygas.sph.dust.grain_size import GrainGrowth, advect_sizes

from ._run import advance_to, build


def _worst_error(name, *overrides):
    prob, cfg, eng = build(name, *overrides)
    worst = [0.0]

    def check(e):
        st = stokes_numbers(e, cfg.growth.omega)
        worst[0] = max(worst[0], float(np.max(np.abs(st / prob.exact(cfg, e.t) - 1))))

    advance_to(eng, cfg.run.tlim, check)
    return worst[0], prob, cfg, eng


def test_growth_matches_vericel_solution():
    """Pure growth from St = 0.01 (rho_d = rho_g, alpha = 0.01, Ro = 3, tau = 10.96/Omega) to t = 50 (St = 2.02):
    the Stokes number of every particle stays within 5e-4 of the analytic one at every step (measured
    5.7e-5; Phantom's test 1.0e-4 - 3.7e-4)."""
    worst, prob, cfg, eng = _worst_error("growth-box")
    assert prob.growth_time(cfg) == pytest.approx(10.956376, rel=1e-6)
    assert stokes_numbers(eng, 1.0)[0] == pytest.approx(2.0236, rel=1e-4)
    assert worst < 5e-4, worst


def test_fragmentation_matches_vericel_solution():
    """Pure fragmentation (V_frag = 0) from St = 1 to t = 25 (St = 0.036; the grains would vanish at
    t = 29.2): within 5e-4 at every step (measured 2.5e-4)."""
    worst, *_ = _worst_error("growth-box-fragmentation")
    assert worst < 5e-4, worst


@pytest.mark.parametrize("c_size", [0.02, 0.5])
def test_fragmenting_grains_stop_at_the_minimum_size(c_size):
    """Fragmenting past the time at which the analytic size reaches zero (t = 40 > 29.2), even with a
    coarse size criterion (c_size = 0.5), no size falls below the minimum (3e-11, 1e-11 of the initial
    size) and every grain ends at it. Without the guard one explicit step of 0.5 from a size of 1e-10
    in this box would give a negative size (rate -1.3e-6), and a grain at the minimum has rate 0."""
    prob, cfg, eng = build("growth-box-fragmentation", "run.tlim=40", f"growth.c_size={c_size}",
                           "growth.min_size=3e-11")
    smallest = [np.inf]
    advance_to(eng, 40.0, lambda e: smallest.__setitem__(0, min(smallest[0], e.particles.extra["grain_size"].min())))
    assert smallest[0] >= 3e-11
    assert np.all(eng.particles.extra["grain_size"] == 3e-11)
    unguarded = GrainGrowth(alpha=0.01, v_frag=0.0, min_size=1e-30)
    guarded = GrainGrowth(alpha=0.01, v_frag=0.0, min_size=3e-11)
    s = np.array([1e-10, 3e-11])
    ts = drag.epstein_stopping_time(s, 1.0, 1.0, 1.0, rho_d=1.0)
    rate = unguarded.rate(s, np.ones(2), ts, np.ones(2))
    assert s[0] + 0.5 * rate[0] < 0.0
    assert guarded.rate(s, np.ones(2), ts, np.ones(2))[1] == 0.0


def test_advected_size_is_the_dust_weighted_mean():
    """Corrected eq. 3.14: keeps (eps - dt out) of size s_a and receives dt*in of the senders' sizes --
    hand-computed values; a particle giving away more than it holds keeps none of its own size;
    sizes stay between the smallest and largest involved; no exchange leaves sizes unchanged."""
    s = advect_sizes(np.array([1.0, 2.0, 5.0]), np.array([0.1, 0.01, 0.2]), np.array([0.2, 0.0, 0.0]),
                     np.array([0.6, 0.0, 0.0]), np.array([0.05, 0.04, 0.0]), dt=0.5)
    np.testing.assert_allclose(s, [(0.075 * 1.0 + 0.3) / 0.175, 2.0, 5.0], rtol=1e-15)
    s = advect_sizes(np.array([1.0]), np.array([0.01]), np.array([0.1]), np.array([0.1 * 4.0]), np.array([1.0]),
                     dt=0.5)
    assert s[0] == pytest.approx(4.0, rel=1e-15)  # retained dust 0.01 - 0.5 < 0: only the received size
    rng = np.random.default_rng(3)
    size, eps = rng.uniform(1, 2, 1000), rng.uniform(0, 0.1, 1000)
    inflow, out = rng.uniform(0, 1, 1000), rng.uniform(0, 1, 1000)
    sender = rng.uniform(0.5, 3, 1000)
    new = advect_sizes(size, eps, inflow, inflow * sender, out, dt=0.3)
    assert np.all(new >= np.minimum(size, sender) - 1e-15) and np.all(new <= np.maximum(size, sender) + 1e-15)


def test_sizes_advected_in_settling_column():
    """Grain sizes carried by the upwind exchange in the settling column (initial size growing with
    height, s = s0 (1 + |z|/H)): dust falling from above brings larger grains, so sizes grow below
    (by up to 15 % of s0 in 1/Omega) and stay within the initial range. The dust-mass-weighted mean
    size is conserved to first order in the time step only -- each half kick mixes with the sizes of
    the last evaluation (eq. 3.14 is a forward-Euler form) -- measured drift 1.2e-4 over 1/Omega, bound
    5e-4 (module docstring of dustygas.sph.dust.grain_size)."""
    prob, cfg, eng = build("dust-settle", "problem.particles=200")
    from dustygas.sph.dust.setup import dust_module

    mod = dust_module(eng)
    base = cfg.dust.grain_size
    z0 = eng.particles.pos[:, 0].copy()
    s0 = base * (1 + np.abs(z0))
    eng.particles.extra["grain_size"][:] = s0
    pid0 = eng.particles.pid.copy()
    eng.update_derivatives()

    def mean_size(e):
        w = e.particles.mass * mod.dust_fractions(e)
        return float(np.sum(w * e.particles.extra["grain_size"]) / np.sum(w))

    m0 = mean_size(eng)
    advance_to(eng, 1.0)
    s = eng.particles.extra["grain_size"]
    before = s0[np.argsort(pid0)][eng.particles.pid]
    assert s.min() >= s0.min() * (1 - 1e-12) and s.max() <= s0.max() * (1 + 1e-12)
    assert np.all(s >= before * (1 - 1e-12)) and 0.05 < np.max(s / before - 1) < 0.3
    assert abs(mean_size(eng) / m0 - 1) < 5e-4
