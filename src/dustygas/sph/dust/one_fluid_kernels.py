"""The pair pass of one-fluid dust: every dust term of the mixture equations in one loop.

Notation: :math:`\\mathbf r_{ab} = \\mathbf r_a - \\mathbf r_b`, :math:`\\mathbf G_a = \\nabla_a W_{ab}(h_a)`,
:math:`\\mathbf G_b = \\nabla_a W_{ab}(h_b)`, :math:`F_{ab}(h) = \\partial W/\\partial r \\le 0`,
:math:`\\bar F_{ab} = [F_{ab}(h_a) + F_{ab}(h_b)]/2`, :math:`\\Omega` the grad-h factor, :math:`t` the
mixture stopping time (:mod:`~dustygas.sph.dust.drag_law`), :math:`\\Delta\\mathbf v = \\mathbf v_d - \\mathbf v_g`.
Each pair contributes a dust-fraction rate :math:`e_{ab}` to particle :math:`a`
(:math:`\\dot\\epsilon_a = \\sum_b e_{ab}`) with :math:`m_a e_{ab} = -m_b e_{ba}`: dust mass is exchanged,
never created, whatever the pair weights (thesis eq. 3.5).

Terminal-velocity approximation (thesis eqs. 2.10-2.11; Price & Laibe 2015): the flux
:math:`\\epsilon(1-\\epsilon)\\rho\\Delta\\mathbf v = \\epsilon t\\nabla P` is discretised with the
second-derivative operator

.. math:: e_{ab} = -\\frac{1}{\\rho_a}\\frac{m_b}{\\rho_b}\\,\\mathcal D_{ab}\\,(P_a - P_b)\\frac{\\bar F_{ab}}{r_{ab}},

``arithmetic``: :math:`\\mathcal D_{ab} = \\epsilon_a t_a + \\epsilon_b t_b` (the average of thesis eq. 3.4),
``upwind``: :math:`\\mathcal D_{ab} = \\epsilon_{\\rm up}(t_a + t_b)` with :math:`\\epsilon_{\\rm up}` the dust
fraction of the particle that gives dust away (thesis eqs. 3.15-3.17). With the square-root variable
:math:`S = \\sqrt{\\rho\\epsilon}` (Ballabio et al. 2018)

.. math:: \\dot S_a = -\\frac12\\sum_b \\frac{m_b S_b}{\\rho_b}\\left(\\frac{t_a}{\\rho_a} + \\frac{t_b}{\\rho_b}\\right)
          (P_a - P_b)\\frac{\\bar F_{ab}}{r_{ab}} - \\frac{S_a}{2}\\nabla\\cdot\\mathbf v_a,

whose pair terms change the dust mass :math:`\\sum_a m_a S_a^2/\\rho_a` by antisymmetric amounts.

Full one-fluid (thesis eq. 2.9; Laibe & Price 2014a,b), with :math:`g_a = (1-\\epsilon_a)\\Delta\\mathbf v_a\\cdot\\mathbf G_a/(\\Omega_a\\rho_a)`,
:math:`g_b = (1-\\epsilon_b)\\Delta\\mathbf v_b\\cdot\\mathbf G_b/(\\Omega_b\\rho_b)`:

.. math::

    e_{ab} &= -m_b\\,(\\epsilon_a g_a + \\epsilon_b g_b) \\quad\\text{(arithmetic, eq. 3.4)}, \\qquad
    e_{ab} = -m_b\\,\\epsilon_{\\rm up}(g_a + g_b) \\quad\\text{(upwind, eq. 3.17)}, \\\\
    \\dot{\\mathbf v}_a &\\mathrel{+}= -\\sum_b m_b\\left[\\frac{\\epsilon_a(1-\\epsilon_a)}{\\Omega_a\\rho_a}\\Delta\\mathbf v_a(\\Delta\\mathbf v_a\\cdot\\mathbf G_a)
        + \\frac{\\epsilon_b(1-\\epsilon_b)}{\\Omega_b\\rho_b}\\Delta\\mathbf v_b(\\Delta\\mathbf v_b\\cdot\\mathbf G_b)\\right], \\\\
    \\dot{\\Delta\\mathbf v}_a &= -\\frac{\\Delta\\mathbf v_a}{t_a} + \\frac{1}{1-\\epsilon_a}\\sum_b m_b\\left[\\frac{P_a}{\\Omega_a\\rho_a^2}\\mathbf G_a
        + \\frac{P_b}{\\Omega_b\\rho_b^2}\\mathbf G_b\\right]
        + \\sum_b\\frac{m_b}{\\Omega_a\\rho_a}\\left[\\mathbf v_{ab}(\\Delta\\mathbf v_a\\cdot\\mathbf G_a) + \\tfrac12(Q_a - Q_b)\\mathbf G_a\\right],

:math:`Q = (1-2\\epsilon)\\Delta v^2` (the terms :math:`\\nabla P/\\rho_g`, :math:`-(\\Delta\\mathbf v\\cdot\\nabla)\\mathbf v` and
:math:`-\\frac12\\nabla Q` of eq. 2.9d). The thermal energy per unit mass of gas obeys

.. math::

    (1-\\epsilon_a)\\dot u_a \\mathrel{+}= \\frac{\\epsilon_a(1-\\epsilon_a)\\Delta v_a^2}{t_a}
    - \\frac{P_a}{\\Omega_a\\rho_a^2}\\sum_b m_b(\\epsilon_a\\Delta\\mathbf v_a - \\epsilon_b\\Delta\\mathbf v_b)\\cdot\\mathbf G_a
    + \\frac12\\sum_b (u_a - u_b)\\,e_{ab}

(drag heating; the :math:`pdV` work of the relative flow; the thermal energy the gas carries with it,
thesis eq. 2.9e). These pairings make the semi-discrete total energy
:math:`\\sum_a m_a[\\tfrac12 v_a^2 + \\tfrac12\\epsilon_a(1-\\epsilon_a)\\Delta v_a^2 + (1-\\epsilon_a)u_a]`
exactly conserved with the arithmetic exchange (each gain is the antisymmetric partner of a loss);
the upwind weights keep the dust mass exact but not the :math:`Q` term's energy. In the
terminal-velocity approximation only the last (advective) heating term applies; it conserves
:math:`\\sum_a m_a(1-\\epsilon_a)u_a` exactly.

The pass also sums, per particle, the dust received (:math:`\\sum_b e_{ab} > 0`, with and without the
sender's grain size) and given away, for :mod:`~dustygas.sph.dust.grain_size` and the time step.

Where this differs from the thesis as printed
---------------------------------------------
* Eq. 3.4 writes the second kernel gradient as :math:`\\nabla_b W_{ab}(h_b) = -\\nabla_a W_{ab}(h_b)`,
  which turns the sum into the difference of the two terms and does not conserve dust mass
  (eq. 3.5 then fails); the conservative form, used here, has :math:`\\nabla_a W_{ab}(h_b)` (the
  symmetric divergence of Price 2012). The sign of :math:`\\dot\\epsilon_{ab}` in eqs. 3.15-3.16 follows.
* Eq. 3.17 weights the two cases with :math:`m_b` and :math:`m_a`; the pair's two contributions then
  cancel only for equal masses. Here both cases carry :math:`m_b` and only the dust fraction is
  upwinded, which conserves dust mass for any masses.
* Eq. 2.11d prints :math:`-\\epsilon t_s(\\nabla P/\\rho\\cdot\\nabla)u`; the gas moves at :math:`\\mathbf v - \\epsilon\\Delta\\mathbf v`
  relative to the barycentre, so the advective term is :math:`+\\epsilon\\Delta\\mathbf v\\cdot\\nabla u` (eq.
  2.9e's sign), as implemented.
* Eq. 2.9e's heating :math:`\\epsilon w^2/t_s` uses eq. 2.6's single-grain :math:`t_s`, whereas eq. 2.9d's
  drag :math:`-w/(t_s(1-\\epsilon))` uses the mixture time :math:`t_s(1-\\epsilon)`; with the mixture time
  :math:`t` of Laibe & Price (2014a) throughout, the heating that balances the drag is
  :math:`\\epsilon\\Delta v^2/t` per unit mass of gas.
"""

