"""The physics terms of the block-time-step engine beyond SPH gas: drag, grain growth, external force.

:class:`BlockPhysics` is a part of :class:`~dustygas.sph.timesteps.BlockStepEngine`: for the
particles active at a sub-step it evaluates the two-fluid drag pair forces (explicit, or averaged
over the coming pair steps), the growth rates of the dust particles' grains, the external
accelerations with their wanted steps, and the wanted SPH steps (thesis eqs. 2.13-2.15).
"""

from __future__ import annotations

import numpy as np

from ..physics.drag import epstein_stopping_time
from .active import active_drag, gas_at_dust
from .dust.two_fluid_kernels import pack
from .particles import DUST, GAS

__all__ = ["BlockPhysics"]


class BlockPhysics:
    """Drag, growth, external force and time-step criteria of the active particles (module docstring)."""

    @property
    def _implicit(self) -> bool:
        return self.drag is not None and self.drag.integration == "implicit"

    def _drag(self, ev, tau_new) -> np.ndarray:
        """Drag pair forces of the active particles into ``ev``'s pair table; returns their sum per slot.
        Implicit drag (``tau_new`` given) averages each pair over its coming pair step."""
        p, k, d = self.particles, self.kernel, self.drag
        _, length, per = self._box_arrays
        act, cross_o, cross_i, cross_n, pair_f = ev[0], ev[5], ev[6], ev[7], ev[8]
        rows, vel_pred = self._rows
        n = act.size
        tmin, acc_d = np.empty(n), np.empty((n, 3))
        c0 = d.drag.pair_factors(np.ones(1), np.ones(1), np.ones(1))[2]
        other = self.acc_other[rows] if tau_new is not None else np.zeros((rows.size, 0))
        tau = tau_new if tau_new is not None else self._tau
        active_drag(act, p.ptype, self._drag_table(rows, vel_pred, other), cross_o, cross_i, cross_n, k.shape,
                    k.ndim, length, per, c0, d.form == "projected", d.drag_kernel == "gas", tau, tau_new is not None,
                    self.grad_v, d.reconstruction == "gas", pair_f, acc_d, tmin)
        self.tmin[act] = tmin
        return acc_d

    def _grow(self, act, cross_o, cross_i, cross_n) -> None:
        """Growth rates of the active dust particles' grains (the ``growth`` parameter)."""
        p, k, g = self.particles, self.kernel, self.growth
        rho_g, cs_g = np.empty(act.size), np.empty(act.size)
        gas_at_dust(act, p.ptype, p.pos, p.mass, p.h, self.rho, self.cs, cross_o, cross_i, cross_n, k.shape, k.norm,
                    k.ndim, rho_g, cs_g)
        dust = p.ptype[act] == DUST
        d = act[dust]
        size = p.extra["grain_size"][d]
        coupled = rho_g[dust] > 0
        R = np.hypot(p.pos[d, 0], p.pos[d, 1])
        omega = np.sqrt(self.external.star_gm / R**3)
        with np.errstate(divide="ignore", invalid="ignore"):
            ts = epstein_stopping_time(size, self.drag.drag.grain_density, np.where(coupled, rho_g[dust], 1.0),
                                       np.where(coupled, cs_g[dust], 1.0))
            rate = np.where(coupled, g.rate(size, self.rho[d], ts, cs_g[dust], omega), 0.0)
        self._size_rate[d] = rate

    def _external(self, sel) -> np.ndarray:
        """External accelerations of the particles ``sel``, their potentials and wanted external steps."""
        acc_ext = np.zeros((sel.size, 3))
        if self.external.active:
            phi = np.empty(sel.size)
            self.external.add(self.particles.pos[sel], acc_ext, phi)
            self.phi[sel] = phi
            amag = np.sqrt(np.einsum("ij,ij->i", acc_ext, acc_ext))
            with np.errstate(divide="ignore"):
                self.dt_want_ext[sel] = self.options.c_force * np.sqrt(self.particles.h[sel] / amag)
        else:
            self.dt_want_ext[sel] = np.inf
        return acc_ext

    def _drag_table(self, rows, vel_pred, other) -> np.ndarray:
        """The drag pair table (:func:`dustygas.sph.dust.two_fluid_kernels.drag_pair`) with current rows."""
        p, k = self.particles, self.kernel
        width = 11 + other.shape[1]
        if self._dtable is None or self._dtable.shape != (len(p), width):
            self._dtable = np.zeros((len(p), width))
        law = self.drag.drag
        is_gas = p.ptype[rows] == GAS
        d = rows[~is_gas]
        size = p.extra["grain_size"][d] if law.needs_sizes else None
        kg, kd, _ = law.pair_factors(self.rho[rows[is_gas]], self.cs[rows[is_gas]], self.rho[d], size)
        kk = np.empty(rows.size)
        kk[is_gas], kk[~is_gas] = kg, kd
        cnorm = k.norm_drag if self.drag.form == "projected" else k.norm
        hinv = 1.0 / p.h[rows]
        self._dtable[rows] = pack(p.pos[rows], vel_pred, p.mass[rows], hinv, cnorm * hinv**k.ndim, self.rho[rows], kk,
                                  other)
        return self._dtable

    def _wanted_steps(self, act, acc) -> np.ndarray:
        """Largest stable SPH step of each active particle: Courant (gas, thesis eq. 2.13), SPH and drag
        acceleration (eq. 2.14), explicit drag (dust, eq. 2.15)."""
        p, o = self.particles, self.options
        if o.fixed_dt > 0:
            return np.full(act.size, o.fixed_dt)
        h = p.h[act]
        amag = np.sqrt(np.einsum("ij,ij->i", acc, acc))
        with np.errstate(divide="ignore"):
            dt = o.c_force * np.sqrt(h / amag)
            gas = p.ptype[act] == GAS
            dt = np.where(gas, np.minimum(dt, o.c_cour * h / np.where(gas, self.vsig[act], 1.0)), dt)
            if self.drag is not None and not self._implicit:
                dt = np.where(gas, dt, np.minimum(dt, self.drag.c_drag * self.tmin[act]))
        return dt
