"""Eigenmodes of the streaming-instability operator against published numbers and limits."""

import numpy as np
import pytest

from dustygas.linear import StreamingParams, eigenmodes, fastest_mode, growth_rate, operator_matrix
from dustygas.physics import nsh_velocities

# Youdin & Johansen (2007) Table 1 (numbers.md §1), standard time convention, Pi = 0.05.
YJ07 = {
    "linA": dict(taus=0.1, mu=3.0, k=30.0, omega=0.3480127 + 0.4190204j, ux=-0.1691398 + 0.0361553j,
                 uy=0.1336704 + 0.0591695j, uz=0.1691389 - 0.0361555j, drho_g=0.0000224 + 0.0000212j,
                 wx=-0.1398623 + 0.0372951j, wy=0.1305628 + 0.0640574j, wz=0.1639549 - 0.0233277j),
    "linB": dict(taus=0.1, mu=0.2, k=6.0, omega=-0.4998786 + 0.0154764j, ux=-0.0174121 - 0.2770347j,
                 uy=0.2767976 - 0.0187568j, uz=0.0174130 + 0.2770423j, drho_g=-0.0000067 - 0.0000691j,
                 wx=0.0462916 - 0.2743072j, wy=0.2739304 + 0.0039293j, wz=0.0083263 + 0.2768866j),
}
# Benitez-Llambay, Krapp & Pessah (2019) Table 4: the consistent fixed-t_s linearisation.
CONSISTENT = {"linA": 0.4190091323, "linB": 0.0154862262}
# psitools (Paardekooper, McNally & Lovascio 2020), test_monodisperse_si.py: Epstein drag
# (t_s ∝ 1/rho_g), taus = 0.1, eps = 3, Kx = 10, Kz = 20, c = 0.05, eta = 0.05**2 (Pi = 0.05).
PSITOOLS_EPSTEIN = 0.2918648213134704 + 0.021006933423273044j


@pytest.mark.parametrize("case", ["linA", "linB"])
def test_yj07_table_eigenvalue_and_eigenvector(case):
    """All eight components and ω match YJ07 Table 1 to 1e-7 (table rounding is 5e-8)."""
    ref = YJ07[case]
    m = fastest_mode(StreamingParams(taus=ref["taus"], mu=ref["mu"], kx=ref["k"], kz=ref["k"], drag="yj07"))
    assert abs(m.omega.real - ref["omega"].real) <= 1e-7
    assert abs(m.omega.imag - ref["omega"].imag) <= 1e-7
    assert m.eigenvector["drho_p"] == 1.0
    for key in ("ux", "uy", "uz", "drho_g", "wx", "wy", "wz"):
        got = m.eigenvector[key]
        assert abs(got.real - ref[key].real) <= 1e-7, (key, got)
        assert abs(got.imag - ref[key].imag) <= 1e-7, (key, got)


@pytest.mark.parametrize("case", ["linA", "linB"])
def test_consistent_linearisation_matches_bkp19(case):
    ref = YJ07[case]
    s = fastest_mode(StreamingParams(taus=ref["taus"], mu=ref["mu"], kx=ref["k"], kz=ref["k"])).growth_rate
    assert abs(s - CONSISTENT[case]) <= 1e-9


def test_epstein_matches_psitools():
    m = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=10.0, kz=20.0, drag="epstein"))
    assert abs(m.omega - PSITOOLS_EPSTEIN) <= 1e-10


def _residual(p: StreamingParams, omega: complex, v: dict) -> float:
    """The eight linearised equations written out (thesis 4.13 corrected + drag variants), in ω form."""
    eq = nsh_velocities(p.taus, p.mu)
    U = np.array([eq.gas_vx, eq.gas_vy, 0.0])
    V = np.array([eq.dust_vx, eq.dust_vy, p.vz_array[0]])
    k = np.array([p.kx, 0.0, p.kz])
    c2 = p.cs**2
    t, mu = p.taus, p.mu
    u = np.array([v["ux"], v["uy"], v["uz"]])
    w = np.array([v["wx"], v["wy"], v["wz"]])
    rg, rp = v["drho_g"], v["drho_p"]
    gamma = {"consistent": 1.0, "yj07": 0.0, "epstein": 0.0}[p.drag]
    beta = {"consistent": 0.0, "yj07": 0.0, "epstein": 1.0}[p.drag]
    cor = lambda a: np.array([2 * a[1], -0.5 * a[0], 0.0])  # noqa: E731
    r = [
        (-1j * omega + 1j * k @ V) * rp + 1j * k @ w,
        (-1j * omega + 1j * k @ U) * rg + 1j * k @ u,
    ]
    r += list((-1j * omega + 1j * k @ V) * w - cor(w) + ((w - u) + beta * rg * (V - U)) / t)
    r += list((-1j * omega + 1j * k @ U) * u - cor(u) + 1j * c2 * k * rg
              - mu / t * ((w - u) + (rp - gamma * rg) * (V - U)))
    return float(np.max(np.abs(r)))


