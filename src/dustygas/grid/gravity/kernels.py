"""Compiled pieces of the Poisson solve: Green's functions applied mode by mode, the gradient.

Every kernel is a function of arrays and scalars, self-contained (it calls no compiled function
of another module, so numba's per-file cache check is enough), parallel over independent
outputs and therefore bit-identical for any thread count.
"""

from __future__ import annotations

import math

from numba import njit, prange

__all__ = ["apply_periodic_green", "apply_sheet_green", "vacuum_columns", "multiply_phase", "gradient"]


@njit(cache=True, parallel=True, error_model="numpy")
def apply_periodic_green(a, kx, ky, kz, four_pi_G) -> None:
    """``a *= -4πG / (k_x² + k_y² + k_z²)`` in place (the spectral Poisson solve, periodic axes).

    ``a`` ``(nkz, my, mx)`` complex; ``kx`` ``(my, mx)``, ``ky`` ``(my,)``, ``kz`` ``(nkz,)``
    wavenumbers, NaN marking a mode that is set to zero (a Nyquist mode); ``k = 0`` is set to
    zero too (the mean density does not gravitate: Jeans' swindle).
    """
    nkz, my, mx = a.shape
    for c in prange(nkz):
        kz2 = kz[c] * kz[c]
        for j in range(my):
            ky2 = ky[j] * ky[j] + kz2
            for i in range(mx):
                k2 = kx[j, i] * kx[j, i] + ky2
                if k2 > 0.0 and math.isfinite(k2):
                    a[c, j, i] *= -four_pi_G / k2
                else:
                    a[c, j, i] = 0.0


@njit(cache=True, parallel=True, error_model="numpy")
def apply_sheet_green(a, kx, ky, four_pi_G, thin) -> None:
    """One layer ``a`` ``(1, my, mx)``: ``-2πG/k`` (``thin``: a razor-thin sheet of surface
    density ``a``, potential in its plane) or ``-4πG/k²`` (a field uniform along z)."""
    _, my, mx = a.shape
    for j in prange(my):
        for i in range(mx):
            k2 = kx[j, i] * kx[j, i] + ky[j] * ky[j]
            if k2 > 0.0 and math.isfinite(k2):
                if thin:
                    a[0, j, i] *= -0.5 * four_pi_G / math.sqrt(k2)
                else:
                    a[0, j, i] *= -four_pi_G / k2
            else:
                a[0, j, i] = 0.0


@njit(cache=True, parallel=True, error_model="numpy")
def vacuum_columns(rho, kx, ky, dz, four_pi_G, start, out) -> None:
    """Vertical solve of every horizontal mode with vacuum above and below the box.

    ``rho`` ``(nz, my, mx)`` complex, horizontally transformed density of ``nz`` consecutive
    layers, the only ones holding mass; ``out`` ``(n, my, mx)`` receives the potential at ``n``
    consecutive layers, the first density layer being its layer ``start`` (``out`` may reach
    beyond the box: the potential outside, where the density is zero). With ``k = sqrt(k_x² + k_y²)`` the mode
    obeys ``Φ'' - k² Φ = 4πG ρ`` with ``Φ -> 0`` (``k > 0``) or ``|Φ|`` growing no faster than
    ``|z|`` (``k = 0``) at infinity: ``Φ(z) = ∫ g_k(z - z') ρ(z') dz'`` with
    ``g_k = -2πG e^{-k|z|}/k`` and ``g_0 = 2πG |z|``. The density is taken constant across each
    cell, so the kernel is ``g_k`` averaged over the source cell (exact for such a density):

    * ``k > 0``: ``-(2πG/k) (2/k)(1 - e^{-kΔ/2})`` for the cell itself, and
      ``-(2πG/k) e^{-k|m|Δ} (2/k) sinh(kΔ/2)`` ``m`` cells away;
    * ``k = 0``: ``2πG Δ/4 · Δ`` and ``2πG |m| Δ · Δ``.

    Both sums are done in ``O(nz)`` per mode -- the exponential kernel by two recursive
    sweeps, ``L_k = e^{-kΔ}(L_{k-1} + ρ_{k-1})`` and its mirror, the linear one by running sums
    -- which is the convolution that domain doubling (Hockney & Eastwood 1981, §6-5) computes
    with FFTs of twice the length, without the doubled transform.
    """
    nz, my, mx = rho.shape
    n = out.shape[0]
    g = start
    half = 0.5 * four_pi_G
    for j in prange(my):
        for i in range(mx):
            k = math.sqrt(kx[j, i] * kx[j, i] + ky[j] * ky[j])
            if not math.isfinite(k):
                for c in range(n):
                    out[c, j, i] = 0.0
                continue
            if k == 0.0:
                # Φ_c = 2πG Δ² [ρ_c/4 + Σ_{c'} |c - c'| ρ_{c'}]; running sums of ρ and c' ρ
                s0 = 0j
                s1 = 0j
                t0 = 0j
                t1 = 0j
                for c in range(nz):
                    t0 += rho[c, j, i]
                    t1 += c * rho[c, j, i]
                # t*: sums over c' > c (start: all); s*: over c' < c
                for cc in range(n):
                    c = cc - g
                    own = 0j
                    if 0 <= c < nz:
                        own = rho[c, j, i]
                        t0 -= own
                        t1 -= c * own
                    acc = 0.25 * own + (c * s0 - s1) + (t1 - c * t0)
                    out[cc, j, i] = half * dz * dz * acc
                    if 0 <= c < nz:
                        s0 += own
                        s1 += c * own
                continue
            r = math.exp(-k * dz)
            self_w = 2.0 * (1.0 - math.exp(-0.5 * k * dz)) / k
            other_w = 2.0 * math.sinh(0.5 * k * dz) / k
            scale = -half / k
            # left sweep: L_c = Σ_{c' < c} r^{c-c'} ρ_{c'}
            left = 0j
            for cc in range(n):
                c = cc - g
                own = rho[c, j, i] if 0 <= c < nz else 0j
                out[cc, j, i] = scale * (self_w * own + other_w * left)
                left = r * (left + own)
            right = 0j
            for cc in range(n - 1, -1, -1):
                c = cc - g
                own = rho[c, j, i] if 0 <= c < nz else 0j
                out[cc, j, i] += scale * other_w * right
                right = r * (right + own)


