"""The particle store: one array per field (struct of arrays), a type per particle, room for more.

Vectors are ``(N, 3)`` float64 arrays in every dimensionality (unused components stay zero), so
that the three components of one particle share a cache line in neighbour loops and the same
kernels serve 1D, 2D and 3D. Scalars are ``(N,)`` arrays. ``ptype`` says what a particle is:
:data:`GAS` (hydrodynamics), :data:`TEST` (external forces only) and, for the dust modules,
:data:`DUST`. Modules that need more per-particle fields (dust fraction, grain size, ...) add
them to :attr:`ParticleSet.extra`; they are carried through removal, reordering, snapshots and
checkpoints like the built-in ones.

Examples
--------
>>> import numpy as np
>>> p = ParticleSet.create(np.zeros((4, 3)), mass=0.25, h=0.1)
>>> p.extra["dust_fraction"] = np.full(4, 0.01)
>>> len(p.take(np.array([0, 2]))), p.total_mass
(2, 1.0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np
from numba import njit, prange

__all__ = ["GAS", "DUST", "TEST", "ParticleSet", "count_invalid"]

GAS = 0
DUST = 1
TEST = 2


@dataclass
class ParticleSet:
    """Particles as a struct of arrays (see module docstring)."""

    pos: np.ndarray
    vel: np.ndarray
    mass: np.ndarray
    h: np.ndarray
    u: np.ndarray
    alpha: np.ndarray
    ptype: np.ndarray
    pid: np.ndarray
    extra: dict[str, np.ndarray] = field(default_factory=dict)

    @classmethod
    def create(cls, pos: np.ndarray, vel: np.ndarray | None = None, mass=1.0, h=1.0, u=0.0, alpha=0.0,
               ptype=GAS) -> "ParticleSet":
        """Particles at ``pos`` (``(N, d)``, padded to three components) with broadcast scalars."""
        pos = np.asarray(pos, dtype=np.float64)
        n = pos.shape[0]
        p3 = np.zeros((n, 3))
        p3[:, : pos.shape[1]] = pos
        v3 = np.zeros((n, 3))
        if vel is not None:
            vel = np.asarray(vel, dtype=np.float64)
            v3[:, : vel.shape[1]] = vel

        def full(v, dtype=np.float64):
            return np.array(np.broadcast_to(np.asarray(v, dtype=dtype), (n,)), dtype=dtype)

        return cls(p3, v3, full(mass), full(h), full(u), full(alpha), full(ptype, np.int8),
                   np.arange(n, dtype=np.int64))

    def __len__(self) -> int:
        return self.pos.shape[0]

    def _array_fields(self):
        return [f.name for f in fields(self) if f.name != "extra"]

    def arrays(self) -> dict[str, np.ndarray]:
        """Every field by name (extra fields under ``extra/<name>``)."""
        out = {name: getattr(self, name) for name in self._array_fields()}
        out.update({f"extra/{k}": v for k, v in self.extra.items()})
        return out

    @classmethod
    def from_arrays(cls, arrays: dict[str, np.ndarray]) -> "ParticleSet":
        """Inverse of :meth:`arrays` (copies)."""
        names = [f.name for f in fields(cls) if f.name != "extra"]
        kw = {name: np.array(arrays[name]) for name in names}
        kw["extra"] = {k[len("extra/"):]: np.array(v) for k, v in arrays.items() if k.startswith("extra/")}
        return cls(**kw)

    def take(self, index: np.ndarray) -> "ParticleSet":
        """A new set holding the particles ``index`` in that order (used for removal and sorting)."""
        kw = {name: np.ascontiguousarray(getattr(self, name)[index]) for name in self._array_fields()}
        kw["extra"] = {k: np.ascontiguousarray(v[index]) for k, v in self.extra.items()}
        return ParticleSet(**kw)

    @property
    def total_mass(self) -> float:
        return float(self.mass.sum())


@njit(parallel=True, cache=True)
def count_invalid(vec_a, vec_b, scalar, ptype, positive_gas_scalar):
    """Number of particles with a non-finite component in ``vec_a``/``vec_b`` or ``scalar``
    (or, with ``positive_gas_scalar``, a gas particle whose ``scalar`` is not > 0)."""
    bad = 0
    for a in prange(vec_a.shape[0]):
        ok = math.isfinite(scalar[a])
        for d in range(3):
            ok = ok and math.isfinite(vec_a[a, d]) and math.isfinite(vec_b[a, d])
        if positive_gas_scalar and ptype[a] == GAS:
            ok = ok and scalar[a] > 0.0
        if not ok:
            bad += 1
    return bad