from __future__ import annotations

import math

from numba import njit, prange

from ..kernels import kernel_dshape
from ..neighbours import minimum_image
from ..workshare import CHUNK, WORKERS, new_counter, next_chunk

__all__ = ["TERMINAL_VELOCITY", "FULL", "one_fluid_rates"]

TERMINAL_VELOCITY = 0
FULL = 1


@njit(parallel=True, cache=True)
def one_fluid_rates(pos, vel, mass, h, rho, omega, P, u, eps, sqrt_rho_eps, ts, dv, Q, size,
                    index, count, shape, norm, ndim, length, periodic, model, upwind, sqrt_variable,
                    heat, track_size,
                    dfield, ddv, acc, dudt, inflow, inflow_size, outflow):
    """Accumulate the dust terms (module docstring) for every particle.

    ``dfield`` receives :math:`\\dot\\epsilon` (or the pair part of :math:`\\dot S`); ``ddv`` receives
    :math:`\\dot{\\Delta\\mathbf v}` without the drag term (full model only); ``acc`` and ``dudt`` are
    *added to* (``dudt`` as :math:`(1-\\epsilon)\\dot u`, i.e. before division by :math:`1-\\epsilon`);
    ``inflow``, ``inflow_size``, ``outflow`` receive the exchange sums.
    """
    n = pos.shape[0]
    full = model == FULL
    n_items = n
    n_chunks = (n_items + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        chunk = next_chunk(counter)
        while chunk < n_chunks:
            for a in range(chunk * CHUNK, min(n_items, (chunk + 1) * CHUNK)):
                xa, ya, za = pos[a, 0], pos[a, 1], pos[a, 2]
                hinv_a = 1.0 / h[a]
                gnorm_a = norm * hinv_a ** (ndim + 1)
                rho_a = rho[a]
                eps_a = eps[a]
                t_a = ts[a]
                P_a = P[a]
                u_a = u[a]
                ombar_a = 1.0 / (omega[a] * rho_a)
                Pfac_a = P_a * ombar_a / rho_a
                dvx_a = dvy_a = dvz_a = 0.0
                if full:  # dv (and Q) hold one dummy row in the terminal-velocity model
                    dvx_a, dvy_a, dvz_a = dv[a, 0], dv[a, 1], dv[a, 2]
                wfac_a = eps_a * (1.0 - eps_a) * ombar_a
                fld = 0.0
                du = 0.0
                gin = 0.0
                gins = 0.0
                gout = 0.0
                ax = 0.0
                ay = 0.0
                az = 0.0
                px = 0.0
                py = 0.0
                pz = 0.0
                vx = 0.0
                vy = 0.0
                vz = 0.0
                for k in range(count[a]):
                    b = index[a, k]
                    dx = minimum_image(xa - pos[b, 0], length[0], periodic[0])
                    dy = minimum_image(ya - pos[b, 1], length[1], periodic[1])
                    dz = minimum_image(za - pos[b, 2], length[2], periodic[2])
                    r = math.sqrt(dx * dx + dy * dy + dz * dz)
                    rinv = 1.0 / r
                    hinv_b = 1.0 / h[b]
                    dWa = gnorm_a * kernel_dshape(shape, r * hinv_a)
                    dWb = norm * hinv_b ** (ndim + 1) * kernel_dshape(shape, r * hinv_b)
                    if dWa == 0.0 and dWb == 0.0:
                        continue
                    m_b = mass[b]
                    rho_b = rho[b]
                    eps_b = eps[b]
                    if not full:
                        kfac = m_b / rho_b * 0.5 * (dWa + dWb) * rinv
                        dP = P_a - P[b]
                        if sqrt_variable:
                            s_pair = -0.5 * sqrt_rho_eps[b] * kfac * (t_a / rho_a + ts[b] / rho_b) * dP
                            fld += s_pair
                            e = 2.0 * sqrt_rho_eps[a] / rho_a * s_pair
                        else:
                            if upwind:
                                base = (t_a + ts[b]) * dP * kfac
                                e = -(eps_a if base > 0.0 else eps_b) * base / rho_a
                            else:
                                e = -(eps_a * t_a + eps_b * ts[b]) * dP * kfac / rho_a
                            fld += e
                    else:
                        ombar_b = 1.0 / (omega[b] * rho_b)
                        # unit vector times kernel gradients: G_a = dWa r_hat, G_b = dWb r_hat
                        rx, ry, rz = dx * rinv, dy * rinv, dz * rinv
                        dvx_b, dvy_b, dvz_b = dv[b, 0], dv[b, 1], dv[b, 2]
                        proj_a = dvx_a * rx + dvy_a * ry + dvz_a * rz
                        proj_b = dvx_b * rx + dvy_b * ry + dvz_b * rz
                        g_a = (1.0 - eps_a) * ombar_a * proj_a * dWa
                        g_b = (1.0 - eps_b) * ombar_b * proj_b * dWb
                        if upwind:
                            gsum = g_a + g_b
                            e = -m_b * (eps_a if gsum > 0.0 else eps_b) * gsum
                        else:
                            e = -m_b * (eps_a * g_a + eps_b * g_b)
                        fld += e
                        # momentum: -div(eps(1-eps) rho dv dv)/rho
                        ta = m_b * wfac_a * proj_a * dWa
                        tb = m_b * eps_b * (1.0 - eps_b) * ombar_b * proj_b * dWb
                        ax -= ta * dvx_a + tb * dvx_b
                        ay -= ta * dvy_a + tb * dvy_b
                        az -= ta * dvz_a + tb * dvz_b
                        # grad P / rho (symmetric form of the pressure force)
                        gp = m_b * (Pfac_a * dWa + P[b] * ombar_b / rho_b * dWb)
                        px += gp * rx
                        py += gp * ry
                        pz += gp * rz
                        # -(dv . grad) v and -grad(Q)/2
                        c1 = m_b * proj_a * dWa
                        c2 = 0.5 * m_b * (Q[a] - Q[b]) * dWa
                        vx += c1 * (vel[a, 0] - vel[b, 0]) + c2 * rx
                        vy += c1 * (vel[a, 1] - vel[b, 1]) + c2 * ry
                        vz += c1 * (vel[a, 2] - vel[b, 2]) + c2 * rz
                        if heat:
                            du -= Pfac_a * m_b * dWa * (eps_a * proj_a - eps_b * proj_b)
                    if heat:
                        du += 0.5 * (u_a - u[b]) * e
                    if e > 0.0:
                        gin += e
                        if track_size:
                            gins += e * size[b]
                    else:
                        gout -= e
                dfield[a] = fld
                inflow[a] = gin
                inflow_size[a] = gins
                outflow[a] = gout
                if full:
                    acc[a, 0] += ax
                    acc[a, 1] += ay
                    acc[a, 2] += az
                    inv1me = 1.0 / (1.0 - eps_a)
                    ddv[a, 0] = px * inv1me + ombar_a * vx
                    ddv[a, 1] = py * inv1me + ombar_a * vy
                    ddv[a, 2] = pz * inv1me + ombar_a * vz
                    if heat:
                        du += eps_a * (1.0 - eps_a) * (dvx_a * dvx_a + dvy_a * dvy_a + dvz_a * dvz_a) / t_a
                if heat:
                    dudt[a] += du
            chunk = next_chunk(counter)
