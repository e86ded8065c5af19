"""Streaming instability of a dust-size distribution (polydisperse SI).

A size distribution is represented by N dust species (τ_j, μ_j) of the operator of
:mod:`dustygas.linear.operator`. For grains in the Epstein regime τ_s ∝ a, so a number density
n(a) ∝ a^β (MRN: β = −3.5; Mathis, Rumpl & Nordsieck 1977) puts the dust-to-gas ratio per unit
stopping time

.. math:: σ(τ) = μ\\,\\frac{τ^{3+β}}{\\int_{τ_{min}}^{τ_{max}} τ^{3+β} dτ}, \\qquad τ_{min} ≤ τ ≤ τ_{max}

(total dust-to-gas ratio μ). Three discretisations (``rule``):

``"bins"``
    N logarithmically spaced bins of [τ_min, τ_max]; species j carries the exact mass of its
    bin, μ_j = ∫_bin σ dτ, at the bin's logarithmic centre τ_j = (τ_{j-½} τ_{j+½})^{1/2}: a
    discrete N-species system as in Krapp et al. (2019) and Zhu & Yang (2021);
``"gauss"``
    a quadrature of the continuous distribution: Gauss–Legendre nodes in u = τ^{4+β}, where
    σ dτ ∝ du is uniform, so the weights are the plain Gauss weights (exponentially convergent
    for the smooth integrands of a growing mode);
``"chebyshev-trapezoid"``
    the direct method of psitools (McNally, Lovascio & Paardekooper 2021): τ_j at the roots of
    the Chebyshev polynomial T_N mapped to [τ_min, τ_max], trapezoidal weights between them and
    σ normalised on [τ_1, τ_N].

The background drift is either the NSH drift of the N species (``background="discrete"``: what N
species of particles have; Benítez-Llambay, Krapp & Pessah 2019, eqs. 79-84) or that of the
continuous distribution (``"continuum"``: moments A, B as integrals,
:func:`dustygas.physics.nsh_velocities_moments`; psitools uses it for its quadrature rules).
Both converge to the polydisperse limit N → ∞ (Paardekooper, McNally & Lovascio 2020).

Examples
--------
Benítez-Llambay, Krapp & Pessah (2019) Table 4, "linC" (two species, consistent drag):

>>> s, f = fastest_growth(taus=[0.0425, 0.1], mu=[1.0, 0.5], kx=50.0, kz=50.0)
>>> f"{s:.10f}", f"{f:.10f}"
('0.3027262829', '0.3242790653')
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..errors import UserError
from ..physics import nsh_velocities_moments, nsh_velocities_multi
from .operator import DRAG_MODELS, StreamingParams, drag_code, fill_operator, kernel_array

__all__ = ["PowerLawSizes", "RULES", "species", "fastest_growth", "distribution_growth"]

RULES = ("bins", "gauss", "chebyshev-trapezoid")


@dataclass(frozen=True, kw_only=True)
class PowerLawSizes:
    """Power-law size distribution n(a) ∝ a^β between τ_min and τ_max (module docstring).

    Parameters
    ----------
    mu
        Total dust-to-gas density ratio (> 0).
    taus_min, taus_max
        Range of stopping times, 0 < τ_min < τ_max.
    beta
        Power of the size distribution (MRN: −3.5); β = −4 is allowed (σ ∝ 1/τ).
    """

    mu: float
    taus_min: float
    taus_max: float
    beta: float = -3.5

    def __post_init__(self) -> None:
        for name in ("mu", "taus_min", "taus_max", "beta"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or isinstance(v, bool) or not math.isfinite(v):
                raise UserError(f"{name} = {v!r}: expected a finite number")
        if not self.mu > 0:
            raise UserError(f"mu = {self.mu!r}: the total dust-to-gas ratio must be > 0")
        if not 0 < self.taus_min < self.taus_max:
            raise UserError(f"taus_min = {self.taus_min!r}, taus_max = {self.taus_max!r}: expected 0 < min < max")

    @property
    def p(self) -> float:
        """Exponent of the cumulative mass, ∫σ dτ ∝ τ^p, p = 4 + β."""
        return 4.0 + self.beta

    def cumulative(self, taus: ArrayLike, lo: float | None = None, hi: float | None = None) -> np.ndarray:
        """Fraction of the mass of [lo, hi] (default the whole range) below ``taus``, times μ."""
        lo = self.taus_min if lo is None else lo
        hi = self.taus_max if hi is None else hi
        t = np.clip(np.asarray(taus, dtype=np.float64), lo, hi)
        if self.p == 0.0:
            return self.mu * np.log(t / lo) / math.log(hi / lo)
        return self.mu * (t**self.p - lo**self.p) / (hi**self.p - lo**self.p)

    def density(self, taus: ArrayLike, lo: float | None = None, hi: float | None = None) -> np.ndarray:
        """σ(τ), normalised on [lo, hi] (default the whole range); 0 outside."""
        lo = self.taus_min if lo is None else lo
        hi = self.taus_max if hi is None else hi
        t = np.asarray(taus, dtype=np.float64)
        norm = math.log(hi / lo) if self.p == 0.0 else (hi**self.p - lo**self.p) / self.p
        inside = (t >= lo) & (t <= hi)
        return np.where(inside, self.mu * np.where(inside, t, 1.0) ** (self.p - 1.0) / norm, 0.0)

    def moments(self, lo: float | None = None, hi: float | None = None) -> tuple[float, float]:
        """(A, B) = ∫σ/(1+τ²) dτ, ∫στ/(1+τ²) dτ (the background's moments), by adaptive quadrature
        in ln τ (relative accuracy 1e-13)."""
        lo = self.taus_min if lo is None else lo
        hi = self.taus_max if hi is None else hi

        def f(x, power):
            t = math.exp(x)
            return float(self.density(t, lo, hi)) * t * t**power / (1.0 + t * t)

        from scipy import integrate  # imported here: scipy.integrate costs every process 0.2 s at start-up

        kw = dict(limit=200, epsabs=0.0, epsrel=1e-13)
        a = integrate.quad(f, math.log(lo), math.log(hi), args=(0,), **kw)[0]
        b = integrate.quad(f, math.log(lo), math.log(hi), args=(1,), **kw)[0]
        return a, b


def species(dist: PowerLawSizes, n: int, rule: str = "bins") -> tuple[np.ndarray, np.ndarray, tuple[float, float]]:
    """(τ_j, μ_j, (lo, hi)) of an N-species representation of ``dist`` (module docstring).

    ``(lo, hi)`` is the range on which the distribution is normalised (the whole range, except
    for ``"chebyshev-trapezoid"``: its outermost nodes).

    >>> t, m, _ = species(PowerLawSizes(mu=1.0, taus_min=1e-4, taus_max=0.1), 3)
    >>> [f"{v:.4g}" for v in t], f"{m.sum():.12f}"
    (['0.0003162', '0.003162', '0.03162'], '1.000000000000')
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise UserError(f"n = {n!r}: the number of species must be a positive integer")
    lo, hi = dist.taus_min, dist.taus_max
    if rule == "bins":
        edges = np.logspace(math.log10(lo), math.log10(hi), n + 1)
        edges[0], edges[-1] = lo, hi
        taus = np.sqrt(edges[:-1] * edges[1:])
        mu = np.diff(dist.cumulative(edges))
        return taus, mu, (lo, hi)
    if rule == "gauss":
        if dist.p == 0.0:
            raise UserError("rule 'gauss' needs beta != -4 (the mass coordinate tau^(4+beta))")
        x, w = np.polynomial.legendre.leggauss(n)
        ua, ub = lo**dist.p, hi**dist.p
        u = 0.5 * (x + 1.0) * (ub - ua) + ua
        return u ** (1.0 / dist.p), dist.mu * 0.5 * w, (lo, hi)
    if rule == "chebyshev-trapezoid":
        if n < 2:
            raise UserError("rule 'chebyshev-trapezoid' needs n >= 2")
        i = np.arange(1, n + 1)
        taus = (0.5 - 0.5 * np.cos((2 * i - 1) * math.pi / (2.0 * n))) * (hi - lo) + lo
        d = np.diff(taus)
        w = np.zeros(n)
        w[:-1] += 0.5 * d
        w[1:] += 0.5 * d
        a, b = taus[0], taus[-1]
        return taus, dist.density(taus, a, b) * w, (a, b)
    raise UserError(f"rule {rule!r}: choose one of {', '.join(RULES)}")


def _fastest(L: np.ndarray) -> tuple[float, float]:
    lam = np.linalg.eigvals(L)
    i = int(np.argmax(lam.real))
    return float(lam[i].real), float(-lam[i].imag)  # (Im ω, Re ω) with ω = i λ


def fastest_growth(*, taus: ArrayLike, mu: ArrayLike, kx: float, kz: float, Pi: float = 0.05,
                   drag: str = "consistent", background: tuple[float, float] | None = None) -> tuple[float, float]:
    """(growth rate, frequency) of the fastest mode of N species (LAPACK, any N).

    ``background = (A, B)`` replaces the species' own NSH moments (module docstring, the
    ``"continuum"`` background); None: the NSH drift of these N species.
    """
    p = StreamingParams(taus=list(np.atleast_1d(taus)), mu=list(np.atleast_1d(mu)), kx=kx, kz=kz, Pi=Pi, drag=drag)
    T, M = p.taus_array, p.mu_array
    eq = nsh_velocities_multi(T, M) if background is None else nsh_velocities_moments(*background, T)
    gamma, beta = DRAG_MODELS[list(DRAG_MODELS)[drag_code(drag)]]
    L = np.zeros((p.size, p.size), dtype=np.complex128)
    G = np.zeros((3, 3 + 4 * p.nspecies), dtype=np.complex128)
    fill_operator(L, G, p.kx, 0.0, p.kz, p.cs, float(eq.gas_vx), float(eq.gas_vy), kernel_array(T), kernel_array(M),
                  kernel_array(eq.dust_vx), kernel_array(eq.dust_vy), np.zeros(p.nspecies), gamma, beta)
    return _fastest(L)


def distribution_growth(dist: PowerLawSizes, *, n: int, kx: float, kz: float, rule: str = "bins",
                        background: str | None = None, Pi: float = 0.05, drag: str = "epstein") -> tuple[float, float]:
    """(growth rate, frequency) of the fastest mode of ``dist`` represented by ``n`` species.

    ``background``: ``"discrete"`` (default for ``"bins"``) or ``"continuum"`` (default for the
    quadrature rules). ``drag`` defaults to Epstein drag at fixed grain size (t_s ∝ 1/ρ_g), the
    drag law of a size distribution of real grains and of psitools.

    Examples
    --------
    MRN, μ = 3, τ_s ∈ [1e-8, 0.1], K = (80, 100), 129 Chebyshev nodes: psitools' direct solver
    (test_direct.py) prints ω = 0.5512363292041821 + 0.11242857992948893 i:

    >>> s, f = distribution_growth(PowerLawSizes(mu=3.0, taus_min=1e-8, taus_max=0.1), n=129, kx=80.0, kz=100.0,
    ...                            rule="chebyshev-trapezoid")
    >>> f"{s:.10f}", f"{f:.10f}"
    ('0.1124285799', '0.5512363292')
    """
    taus, mu, (lo, hi) = species(dist, n, rule)
    background = background or ("discrete" if rule == "bins" else "continuum")
    if background not in ("discrete", "continuum"):
        raise UserError(f"background {background!r}: 'discrete' or 'continuum'")
    moments = dist.moments(lo, hi) if background == "continuum" else None
    return fastest_growth(taus=taus, mu=mu, kx=kx, kz=kz, Pi=Pi, drag=drag, background=moments)
