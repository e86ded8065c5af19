"""Drag between gas and particles over one step, exact in the stiff limit (thesis eqs. 4.22-4.25).

A particle of stopping time ``t_s`` obeys, per velocity component,

.. math:: \\dot v = g + \\frac{\\tilde u(t) - v}{t_s},

where ``g`` is every other acceleration (rotating frame, pressure-gradient forcing, fields;
held at its time-centred value over the step, :mod:`dustygas.particles.terms`) and
``ũ(t)`` is the gas velocity at the particle *as the gas itself evolves during the step*.
Treating ``ũ`` as constant (Bai & Stone 2010a) is second order but unstable for stiff,
heavy dust (``h ≫ t_s`` with ``ε = ρ_p/ρ_g > 1``): the particles relax to the old gas velocity
and the gas then receives ``ε`` times their impulse. Here, as in Yang & Johansen (2016), each
cell solves the *local* drag problem of its gas and its dust exactly and the particles see the
resulting gas velocity.

The local problem (:func:`cell_model`)
--------------------------------------
In a cell with gas density ``ρ_g``, velocity ``u^n`` and non-drag acceleration ``f_g`` (from the
gas predictor), and dust species ``s`` of density ``ρ_s``, mean velocity ``V_s`` and mean
non-drag acceleration ``f_s`` (from the deposit of the particles), the linear system

.. math:: \\dot u = f_g + \\sum_s \\frac{ε_s (V_s - u)}{T_s}, \\qquad
          \\dot V_s = f_s - \\frac{V_s - u}{T_s}\\qquad (ε_s = ρ_s/ρ_g)

is the star-graph Laplacian ``D`` of the drag couplings ``ρ_s/T_s``, symmetric with respect to
the masses ``M``. Its modes: the centre of mass (rate 0) and ``N`` relaxation modes whose
rates ``μ_k`` are the roots of ``1 + Σ_s ε_s/(1 - μ T_s) = 0`` (one between each pair of
consecutive ``1/T_s`` and one above the largest; ``(1 + ε)/T`` for one species), with gas
component 1 and species components ``1/(1 - μ_k T_s)``. With the forcing held fixed, the gas
velocity is exactly

.. math:: \\tilde u(t) = u^n + A t + \\sum_k B_k (e^{-μ_k t} - 1),

``A`` the mixture's acceleration ``(ρ_g f_g + Σ ρ_s f_s)/(ρ_g + Σ ρ_s)`` and ``B_k`` the gas
part of mode ``k`` of the initial state less its forced equilibrium. A particle of species ``s``
then integrates its own equation exactly (:func:`relax`):

.. math:: v(h) = v e^{-h/t_s} + (1 - e^{-h/t_s})(u^n + g t_s) + A\\,[h - t_s(1 - e^{-h/t_s})] + R_s,
          \\qquad R_s = \\sum_k B_k\\left[\\frac{e^{-μ_k h} - e^{-h/T_s}}{1 - μ_k T_s} - (1 - e^{-h/T_s})\\right],

with ``R_s`` computed per cell (the particles gather ``u^n``, ``A`` and their species' ``R_s``
with their weights), and the gas receives minus the drag impulse ``v(h) - v - g h`` of every
particle. Properties: total momentum is conserved to round-off (the gas receives exactly what
the particles lose); a uniform dusty box relaxes at exactly ``(1 + ε)/t_s`` for any step (one
species; any number of species with their exact modes); a steady drift (NSH) is a fixed
point, since its forced equilibrium has ``A = 0`` and ``B_k = 0`` (in the velocities relative to
the shear, in which the engine solves it); for ``h ≪ t_s`` the gas
velocity the particle sees changes at the gas's true rate ``f_g + Σ ε_s (V_s - u)/T_s``, so
the coupling stays second order. The particle's own deviation from the mean of its species
relaxes at its own rate ``1/t_s``; only the mean is coupled implicitly to the gas.

Without back-reaction ``B_k = 0`` and ``A = f_g``: the particle relaxes to a gas velocity that
changes linearly at the gas's own rate.

The vertical oscillator (:func:`oscillator_step`)
-------------------------------------------------
With vertical gravity ``-Ω² z`` the vertical motion is the damped oscillator
``z̈ = -ż/t_s - Ω²z + ...`` (thesis eq. 4.18's source), integrated exactly over the step
(matrix exponential of ``[[0, 1], [-Ω², -1/t_s]]`` through its eigenvalues, written so that
it is accurate for any ``Ω t_s`` from stiff to free, including critical damping).
"""

