"""Outputs of the coupled particle-gas engine: dust density, momenta, Fourier modes, history,
snapshots, checkpoints and restarts (:class:`CoupledOutputs`, a base of
:class:`~dustygas.particles.coupling.ParticleGridEngine`).

The dust density of outputs is the run's assignment function without the grid-scale filter
(thesis eq. 4.24) at the current positions; the particle momentum is ``Σ m v`` with the full
azimuthal velocity (``v_y - q Ω x`` is added back under orbital advection, thesis eq. 4.2).
A checkpoint holds everything a bit-identical continuation needs: the particles, the
back-reaction source of the last corrector (the next predictor's) and the running budgets.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import SetupError, UserError
from ..grid.mesh import cell_average_factor
from .diagnostics import MODE_FIELDS, gas_mode, particle_mode, species_statistics
from .push import dust_values
from .store import ParticleStore

__all__ = ["CoupledOutputs", "FACES"]

FACES = ("x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper")


class CoupledOutputs:
    """Outputs and restarts of :class:`~dustygas.particles.coupling.ParticleGridEngine` (module docstring)."""

    def _mode_setup(self) -> None:
        if self.mode is None:
            return
        geom = self.geometry
        k = np.array([2 * np.pi * m / length if n > 1 else 0.0 for m, length, n in zip(self.mode, geom.box, geom.shape)])
        if not np.any(k):
            raise SetupError(f"mode {self.mode}: give a non-zero mode number along an active axis")
        self._k = k
        x, y, z = self.mesh.meshgrid()
        self._phase = np.exp(-1j * (k[0] * x + k[1] * y + k[2] * z)) * np.ones(tuple(reversed(self.mesh.shape)))
        self._cell_factor = cell_average_factor(k, geom.dx)
        self._xc = x

    # ------------------------------------------------------------------ outputs
    def prepared_particle_density(self) -> np.ndarray:
        """Particle mass density ``(nz, ny, nx)`` of the prepared (sorted, weighted) particles,
        the deposit of the drag problem (no grid-scale filter): for a mesh term's ``update``."""
        if self.feedback:
            return self._dep1[..., 0::4].sum(axis=-1)
        p = self.particles
        pos, vel, species, pid, mass = p.buffers()
        dust_values(pos, vel, species, mass, p.n, self._inv_vol, False, 0.0, 0.0, self._values, self._cols)
        self._rho_p[...] = 0.0
        self._deposit(self._rho_p, (0, 0, 0), self._values[:, :1], self._zero_cols)
        return self._rho_p[..., 0].copy()

    # ------------------------------------------------------------------ outputs
    def dust_density(self, per_species: bool = False) -> np.ndarray:
        """Particle mass density on the mesh ``(nz, ny, nx)`` (or ``(nspecies, nz, ny, nx)``)
        with the run's kernel (without the grid-scale filter), at the current positions."""
        p = self.particles
        self._prepare(self.t)
        pos, vel, species, pid, mass = p.buffers()
        dust_values(pos, vel, species, mass, p.n, self._inv_vol, False, 0.0, 0.0, self._values, self._cols)
        self._rho_p[...] = 0.0
        self._deposit(self._rho_p, (0, 0, 0), self._values[:, :1], self._cols)
        rho = np.moveaxis(self._rho_p, -1, 0).copy()
        return rho if per_species else rho.sum(axis=0)

    def particle_momentum(self) -> np.ndarray:
        """``Σ m v`` of the particles with the full azimuthal velocity (3,)."""
        p = self.particles
        mom = p.momentum()
        if self.geometry.velocity_relative_to_shear:
            mom[1] -= self.geometry.q * self.geometry.omega * float(p.mass @ p.pos[0])
        return mom

    def mode_amplitudes(self) -> np.ndarray:
        """Complex amplitudes of :data:`~dustygas.particles.diagnostics.MODE_FIELDS` for :attr:`mode`."""
        rho, vx, vy, vz = self.gas.primitive()
        qo = self.geometry.q * self.geometry.omega
        gas = gas_mode(rho, (vx, vy + qo * self._xc, vz), self._phase, self._cell_factor)
        dust = np.empty(4, dtype=np.complex128)
        p = self.particles
        shear_y = 0.0 if self.geometry.velocity_relative_to_shear else qo
        particle_mode(p.pos, p.vel, p.mass, self._k[0], self._k[1], self._k[2], shear_y, dust)
        return np.concatenate([gas, dust])

    def history(self) -> dict[str, float]:
        out = self.gas.history()
        pm = self.particle_momentum()
        p = self.particles
        out["particle_mass"] = float(p.mass.sum())
        for a, name in enumerate("xyz"):
            out[f"particle_momentum_{name}"] = float(pm[a])
            out[f"total_momentum_{name}"] = out[f"momentum_{name}"] + float(pm[a])
            out[f"particle_terms_impulse_{name}"] = float(self.terms_impulse[a])
            if self.gas_terms:
                out[f"gas_terms_impulse_{name}"] = float(self.gas_terms_impulse[a])
        if any(k in ("outflow",) for k in self.boundary_kinds):
            for face, name in enumerate(FACES):
                out[f"particle_mass_lost_{name}"] = float(self.lost[face, 0])
            out["particle_mass_lost"] = float(self.lost[:, 0].sum())
            for a, name in enumerate("xyz"):
                out[f"particle_momentum_lost_{name}"] = float(self.lost[:, 1 + a].sum())
        if self.forces.gravity_z > 0 or self.nspecies > 1 or self.geometry.shape[2] > 1:
            shear_y = 0.0 if self.geometry.velocity_relative_to_shear else self.geometry.q * self.geometry.omega
            stats = species_statistics(p.pos, p.vel, p.mass, p.species, self.nspecies, shear_y)
            for s in range(self.nspecies):
                for key, value in stats[s].items():
                    out[f"species_{s}_{key}"] = value
            rho_p = self.dust_density()
            out["rho_p_max"] = float(rho_p.max())
        for term in self.particle_terms:
            if hasattr(term, "history"):
                out.update(term.history(self, self.dust_density()))
        if self.mode is not None:
            for name, value in zip(MODE_FIELDS, self.mode_amplitudes()):
                out[f"mode_{name}_re"] = float(value.real)
                out[f"mode_{name}_im"] = float(value.imag)
        return out

    def _attrs(self) -> dict[str, Any]:
        attrs = {"particle_kernel": self.kernel, "feedback": self.feedback, "particle_smoothing": self.smooth,
                 "t_stop": self.species.t_stop.tolist(), "drag_law": list(self.laws), "nspecies": self.nspecies,
                 "particle_boundaries": list(self.boundary_kinds)}
        if self.mode is not None:
            attrs["mode"] = list(self.mode)
            attrs["mode_k"] = self._k.tolist()
        for term in self.particle_terms:
            if hasattr(term, "attrs"):
                attrs.update(term.attrs())
        return attrs

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays, attrs = self.gas.snapshot()
        rho_s = self.dust_density(per_species=True)
        arrays["rho_p"] = rho_s.sum(axis=0)
        if self.nspecies > 1:
            arrays["rho_p_species"] = rho_s
        for name, value in self.particles.arrays().items():
            arrays[f"particles/{name}"] = value
        for term in self.particle_terms:
            if hasattr(term, "snapshot"):
                arrays.update(term.snapshot(self, arrays["rho_p"]))
        return arrays, {**attrs, **self._attrs()}

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
        arrays, attrs = self.gas.checkpoint()
        for name, value in self.particles.arrays().items():
            arrays[f"particles/{name}"] = value
        if self._have_source:
            arrays["particles/gas_source"] = self._source.copy()
        arrays["particles/lost"] = self.lost.copy()
        arrays["particles/terms_impulse"] = np.concatenate([self.terms_impulse, self.gas_terms_impulse])
        arrays["particles/terms_impulse_rows"] = np.concatenate([self.terms_rows, self.gas_terms_rows], axis=1)
        return arrays, attrs

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        self.gas.restore({k: v for k, v in arrays.items() if not k.startswith("particles/")}, attrs)
        try:
            parts = {k: np.asarray(arrays[f"particles/{k}"]) for k in ("pos", "vel", "species", "pid", "mass")}
        except KeyError as exc:
            raise UserError(f"checkpoint has no particle array {exc}") from None
        self.particles = ParticleStore(**parts)
        self._allocate(self.particles.capacity)
        self._check_inside()
        self._vmax = np.max(np.abs(self.particles.vel), axis=1) if self.particles.n else np.zeros(3)
        self._have_source = "particles/gas_source" in arrays
        if self._have_source:
            self._source[...] = arrays["particles/gas_source"]
        self.lost[...] = arrays["particles/lost"] if "particles/lost" in arrays else 0.0
        rows = impulse_rows_from(arrays, self.terms_rows.shape[0])
        self.terms_rows[...] = rows[:, :3]
        self.gas_terms_rows[...] = rows[:, 3:]


def impulse_rows_from(arrays: dict, nrows: int) -> np.ndarray:
    """The impulse of the particle and the gas terms per row of cells ``(nrows, 6)`` of a whole-box
    checkpoint: its ``particles/terms_impulse_rows``, or, in a checkpoint written before them, its
    totals ``particles/terms_impulse`` in the first row (whose block then goes on adding to them:
    a restart on any rank count gives the same numbers); zeros without either.

    >>> impulse_rows_from({"particles/terms_impulse": np.arange(6.0)}, 2).tolist()
    [[0.0, 1.0, 2.0, 3.0, 4.0, 5.0], [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]]
    """
    if "particles/terms_impulse_rows" in arrays:
        rows = np.asarray(arrays["particles/terms_impulse_rows"], dtype=np.float64)
        if rows.shape != (nrows, 6):
            raise UserError(f"checkpoint holds impulse rows of shape {rows.shape}, the configuration needs ({nrows}, 6)")
        return rows.copy()
    rows = np.zeros((nrows, 6))
    if "particles/terms_impulse" in arrays:
        rows[0] = np.asarray(arrays["particles/terms_impulse"], dtype=np.float64)
    return rows
