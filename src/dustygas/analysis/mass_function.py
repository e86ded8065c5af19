"""The planetesimal mass function: N(>M), maximum-likelihood fits, bootstrap errors, model choice.

Models of the differential mass function above ``M_min`` (the smallest mass fitted):

* power law, ``dN/dM ∝ M^{-p}`` (Simon et al. 2016, ApJ 822, 55, p ≈ 1.6; the thesis's q),
  normalised ``f(M) = (p - 1) M_min^{p-1} M^{-p}``. Its maximum-likelihood slope is closed-form
  (Clauset, Shalizi & Newman 2009, SIAM Rev. 51, 661, eq. 3.1), used here with the factor
  that removes its bias, ``(n - 1)/n`` (``(n - 2)/n`` when ``M_min`` is the sample's smallest mass):

  .. math:: \\hat p = 1 + (n - 1) \\Big/ \\sum_i \\ln(M_i / M_{\\min});

* exponentially truncated power law, ``dN/dM ∝ M^{-p} e^{-M/M_e}`` (Abod et al. 2019, ApJ 883,
  192: p ≈ 1.3 with a truncation mass), normalised by
  ``Z = ∫_{M_min}^∞ M^{-p} e^{-M/M_e} dM = M_e^{1-p} Γ(1 - p, M_min/M_e)``; fitted by maximising
  the likelihood over ``(p, ln M_e)``.

Errors: the standard deviation of the fitted parameters over bootstrap resamples of the masses
(Efron 1979). Model choice: the Akaike (AIC = 2k - 2 ln L) and Bayesian (BIC = k ln n -
2 ln L) information criteria; the model with the smaller value of the chosen one is preferred
(Li, Youdin & Simon 2019, ApJ 885, 69 compare models this way).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

__all__ = ["cumulative_number", "upper_incomplete_gamma", "MassFunctionFit", "fit_power_law",
           "fit_truncated_power_law", "fit_mass_function", "sample_power_law"]


def cumulative_number(masses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Masses in decreasing order and ``N(≥M)`` at each: ``(M_sorted, 1, 2, ..., n)``.

    >>> cumulative_number(np.array([2.0, 5.0, 1.0]))
    (array([5., 2., 1.]), array([1, 2, 3]))
    """
    m = np.sort(np.asarray(masses, dtype=np.float64))[::-1]
    return m, np.arange(1, m.size + 1)


def upper_incomplete_gamma(s: float, x: float) -> float:
    """``Γ(s, x) = ∫_x^∞ t^{s-1} e^{-t} dt`` for any real ``s`` and ``x > 0``.

    ``s > 0`` from scipy's regularised function; below, the recurrence
    ``Γ(s, x) = (Γ(s + 1, x) - x^s e^{-x}) / s`` (``Γ(0, x) = E_1(x)``).

    >>> round(upper_incomplete_gamma(-0.5, 1.0), 12)  # 2 (e^-1 - sqrt(pi) erfc(1))
    0.178147711782
    """
    from scipy import special  # imported here: scipy.special costs every process 0.15 s at start-up

    if s > 0:
        return float(special.gammaincc(s, x) * special.gamma(s))
    if s == 0:
        return float(special.exp1(x))
    return (upper_incomplete_gamma(s + 1.0, x) - x**s * math.exp(-x)) / s


@dataclass
class MassFunctionFit:
    """One model fitted to ``n`` masses above ``m_min``."""

    model: str  # "power-law" or "truncated-power-law"
    params: dict[str, float]  # p, and M_e for the truncated law
    errors: dict[str, float]  # bootstrap standard deviations
    log_likelihood: float
    n: int
    m_min: float
    aic: float = field(init=False)
    bic: float = field(init=False)

    def __post_init__(self) -> None:
        k = len(self.params)
        self.aic = 2 * k - 2 * self.log_likelihood
        self.bic = k * math.log(self.n) - 2 * self.log_likelihood

    def to_dict(self) -> dict:
        return asdict(self)

    def cumulative(self, m: np.ndarray) -> np.ndarray:
        """The model's ``N(≥M)`` for the fitted sample (``n`` at ``M_min``)."""
        m = np.asarray(m, dtype=np.float64)
        p = self.params["p"]
        if self.model == "power-law":
            return self.n * (m / self.m_min) ** (1.0 - p)
        me = self.params["M_e"]
        z = upper_incomplete_gamma(1.0 - p, self.m_min / me)
        return self.n * np.array([upper_incomplete_gamma(1.0 - p, v / me) for v in np.atleast_1d(m)]).reshape(m.shape) / z


def _power_law_slope(logs: np.ndarray, fitted_min: bool = False) -> np.ndarray:
    """Unbiased closed-form slope from ``ln(M/M_min)`` along the last axis.

    ``S = Σ ln(M_i/M_min)`` of ``n`` masses above a known ``M_min`` is a Gamma(n, p - 1)
    variable, so the MLE ``1 + n/S`` is biased high by ``(p - 1)/(n - 1)``; ``1 + (n - 1)/S``
    is unbiased (Clauset et al. 2009, §3.1). With ``M_min`` the sample's own smallest mass
    (``fitted_min``) one term is zero and the other ``n - 1`` are again independent
    (memorylessness of the exponential ``ln(M/M_min)``): ``1 + (n - 2)/S``.
    """
    n = logs.shape[-1]
    return 1.0 + (n - (2.0 if fitted_min else 1.0)) / logs.sum(axis=-1)