from __future__ import annotations

import cmath
import math
from typing import NamedTuple

import numpy as np
from numba import njit

from ..physics.drag import epstein_stopping_time_scalar

__all__ = ["FIXED", "EPSTEIN", "DRAG_LAWS", "Species", "stopping_time", "relax", "oscillator_step", "relaxation_rates",
           "relaxation_modes",
           "cell_model", "cell_model_decay", "step_decay", "one_species_mode",
           "one_species_response", "MAX_SPECIES", "N_COEF", "step_coefficients", "relax_row"]

FIXED, EPSTEIN = 0, 1
#: name -> code of the stopping-time laws
DRAG_LAWS = {"fixed": FIXED, "epstein": EPSTEIN}
#: most dust species one run may hold (the per-cell work arrays are this long)
MAX_SPECIES = 32
#: a species below this fraction of the gas density in a cell has no drag mode of its own there
#: (its back-reaction is below round-off; its particles respond to the gas like test particles)
NEGLIGIBLE = 1e-30


class Species(NamedTuple):
    """Per-species tables: drag law (:data:`FIXED` or :data:`EPSTEIN`), the stopping time of a
    fixed law, and for Epstein drag the product ``rho_grain s`` (code units) with the gas
    sound speed ``cs`` (thesis eq. 2.6 via :func:`~dustygas.physics.drag.epstein_stopping_time_scalar`)."""

    law: np.ndarray
    t_stop: np.ndarray
    grain: np.ndarray
    cs: float


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def stopping_time(law: int, t_stop: float, grain: float, cs: float, rho: float) -> float:
    """Stopping time of a species with drag ``law`` in gas of density ``rho`` (thesis eq. 2.6)."""
    if law == EPSTEIN:
        return epstein_stopping_time_scalar(grain, 1.0, rho, cs, 1.0)
    return t_stop


@njit(cache=True, error_model="numpy")
def relax(v0: float, ts: float, h: float, u0: float, a: float, g: float, r: float) -> float:
    """Velocity after ``h`` of ``v' = g + (u0 + a t - v)/ts`` from ``v0``, plus the mode response
    ``r`` (module docstring); exact for any ``h/ts``."""
    e = math.exp(-h / ts)
    om = -math.expm1(-h / ts)  # 1 - e without cancellation
    return v0 * e + om * (u0 + g * ts) + a * (h - ts * om) + r


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def relax_row(v0: float, c, row: int, base: int, ts: float, u0: float, a: float, g: float, r: float) -> float:
    """:func:`relax` with its step factors in row ``row`` of the table ``c``,
    ``c[row, base .. base+2] = (e^{-h/ts}, 1 - e^{-h/ts}, h - ts (1 - e^{-h/ts}))`` (a kernel over
    particles reads the table of its species without a view per particle)."""
    return v0 * c[row, base] + c[row, base + 1] * (u0 + g * ts) + a * c[row, base + 2] + r


#: per-species step coefficients: relax factors for h and h/2, then the vertical oscillator's
#: linear map (z, v) <- (z0, v0, beta0, beta1)
N_COEF = 14


