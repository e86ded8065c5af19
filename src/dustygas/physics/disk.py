"""Power-law protoplanetary disks: structure, pressure support, viscous and drift velocities.

Thesis §3.2.2 and §3.3.1; all quantities cgs unless stated (``G`` may be passed to work in
code units, e.g. ``DISK_UNITS.G = 1``).

Structure
---------
:math:`\\Sigma = \\Sigma_0 (r/r_0)^{-p}`, :math:`T = T_0 (r/r_0)^{-q}`, isothermal sound
speed :math:`c_s = \\sqrt{k_B T/(\\mu m_H)}`, :math:`\\Omega_K = \\sqrt{GM_\\star/r^3}`,
:math:`v_K = r\\Omega_K`, :math:`H = c_s/\\Omega_K` and, for a vertically Gaussian (isothermal)
disk, midplane density :math:`\\rho_0 = \\Sigma/(\\sqrt{2\\pi}H)`.

Midplane pressure :math:`P = \\rho_0 c_s^2 \\propto r^{-n}`: with :math:`H \\propto c_s/\\Omega
\\propto r^{(3-q)/2}`, :math:`\\rho_0 \\propto r^{-p-(3-q)/2}` and :math:`c_s^2 \\propto r^{-q}`,
so :math:`n = p + q/2 + 3/2` (:func:`pressure_exponent`).

The two conventions for :math:`\\eta`
------------------------------------
Radial force balance of the gas, :math:`v_{\\theta,g}^2/r = \\Omega_K^2 r + \\rho^{-1}\\,dP/dr`,
gives exactly :math:`v_{\\theta,g} = v_K(1 - \\eta)^{1/2}` (thesis eq. 3.25) with

.. math:: \\eta = n\\left(\\frac{c_s}{v_K}\\right)^2 = -\\left(\\frac{c_s}{v_K}\\right)^2 \\frac{d\\ln P}{d\\ln r}

(thesis eq. 3.24; Armitage 2013, §4.3): :func:`eta_armitage`. This is the :math:`\\eta` of the
drift law eq. 3.23 and of thesis Figure 3.5. The streaming-instability literature
(Nakagawa, Sekiya & Hayashi 1986; Youdin & Goodman 2005; Youdin & Johansen 2007)
defines instead :math:`v_{\\theta,g} \\approx v_K(1 - \\eta_{\\rm YJ})`, i.e.
:math:`\\eta_{\\rm YJ} = -\\tfrac12 (c_s/v_K)^2\\, d\\ln P/d\\ln r = \\eta/2` to first order
(:func:`eta_nakagawa`); the headwind :math:`v_K - v_{\\theta,g}` is :math:`\\eta_{\\rm YJ}v_K`
and the shearing-box pressure force is :math:`2\\eta_{\\rm YJ}v_K\\Omega`. In
:math:`\\eta_{\\rm YJ}` units eq. 3.23 reads :math:`v_r = -2\\eta_{\\rm YJ}v_K\\tau_s/(1+\\tau_s^2)`
for :math:`v_{r,g} = 0`, the dust drift of Nakagawa et al. (1986) at vanishing dust-to-gas ratio.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ..units import MEAN_MOLECULAR_WEIGHT, G as G_CGS, k_B, m_H

__all__ = [
    "power_law",
    "surface_density",
    "temperature",
    "surface_density_normalisation",
    "isothermal_sound_speed",
    "temperature_from_sound_speed",
    "keplerian_angular_velocity",
    "keplerian_velocity",
    "scale_height",
    "midplane_density",
    "pressure_exponent",
    "eta_armitage",
    "eta_nakagawa",
    "gas_azimuthal_velocity",
    "alpha_viscosity",
    "viscous_radial_velocity",
    "viscous_radial_velocity_power_law",
    "radial_drift_velocity",
    "azimuthal_drift_velocity",
    "vertical_pressure_gradient_exponent",
    "PowerLawDisk",
]


def _f(x: ArrayLike) -> np.ndarray:
    return np.asarray(x, dtype=np.float64)


def power_law(r: ArrayLike, value0: ArrayLike, r0: ArrayLike, exponent: ArrayLike) -> np.ndarray:
    """:math:`X(r) = X_0 (r/r_0)^{-k}` with ``exponent`` :math:`k` (note the minus sign)."""
    return _f(value0) * (_f(r) / _f(r0)) ** (-_f(exponent))


def surface_density(r: ArrayLike, Sigma0: ArrayLike, r0: ArrayLike, p: ArrayLike) -> np.ndarray:
    """Gas surface density :math:`\\Sigma = \\Sigma_0 (r/r_0)^{-p}` [g/cm^2]."""
    return power_law(r, Sigma0, r0, p)


def temperature(r: ArrayLike, T0: ArrayLike, r0: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Midplane temperature :math:`T = T_0 (r/r_0)^{-q}` [K]."""
    return power_law(r, T0, r0, q)


