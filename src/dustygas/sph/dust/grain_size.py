"""Per-particle grain sizes: local growth and fragmentation, and advection with the dust mass exchange.

Local growth and fragmentation (thesis §3.2.2, eqs. 3.6-3.7; Stepinski & Valageas 1996;
Gonzalez et al. 2017): :math:`ds/dt = \\pm(\\rho_d/\\rho_{\\rm grain})V_{\\rm rel}` with the turbulent
relative velocity :math:`V_{\\rm rel}(\\tau_s)` of the grains, whose Stokes number
:math:`\\tau_s = t_s\\Omega` uses the Epstein stopping time from the local gas properties. Both
formulas are :func:`dustygas.physics.growth.growth_rate` and
:func:`dustygas.physics.growth.relative_velocity`; this module only applies them per particle.

**Minimum size.** Fragmentation shrinks grains at a rate :math:`\\propto\\sqrt{s}` as
:math:`s \\to 0`, so they reach zero size in a finite time, and an explicit step can overshoot
to negative sizes (and then to negative stopping times) -- the failure Phantom users reported.
Here sizes never fall below ``min_size``: a grain at the minimum does not shrink further
(:meth:`GrainGrowth.rate`), and every update is followed by :func:`enforce_minimum_size`.

Advection (thesis §3.2.3, eqs. 3.11-3.14). When a one-fluid particle :math:`a` exchanges dust with
its neighbours, the dust it receives from :math:`b` carries the size :math:`s_b` and the dust it
gives away carries :math:`s_a`, so its new size is the dust-mass-weighted mean (eq. 3.12)

.. math::

    s'_a = \\frac{(m_{d,a} - \\sum_b|\\Delta m_{d,ab}|)\\,s_a + \\sum_b \\Delta m_{d,ba}\\,s_b}
                {m_{d,a} - \\sum_b|\\Delta m_{d,ab}| + \\sum_b \\Delta m_{d,ba}} .

With :math:`m_{d,a} = \\epsilon_a m_a` and :math:`\\Delta m_d = \\dot\\epsilon\\,m_a\\Delta t` (eq. 3.13)
this is

.. math::

    s'_a = \\frac{(\\epsilon_a - \\Delta t\\sum_b|\\dot\\epsilon_{ab}|)\\,s_a + \\Delta t\\sum_b\\dot\\epsilon_{ba}s_b}
                {\\epsilon_a - \\Delta t\\sum_b|\\dot\\epsilon_{ab}| + \\Delta t\\sum_b\\dot\\epsilon_{ba}} .

**Thesis eq. 3.14 as printed is dimensionally inconsistent**: its numerator reads
:math:`(\\epsilon_a - \\sum_b|\\dot\\epsilon_{ab}|)s_a\\Delta t + (\\sum_b\\dot\\epsilon_{ba}s_b)\\Delta t`, adding the
dimensionless :math:`\\epsilon_a` to rates and multiplying the retained dust by :math:`\\Delta t`; the
form above follows from eqs. 3.11-3.13 and is what :func:`advect_sizes` computes. The retained dust
:math:`\\epsilon_a - \\Delta t\\sum|\\dot\\epsilon_{ab}|` is taken as zero if a particle gives away more
than it holds (possible with the arithmetic exchange), so :math:`s'_a` is always a weighted mean
of non-negative sizes with non-negative weights and stays between the smallest and largest size
involved. In the kick-drift-kick step each half kick applies this update with the exchange rates
(and senders' sizes) of the last derivative evaluation, so the dust-mass-weighted mean size
:math:`\\sum m\\epsilon s/\\sum m\\epsilon` is conserved to first order in :math:`\\Delta t`, not to round-off
(the thesis's scheme favours sizes that stay positive and bounded over exact conservation).

Examples
--------
>>> import numpy as np
>>> advect_sizes(np.array([1.0]), np.array([0.1]), np.array([0.2]), np.array([0.2 * 3.0]),
...              np.array([0.05]), dt=0.5).tolist()  # retains 0.075 of size 1, receives 0.1 of size 3
[2.142857142857143]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import SetupError
from ...physics.drag import stokes_number
from ...physics.growth import DEFAULT_ROSSBY, growth_rate, relative_velocity

__all__ = ["GrainGrowth", "advect_sizes", "enforce_minimum_size"]


@dataclass(frozen=True)
class GrainGrowth:
    """Parameters of local growth and fragmentation (code units).

    Attributes
    ----------
    alpha, rossby
        Turbulence :math:`\\alpha` and Rossby number of :math:`\\tilde\\alpha = \\sqrt2\\,Ro\\,\\alpha` (eq. 3.7).
    omega
        Orbital frequency :math:`\\Omega` of the Stokes number :math:`\\tau_s = t_s\\Omega`.
    v_frag
        Fragmentation threshold :math:`V_{\\rm frag}` (``inf``: pure growth; 0: pure fragmentation).
    grain_density
        :math:`\\rho_{\\rm grain}`.
    min_size
        Smallest grain radius (module docstring).
    c_size
        Time-step factor: :math:`\\Delta t \\le c\\,s/|ds/dt|` for grains above twice the minimum size.
    """

    alpha: float = 1e-2
    rossby: float = DEFAULT_ROSSBY
    omega: float = 1.0
    v_frag: float = math.inf
    grain_density: float = 1.0
    min_size: float = 1e-10
    c_size: float = 0.02

    def __post_init__(self) -> None:
        if not (self.alpha > 0 and self.rossby > 0 and self.omega > 0 and self.v_frag >= 0
                and self.grain_density > 0 and self.min_size > 0 and self.c_size > 0):
            raise SetupError("grain growth: alpha, rossby, omega, grain density, minimum size and c_size must be "
                             "> 0 and v_frag >= 0")

    def rate(self, size: np.ndarray, rho_d: np.ndarray, ts: np.ndarray, cs: np.ndarray,
             omega: np.ndarray | None = None) -> np.ndarray:
        """:math:`ds/dt` (eq. 3.6) with :math:`V_{\\rm rel}(t_s\\Omega)` (eq. 3.7); zero for fragmenting grains
        already at the minimum size. ``omega``: the local orbital frequency of each grain (a global
        disk) instead of the constant :attr:`omega`."""
        v_rel = relative_velocity(stokes_number(ts, self.omega if omega is None else omega), cs, self.alpha,
                                  self.rossby)
        rate = growth_rate(rho_d, self.grain_density, v_rel, self.v_frag)
        return np.where((rate < 0.0) & (size <= self.min_size), 0.0, rate)

    def timesteps(self, size: np.ndarray, rate: np.ndarray) -> np.ndarray:
        """:math:`c\\,s/|ds/dt|` of each grain (infinite for grains within twice the minimum size or not
        changing)."""
        big = (size > 2.0 * self.min_size) & (rate != 0.0)
        with np.errstate(divide="ignore"):
            return np.where(big, self.c_size * size / np.abs(rate), math.inf)

    def timestep(self, size: np.ndarray, rate: np.ndarray) -> float:
        """:math:`\\min c\\,s/|ds/dt|` over grains larger than twice the minimum size."""
        return float(np.min(self.timesteps(size, rate), initial=math.inf))


def enforce_minimum_size(size: np.ndarray, min_size: float) -> None:
    """Raise sizes below ``min_size`` to it, in place (module docstring)."""
    np.maximum(size, min_size, out=size)


def advect_sizes(size: np.ndarray, eps: np.ndarray, inflow: np.ndarray, inflow_size: np.ndarray,
                 outflow: np.ndarray, dt: float) -> np.ndarray:
    """Sizes after a step ``dt`` of dust exchange (corrected eq. 3.14, module docstring).

    ``inflow`` is :math:`\\sum_b\\dot\\epsilon_{ba}` (dust received, per unit time, in units of the
    particle's mass), ``inflow_size`` is :math:`\\sum_b\\dot\\epsilon_{ba}s_b`, ``outflow`` is
    :math:`\\sum_b|\\dot\\epsilon_{ab}|`; ``eps`` is :math:`\\epsilon_a` before the step.
    """
    kept = np.maximum(eps - dt * outflow, 0.0)
    total = kept + dt * inflow
    with np.errstate(invalid="ignore", divide="ignore"):
        new = (kept * size + dt * inflow_size) / total
    return np.where(total > 0.0, new, size)