@njit(cache=True, error_model="numpy")
def step_coefficients(ts: float, w2: float, h: float, out) -> None:
    """``out[0:6]``: ``e^{-x}, 1 - e^{-x}, x ts - ts (1 - e^{-x})`` for ``x = h/ts`` and ``h/(2 ts)``;
    ``out[6:14]``: the oscillator map ``z = out[6] z0 + out[7] v0 + out[8] β0 + out[9] β1``,
    ``v = out[10] z0 + out[11] v0 + out[12] β0 + out[13] β1`` (:func:`oscillator_step` is
    linear in its four inputs; zeros without gravity). The same for every particle of a
    species of fixed stopping time, so the kernel computes them once per step."""
    for m, hh in enumerate((h, 0.5 * h)):
        e = math.exp(-hh / ts)
        om = -math.expm1(-hh / ts)
        out[3 * m] = e
        out[3 * m + 1] = om
        out[3 * m + 2] = hh - ts * om
    if w2 > 0.0:
        for col in range(4):
            z0 = 1.0 if col == 0 else 0.0
            v0 = 1.0 if col == 1 else 0.0
            b0 = 1.0 if col == 2 else 0.0
            b1 = 1.0 if col == 3 else 0.0
            z, v = oscillator_step(z0, v0, ts, w2, h, b0, b1)
            out[6 + col] = z
            out[10 + col] = v
    else:
        for col in range(8):
            out[6 + col] = 0.0


@njit(cache=True, error_model="numpy")
def _phi(z: complex, k: int) -> complex:
    """``φ_k(z) = (e^z - Σ_{j<k} z^j/j!)/z^k`` for ``k = 1, 2``: the Taylor series
    ``Σ_j z^j/(j+k)!`` where the closed form would cancel."""
    if abs(z) < 0.1 * k * k:
        term = 1.0 + 0j
        for j in range(2, k + 1):
            term /= j
        s = term
        for j in range(1, 16):
            term = term * z / (j + k)
            s += term
        return s
    if k == 1:
        return (cmath.exp(z) - 1.0) / z
    return (cmath.exp(z) - 1.0 - z) / (z * z)


@njit(cache=True, error_model="numpy")
def oscillator_step(z0, v0, ts, w2, h, beta0, beta1):
    """Exact ``(z, v)`` after ``h`` of ``z' = v, v' = -w2 z - v/ts + beta0 + beta1 t``.

    Through the eigenvalues ``λ_{1,2}`` of ``M = [[0, 1], [-w2, -1/ts]]``
    (``λ² + λ/ts + w2 = 0``): ``f(M) = f(λ_2) I + f[λ_1, λ_2] (M - λ_2 I)`` for ``f`` = exp,
    ``φ_1``, ``φ_2``, with the divided differences written without cancellation for real,
    complex and (nearly) equal eigenvalues, λ_2 the fast one:

    .. math:: y(h) = e^{Mh} y_0 + h φ_1(Mh)\\,β_0 \\hat e_v + h^2 φ_2(Mh)\\,β_1 \\hat e_v.
    """
    gam = 0.5 / ts
    disc = gam * gam - w2
    if disc >= 0.0:  # real: λ = -γ ± δ; the slow one -w2/(γ + δ) without cancellation
        dlt = math.sqrt(disc)
        lam2 = complex(-gam - dlt, 0.0)
        lam1 = complex(-w2 / (gam + dlt), 0.0)
        if dlt * h > 1e-8:
            ediv = complex((math.exp(lam1.real * h) - math.exp(lam2.real * h)) / (2.0 * dlt), 0.0)
        else:  # nearly critical: e^{-γh} sinh(δh)/δ
            ediv = complex(math.exp(-gam * h) * h * (1.0 + (dlt * h) ** 2 / 6.0), 0.0)
    else:  # complex pair -γ ± iω
        om = math.sqrt(-disc)
        lam1 = complex(-gam, om)
        lam2 = complex(-gam, -om)
        sw = math.sin(om * h) / om if om * h > 1e-8 else h * (1.0 - (om * h) ** 2 / 6.0)
        ediv = complex(math.exp(-gam * h) * sw, 0.0)
    e2 = cmath.exp(lam2 * h)
    f1_1, f1_2 = _phi(lam1 * h, 1), _phi(lam2 * h, 1)
    f2_1, f2_2 = _phi(lam1 * h, 2), _phi(lam2 * h, 2)
    # divided differences: from (λ F_k)[λ1, λ2] h = F_{k-1}[λ1, λ2] with the product rule,
    # dividing by the fast eigenvalue λ_2
    f1div = (ediv / h - f1_1) / lam2
    f2div = (f1div / h - f2_1) / lam2
    # M - λ2 I; its lower right entry -1/ts - λ2 is λ1 (written so: no cancellation)
    a00, a01, a10, a11 = -lam2, 1.0 + 0j, complex(-w2, 0.0), lam1
    # e^{Mh} y0
    z = e2 * z0 + ediv * (a00 * z0 + a01 * v0)
    v = e2 * v0 + ediv * (a10 * z0 + a11 * v0)
    # forcing along e_v: f(M) e_v = f(λ2) e_v + f[λ1,λ2] (a01, a11)
    c1 = h * beta0
    c2 = h * h * beta1
    z += c1 * f1div * a01 + c2 * f2div * a01
    v += c1 * (f1_2 + f1div * a11) + c2 * (f2_2 + f2div * a11)
    return z.real, v.real


