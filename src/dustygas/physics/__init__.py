"""Formulas of the thesis as pure, vectorised functions (no state, no imports of our engines).

Each function's docstring names the thesis equation and the paper it comes from, and states
units: cgs for dimensional quantities, dimensionless where the thesis is. Engines and tests
call these functions; no formula is written twice.

Modules
-------
equilibrium
    Nakagawa-Sekiya-Hayashi steady drift, one and N species (thesis eq. 4.8).
settling
    Settling time, steady settling speed, growth-versus-settling criterion (eqs. 4.18-4.20).
"""

from .equilibrium import NSHEquilibrium, nsh_velocities, nsh_velocities_multi
from .settling import (
    growth_settling_threshold,
    growth_to_settling_ratio,
    settling_time,
    steady_settling_velocity,
)

__all__ = [
    "NSHEquilibrium",
    "nsh_velocities",
    "nsh_velocities_multi",
    "settling_time",
    "steady_settling_velocity",
    "growth_settling_threshold",
    "growth_to_settling_ratio",
]
