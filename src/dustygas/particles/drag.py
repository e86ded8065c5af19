"""Velocity update of one particle over a step: drag, Coriolis and the other forces.

In the frame of the gas (thesis eq. 4.2c-d written for particles; Bai & Stone 2010a, eq. 5)
a particle of stopping time ``t_s`` obeys

.. math::

    \\dot v_x = c_x v_y + F_x - \\frac{v_x - u_x}{t_s}, \\qquad
    \\dot v_y = -c_y v_x + F_y - \\frac{v_y - u_y}{t_s}, \\qquad
    \\dot v_z = F_z - \\frac{v_z - u_z}{t_s},

with the Coriolis coefficients ``c_x = 2Ω`` and ``c_y = 2Ω`` for full velocities or
``c_y = (2 - q)Ω`` for velocities relative to the shear (orbital advection), and ``F`` every
force per unit mass that does not depend on the velocity (tidal ``2qΩ²x``, vertical gravity
``-Ω²z``, the global pressure gradient ``-2ηv_KΩ x̂`` when it is put on the particles, a
constant settling acceleration), evaluated by the caller at the time-centred position.
``u`` is the gas velocity interpolated at that position (thesis eq. 4.22). Both integrators
hold ``u`` and ``F`` fixed over the step and return the new velocity and the part of the
velocity change due to drag (per unit mass), whose opposite the gas receives (eq. 4.24):

``semi-implicit`` (:func:`kick_semi_implicit`)
    Bai & Stone (2010a, §2.3): Crank-Nicolson in the velocity,
    ``v' - v = h [F + C v̄ - (v̄ - u)/t_s]`` with ``v̄ = (v + v')/2``, a 2×2 linear system
    solved in closed form. Second order, exact for the steady drift (NSH) and stable for any
    ``h/t_s``; for ``h ≫ t_s`` the relative velocity flips sign each step instead of decaying
    (amplification ``(1 - h/2t_s)/(1 + h/2t_s) → -1``).
``exponential`` (:func:`kick_exponential`)
    the exact solution of the linear ODE over the step,
    ``v(h) = v_∞ + e^{Ah}(v - v_∞)`` with ``A = C - I/t_s`` and the terminal velocity
    ``v_∞ = -A^{-1}(F + u/t_s)``; ``e^{Ah} = e^{-h/t_s} R(κh)`` where R is the epicyclic
    rotation with ``κ = sqrt(c_x c_y)``. The drag impulse is ``-(∫v dt - h u)/t_s`` with
    ``∫v dt = v_∞ h + A^{-1}(e^{Ah} - I)(v - v_∞)``. Second order in the variation of ``u``,
    exact for constant ``u`` whatever ``h/t_s`` (L-stable: stiff grains land on ``v_∞``).
"""

from __future__ import annotations

import math

from numba import njit

__all__ = ["SEMI_IMPLICIT", "EXPONENTIAL", "DRAG_INTEGRATORS", "kick", "kick_semi_implicit", "kick_exponential"]

SEMI_IMPLICIT, EXPONENTIAL = 0, 1
#: name -> code of the drag integrators
DRAG_INTEGRATORS = {"semi-implicit": SEMI_IMPLICIT, "exponential": EXPONENTIAL}


@njit(cache=True, error_model="numpy")
def kick_semi_implicit(vx, vy, vz, ux, uy, uz, fx, fy, fz, cx, cy, ts, h):
    """Crank-Nicolson step (module docstring); returns ``(v'_x, v'_y, v'_z, Δv_x, Δv_y, Δv_z)``
    with ``Δv`` the drag part of ``v' - v``."""
    beta = 0.5 * h / ts
    hh = 0.5 * h
    rx = vx + hh * fx + beta * ux
    ry = vy + hh * fy + beta * uy
    rz = vz + hh * fz + beta * uz
    d = 1.0 + beta
    det = d * d + hh * hh * cx * cy
    mx = (d * rx + hh * cx * ry) / det  # time-centred velocity (v + v')/2
    my = (d * ry - hh * cy * rx) / det
    mz = rz / d
    return (2.0 * mx - vx, 2.0 * my - vy, 2.0 * mz - vz,
            -2.0 * beta * (mx - ux), -2.0 * beta * (my - uy), -2.0 * beta * (mz - uz))


@njit(cache=True, error_model="numpy")
def kick_exponential(vx, vy, vz, ux, uy, uz, fx, fy, fz, cx, cy, ts, h):
    """Exact step for fixed ``u`` and ``F`` (module docstring); returns like
    :func:`kick_semi_implicit`."""
    a = 1.0 / ts
    bx = fx + a * ux
    by = fy + a * uy
    det = a * a + cx * cy
    # terminal velocity v_inf = -A^{-1} b, A = [[-a, cx], [-cy, -a]]
    sx = (a * bx + cx * by) / det
    sy = (a * by - cy * bx) / det
    sz = uz + fz * ts
    dx0 = vx - sx
    dy0 = vy - sy
    dz0 = vz - sz
    kappa2 = cx * cy
    if kappa2 > 0.0:
        kappa = math.sqrt(kappa2)
        s = math.sin(kappa * h)
        sk = s / kappa
        half = math.sin(0.5 * kappa * h)
        cm1 = -2.0 * half * half  # cos(kappa h) - 1 without cancellation
    else:
        sk = h
        cm1 = 0.0
    em1 = math.expm1(-a * h)  # e^{-a h} - 1
    e = em1 + 1.0
    # e^{Ah} - I = (e - 1) R + (R - I),  R = [[1 + cm1, cx sk], [-cy sk, 1 + cm1]]
    m00 = em1 * (1.0 + cm1) + cm1
    m01 = e * cx * sk
    m10 = -e * cy * sk
    m11 = m00
    gx = m00 * dx0 + m01 * dy0  # (e^{Ah} - I)(v - v_inf)
    gy = m10 * dx0 + m11 * dy0
    nvx = vx + gx
    nvy = vy + gy
    nvz = sz + e * dz0
    # integral of v over the step: v_inf h + A^{-1} g,  A^{-1} = [[-a, -cx], [cy, -a]] / det
    ix = sx * h + (-a * gx - cx * gy) / det
    iy = sy * h + (cy * gx - a * gy) / det
    iz = sz * h - em1 * dz0 * ts
    return nvx, nvy, nvz, -a * (ix - h * ux), -a * (iy - h * uy), -a * (iz - h * uz)


@njit(cache=True, error_model="numpy")
def kick(method, vx, vy, vz, ux, uy, uz, fx, fy, fz, cx, cy, ts, h):
    """:func:`kick_semi_implicit` or :func:`kick_exponential` by code."""
    if method == EXPONENTIAL:
        return kick_exponential(vx, vy, vz, ux, uy, uz, fx, fy, fz, cx, cy, ts, h)
    return kick_semi_implicit(vx, vy, vz, ux, uy, uz, fx, fy, fz, cx, cy, ts, h)
