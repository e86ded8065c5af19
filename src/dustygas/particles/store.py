"""The particle store: struct-of-arrays with room to grow, kept sorted by cell.

:class:`ParticleStore` holds, for N particles (arrays of a capacity C ≥ N; entries ``0 .. N-1``
are the particles):

* ``pos`` ``(3, C)`` positions and ``vel`` ``(3, C)`` velocities (float64; the velocity frame
  is the gas's: full velocities, or relative to the shear ``v + q Ω x ŷ`` under orbital
  advection; an inactive axis keeps its coordinate and evolves its velocity);
* ``species`` ``(C,)`` int32 (index into the engine's species table), ``pid`` ``(C,)`` int64
  (a label that follows the particle through sorts, block exchanges and restarts), ``mass``
  ``(C,)`` float64 (per unit length of the inactive axes, like the gas).

Particles enter (set-up, a neighbouring block) with :meth:`ParticleStore.append` and leave
(an outflow boundary, a neighbouring block) with :meth:`ParticleStore.remove`; both keep the
order of the others. The views :attr:`~ParticleStore.pos` etc. are the first N entries.

The engine keeps the particles in *canonical order*: by the flat index ``(k ny + j) nx + i``
of the cell that contains them and, within a cell, by ``pid`` (:func:`sort_by_cell`). The order
then depends only on the positions and labels -- not on the thread count, nor on the order in
which particles arrived from other blocks -- and so does every sum taken over particles in this
order; each cell's particles and each row's are contiguous ranges (``cell_start``), which is
what the race-free deposit of :mod:`dustygas.particles.deposit` reads.
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from ..arrays import serial_full
from ..errors import SetupError
from ..grid.mesh import Layout, Offsets, Spacing
from .interp import axis_cell, stencil_into

__all__ = ["ParticleStore", "compact", "sort_by_cell"]


class ParticleStore:
    """Struct-of-arrays particle data with spare capacity (see module docstring).

    Parameters
    ----------
    pos, vel
        ``(3, N)`` positions and velocities.
    species, pid, mass
        ``(N,)`` (species and mass broadcast from scalars).
    capacity
        Room for this many particles (default N).
    """

    def __init__(self, pos, vel, species, pid, mass, capacity: int | None = None):
        pos = np.asarray(pos, dtype=np.float64)
        vel = np.asarray(vel, dtype=np.float64)
        if pos.ndim != 2 or pos.shape[0] != 3 or vel.shape != pos.shape:
            raise SetupError(f"particle positions and velocities must both be (3, N) arrays, got {pos.shape}"
                             f" and {vel.shape}")
        n = pos.shape[1]
        species = np.broadcast_to(np.asarray(species), (n,))
        mass = np.broadcast_to(np.asarray(mass, dtype=np.float64), (n,))
        pid = np.asarray(pid, dtype=np.int64)
        if pid.shape != (n,):
            raise SetupError(f"particle ids: expected {n} entries, got {pid.shape}")
        if not (np.all(np.isfinite(pos)) and np.all(np.isfinite(vel))):
            raise SetupError("particle positions and velocities must be finite")
        if n and not np.all(mass > 0):
            raise SetupError("particle masses must be positive")
        self.n = 0
        self._allocate(max(n, capacity or 0, 1))
        self.append(pos, vel, species, pid, mass)

    def _allocate(self, capacity: int) -> None:
        old = self.n
        new_pos = np.zeros((3, capacity))
        new_vel = np.zeros((3, capacity))
        new_species = np.zeros(capacity, dtype=np.int32)
        new_pid = np.zeros(capacity, dtype=np.int64)
        new_mass = np.zeros(capacity)
        if old:
            new_pos[:, :old] = self._pos[:, :old]
            new_vel[:, :old] = self._vel[:, :old]
            new_species[:old] = self._species[:old]
            new_pid[:old] = self._pid[:old]
            new_mass[:old] = self._mass[:old]
        self._pos, self._vel, self._species, self._pid, self._mass = new_pos, new_vel, new_species, new_pid, new_mass

    @classmethod
    def create(cls, pos, vel, species=0, mass=1.0) -> "ParticleStore":
        """A store with ids ``0 .. N-1`` (``species`` and ``mass`` broadcast)."""
        pos = np.asarray(pos, dtype=np.float64)
        return cls(pos, vel, species, np.arange(pos.shape[1], dtype=np.int64), mass)

    # ------------------------------------------------------------------ views
    @property
    def capacity(self) -> int:
        return int(self._pos.shape[1])

    @property
    def pos(self) -> np.ndarray:
        return self._pos[:, :self.n]

    @property
    def vel(self) -> np.ndarray:
        return self._vel[:, :self.n]

    @property
    def species(self) -> np.ndarray:
        return self._species[:self.n]

    @property
    def pid(self) -> np.ndarray:
        return self._pid[:self.n]

    @property
    def mass(self) -> np.ndarray:
        return self._mass[:self.n]

    def buffers(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The whole arrays (capacity C, contiguous) for compiled kernels, which take N apart."""
        return self._pos, self._vel, self._species, self._pid, self._mass

    # ------------------------------------------------------------------ growth
    def append(self, pos, vel, species, pid, mass) -> None:
        """Add particles at the end (growing the arrays by doubling when full)."""
        pos = np.asarray(pos, dtype=np.float64)
        m = pos.shape[1]
        if self.n + m > self.capacity:
            self._allocate(max(2 * self.capacity, self.n + m))
        s = slice(self.n, self.n + m)
        self._pos[:, s] = pos
        self._vel[:, s] = vel
        self._species[s] = species
        self._pid[s] = pid
        self._mass[s] = mass
        self.n += m

    def reserve(self, capacity: int) -> None:
        """Room for ``capacity`` particles (the arrays grow, the particles stay)."""
        if capacity > self.capacity:
            self._allocate(int(capacity))

    def remove(self, keep: np.ndarray) -> None:
        """Keep only the particles where ``keep`` (N,) is True, in their order."""
        m = compact(self._pos, self._vel, self._species, self._pid, self._mass, self.n, np.asarray(keep, dtype=np.bool_))
        self.n = int(m)

    # ------------------------------------------------------------------ outputs
    def arrays(self) -> dict[str, np.ndarray]:
        """Copies of every array, by name (snapshots and checkpoints)."""
        return {"pos": self.pos.copy(), "vel": self.vel.copy(), "species": self.species.copy(),
                "pid": self.pid.copy(), "mass": self.mass.copy()}

    def momentum(self) -> np.ndarray:
        """Total momentum ``sum m v`` (3,) of the stored velocities."""
        return self.vel @ self.mass


