"""Exact solutions of the standard test problems: the references the problems start from and the tests compare to.

Each function is the closed form (or exact initial-value solution) of one test of the thesis's
engines, with the paper it comes from; the problems of :mod:`dustygas.problems` build their
initial states from these functions and the tests compare the simulations with them. Parameters
that could be swapped are keyword-only. The Riemann problems have modules of their own
(:mod:`~dustygas.physics.riemann`, isothermal; :mod:`~dustygas.physics.exact_riemann`, ideal
gas), as has Kelvin's shearing wave (:mod:`~dustygas.physics.shearing_sheet`).

=================================  ============================================================
:func:`sound_wave`                 linear isothermal sound wave (thesis eqs. 2.1, linearised)
:func:`dusty_box`                  relative-velocity decay of uniform gas and dust (Laibe & Price 2011)
:func:`dusty_wave_matrix`,         linear sound wave in a dust-gas mixture with constant drag
:func:`dusty_wave`                 (thesis eq. 2.5; Laibe & Price 2011)
:func:`dust_diffusion`             spreading of the terminal-velocity dust fraction (Price & Laibe 2015)
:func:`dusty_column_density`       isothermal column of dust and gas in hydrostatic balance (thesis §3.2.5)
=================================  ============================================================

References: Laibe & Price (2011), MNRAS 418, 1491 ("DUSTYBOX and DUSTYWAVE"); Price & Laibe (2015),
MNRAS 451, 813.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["sound_wave", "dusty_box", "dusty_wave_matrix", "dusty_wave", "dust_diffusion", "dusty_column_density"]


def _f(x: ArrayLike) -> np.ndarray:
    return np.asarray(x, dtype=np.float64)


def sound_wave(x: ArrayLike, y: ArrayLike, z: ArrayLike, t: float, *, k: ArrayLike, amplitude: float,
               cs: float = 1.0, rho0: float = 1.0, direction: int = 1) -> tuple[np.ndarray, ...]:
    """Density and velocity ``(rho, vx, vy, vz)`` of a linear isothermal sound wave.

    The linearised isothermal Euler equations (thesis eqs. 2.1 with :math:`P = c_s^2\\rho`) are solved
    by the plane wave travelling along :math:`s\\hat k` (``direction`` :math:`s = \\pm1`)

    .. math::

        \\frac{\\delta\\rho}{\\rho_0} = A \\sin(k\\cdot x - s c_s |k| t), \\qquad
        \\delta v = s c_s A \\hat k \\sin(k\\cdot x - s c_s |k| t).

    ``x, y, z`` broadcast against each other; ``k`` is the wave vector (three components).

    >>> rho, vx, vy, vz = sound_wave(0.3125, 0.0, 0.0, 0.0, k=(2 * np.pi, 0, 0), amplitude=1e-3)
    >>> round(float(rho - 1), 6), round(float(vx), 6), float(vy)
    (0.000924, 0.000924, 0.0)
    """
    k = _f(k)
    kmag = float(np.sqrt(np.sum(k**2)))
    x, y, z = np.broadcast_arrays(_f(x), _f(y), _f(z))
    wave = amplitude * np.sin(k[0] * x + k[1] * y + k[2] * z - direction * cs * kmag * t)
    return (rho0 * (1.0 + wave), *(direction * cs * (kd / kmag) * wave for kd in k))


def dusty_box(t: ArrayLike, *, rho_gas: float, rho_dust: float, v_gas0: float, v_dust0: float,
              stopping_time: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocities ``(v_gas, v_dust)`` of uniform gas and dust coupled by drag (DUSTYBOX).

    With uniform densities nothing but drag acts: the centre-of-mass velocity stays constant and
    the relative velocity decays on the mixture stopping time :math:`t_s` (Laibe & Price 2011, §3;
    :math:`t_s = \\rho_g\\rho_d/(K\\rho)` for a constant drag coefficient :math:`K`,
    :func:`~dustygas.physics.drag.mixture_stopping_time`):

    .. math::

        \\Delta v(t) = \\Delta v_0 e^{-t/t_s}, \\qquad v_g = \\bar v - \\frac{\\rho_d}{\\rho}\\Delta v, \\qquad
        v_d = \\bar v + \\frac{\\rho_g}{\\rho}\\Delta v, \\qquad \\bar v = \\frac{\\rho_g v_{g0} + \\rho_d v_{d0}}{\\rho}.

    >>> vg, vd = dusty_box(0.0, rho_gas=1.0, rho_dust=1.0, v_gas0=0.0, v_dust0=1.0, stopping_time=1 / 0.7)
    >>> float(vg), float(vd)
    (0.0, 1.0)
    """
    rho = rho_gas + rho_dust
    vbar = (rho_gas * v_gas0 + rho_dust * v_dust0) / rho
    dv = (v_dust0 - v_gas0) * np.exp(-_f(t) / stopping_time)
    return vbar - rho_dust / rho * dv, vbar + rho_gas / rho * dv