@njit(cache=True, error_model="numpy")
def _pole_distance(t_ref: float, offset: float, t: float) -> float:
    """``1 - μ T`` for ``μ = 1/T_ref + offset``, written so that it has no cancellation near the
    pole ``T = T_ref`` (where it is ``-offset T_ref``)."""
    return (t_ref - t) / t_ref - offset * t


@njit(cache=True, error_model="numpy")
def _secular(offset, t_ref, eps, ts, n):
    """``1 + Σ ε_s/(1 - μ T_s)`` at ``μ = 1/T_ref + offset`` and its derivative in ``offset``."""
    f = 1.0
    df = 0.0
    for s in range(n):
        d = _pole_distance(t_ref, offset, ts[s])
        f += eps[s] / d
        df += eps[s] * ts[s] / (d * d)
    return f, df


@njit(cache=True, error_model="numpy")
def relaxation_modes(eps, ts, n, mu, offset, ref) -> None:
    """The ``n`` relaxation rates ``μ_k`` of the local drag problem (module docstring) into ``mu``,
    each also as ``μ_k = 1/T_{ref_k} + offset_k`` from its nearer pole (``ref`` as float).

    ``eps`` (> 0) and ``ts`` (distinct, sorted by decreasing ``ts``, i.e. increasing ``1/T``):
    root ``k`` lies between ``1/T_k`` and ``1/T_{k+1}`` (the last above ``1/T_{n-1}``); the
    secular function increases from -∞ to +∞ (to 1 on the last interval), so a safeguarded
    Newton iteration on each bracket converges. The root is sought as the offset from the pole
    of the half bracket it lies in: a species of tiny ``ε`` (a cell at the edge of a particle's
    stencil holds 1e-17 of the gas's density) has a root within ``~ε/T`` of its pole, where
    ``1 - μ T`` computed from ``μ`` would be pure round-off (or 0, and the mode vector infinite).
    """
    if n == 1:
        mu[0] = (1.0 + eps[0]) / ts[0]
        offset[0] = eps[0] / ts[0]
        ref[0] = 0.0
        return
    for k in range(n):
        if k + 1 < n:  # between the poles k and k+1: from the nearer one
            half = 0.5 * (ts[k] - ts[k + 1]) / (ts[k] * ts[k + 1])
            f, _ = _secular(half, ts[k], eps, ts, n)
            if f >= 0.0:
                r, lo, hi = k, 0.0, half
            else:
                r, lo, hi = k + 1, -half, 0.0
        else:  # above the last pole: f(mu) <= 1 + sum eps/(1 - mu T) < 0 at mu = (1 + sum eps)/T_min
            tot = 1.0
            for s in range(n):
                tot += eps[s]
            r, lo, hi = k, 0.0, tot / ts[n - 1]
        tr = ts[r]
        x = 0.5 * (lo + hi)
        for _ in range(400):
            f, df = _secular(x, tr, eps, ts, n)
            if abs(f) < 1e-15:
                break
            if f > 0.0:
                hi = x
            else:
                lo = x
            if hi - lo <= 4e-16 * max(abs(lo), abs(hi)):
                break
            step = x - f / df
            x = step if lo < step < hi else 0.5 * (lo + hi)
        mu[k] = 1.0 / tr + x
        offset[k] = x
        ref[k] = r


