"""Density summation with self-consistent smoothing lengths (thesis eq. 3.1; Price 2012, Sect. 2.3).

The density of particle :math:`a` is the kernel-weighted sum over its neighbours (thesis eq. 3.1),

.. math:: \\rho_a = \\sum_b m_b W(r_{ab}, h_a),

and the smoothing length is tied to it by :math:`\\rho_a h_a^d = m_a h_{\\rm fact}^d`
(Springel & Hernquist 2002; Price & Monaghan 2007). Both hold at once when :math:`h_a` is a root of

.. math:: F(h) = m_a (h_{\\rm fact}/h)^d - \\sum_b m_b W(r_{ab}, h),

which is found per particle by Newton-Raphson with :math:`F'(h) = -d\\,\\rho_a\\Omega_a/h`, kept
inside a bracket and falling back to bisection when a Newton step leaves it. The by-product

.. math:: \\Omega_a = 1 + \\frac{h_a}{d\\,\\rho_a}\\sum_b m_b \\frac{\\partial W_{ab}(h_a)}{\\partial h_a}

is the grad-h correction (the :math:`\\Omega_a` of thesis eq. 3.4; :math:`f_a = 1/\\Omega_a` in
thesis eq. 3.3). Densities are reported as :math:`\\rho_a = m_a (h_{\\rm fact}/h_a)^d` at the
converged :math:`h_a`, which equals the sum to :math:`O(\\text{tol}^2)`.

:func:`gasoline2_correction` computes the alternative :math:`f_a` of Wadsley, Keller & Quinn
(2017), :math:`f_a = \\sum_b (m_b/\\rho_a) r_{ab}^2 f'(q_{ab}) / \\sum_b (m_b/\\rho_b) r_{ab}^2 f'(q_{ab})`
with :math:`q_{ab} = r_{ab}/h_a`, for the GASOLINE2 force of thesis eqs. 3.2-3.3.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from .kernels import kernel_shape
from .neighbours import minimum_image
from .workshare import CHUNK, WORKERS, new_counter, next_chunk

__all__ = ["H_CONVERGED", "H_NEEDS_NEIGHBOURS", "H_NOT_CONVERGED", "solve_smoothing_lengths",
           "solve_one_smoothing_length", "row_buffers", "gasoline2_correction", "DENSITY_CHUNK"]

H_CONVERGED = 0
H_NEEDS_NEIGHBOURS = 1  # the root lies beyond the radius the neighbour list is complete for
H_NOT_CONVERGED = 2

#: particles per work item of the parallel density solve (each allocates its scratch rows once)
DENSITY_CHUNK = 64


@njit(parallel=True, cache=True)
def solve_smoothing_lengths(pos, mass, h, index, count, h_search, shape, norm, radius, ndim, hfact,
                            length, periodic, tol, maxiter, rho, omega, status, iterations):
    """Solve :math:`\\rho_a h_a^d = m_a h_{\\rm fact}^d` with :math:`\\rho_a` from eq. 3.1, per particle.

    ``h`` holds the initial guesses on entry and the solutions on exit; ``rho``, ``omega``,
    ``status`` (``H_*`` codes) and ``iterations`` are outputs. The neighbour list must be complete
    for ``h_search`` (every neighbour with :math:`r < R h^{\\rm search}_a`).
    """
    n = pos.shape[0]
    cap = index.shape[1]
    flat = index.reshape(n * cap)  # rows read at offsets: no row view (and no reference count) per particle
    nchunk = (n + DENSITY_CHUNK - 1) // DENSITY_CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        c = next_chunk(counter)
        while c < nchunk:
            a0, a1 = c * DENSITY_CHUNK, min(n, (c + 1) * DENSITY_CHUNK)
            r, m = row_buffers(count, a0, a1)
            for a in range(a0, a1):
                h[a], rho[a], omega[a], status[a], iterations[a] = solve_one_smoothing_length(
                    pos[a, 0], pos[a, 1], pos[a, 2], mass[a], h[a], h_search[a], flat, a * cap, count[a], pos,
                    mass, shape, norm, ndim, hfact, length, periodic, tol, maxiter, r, m)
            c = next_chunk(counter)


@njit(inline="always")
def row_buffers(count, a0, a1):
    """Scratch ``(r, m)`` for the longest of the rows ``count[a0:a1]`` (one allocation per chunk of
    particles, not per particle: allocations inside a parallel region serialise the threads)."""
    longest = 0
    for a in range(a0, a1):
        longest = max(longest, count[a])
    return np.empty(longest), np.empty(longest)


@njit(inline="always")
def solve_one_smoothing_length(xa, ya, za, ma, h_guess, h_search, index, start, n_row, pos, mass, shape, norm, ndim,
                               hfact, length, periodic, tol, maxiter, r, m):
    """Newton-Raphson with bisection fallback for one particle at ``(xa, ya, za)`` of mass ``ma``
    whose neighbours are ``pos[index[start:start + n_row]]`` (complete within :math:`R h_{\\rm search}`;
    ``index`` one-dimensional, read in place: a row view per particle would count references to the
    shared table atomically, a cache line that two threads then fight over).

    ``r``, ``m``: scratch arrays of at least ``n_row`` entries (:func:`row_buffers`). Returns
    ``(h, rho, omega, status, iterations)`` (module docstring); shared by
    :func:`solve_smoothing_lengths` and the active-particle kernels of individual time steps.
    """
    f0 = kernel_shape(shape, 0.0)[0]
    target = ma * hfact**ndim
    h_lo = 0.0
    h_hi = h_search
    hi_known = False  # F(h_hi) < 0 established by an evaluation
    ha = min(h_guess, h_hi)
    st = H_NOT_CONVERGED
    om = 1.0
    it = 0
    # the distances and masses of the row, gathered once for every iteration
    for k in range(n_row):
        b = index[start + k]
        dx = minimum_image(xa - pos[b, 0], length[0], periodic[0])
        dy = minimum_image(ya - pos[b, 1], length[1], periodic[1])
        dz = minimum_image(za - pos[b, 2], length[2], periodic[2])
        r[k] = np.sqrt(dx * dx + dy * dy + dz * dz)
        m[k] = mass[b]
    while it < maxiter:
        it += 1
        hinv = 1.0 / ha
        hinv_d = hinv**ndim
        wsum = ma * f0
        dwsum = ma * ndim * f0
        for k in range(n_row):
            q = r[k] * hinv
            f, df = kernel_shape(shape, q)  # zero beyond the support: no branch
            wsum += m[k] * f
            dwsum += m[k] * (ndim * f + q * df)
        rho_sum = norm * hinv_d * wsum
        drho_dh = -norm * hinv_d * hinv * dwsum
        rho_h = target * hinv_d
        fval = rho_h - rho_sum
        om = 1.0 + ha * drho_dh / (ndim * rho_sum)
        dfdh = -ndim * rho_h * hinv - drho_dh
        if fval > 0.0:
            h_lo = ha
        else:
            h_hi = ha
            hi_known = True
        if fval > 0.0 and ha >= h_search:
            st = H_NEEDS_NEIGHBOURS
            break
        h_new = ha - fval / dfdh if dfdh < 0.0 else -1.0
        converged = abs(h_new - ha) < tol * ha
        if not converged and not (h_lo < h_new < h_hi):
            if h_new >= h_hi and not hi_known:
                h_new = h_hi  # look at the edge of the list first
            else:
                h_new = 0.5 * (h_lo + h_hi)  # bisection
            converged = h_hi - h_lo < tol * ha
        ha = h_new
        if converged:
            st = H_CONVERGED
            break
    return ha, target / ha**ndim, om, st, it


@njit(parallel=True, cache=True)
def gasoline2_correction(pos, mass, h, rho, index, count, shape, radius, length, periodic, f_out):
    """:math:`f_a` of Wadsley et al. (2017) for the geometric-density-average force (eq. 3.3)."""
    n = pos.shape[0]
    r2max = radius * radius
    n_items = n
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for a in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                xa, ya, za = pos[a, 0], pos[a, 1], pos[a, 2]
                hinv = 1.0 / h[a]
                num = 0.0
                den = 0.0
                for k in range(count[a]):
                    b = index[a, k]
                    dx = minimum_image(xa - pos[b, 0], length[0], periodic[0])
                    dy = minimum_image(ya - pos[b, 1], length[1], periodic[1])
                    dz = minimum_image(za - pos[b, 2], length[2], periodic[2])
                    r2 = dx * dx + dy * dy + dz * dz
                    q2 = r2 * hinv * hinv
                    if q2 < r2max:
                        w = mass[b] * r2 * kernel_shape(shape, np.sqrt(q2))[1]
                        num += w / rho[a]
                        den += w / rho[b]
                f_out[a] = num / den if den != 0.0 else 1.0
            chunk = next_chunk(counter)