def dusty_wave_matrix(k: float, *, K: float, cs: float, rho_gas: float, rho_dust: float) -> np.ndarray:
    """The 4x4 matrix of the linearised two-fluid equations for perturbations :math:`\\propto e^{ikx}`.

    The isothermal two-fluid equations with a constant drag coefficient :math:`K` (thesis eq. 2.5)
    linearised about uniform gas and dust at rest (Laibe & Price 2011, §4):

    .. math::

        \\frac{d}{dt}\\begin{pmatrix}\\delta\\rho_g\\\\ \\delta\\rho_d\\\\ \\delta v_g\\\\ \\delta v_d\\end{pmatrix} =
        \\begin{pmatrix} 0 & 0 & -ik\\rho_{g0} & 0\\\\ 0 & 0 & 0 & -ik\\rho_{d0}\\\\
        -ikc_s^2/\\rho_{g0} & 0 & -K/\\rho_{g0} & K/\\rho_{g0}\\\\ 0 & 0 & K/\\rho_{d0} & -K/\\rho_{d0}\\end{pmatrix}
        \\begin{pmatrix}\\delta\\rho_g\\\\ \\delta\\rho_d\\\\ \\delta v_g\\\\ \\delta v_d\\end{pmatrix};

    its eigenvalues :math:`-i\\omega` are the roots of Laibe & Price's dispersion relation.
    """
    ik = 1j * k
    return np.array([[0, 0, -ik * rho_gas, 0],
                     [0, 0, 0, -ik * rho_dust],
                     [-ik * cs**2 / rho_gas, 0, -K / rho_gas, K / rho_gas],
                     [0, 0, K / rho_dust, -K / rho_dust]], dtype=complex)


def dusty_wave(x: ArrayLike, t: float, *, amplitude: float, K: float, cs: float = 1.0, rho_gas: float = 1.0,
               rho_dust: float = 1.0, wavelength: float = 1.0, x0: float = -0.5) -> tuple[np.ndarray, ...]:
    """``(rho_gas, rho_dust, v_gas, v_dust)`` at positions ``x`` and time ``t`` (DUSTYWAVE).

    The exact initial-value solution of the linear system of :func:`dusty_wave_matrix`, the matrix
    exponential (:func:`scipy.linalg.expm`), for Phantom's initial state (Laibe & Price 2011, §4):
    both densities :math:`\\rho_0[1 + A\\sin k(x-x_0)]`, both velocities :math:`Ac_s\\sin k(x-x_0)`,
    :math:`k = 2\\pi/\\lambda`.

    >>> rg, rd, vg, vd = dusty_wave(np.array([-0.25]), 0.0, amplitude=1e-4, K=1000.0)
    >>> float(rg[0]), float(vd[0])
    (1.0001, 0.0001)
    """
    k = 2.0 * np.pi / wavelength
    c0 = amplitude * np.array([rho_gas, rho_dust, cs, cs], dtype=complex)
    from scipy.linalg import expm  # imported here: scipy.linalg costs every process 0.25 s

    c = expm(dusty_wave_matrix(k, K=K, cs=cs, rho_gas=rho_gas, rho_dust=rho_dust) * t) @ c0
    phase = np.exp(1j * k * (_f(x) - x0))
    dens_g, dens_d, vg, vd = (np.imag(ci * phase) for ci in c)
    return rho_gas + dens_g, rho_dust + dens_d, vg, vd


def dust_diffusion(r: ArrayLike, t: float, *, eta: float, eps0: float, r_c: float) -> np.ndarray:
    """Dust fraction :math:`\\epsilon(r, t)` spreading by terminal-velocity diffusion in gas at rest.

    With a constant stopping time the terminal-velocity equation (thesis eq. 2.11b) for gas at rest
    is the non-linear diffusion equation :math:`\\partial\\epsilon/\\partial t = \\nabla\\cdot(\\eta\\epsilon\\nabla\\epsilon)`,
    :math:`\\eta = t_s c_s^2`, whose 3D spreading solution is (Price & Laibe 2015, eq. 51)

    .. math:: \\epsilon(r, t) = \\max\\left[A(10\\eta t + B)^{-3/5} - \\frac{r^2}{10\\eta t + B},\\ 0\\right],
              \\qquad B = r_c^2/\\epsilon_0, \\quad A = \\epsilon_0 B^{3/5},

    i.e. :math:`\\epsilon = \\epsilon_0(1 - r^2/r_c^2)` inside :math:`r_c` at :math:`t = 0`.

    >>> [round(float(e), 6) for e in dust_diffusion([0.0, 0.125, 0.3], 0.0, eta=0.1, eps0=0.1, r_c=0.25)]
    [0.1, 0.075, 0.0]
    """
    B = r_c**2 / eps0
    A = eps0 * B**0.6
    term = 10.0 * eta * t + B
    return np.maximum(A * term**-0.6 - _f(r) ** 2 / term, 0.0)


def dusty_column_density(z: ArrayLike, *, dust_fraction: float, surface_density: float = 1.0,
                         scale_height: float = 1.0) -> np.ndarray:
    """Density :math:`\\rho(z)` of an isothermal dust-gas column in hydrostatic balance.

    Under the vertical gravity :math:`-\\Omega^2 z` of a disk, the gas pressure
    :math:`P = c_s^2(1-\\epsilon)\\rho` of a mixture with a uniform dust fraction :math:`\\epsilon` balances
    the weight of gas and dust (the dust adds weight, not pressure; thesis §3.2.5):

    .. math:: \\rho(z) = \\frac{\\Sigma}{\\sqrt{2\\pi}H_{\\rm mix}}\\,e^{-z^2/2H_{\\rm mix}^2}, \\qquad
              H_{\\rm mix} = \\sqrt{1-\\epsilon}\\,H, \\quad H = c_s/\\Omega.

    >>> round(float(dusty_column_density(0.0, dust_fraction=0.0)), 6)  # 1/sqrt(2 pi)
    0.398942
    """
    h_mix = np.sqrt(1.0 - dust_fraction) * scale_height
    return surface_density * np.exp(-0.5 * (_f(z) / h_mix) ** 2) / (np.sqrt(2.0 * np.pi) * h_mix)
