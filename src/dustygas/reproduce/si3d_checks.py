"""Checks of the stratified streaming-instability figures (Figs 1.10, 1.13 and 4.10 analogues).

They test that a run has reached the saturated, non-linear state of the streaming instability
(thesis §4.5; Johansen et al. 2007, Nature 448, 1022; Bai & Stone 2010b, ApJ 722, 1437) over the
*window* of the run: its last 10 orbits, or its last two thirds if it is shorter than 15 orbits
(:func:`window_start`):

* Fig 1.10 -- the largest dust density reached in the window is at least ten times the mean
  midplane dust density ``Σ_p / (√(2π) H_p)`` over the window (dense filaments, not a smooth
  layer);
* Fig 4.10 -- the 2D FFT of the dust surface density ``Σ_d(x, y)`` holds a non-axisymmetric
  peak (``k_y ≠ 0``, ``θ_k ≠ 0``, as in thesis Fig 4.10) at least :data:`NONAXI_OVER_NOISE`
  times the particle shot noise ``<Σ_d>/√N`` in at least half of the window's snapshots (the
  initial random layer's largest mode is 1.3 times it). This is weaker than the thesis's
  256² run, where the *dominant* peak lies at an angle: in the 16² and 32² laptop runs the
  dominant peak is mostly the axisymmetric ``k_x = 2π/L_x`` (its ``θ_k`` is in the CSV);
* Fig 1.13 -- the particle scale height is steady: its mean over the second half of the window
  is within 25 % of that over the first half (no secular settling or puffing; the saturated
  layers of Bai & Stone 2010b fluctuate by tens of per cent about a steady mean). Judged only
  where the window starts at :data:`SATURATED_AFTER` orbits or later (a run of 20 orbits or
  more): before that the layer is still settling and being stirred up by the growing
  instability (in our runs of the ``si3d`` physics it is thinnest at orbits 2-6 and thickens
  until orbit 10 or later), so a shorter run cannot show a steady state. In such a run the check
  is reported as not judged (:func:`~dustygas.reproduce.checks.not_judged`), with its value.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from . import register_checks
from .checks import Check, not_judged, within
from .thesis_checks import _csv

__all__ = ["window_start", "STEADY_RATIO", "NONAXI_OVER_NOISE", "SATURATED_AFTER"]

#: the non-axisymmetric FFT peak must stand this many times above the particle shot noise
NONAXI_OVER_NOISE = 4.0
#: allowed ratio (either way) of the mean H_p over the second half of the window to the first half's
STEADY_RATIO = 1.25
#: a steady layer is judged only over a window that starts this many orbits or later
SATURATED_AFTER = 10.0
#: the window: this many orbits before the end ...
WINDOW_ORBITS = 10.0
#: ... or, for a run shorter than 1.5 windows, its last two thirds (from a third of its end time)
SHORT_RUN_START = 3.0


def window_start(t_end: float) -> float:
    """First time (orbits) of the saturated-state window of a run ending at ``t_end`` orbits.

    >>> window_start(30.0), window_start(15.0), window_start(9.0)
    (20.0, 5.0, 3.0)
    """
    return max(t_end - WINDOW_ORBITS, t_end / SHORT_RUN_START)


def _window(t: np.ndarray) -> np.ndarray:
    return t >= window_start(float(t[-1])) * (1 - 1e-12)


@register_checks("fig1.10")
def fig1_10_checks(output: Path) -> list[Check]:
    data = _csv(Path(output) / "fig1_10.csv")
    w = _window(data["t_orbits"])
    ratio = float(np.max(data["rho_p_max"][w]) / np.mean(data["rho_p_midplane"][w]))
    return [within("max rho_p over the window / mean midplane dust density", ratio, 10.0, np.inf,
                   reference="saturated streaming instability: filaments >= 10x the layer's mean density "
                             "(Johansen et al. 2007; Bai & Stone 2010b)")]


@register_checks("fig4.10")
def fig4_10_checks(output: Path) -> list[Check]:
    data = _csv(Path(output) / "fig4_10.csv")
    w = _window(data["t_orbits"])
    fraction = float(np.mean(data["nonaxisymmetric_over_noise"][w] >= NONAXI_OVER_NOISE))
    return [within(f"fraction of the window's snapshots with a k_y != 0 FFT peak >= {NONAXI_OVER_NOISE:g}x shot noise",
                   fraction, 0.5, 1.0, reference="thesis Fig 4.10: modes at an angle theta_k in the k_x-k_y plane "
                                                 "(there the dominant ones, at 256^2)")]


@register_checks("fig1.13")
def fig1_13_checks(output: Path) -> list[Check]:
    data = _csv(Path(output) / "fig1_13.csv")
    t = data["t_orbits"]
    w = _window(t)
    mid = 0.5 * (t[w][0] + t[w][-1])
    out = []
    start = window_start(float(t[-1]))
    for name in (k for k in data if k.startswith("Hp_")):
        late, early = data[name][w & (t >= mid)], data[name][w & (t < mid)]
        ratio = float(np.mean(late) / np.mean(early)) if late.size and early.size else float("nan")
        label = f"{name}: mean scale height, second half of the window / first half"
        reference = "a steady particle layer (Bai & Stone 2010b, Fig 1.13 analogue)"
        if start < SATURATED_AFTER * (1 - 1e-12):
            out.append(not_judged(label, ratio, f"the window starts at {start:.3g} orbits: a steady layer is "
                                                f"judged from {SATURATED_AFTER:g} orbits on, in runs of "
                                                f"{SATURATED_AFTER + WINDOW_ORBITS:g} orbits or more",
                                  reference=reference))
        else:
            out.append(within(label, ratio, 1.0 / STEADY_RATIO, STEADY_RATIO, reference=reference))
    return out
