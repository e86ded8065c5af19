"""Conservation of gas + particles (thesis eq. 4.25): momentum and mass.

Random gas (density and velocity) and randomly placed particles of two species (one with a
fixed stopping time, one with Epstein drag) exchange momentum through drag. The gas fluxes
conserve mass and momentum to round-off, and the gas receives exactly minus the drag impulse
of the particles with weights that sum to one inside the domain, so

* without external forces the total momentum changes only by round-off (1e-12 relative per
  unit time, relative to ``Σ|ρu|V + Σ|mv|``; measured ≤ 2e-16);
* with forces (vertical gravity and a constant acceleration on the particles, a constant
  acceleration on the gas) it changes by exactly the impulse of those terms, which the
  history integrates (1e-12 relative; measured 1e-16);
* with periodic z the total mass is constant to 1e-13 relative; with outflow z the mass that
  left (gas and particles) equals the mass recorded as lost through the two faces to 1e-12:
  the particles that crossed them, and the time integral of the gas's face mass fluxes.
"""

import numpy as np
import pytest

from dustygas.grid import GridEngine, Mesh
from dustygas.particles import (ConstantAcceleration, GasConstantAcceleration, ParticleGridEngine, ParticleStore,
                                VerticalGravity)


def random_box(kernel: str, shape=(16, 1, 12), seed=1, terms=None, gas_terms=(), z_kind="periodic",
               particle_z="periodic", spread=0.3, x_kind="periodic", particle_x="periodic") -> ParticleGridEngine:
    rng = np.random.default_rng(seed)
    mesh = Mesh(shape, (1.0, 1.0, 0.75))
    gas = GridEngine(mesh, cs=1.0, reconstruction="ppm", riemann="hllc", cfl=0.4 if mesh.ndim < 3 else 0.3,
                     boundaries=(x_kind, "periodic", z_kind))
    sh = tuple(reversed(shape))
    gas.set_primitive(1 + 0.3 * rng.random(sh), 0.2 + 0.1 * rng.standard_normal(sh), 0.1 * rng.standard_normal(sh),
                      -0.1 + 0.1 * rng.standard_normal(sh))
    n = 4 * mesh.ncells
    pos = np.zeros((3, n))
    for a, (lo, length, m) in enumerate(zip(mesh.lower, mesh.size, shape)):
        if m > 1:
            pos[a] = lo + length * rng.random(n)
    vel = spread * rng.standard_normal((3, n))
    species = rng.integers(0, 2, n)
    mass = 1.5 * mesh.cell_volume / 4 * rng.uniform(0.5, 1.5, n)
    store = ParticleStore.create(pos, vel, species, mass)
    return ParticleGridEngine(gas, store, [0.05, 0.2], drag_law=["fixed", "epstein"], kernel=kernel,
                              particle_terms=terms, gas_terms=gas_terms, boundaries=(particle_x, "periodic", particle_z))


def scale(eng) -> float:
    rho, vx, vy, vz = eng.gas.primitive()
    return float(np.sum(rho * (np.abs(vx) + np.abs(vy) + np.abs(vz))) * eng.gas.mesh.cell_volume
                 + np.sum(eng.particles.mass * np.abs(eng.particles.vel).sum(axis=0)))


def momentum(h) -> np.ndarray:
    return np.array([h[f"total_momentum_{a}"] for a in "xyz"])


def run(eng, t_end):
    while eng.t < t_end * (1 - 1e-14):
        eng.advance(min(eng.timestep(), t_end - eng.t))
    return eng


@pytest.mark.parametrize("kernel", ["tsc", "cic", "ngp", "tsc-c"])
def test_total_momentum_is_conserved_to_round_off(kernel):
    eng = random_box(kernel)
    p0, s0 = momentum(eng.history()), scale(eng)
    part0 = eng.particle_momentum().copy()
    run(eng, 1.0)
    drift = np.abs(momentum(eng.history()) - p0).max() / s0 / eng.t
    assert drift < 1e-12, drift
    # and the drag did exchange momentum: the particles' momentum changed by a good fraction
    assert eng.cycle > 40
    assert np.abs(eng.particle_momentum() - part0).max() > 0.1 * np.abs(part0).max()


def test_momentum_changes_by_the_impulse_of_the_terms_in_3d():
    terms = [VerticalGravity(1.3), ConstantAcceleration(0.2, -0.1, 0.05)]
    gas_terms = [GasConstantAcceleration(-0.05, 0.1, 0.02)]
    eng = random_box("tsc", shape=(8, 8, 8), seed=5, terms=terms, gas_terms=gas_terms)
    h0 = eng.history()
    p0, s0 = momentum(h0), scale(eng)
    for _ in range(30):
        eng.advance(eng.timestep())
    h = eng.history()
    forced = np.array([h[f"particle_terms_impulse_{a}"] + h[f"gas_terms_impulse_{a}"] for a in "xyz"])
    assert np.abs(forced).max() > 1e-3 * s0  # the terms did act
    err = np.abs(momentum(h) - p0 - forced).max() / s0
    assert err < 1e-12, err


def test_mass_is_conserved_with_periodic_z_and_lost_mass_is_recorded_with_outflow():
    eng = random_box("tsc", shape=(8, 1, 8), seed=3)
    m0 = eng.history()
    total0 = m0["mass"] + m0["particle_mass"]
    run(eng, 0.5)
    h = eng.history()
    assert abs(h["mass"] + h["particle_mass"] - total0) < 1e-13 * total0
    # outflow in z for gas and particles; fast particles leave through both faces
    eng = random_box("tsc", shape=(8, 1, 8), seed=3, z_kind="outflow", particle_z="outflow", spread=1.5)
    h0 = eng.history()
    run(eng, 0.5)
    h = eng.history()
    lost = h["particle_mass_lost"]
    assert h["particle_mass_lost_z_lower"] > 0 and h["particle_mass_lost_z_upper"] > 0
    assert abs(h0["particle_mass"] - h["particle_mass"] - lost) < 1e-12 * h0["particle_mass"]
    assert lost == pytest.approx(h["particle_mass_lost_z_lower"] + h["particle_mass_lost_z_upper"], rel=1e-15)
    # the gas: what left through the two z faces is the time integral of their mass fluxes
    gas_lost = h["gas_mass_lost"]
    assert abs(h["gas_mass_lost_z_lower"]) > 1e-3 * h0["mass"] and abs(h["gas_mass_lost_z_upper"]) > 1e-3 * h0["mass"]
    assert abs(h0["mass"] - h["mass"] - gas_lost) < 1e-12 * h0["mass"]
    total0, total = h0["mass"] + h0["particle_mass"], h["mass"] + h["particle_mass"]
    assert abs(total0 - total - gas_lost - lost) < 1e-12 * total0