def surface_density_normalisation(
    disk_mass: float, r_in: float, r_out: float, r0: float, p: float
) -> float:
    """:math:`\\Sigma_0` such that :math:`\\int_{r_{in}}^{r_{out}} 2\\pi r\\Sigma\\,dr` equals ``disk_mass``.

    :math:`M = 2\\pi\\Sigma_0 r_0^p (r_{out}^{2-p} - r_{in}^{2-p})/(2-p)`, or
    :math:`2\\pi\\Sigma_0 r_0^2\\ln(r_{out}/r_{in})` for :math:`p = 2`.

    >>> surface_density_normalisation(1.0, 0.0, 1.0, 1.0, 0.0) * 3.141592653589793
    1.0
    """
    if abs(p - 2.0) < 1e-12:
        integral = r0**2 * np.log(r_out / r_in)
    else:
        integral = r0**p * (r_out ** (2.0 - p) - r_in ** (2.0 - p)) / (2.0 - p)
    return float(disk_mass / (2.0 * np.pi * integral))


def isothermal_sound_speed(T: ArrayLike, mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT) -> np.ndarray:
    """Isothermal sound speed :math:`c_s = \\sqrt{k_B T/(\\mu m_H)}` [cm/s]."""
    return np.sqrt(k_B * _f(T) / (mean_molecular_weight * m_H))


def temperature_from_sound_speed(c_s: ArrayLike, mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT) -> np.ndarray:
    """Inverse of :func:`isothermal_sound_speed`: :math:`T = \\mu m_H c_s^2/k_B` [K]."""
    return mean_molecular_weight * m_H * _f(c_s) ** 2 / k_B


def keplerian_angular_velocity(r: ArrayLike, M_star: ArrayLike, G: float = G_CGS) -> np.ndarray:
    """:math:`\\Omega_K = \\sqrt{G M_\\star/r^3}` [1/s in cgs]."""
    r = _f(r)
    return np.sqrt(G * _f(M_star) / r**3)


def keplerian_velocity(r: ArrayLike, M_star: ArrayLike, G: float = G_CGS) -> np.ndarray:
    """:math:`v_K = \\sqrt{G M_\\star/r}` [cm/s in cgs]."""
    return np.sqrt(G * _f(M_star) / _f(r))


def scale_height(c_s: ArrayLike, Omega: ArrayLike) -> np.ndarray:
    """Gas pressure scale height :math:`H = c_s/\\Omega` (thesis §3.2.2)."""
    return _f(c_s) / _f(Omega)


def midplane_density(Sigma: ArrayLike, H: ArrayLike) -> np.ndarray:
    """Midplane density of a vertically Gaussian disk :math:`\\rho_0 = \\Sigma/(\\sqrt{2\\pi}H)`."""
    return _f(Sigma) / (np.sqrt(2.0 * np.pi) * _f(H))


def pressure_exponent(p: ArrayLike, q: ArrayLike) -> np.ndarray:
    """Exponent :math:`n` of the midplane pressure :math:`P \\propto r^{-n}`: :math:`n = p + q/2 + 3/2`.

    >>> float(pressure_exponent(1.0, 0.5))
    2.75
    """
    return _f(p) + 0.5 * _f(q) + 1.5


def eta_armitage(n: ArrayLike, c_s: ArrayLike, v_K: ArrayLike) -> np.ndarray:
    """Pressure-support parameter :math:`\\eta = n (c_s/v_K)^2` (thesis eq. 3.24; Armitage 2013).

    The :math:`\\eta` of eqs. 3.23 and 3.25 (:math:`v_{\\theta,g} = v_K\\sqrt{1-\\eta}`); twice the
    :math:`\\eta` of Nakagawa et al. (1986) and Youdin & Johansen (2007), see the module docstring.
    """
    return _f(n) * (_f(c_s) / _f(v_K)) ** 2


def eta_nakagawa(n: ArrayLike, c_s: ArrayLike, v_K: ArrayLike) -> np.ndarray:
    """Streaming-instability :math:`\\eta = \\tfrac{n}{2}(c_s/v_K)^2` (Nakagawa et al. 1986; YJ07).

    :math:`v_{\\theta,g} \\approx v_K(1-\\eta)`, headwind :math:`\\eta v_K`; equal to
    :func:`eta_armitage` / 2.
    """
    return 0.5 * eta_armitage(n, c_s, v_K)


