"""Small helpers shared by the grid tests."""

from __future__ import annotations

import numpy as np

from dustygas.grid import GridEngine


def run_to(engine: GridEngine, t_end: float) -> GridEngine:
    """Advance with the engine's own time step, landing exactly on ``t_end``."""
    while engine.t < t_end * (1 - 1e-14):
        engine.advance(min(engine.timestep(), t_end - engine.t))
    return engine


def order(ns, errors) -> float:
    """Least-squares slope of log(error) against log(1/n): the measured order of convergence."""
    return float(-np.polyfit(np.log(np.asarray(ns, float)), np.log(np.asarray(errors, float)), 1)[0])


def pair_orders(errors) -> np.ndarray:
    """Orders between successive doublings of the resolution."""
    e = np.asarray(errors, float)
    return np.log2(e[:-1] / e[1:])
