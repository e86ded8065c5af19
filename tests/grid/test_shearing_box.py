"""Shearing box: epicycles, conservation and the y-momentum budget,
the pressure-gradient force and vertical gravity.

The y-momentum budget. With shear-periodic radial boundaries the flux through the outer face at
``y`` is the flux through the inner face at ``y + q Omega Lx t``, except that ``v_y`` is smaller
there by ``q Omega Lx``: ``F_y(out) = F_y(in) - q Omega Lx F_rho(in)``. The engine makes the two
faces agree exactly (remapped averages), so the fluxes of ``rho v_y`` through the two radial
faces differ by ``q Omega Lx`` times the mass flux, and summed over the box

    P_y(t) - P_y(0) = q Omega Lx M_r(t) + Int_0^t S_y dt,

where ``M_r`` is the mass that crossed the radial boundary outwards and ``S_y = -2 Omega P_x``
is the Coriolis force on the box (``-(2 - q) Omega P'_x`` and no boundary term for the momentum
``P'`` of the velocity relative to the shear, which orbital advection stores). The engine
reports ``M_r`` and the source integral in its history; the test checks the identity to
round-off on a strongly perturbed flow.
"""

import math

import numpy as np
import pytest
from scipy.optimize import curve_fit

from dustygas import api
from dustygas.grid import GridEngine, Mesh
from dustygas.io import read_h5
from dustygas.physics import nsh_velocities
from dustygas.physics.shearing_sheet import epicyclic_frequency

from ._helpers import pair_orders, run_to

Q, OMEGA = 1.5, 1.0


@pytest.mark.parametrize("orbital_advection", [False, True])
def test_epicycle_frequency_over_ten_orbits(tmp_path, orbital_advection):
    res = api.run("epicycle", output=tmp_path / "run",
                  set=[f"shearing_box.orbital_advection={str(orbital_advection).lower()}", "run.log_every=1000000"])
    assert res.status == "finished" and res.engine.t == pytest.approx(20 * math.pi)
    hist, _ = read_h5(tmp_path / "run" / "history.h5")
    t, px = hist["time"], hist["momentum_x"]
    (amp, freq, phase), _ = curve_fit(lambda t, a, w, p: a * np.cos(w * t + p), t, px, p0=[0.01, 1.0, 0.0])
    kappa = float(epicyclic_frequency(OMEGA, Q))
    # measured: 8.7e-6 (velocity in the rotating frame, dt ~ 0.0072) and 2.6e-5 (orbital
    # advection, dt ~ 0.0124); the error is VL2's (kappa dt)^2 / 6
    assert abs(freq / kappa - 1) <= 1e-4
    assert abs(amp) == pytest.approx(0.01, rel=1e-3)  # box mass 1, delta v_x = 0.01


def _perturbed_box(shape, size, orbital_advection, reconstruction="plm", riemann="hlle"):
    mesh = Mesh(shape, size)
    eng = GridEngine(mesh, boundaries=("shear-periodic", "periodic", "periodic"), omega=OMEGA, q=Q,
                     orbital_advection=orbital_advection, reconstruction=reconstruction, riemann=riemann,
                     cfl=0.3 if mesh.ndim == 3 else 0.4)
    x, y, z = eng.mesh.meshgrid()
    lx, ly, lz = eng.mesh.size
    rng = np.random.default_rng(7)
    full = tuple(reversed(eng.mesh.shape))
    rho = 1 + 0.3 * np.sin(2 * np.pi * x / lx) * np.cos(2 * np.pi * y / ly) + 0.05 * rng.random(full)
    vx = 0.2 * np.cos(2 * np.pi * (x / lx + 0.3)) * np.sin(2 * np.pi * y / ly) + 0.05 * np.cos(2 * np.pi * z / lz)
    vy = -Q * OMEGA * x + 0.1 * np.sin(2 * np.pi * x / lx)
    eng.set_primitive(rho, vx, vy, 0.02 * np.sin(2 * np.pi * x / lx))
    return eng


def _stored_py(eng):
    return float(eng.state[(2,) + eng.mesh.interior()].sum() * eng.mesh.cell_volume)


