"""Two-fluid drag: consistency with dustygas.physics, conservation laws of the pair forms, determinism,
restarts through the run loop."""

import numpy as np
import pytest

from _threads import assert_identical, results_at_threads

from dustygas import api
from dustygas.io.rundir import RunDirectory
from dustygas.physics import drag
from dustygas.sph import DUST, GAS, Box, EquationOfState, ParticleSet, SPHEngine, SPHOptions
from dustygas.sph.dust import DragLaw, TwoFluidDust, TwoFluidOptions
from dustygas.sph.dust.two_fluid_kernels import mc_limiter
from dustygas.sph.lattice import cubic_lattice


def test_drag_law_factors_are_the_physics_formulas():
    """k_a k_i + c/(rho_a + rho_i) times rho_a rho_i is the drag coefficient K of dustygas.physics for the
    three laws (Epstein: epstein_drag_coefficient; constant t_s: K = rho_g rho_d/(t_s rho)); the one-fluid
    stopping times are epstein_stopping_time(rho_d=...) and mixture_stopping_time (to 1e-15)."""
    rho_g, cs, rho_d, s = np.array([0.7, 2.0]), np.array([0.3, 1.1]), np.array([0.2, 0.05]), np.array([0.01, 0.4])
    for law, K in [(DragLaw("epstein", grain_size=1.0, grain_density=3.0, gamma=1.4),
                    drag.epstein_drag_coefficient(rho_g, rho_d, s, 3.0, cs, 1.4)),
                   (DragLaw("constant-K", K=0.35), np.full(2, 0.35)),
                   (DragLaw("constant-ts", ts=0.1), rho_g * rho_d / (0.1 * (rho_g + rho_d)))]:
        kg, kd, c = law.pair_factors(rho_g, cs, rho_d, s)
        np.testing.assert_allclose((kg * kd + c / (rho_g + rho_d)) * rho_g * rho_d, K, rtol=1e-15)
    rho, eps = rho_g + rho_d, rho_d / (rho_g + rho_d)
    law = DragLaw("epstein", grain_density=3.0, gamma=1.4)
    np.testing.assert_allclose(law.one_fluid_stopping_time(rho, eps, cs, s),
                               drag.epstein_stopping_time(s, 3.0, rho_g, cs, 1.4, rho_d=rho_d), rtol=1e-15)
    np.testing.assert_allclose(DragLaw("constant-K", K=2.0).one_fluid_stopping_time(rho, eps, cs),
                               drag.mixture_stopping_time(2.0, rho_g, rho_d), rtol=1e-15)


def test_mc_limiter():
    """Van Leer's monotonised central limiter: mean of equal-sign slopes capped at twice the smaller, 0
    for opposite signs, odd and symmetric."""
    assert mc_limiter(1.0, 3.0) == 2.0 and mc_limiter(1.0, 1.2) == pytest.approx(1.1)
    assert mc_limiter(0.1, 5.0) == pytest.approx(0.2) and mc_limiter(-1.0, 2.0) == 0.0
    assert mc_limiter(-1.0, -3.0) == -2.0 and mc_limiter(3.0, 1.0) == mc_limiter(1.0, 3.0)


def _cloud(form, recon="none", nx=8, seed=2):
    """A 3D periodic box of gas and dust particles on jittered, offset lattices with random velocities."""
    rng = np.random.default_rng(seed)
    n = nx**3
    lat = cubic_lattice((nx, nx, nx), (0.0,) * 3, (1.0,) * 3)
    pos = np.concatenate([lat, (lat + 0.5 / nx) % 1.0]) + rng.uniform(-0.3, 0.3, (2 * n, 3)) / nx
    vel = rng.normal(0.0, 0.3, (2 * n, 3))
    ptype = np.repeat([GAS, DUST], n)
    p = ParticleSet.create(pos % 1.0, vel, mass=1.0 / n, h=1.2 / nx, u=1.0, alpha=0.0, ptype=ptype)
    mod = TwoFluidDust(TwoFluidOptions(drag=DragLaw("constant-K", K=3.0), form=form, reconstruction=recon))
    eng = SPHEngine(p, Box.periodic_box(3, (0.0,) * 3, (1.0,) * 3), EquationOfState.adiabatic(5 / 3),
                    SPHOptions(kernel="cubic", alpha=0.0, switch="none", alpha_u=0.0), modules=(mod,))
    eng.update_derivatives()
    return eng


