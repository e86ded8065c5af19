"""Density summation and the smoothing-length iteration (thesis eq. 3.1, rho h^d = m h_fact^d)."""

import numpy as np
import pytest
from scipy.optimize import brentq

from dustygas.errors import SimulationError
from dustygas.sph import Box, EquationOfState, ParticleSet, SPHEngine, SPHOptions, get_kernel
from dustygas.sph.lattice import close_packed_lattice, cubic_lattice


def _lattice_density_exact(kernel, hfact, pos, box_length, mass):
    """rho(h) of particle 0 by brute-force summation over all particles (minimum image), and the
    h solving rho(h) h^d = m h_fact^d by bracketing root-finding: independent of the engine."""
    d = kernel.ndim
    sep = pos[:, :d] - pos[0, :d]
    sep -= box_length[:d] * np.rint(sep / box_length[:d])
    r = np.sqrt((sep**2).sum(1))

    def residual(h):
        return mass * float(np.sum(kernel.w(r, h))) * h**d - mass * hfact**d

    h0 = hfact * (float(np.prod(box_length[:d])) / len(pos)) ** (1 / d)
    h = brentq(residual, 0.8 * h0, 1.2 * h0, xtol=1e-16, rtol=1e-15)
    return mass * (hfact / h) ** d


@pytest.mark.parametrize("ndim,n", [(1, 64), (2, 24), (3, 12)])
@pytest.mark.parametrize("kernel", ["cubic", "quintic"])
def test_cubic_lattice_gives_the_exact_uniform_density(ndim, n, kernel):
    """After the h iteration (tolerance 1e-6 on h; guesses 20-30 % off) every particle
    of a periodic cubic lattice has the density of the exact lattice sum to 1e-10, and that density
    is the lattice's m/dx^d to the kernel's own discretisation error (< 1 %). With the default
    tolerance 1e-4 the residual is ~1e-8 (Newton converges quadratically from the last step)."""
    dx = 1.0 / n
    pos = cubic_lattice((n,) * ndim, (0.0,) * ndim, (1.0,) * ndim)
    mass = dx**ndim  # rho = 1
    k = get_kernel(kernel, ndim)
    guess = 1.2 * k.default_hfact * dx * np.where(np.arange(len(pos)) % 2, 1.0, 0.85)
    p = ParticleSet.create(pos, mass=mass, h=guess)
    eng = SPHEngine(p, Box.periodic_box(ndim, (0.0,) * ndim, (1.0,) * ndim), EquationOfState.isothermal(1.0),
                    SPHOptions(kernel=kernel, h_tolerance=1e-6))
    eng.update_derivatives()
    exact = _lattice_density_exact(k, k.default_hfact, pos, np.ones(3), mass)
    assert np.max(np.abs(eng.rho / exact - 1)) < 1e-10
    assert abs(exact - 1.0) < 1e-2
    assert np.max(np.abs(eng.acc)) < 1e-10  # and it is in equilibrium


def test_close_packed_lattice_density_3d():
    """Same on a 3D hexagonal-close-packed lattice (the test lattices of the 3D problems)."""
    a = 1.0 / 12
    pos, hi = close_packed_lattice((12, 12, 12), a, (0.0, 0.0, 0.0))
    mass = float(np.prod(hi)) / len(pos)
    k = get_kernel("cubic", 3)
    p = ParticleSet.create(pos, mass=mass, h=k.default_hfact * a)
    eng = SPHEngine(p, Box.periodic_box(3, (0.0,) * 3, tuple(hi)), EquationOfState.isothermal(1.0),
                    SPHOptions(h_tolerance=1e-6))
    eng.update_derivatives()
    exact = _lattice_density_exact(k, k.default_hfact, pos, np.asarray(hi), mass)
    assert np.max(np.abs(eng.rho / exact - 1)) < 1e-10
    assert abs(exact - 1.0) < 1e-2


def test_grad_h_term_matches_finite_difference():
    """Omega_a = 1 + h/(d rho) sum m dW/dh (thesis eq. 3.4) against a centred difference of the
    density sum in h, for a disordered 2D distribution, to 1e-6."""
    rng = np.random.default_rng(5)
    n = 400
    pos = rng.random((n, 2))
    p = ParticleSet.create(pos, mass=1.0 / n, h=1.2 / np.sqrt(n))
    eng = SPHEngine(p, Box.periodic_box(2, (0.0, 0.0), (1.0, 1.0)), EquationOfState.isothermal(1.0),
                    SPHOptions(h_tolerance=1e-12))
    eng.update_derivatives()
    k = eng.kernel
    for a in (0, 123, 399):
        d = pos - pos[a]
        d -= np.rint(d)
        r = np.hypot(d[:, 0], d[:, 1])
        ha = eng.particles.h[a]
        eps = 1e-6 * ha
        drho_dh = (np.sum(k.w(r, ha + eps)) - np.sum(k.w(r, ha - eps))) / (2 * eps) / n
        omega = 1 + ha / (2 * eng.rho[a]) * drho_dh
        assert eng.omega[a] == pytest.approx(omega, abs=1e-6)


def test_density_matches_direct_sum_for_disordered_particles():
    """rho_a = sum_b m_b W(r_ab, h_a) with the returned h, by brute force, to 1e-9 (tolerance 1e-6)."""
    rng = np.random.default_rng(8)
    n = 300
    pos = np.zeros((n, 3))
    pos[:, :3] = rng.random((n, 3))
    masses = rng.uniform(0.5, 1.5, n) / n
    p = ParticleSet.create(pos, mass=masses, h=0.15)
    p.mass[:] = masses
    eng = SPHEngine(p, Box.periodic_box(3, (0.0,) * 3, (1.0,) * 3), EquationOfState.isothermal(1.0),
                    SPHOptions(h_tolerance=1e-6))
    eng.update_derivatives()
    d = pos[:, None, :] - pos[None, :, :]
    d -= np.rint(d)
    r = np.sqrt((d**2).sum(-1))
    h = eng.particles.h
    direct = (masses[None, :] * eng.kernel.w(r, h[:, None])).sum(1)
    assert np.max(np.abs(eng.rho / direct - 1)) < 1e-9


def test_iteration_that_cannot_converge_stops_the_run():
    """One iteration allowed with a tolerance of 1e-15: a one-line SimulationError with the state."""
    rng = np.random.default_rng(9)
    pos = rng.random((200, 2))
    p = ParticleSet.create(pos, mass=1 / 200, h=0.05)
    eng = SPHEngine(p, Box.periodic_box(2, (0.0, 0.0), (1.0, 1.0)), EquationOfState.isothermal(1.0),
                    SPHOptions(h_tolerance=1e-15, h_max_iterations=1))
    with pytest.raises(SimulationError, match="did not converge in 1 iterations") as err:
        eng.update_derivatives()
    assert "\n" not in str(err.value) and err.value.state["particles"].size > 0