CASES = [
    ((32, 24, 1), (1.0, 2.0, 1.0), False, "plm", "hlle"),
    ((32, 24, 1), (1.0, 2.0, 1.0), True, "plm", "hlle"),
    ((32, 24, 1), (1.0, 2.0, 1.0), False, "ppm", "hllc"),
    ((16, 12, 8), (1.0, 2.0, 0.5), False, "plm", "hllc"),
    ((16, 12, 8), (1.0, 2.0, 0.5), True, "ppm", "hlle"),
    ((32, 1, 16), (1.0, 1.0, 0.5), False, "plm", "hlle"),  # radial-vertical plane
    ((32, 1, 16), (1.0, 1.0, 0.5), True, "ppm", "hllc"),  # same, velocity relative to the shear
]


@pytest.mark.parametrize("shape, size, orbital_advection, reconstruction, riemann", CASES)
def test_mass_and_y_momentum_budget_over_1000_steps(shape, size, orbital_advection, reconstruction, riemann):
    eng = _perturbed_box(shape, size, orbital_advection, reconstruction, riemann)
    m0, py0 = eng.history()["mass"], _stored_py(eng)
    for _ in range(1000):
        eng.advance(eng.timestep())
    h = eng.history()
    assert abs(h["mass"] / m0 - 1) <= 1e-13
    jump = 0.0 if orbital_advection else Q * OMEGA * size[0]
    boundary_term = jump * h["radial_boundary_mass"]
    budget = boundary_term + h["momentum_y_source"]
    change = _stored_py(eng) - py0
    assert abs(change - budget) <= 1e-13 * max(1.0, abs(py0))
    if not orbital_advection and shape[1] > 1:
        assert abs(boundary_term) > 1e-4  # the boundary term is really exercised (measured ~1e-2)


def test_gas_nsh_equilibrium_holds_with_the_pressure_gradient_force():
    """Gas alone under the force 2 eta v_K Omega x^ orbits at v_y = -q Omega x - eta v_K (thesis 4.8, eps = 0)."""
    eta_vk = 0.05
    gas_vy = float(nsh_velocities(0.1, 0.0, eta_vk).gas_vy)  # -eta v_K: no dust, no drag
    for oa in (False, True):
        eng = GridEngine(Mesh((16, 16, 1), (1.0, 1.0, 1.0)), boundaries=("shear-periodic", "periodic", "periodic"),
                         omega=OMEGA, q=Q, orbital_advection=oa, eta_vK=eta_vk)
        x = eng.mesh.centers(0)[None, None, :]
        eng.set_primitive(1.0, 0.0, -Q * OMEGA * x + gas_vy + np.zeros((1, 16, 1)), 0.0)
        run_to(eng, 2 * math.pi)
        rho, vx, vy, _ = eng.primitive()
        assert np.max(np.abs(vx)) < 1e-13
        assert np.max(np.abs(vy + Q * OMEGA * x - gas_vy)) < 1e-13
        # without the force the same state is not an equilibrium: v_x reaches ~2 eta v_K
        eng2 = GridEngine(Mesh((16, 16, 1), (1.0, 1.0, 1.0)), boundaries=("shear-periodic", "periodic", "periodic"),
                          omega=OMEGA, q=Q, orbital_advection=oa)
        eng2.set_primitive(1.0, 0.0, -Q * OMEGA * x + gas_vy + np.zeros((1, 16, 1)), 0.0)
        run_to(eng2, 0.5 * math.pi)
        assert np.max(np.abs(eng2.primitive()[1])) > eta_vk


@pytest.mark.parametrize("boundary, region", [("reflecting", 2.0), ("hydrostatic", 3.0)])
def test_vertical_gravity_hydrostatic_column_converges(boundary, region):
    """rho = exp(-z^2 / 2H^2) on |z| < 3H stays at rest to O(dz^2) under vertical gravity.

    Measured max |v_z| at t = 1/Omega, PPM, 32..256 cells: with reflecting walls, inside
    |z| < 2H (the walls themselves disturb the profile at first order), 1.13e-2, 2.92e-3,
    7.36e-4, 1.85e-4 (orders 1.95, 1.99, 1.99); with the open hydrostatic boundaries, over the
    whole column, 1.74e-2, 3.93e-3, 9.06e-4, 2.17e-4 (orders 2.1), the mass changing by the
    discretisation error of the start, 5.2e-5, 1.5e-5, 4.1e-6, 1.1e-6 (second order; tolerance
    7e-5 (32/n)^2) -- zero-gradient outflow instead lets the atmosphere fall in: |v_z| = 2.5.
    """
    errors = []
    for n in (32, 64, 128, 256):
        eng = GridEngine(Mesh((1, 1, n), (1.0, 1.0, 6.0)), omega=OMEGA, vertical_gravity=True,
                         boundaries=("periodic", "periodic", boundary), reconstruction="ppm")
        z = eng.mesh.centers(2)[:, None, None]
        eng.set_primitive(np.exp(-0.5 * z**2), 0.0, 0.0, 0.0)
        m0 = eng.history()["mass"]
        run_to(eng, 1.0)
        change = abs(eng.history()["mass"] / m0 - 1)
        assert change < (1e-14 if boundary == "reflecting" else 7e-5 * (32 / n) ** 2)
        errors.append(np.max(np.abs(eng.primitive()[3][np.abs(z[:, 0, 0]) < region])))
    assert errors[0] < 0.02
    assert min(pair_orders(errors)) >= 1.8, errors


