"""Pair sums of two-fluid dust: velocity gradients and the gas-dust drag (thesis eqs. 3.18-3.19).

For a particle :math:`a` of one species and a neighbour :math:`j` of the other, with
:math:`\\hat{\\mathbf r} = (\\mathbf r_j - \\mathbf r_a)/r` pointing from :math:`a` to :math:`j` and the
relative velocity :math:`\\mathbf w = \\mathbf v_j - \\mathbf v_a`, the drag acceleration of :math:`a` is

.. math::

    \\text{projected (eq. 3.19):}\\quad \\dot{\\mathbf v}_a = \\nu\\sum_j m_j\\,\\kappa_{aj}\\,(\\mathbf w^*\\cdot\\hat{\\mathbf r})\\,\\hat{\\mathbf r}\\,\\bar D_{aj},
    \\qquad
    \\text{non-projected (eq. 3.18):}\\quad \\dot{\\mathbf v}_a = \\sum_j m_j\\,\\kappa_{aj}\\,\\mathbf w^*\\,\\bar W_{aj},

with :math:`\\kappa_{aj} = K_{aj}/(\\rho_a\\rho_j)` (:mod:`~dustygas.sph.dust.drag_law`), :math:`\\nu` the number
of dimensions, the double-hump kernel :math:`D` (Laibe & Price 2012a) and
:math:`\\bar D_{aj} = [D(r, h_a) + D(r, h_j)]/2` (likewise :math:`\\bar W`). The same expression, evaluated
from either side, gives the gas and the dust accelerations, which are therefore equal and opposite
pair by pair (momentum is conserved to round-off; the projected form also conserves angular
momentum). **Thesis eq. 3.18 prints the factor** :math:`\\nu` **in the non-projected sum too**; since
:math:`\\int W dV = 1` (while :math:`\\nu\\int\\hat r\\hat r D\\, dV = I`) that would make the drag
:math:`\\nu` times too strong, so it is omitted here. The gas is heated at the rate
:math:`\\dot u_a = \\nu\\sum_j m_j\\kappa_{aj}(\\mathbf w^*\\cdot\\hat{\\mathbf r})(\\mathbf w\\cdot\\hat{\\mathbf r})\\bar D_{aj}`
(or :math:`\\sum_j m_j\\kappa_{aj}\\mathbf w^*\\cdot\\mathbf w\\,\\bar W_{aj}`), the kinetic energy the pair loses.

**Reconstruction** (Price & Laibe 2020, against the over-damping of strongly coupled waves at
:math:`h > c_s t_s`): :math:`\\mathbf w^*` is the relative velocity at the midpoint of the pair, each
velocity extrapolated from its particle with its own SPH gradient,
:math:`\\mathbf v^*_a = \\mathbf v_a + \\tfrac12 (\\mathbf r_j - \\mathbf r_a)\\cdot\\nabla\\mathbf v_a` and
:math:`\\mathbf v^*_j = \\mathbf v_j - \\tfrac12(\\mathbf r_j - \\mathbf r_a)\\cdot\\nabla\\mathbf v_j`, i.e.
:math:`w^* = w - \\tfrac12(\\sigma_a + \\sigma_j)` with the changes :math:`\\sigma = r\\,\\hat{\\mathbf r}\\cdot\\nabla\\mathbf v\\cdot\\hat{\\mathbf r}`
of the projected velocity across the pair (componentwise for the non-projected form). With the
van Leer monotonised-central limiter :math:`\\tfrac12(\\sigma_a + \\sigma_j)` is replaced by
:math:`{\\rm sign}(\\sigma_a)\\min(|\\sigma_a+\\sigma_j|/2, 2|\\sigma_a|, 2|\\sigma_j|)` when :math:`\\sigma_a\\sigma_j > 0`
and by 0 otherwise, so that nothing is extrapolated across a shock.

**Pairwise exponential (implicit) drag** (after Lorén-Aguilar & Bate 2014, 2015): over a step
:math:`\\Delta t`, an isolated pair obeys :math:`\\dot w = -w/t_{aj} + \\Delta f` with the pair's mixture
stopping time :math:`t_{aj} = 1/((\\rho_a+\\rho_j)\\kappa_{aj})` and the difference :math:`\\Delta f` of the
other accelerations; the drag uses the step average of its exact solution,
:math:`\\bar w = w^*\\phi(x) + \\Delta f\\,t_{aj}[1 - \\phi(x)]`, :math:`\\phi(x) = (1 - e^{-x})/x`,
:math:`x = \\Delta t/t_{aj}`, which tends to the explicit :math:`w^*` for :math:`\\Delta t \\ll t_{aj}` and to
the terminal drift :math:`\\Delta f\\,t_{aj}` for :math:`\\Delta t \\gg t_{aj}`, so no :math:`\\Delta t \\le t_s` limit applies.

All loops gather per particle (no scatter, no atomic sums): deterministic for any thread count. A
neighbour's columns are read in place (``table[j, _X]``), never through a row view ``table[j]``: numba
counts the references of a view's parent with an atomic add and subtract, one cache line shared by
all threads (measured: see benchmarks/RESULTS.md, 2026-12-03).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from ..kernels import kernel_dshape, kernel_shape
from ..neighbours import minimum_image
from ..workshare import CHUNK, WORKERS, new_counter, next_chunk

__all__ = ["pack", "velocity_gradient", "drag_pass", "drag_pair", "mc_limiter", "KERNEL_AVERAGE", "KERNEL_OWN",
           "KERNEL_OTHER"]


def pack(*columns) -> np.ndarray:
    """One row per particle of the given per-particle scalars and ``(N, k)`` arrays, so that a
    neighbour's data share cache lines in the pair loops."""
    cols = [np.asarray(c, dtype=np.float64).reshape(len(c), -1) for c in columns]
    return np.ascontiguousarray(np.concatenate(cols, axis=1))


