"""Approximate Riemann solvers for isothermal gas, ``P = c_s^2 rho``.

The variables of a pencil are ``(rho, v_n, v_t1, v_t2)`` (normal velocity first); the fluxes
``(F_rho, F_n, F_t1, F_t2)`` of ``(rho, rho v_n, rho v_t1, rho v_t2)`` are written per face.

hlle
    Harten, Lax & van Leer (1983) with Einfeldt's (1988) wave-speed bounds built from the Roe
    average ``u_roe = (sqrt(rho_L) u_L + sqrt(rho_R) u_R) / (sqrt(rho_L) + sqrt(rho_R))``:
    ``b+ = max(u_roe + c_s, u_R + c_s, 0)``, ``b- = min(u_roe - c_s, u_L - c_s, 0)`` and

    .. math:: F = \\frac{b_+ F_L - b_- F_R + b_+ b_- (U_R - U_L)}{b_+ - b_-}.

hllc
    The isothermal HLLC flux: the isothermal Riemann fan has no density jump at the contact,
    only the transverse velocities jump there. The density and normal-momentum fluxes are the
    HLLE ones (the single intermediate state ``U*`` of HLL), and the transverse momenta are
    carried by the HLL mass flux with the transverse velocity of the upwind side of the
    contact, whose speed ``S* = (rho u)^hll / rho^hll`` has the sign of that mass flux:
    ``F_t = F_rho (v_t,L if F_rho >= 0 else v_t,R)``. This is the B -> 0 limit of the
    isothermal HLLD solver of Mignone (2007, J. Comput. Phys. 225, 1427); unlike HLLE it
    keeps a stationary shear layer (contact) exactly.
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["HLLE", "HLLC", "RIEMANN_SOLVERS", "hll_face", "riemann_fluxes"]

HLLE, HLLC = 0, 1
#: name -> code of the Riemann solvers
RIEMANN_SOLVERS = {"hlle": HLLE, "hllc": HLLC}


@njit(cache=True, error_model="numpy", inline="always")
def hll_face(dl, ul, vl, zl, dr, ur, vr, zr, cs, contact):
    """Fluxes ``(F_rho, F_n, F_t1, F_t2)`` of one face from its left and right primitive states
    (HLLE, or HLLC if ``contact``; module docstring)."""
    cs2 = cs * cs
    sdl = math.sqrt(dl)
    sdr = math.sqrt(dr)
    uroe = (sdl * ul + sdr * ur) / (sdl + sdr)
    bp = max(max(uroe + cs, ur + cs), 0.0)
    bm = min(min(uroe - cs, ul - cs), 0.0)
    # fluxes along the lines x/t = b-, b+ (Einfeldt 1988): F_K - b U_K
    ml = dl * (ul - bm)
    mr = dr * (ur - bp)
    inv = 1.0 / (bp - bm)
    frho = (bp * ml - bm * mr) * inv
    fn = (bp * (ml * ul + cs2 * dl) - bm * (mr * ur + cs2 * dr)) * inv
    if contact:
        upwind = frho >= 0.0
        return frho, fn, frho * (vl if upwind else vr), frho * (zl if upwind else zr)
    return frho, fn, (bp * ml * vl - bm * mr * vr) * inv, (bp * ml * zl - bm * mr * zr) * inv


@njit(cache=True, error_model="numpy")
def _hll(wl, wr, lo, hi, cs, flux, contact, k):
    # views from face lo on: indices i >= 0 let numba skip negative-index handling
    first = lo * k
    d_l, u_l, v_l, z_l = wl[0, first:], wl[1, first:], wl[2, first:], wl[3, first:]
    d_r, u_r, v_r, z_r = wr[0, first:], wr[1, first:], wr[2, first:], wr[3, first:]
    f0, f1, f2, f3 = flux[0, first:], flux[1, first:], flux[2, first:], flux[3, first:]
    for i in range((hi - lo + 1) * k):
        f0[i], f1[i], f2[i], f3[i] = hll_face(d_l[i], u_l[i], v_l[i], z_l[i], d_r[i], u_r[i], v_r[i], z_r[i], cs,
                                              contact)


@njit(cache=True, error_model="numpy")
def riemann_fluxes(wl, wr, lo, hi, cs, solver, flux, k=1):
    """Fluxes at faces ``lo .. hi`` from the face states ``wl``, ``wr`` (see module docstring).

    Parameters
    ----------
    wl, wr
        Primitive face states ``(4, N + 1)``: density, normal and two transverse velocities.
    cs
        Isothermal sound speed.
    solver
        Code from :data:`RIEMANN_SOLVERS`.
    flux
        Output ``(4, N + 1)``.
    k
        ``k`` pencils stored face-major (face ``f`` of pencil ``c`` at ``f k + c``; arrays
        ``(4, (N + 1) k)``), solved together (:func:`~dustygas.grid.reconstruct.reconstruct_faces`).
    """
    if solver == HLLC:
        _hll(wl, wr, lo, hi, cs, flux, True, k)
    else:
        _hll(wl, wr, lo, hi, cs, flux, False, k)
