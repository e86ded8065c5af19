"""A cheap deterministic engine for testing the run loop (registered only by the tests).

``toy-oscillator``: N uncoupled harmonic oscillators x'' = -omega^2 x integrated with the
kick-drift-kick leapfrog; energy is conserved to O(dt^2) and the phase error is known, so the
engine is also a small honest check of the loop's time-step handling.
"""

from __future__ import annotations

import time

import numpy as np

from dustygas.config import Param, with_defaults
from dustygas.problems import Problem, register
from dustygas.runner import RUN_SCHEMA


class OscillatorEngine:
    work_label = "particle-updates"

    def __init__(self, n: int, omega: float, cfl: float, sleep: float):
        k = np.arange(n)
        self.omega = omega
        self.cfl = cfl
        self.sleep = sleep
        self.x = np.cos(0.1 * k)
        self.v = -omega * np.sin(0.1 * k)
        self.t = 0.0
        self.cycle = 0
        self.work_units = n

    def timestep(self) -> float:
        return self.cfl / self.omega

    def advance(self, dt: float) -> None:
        self.v -= 0.5 * dt * self.omega**2 * self.x
        self.x += dt * self.v
        self.v -= 0.5 * dt * self.omega**2 * self.x
        self.t += dt
        self.cycle += 1
        if self.sleep:
            time.sleep(self.sleep)

    def energy(self) -> float:
        return float(0.5 * np.sum(self.v**2 + self.omega**2 * self.x**2))

    def history(self) -> dict[str, float]:
        return {"energy": self.energy(), "x0": float(self.x[0])}

    def snapshot(self):
        return {"x": self.x.copy(), "v": self.v.copy()}, {"omega": self.omega}

    def checkpoint(self):
        return {"x": self.x.copy(), "v": self.v.copy()}, {}

    def restore(self, arrays, attrs) -> None:
        self.x = np.array(arrays["x"])
        self.v = np.array(arrays["v"])


@register
class ToyOscillator(Problem):
    name = "toy-oscillator"
    summary = "Uncoupled harmonic oscillators (test engine for the run loop)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=2.0, dt_snapshot=0.5, log_every=1000),
        "problem": {
            "n": Param(16, "number of oscillators", min=1),
            "omega": Param(1.0, "angular frequency", "1/time", min=0.0, min_open=True),
            "cfl": Param(0.01, "omega * dt", min=0.0, max=1.0, min_open=True),
            "sleep": Param(0.0, "seconds slept per step (to make runs killable in tests)", "s", min=0.0),
            "scheme": Param("leapfrog", "integrator", choices=("leapfrog",)),
        },
    }

    def build(self, cfg):
        p = cfg.problem
        return OscillatorEngine(p.n, p.omega, p.cfl, p.sleep)
