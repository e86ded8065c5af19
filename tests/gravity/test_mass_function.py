"""Acceptance 3 (mass function): maximum-likelihood slopes, their bootstrap errors, model choice."""

import numpy as np
import pytest

from dustygas.analysis.mass_function import (cumulative_number, fit_mass_function, fit_power_law,
                                             fit_truncated_power_law, sample_power_law, upper_incomplete_gamma)


def _truncated_sample(n, p, m_e, rng):
    """``dN/dM ∝ M^-p exp(-M/M_e)`` above 1 by rejection from the power law."""
    out = np.zeros(0)
    while out.size < n:
        m = sample_power_law(4 * n, p, 1.0, rng)
        out = np.concatenate((out, m[rng.uniform(size=m.size) < np.exp(-(m - 1.0) / m_e)]))
    return out[:n]


def test_power_law_slope_of_1000_masses():
    # p = 1.6 (Simon et al. 2016); seed 0 gives 1.6287 +- 0.0216: 1.3 bootstrap sigma off, inside 0.05
    fit = fit_power_law(sample_power_law(1000, 1.6, 1.0, np.random.default_rng(0)))
    p, err = fit.params["p"], fit.errors["p"]
    assert abs(p - 1.6) < 0.05
    assert abs(p - 1.6) < 2 * err
    # the bootstrap error agrees with the asymptotic one, (p - 1)/sqrt(n) = 0.0199
    assert abs(err / ((p - 1) / np.sqrt(1000)) - 1) < 0.15


def test_bootstrap_errors_cover_the_truth_68_percent_of_the_time():
    # 400 independent samples of 1000 masses: |p - 1.6| < bootstrap sigma should hold with
    # probability 0.683 (binomial sd 0.023); measured 0.685 with 100 resamples each
    inside = 0
    for s in range(400):
        fit = fit_power_law(sample_power_law(1000, 1.6, 1.0, np.random.default_rng(100 + s)), bootstrap=100, seed=s)
        inside += abs(fit.params["p"] - 1.6) < fit.errors["p"]
    assert abs(inside / 400 - 0.683) < 3 * 0.023, inside / 400


def test_information_criterion_chooses_the_right_model():
    rng = np.random.default_rng(7)
    pure = fit_mass_function(sample_power_law(1000, 1.6, 1.0, rng), bootstrap=20)
    assert pure["preferred"] == "power-law"
    # truncated sample (p = 1.3, M_e = 30 M_min; Abod et al. 2019's form): measured
    # p = 1.334 +- 0.039, M_e = 31.5 +- 3.5 with 200 resamples; BIC lower by 215
    cut = fit_mass_function(_truncated_sample(2000, 1.3, 30.0, np.random.default_rng(7)), bootstrap=50)
    assert cut["preferred"] == "truncated-power-law"
    fit = cut["truncated-power-law"]
    assert abs(fit.params["p"] - 1.3) < 2 * fit.errors["p"] and abs(fit.params["M_e"] / 30 - 1) < 0.25
    assert cut["power-law"].bic - fit.bic > 100


def test_cumulative_numbers_and_model_curves():
    m, n = cumulative_number(np.array([3.0, 1.0, 2.0, 5.0]))
    assert m.tolist() == [5.0, 3.0, 2.0, 1.0] and n.tolist() == [1, 2, 3, 4]
    fit = fit_power_law(np.array([1.0, 2.0, 4.0, 8.0]), bootstrap=0)
    # the MLE p = 1 + n / sum ln(M/M_min) = 1 + 4 / (6 ln 2)
    assert fit.params["p"] == pytest.approx(1 + 4 / (6 * np.log(2)), rel=1e-14)
    assert fit.cumulative(np.array([1.0]))[0] == pytest.approx(4.0)
    tr = fit_truncated_power_law(_truncated_sample(300, 1.5, 10.0, np.random.default_rng(1)), bootstrap=0)
    assert tr.cumulative(np.array([tr.m_min]))[0] == pytest.approx(tr.n, rel=1e-12)


@pytest.mark.parametrize("s, x", [(0.7, 0.3), (0.0, 2.0), (-0.4, 0.05), (-1.0, 1.5), (-1.6, 0.2)])
def test_upper_incomplete_gamma_against_quadrature(s, x):
    from scipy.integrate import quad

    ref = quad(lambda t: t ** (s - 1) * np.exp(-t), x, np.inf, epsabs=0, epsrel=1e-13)[0]
    assert upper_incomplete_gamma(s, x) == pytest.approx(ref, rel=1e-11)