@njit(cache=True, error_model="numpy")
def compact(pos, vel, species, pid, mass, n, keep) -> int:
    """Move the kept particles of ``0 .. n-1`` to the front in order; returns their number."""
    m = 0
    for p in range(n):
        if keep[p]:
            if m != p:
                for a in range(3):
                    pos[a, m] = pos[a, p]
                    vel[a, m] = vel[a, p]
                species[m] = species[p]
                pid[m] = pid[p]
                mass[m] = mass[p]
            m += 1
    return m


@njit(inline="always")
def _out_of_order(keys, pid, p):
    """Particles ``p - 1`` and ``p`` are not in canonical order (by cell, then by pid)."""
    return keys[p] < keys[p - 1] or (keys[p] == keys[p - 1] and pid[p] < pid[p - 1])


@njit(cache=True, error_model="numpy", inline="always")
def _cell_key(pos, p, sp, ix, iy, iz, off, nx, ny, nz):
    """The flat index ``(k ny + j) nx + i`` of the domain cell of particle ``p``."""
    i = axis_cell(pos[0, p], sp.x0, ix, off.i0, nx)
    j = axis_cell(pos[1, p], sp.y0, iy, off.j0, ny)
    k = axis_cell(pos[2, p], sp.z0, iz, off.k0, nz)
    return (k * ny + j) * nx + i


