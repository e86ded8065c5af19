"""State, diagnostics and checkpoints of the block-time-step engine (:mod:`~dustygas.sph.timesteps`).

:class:`BlockState` holds the particles and every per-particle array of the scheme -- derived
fields of the last evaluation, the levels and last activation ticks of the SPH and external-force
steps, the synchronised velocities and the pending opening kicks -- and implements the parts of the
run-loop protocol (:mod:`dustygas.runner`) that only read or copy them: ``history``, ``snapshot``,
``checkpoint`` and ``restore``. A checkpoint holds all of it, so a restarted run continues
bit-identically; scratch arrays (tree, row buffers) are rebuilt from it.
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

import numpy as np

from ..errors import SimulationError
from .active import NPACK
from .active_search import DEAD
from .engine import snapshot_attrs
from .particles import ParticleSet, count_invalid

__all__ = ["BlockState"]

#: per-particle arrays: derived fields of the last evaluation, vectors, and the step bookkeeping
FIELDS = ("rho", "omega", "P", "cs", "divv", "curlv", "vsig", "tmin", "dt_want", "dt_want_ext", "phi", "_tau",
          "_tau_ext", "_pending_size")
VECTORS = ("acc", "acc_other", "v_sync", "pending")
INTEGERS = ("level", "ext_level", "last_tick", "last_ext", "_n_same", "_n_cross")


class BlockState:
    """Arrays and run-loop protocol shared by :class:`~dustygas.sph.timesteps.BlockStepEngine` (module docstring)."""

    def _init_state(self, particles: ParticleSet) -> None:
        self.particles = particles
        self.t = 0.0
        self.cycle = 0
        self._accreted = np.zeros(7)  # mass, momentum (3), angular momentum (3) given to the star
        self.updates = len(particles)  # particle updates of the last block
        self.total_updates = 0
        self.substeps = 0
        self.dt_block = 0.0
        self.started = False
        n = len(particles)
        for name in FIELDS:
            setattr(self, name, np.zeros(n))
        for name in VECTORS:
            setattr(self, name, np.zeros((n, 3)))
        for name in INTEGERS:
            setattr(self, name, np.zeros(n, np.int64))
        self.omega[:] = 1.0
        self.tmin[:] = np.inf
        self._n_same[:] = 64
        self.grad_v = np.zeros((n, 9))  # SPH velocity gradient of the gas at its last evaluation
        self._wake = np.zeros(n, np.bool_)
        self._scratch()

    def _scratch(self) -> None:
        """Per-particle scratch of the kernels (not part of the state)."""
        n = len(self.particles)
        self._packed = np.zeros((n, NPACK))
        self._dtable = None
        self._slot = np.full(n, -1, np.int64)
        self._size_rate = np.zeros(n)
        self._h_src = self.particles.h.copy()

    @property
    def work_units(self) -> int:
        return int(self.updates)

    @property
    def n_levels(self) -> int:
        return int(self.ext_level.max(initial=0)) + 1

    def _reorder(self, order: np.ndarray) -> None:
        """Keep the particles ``order`` (in that order), with all their arrays."""
        self.particles = self.particles.take(order)
        for name in FIELDS + VECTORS + INTEGERS + ("_wake", "grad_v"):
            setattr(self, name, np.ascontiguousarray(getattr(self, name)[order]))
        self._scratch()

    def _remove_dead(self) -> None:
        dead = self.particles.ptype == DEAD
        if dead.any():
            self._reorder(np.flatnonzero(~dead))

    def _check_state(self) -> None:
        p = self.particles
        if count_invalid(p.pos, p.vel, np.zeros(len(p)), p.ptype, False):
            bad = np.flatnonzero(~np.isfinite(p.pos).all(axis=1) | ~np.isfinite(p.vel).all(axis=1))
            raise SimulationError(f"non-finite position/velocity for {bad.size} particles at time={self.t:.6g} "
                                  f"cycle={self.cycle} (first: particle {int(bad[0])})",
                                  state={"particles": bad, "position": p.pos[bad], "velocity": p.vel[bad]})

    # ------------------------------------------------------------------ run-loop protocol
    def history(self) -> dict[str, float]:
        """Mass, momentum, angular momentum (about the star) and energies, accreted shares included, and
        the cost of the last block."""
        self.timestep()
        p = self.particles
        m = p.mass
        acc = self._accreted
        mom = (m[:, None] * p.vel).sum(axis=0) + acc[1:4]
        ang = (m[:, None] * np.cross(p.pos, p.vel)).sum(axis=0) + acc[4:7]
        ekin = 0.5 * float(np.sum(m * np.einsum("ij,ij->i", p.vel, p.vel)))
        epot = float(np.sum(m * self.phi)) if self.external.active else 0.0
        out = {"mass": float(m.sum() + acc[0]), "n_particles": float(len(p)), "accreted_mass": float(acc[0])}
        for i, ax in enumerate("xyz"):
            out[f"momentum_{ax}"] = float(mom[i])
            out[f"angular_momentum_{ax}"] = float(ang[i])
        out.update(kinetic_energy=ekin, potential_energy=epot, total_energy=ekin + epot,
                   block_dt=self.dt_block, levels=float(self.n_levels), substeps=float(self.substeps),
                   updates=float(self.updates), total_updates=float(self.total_updates))
        for f in self.diagnostics:
            f(self, out)
        return out

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        """The particles (arrays named as :meth:`dustygas.sph.SPHEngine.snapshot` names them) and their levels."""
        self.timestep()
        p = self.particles
        arrays = {"pos": p.pos, "vel": p.vel, "mass": p.mass, "h": p.h, "rho": self.rho, "u": p.u, "P": self.P,
                  "alpha": p.alpha, "pid": p.pid, "ptype": p.ptype, "level": self.level}
        arrays.update({f"extra/{k}": v for k, v in p.extra.items()})
        return {k: np.array(v) for k, v in arrays.items()}, snapshot_attrs(self)

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays = {f"particles/{k}": np.array(v) for k, v in self.particles.arrays().items()}
        arrays.update({f"block/{name}": np.array(getattr(self, name)) for name in FIELDS + VECTORS + INTEGERS})
        arrays["block/_wake"] = self._wake.astype(np.int8)
        arrays["block/grad_v"] = self.grad_v.copy()
        arrays["accreted"] = self._accreted.copy()
        attrs = {**snapshot_attrs(self), "started": int(self.started), "dt_block": self.dt_block, "updates": self.updates,
                 "total_updates": self.total_updates, "substeps": self.substeps,
                 "options": str(asdict(self.options)), "steps": str(asdict(self.steps))}
        return arrays, attrs

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        self.particles = ParticleSet.from_arrays(
            {k[len("particles/"):]: v for k, v in arrays.items() if k.startswith("particles/")})
        for name in FIELDS + VECTORS + INTEGERS:
            setattr(self, name, np.array(arrays[f"block/{name}"]))
        self._wake = np.array(arrays["block/_wake"]).astype(np.bool_)
        self.grad_v = np.array(arrays["block/grad_v"])
        self._accreted = np.array(arrays["accreted"])
        self.started = bool(attrs["started"])
        self.dt_block = float(attrs["dt_block"])
        self.updates, self.total_updates = int(attrs["updates"]), int(attrs["total_updates"])
        self.substeps = int(attrs["substeps"])
        self._scratch()
