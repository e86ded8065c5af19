"""Physics modules: how extra physics (dust, grain growth, ...) plugs into :class:`~dustygas.sph.SPHEngine`.

A module is an object with the methods of :class:`SPHModule` (all optional: the base class does
nothing). The engine calls them at fixed points of one kick-drift-kick step
(:mod:`~dustygas.sph.integrator`):

====================================  ==============================================================
``attach(engine)``                    once, when the engine is built: check the particles, add the
                                      module's per-particle fields to ``particles.extra``, append
                                      time-step criteria to ``engine.timestep_limits``
``kick(engine, dt, final)``           after each half kick of the velocities (``final`` on the
                                      second): advance the module's own fields by ``dt``
``predict(engine, dt)``               after the drift: predicted fields for the next evaluation
``adjust_pressure(engine, gas, ...)`` in every derivative evaluation, after the equation of state of
                                      the gas particles ``gas`` (an index array, ``None`` = all)
``add_derivatives(engine, vel, u)``   after the hydrodynamic and external forces: add to
                                      ``engine.acc`` / ``engine.dudt`` and compute the module's rates
``history(engine, out)``              add (or correct) scalar diagnostics
``messages()``                        log lines produced since the last call (warnings, events)
``state()`` / ``restore_state(d)``    scalars a checkpoint must hold to continue bit-identically
====================================  ==============================================================

Per-particle arrays of a module (its evolved fields *and* their time derivatives) live in
``engine.particles.extra``, so that removal, spatial re-ordering, snapshots and checkpoints carry
them like the built-in fields; a module never keeps references to particle arrays between calls.
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["SPHModule"]


class SPHModule:
    """Base class of engine modules: every hook is a no-op (see module docstring)."""

    #: short name, used as a prefix of checkpoint attributes
    name: str = "module"

    def attach(self, engine: Any) -> None:
        """Called once by :class:`~dustygas.sph.SPHEngine` after its own set-up checks."""

    def kick(self, engine: Any, dt: float, final: bool) -> None:
        """Advance the module's fields by ``dt`` with the current rates."""

    def predict(self, engine: Any, dt: float) -> None:
        """Predict the module's fields at the end of a step of length ``dt``."""

    def adjust_pressure(self, engine: Any, gas: np.ndarray | None, rho: np.ndarray, u: np.ndarray,
                        P: np.ndarray, cs: np.ndarray) -> None:
        """Modify pressures / sound speeds of the gas particles ``gas`` in place."""

    def add_derivatives(self, engine: Any, vel: np.ndarray, u: np.ndarray) -> None:
        """Add accelerations and heating; compute the module's own rates."""

    def history(self, engine: Any, out: dict[str, float]) -> None:
        """Add or correct entries of the engine's history row ``out``."""

    def messages(self) -> list[str]:
        """Log lines produced since the last call."""
        return []

    def state(self) -> dict[str, Any]:
        """Scalars to checkpoint (numbers or strings)."""
        return {}

    def restore_state(self, state: dict[str, Any]) -> None:
        """Inverse of :meth:`state`."""
