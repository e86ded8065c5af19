"""Pressure forces, artificial dissipation and the energy equation in one pass over the pairs.

Two discretisations of :math:`-\\nabla P/\\rho` (thesis eq. 2.5b) are selectable:

**GASOLINE2** (``form = GASOLINE2``; thesis eqs. 3.2-3.3, Wadsley et al. 2017), the
geometric-density-average force

.. math::

    \\frac{d\\mathbf v_a}{dt} = -\\sum_b m_b \\frac{P_a + P_b}{\\rho_a\\rho_b} \\nabla_a\\bar W_{ab},
    \\qquad \\nabla_a\\bar W_{ab} = \\tfrac12\\left[f_a\\nabla_a W(r_{ab}, h_a) + f_b\\nabla_a W(r_{ab}, h_b)\\right],

    \\frac{du_a}{dt} = \\sum_b m_b \\frac{P_a}{\\rho_a\\rho_b}\\, \\mathbf v_{ab}\\cdot\\nabla_a\\bar W_{ab},

with :math:`f_a = 1/\\Omega_a` (grad-h, the default) or the :math:`f_a` of Wadsley et al. (2017)
(:func:`~dustygas.sph.density.gasoline2_correction`).

**Price 2012** (``form = PRICE2012``; Springel & Hernquist 2002, Price 2012 eqs. 35, 36, 39),
the variational grad-h form

.. math::

    \\frac{d\\mathbf v_a}{dt} = -\\sum_b m_b \\left[\\frac{P_a}{\\Omega_a\\rho_a^2}\\nabla_a W(r_{ab}, h_a)
        + \\frac{P_b}{\\Omega_b\\rho_b^2}\\nabla_a W(r_{ab}, h_b)\\right], \\qquad
    \\frac{du_a}{dt} = \\frac{P_a}{\\Omega_a\\rho_a^2}\\sum_b m_b\\, \\mathbf v_{ab}\\cdot\\nabla_a W(r_{ab}, h_a).

Artificial viscosity and conductivity (:mod:`dustygas.sph.viscosity`) are added in the same
pass. Every pair term is antisymmetric under :math:`a \\leftrightarrow b` and evaluated with
bitwise-antisymmetric separations, so total momentum is conserved to round-off and total energy
:math:`\\sum_a m_a (v_a^2/2 + u_a)` is conserved exactly by the semi-discrete equations.

Each particle gathers from its own neighbour row (no scatter, no atomic sums): the loop is parallel
over particles (in chunks taken dynamically by the threads, :mod:`~dustygas.sph.workshare`) and
deterministic. The neighbours' columns of the packed table are read in place (``packed[b, _X]``): a
row view ``packed[b]`` per pair would make numba count references to the table with an atomic add
and subtract, on one cache line shared by the threads. The pass also returns
:math:`\\nabla\\cdot\\mathbf v_a` and :math:`|\\nabla\\times\\mathbf v_a|` (Price 2012 eqs. 84-85, used by the
viscosity switches and to predict :math:`h`) and the largest pair signal speed (Courant condition,
:meth:`dustygas.sph.SPHEngine.timestep`). A new pairwise term (e.g. dust drag) is one more block
inside the loop of :func:`hydro_forces` or a second loop of the same shape over another neighbour
table.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

from .kernels import kernel_dshape
from .neighbours import minimum_image
from .viscosity import conductivity_signal, signal_speed, viscous_pair
from .workshare import CHUNK, WORKERS, new_counter, next_chunk

__all__ = ["PRICE2012", "GASOLINE2", "FORCE_FORMS", "NPACK", "pack_particles", "pack_row", "pressure_pair",
           "hydro_forces"]

PRICE2012 = 0
GASOLINE2 = 1
FORCE_FORMS = {"price2012": PRICE2012, "gasoline2": GASOLINE2}

# columns of the packed per-particle table read for every neighbour
_X, _Y, _Z, _VX, _VY, _VZ, _HINV, _GRADNORM, _M, _P, _RHOINV, _OMBAR, _FORM, _CS, _ALPHA, _U, _RHO = range(17)
NPACK = 17


@njit(parallel=True, cache=True)
def pack_particles(pos, vel, mass, h, rho, omega, P, cs, alpha, u, fcorr, norm, ndim, form, out):
    """Copy what a neighbour contributes into one row per particle (``out`` is (N, NPACK))."""
    for a in prange(pos.shape[0]):
        pack_row(out, a, pos, vel[a, 0], vel[a, 1], vel[a, 2], mass, h, rho, omega, P, cs, alpha, u, fcorr[a], norm,
                 ndim, form)


@njit(inline="always")
def pack_row(out, a, pos, vx, vy, vz, mass, h, rho, omega, P, cs, alpha, u, fcorr_a, norm, ndim, form):
    """Row ``a`` of the packed table (:func:`pack_particles`) with velocity ``(vx, vy, vz)`` (the predicted
    one) and the GASOLINE2 factor ``fcorr_a``; shared by the individual-time-step kernels."""
    hinv = 1.0 / h[a]
    out[a, _X] = pos[a, 0]
    out[a, _Y] = pos[a, 1]
    out[a, _Z] = pos[a, 2]
    out[a, _VX] = vx
    out[a, _VY] = vy
    out[a, _VZ] = vz
    out[a, _HINV] = hinv
    out[a, _GRADNORM] = norm * hinv ** (ndim + 1)
    out[a, _M] = mass[a]
    out[a, _P] = P[a]
    out[a, _RHOINV] = 1.0 / rho[a]
    out[a, _OMBAR] = 1.0 / (omega[a] * rho[a])
    if form == PRICE2012:
        out[a, _FORM] = P[a] / (omega[a] * rho[a] * rho[a])
    else:
        out[a, _FORM] = fcorr_a
    out[a, _CS] = cs[a]
    out[a, _ALPHA] = alpha[a]
    out[a, _U] = u[a]
    out[a, _RHO] = rho[a]


@njit(inline="always")
def pressure_pair(form, form_a, form_b, dW_a, dW_b, P_a, P_b, rhoinv_a, rhoinv_b, vdotr):
    """Pressure part of the pair force and of :math:`du_a/dt` (module docstring), per unit :math:`m_b`.

    ``form_a`` is :math:`P_a/(\\Omega_a\\rho_a^2)` (Price 2012) or :math:`f_a` (GASOLINE2); ``dW`` are
    :math:`\\partial W/\\partial r` with each particle's :math:`h`. Returns ``(s, du)``: the force on
    :math:`a` is :math:`-m_b s\\,\\hat r_{ab}` and ``s`` is symmetric in :math:`a \\leftrightarrow b` bit for bit.
    """
    if form == PRICE2012:
        return form_a * dW_a + form_b * dW_b, form_a * vdotr * dW_a
    rr = rhoinv_a * rhoinv_b  # symmetric product: bitwise antisymmetric pair force
    gbar = 0.5 * (form_a * dW_a + form_b * dW_b)
    return (P_a + P_b) * rr * gbar, P_a * rr * vdotr * gbar


@njit(parallel=True, cache=True)
def hydro_forces(packed, index, count, shape, radius, length, periodic, form, beta, alpha_u,
                 evolve_u, acc, dudt, divv, curlv, vsig):
    """Hydrodynamic accelerations, :math:`du/dt`, :math:`\\nabla\\cdot v`, :math:`|\\nabla\\times v|` and signal speeds.

    ``acc``, ``dudt``, ``divv``, ``curlv`` and ``vsig`` are overwritten. ``alpha_u = 0`` switches the
    conductivity off; ``evolve_u = False`` skips the energy equation (isothermal gas).
    """
    n = packed.shape[0]
    r2max = radius * radius
    conduct = evolve_u and alpha_u > 0.0
    nchunk = (n + CHUNK - 1) // CHUNK
    counter = new_counter()
    for _worker in prange(WORKERS):  # chunks handed out dynamically (dustygas.sph.workshare)
        c = next_chunk(counter)
        while c < nchunk:
            for a in range(c * CHUNK, min(n, (c + 1) * CHUNK)):
                _hydro_row(a, packed, index, count, shape, r2max, length, periodic, form, beta, alpha_u, evolve_u,
                           conduct, acc, dudt, divv, curlv, vsig)
            c = next_chunk(counter)


@njit(inline="always")
def _hydro_row(a, packed, index, count, shape, r2max, length, periodic, form, beta, alpha_u, evolve_u, conduct, acc,
               dudt, divv, curlv, vsig):
    """The pair sums of particle ``a`` (:func:`hydro_forces`)."""
    xa, ya, za = packed[a, _X], packed[a, _Y], packed[a, _Z]
    vxa, vya, vza = packed[a, _VX], packed[a, _VY], packed[a, _VZ]
    hinv_a = packed[a, _HINV]
    gnorm_a = packed[a, _GRADNORM]
    P_a = packed[a, _P]
    rhoinv_a = packed[a, _RHOINV]
    ombar_a = packed[a, _OMBAR]
    form_a = packed[a, _FORM]
    cs_a = packed[a, _CS]
    alpha_a = packed[a, _ALPHA]
    u_a = packed[a, _U]
    rho_a = packed[a, _RHO]
    ax = 0.0
    ay = 0.0
    az = 0.0
    du = 0.0
    div = 0.0
    cx = 0.0
    cy = 0.0
    cz = 0.0
    vs = cs_a
    for k in range(count[a]):
        b = index[a, k]
        dx = minimum_image(xa - packed[b, _X], length[0], periodic[0])
        dy = minimum_image(ya - packed[b, _Y], length[1], periodic[1])
        dz = minimum_image(za - packed[b, _Z], length[2], periodic[2])
        r2 = dx * dx + dy * dy + dz * dz
        hinv_b = packed[b, _HINV]
        qa2 = r2 * hinv_a * hinv_a
        qb2 = r2 * hinv_b * hinv_b
        if qa2 >= r2max and qb2 >= r2max:
            continue
        r = math.sqrt(r2)
        rinv = 1.0 / r
        # kernel shapes vanish beyond the support: no branch on q needed
        dW_a = gnorm_a * kernel_dshape(shape, r * hinv_a)
        dW_b = packed[b, _GRADNORM] * kernel_dshape(shape, r * hinv_b)
        m_b = packed[b, _M]
        dvx = vxa - packed[b, _VX]
        dvy = vya - packed[b, _VY]
        dvz = vza - packed[b, _VZ]
        vdotr = (dvx * dx + dvy * dy + dvz * dz) * rinv
        # pressure
        s, du_a = pressure_pair(form, form_a, packed[b, _FORM], dW_a, dW_b, P_a, packed[b, _P], rhoinv_a,
                                packed[b, _RHOINV], vdotr)
        du += du_a * m_b
        # artificial viscosity (zero for receding pairs)
        qa, qb = viscous_pair(vdotr, alpha_a, cs_a, packed[b, _ALPHA], packed[b, _CS], beta, ombar_a,
                              packed[b, _OMBAR])
        s += qa * dW_a + qb * dW_b
        du += qa * dW_a * vdotr * m_b
        # artificial conductivity
        if conduct:
            vsu = conductivity_signal(P_a, packed[b, _P], rho_a, packed[b, _RHO])
            du += m_b * alpha_u * vsu * (u_a - packed[b, _U]) * 0.5 * (ombar_a * dW_a
                                                                       + packed[b, _OMBAR] * dW_b)
        s *= m_b * rinv
        ax -= s * dx
        ay -= s * dy
        az -= s * dz
        div += m_b * vdotr * dW_a
        w = m_b * dW_a * rinv  # v_ab x grad_a W_ab(h_a), summed
        cx += w * (dvy * dz - dvz * dy)
        cy += w * (dvz * dx - dvx * dz)
        cz += w * (dvx * dy - dvy * dx)
        v = signal_speed(cs_a, packed[b, _CS], vdotr, beta)
        vs = max(vs, v)
    acc[a, 0] = ax
    acc[a, 1] = ay
    acc[a, 2] = az
    dudt[a] = du if evolve_u else 0.0
    divv[a] = -ombar_a * div
    curlv[a] = ombar_a * math.sqrt(cx * cx + cy * cy + cz * cz)
    vsig[a] = vs


def packed_table(n: int) -> np.ndarray:
    """An empty packed table for ``n`` particles."""
    return np.empty((n, NPACK), dtype=np.float64)