@pytest.mark.parametrize("drag", ["consistent", "yj07", "epstein"])
@pytest.mark.parametrize("vz", [0.0, -1.7])
def test_modes_solve_the_written_out_equations(drag, vz):
    """Every eigenpair satisfies the equations written out independently here (residual < 1e-9)."""
    p = StreamingParams(taus=0.3, mu=1.7, kx=12.0, kz=-7.0, drag=drag, vz=vz)
    modes = eigenmodes(p)
    assert len(modes) == 8
    for i in range(8):
        m = modes.mode(i)
        scale = max(1.0, np.max(np.abs(m.vector))) * p.cs**2 * abs(p.kx)
        assert _residual(p, m.omega, m.eigenvector) <= 1e-10 * scale


def test_splitting_a_species_in_two_identical_halves():
    """μ = 3 as one species or as 1.5 + 1.5: the same growing eigenvalues to round-off."""
    one = eigenmodes(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, vz=-0.4))
    two = eigenmodes(StreamingParams(taus=[0.1, 0.1], mu=[1.5, 1.5], kx=30, kz=30, vz=-0.4))
    # the split system has the 8 eigenvalues of the single one plus 4 of the relative motion
    for w in one.omega:
        assert np.min(np.abs(two.omega - w)) <= 1e-12 * max(1.0, abs(w)) * 1e2
    m1, m2 = one.mode(0), two.mode(0)
    assert abs(m1.omega - m2.omega) <= 1e-11
    assert np.allclose(m2.eigenvector["drho_p"], 1.0, atol=1e-11)
    assert np.allclose(m2.eigenvector["wx"], m1.eigenvector["wx"], atol=1e-11)
    s = growth_rate(taus=[0.1, 0.1], mu=[1.5, 1.5], kx=30.0, kz=30.0, vz=-0.4, species_axis=0)
    assert abs(float(s) - m1.growth_rate) <= 1e-11


def test_incompressible_limit_is_a_limit():
    """|s(Π) − s(0)| falls as Π² (δρ_g = O(Π²)); Π = 1e-4 agrees with Π = 0 to 1e-9."""
    s0 = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, Pi=0.0)).growth_rate
    d = [abs(fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, Pi=pi)).growth_rate - s0)
         for pi in (1e-2, 1e-3)]
    assert 50 < d[0] / d[1] < 200  # Π² scaling: ratio 100
    s4 = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, Pi=1e-4)).growth_rate
    assert abs(s4 - s0) <= 1e-9
    assert len(eigenmodes(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, Pi=0.0))) == 6  # sound waves gone
    # all three drag linearisations differ only through δρ_g, which vanishes in the limit
    s = [fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, Pi=0.0, drag=d)).growth_rate
         for d in ("consistent", "yj07", "epstein")]
    assert max(s) - min(s) <= 1e-13


def test_incompressible_mode_is_divergence_free():
    m = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=20, Pi=0.0))
    assert m.eigenvector["drho_g"] == 0
    assert abs(30 * m.eigenvector["ux"] + 20 * m.eigenvector["uz"]) <= 1e-13


def test_operator_reduces_to_gas_epicycles_without_dust():
    """μ = 0, k_z = 0: the gas carries Doppler-shifted density waves ω = k_x U_x ± (c_s²k_x² + κ²)^½
    with epicyclic frequency κ = Ω (to 1e-12, relative)."""
    p = StreamingParams(taus=0.5, mu=0.0, kx=3.0, kz=0.0)
    w = eigenmodes(p).omega
    eq = nsh_velocities(0.5, 0.0)
    expected = [3.0 * eq.gas_vx + sgn * np.sqrt(p.cs**2 * 9.0 + 1.0) for sgn in (1, -1)]
    for e in expected:
        assert np.min(np.abs(w - e)) <= 1e-12 * abs(e)


def test_settling_default_and_sign():
    p = StreamingParams(taus=0.1, mu=0.1, kx=1.0, kz=1.0, vz="settling")
    assert p.vz_array[0] == pytest.approx(-(1 / 0.05) * 0.1 / (2 * 0.01 + 1), rel=1e-15)
    # z -> -z symmetry: (k_z, v_z) and (-k_z, -v_z) have the same spectrum
    a = eigenmodes(StreamingParams(taus=0.1, mu=0.1, kx=5.0, kz=3.0, vz=-1.0)).omega
    b = eigenmodes(StreamingParams(taus=0.1, mu=0.1, kx=5.0, kz=-3.0, vz=1.0)).omega
    assert np.max(np.abs(np.sort_complex(a) - np.sort_complex(b))) <= 1e-11


def test_matrix_is_the_documented_operator_for_linA():
    """The compressible operator uses h = c_s δρ_g: entries (0, 1) and (1, 0) are −i c_s k_x."""
    L = operator_matrix(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, drag="yj07"))
    assert L[0, 1] == pytest.approx(-1j * 20 * 30)
    assert L[1, 0] == pytest.approx(-1j * 20 * 30)
