"""Steady drift (NSH, thesis eq. 4.8) and the dusty box (Laibe & Price 2011) of the particle-gas engine.

NSH: uniform gas and particle lattices in the NSH equilibrium of
:func:`dustygas.physics.nsh_velocities_multi`, ten orbits (about 12,600 steps) in a
shear-periodic 2D x-z box of 8², with the full azimuthal velocity stored (particles crossing
the radial boundary change v_y by q Ω L_x) or under orbital advection with the pressure gradient
on the particles. The equilibrium is an exact fixed point of the discrete scheme (the drag is
solved in the velocities relative to the shear, and the first predictor has the drag at t^0),
so what is left is round-off: measured (largest relative error of the gas's and every species'
mean v_x, v_y, 2026-12-02) 2.3e-14 (τ_s = 0.1, μ = 1), 2.1e-14 (τ_s = 1, μ = 0.2), 4.8e-14
(two species), 9.0e-15 (orbital advection, particle pressure frame); tolerances 10× those.
(Without the first step's drag the mixture starts an epicycle of relative amplitude 1e-5 ..
1e-4; with v_y integrated in the full velocity, held gas velocity and forces, the drift is off
by 3e-6 (τ_s = 0.1) .. 4e-5 (two species) after one orbit.)

Dusty box: the relative velocity of uniform gas and dust decays as exp(-t/t_s) with the
mixture stopping time;
the local drag problem of every cell is solved exactly, so the decay is exact at any step: at
the Courant step for Phantom's unit test (K = 0.35), and for stiff heavy dust (t_s = 1e-3,
ε = 100; issue acceptance 3) where the step is hundreds of stopping times.
"""

import math

import numpy as np
import pytest

from dustygas.physics import nsh_velocities_multi
from dustygas.physics.drag import mixture_stopping_time
from dustygas.physics.exact import dusty_box
from dustygas.problems import get_problem


def run_to_end(eng, tlim):
    while eng.t < tlim * (1 - 1e-14):
        eng.advance(min(eng.timestep(), tlim - eng.t))
    return eng


@pytest.mark.parametrize("taus, mu, extra, tol", [
    ([0.1], [1.0], [], 2e-13),
    ([1.0], [0.2], [], 2e-13),
    ([0.1, 1.0], [0.5, 0.5], [], 5e-13),
    ([1.0], [0.2], ["problem.orbital_advection=true", "problem.pressure_frame=particles",
                    "particles.kernel=cic"], 1e-13),
])
def test_nsh_drift_holds_for_ten_orbits(taus, mu, extra, tol):
    prob = get_problem("nsh")
    cfg = prob.config(overrides=[f"problem.taus={taus}", f"problem.mu={mu}", "grid.nx=8", "grid.nz=8"] + extra)
    assert cfg.run.tlim == pytest.approx(20 * math.pi)
    eng = run_to_end(prob.build(cfg), cfg.run.tlim)
    h = eng.history()
    eq = nsh_velocities_multi(np.array(taus), np.array(mu))
    boost = 1.0 if "problem.pressure_frame=particles" in extra else 0.0
    errors = [h["gas_vx"] / eq.gas_vx - 1, h["gas_vy"] / (eq.gas_vy + boost) - 1]
    for s in range(len(taus)):
        errors += [h[f"species_{s}_vx"] / eq.dust_vx[s] - 1, h[f"species_{s}_vy"] / (eq.dust_vy[s] + boost) - 1]
    assert max(abs(e) for e in errors) < tol, errors
    # particles did cross the radial boundary (|V_x| t > L_x) for the fast drifters
    if max(taus) >= 1.0:
        assert abs(eq.dust_vx.min()) * 0.05 * cfg.run.tlim > cfg.grid.lx


def dustybox_run(sets: list[str], tlim: float):
    prob = get_problem("dustybox-grid")
    cfg = prob.config(overrides=sets + [f"run.tlim={tlim}"])
    eng = prob.build(cfg)
    p = cfg.problem
    volume = float(np.prod(eng.gas.mesh.size))
    rows = []
    while eng.t < tlim * (1 - 1e-14):
        courant = eng.gas.timestep()
        dt = eng.timestep()
        eng.advance(min(dt, tlim - eng.t))
        h = eng.history()
        rows.append((eng.t, h["gas_vx"], h["dust_vx"], dt / courant))
        assert h["total_momentum_x"] == pytest.approx((p.rho_g * p.v_g0 + p.rho_d * p.v_d0) * volume, rel=1e-13)
    return np.array(rows), p


