"""Time-step criteria of thesis §2.3 in their SPH form, kept in one place.

* Courant (thesis eq. 2.13, :math:`\\Delta t \\le h/c_s`): :math:`\\Delta t_a = C_{\\rm cour} h_a/v_{{\\rm sig},a}`
  with the largest pair signal speed :math:`v_{{\\rm sig},a}` seen by particle :math:`a`
  (:func:`~dustygas.sph.viscosity.signal_speed`, Monaghan 1997);
* acceleration (thesis eq. 2.14, Monaghan 1992): :math:`\\Delta t_a = C_{\\rm force}\\sqrt{h_a/|\\mathbf a_a|}`;
* drag (thesis eq. 2.15): :math:`\\Delta t \\le t_s` for explicit drag, offered to the dust
  modules as :func:`drag_timestep` with a safety factor.

The global step is the minimum over particles and criteria. Extra criteria (drag, diffusion)
are passed to :func:`combined_timestep` as arrays of per-particle limits.

Examples
--------
>>> import numpy as np
>>> float(courant_force_timestep(np.array([0.1]), np.array([1.0]), np.zeros((1, 3)), 0.3, 0.25))
0.03
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit, prange

__all__ = ["courant_force_timestep", "drag_timestep", "combined_timestep"]


@njit(parallel=True, cache=True)
def _min_dt(h, vsig, acc, c_cour, c_force):
    n = h.shape[0]
    dt = np.empty(n)
    for a in prange(n):
        d = math.inf
        if vsig[a] > 0.0:
            d = c_cour * h[a] / vsig[a]
        amag = math.sqrt(acc[a, 0] * acc[a, 0] + acc[a, 1] * acc[a, 1] + acc[a, 2] * acc[a, 2])
        if amag > 0.0:
            df = c_force * math.sqrt(h[a] / amag)
            if df < d:
                d = df
        dt[a] = d
    return dt


def courant_force_timestep(h: np.ndarray, vsig: np.ndarray, acc: np.ndarray, c_cour: float,
                           c_force: float) -> float:
    """:math:`\\min_a \\min(C_{\\rm cour} h_a/v_{{\\rm sig},a},\\ C_{\\rm force}\\sqrt{h_a/|a_a|})` (eqs. 2.13-2.14)."""
    if h.size == 0:
        return math.inf
    return float(_min_dt(h, vsig, acc, c_cour, c_force).min())


def drag_timestep(stopping_time: np.ndarray, safety: float = 0.9) -> float:
    """Explicit-drag limit :math:`\\Delta t \\le t_s` (thesis eq. 2.15), times ``safety``."""
    return float(safety * np.min(stopping_time)) if np.size(stopping_time) else math.inf


def combined_timestep(*limits: float) -> float:
    """The smallest of several limits (each already a float)."""
    return float(min(limits, default=math.inf))
