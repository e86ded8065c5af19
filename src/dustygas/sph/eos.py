"""Equations of state for the SPH gas: isothermal, locally isothermal and adiabatic.

* isothermal: :math:`P = c_s^2 \\rho` with a constant sound speed;
* locally isothermal (disks): :math:`P = c_s(R)^2 \\rho`, :math:`c_s = c_{s,0} (R/R_0)^{-q}` with
  :math:`R` the cylindrical radius (the usual vertically isothermal disk, e.g. Lodato & Price 2010);
* adiabatic: :math:`P = (\\gamma - 1)\\rho u`, :math:`c_s = \\sqrt{\\gamma P/\\rho}` (the ideal-gas
  law quoted with thesis eq. 2.3), with :math:`u` evolved by the energy equation.

Examples
--------
>>> import numpy as np
>>> eos = EquationOfState.adiabatic(5.0 / 3.0)
>>> P, c = eos.evaluate(np.array([1.0]), np.array([1.5]), np.zeros((1, 3)))
>>> float(P[0]), round(float(c[0]), 12)
(1.0, 1.290994448736)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

__all__ = ["ISOTHERMAL", "ADIABATIC", "LOCALLY_ISOTHERMAL", "EquationOfState", "pressure_sound_speed"]

ISOTHERMAL = 0
ADIABATIC = 1
LOCALLY_ISOTHERMAL = 2
_NAMES = {"isothermal": ISOTHERMAL, "adiabatic": ADIABATIC, "locally-isothermal": LOCALLY_ISOTHERMAL}


@njit(parallel=True, cache=True)
def pressure_sound_speed(kind, cs0, gamma, r0, q, rho, u, pos, P, cs):
    """Fill ``P`` and ``cs`` from ``rho``, ``u`` and (locally isothermal) the cylindrical radius."""
    for a in prange(rho.shape[0]):
        if kind == ADIABATIC:
            p = (gamma - 1.0) * rho[a] * u[a]
            P[a] = p
            cs[a] = math.sqrt(gamma * p / rho[a]) if p > 0.0 else 0.0
        elif kind == LOCALLY_ISOTHERMAL:
            R = math.sqrt(pos[a, 0] * pos[a, 0] + pos[a, 1] * pos[a, 1])
            c = cs0 * (R / r0) ** (-q)
            P[a] = c * c * rho[a]
            cs[a] = c
        else:
            P[a] = cs0 * cs0 * rho[a]
            cs[a] = cs0


@dataclass(frozen=True)
class EquationOfState:
    """Which equation of state and its constants (see module docstring)."""

    kind: int
    cs0: float = 1.0
    gamma: float = 5.0 / 3.0
    r0: float = 1.0
    q: float = 0.0

    @classmethod
    def isothermal(cls, cs: float) -> "EquationOfState":
        return cls(ISOTHERMAL, cs0=float(cs), gamma=1.0)

    @classmethod
    def locally_isothermal(cls, cs0: float, r0: float, q: float) -> "EquationOfState":
        return cls(LOCALLY_ISOTHERMAL, cs0=float(cs0), gamma=1.0, r0=float(r0), q=float(q))

    @classmethod
    def adiabatic(cls, gamma: float) -> "EquationOfState":
        return cls(ADIABATIC, gamma=float(gamma))

    @classmethod
    def from_name(cls, name: str, **kw) -> "EquationOfState":
        if name not in _NAMES:
            raise ValueError(f"unknown equation of state {name!r}; choose one of {', '.join(_NAMES)}")
        return cls(_NAMES[name], **kw)

    @property
    def evolves_energy(self) -> bool:
        """Whether :math:`u` is evolved (adiabatic) or fixed by the sound speed (isothermal)."""
        return self.kind == ADIABATIC

    def evaluate(self, rho: np.ndarray, u: np.ndarray, pos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pressure and sound speed for the given states."""
        P = np.empty_like(rho)
        cs = np.empty_like(rho)
        pressure_sound_speed(self.kind, self.cs0, self.gamma, self.r0, self.q, rho, u, pos, P, cs)
        return P, cs