@pytest.mark.parametrize("recon", ["none", "mc"])
def test_projected_drag_conserves_momentum_and_energy(recon):
    """Projected drag (eq. 3.19) on a random periodic 3D cloud: sum m a_drag = 0 to 1e-13 of sum m |a_drag|,
    and the drag heating equals the kinetic energy the drag removes, sum m (a_drag . v) + sum m du/dt = 0,
    to 1e-13 (with and without reconstruction)."""
    eng = _cloud("projected", recon)
    p = eng.particles
    a = p.extra["drag_acc"]
    scale = float(np.sum(p.mass * np.linalg.norm(a, axis=1)))
    assert np.abs((p.mass[:, None] * a).sum(axis=0)).max() < 1e-13 * scale
    work = float(np.sum(p.mass * np.einsum("ij,ij->i", a, p.vel)))
    heat = float(np.sum(p.mass * p.extra["drag_heating"]))
    assert abs(work + heat) < 1e-13 * abs(heat)


def test_projected_drag_torque_free_nonprojected_not():
    """In an open 2D-like slab (no periodic images) the projected drag exerts no net torque
    (|sum m r x a| < 1e-13 of sum m |r||a|) while the non-projected drag of eq. 3.18 does (> 1e-3): the
    reason the thesis (and Laibe & Price 2012) use the projected form."""
    rng = np.random.default_rng(5)
    n = 200
    pos = rng.uniform(-0.5, 0.5, (2 * n, 3))
    vel = rng.normal(0.0, 0.3, (2 * n, 3))
    ptype = np.repeat([GAS, DUST], n)
    torques = {}
    for form in ("projected", "non-projected"):
        p = ParticleSet.create(pos, vel, mass=1.0 / n, h=0.25, u=1.0, alpha=0.0, ptype=ptype)
        mod = TwoFluidDust(TwoFluidOptions(drag=DragLaw("constant-K", K=3.0), form=form, reconstruction="none"))
        eng = SPHEngine(p, Box.open_box(3), EquationOfState.adiabatic(5 / 3),
                        SPHOptions(alpha=0.0, switch="none", alpha_u=0.0), modules=(mod,))
        eng.update_derivatives()
        a = eng.particles.extra["drag_acc"]
        r = eng.particles.pos
        m = eng.particles.mass[:, None]
        torque = np.abs((m * np.cross(r, a)).sum(axis=0)).max()
        torques[form] = torque / float(np.sum(m[:, 0] * np.linalg.norm(r, axis=1) * np.linalg.norm(a, axis=1)))
    assert torques["projected"] < 1e-13 and torques["non-projected"] > 1e-3, torques


def thread_case() -> dict:
    """Five steps of the random two-fluid cloud with reconstruction."""
    eng = _cloud("projected", "mc")
    for _ in range(5):
        eng.advance(eng.timestep())
    return {"pos": eng.particles.pos, "vel": eng.particles.vel, "u": eng.particles.u}


def test_results_independent_of_thread_count(tmp_path):
    """Every pair sum gathers per particle: one and two threads (each in its own interpreter) give
    bit-identical two-fluid states after 5 steps with reconstruction (random cloud)."""
    assert_identical(results_at_threads("dustysph.test_two_fluid:thread_case", tmp_path))


@pytest.mark.parametrize("problem, overrides", [
    ("dustywave", ["dust.integration=implicit", "problem.nx=32"]),
    ("dust-settle", ["problem.particles=100", "dust.exchange=arithmetic", "dust.clamp=true"]),
])
def test_restart_is_bit_identical(tmp_path, problem, overrides):
    """A run stopped by max_cycles and restarted from its checkpoint ends bit-identical to an
    uninterrupted run (module state -- implicit drag step, clamp counters -- is checkpointed)."""
    base = [*overrides, "run.tlim=1.0", "run.threads=1"]
    full = api.run(problem, tmp_path / "full", set=base)
    api.run(problem, tmp_path / "part", set=[*base, "run.max_cycles=7"])
    api.restart(tmp_path / "part", set=["run.max_cycles=0"])
    a, _ = RunDirectory(full.path).read_snapshot(-1)
    b, _ = RunDirectory(tmp_path / "part").read_snapshot(-1)
    for key in a:
        np.testing.assert_array_equal(a[key], b[key], err_msg=key)
    ha, _ = RunDirectory(full.path).read_history()
    hb, _ = RunDirectory(tmp_path / "part").read_history()
    for key in ("dust_mass", "clamp_events") if problem == "dust-settle" else ("dust_mass",):
        assert ha[key][-1] == hb[key][-1]
