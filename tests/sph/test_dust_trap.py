"""The self-induced dust-trap experiment (Gonzalez, Laibe & Maddison 2017): its set-up and its trap finder.

The set-up must hold the disk of thesis Figure 3.1 -- gas :math:`\\Sigma \\propto R^{-1}` with 0.01 M_sun
from 4 to 120 au, dust-to-gas ratio 0.01 everywhere and 10 µm grains -- and the analysis must find a
radial pressure maximum where there is one (and none in a smooth power-law disk or in noise).
"""

import numpy as np
import pytest

from dustygas.analysis.dust_trap import pressure_maxima
from dustygas.problems import get_problem
from dustygas.sph.disk import cylindrical
from dustygas.sph.particles import DUST, GAS
from dustygas.units import DISK_UNITS


def test_dust_trap_setup_matches_the_analytic_disk():
    """Gas mass per annulus as Sigma ~ 1/R gives it (equal mass per unit radius) to within one
    particle's mass (measured: half of one, the quantisation of 1000 particles), dust-to-gas ratio
    0.01 and 10 µm grains exactly, and the dust moving with the gas."""
    n = 1000
    prob = get_problem("dust-trap")
    eng = prob.build(prob.config(overrides=[f"disk.n_gas={n}"]))
    p = eng.particles
    gas, dust = p.ptype == GAS, p.ptype == DUST
    assert gas.sum() == dust.sum() == n
    assert p.mass[gas].sum() == pytest.approx(0.01, rel=1e-12)
    R, _ = cylindrical(p.pos)
    edges = np.array([4.0, 8.0, 16.0, 32.0, 64.0, 120.0])
    m_gas = np.histogram(R[gas], edges, weights=p.mass[gas])[0]
    m_dust = np.histogram(R[dust], edges, weights=p.mass[dust])[0]
    expected = 0.01 * np.diff(edges) / (120.0 - 4.0)  # Sigma ~ 1/R: the mass of an annulus grows with its width
    np.testing.assert_allclose(m_gas, expected, atol=1.0 * 0.01 / n)
    np.testing.assert_allclose(m_dust / m_gas, 0.01, rtol=1e-12)
    np.testing.assert_array_equal(p.extra["grain_size"][dust], 1e-3 / DISK_UNITS.length)
    np.testing.assert_array_equal(p.vel[dust], p.vel[gas])


def _pressure(R, bump):
    """Midplane pressure of the disk (R^-2.75) with a Gaussian ring of relative height ``bump`` at 20 au."""
    return R**-2.75 * (1.0 + bump * np.exp(-(((R - 20.0) / 4.0) ** 2)))


@pytest.mark.parametrize("bump, noise, found", [(0.0, 1e-3, False), (2.0, 1e-3, True), (2.0, 0.5, False)])
def test_pressure_maxima_finds_a_ring_above_the_noise(bump, noise, found):
    """A ring tall enough to reverse the pressure gradient (twice the disk's pressure at 20 au, 4 au wide)
    is found in the annulus holding the true maximum (24 logarithmic annuli from 4 to 120 au, as
    :func:`~dustygas.analysis.dust_trap.trap_profiles` bins); a smooth power law has none, and neither
    has the ring drowned in noise of 50 % per annulus."""
    edges = np.geomspace(4.0, 120.0, 25)
    R = np.sqrt(edges[1:] * edges[:-1])
    P = _pressure(R, bump)
    radii = pressure_maxima({"R": R, "P_mid": P, "P_err": noise * P})
    if not found:
        assert radii.size == 0
        return
    fine = np.linspace(10.0, 30.0, 20001)
    P_fine = _pressure(fine, bump)
    peak = fine[1:-1][(P_fine[1:-1] > P_fine[:-2]) & (P_fine[1:-1] > P_fine[2:])]
    assert peak.size == 1 and radii.size == 1
    k = np.searchsorted(edges, peak[0]) - 1  # the annulus holding the true maximum
    assert radii[0] == R[k]
