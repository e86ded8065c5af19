"""Vertical settling of dust grains through the gas (thesis §4.1.4-4.1.5; Chiang & Youdin 2010).

A grain at height :math:`z` above the midplane obeys the damped oscillator

.. math:: \\ddot z = -\\dot z / t_s - \\Omega^2 z,

whose characteristic damping (settling) time is thesis eq. 4.18,

.. math:: t_{\\rm settle} \\simeq \\frac{1}{\\Omega} \\frac{2\\tau_s^2 + 1}{\\tau_s},

so that a grain falling from one gas scale height :math:`H_g = c_s/\\Omega` streams vertically
through the gas at the speed of thesis eq. 4.19,

.. math:: \\bar v_z = \\frac{H_g}{t_{\\rm settle}} = c_s \\frac{\\tau_s}{2\\tau_s^2 + 1}.

(The thesis writes :math:`H_g/t_s` in the middle member of 4.19; the right-hand side, which is
what the thesis and Squire & Hopkins 2018 use, is :math:`H_g/t_{\\rm settle}`.)

Settling-enhanced streaming-instability growth (Squire & Hopkins 2018) applies only while the
grains are still settling, i.e. when :math:`t_{\\rm growth} = 1/s < t_{\\rm settle}`, which is
thesis eq. 4.20: :math:`s/\\Omega > \\tau_s/(2\\tau_s^2 + 1)`.

All functions are dimensionless in :math:`\\Omega` and :math:`c_s` unless those are passed.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "settling_time",
    "oscillator_rates",
    "damping_time",
    "settling_trajectory",
    "steady_settling_velocity",
    "growth_settling_threshold",
    "growth_to_settling_ratio",
]


def settling_time(taus: ArrayLike, Omega: ArrayLike = 1.0) -> np.ndarray:
    """Settling time :math:`t_{\\rm settle} = (2\\tau_s^2 + 1)/(\\tau_s\\Omega)` (thesis eq. 4.18).

    Parameters
    ----------
    taus
        Dimensionless stopping time :math:`\\tau_s = t_s\\Omega` (> 0).
    Omega
        Orbital angular frequency (same time units as the result's inverse).
    """
    taus = np.asarray(taus, dtype=np.float64)
    return (2.0 * taus**2 + 1.0) / (taus * np.asarray(Omega, dtype=np.float64))


def oscillator_rates(taus: float, Omega: float = 1.0) -> tuple[complex, complex]:
    """The two rates :math:`\\lambda_\\pm = -\\frac{1}{2t_s} \\pm \\sqrt{\\frac{1}{4t_s^2} - \\Omega^2}` of
    :math:`\\ddot z = -\\dot z/t_s - \\Omega^2 z` (solutions :math:`e^{\\lambda t}`), ``λ_+`` the slower.

    >>> [complex(round(l.real, 12), round(l.imag, 12)) for l in oscillator_rates(1.0)]
    [(-0.5+0.866025403784j), (-0.5-0.866025403784j)]
    """
    ts = taus / Omega
    root = np.sqrt(complex(0.25 / ts**2 - Omega**2))
    return -0.5 / ts + root, -0.5 / ts - root


def damping_time(taus: float, Omega: float = 1.0) -> float:
    """e-folding time :math:`1/|{\\rm Re}\\,\\lambda_+|` of the slowest solution of the settling
    oscillator: the exact counterpart of thesis eq. 4.18, which it approaches in both limits
    (:math:`1/(\\tau_s\\Omega)` for :math:`\\tau_s \\ll 1`, :math:`2\\tau_s/\\Omega` for :math:`\\tau_s \\gg 1`).

    >>> round(damping_time(0.01) / float(settling_time(0.01)), 6), damping_time(1.0)
    (0.9997, 2.0)
    """
    return float(-1.0 / oscillator_rates(taus, Omega)[0].real)


def settling_trajectory(t: ArrayLike, z0: float, v0: float, taus: float, Omega: float = 1.0) -> np.ndarray:
    """Exact height :math:`z(t)` of a grain in gas at rest, :math:`\\ddot z = -\\dot z/t_s - \\Omega^2 z`,
    from :math:`z(0) = z_0, \\dot z(0) = v_0` (superposition of :func:`oscillator_rates`; the
    critically damped :math:`\\tau_s = 1/2` as the limit).

    >>> float(settling_trajectory(0.0, 0.3, 0.0, 0.1))
    0.3
    """
    t = np.asarray(t, dtype=np.float64)
    lp, lm = oscillator_rates(taus, Omega)
    if abs(lp - lm) < 1e-9 * abs(lp):
        return ((z0 + (v0 - lp * z0) * t) * np.exp(lp * t)).real
    a = (v0 - lm * z0) / (lp - lm)
    b = z0 - a
    return (a * np.exp(lp * t) + b * np.exp(lm * t)).real


def steady_settling_velocity(taus: ArrayLike, c_s: ArrayLike = 1.0) -> np.ndarray:
    """Steady vertical dust streaming speed :math:`c_s\\tau_s/(2\\tau_s^2+1)` (thesis eq. 4.19).

    The magnitude of the speed of grains falling from one gas scale height; the velocity points
    towards the midplane. Units are those of ``c_s``.
    """
    taus = np.asarray(taus, dtype=np.float64)
    return np.asarray(c_s, dtype=np.float64) * taus / (2.0 * taus**2 + 1.0)


def growth_settling_threshold(taus: ArrayLike) -> np.ndarray:
    """Smallest growth rate :math:`s/\\Omega` that beats settling: :math:`\\tau_s/(2\\tau_s^2+1)` (eq. 4.20).

    >>> [f"{x:.6g}" for x in growth_settling_threshold([1, 0.1, 0.01, 0.001])]
    ['0.333333', '0.0980392', '0.009998', '0.000999998']
    """
    taus = np.asarray(taus, dtype=np.float64)
    return taus / (2.0 * taus**2 + 1.0)


def growth_to_settling_ratio(growth_rate: ArrayLike, taus: ArrayLike, Omega: ArrayLike = 1.0) -> np.ndarray:
    """:math:`t_{\\rm growth}/t_{\\rm settle} = (\\Omega/s)\\,\\tau_s/(2\\tau_s^2+1)` (thesis §4.1.5).

    Values below 1 mean the settling-enhanced streaming instability outgrows settling.
    ``growth_rate`` is :math:`s` in the units of ``Omega``.
    """
    s = np.asarray(growth_rate, dtype=np.float64)
    return np.asarray(Omega, dtype=np.float64) / s * growth_settling_threshold(taus)