def test_hydrostatic_boundary_needs_vertical_gravity_and_the_z_axis():
    from dustygas.errors import SetupError

    with pytest.raises(SetupError, match="z axis only"):
        GridEngine(Mesh((1, 1, 16), (1.0, 1.0, 6.0)), omega=OMEGA, boundaries=("periodic", "periodic", "hydrostatic"))
    with pytest.raises(SetupError, match="z axis only"):
        GridEngine(Mesh((16, 1, 1), (1.0, 1.0, 1.0)), omega=OMEGA, vertical_gravity=True,
                   boundaries=("hydrostatic", "periodic", "periodic"))


def test_periodic_tidal_potential_is_periodic_and_its_lever_is_its_slope():
    """The periodic potential of a box ``|z| < 0.15 H`` (smoothing 0.01 H): its lever equals the
    centred difference of the potential to 1e-8 (measured 2e-9), is ``z`` to 1 % at |z| < 0.05 H
    (analytic: ``1 - (0.01/0.11)^3 = 0.99925`` at 0.05 H), and vanishes at the faces, where the
    potential is continuous (the same value from both sides)."""
    from dustygas.grid.shearing_box import periodic_tidal_lever, periodic_tidal_potential

    box = dict(z_lo=-0.15, lz=0.3, smoothing=0.01)
    z = np.linspace(-0.149, 0.149, 301)
    h = 1e-6
    slope = (periodic_tidal_potential(z + h, **box) - periodic_tidal_potential(z - h, **box)) / (2 * h)
    assert np.max(np.abs(slope - periodic_tidal_lever(z, **box))) < 1e-8
    inner = np.abs(z) < 0.05
    assert np.allclose(periodic_tidal_lever(z[inner], **box), z[inner], rtol=1e-2, atol=0)
    assert abs(float(periodic_tidal_lever(0.15, **box))) < 1e-15
    assert abs(float(periodic_tidal_lever(-0.15 + 1e-12, **box))) < 1e-9
    lo, hi = periodic_tidal_potential([-0.15 + 1e-9, 0.15 - 1e-9], **box)
    assert abs(lo - hi) < 1e-12


def test_stratified_column_periodic_in_z_stays_at_rest():
    """``rho = exp(-phi)`` in the periodic potential (box 0.3 H, the si3d preset's height) under
    vertical gravity, PPM, to t = 10/Omega: max |v_z| 3.21e-4, 1.66e-4, 8.27e-5 c_s at 32, 64, 128
    cells (first order: the smoothing length is the ghost depth, 3 cells, so the flattened
    region narrows with the cells); mass conserved to round-off (measured <= 7e-16) and the net
    vertical momentum stays zero (measured <= 2.4e-17)."""
    errors = []
    for n in (32, 64, 128):
        eng = GridEngine(Mesh((1, 1, n), (1.0, 1.0, 0.3)), omega=OMEGA, vertical_gravity=True,
                         boundaries=("periodic", "periodic", "periodic"), reconstruction="ppm")
        z = eng.mesh.centers(2)[:, None, None]
        eng.set_primitive(np.exp(-eng.tidal_potential(z)), 0.0, 0.0, 0.0)
        m0 = eng.history()["mass"]
        run_to(eng, 10.0)
        assert abs(eng.history()["mass"] / m0 - 1) < 1e-14
        assert abs(eng.history()["momentum_z"]) < 1e-15
        errors.append(np.max(np.abs(eng.primitive()[3])))
    assert errors[0] < 4e-4
    assert min(pair_orders(errors)) >= 0.9, errors
