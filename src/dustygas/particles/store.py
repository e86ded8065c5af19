"""The particle store: struct-of-arrays, kept sorted by cell.

:class:`ParticleStore` holds, for N particles,

* ``pos`` ``(3, N)`` positions and ``vel`` ``(3, N)`` velocities (float64; the velocity frame
  is the gas's: full velocities, or relative to the shear ``v + q Ω x ŷ`` under orbital
  advection; an inactive axis keeps its coordinate and evolves its velocity);
* ``species`` ``(N,)`` int32 (index into the engine's species table), ``pid`` ``(N,)`` int64
  (a label that follows the particle through sorts and restarts), ``mass`` ``(N,)`` float64
  (per unit length of the inactive axes, like the gas).

The engine keeps the particles sorted by the flat index of the cell that holds them, slab by
slab along the *slab axis* (z in 3D and x-z boxes, x in x-y boxes): neighbours in memory are
neighbours in space (cache locality for the gather and the deposit), and each slab's particles
are a contiguous range, which is what lets threads deposit into disjoint slabs without races
(:mod:`dustygas.particles.deposit`). The sort is a stable counting sort, so the order -- and
with it every floating-point sum -- depends only on the particles, not on the thread count.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from ..errors import SetupError

__all__ = ["ParticleStore", "slab_axis", "cell_keys", "counting_sort", "slab_starts"]


@dataclass
class ParticleStore:
    """Struct-of-arrays particle data (see module docstring)."""

    pos: np.ndarray
    vel: np.ndarray
    species: np.ndarray
    pid: np.ndarray
    mass: np.ndarray

    def __post_init__(self) -> None:
        # own, writable, contiguous copies (the engine sorts them in place)
        self.pos = np.array(self.pos, dtype=np.float64, order="C")
        self.vel = np.array(self.vel, dtype=np.float64, order="C")
        n = self.pos.shape[1] if self.pos.ndim == 2 else -1
        self.species = np.array(np.broadcast_to(self.species, (max(n, 0),)), dtype=np.int32)
        self.pid = np.array(self.pid, dtype=np.int64)
        self.mass = np.array(np.broadcast_to(self.mass, (max(n, 0),)), dtype=np.float64)
        if self.pos.ndim != 2 or self.pos.shape[0] != 3 or self.vel.shape != self.pos.shape:
            raise SetupError(f"particle positions and velocities must both be (3, N) arrays, got {self.pos.shape}"
                             f" and {self.vel.shape}")
        if self.pid.shape != (n,):
            raise SetupError(f"particle ids: expected {n} entries, got {self.pid.shape}")
        if not (np.all(np.isfinite(self.pos)) and np.all(np.isfinite(self.vel))):
            raise SetupError("particle positions and velocities must be finite")
        if n and not np.all(self.mass > 0):
            raise SetupError("particle masses must be positive")

    @classmethod
    def create(cls, pos, vel, species=0, mass=1.0) -> "ParticleStore":
        """A store with ids ``0 .. N-1`` (``species`` and ``mass`` broadcast)."""
        pos = np.asarray(pos, dtype=np.float64)
        return cls(pos, vel, species, np.arange(pos.shape[1], dtype=np.int64), mass)

    @property
    def n(self) -> int:
        return int(self.pos.shape[1])

    def arrays(self) -> dict[str, np.ndarray]:
        """Copies of every array, by name (for checkpoints)."""
        return {"pos": self.pos.copy(), "vel": self.vel.copy(), "species": self.species.copy(),
                "pid": self.pid.copy(), "mass": self.mass.copy()}

    def momentum(self) -> np.ndarray:
        """Total momentum ``sum m v`` (3,) of the stored velocities."""
        return self.vel @ self.mass


def slab_axis(shape: tuple[int, int, int]) -> int:
    """Axis along which particles are grouped in slabs: z if active, else x if active, else y.

    The x axis rather than y in an x-y box: velocities along x are bounded by the Courant
    condition, azimuthal ones under orbital advection are not, and the slab scheme needs
    particles to move by less than a cell per half step along the slab axis.
    """
    if shape[2] > 1:
        return 2
    if shape[0] > 1:
        return 0
    return 1


@njit(cache=True, error_model="numpy")
def _cell(v: float, lo: float, d: float, n: int) -> int:
    if n == 1:
        return 0
    i = int((v - lo) / d)  # truncation is floor here: v >= lo inside the box
    return min(max(i, 0), n - 1)


@njit(cache=True, error_model="numpy")
def cell_key(x, y, z, cells, axis) -> int:
    """Sort key of a position: the slab index times the cells per slab plus the cell's index
    within the slab (slab axis ``axis``; positions must be inside the box)."""
    i = _cell(x, cells.x0, cells.dx, cells.nx)
    j = _cell(y, cells.y0, cells.dy, cells.ny)
    k = _cell(z, cells.z0, cells.dz, cells.nz)
    if axis == 2:
        return (k * cells.ny + j) * cells.nx + i
    if axis == 0:
        return (i * cells.nz + k) * cells.ny + j
    return (j * cells.nz + k) * cells.nx + i


@njit(cache=True, error_model="numpy")
def cell_keys(pos, cells, axis, keys) -> None:
    """:func:`cell_key` of every particle into ``keys``."""
    for p in range(pos.shape[1]):
        keys[p] = cell_key(pos[0, p], pos[1, p], pos[2, p], cells, axis)


@njit(cache=True, error_model="numpy")
def counting_sort(keys, ncell, pos, vel, species, pid, mass, order) -> bool:
    """Stable counting sort of every particle array by ``keys`` (in place; ``keys`` too).

    ``order`` is an int64 work array of length N. Returns False (and does nothing) if the
    keys were already non-decreasing.
    """
    n = keys.shape[0]
    done = True
    for p in range(1, n):
        if keys[p] < keys[p - 1]:
            done = False
            break
    if done:
        return False
    start = np.zeros(ncell + 1, dtype=np.int64)
    for p in range(n):
        start[keys[p] + 1] += 1
    for c in range(ncell):
        start[c + 1] += start[c]
    for p in range(n):
        c = keys[p]
        order[start[c]] = p
        start[c] += 1
    tmp = np.empty(n)
    for a in range(3):
        for p in range(n):
            tmp[p] = pos[a, order[p]]
        for p in range(n):
            pos[a, p] = tmp[p]
        for p in range(n):
            tmp[p] = vel[a, order[p]]
        for p in range(n):
            vel[a, p] = tmp[p]
    for p in range(n):
        tmp[p] = mass[order[p]]
    for p in range(n):
        mass[p] = tmp[p]
    itmp = np.empty(n, dtype=np.int64)
    for p in range(n):
        itmp[p] = pid[order[p]]
    for p in range(n):
        pid[p] = itmp[p]
    for p in range(n):
        itmp[p] = species[order[p]]
    for p in range(n):
        species[p] = itmp[p]
    for p in range(n):
        itmp[p] = keys[order[p]]
    for p in range(n):
        keys[p] = itmp[p]
    return True


@njit(cache=True, error_model="numpy")
def slab_starts(keys, cells_per_slab, nslab, starts) -> None:
    """``starts[s]``: index of the first particle of slab ``s`` (``starts[nslab] = N``); the
    keys must be sorted."""
    n = keys.shape[0]
    p = 0
    for s in range(nslab):
        first = s * cells_per_slab
        while p < n and keys[p] < first:
            p += 1
        starts[s] = p
    starts[nslab] = n
