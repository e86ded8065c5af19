"""Time-step criteria (thesis §2.3, eqs. 2.12-2.15), reduced to one number over arrays.

Each function returns the largest step allowed by its criterion over all elements, as a
Python ``float`` (``inf`` when nothing limits the step: zero speeds, zero accelerations, empty
arrays). Engines take the minimum of the criteria they need, times their safety factors:

* Courant-Friedrichs-Lewy (eqs. 2.12-2.13; Courant, Friedrichs & Lewy 1928):
  :math:`\\Delta t \\le C\\,\\Delta x/|v|`, with :math:`|v|` the signal speed (e.g.
  :math:`|u| + c_s` for a grid, :math:`c_s` with :math:`\\Delta x = h` in SPH) and Courant
  number :math:`C \\le 1`;
* acceleration (eq. 2.14; Monaghan 1992): :math:`\\Delta t \\le \\eta_a\\sqrt{h/|a|}`,
  :math:`0 < \\eta_a < 1`;
* explicit drag (eq. 2.15): :math:`\\Delta t \\le t_s` (times a safety factor).

>>> courant_timestep([0.1, 0.2], [1.0, 4.0], courant=0.5)
0.025
>>> min_timestep(courant_timestep(0.1, 0.0), drag_timestep([3e-3, 1e-3]))
0.001
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["courant_timestep", "acceleration_timestep", "drag_timestep", "min_timestep"]


def _min_or_inf(x: np.ndarray) -> float:
    return float(np.min(x)) if x.size else float("inf")


def courant_timestep(dx: ArrayLike, speed: ArrayLike, courant: float = 1.0) -> float:
    """:math:`\\min C\\,\\Delta x/|v|` (thesis eqs. 2.12-2.13); ``inf`` where every speed is 0.

    ``dx`` and ``speed`` broadcast against each other (a scalar cell size with an array of
    speeds, or per-particle smoothing lengths and sound speeds).
    """
    dx, speed = np.broadcast_arrays(np.asarray(dx, dtype=np.float64), np.abs(np.asarray(speed, dtype=np.float64)))
    with np.errstate(divide="ignore"):
        dt = np.where(speed > 0.0, dx / speed, np.inf)
    return courant * _min_or_inf(dt)


def acceleration_timestep(h: ArrayLike, acceleration: ArrayLike, eta: float = 0.3, axis: int | None = None) -> float:
    """:math:`\\min \\eta_a\\sqrt{h/|a|}` (thesis eq. 2.14; Monaghan 1992).

    ``acceleration`` holds magnitudes, or vectors whose component axis is ``axis`` (e.g.
    ``axis=-1`` for an ``(N, 3)`` array); ``h`` is the resolution length of each element.
    """
    a = np.asarray(acceleration, dtype=np.float64)
    a = np.abs(a) if axis is None else np.sqrt(np.sum(a * a, axis=axis))
    h, a = np.broadcast_arrays(np.asarray(h, dtype=np.float64), a)
    with np.errstate(divide="ignore"):
        dt = np.where(a > 0.0, np.sqrt(h / np.where(a > 0.0, a, 1.0)), np.inf)
    return eta * _min_or_inf(dt)


def drag_timestep(t_s: ArrayLike, safety: float = 1.0) -> float:
    """:math:`\\min` (safety :math:`\\times t_s`) for explicit drag (thesis eq. 2.15)."""
    return safety * _min_or_inf(np.asarray(t_s, dtype=np.float64))


def min_timestep(*dts: float) -> float:
    """The smallest of the given criteria (``inf`` if none)."""
    return float(min(dts, default=float("inf")))