def _select(masses, m_min):
    m = np.asarray(masses, dtype=np.float64)
    if m.ndim != 1 or m.size == 0 or not np.all(m > 0):
        raise ValueError("masses must be a non-empty 1-D array of positive values")
    m_min = float(m.min()) if m_min is None else float(m_min)
    m = m[m >= m_min]
    if m.size < 3:
        raise ValueError(f"{m.size} masses at or above m_min = {m_min:g}: a fit needs at least 3")
    return m, m_min


def fit_power_law(masses: np.ndarray, m_min: float | None = None, bootstrap: int = 200,
                  seed: int = 0) -> MassFunctionFit:
    """Maximum-likelihood power law above ``m_min`` (default: the smallest mass)."""
    fitted_min = m_min is None
    m, m_min = _select(masses, m_min)
    logs = np.log(m / m_min)
    p = float(_power_law_slope(logs, fitted_min))
    n = m.size
    lnl = n * math.log((p - 1.0) / m_min) - p * logs.sum()
    rng = np.random.default_rng(seed)
    boot = (_power_law_slope(logs[rng.integers(0, n, (bootstrap, n))], fitted_min) if bootstrap
            else np.array([np.nan]))
    return MassFunctionFit("power-law", {"p": p}, {"p": float(np.std(boot, ddof=1)) if bootstrap > 1 else math.nan},
                           lnl, n, m_min)


def _truncated_nll(theta, logs_sum, m_sum, n, m_min):
    p, ln_me = theta
    me = math.exp(ln_me)
    z = me ** (1.0 - p) * upper_incomplete_gamma(1.0 - p, m_min / me)
    if not (z > 0 and math.isfinite(z)):
        return math.inf
    return p * logs_sum + m_sum / me + n * math.log(z)


def _truncated_mle(m: np.ndarray, m_min: float, start: tuple[float, float]) -> tuple[float, float, float]:
    from scipy import optimize  # imported here: scipy.optimize costs every process 0.2 s at start-up

    logs_sum, m_sum, n = float(np.log(m).sum()), float(m.sum()), m.size
    best = optimize.minimize(_truncated_nll, np.array(start), args=(logs_sum, m_sum, n, m_min), method="Nelder-Mead",
                             options={"xatol": 1e-8, "fatol": 1e-10, "maxiter": 4000})
    p, ln_me = best.x
    return float(p), float(math.exp(ln_me)), -float(best.fun)


def fit_truncated_power_law(masses: np.ndarray, m_min: float | None = None, bootstrap: int = 200,
                            seed: int = 0) -> MassFunctionFit:
    """Maximum-likelihood exponentially truncated power law above ``m_min``."""
    m, m_min = _select(masses, m_min)
    p0 = float(_power_law_slope(np.log(m / m_min)))
    p, me, lnl = _truncated_mle(m, m_min, (max(p0 - 0.2, 0.5), math.log(m.max())))
    rng = np.random.default_rng(seed)
    boot = np.array([_truncated_mle(m[rng.integers(0, m.size, m.size)], m_min, (p, math.log(me)))[:2]
                     for _ in range(bootstrap)]) if bootstrap > 1 else np.full((2, 2), np.nan)
    errors = {"p": float(np.std(boot[:, 0], ddof=1)), "M_e": float(np.std(boot[:, 1], ddof=1))}
    return MassFunctionFit("truncated-power-law", {"p": p, "M_e": me}, errors, lnl, m.size, m_min)


def fit_mass_function(masses: np.ndarray, m_min: float | None = None, bootstrap: int = 200, seed: int = 0,
                      criterion: str = "bic") -> dict:
    """Both models, and the one the information criterion (``"aic"`` or ``"bic"``) prefers.

    Returns ``{"power-law": fit, "truncated-power-law": fit, "preferred": name, "criterion": ...}``.
    """
    if criterion not in ("aic", "bic"):
        raise ValueError(f"criterion {criterion!r}: choose aic or bic")
    fits = {f.model: f for f in (fit_power_law(masses, m_min, bootstrap, seed),
                                 fit_truncated_power_law(masses, m_min, bootstrap, seed))}
    preferred = min(fits, key=lambda k: getattr(fits[k], criterion))
    return {**fits, "preferred": preferred, "criterion": criterion}


def sample_power_law(n: int, p: float, m_min: float, rng: np.random.Generator) -> np.ndarray:
    """``n`` masses from ``dN/dM ∝ M^{-p}`` above ``m_min``: ``M = M_min u^{-1/(p-1)}``."""
    return m_min * rng.uniform(0.0, 1.0, n) ** (-1.0 / (p - 1.0))