@njit(cache=True, error_model="numpy")
def relaxation_rates(eps, ts, n, mu) -> None:
    """The ``n`` relaxation rates ``μ_k`` of the local drag problem into ``mu``
    (:func:`relaxation_modes`, same arguments)."""
    relaxation_modes(eps, ts, n, mu, np.empty(n), np.empty(n))


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def _dexp(a: float, b: float) -> float:
    """``(e^{-a} - e^{-b})/(b - a)`` without cancellation (``a, b >= 0``)."""
    lo, d = (a, b - a) if a <= b else (b, a - b)
    if d < 1e-12:
        return math.exp(-lo) * (1.0 - 0.5 * d)
    return math.exp(-lo) * (-math.expm1(-d)) / d


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def _dexp_known(a: float, b: float, e_b: float) -> float:
    """:func:`_dexp` given ``e_b = e^{-b}`` (the same value: ``e^{-b}`` is its factor when ``a >= b``)."""
    if a < b:
        return _dexp(a, b)
    d = a - b
    if d < 1e-12:
        return e_b * (1.0 - 0.5 * d)
    return e_b * (-math.expm1(-d)) / d


@njit(cache=True, error_model="numpy")
def step_decay(h: float, ts, s: int, decay) -> None:
    """``decay[0, s] = e^{-h/T_s}``, ``decay[1, s] = e^{-h/T_s} - 1`` (``expm1``) for species ``s``
    of stopping time ``ts[s]``: the factors of :func:`cell_model_decay` (the same for every cell
    when the stopping time is fixed)."""
    b = h / ts[s]
    decay[0, s] = math.exp(-b)
    decay[1, s] = math.expm1(-b)


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def one_species_mode(rho_g: float, rho_1: float, T: float, h: float, e_b: float, em1_b: float) -> tuple[float, float]:
    """One species in the cell (:func:`cell_model`): ``ε = ρ_1/ρ_g`` and the factor of its one mode
    (rate ``μ = (1 + ε)/T``, components ``(1, -1/ε)``), ``b (e^{-μh} - e^{-b})/(μh - b) + e^{-b} - 1``
    with ``b = h/T``; ``e_b``, ``em1_b``: :func:`step_decay`. Scalars only: a kernel inlines it."""
    eps = rho_1 / rho_g
    mu1 = (1.0 + eps) / T
    b = h / T
    return eps, b * _dexp_known(mu1 * h, b, e_b) + em1_b


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def one_species_response(eps: float, fac: float, T: float, du: float, df: float) -> float:
    """The response ``R`` of one component for one species (:func:`one_species_mode`), from
    ``du = u0 - V`` and ``df = f_g - f_s``: ``c_k = ε du/(1 + ε)``, ``f_k/μ = ε T df/(1 + ε)²``."""
    return eps / (1.0 + eps) * (du - T * df / (1.0 + eps)) * fac


@njit(cache=True, error_model="numpy")
def cell_model(rho_g, u0, f_g, nsp, rho_s, vel_s, acc_s, ts_s, h, out_a, out_r, work, perm, bk) -> None:
    """The local drag problem of one cell (module docstring): writes ``A`` into ``out_a`` (3,) and
    every species' response ``R_s`` into ``out_r`` (nsp, 3).

    ``u0``, ``f_g`` (3,): gas velocity and non-drag acceleration; ``rho_s`` (nsp,), ``vel_s``,
    ``acc_s`` (nsp, 3): dust density, mean velocity and mean non-drag acceleration per species
    (``rho_s = 0``: absent); ``ts_s`` (nsp,): the species' stopping times in this cell;
    scratch: ``work`` (6, nsp) float, ``perm`` (nsp,) int64, ``bk`` (nsp, 3) float.
    """
    decay = np.empty((2, nsp))
    for s in range(nsp):
        step_decay(h, ts_s, s, decay)
    cell_model_decay(rho_g, u0, f_g, nsp, rho_s, vel_s, acc_s, ts_s, h, decay, out_a, out_r, work, perm, bk)


