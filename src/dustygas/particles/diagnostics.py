"""Diagnostics of the particles: Fourier-mode amplitudes for the growth analysis, and per-species
moments (mass, scale height, velocity dispersion) for the history.

For a wave vector ``k`` the complex amplitude of a field ``f = Re(A e^{i k·x})`` is
``A = (2/N) sum f e^{-i k·x}`` over the N cells (or particles). Densities are relative
perturbations, velocities are relative to the background shear ``-q Ω x ŷ``:

* gas (cells of volume ``Π Δx_d``): ``δρ_g/ρ̄_g`` and ``u`` from the cell averages, divided by
  ``Π_d sinc(k_d Δx_d / 2)`` (the cell average of ``e^{i k x}`` is that factor times the
  value at the centre), so they estimate the point-wise amplitudes;
* particles, straight from positions and velocities (no kernel smoothing):
  ``δρ_p/ρ̄_p = 2 Σ m_i e^{-i k·x_i} / Σ m_i`` and the dust velocity
  ``w = 2 Σ m_i v_i e^{-i k·x_i} / Σ m_i - V̄ δρ_p/ρ̄_p`` (the momentum-density mode minus
  the advection of the density mode by the mean velocity ``V̄``: exact to first order).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["MODE_FIELDS", "gas_mode", "particle_mode", "species_statistics"]

#: field names of the mode amplitudes, gas then dust (the order of the linear eigenvectors)
MODE_FIELDS = ("drho_g", "ux", "uy", "uz", "drho_p", "wx", "wy", "wz")


def gas_mode(rho: np.ndarray, vel: tuple[np.ndarray, np.ndarray, np.ndarray], phase: np.ndarray,
             cell_factor: float) -> np.ndarray:
    """``[δρ_g/ρ̄_g, u_x, u_y, u_z]`` amplitudes (complex) from domain fields and ``e^{-i k·x_c}``."""
    n = rho.size
    out = np.empty(4, dtype=np.complex128)
    out[0] = 2.0 * np.sum(rho * phase) / (n * rho.mean())
    for a in range(3):
        out[1 + a] = 2.0 * np.sum(vel[a] * phase) / n
    return out / cell_factor


@njit(cache=True, error_model="numpy")
def particle_mode(pos, vel, mass, kx, ky, kz, shear_y, out) -> None:
    """``out[:4] = [δρ_p/ρ̄_p, w_x, w_y, w_z]`` of the particles for wave vector ``k``.

    ``shear_y`` is added times x to ``v_y`` (``q Ω`` for full velocities: the velocity relative to
    the shear; 0 if they are stored relative to it).
    """
    total = 0.0
    vbar0 = vbar1 = vbar2 = 0.0
    d_re = d_im = 0.0
    p_re = np.zeros(3)
    p_im = np.zeros(3)
    for p in range(pos.shape[1]):
        m = mass[p]
        x, y, z = pos[0, p], pos[1, p], pos[2, p]
        ph = kx * x + ky * y + kz * z
        c = math.cos(ph)
        s = -math.sin(ph)
        v0 = vel[0, p]
        v1 = vel[1, p] + shear_y * x
        v2 = vel[2, p]
        total += m
        vbar0 += m * v0
        vbar1 += m * v1
        vbar2 += m * v2
        d_re += m * c
        d_im += m * s
        p_re[0] += m * v0 * c
        p_im[0] += m * v0 * s
        p_re[1] += m * v1 * c
        p_im[1] += m * v1 * s
        p_re[2] += m * v2 * c
        p_im[2] += m * v2 * s
    d = 2.0 * complex(d_re, d_im) / total
    out[0] = d
    vb = (vbar0 / total, vbar1 / total, vbar2 / total)
    for a in range(3):
        out[1 + a] = 2.0 * complex(p_re[a], p_im[a]) / total - vb[a] * d


def species_statistics(pos, vel, mass, species, nspecies: int, shear_y: float) -> list[dict[str, float]]:
    """Mass-weighted moments of every species (sums in the particles' canonical order).

    ``mass``; ``z_mean``; ``scale_height`` ``H_p = sqrt(<(z - z̄)²>)`` (the standard deviation of
    the vertical positions: for a Gaussian layer its scale height); ``vx``, ``vy`` (mean, ``v_y``
    relative to the shear, ``shear_y`` = ``q Ω`` for full velocities else 0); ``sigma_x``,
    ``sigma_y``, ``sigma_z``: the velocity dispersions about the means.

    >>> z = np.array([-1.0, 1.0]); pos = np.zeros((3, 2)); pos[2] = z
    >>> species_statistics(pos, np.zeros((3, 2)), np.ones(2), np.zeros(2, int), 1, 0.0)[0]["scale_height"]
    1.0
    """
    out = []
    vy = vel[1] + shear_y * pos[0]
    for s in range(nspecies):
        sel = species == s
        m = mass[sel]
        tot = float(m.sum())
        if tot == 0.0:
            out.append({"mass": 0.0})
            continue
        z = pos[2, sel]
        zm = float(m @ z) / tot
        row = {"mass": tot, "z_mean": zm, "scale_height": float(np.sqrt(max(float(m @ (z - zm) ** 2) / tot, 0.0)))}
        for name, v in (("x", vel[0, sel]), ("y", vy[sel]), ("z", vel[2, sel])):
            mean = float(m @ v) / tot
            if name != "z":
                row[f"v{name}"] = mean
            row[f"sigma_{name}"] = float(np.sqrt(max(float(m @ (v - mean) ** 2) / tot, 0.0)))
        out.append(row)
    return out