def gas_azimuthal_velocity(v_K: ArrayLike, eta: ArrayLike) -> np.ndarray:
    """Pressure-supported gas rotation :math:`v_{\\theta,g} = v_K(1-\\eta)^{1/2}` (thesis eq. 3.25).

    ``eta`` in the convention of eq. 3.24 (:func:`eta_armitage`).
    """
    return _f(v_K) * np.sqrt(1.0 - _f(eta))


def alpha_viscosity(alpha: ArrayLike, c_s: ArrayLike, H: ArrayLike) -> np.ndarray:
    """Shakura-Sunyaev turbulent viscosity :math:`\\nu = \\alpha c_s H` (thesis eq. 3.8)."""
    return _f(alpha) * _f(c_s) * _f(H)


def viscous_radial_velocity(r: ArrayLike, Sigma: ArrayLike, nu: ArrayLike) -> np.ndarray:
    """Viscous gas radial velocity :math:`v_{r,g} = -\\frac{3}{\\Sigma\\sqrt r}\\partial_r(\\Sigma\\nu\\sqrt r)`.

    Thesis eq. 3.22 (Lynden-Bell & Pringle 1974). General version for profiles sampled on a
    (possibly non-uniform) radial grid ``r``: the derivative is taken by second-order finite
    differences (:func:`numpy.gradient`, second order also at the end points). Positive is
    outward.
    """
    r, Sigma, nu = _f(r), _f(Sigma), _f(nu)
    flux = Sigma * nu * np.sqrt(r)
    return -3.0 / (Sigma * np.sqrt(r)) * np.gradient(flux, r, edge_order=2)


def viscous_radial_velocity_power_law(
    r: ArrayLike, nu: ArrayLike, p: ArrayLike, nu_slope: ArrayLike
) -> np.ndarray:
    """Eq. 3.22 for :math:`\\Sigma \\propto r^{-p}` and :math:`\\nu \\propto r^{\\beta}`:
    :math:`v_{r,g} = -3(\\beta - p + \\tfrac12)\\,\\nu/r`.

    ``nu_slope`` is :math:`\\beta = d\\ln\\nu/d\\ln r`; for an α-disk (:math:`\\nu = \\alpha c_s H`,
    constant α, :math:`T \\propto r^{-q}`) :math:`\\beta = 3/2 - q`. For :math:`p = 1`,
    :math:`q = 1/2` this is the steady accretion flow :math:`v_{r,g} = -3\\nu/(2r)`.
    """
    return -3.0 * (_f(nu_slope) - _f(p) + 0.5) * _f(nu) / _f(r)


def radial_drift_velocity(
    taus: ArrayLike, eta: ArrayLike, v_K: ArrayLike = 1.0, v_r_gas: ArrayLike = 0.0
) -> np.ndarray:
    """Radial dust drift :math:`v_r = (\\tau_s^{-1}v_{r,g} - \\eta v_K)/(\\tau_s + \\tau_s^{-1})`.

    Thesis eq. 3.23 (Takeuchi & Lin 2002; Armitage 2013, §4.3), with ``eta`` in the convention
    of eq. 3.24 (:func:`eta_armitage`). Evaluated as :math:`(v_{r,g} - \\eta v_K\\tau_s)/(1+\\tau_s^2)`,
    which is the same expression and finite at :math:`\\tau_s \\to 0`. Limits: :math:`v_r \\to v_{r,g}`
    for :math:`\\tau_s \\ll 1`, :math:`v_r \\to -\\eta v_K/\\tau_s` for :math:`\\tau_s \\gg 1`; for
    :math:`v_{r,g} = 0` the inward speed peaks at :math:`\\tau_s = 1` with :math:`\\eta v_K/2`.

    >>> float(radial_drift_velocity(1.0, 7.5e-3))
    -0.00375
    """
    taus = _f(taus)
    return (_f(v_r_gas) - _f(eta) * _f(v_K) * taus) / (1.0 + taus**2)


