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

__all__ = ["HLLE", "HLLC", "RIEMANN_SOLVERS", "riemann_fluxes"]

HLLE, HLLC = 0, 1
#: name -> code of the Riemann solvers
RIEMANN_SOLVERS = {"hlle": HLLE, "hllc": HLLC}


@njit(cache=True, error_model="numpy")
def _hll(wl, wr, lo, hi, cs, flux, contact):
    cs2 = cs * cs
    # views from face lo on: indices i >= 0 let numba skip negative-index handling
    d_l, u_l, v_l, z_l = wl[0, lo:], wl[1, lo:], wl[2, lo:], wl[3, lo:]
    d_r, u_r, v_r, z_r = wr[0, lo:], wr[1, lo:], wr[2, lo:], wr[3, lo:]
    f0, f1, f2, f3 = flux[0, lo:], flux[1, lo:], flux[2, lo:], flux[3, lo:]
    for i in range(hi - lo + 1):
        dl = d_l[i]
        ul = u_l[i]
        dr = d_r[i]
        ur = u_r[i]
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
        f0[i] = frho
        f1[i] = (bp * (ml * ul + cs2 * dl) - bm * (mr * ur + cs2 * dr)) * inv
        if contact:
            upwind = frho >= 0.0
            f2[i] = frho * (v_l[i] if upwind else v_r[i])
            f3[i] = frho * (z_l[i] if upwind else z_r[i])
        else:
            f2[i] = (bp * ml * v_l[i] - bm * mr * v_r[i]) * inv
            f3[i] = (bp * ml * z_l[i] - bm * mr * z_r[i]) * inv


@njit(cache=True, error_model="numpy")
def riemann_fluxes(wl, wr, lo, hi, cs, solver, flux):
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
    """
    if solver == HLLC:
        _hll(wl, wr, lo, hi, cs, flux, True)
    else:
        _hll(wl, wr, lo, hi, cs, flux, False)
