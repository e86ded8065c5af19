"""Characteristic tracing: time-centred face states for the corner-transport-upwind integrator.

The reconstruction of :mod:`dustygas.grid.reconstruct` gives each cell of a pencil a profile
of the primitive variables ``W = (rho, v_n, v_t1, v_t2)`` with edge values ``W_L`` (left) and
``W_R`` (right), and ``dW = W_R - W_L``, ``W_6 = 6 (W - (W_L + W_R)/2)`` (CW84 eq. 1.5; a line
has ``W_6 = 0``). The face states of a single-step scheme are the time-centred values, the
averages of the profile over the domain of dependence of the face during the step (Colella
1990; Colella & Woodward 1984, §2; Stone et al. 2008, ApJS 178, 137, §4.2, eqs. 38-48). For a
wave of speed ``lambda`` the average over the ``sigma = lambda Delta t / Delta x`` cells next to
the right edge is

.. math:: A(\\sigma) = W_R - \\tfrac12\\sigma\\,(dW - W_6) - \\tfrac13\\sigma^2 W_6,

next to the left edge :math:`B(\\sigma) = W_L + \\tfrac12\\sigma\\,(dW + W_6) - \\tfrac13\\sigma^2 W_6`.
Each characteristic field takes its own domain of dependence: with the eigenvalues
``lambda_k = v_n - c_s, v_n, v_n + c_s`` of the isothermal equations, ``sigma_k = lambda_k
Delta t / Delta x`` and the projections ``P_k = r_k l_k`` on their eigenvectors,

.. math::

    W_{left\\ of\\ face} = \\sum_k P_k\\,A(\\sigma_k), \\qquad
    W_{right\\ of\\ face} = \\sum_k P_k\\,B(-\\sigma_k).

For isothermal gas the acoustic waves couple only ``(rho, v_n)``: ``l_+- = (1/(2 rho),
+-1/(2 c_s))``, ``r_+- = (rho, +-c_s)``; the transverse velocities are carried by the wave
``lambda_0 = v_n`` alone, so their face values are ``A(sigma_0)`` and ``B(-sigma_0)``.

Every wave enters, also those moving away from the face (for them the profile is extrapolated
by ``|sigma|/2`` cells beyond the edge): Colella's (1990) upwind selection, which keeps only the
waves moving towards the face, suits solvers that take each characteristic from its upwind
side; the HLLE and HLLC solvers here average the two states of a face, so both must be
time-centred to second order (Athena's ``HLL_ALL_WAVES`` choice for its HLL-type solvers). With
the upwind selection the 2D CTU step is only first order on a sheared or oblique flow.

Limiting stays in the primitive variables (the PLM, PPM and PPM-CS profiles of
:mod:`~dustygas.grid.reconstruct`), the tracing is characteristic: Athena's ``2p``/``3p``
options (Stone et al. 2008, §4.2.1-4.2.2).
"""

from __future__ import annotations

from numba import njit

__all__ = ["trace_pencil"]


@njit(cache=True, error_model="numpy", inline="always")
def _right_average(wr: float, dw: float, w6: float, sigma: float) -> float:
    """``A(sigma)``: mean of a parabola over ``sigma`` cells next to its right edge."""
    return wr - 0.5 * sigma * (dw - w6) - sigma * sigma * w6 / 3.0


@njit(cache=True, error_model="numpy", inline="always")
def _left_average(wl: float, dw: float, w6: float, sigma: float) -> float:
    """``B(sigma)``: mean of a parabola over ``sigma`` cells next to its left edge."""
    return wl + 0.5 * sigma * (dw + w6) - sigma * sigma * w6 / 3.0


@njit(cache=True, error_model="numpy")
def trace_pencil(w, wl, wr, c0, c1, cs, dtdx) -> None:
    """Replace the edge values of cells ``c0 .. c1-1`` of a pencil by their traced face states.

    Parameters
    ----------
    w
        Cell primitives ``(4, N)``, normal velocity in row 1.
    wl, wr
        Face arrays ``(4, N + 1)`` as :func:`~dustygas.grid.reconstruct.reconstruct_faces`
        leaves them: cell ``c`` has its left edge in ``wr[:, c]`` and its right edge in
        ``wl[:, c + 1]``; both are overwritten with the half-step averages of the module
        docstring (``wl[:, c + 1]``: the state left of face ``c + 1``; ``wr[:, c]``: right of
        face ``c``).
    cs, dtdx
        Sound speed and ``Delta t / Delta x`` of the full step.
    """
    half_inv_cs = 0.5 / cs
    ncell = c1 - c0
    # views from cell c0 on: loop indices from 0 (no negative-index handling, see reconstruct.py)
    rho_c, u_c = w[0, c0:], w[1, c0:]
    rho_lo, u_lo = wr[0, c0:], wr[1, c0:]
    rho_hi, u_hi = wl[0, c0 + 1:], wl[1, c0 + 1:]
    for v in range(2, 4):  # transverse velocities: the lambda_0 wave alone
        a, lo, hi = w[v, c0:], wr[v, c0:], wl[v, c0 + 1:]
        for i in range(ncell):
            s_0 = u_c[i] * dtdx
            left, right = lo[i], hi[i]
            dw = right - left
            w6 = 6.0 * (a[i] - 0.5 * (left + right))
            hi[i] = _right_average(right, dw, w6, s_0)
            lo[i] = _left_average(left, dw, w6, -s_0)
    for i in range(ncell):  # density and normal velocity: the acoustic pair, projected on r_- and r_+
        rho = rho_c[i]
        u = u_c[i]
        s_m = (u - cs) * dtdx
        s_p = (u + cs) * dtdx
        half_inv_rho = 0.5 / rho
        r_lo, r_hi = rho_lo[i], rho_hi[i]
        v_lo, v_hi = u_lo[i], u_hi[i]
        drho = r_hi - r_lo
        du = v_hi - v_lo
        rho6 = 6.0 * (rho - 0.5 * (r_lo + r_hi))
        u6 = 6.0 * (u - 0.5 * (v_lo + v_hi))
        # right edge: alpha_-+ = l_-+ . A(sigma_-+)
        a_m = _right_average(r_hi, drho, rho6, s_m) * half_inv_rho - _right_average(v_hi, du, u6, s_m) * half_inv_cs
        a_p = _right_average(r_hi, drho, rho6, s_p) * half_inv_rho + _right_average(v_hi, du, u6, s_p) * half_inv_cs
        rho_hi[i] = rho * (a_m + a_p)
        u_hi[i] = cs * (a_p - a_m)
        # left edge
        a_m = _left_average(r_lo, drho, rho6, -s_m) * half_inv_rho - _left_average(v_lo, du, u6, -s_m) * half_inv_cs
        a_p = _left_average(r_lo, drho, rho6, -s_p) * half_inv_rho + _left_average(v_lo, du, u6, -s_p) * half_inv_cs
        rho_lo[i] = rho * (a_m + a_p)
        u_lo[i] = cs * (a_p - a_m)