def azimuthal_drift_velocity(taus: ArrayLike, eta: ArrayLike, v_K: ArrayLike = 1.0) -> np.ndarray:
    """Azimuthal velocity of drifting dust relative to Keplerian, :math:`v_{\\theta} - v_K = -\\tfrac12\\eta v_K/(1+\\tau_s^2)`.

    The companion of eq. 3.23 for :math:`v_{r,g} = 0` (Nakagawa, Sekiya & Hayashi 1986 at vanishing
    dust-to-gas ratio; Takeuchi & Lin 2002, eq. 17), ``eta`` in the convention of eq. 3.24: tightly
    coupled dust moves with the gas (:math:`v_K\\sqrt{1-\\eta} \\approx v_K(1-\\eta/2)`), decoupled dust
    is Keplerian.

    >>> float(azimuthal_drift_velocity(1.0, 7.5e-3))
    -0.001875
    """
    return -0.5 * _f(eta) * _f(v_K) / (1.0 + _f(taus) ** 2)


def vertical_pressure_gradient_exponent(p: ArrayLike, q: ArrayLike, z_over_H: ArrayLike) -> np.ndarray:
    """:math:`\\partial\\ln P/\\partial\\ln R` at height :math:`z` of a vertically isothermal Gaussian disk.

    With :math:`\\rho = \\Sigma/(\\sqrt{2\\pi}H)\\,e^{-z^2/2H^2}`, :math:`\\Sigma \\propto R^{-p}`,
    :math:`c_s^2 \\propto R^{-q}` and :math:`H \\propto R^{(3-q)/2}`:
    :math:`\\partial\\ln P/\\partial\\ln R = -n + \\tfrac{3-q}{2}\\,z^2/H^2` with the midplane exponent
    :math:`n = p + q/2 + 3/2` (:func:`pressure_exponent`). The gas then rotates with
    :math:`v_\\theta^2 = GMR^2/(R^2+z^2)^{3/2} + c_s^2\\,\\partial\\ln P/\\partial\\ln R`.

    >>> float(vertical_pressure_gradient_exponent(1.0, 0.5, 0.0))
    -2.75
    """
    return -pressure_exponent(p, q) + 0.5 * (3.0 - _f(q)) * _f(z_over_H) ** 2


@dataclass(frozen=True)
class PowerLawDisk:
    """A vertically isothermal power-law disk around a star (cgs unless ``G`` is changed).

    Parameters
    ----------
    Sigma0, T0
        Surface density [g/cm^2] and temperature [K] at ``r0`` [cm].
    p, q
        :math:`\\Sigma \\propto r^{-p}`, :math:`T \\propto r^{-q}`.
    M_star
        Stellar mass [g].
    mean_molecular_weight
        :math:`\\mu` of the gas (default 2.34).
    """

    Sigma0: float
    r0: float
    p: float
    T0: float
    q: float
    M_star: float
    mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT
    G: float = G_CGS

    @classmethod
    def from_aspect_ratio(
        cls, Sigma0: float, r0: float, p: float, aspect_ratio: float, r_aspect: float, q: float,
        M_star: float, mean_molecular_weight: float = MEAN_MOLECULAR_WEIGHT, G: float = G_CGS,
    ) -> "PowerLawDisk":
        """Disk whose :math:`H/r` equals ``aspect_ratio`` at radius ``r_aspect``."""
        c_s = aspect_ratio * float(keplerian_velocity(r_aspect, M_star, G))
        T_aspect = float(temperature_from_sound_speed(c_s, mean_molecular_weight))
        T0 = T_aspect * (r_aspect / r0) ** q
        return cls(Sigma0, r0, p, T0, q, M_star, mean_molecular_weight, G)

    def sigma(self, r: ArrayLike) -> np.ndarray:
        return surface_density(r, self.Sigma0, self.r0, self.p)

    def temperature(self, r: ArrayLike) -> np.ndarray:
        return temperature(r, self.T0, self.r0, self.q)

    def sound_speed(self, r: ArrayLike) -> np.ndarray:
        return isothermal_sound_speed(self.temperature(r), self.mean_molecular_weight)

    def omega(self, r: ArrayLike) -> np.ndarray:
        return keplerian_angular_velocity(r, self.M_star, self.G)

    def v_kepler(self, r: ArrayLike) -> np.ndarray:
        return keplerian_velocity(r, self.M_star, self.G)

    def scale_height(self, r: ArrayLike) -> np.ndarray:
        return scale_height(self.sound_speed(r), self.omega(r))

    def midplane_density(self, r: ArrayLike) -> np.ndarray:
        return midplane_density(self.sigma(r), self.scale_height(r))

    @property
    def pressure_exponent(self) -> float:
        return float(pressure_exponent(self.p, self.q))

    def eta(self, r: ArrayLike) -> np.ndarray:
        """:math:`\\eta` of thesis eq. 3.24 (:func:`eta_armitage`)."""
        return eta_armitage(self.pressure_exponent, self.sound_speed(r), self.v_kepler(r))