@njit(parallel=True, cache=True)
def velocity_gradient(packed, h, rho, omega, index, count, shape, norm, ndim, length, periodic, grad):
    """:math:`(\\nabla\\mathbf v_a)_{kj} = \\partial_j v_k = -\\frac{1}{\\Omega_a\\rho_a}\\sum_b m_b (v_a - v_b)_k\\,\\partial_j W_{ab}(h_a)`,
    stored row-major in ``grad[a, 3 k + j]``; ``packed`` rows are ``(x, y, z, vx, vy, vz, m)`` (:func:`pack`)."""
    n_items = packed.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for a in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                hinv = 1.0 / h[a]
                xa, ya, za = packed[a, 0], packed[a, 1], packed[a, 2]
                vxa, vya, vza = packed[a, 3], packed[a, 4], packed[a, 5]
                g0 = g1 = g2 = g3 = g4 = g5 = g6 = g7 = g8 = 0.0
                for kk in range(count[a]):
                    b = index[a, kk]  # the neighbour's columns read in place (module docstring)
                    dx = minimum_image(xa - packed[b, 0], length[0], periodic[0])
                    dy = minimum_image(ya - packed[b, 1], length[1], periodic[1])
                    dz = minimum_image(za - packed[b, 2], length[2], periodic[2])
                    r = math.sqrt(dx * dx + dy * dy + dz * dz)
                    f = packed[b, 6] * kernel_dshape(shape, r * hinv) / r
                    ux = (vxa - packed[b, 3]) * f
                    uy = (vya - packed[b, 4]) * f
                    uz = (vza - packed[b, 5]) * f
                    g0 += ux * dx
                    g1 += ux * dy
                    g2 += ux * dz
                    g3 += uy * dx
                    g4 += uy * dy
                    g5 += uy * dz
                    g6 += uz * dx
                    g7 += uz * dy
                    g8 += uz * dz
                c = -norm * hinv ** (ndim + 1) / (omega[a] * rho[a])
                grad[a, 0] = c * g0
                grad[a, 1] = c * g1
                grad[a, 2] = c * g2
                grad[a, 3] = c * g3
                grad[a, 4] = c * g4
                grad[a, 5] = c * g5
                grad[a, 6] = c * g6
                grad[a, 7] = c * g7
                grad[a, 8] = c * g8
            chunk = next_chunk(counter)


@njit(cache=True)
def mc_limiter(sl: float, sr: float) -> float:
    """Van Leer's monotonised-central average of two slopes (0 if they differ in sign)."""
    if sl * sr <= 0.0:
        return 0.0
    s = min(abs(0.5 * (sl + sr)), 2.0 * abs(sl), 2.0 * abs(sr))
    return s if sl > 0.0 else -s


