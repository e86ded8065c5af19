"""Steady drift (NSH, thesis eq. 4.8) and the dusty box (Laibe & Price 2011) of the particle-gas engine.

NSH: uniform gas and particle lattices in the NSH equilibrium of
:func:`dustygas.physics.nsh_velocities_multi`, ten orbits in a shear-periodic 2D x-z box with
the full azimuthal velocity stored (particles crossing the radial boundary change v_y by
q Ω L_x). The equilibrium is an exact fixed point of the discrete scheme, so what is left is
round-off accumulated over 12,600 steps: measured at most 3.8e-13 relative on every mean
velocity (gas and each species, x and y; 1.6e-15 with the exponential drag integrator);
tolerance 2e-12.

Dusty box: the relative velocity of uniform gas and dust decays as exp(-t/t_s) with the
mixture stopping time; the scheme is second order in the step, and within Phantom's tolerance
(|v_d| error < 1e-5) with a step of 1/200 of the particles' stopping time.
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


@pytest.mark.parametrize("taus, mu, extra", [
    ([0.1], [1.0], []),
    ([1.0], [0.2], []),
    ([0.1, 1.0], [0.5, 0.5], []),
    ([1.0], [0.2], ["problem.orbital_advection=true", "problem.pressure_frame=particles",
                    "particles.integrator=exponential"]),
])
def test_nsh_drift_holds_for_ten_orbits(taus, mu, extra):
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
    assert max(abs(e) for e in errors) < 2e-12, errors
    # particles did cross the radial boundary (|V_x| t > L_x) for the fast drifters
    if max(taus) >= 1.0:
        assert abs(eq.dust_vx.min()) * 0.05 * cfg.run.tlim > cfg.grid.lx


def dustybox_error(integrator: str, drag_cfl: float, tlim: float = 2.0) -> tuple[float, int]:
    prob = get_problem("dustybox-grid")
    cfg = prob.config(overrides=[f"particles.integrator={integrator}", f"particles.drag_cfl={drag_cfl}",
                                 f"run.tlim={tlim}"])
    eng = prob.build(cfg)
    p = cfg.problem
    ts = p.rho_g * p.rho_d / (p.K * (p.rho_g + p.rho_d))  # the mixture stopping time of constant K
    err = 0.0
    while eng.t < tlim * (1 - 1e-14):
        eng.advance(min(eng.timestep(), tlim - eng.t))
        h = eng.history()
        vg, vd = dusty_box(eng.t, rho_gas=p.rho_g, rho_dust=p.rho_d, v_gas0=p.v_g0, v_dust0=p.v_d0,
                           stopping_time=ts)
        err = max(err, abs(h["gas_vx"] - vg), abs(h["dust_vx"] - vd))
        assert h["total_momentum_x"] == pytest.approx(p.rho_g * p.v_g0 + p.rho_d * p.v_d0, rel=1e-13)
    return err, eng.cycle


@pytest.mark.parametrize("integrator", ["semi-implicit", "exponential"])
def test_dustybox_second_order_and_phantom_tolerance(integrator):
    # particle stopping time rho_d/K = 2.857, mixture t_s = 1.429; steps of t_p/100, t_p/200, t_p/400
    errors = [dustybox_error(integrator, f)[0] for f in (0.01, 0.005, 0.0025)]
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert np.all(orders > 1.9), (errors, orders)
    assert errors[1] < 1e-5, errors  # Phantom's unit test tolerance on |v_d|; measured 3.1e-6 / 3.5e-6
    assert mixture_stopping_time(0.35, 1.0, 1.0) == pytest.approx(1 / 0.7, rel=1e-15)