@njit(cache=True, parallel=True, error_model="numpy")
def multiply_phase(src, phase, out) -> None:
    """``out[k, j, i] = src[k, j, i] phase[j, i]`` for the rows ``j`` of ``phase``, 0 in the rows
    of ``out`` beyond (the sheared-frame phase of the y modes, and the dropped Nyquist row)."""
    layers, rows, nx = out.shape
    my = phase.shape[0]
    for k in prange(layers):
        for j in range(rows):
            if j < my:
                for i in range(nx):
                    out[k, j, i] = src[k, j, i] * phase[j, i]
            else:
                for i in range(nx):
                    out[k, j, i] = 0.0


@njit(inline="always")
def _value(phi, x_lo, x_hi, k, j, i, nx, ox):
    """``Φ`` at column ``i`` (may lie beyond the radial faces) of row ``j``, layer ``k``."""
    g = x_lo.shape[2]
    if g > 0:
        if i < 0:
            return x_lo[k, j, g + i]
        if i >= nx:
            return x_hi[k, j, i - nx]
        return phi[k, j, i]
    return phi[k, j, i + ox]


@njit(inline="always")
def _neighbour(j, d, n, offset, periodic, active, reach):
    """Array index of the cell ``d`` away from cell ``j`` along an axis (wrapped if periodic,
    else into the exterior layers); the cell itself along an inactive axis or beyond ``reach``."""
    if not active or abs(d) > reach:
        return j + offset
    if periodic:
        return (j + d) % n
    return j + d + offset


@njit(cache=True, parallel=True, error_model="numpy")
def gradient(phi, x_lo, x_hi, offsets, periodic, active, spacing, order, out) -> None:
    """``out = -∇Φ`` ``(3, nz, ny, nx)`` by centred differences of second or fourth order.

    ``phi`` holds the potential of the cells, with ``offsets[a]`` exterior layers before them
    along axis ``a`` (x, y, z) where the axis is not periodic (``periodic[a]``: wrap instead);
    along x, when ``x_lo``/``x_hi`` ``(layers, rows, g)`` are not empty, they hold the ``g``
    columns beyond the inner/outer face (the sheared images) and ``phi`` has none. Inactive
    axes (``active[a]`` false) get 0. Second order: ``(Φ_{i+1} - Φ_{i-1}) / 2Δ``; fourth:
    ``(8(Φ_{i+1} - Φ_{i-1}) - (Φ_{i+2} - Φ_{i-2})) / 12Δ``.
    """
    _, nz, ny, nx = out.shape
    four = order == 4
    c1, c2 = (2.0 / 3.0, -1.0 / 12.0) if four else (0.5, 0.0)
    reach = 2 if four else 1
    ox, oy, oz = offsets
    ax = (1.0 / spacing[0]) if active[0] else 0.0
    ay = (1.0 / spacing[1]) if active[1] else 0.0
    az = (1.0 / spacing[2]) if active[2] else 0.0
    for k in prange(nz):
        kk = k + oz
        # neighbour layers (wrapped, or exterior layers); an inactive axis reads its own layer
        zm2 = _neighbour(k, -2, nz, oz, periodic[2], active[2], reach)
        zm1 = _neighbour(k, -1, nz, oz, periodic[2], active[2], reach)
        zp1 = _neighbour(k, 1, nz, oz, periodic[2], active[2], reach)
        zp2 = _neighbour(k, 2, nz, oz, periodic[2], active[2], reach)
        for j in range(ny):
            jj = j + oy
            ym2 = _neighbour(j, -2, ny, oy, periodic[1], active[1], reach)
            ym1 = _neighbour(j, -1, ny, oy, periodic[1], active[1], reach)
            yp1 = _neighbour(j, 1, ny, oy, periodic[1], active[1], reach)
            yp2 = _neighbour(j, 2, ny, oy, periodic[1], active[1], reach)
            row = phi[kk, jj]
            for i in range(nx):
                ii = i + ox
                if not active[0]:
                    fx = 0.0
                elif reach <= i < nx - reach:
                    fx = c1 * (row[ii + 1] - row[ii - 1])
                    if four:
                        fx += c2 * (row[ii + 2] - row[ii - 2])
                else:
                    fx = c1 * (_value(phi, x_lo, x_hi, kk, jj, i + 1, nx, ox)
                               - _value(phi, x_lo, x_hi, kk, jj, i - 1, nx, ox))
                    if four:
                        fx += c2 * (_value(phi, x_lo, x_hi, kk, jj, i + 2, nx, ox)
                                    - _value(phi, x_lo, x_hi, kk, jj, i - 2, nx, ox))
                fy = c1 * (phi[kk, yp1, ii] - phi[kk, ym1, ii])
                fz = c1 * (phi[zp1, jj, ii] - phi[zm1, jj, ii])
                if four:
                    fy += c2 * (phi[kk, yp2, ii] - phi[kk, ym2, ii])
                    fz += c2 * (phi[zp2, jj, ii] - phi[zm2, jj, ii])
                out[0, k, j, i] = -fx * ax
                out[1, k, j, i] = -fy * ay
                out[2, k, j, i] = -fz * az