@njit(cache=True, parallel=True, error_model="numpy")
def sort_by_cell(pos, vel, species, pid, mass, n, layout, spacing, offsets, keys, order, ptr, cell_start, fwork, iwork,
                 kernel, R, wts) -> int:
    """Put particles ``0 .. n-1`` into canonical order (module docstring), fill ``cell_start``
    and the weights ``wts`` ``(>= n, 3, 2R + 1)`` of assignment function ``kernel`` (code of
    :data:`~dustygas.particles.interp.KERNELS`, reach ``R``) of the sorted particles
    (:func:`~dustygas.particles.interp.stencil_into`). Returns -1, or the index of the first
    particle whose position or velocity is not finite (then nothing is sorted nor weighed:
    the cell search assumes finite positions, a NaN never finds its cell).

    ``layout``, ``spacing``, ``offsets``: the block (:mod:`dustygas.grid.mesh`; ``spacing.x0`` the global origin).
    ``keys``, ``order`` are int64 work arrays of length >= n, ``ptr`` one of length ncell;
    ``cell_start`` has ``ncell + 1`` entries (``cell_start[c] .. cell_start[c+1]`` are the particles of domain cell ``c``);
    ``fwork`` (7, >= n) float and ``iwork`` (3, >= n) int64 hold the permuted arrays (one gather
    pass, one copy-back pass that also weighs the particles). The first pass computes the keys,
    checks the order and, as if it held (as at most steps in 2D), weighs the particles and reads
    ``cell_start`` off the keys: then it is the only one. Otherwise the histogram and its prefix
    sum are serial (``O(N + ncell)``); computing the keys and checking the order, permuting the
    arrays, ordering each cell by ``pid`` and weighing run in parallel.
    """
    # the records arrive as plain tuples (dustygas.grid.mesh: faster to dispatch)
    lay = Layout(*layout)
    sp = Spacing(*spacing)
    off = Offsets(*offsets)
    nx, ny, nz = lay.nx, lay.ny, lay.nz
    ncell = nx * ny * nz
    ix, iy, iz = 1.0 / sp.dx, 1.0 / sp.dy, 1.0 / sp.dz
    nchunk = min(max(n, 1), 64)
    first_bad = serial_full(nchunk, -1)  # (small arrays: serial, see dustygas.arrays)
    unordered = serial_full(nchunk, 0)  # per chunk: a particle out of canonical order
    # one pass: keys, the order within the chunk, the weights and cell_start as if the order
    # held (as at most steps: few particles change cells); both are redone below if it does not
    for c in prange(nchunk):
        p0, p1 = c * n // nchunk, (c + 1) * n // nchunk
        prev = 0  # the key of particle p0 - 1 (computed here too: another chunk writes it)
        if p0 > 0 and np.isfinite(pos[0, p0 - 1]) and np.isfinite(pos[1, p0 - 1]) and np.isfinite(pos[2, p0 - 1]):
            prev = _cell_key(pos, p0 - 1, sp, ix, iy, iz, off, nx, ny, nz)
        for p in range(p0, p1):
            ok = True
            for a in range(3):
                if not (np.isfinite(pos[a, p]) and np.isfinite(vel[a, p])):
                    ok = False
            if not ok:
                if first_bad[c] < 0:
                    first_bad[c] = p
                keys[p] = 0
                continue
            # the cells of the stencils are those of _cell_key (the same arithmetic)
            ci = stencil_into(pos[0, p], sp.x0, ix, off.i0, nx, kernel, R, wts, p, 0)
            cj = stencil_into(pos[1, p], sp.y0, iy, off.j0, ny, kernel, R, wts, p, 1)
            ck = stencil_into(pos[2, p], sp.z0, iz, off.k0, nz, kernel, R, wts, p, 2)
            key = (ck * ny + cj) * nx + ci
            keys[p] = key
            for cell in range(prev + 1 if p > 0 else 0, key + 1):
                cell_start[cell] = p
            prev = key
        for p in range(p0 + 1, p1):  # the pairs (p - 1, p) inside the chunk
            if _out_of_order(keys, pid, p):
                unordered[c] = 1
                break
    ordered = True
    for c in range(nchunk):
        if first_bad[c] >= 0:
            return first_bad[c]
        p = c * n // nchunk  # and the pair across the chunk boundary
        if unordered[c] or (0 < p < n and _out_of_order(keys, pid, p)):
            ordered = False
    if ordered:
        for cell in range(keys[n - 1] + 1 if n > 0 else 0, ncell + 1):
            cell_start[cell] = n
        return -1
    for c in range(ncell + 1):
        cell_start[c] = 0
    for p in range(n):
        cell_start[keys[p] + 1] += 1
    for c in range(ncell):
        cell_start[c + 1] += cell_start[c]
    # stable placement: order[slot] = old index
    for c in range(ncell):
        ptr[c] = cell_start[c]
    for p in range(n):
        c = keys[p]
        order[ptr[c]] = p
        ptr[c] += 1
    # within a cell by pid (insertion sort on the permutation; cells hold few particles, and
    # a cell's particles arrive in runs already ordered)
    for c in prange(ncell):
        a, b = cell_start[c], cell_start[c + 1]
        for q in range(a + 1, b):
            v = order[q]
            key = pid[v]
            r = q - 1
            while r >= a and pid[order[r]] > key:
                order[r + 1] = order[r]
                r -= 1
            order[r + 1] = v
    for c in prange(nchunk):  # gather every array in the new order ...
        for p in range(c * n // nchunk, (c + 1) * n // nchunk):
            o = order[p]
            for a in range(3):
                fwork[a, p] = pos[a, o]
                fwork[3 + a, p] = vel[a, o]
            fwork[6, p] = mass[o]
            iwork[0, p] = pid[o]
            iwork[1, p] = species[o]
            iwork[2, p] = keys[o]
    for c in prange(nchunk):  # ... and copy it back, with the weights of the new order
        for p in range(c * n // nchunk, (c + 1) * n // nchunk):
            for a in range(3):
                pos[a, p] = fwork[a, p]
                vel[a, p] = fwork[3 + a, p]
            mass[p] = fwork[6, p]
            pid[p] = iwork[0, p]
            species[p] = iwork[1, p]
            keys[p] = iwork[2, p]
            stencil_into(pos[0, p], sp.x0, ix, off.i0, nx, kernel, R, wts, p, 0)
            stencil_into(pos[1, p], sp.y0, iy, off.j0, ny, kernel, R, wts, p, 1)
            stencil_into(pos[2, p], sp.z0, iz, off.k0, nz, kernel, R, wts, p, 2)
    return -1