@njit(cache=True, error_model="numpy")
def cell_model_decay(rho_g, u0, f_g, nsp, rho_s, vel_s, acc_s, ts_s, h, decay, out_a, out_r, work, perm, bk) -> None:
    """:func:`cell_model` with the species' decay factors ``decay`` (2, nsp) given
    (:func:`step_decay`): a kernel computes those of fixed stopping times once per step."""
    tot = rho_g
    for c in range(3):
        out_a[c] = rho_g * f_g[c]
    for s in range(nsp):
        if rho_s[s] > 0.0:
            tot += rho_s[s]
            for c in range(3):
                out_a[c] += rho_s[s] * acc_s[s, c]
    for c in range(3):
        out_a[c] /= tot
    for s in range(nsp):
        for c in range(3):
            out_r[s, c] = 0.0
    if tot == rho_g:
        return
    if nsp == 1:
        T = ts_s[0]
        eps, fac = one_species_mode(rho_g, rho_s[0], T, h, decay[0, 0], decay[1, 0])
        for c in range(3):
            out_r[0, c] = one_species_response(eps, fac, T, u0[c] - vel_s[0, c], f_g[c] - acc_s[0, c])
        return
    # group the present species by stopping time (equal times share a pole), sorted by
    # decreasing T: group g has eps_g, T_g; member species map to it
    eps = work[0]
    tg = work[1]
    mu = work[2]
    ng = 0
    group = work[3]  # group index of each species (float storage)
    for s in range(nsp):
        group[s] = -1.0
        if rho_s[s] <= NEGLIGIBLE * rho_g:  # no mode of its own: it responds like the absent species
            continue
        found = -1
        for q in range(ng):
            if abs(tg[q] - ts_s[s]) <= 1e-12 * ts_s[s]:
                found = q
        if found < 0:
            tg[ng] = ts_s[s]
            eps[ng] = 0.0
            found = ng
            ng += 1
        eps[found] += rho_s[s] / rho_g
        group[s] = found
    # sort groups by decreasing T (insertion; few species)
    for q in range(ng):
        perm[q] = q
    for q in range(1, ng):
        v = perm[q]
        r = q - 1
        while r >= 0 and tg[perm[r]] < tg[v]:
            perm[r + 1] = perm[r]
            r -= 1
        perm[r + 1] = v
    es = work[4]
    ts = work[5]
    for q in range(ng):
        es[q] = eps[perm[q]]
        ts[q] = tg[perm[q]]
    offset = work[0]  # eps and tg are copied into es, ts: their rows are free
    ref = work[1]
    relaxation_modes(es, ts, ng, mu, offset, ref)
    for s in range(nsp):  # the sorted group of each present species
        if group[s] >= 0.0:
            for q in range(ng):
                if perm[q] == int(group[s]):
                    group[s] = q
                    break
    # B_k = (gas part of mode k of the state) - (of the forcing)/mu_k, M-orthogonal projections;
    # mode k has gas component 1 and species components 1/d_s, d_s = 1 - mu_k T_s, scaled here by
    # sigma = min(1, |d_s|) so that no component exceeds 1 (a species of tiny eps near its pole)
    for k in range(ng):
        tr = ts[int(ref[k])]
        sigma = 1.0
        for s in range(nsp):
            if group[s] >= 0.0:
                sigma = min(sigma, abs(_pole_distance(tr, offset[k], ts[int(group[s])])))
        norm = rho_g * sigma * sigma
        for c in range(3):
            bk[k, c] = 0.0
        for c in range(3):
            cs = rho_g * sigma * u0[c]
            fs = rho_g * sigma * f_g[c]
            for s in range(nsp):
                if group[s] >= 0.0:
                    e = sigma / _pole_distance(tr, offset[k], ts[int(group[s])])
                    if c == 0:
                        norm += rho_s[s] * e * e
                    cs += rho_s[s] * e * vel_s[s, c]
                    fs += rho_s[s] * e * acc_s[s, c]
            bk[k, c] = cs - fs / mu[k]
        for c in range(3):
            bk[k, c] *= sigma / norm
    # every species' response (absent species too: a particle at the edge of its stencil)
    for s in range(nsp):
        T = ts_s[s]
        b = h / T
        om = -decay[1, s]
        for k in range(ng):
            fac = b * _dexp_known(mu[k] * h, b, decay[0, s]) - om
            for c in range(3):
                out_r[s, c] += bk[k, c] * fac