def test_dustybox_exact_at_the_courant_step():
    """Phantom's unit test (rho_g = rho_d = 1, K = 0.35): every step is the Courant step and the
    velocities are exact to 1e-13 (measured 2e-16)."""
    rows, p = dustybox_run([], 2.0)
    assert np.all(rows[:, 3] == 1.0)
    vg, vd = dusty_box(rows[:, 0], rho_gas=p.rho_g, rho_dust=p.rho_d, v_gas0=p.v_g0, v_dust0=p.v_d0,
                       stopping_time=mixture_stopping_time(p.K, p.rho_g, p.rho_d))
    assert np.abs(rows[:, 1] - vg).max() < 1e-13 and np.abs(rows[:, 2] - vd).max() < 1e-13
    ts = mixture_stopping_time(0.35, 1.0, 1.0)
    assert ts == pytest.approx(1 / 0.7)


@pytest.mark.parametrize("box", [1.0, 1e-3])
def test_stiff_heavy_dust_runs_at_the_courant_step_and_decays_at_the_exact_rate(box):
    """t_s = 1e-3, ε = 100 (K = ρ_d/t_s = 1e5): the step is the gas's Courant step (not limited by
    the drag), the velocities follow the exact solution at every step, and the relative velocity
    decays per step by exactly exp(-(1+ε) h/t_s): in a unit box h(1+ε)/t_s ≈ 2.5e3 (the decay
    is complete to round-off after one step); in a box of 1e-3 h(1+ε)/t_s ≈ 2.5, and the rate
    is measured to 1e-6 relative while the relative velocity is above 1e-6 of its initial
    value (measured 1e-9: the round-off of the velocity difference)."""
    sets = ["problem.rho_d=100", "problem.K=1e5", f"grid.lx={box}", f"grid.lz={box}"]
    rows, p = dustybox_run(sets, 0.2 if box == 1.0 else 4e-4)
    assert np.all(rows[:, 3] == 1.0) and len(rows) > 4
    vg, vd = dusty_box(rows[:, 0], rho_gas=p.rho_g, rho_dust=p.rho_d, v_gas0=p.v_g0, v_dust0=p.v_d0,
                       stopping_time=mixture_stopping_time(p.K, p.rho_g, p.rho_d))
    dv0 = p.v_d0 - p.v_g0
    assert np.abs(rows[:, 1] - vg).max() < 1e-13 * dv0 and np.abs(rows[:, 2] - vd).max() < 1e-13 * dv0
    if box < 1.0:
        dv = rows[:, 2] - rows[:, 1]
        t = np.r_[0.0, rows[:, 0]]
        with np.errstate(invalid="ignore", divide="ignore"):  # round-off differences may change sign
            rate = -np.log(dv / np.r_[dv0, dv[:-1]]) / np.diff(t)
        ts = mixture_stopping_time(p.K, p.rho_g, p.rho_d)
        measurable = dv > 1e-6 * dv0  # further down the differences of O(1) velocities are round-off
        assert measurable.sum() >= 3
        np.testing.assert_allclose(rate[measurable], 1.0 / ts, rtol=1e-6)


@pytest.mark.parametrize("frame", ["gas", "dust"])
def test_settling_drift_is_a_fixed_point_in_either_frame(frame):
    """si-settling at τ_s = 0.001, μ = 0.1 (thesis Fig 4.6's smallest grain) with no perturbation
    (amplitude 1e-300): the gas and the dust keep their velocities — the NSH drift (thesis
    eq. 4.8), the vertical drift v̄_z = -c_s τ_s/(2τ_s² + 1) = -1e-3 c_s of eq. 4.19, and in the
    dust frame the boost W = (-V_x, -v̄_z) held by the (2 - q) Ω W_x ŷ force (without that force
    the gas and dust v_y would drift by 0.5 W_x t = 2.5e-6 c_s over these 200 steps) — to 1e-13 c_s."""
    from dustygas.physics import nsh_velocities
    from dustygas.preflight import build_engine

    prob = get_problem("si-settling")
    cfg = prob.config([], ["problem.taus=0.001", "problem.mu=0.1", "problem.k=59.7", "problem.amplitude=1e-300",
                           f"problem.frame={frame}", "grid.nx=8", "grid.nz=8"], None)
    eng = build_engine(prob, cfg)
    eq = nsh_velocities(0.001, 0.1)
    Pi, vz = 0.05, -0.001 / (2e-6 + 1)
    wx, wz = (-float(eq.dust_vx) * Pi, -vz) if frame == "dust" else (0.0, 0.0)
    gas_expect = np.array([float(eq.gas_vx) * Pi + wx, float(eq.gas_vy) * Pi, wz])
    dust_expect = np.array([float(eq.dust_vx) * Pi + wx, float(eq.dust_vy) * Pi, vz + wz])
    xc = eng.gas.mesh.centers(0)[None, None, :]
    for _ in range(200):
        eng.advance(eng.timestep())
    rho, ux, uy, uz = eng.gas.primitive()
    gas = np.array([ux, uy + 1.5 * xc, uz])
    dust = eng.particles.vel[:, :eng.particles.n]
    assert np.abs(gas - gas_expect[:, None, None, None]).max() < 1e-13
    assert np.abs(dust - dust_expect[:, None]).max() < 1e-13
    assert np.abs(rho - 1.0).max() < 1e-13
