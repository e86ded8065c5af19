"""Polydisperse streaming instability against published values and the published N-trend.

Reference values. Printed in a paper (digits as printed by the authors):

* Benítez-Llambay, Krapp & Pessah (2019, Table 4), "linC": two species τ_s = (0.0425, 0.1),
  μ = (1, 0.5), K_x = K_z = 50, consistent fixed-t_s drag: ω = 0.3242790653 + 0.3027262829 i
  (ten digits; we agree to 5e-11).

Independent-code values (the regression values of psitools' own test suite, an independent
implementation by Paardekooper, McNally & Lovascio 2020/2021 -- code output, not numbers printed
in their papers):

* psitools' direct solver (McNally, Lovascio & Paardekooper 2021; its ``test_direct.py``): MRN,
  μ = 3, τ_s ∈ [1e-8, 0.1], K = (80, 100), Epstein drag (t_s ∝ 1/ρ_g), trapezoidal weights on
  N = 129, 257, 513 Chebyshev roots, continuum background: three values printed to 16 digits
  (we agree to ≤ 2e-11 relative at N = 129, 257 and 4.6e-9 at 513, the eigenvalue precision of
  a 2056² matrix with 1/τ_min = 1e8 entries);
* psitools' continuum solver (Paardekooper, McNally & Lovascio 2020; ``test_psi_mode.py``): MRN,
  μ = 3, τ_s ∈ [1e-8, 0.01], K = (10, 1000): ω = −1.0062579942553218 + 1.3209784880018007e-05 i
  from a root of the dispersion relation whose resonant denominators psitools regularises by
  +1e-10 i; Gauss quadrature in √τ converges to it to |Δω| ≤ 2e-10 (Re ω to 5e-11).

Published trend (Krapp et al. 2019; Zhu & Yang 2021; Paardekooper et al. 2020): at μ ≲ 1 the
growth rate of a wide size distribution falls as the number of species grows (no fast growth in
the continuum limit); at μ > 1 it converges to a finite value. Zhu & Yang (2021, MNRAS 501, 467;
the abstract of arXiv:2008.01119) state it with numbers: "With a wide range of dust sizes present
in the disc (e.g. T_s,min ≲ 10⁻³), the growth rate in the slow-growth regime decreases as more dust
species are considered. With a narrow range of dust sizes (e.g. T_s,max/T_s,min = 5), on the other
hand, the growth rate in most of the ε-T_s,max space is converged with increasing dust species, but
the fast and the slow growth regimes remain clearly separated." Their conventions, used in the
``zhu_yang`` tests below: N species on logarithmic bins of [T_s,min, T_s,max], each with its bin's
mass of n(a) ∝ a^-q (q = 3.5, ``beta = -3.5``), fixed stopping times (``drag="consistent"``), the
N species' own drift (``rule="bins"``), and the growth rate maximised over (K_x, K_z); here over
an 11 × 11 grid, half a decade apart, of [0.1, 10⁴]² (their window is not in the abstract).
"""

import numpy as np
import pytest

from dustygas.errors import UserError
from dustygas.linear import StreamingParams, fastest_mode, growth_rate
from dustygas.linear.polydisperse import PowerLawSizes, distribution_growth, fastest_growth, species

LINC = dict(taus=[0.0425, 0.1], mu=[1.0, 0.5], kx=50.0, kz=50.0)
LINC_OMEGA = 0.3242790653 + 0.3027262829j  # BKP19 Table 4 (their sign: -0.3027262829 - 0.3242790653 i)
MRN3 = PowerLawSizes(mu=3.0, taus_min=1e-8, taus_max=0.1)
PSITOOLS_DIRECT = {129: 0.5512363292041821 + 0.11242857992948893j, 257: 0.5489690582185277 + 0.11216071905699404j,
                   513: 0.5478173144269354 + 0.11203395665778133j}


def test_bkp19_linC_two_species():
    s, f = fastest_growth(**LINC)
    assert abs(s - LINC_OMEGA.imag) <= 5e-11 and abs(f - LINC_OMEGA.real) <= 5e-11
    m = fastest_mode(StreamingParams(**LINC))
    assert abs(m.omega - LINC_OMEGA) <= 5e-11
    compiled = growth_rate(taus=np.array(LINC["taus"]), mu=np.array(LINC["mu"]), kx=50.0, kz=50.0, species_axis=0)
    assert abs(float(compiled) - LINC_OMEGA.imag) <= 5e-11