@njit(cache=True)
def _project(grad, a, rx, ry, rz):
    """:math:`\\hat{\\mathbf r}\\cdot\\nabla\\mathbf v_a\\cdot\\hat{\\mathbf r}` (even in :math:`\\hat{\\mathbf r}`, bit for bit)."""
    return (rx * (grad[a, 0] * rx + grad[a, 1] * ry + grad[a, 2] * rz)
            + ry * (grad[a, 3] * rx + grad[a, 4] * ry + grad[a, 5] * rz)
            + rz * (grad[a, 6] * rx + grad[a, 7] * ry + grad[a, 8] * rz))


@njit(cache=True)
def _phi(x):
    """:math:`(1 - e^{-x})/x`, accurate near 0."""
    if x < 1e-6:
        return 1.0 - 0.5 * x
    return -math.expm1(-x) / x


# columns of the packed drag tables (:func:`pack`)
_X, _Y, _Z, _VX, _VY, _VZ, _M, _HINV, _WN, _RHO, _K, _FX, _FY, _FZ = range(14)


#: which smoothing lengths the drag kernel of a pair uses: the average of both (Laibe & Price 2012a),
#: or only the gas particle's, :math:`D_{ai}(h_a)` as thesis eq. 3.19 writes it (``a`` or ``j`` the gas)
KERNEL_AVERAGE, KERNEL_OWN, KERNEL_OTHER = 0, 1, 2


@njit(parallel=True, cache=True)
def drag_pass(table, grad, otable, ograd, index, count, shape, ndim, length, periodic,
              c_const, projected, recon, limit, dt_implicit, heat, acc, dudt, tmin, kernel_side=KERNEL_AVERAGE,
              gas_slope=0):
    """Drag on every particle of one species from its neighbours of the other (module docstring).

    ``table``/``otable`` hold one row per particle: position, velocity, mass, :math:`1/h`, the kernel
    normalisation over :math:`h^d` (:math:`C^D_d/h^d` projected, :math:`C_d/h^d` otherwise), density,
    the drag factor :math:`k` with :math:`\\kappa_{aj} = k_a k_j + c/(\\rho_a+\\rho_j)` and the non-drag
    acceleration (read only for the implicit average). ``recon``: reconstruct with the velocity
    gradients ``grad``/``ograd`` (``limit``: MC limiter); ``dt_implicit > 0``: the pairwise
    exponential average over that step. Overwrites ``acc``, ``dudt`` (heating, if ``heat``) and
    ``tmin``, the smallest pair stopping time seen by each particle. ``kernel_side`` selects the
    smoothing lengths of the drag kernel (``KERNEL_*``); ``gas_slope`` (1: the ``table`` species is the
    gas, 2: the other one) replaces the midpoint reconstruction by the gas velocity extrapolated to the
    dust particle with the gas's own gradient, :math:`w^* = w - \\sigma_{\\rm gas}`.
    """
    n_items = table.shape[0]
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for a in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                ax = 0.0
                ay = 0.0
                az = 0.0
                du = 0.0
                tm = math.inf
                for kk in range(count[a]):
                    j = index[a, kk]
                    fx, fy, fz, dq, tpair = drag_pair(table, grad, otable, ograd, a, j, shape, ndim, length, periodic,
                                                      c_const, projected, recon, limit, dt_implicit, heat, kernel_side,
                                                      gas_slope)
                    if tpair == math.inf:
                        continue
                    tm = min(tm, tpair)
                    ax += fx
                    ay += fy
                    az += fz
                    du += dq
                acc[a, 0] = ax
                acc[a, 1] = ay
                acc[a, 2] = az
                dudt[a] = du
                tmin[a] = tm
            chunk = next_chunk(counter)


