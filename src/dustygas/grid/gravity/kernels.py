"""Compiled pieces of the Poisson solve: Green's functions applied mode by mode, the gradient.

Every kernel is a function of arrays and scalars, self-contained (it calls no compiled function
of another module, so numba's per-file cache check is enough), parallel over independent
outputs and therefore bit-identical for any thread count.
"""

from __future__ import annotations

import math

from numba import njit, prange

__all__ = ["apply_periodic_green", "apply_sheet_green", "vacuum_columns", "gradient"]


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
def vacuum_columns(rho, kx, ky, dz, four_pi_G, g, out) -> None:
    """Vertical solve of every horizontal mode with vacuum above and below the box.

    ``rho`` ``(nz, my, mx)`` complex, horizontally transformed density; ``out``
    ``(nz + 2g, my, mx)`` receives the potential at the ``nz`` cell centres and at ``g`` cells
    outside each vertical face (density zero there). With ``k = sqrt(k_x² + k_y²)`` the mode
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
    n = nz + 2 * g
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
def gradient(phi, gx, gy, gz, dx, dy, dz, order, out) -> None:
    """``out = -∇Φ`` ``(3, nz, ny, nx)`` by centred differences of second or fourth order.

    ``phi`` ``(nz + 2gz, ny + 2gy, nx + 2gx)`` holds the potential with ``g*`` ghost layers on
    each side of the active axes (``g* = 0``: inactive, component 0). Second order:
    ``(Φ_{i+1} - Φ_{i-1}) / 2Δ``; fourth: ``(8(Φ_{i+1} - Φ_{i-1}) - (Φ_{i+2} - Φ_{i-2})) / 12Δ``.
    """
    _, nz, ny, nx = out.shape
    if order == 4:
        c1, c2 = 2.0 / 3.0, -1.0 / 12.0
    else:
        c1, c2 = 0.5, 0.0
    ax, ay, az = 1.0 / dx, 1.0 / dy, 1.0 / dz
    for k in prange(nz):
        kk = k + gz
        for j in range(ny):
            jj = j + gy
            for i in range(nx):
                ii = i + gx
                fx = fy = fz = 0.0
                if gx > 0:
                    fx = c1 * (phi[kk, jj, ii + 1] - phi[kk, jj, ii - 1])
                    if c2 != 0.0:
                        fx += c2 * (phi[kk, jj, ii + 2] - phi[kk, jj, ii - 2])
                if gy > 0:
                    fy = c1 * (phi[kk, jj + 1, ii] - phi[kk, jj - 1, ii])
                    if c2 != 0.0:
                        fy += c2 * (phi[kk, jj + 2, ii] - phi[kk, jj - 2, ii])
                if gz > 0:
                    fz = c1 * (phi[kk + 1, jj, ii] - phi[kk - 1, jj, ii])
                    if c2 != 0.0:
                        fz += c2 * (phi[kk + 2, jj, ii] - phi[kk - 2, jj, ii])
                out[0, k, j, i] = -fx * ax
                out[1, k, j, i] = -fy * ay
                out[2, k, j, i] = -fz * az
