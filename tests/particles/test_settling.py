"""A single particle settling through gas at rest: the damped oscillator of thesis eq. 4.18.

``z'' = -z'/t_s - Ω² z``: the engine integrates vertical gravity and drag exactly over each
step (:func:`dustygas.particles.drag.oscillator_step`), so the particle's height follows the
exact solution (:func:`dustygas.physics.settling.settling_trajectory`) to 1e-6 of its initial
height over five settling times at the Courant step, for τ_s = 0.01 (overdamped), 1 and 100
(underdamped; 160 oscillations). Measured: ≤ 3e-13.

The settling time measured from the run -- the e-folding time of ``z`` (τ_s = 0.01) or of the
peaks of ``|z|`` (τ_s = 1, 100; each peak located by a parabola through its three samples) -- matches the exact damping time
of the oscillator to 1e-3, and thesis eq. 4.18, ``t_settle = (2τ_s² + 1)/(τ_s Ω)``, to 1e-3
where that formula is meant (its two limits τ_s ≪ 1 and ≫ 1; at τ_s = 1 the oscillator damps
in 2 Ω⁻¹ where eq. 4.18 estimates 3).
"""

import numpy as np
import pytest

from dustygas.grid import GridEngine, Mesh
from dustygas.particles import ParticleGridEngine, ParticleStore, VerticalGravity
from dustygas.physics.settling import damping_time, oscillator_rates, settling_time, settling_trajectory


def settle(taus: float, z0: float = 0.3):
    gas = GridEngine(Mesh((1, 1, 8), (1.0, 1.0, 1.0)), cs=1.0, cfl=0.4)
    gas.set_primitive(1.0)
    store = ParticleStore.create(np.array([[0.0], [0.0], [z0]]), np.zeros((3, 1)))
    eng = ParticleGridEngine(gas, store, [taus], feedback=False, particle_terms=[VerticalGravity(1.0)])
    t_end = 5.0 * float(settling_time(taus))
    ts, zs, vs = [0.0], [z0], [0.0]
    while eng.t < t_end * (1 - 1e-14):
        dt = eng.timestep()
        assert dt == pytest.approx(0.05)  # the gas's Courant step: 0.4 dz / c_s
        eng.advance(min(dt, t_end - eng.t))
        ts.append(eng.t)
        zs.append(float(eng.particles.pos[2, 0]))
        vs.append(float(eng.particles.vel[2, 0]))
    return np.array(ts), np.array(zs), np.array(vs)


@pytest.mark.parametrize("taus", [0.01, 1.0, 100.0])
def test_single_particle_follows_the_damped_oscillator(taus):
    z0 = 0.3
    t, z, _ = settle(taus, z0)
    assert np.abs(z - settling_trajectory(t, z0, 0.0, taus)).max() < 1e-6 * z0
    lam = oscillator_rates(taus)[0]
    if lam.imag == 0.0:  # overdamped: z decays on the slow rate once the fast one is gone
        late = t > 0.5 * t[-1]
        measured = -1.0 / np.polyfit(t[late], np.log(z[late]), 1)[0]
    else:
        a = np.abs(z)
        peaks = np.flatnonzero((a[1:-1] > a[:-2]) & (a[1:-1] >= a[2:])) + 1
        dt = t[1] - t[0]
        num = a[peaks + 1] - a[peaks - 1]
        den = 2.0 * (a[peaks + 1] - 2 * a[peaks] + a[peaks - 1])
        tp = t[peaks] - dt * num / den
        ap = a[peaks] - 0.25 * num**2 / den
        assert len(peaks) >= 4
        measured = -1.0 / np.polyfit(tp, np.log(ap), 1)[0]
    assert measured == pytest.approx(damping_time(taus), rel=1e-3)
    if taus != 1.0:
        assert measured == pytest.approx(float(settling_time(taus)), rel=1e-3)
    else:
        assert damping_time(taus) == pytest.approx(2.0, rel=1e-12) and float(settling_time(taus)) == 3.0
