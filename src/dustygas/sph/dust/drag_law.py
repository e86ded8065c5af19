"""Drag laws of the dust modules: constant K, constant stopping time, or Epstein from the grain size.

Every law is evaluated with the functions of :mod:`dustygas.physics.drag`; the SPH kernels only
multiply the per-particle factors computed here.

* **one-fluid** codes need the stopping time of the relative velocity (the *mixture* stopping
  time, Laibe & Price 2014) per mixture particle:
  :math:`t_s = \\rho_g\\rho_d/(K\\rho)` (:func:`~dustygas.physics.drag.mixture_stopping_time`) for a
  constant :math:`K`, :math:`t_s = \\sqrt{\\pi\\gamma/8}\\,\\rho_{\\rm grain}s/(\\rho c_s)`
  (:func:`~dustygas.physics.drag.epstein_stopping_time` with ``rho_d``) for Epstein drag, or a
  constant :math:`t_s`.
* **two-fluid** pair sums (thesis eq. 3.19) need :math:`K_{ai}/(\\rho_a\\rho_i)` for a gas particle
  :math:`a` and a dust particle :math:`i`. It is written
  :math:`k_a k_i + c/(\\rho_a + \\rho_i)` with per-particle factors: constant :math:`K`:
  :math:`k = \\sqrt K/\\rho`; Epstein (:func:`~dustygas.physics.drag.epstein_drag_coefficient`,
  :math:`K = \\rho_d\\rho_g v_{\\rm th}/(\\rho_{\\rm grain}s)`): :math:`k_a = v_{\\rm th}(c_{s,a})`,
  :math:`k_i = 1/(\\rho_{\\rm grain}s_i)`; constant mixture stopping time (:math:`K = \\rho_g\\rho_d/(t_s\\rho)`):
  :math:`k = 0`, :math:`c = 1/t_s`. The pair's mixture stopping time is then
  :math:`t_{s,ai} = 1/((\\rho_a+\\rho_i)\\,K_{ai}/(\\rho_a\\rho_i))`.

Examples
--------
>>> import numpy as np
>>> law = DragLaw("constant-K", K=0.35)
>>> float(law.one_fluid_stopping_time(np.array([2.0]), np.array([0.5]), np.array([1.0]))[0])
1.4285714285714286
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...errors import SetupError
from ...physics.drag import epstein_stopping_time, mixture_stopping_time, thermal_speed

__all__ = ["DRAG_LAWS", "DragLaw"]

DRAG_LAWS = ("constant-K", "constant-ts", "epstein")


@dataclass(frozen=True)
class DragLaw:
    """Which drag coefficient, and its constants (code units).

    Attributes
    ----------
    kind
        ``constant-K`` (:math:`K`), ``constant-ts`` (mixture stopping time :math:`t_s`) or
        ``epstein`` (grain radius and material density; per-particle radii when grains grow).
    K, ts
        The constant drag coefficient or stopping time.
    grain_size, grain_density
        Grain radius :math:`s` and material density :math:`\\rho_{\\rm grain}` (Epstein).
    gamma
        Adiabatic index in :math:`v_{\\rm th} = \\sqrt{8/(\\pi\\gamma)}c_s` (1 for isothermal gas).
    """

    kind: str = "constant-K"
    K: float = 1.0
    ts: float = 1.0
    grain_size: float = 1.0
    grain_density: float = 1.0
    gamma: float = 1.0

    def __post_init__(self) -> None:
        if self.kind not in DRAG_LAWS:
            raise SetupError(f"drag law must be one of {', '.join(DRAG_LAWS)}, not {self.kind!r}")
        for name in ("K", "ts", "grain_size", "grain_density", "gamma"):
            if not getattr(self, name) > 0:
                raise SetupError(f"drag law: {name} must be > 0")

    @property
    def needs_sizes(self) -> bool:
        return self.kind == "epstein"

    def one_fluid_stopping_time(self, rho: np.ndarray, eps: np.ndarray, cs: np.ndarray,
                                size: np.ndarray | None = None) -> np.ndarray:
        """Mixture stopping time of each one-fluid particle (total density ``rho``, dust fraction ``eps``)."""
        rho_d = eps * rho
        rho_g = rho - rho_d
        if self.kind == "constant-ts":
            return np.full(rho.shape, self.ts)
        if self.kind == "constant-K":
            return mixture_stopping_time(self.K, rho_g, rho_d)
        s = self.grain_size if size is None else size
        return epstein_stopping_time(s, self.grain_density, rho_g, cs, self.gamma, rho_d=rho_d)

    def pair_factors(self, rho_gas: np.ndarray, cs_gas: np.ndarray, rho_dust: np.ndarray,
                     size: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray, float]:
        """``(k_gas, k_dust, c)`` with :math:`K_{ai}/(\\rho_a\\rho_i) = k_a k_i + c/(\\rho_a+\\rho_i)` (module docstring)."""
        if self.kind == "constant-ts":
            return np.zeros_like(rho_gas), np.zeros_like(rho_dust), 1.0 / self.ts
        if self.kind == "constant-K":
            root = np.sqrt(self.K)
            return root / rho_gas, root / rho_dust, 0.0
        s = np.full(rho_dust.shape, self.grain_size) if size is None else size
        return thermal_speed(cs_gas, self.gamma), 1.0 / (self.grain_density * s), 0.0