@pytest.mark.parametrize("n", [129, 257])
def test_psitools_direct_mrn(n):
    s, f = distribution_growth(MRN3, n=n, kx=80.0, kz=100.0, rule="chebyshev-trapezoid")
    ref = PSITOOLS_DIRECT[n]
    assert abs(s / ref.imag - 1) <= 1e-9 and abs(f / ref.real - 1) <= 1e-9


@pytest.mark.slow
def test_psitools_direct_mrn_513_and_its_convergence():
    """N = 513 (a 2056² eigenproblem), and the first-order convergence in N both codes show:
    successive differences of s halve, (s_129 − s_257)/(s_257 − s_513) = 2.11."""
    s, f = distribution_growth(MRN3, n=513, kx=80.0, kz=100.0, rule="chebyshev-trapezoid")
    ref = PSITOOLS_DIRECT[513]
    assert abs(s / ref.imag - 1) <= 1e-8 and abs(f / ref.real - 1) <= 1e-8  # measured 4.6e-9, 1e-10
    s129 = distribution_growth(MRN3, n=129, kx=80.0, kz=100.0, rule="chebyshev-trapezoid")[0]
    s257 = distribution_growth(MRN3, n=257, kx=80.0, kz=100.0, rule="chebyshev-trapezoid")[0]
    ratio = (s129 - s257) / (s257 - s)
    published = (PSITOOLS_DIRECT[129].imag - PSITOOLS_DIRECT[257].imag) / (PSITOOLS_DIRECT[257].imag - ref.imag)
    assert ratio == pytest.approx(published, rel=1e-5)
    assert ratio == pytest.approx(2.11, abs=0.01)


def test_psitools_continuum_mrn_by_gauss_quadrature():
    ref = -1.0062579942553218 + 1.3209784880018007e-05j
    dist = PowerLawSizes(mu=3.0, taus_min=1e-8, taus_max=0.01)
    for n in (8, 12):
        s, f = distribution_growth(dist, n=n, kx=10.0, kz=1000.0, rule="gauss")
        assert abs(s - ref.imag) <= 2e-10 and abs(f - ref.real) <= 2e-10  # measured 4.4e-11, 1.5e-11 here; 5.2e-11 on the CI machine (LAPACK build)


def test_psitools_single_size_epstein_linA():
    """psitools ``test_psi_mode_0`` (single size at τ_max = 0.1, μ = 3, K = 30, Epstein drag)."""
    m = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30.0, kz=30.0, drag="epstein"))
    assert abs(m.omega - (0.34801869149969916 + 0.4190301951732903j)) <= 1e-10


def test_growth_falls_with_the_number_of_species_at_mu_one():
    """Krapp et al. (2019)'s trend: MRN, μ = 1, τ_s ∈ [1e-4, 0.1], K = (80, 100), N log-spaced bins
    with the N-species background: s(N) decreases monotonically from N = 4 and halves with every
    doubling of N (s ∝ 1/N, measured ratios 0.49-0.58), far below the N = 4 value."""
    dist = PowerLawSizes(mu=1.0, taus_min=1e-4, taus_max=0.1)
    ns = [4, 8, 16, 32, 64, 128]
    s = np.array([distribution_growth(dist, n=n, kx=80.0, kz=100.0, drag="consistent")[0] for n in ns])
    assert np.all(np.diff(s) < 0)
    ratios = s[1:] / s[:-1]
    assert np.all((ratios > 0.45) & (ratios < 0.62)), ratios
    assert s[-1] < 0.05 * s[0]


def test_growth_converges_with_the_number_of_species_at_mu_three():
    """At μ = 3 (the fast-growth regime of Zhu & Yang 2021) the growth converges with N to a finite
    value: MRN, τ_s ∈ [1e-4, 0.1], K = (80, 100), Gauss quadrature s(N) = 0.1429, 0.1317, 0.1252,
    0.1245 for N = 8 .. 64 (successive changes shrink), and log-spaced bins with the N-species
    background give the same limit (0.1249 at N = 64, within 0.5 %)."""
    dist = PowerLawSizes(mu=3.0, taus_min=1e-4, taus_max=0.1)
    s = np.array([distribution_growth(dist, n=n, kx=80.0, kz=100.0, rule="gauss")[0] for n in (8, 16, 32, 64)])
    steps = np.abs(np.diff(s))
    assert np.all(np.diff(steps) < 0) and steps[-1] < 0.01 * s[-1]
    bins = distribution_growth(dist, n=64, kx=80.0, kz=100.0, rule="bins")[0]
    assert bins == pytest.approx(s[-1], rel=5e-3) and s[-1] > 0.1