@njit(inline="always")
def drag_pair(table, grad, otable, ograd, a, j, shape, ndim, length, periodic, c_const, projected, recon, limit,
              dt_implicit, heat, kernel_side, gas_slope=0):
    """Drag acceleration of particle ``a`` (row of ``table``) from ``j`` (row of ``otable``), the heating
    it causes (if ``heat``) and the pair stopping time: ``(ax, ay, az, du, t_pair)``, with
    ``t_pair = inf`` for a pair that does not interact. Evaluated from either side it gives equal and
    opposite momentum changes (module docstring); arguments as :func:`drag_pass`."""
    dx = minimum_image(otable[j, _X] - table[a, _X], length[0], periodic[0])
    dy = minimum_image(otable[j, _Y] - table[a, _Y], length[1], periodic[1])
    dz = minimum_image(otable[j, _Z] - table[a, _Z], length[2], periodic[2])
    r2 = dx * dx + dy * dy + dz * dz
    if r2 == 0.0:
        return 0.0, 0.0, 0.0, 0.0, math.inf  # coincident particles: D = 0 and no direction
    r = math.sqrt(r2)
    rinv = 1.0 / r
    rx, ry, rz = dx * rinv, dy * rinv, dz * rinv
    qa = r * table[a, _HINV]
    qj = r * otable[j, _HINV]
    fa = kernel_shape(shape, qa)[0]
    fj = kernel_shape(shape, qj)[0]
    if kernel_side == KERNEL_OWN:
        fj = 0.0
    elif kernel_side == KERNEL_OTHER:
        fa = 0.0
    if fa == 0.0 and fj == 0.0:
        return 0.0, 0.0, 0.0, 0.0, math.inf
    half = 0.5 if kernel_side == KERNEL_AVERAGE else 1.0
    rho_sum = table[a, _RHO] + otable[j, _RHO]
    kappa = table[a, _K] * otable[j, _K] + c_const / rho_sum
    tpair = 1.0 / (rho_sum * kappa)
    wx = otable[j, _VX] - table[a, _VX]
    wy = otable[j, _VY] - table[a, _VY]
    wz = otable[j, _VZ] - table[a, _VZ]
    du = 0.0
    if projected:
        weight = float(ndim) * half * (qa * qa * fa * table[a, _WN] + qj * qj * fj * otable[j, _WN])
        w = wx * rx + wy * ry + wz * rz
        ws = w
        if recon:
            sa = r * _project(grad, a, rx, ry, rz)
            sj = r * _project(ograd, j, rx, ry, rz)
            if gas_slope == 1:
                ws = w - sa
            elif gas_slope == 2:
                ws = w - sj
            else:
                ws = w - (mc_limiter(sa, sj) if limit else 0.5 * (sa + sj))
        if dt_implicit > 0.0:
            df = ((otable[j, _FX] - table[a, _FX]) * rx + (otable[j, _FY] - table[a, _FY]) * ry
                  + (otable[j, _FZ] - table[a, _FZ]) * rz)
            ph = _phi(dt_implicit / tpair)
            ws = ws * ph + df * tpair * (1.0 - ph)
        f = otable[j, _M] * kappa * ws * weight
        if heat:
            du = f * w
        return f * rx, f * ry, f * rz, du, tpair
    weight = half * (fa * table[a, _WN] + fj * otable[j, _WN])
    wsx, wsy, wsz = wx, wy, wz
    if recon:
        wsx -= _component_slope(grad, ograd, a, j, 0, r, rx, ry, rz, limit, gas_slope)
        wsy -= _component_slope(grad, ograd, a, j, 1, r, rx, ry, rz, limit, gas_slope)
        wsz -= _component_slope(grad, ograd, a, j, 2, r, rx, ry, rz, limit, gas_slope)
    if dt_implicit > 0.0:
        ph = _phi(dt_implicit / tpair)
        c2 = tpair * (1.0 - ph)
        wsx = wsx * ph + (otable[j, _FX] - table[a, _FX]) * c2
        wsy = wsy * ph + (otable[j, _FY] - table[a, _FY]) * c2
        wsz = wsz * ph + (otable[j, _FZ] - table[a, _FZ]) * c2
    f = otable[j, _M] * kappa * weight
    if heat:
        du = f * (wsx * wx + wsy * wy + wsz * wz)
    return f * wsx, f * wsy, f * wsz, du, tpair


@njit(cache=True)
def _component_slope(grad, ograd, a, j, k, r, rx, ry, rz, limit, gas_slope=0):
    """Limited (or averaged) change of velocity component ``k`` across the pair (odd in :math:`\\hat{\\mathbf r}`);
    with ``gas_slope`` the whole change along the gas particle's gradient (:func:`drag_pass`)."""
    sa = r * (rx * grad[a, 3 * k] + ry * grad[a, 3 * k + 1] + rz * grad[a, 3 * k + 2])
    sj = r * (rx * ograd[j, 3 * k] + ry * ograd[j, 3 * k + 1] + rz * ograd[j, 3 * k + 2])
    if gas_slope == 1:
        return sa
    if gas_slope == 2:
        return sj
    return mc_limiter(sa, sj) if limit else 0.5 * (sa + sj)
