"""Time-step criteria (thesis eqs. 2.12-2.15)."""

import math

import numpy as np

from dustygas.physics import acceleration_timestep, courant_timestep, drag_timestep, min_timestep


def test_courant_timestep():
    """min C dx/|v|: dx = 0.1, v = (1, -4, 0) -> 0.1/4 = 0.025, times C = 0.8 -> 0.02."""
    assert math.isclose(courant_timestep(0.1, [1.0, -4.0, 0.0], courant=0.8), 0.02, rel_tol=1e-15)
    assert math.isclose(courant_timestep([0.1, 0.01], [1.0, 1.0]), 0.01, rel_tol=1e-15)
    assert courant_timestep(0.1, [0.0, 0.0]) == math.inf
    assert courant_timestep([], []) == math.inf


def test_acceleration_timestep():
    """eta sqrt(h/|a|): h = 0.02, |a| = 8 -> sqrt(0.0025) = 0.05; with eta = 0.3 -> 0.015.
    Vectors (3, 4, 0) have |a| = 5: sqrt(0.02/5) = 0.0632456 with eta = 1."""
    assert math.isclose(acceleration_timestep([0.02, 0.02], [-8.0, 2.0], eta=0.3), 0.015, rel_tol=1e-15)
    a = np.array([[3.0, 4.0, 0.0], [0.0, 0.0, 0.0]])
    assert math.isclose(acceleration_timestep(0.02, a, eta=1.0, axis=-1), math.sqrt(0.004), rel_tol=1e-15)
    assert acceleration_timestep(0.02, np.zeros(4)) == math.inf


def test_drag_timestep_and_minimum():
    assert drag_timestep([3e-3, 1e-3, 2e-3], safety=0.5) == 5e-4
    assert min_timestep(0.02, 0.015, 5e-4) == 5e-4
    assert min_timestep() == math.inf