def test_species_conserve_the_dust_mass_and_bad_input():
    dist = PowerLawSizes(mu=2.0, taus_min=1e-3, taus_max=1.0, beta=-3.0)
    for rule in ("bins", "gauss"):
        t, m, _ = species(dist, 16, rule)
        assert m.sum() == pytest.approx(2.0, rel=1e-13) and np.all((t > 1e-3) & (t < 1.0))
    with pytest.raises(UserError, match="taus_min"):
        PowerLawSizes(mu=1.0, taus_min=0.1, taus_max=0.01)
    with pytest.raises(UserError, match="rule"):
        species(dist, 4, "midpoint")
    with pytest.raises(UserError, match="positive integer"):
        species(dist, 0)


ZY21_WINDOW = np.logspace(-1.0, 4.0, 11)  # K_x = K_z grid, half a decade apart


def _zy21_fastest(mu: float, taus_min: float, taus_max: float, n: int) -> float:
    """Zhu & Yang (2021)'s growth rate: the N-species bins of an MRN distribution, fixed stopping
    times, maximised over the (K_x, K_z) window ``ZY21_WINDOW``² (compiled QR, vectorised)."""
    taus, mu_j, _ = species(PowerLawSizes(mu=mu, taus_min=taus_min, taus_max=taus_max), n, "bins")
    kx, kz = np.meshgrid(ZY21_WINDOW, ZY21_WINDOW, indexing="ij")
    s = growth_rate(taus=taus[:, None, None], mu=mu_j[:, None, None], kx=kx, kz=kz, species_axis=0)
    return float(s.max())


def test_zhu_yang_2021_narrow_distributions_converge_and_the_regimes_stay_apart():
    """T_s,max/T_s,min = 5 (Zhu & Yang 2021's narrow range). Fast regime, ε = 3 on [0.02, 0.1] and
    ε = 1 on [0.002, 0.01]: N = 8 -> 16 changes s by -0.52 % (0.46479 -> 0.46236) and -1.38 %
    (0.37292 -> 0.36778), converged within 3 %. The slow regime, ε = 0.5 on [0.02, 0.1], grows at
    s = 0.00232 at N = 16, 160 times slower than the slower fast case: clearly separated (< 1/50).
    About 1 CPU-s."""
    fast = []
    for mu, lo in ((3.0, 0.02), (1.0, 0.002)):
        s8, s16 = (_zy21_fastest(mu, lo, 5 * lo, n) for n in (8, 16))
        assert abs(s16 / s8 - 1) <= 0.03, (mu, s8, s16)
        assert s16 > 0.3
        fast.append(s16)
    slow = _zy21_fastest(0.5, 0.02, 0.1, 16)
    assert 0 < slow < min(fast) / 50, (slow, fast)


def test_zhu_yang_2021_wide_distribution_in_the_slow_regime_falls_with_n():
    """T_s on [10⁻⁴, 0.1] (T_s,min ≲ 10⁻³: Zhu & Yang 2021's wide range), ε = 0.5 (slow regime):
    s = 0.05121, 0.02251, 0.01033 for N = 4, 8, 16 (each doubling x 0.44, x 0.46 < 0.6)."""
    s = [_zy21_fastest(0.5, 1e-4, 0.1, n) for n in (4, 8, 16)]
    assert s[1] < 0.6 * s[0] and s[2] < 0.6 * s[1], s


@pytest.mark.slow
def test_zhu_yang_2021_narrow_distribution_converges_in_the_slow_regime_once_n_is_large():
    """The narrow range in the slow regime, ε = 0.5 on [0.02, 0.1]: s first halves with every
    doubling of N (the N = 4 .. 16 species each resonate alone), then converges as the bins resolve
    the resonance: s = 2.315e-3, 1.392e-3, 1.225e-3, 1.141e-3 for N = 16, 32, 64, 128, successive
    ratios 0.601, 0.880, 0.932 (Zhu & Yang 2021: "converged with increasing dust species"). And
    T_s,max > 1, ε = 0.3 on [2, 10]: N = 16 -> 32 changes s by -0.39 % (0.051860 -> 0.051657).
    About 115 CPU-s (N = 128: a 516² eigenproblem at 121 wavenumbers)."""
    s = np.array([_zy21_fastest(0.5, 0.02, 0.1, n) for n in (16, 32, 64, 128)])
    ratios = s[1:] / s[:-1]
    assert np.all(np.diff(ratios) > 0) and ratios[0] < 0.7 and ratios[-1] > 0.9, (s, ratios)
    s16, s32 = (_zy21_fastest(0.3, 2.0, 10.0, n) for n in (16, 32))
    assert abs(s32 / s16 - 1) <= 0.02, (s16, s32)
