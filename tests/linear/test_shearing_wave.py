"""Non-axisymmetric shearing waves (scipy integration): limits and conservation laws."""

import math

import numpy as np
import pytest

from dustygas.linear import StreamingParams, fastest_mode
from dustygas.linear.shearing_wave import shearing_wave, swing_time


def test_ky_zero_recovers_axisymmetric_growth():
    """k_y = 0: the linA eigenmode grows as e^{st}, s = 0.4190091323 (consistent drag)."""
    w = shearing_wave(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30), (0.0, 3.0), n_out=31)
    rate = np.log(w.amplitude("drho_p_0")[1:]) / w.t[1:]
    assert np.max(np.abs(rate - 0.4190091323)) <= 1e-7
    assert np.log(w.energy_amplification) / 3.0 == pytest.approx(0.4190091323, abs=1e-7)


def test_small_ky_approaches_axisymmetric_growth():
    """k_y = 1e-4: over t = 2 k_x moves by 3e-4, the growth stays within 1e-5 of linA's."""
    w = shearing_wave(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, ky=1e-4), (0.0, 2.0), n_out=3)
    assert math.log(w.amplification) / 2.0 == pytest.approx(0.4190091323, abs=1e-5)


def test_gas_only_potential_vorticity_is_conserved():
    """μ = 0, k_z = 0, compressible: |δq| = |i(k_x u_y − k_y u_x) − δρ_g/2| is constant."""
    p = StreamingParams(taus=0.1, mu=0.0, kx=-8.0, ky=1.0, kz=0.0, Pi=0.2)
    x0 = np.zeros(8, complex)
    x0[1], x0[2], x0[0] = 1.0, 8.0, 0.01  # vortical velocity plus some sound
    w = shearing_wave(p, initial=x0, n_out=301, rtol=1e-10, atol=1e-13)
    q = np.abs(w.potential_vorticity)
    assert np.max(np.abs(q / q[0] - 1)) <= 1e-7
    assert w.t[-1] == pytest.approx(2 * swing_time(-8.0, 1.0))
    assert w.kx[-1] == pytest.approx(8.0)


def test_incompressible_vortical_wave_swing_amplification():
    """Kelvin (1887) / Johnson & Gammie (2005) incompressive shwave: |u| ∝ 1/|k(t)|, so the energy
    at the swing is (k_x0² + k_y²)/k_y² = 401 times the initial one (k_x0 = −20 k_y), and the
    net amplification over the symmetric swing is 1."""
    p = StreamingParams(taus=0.1, mu=0.0, kx=-20.0, ky=1.0, kz=0.0, Pi=0.0)
    x0 = np.zeros(8, complex)
    x0[1], x0[2] = 1.0, 20.0  # k·u = 0
    w = shearing_wave(p, initial=x0, n_out=801, rtol=1e-10, atol=1e-14)
    E = w.energy
    k2 = w.kx**2 + 1.0
    assert np.max(np.abs(E * k2 / (E[0] * k2[0]) - 1)) <= 1e-7
    assert E.max() / E[0] == pytest.approx(401.0, rel=1e-6)
    assert w.energy_amplification == pytest.approx(1.0, abs=1e-7)


def test_compressible_vortical_wave_approaches_the_incompressible_swing():
    """With k_y c_s/Ω = 20 the compressible swing peak is within 1 % of 401 and sound emission
    leaves the net energy amplification within 1e-2 of 1 (Chagelishvili et al. 1997: it is
    exponentially small in k_y c_s/Ω)."""
    p = StreamingParams(taus=0.1, mu=0.0, kx=-20.0, ky=1.0, kz=0.0, Pi=0.05)
    x0 = np.zeros(8, complex)
    x0[1], x0[2] = 1.0, 20.0
    w = shearing_wave(p, initial=x0, n_out=2001)
    assert w.energy.max() / w.energy[0] == pytest.approx(401.0, rel=1e-2)
    assert abs(w.energy_amplification - 1) <= 1e-2


def test_incompressible_3d_wave_keeps_k_dot_u_zero():
    p = StreamingParams(taus=0.1, mu=3.0, kx=-30.0, ky=2.0, kz=30.0, Pi=0.0)
    w = shearing_wave(p, (0.0, 5.0), n_out=51)
    s = w.state
    div = w.kx * s[:, 1] + 2.0 * s[:, 2] + 30.0 * s[:, 3]
    assert np.max(np.abs(div)) <= 1e-9 * np.max(np.abs(s[:, 1:4])) * 30


def test_stiff_small_stopping_time_methods_agree():
    """τ_s = 1e-3 (drag rate 1e3 Ω): LSODA, BDF and Radau give the same amplification."""
    p = StreamingParams(taus=1e-3, mu=1.0, kx=-300.0, ky=20.0, kz=300.0)
    amps = [shearing_wave(p, (0.0, 3.0), method=m, n_out=2, rtol=1e-9).amplification
            for m in ("LSODA", "BDF", "Radau")]
    assert max(amps) - min(amps) <= 1e-5 * max(amps)


def test_leading_wave_default_window_and_fastest_initial_state():
    p = StreamingParams(taus=0.1, mu=3.0, kx=-30.0, ky=3.0, kz=30.0)
    w = shearing_wave(p, n_out=5)
    assert w.kx[0] == -30.0 and w.kx[-1] == pytest.approx(30.0)
    m = fastest_mode(p)
    assert np.allclose(w.state[0], m.vector, atol=1e-12)
