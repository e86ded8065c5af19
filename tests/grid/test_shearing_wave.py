"""The vortical shearing wave through its swing.

Reference: Kelvin's incompressible solution (:mod:`dustygas.physics.shearing_sheet`), which the
compressible gas of the default problem follows to 0.15 % of the peak amplitude (box of H/4,
``k_x0 = -2 k_y``; measured with an independent ODE integration of the compressible linear
equations). Error measure: the least-squares complex amplitude of ``delta v_x`` on the sheared
wave ``exp(i (k_x(t) x + k_y y))`` at eight times through ``t = 0 .. 8/3`` (swing at 4/3), minus
the reference, relative to the peak amplitude (5 times the initial one).

Measured worst errors, 64^2: PLM/VL2 1.8 % (orbital advection 2.0 %), PPM/VL2 0.42 % (0.40 %),
PPM-CS/RK3 0.21 % (0.14 %); PLM at 32^2, 64^2, 128^2: 13.6 %, 1.8 %, 0.35 %.
"""

import numpy as np
import pytest

from dustygas.physics.shearing_sheet import vortical_shearing_wave
from dustygas.problems import get_problem
from dustygas.problems.shearing_wave import wavenumbers


def wave_amplitude(eng, kx, ky) -> complex:
    """Complex a with delta v_x ~ Re[a exp(i (kx x + ky y))] (least squares over the cells)."""
    x, y, _ = eng.mesh.meshgrid()
    phase = (kx * x + ky * y).ravel()
    c, s, f = np.cos(phase), np.sin(phase), eng.primitive()[1].ravel()
    a, b = np.linalg.solve([[c @ c, c @ s], [c @ s, s @ s]], [c @ f, s @ f])
    return complex(a, -b)


def worst_error(overrides) -> float:
    prob = get_problem("shearing-wave")
    cfg = prob.config(overrides=overrides)
    eng = prob.build(cfg)
    p = cfg.problem
    kx0, ky = wavenumbers(p, eng.mesh)
    worst = 0.0
    for t_check in np.linspace(0.0, cfg.run.tlim, 9)[1:]:
        while eng.t < t_check * (1 - 1e-14):
            eng.advance(min(eng.timestep(), t_check - eng.t))
        ref = vortical_shearing_wave(eng.t, kx0, ky, p.amplitude)
        got = wave_amplitude(eng, ref.kx, ky)
        worst = max(worst, abs(got - complex(ref.ux)) / (5 * p.amplitude))
    return worst


@pytest.mark.parametrize("orbital_advection", ["false", "true"])
def test_shearing_wave_plm_64(orbital_advection):
    assert worst_error([f"shearing_box.orbital_advection={orbital_advection}"]) <= 0.03


@pytest.mark.parametrize("orbital_advection", ["false", "true"])
def test_shearing_wave_ppm_64(orbital_advection):
    assert worst_error(["scheme.reconstruction=ppm", f"shearing_box.orbital_advection={orbital_advection}"]) <= 0.006


@pytest.mark.slow
def test_shearing_wave_converges_to_kelvins_solution():
    errors = [worst_error([f"grid.nx={n}", f"grid.ny={n}"]) for n in (32, 64, 128)]
    assert errors[2] <= 0.005
    assert np.all(np.diff(errors) < 0) and errors[0] / errors[2] > 16, errors


def test_kelvins_solution_is_the_nearly_incompressible_limit_of_the_default_wave():
    """Integrate the compressible linear shearing-wave equations (isothermal, relative to the shear)

        ds/dt = -i (k_x u_x + k_y u_y),  du_x/dt = 2 Omega u_y - i k_x c_s^2 s,
        du_y/dt = -(2 - q) Omega u_x - i k_y c_s^2 s,    k_x = k_x0 + q Omega k_y t,

    from Kelvin's initial state and check that the reference differs from it by < 0.2 % of the
    peak (measured 0.146 %), while in a box of one scale height it would not (23 %)."""
    from scipy.integrate import solve_ivp

    prob = get_problem("shearing-wave")
    cfg = prob.config()

    def deviation(box: float) -> float:
        kx0, ky = -2 * 2 * np.pi / box, 2 * np.pi / box
        q, om, cs = 1.5, 1.0, 1.0
        w0 = vortical_shearing_wave(0.0, kx0, ky, 1.0)

        def rhs(t, y):
            s, ux, uy = y[0] + 1j * y[1], y[2] + 1j * y[3], y[4] + 1j * y[5]
            kx = kx0 + q * om * ky * t
            d = (-1j * (kx * ux + ky * uy), 2 * om * uy - 1j * kx * cs**2 * s, -(2 - q) * om * ux - 1j * ky * cs**2 * s)
            return [v for z in d for v in (z.real, z.imag)]

        s0 = complex(w0.pressure) / cs**2
        y0 = [s0.real, s0.imag, float(w0.ux.real), 0.0, float(w0.uy.real), 0.0]
        t = np.linspace(0.0, cfg.run.tlim, 201)
        sol = solve_ivp(rhs, (0.0, cfg.run.tlim), y0, t_eval=t, rtol=1e-10, atol=1e-12, max_step=1e-3)
        ref = vortical_shearing_wave(t, kx0, ky, 1.0).ux
        return float(np.max(np.abs(sol.y[2] + 1j * sol.y[3] - ref)) / np.max(np.abs(ref)))

    assert cfg.grid.lx == cfg.grid.ly == 0.25 and cfg.gas.cs == 1.0
    assert deviation(0.25) < 0.002
    assert deviation(1.0) > 0.1
