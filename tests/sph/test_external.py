"""External forces on test particles: constant field, vertical disk gravity, point mass."""

import numpy as np
import pytest

from dustygas.sph import TEST, Box, EquationOfState, ExternalForces, ParticleSet, SPHEngine, SPHOptions

from dustygas.physics.timestep import drag_timestep

from ._run import advance_to, build


def _test_particles(pos, vel, external, dt):
    p = ParticleSet.create(pos, vel, mass=1.0, h=0.1, ptype=TEST)
    return SPHEngine(p, Box.open_box(3), EquationOfState.isothermal(1.0), SPHOptions(fixed_dt=dt), external)


def test_constant_field_is_integrated_exactly():
    """Leapfrog is exact for a constant acceleration: x = x0 + v0 t + g t^2/2 to 1e-13."""
    g = (0.3, -1.0, 0.5)
    eng = _test_particles(np.array([[0.0, 1.0, 2.0]]), np.array([[1.0, 0.0, -1.0]]), ExternalForces(field=g), 0.01)
    advance_to(eng, 1.0, 0.01)
    expect = np.array([0.0, 1.0, 2.0]) + np.array([1.0, 0.0, -1.0]) + 0.5 * np.array(g)
    assert np.max(np.abs(eng.particles.pos[0] - expect)) < 1e-13


def test_vertical_gravity_oscillation():
    """a_z = -Omega^2 z: after one period 2 pi/Omega the particle is back at z0 (to 1e-4 with
    Omega dt = 0.01, leapfrog phase error (Omega dt)^2/24 per radian), and the energy
    v^2/2 + Omega^2 z^2/2 stays within (Omega dt)^2/4 of its start."""
    omega = 2.0
    dt = 0.005
    eng = _test_particles(np.array([[0.0, 0.0, 0.1]]), np.zeros((1, 3)), ExternalForces(omega_z=omega), dt)
    e0 = eng.history()["total_energy"]
    advance_to(eng, 2 * np.pi / omega, dt)
    assert eng.particles.pos[0, 2] == pytest.approx(0.1, abs=1e-4)
    assert abs(eng.history()["total_energy"] / e0 - 1) < 0.25 * (omega * dt) ** 2


def test_softened_point_mass_circular_orbit():
    """Circular orbit in the Plummer-softened potential at r = 1, eps = 0.1: radius kept to 1e-5
    over one orbit (C_force = 0.05)."""
    eps = 0.1
    v = np.sqrt(1.0 / (1.0 + eps**2) ** 1.5)
    p = ParticleSet.create(np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, v, 0.0]]), mass=1.0, h=0.1, ptype=TEST)
    eng = SPHEngine(p, Box.open_box(3), EquationOfState.isothermal(1.0), SPHOptions(c_force=0.05),
                    ExternalForces(star_gm=1.0, softening=eps))
    advance_to(eng, 2 * np.pi / (v / 1.0))
    assert np.linalg.norm(eng.particles.pos[0]) == pytest.approx(1.0, abs=1e-5)


def test_extra_time_step_limits_are_honoured():
    """A registered limit (here the explicit-drag bound dt <= 0.9 t_s of thesis eq. 2.15 with
    t_s = 1e-3) caps the step; without it the Courant/acceleration step is larger."""
    prob, cfg, eng = build("sph-sod", "problem.nx=32")
    free = eng.timestep()
    eng.timestep_limits.append(lambda e: drag_timestep(np.full(len(e.particles), 1e-3), safety=0.9))
    assert free > 1e-3 and eng.timestep() == pytest.approx(0.9e-3, rel=1e-15)
