"""Two-fluid dust: a species of dust particles coupled to the gas particles by drag (thesis §2.1, §3.3).

Dust particles (``ptype == DUST``) carry the dust mass and move with the dust velocity (eq. 2.5a);
their density is summed over dust particles only (eq. 3.1 with the dust's own smoothing
lengths). Each derivative evaluation adds the drag of :mod:`~dustygas.sph.dust.two_fluid_kernels`
to both species -- projected (Monaghan & Kocharyan 1995, eq. 3.19, default) or non-projected
(eq. 3.18), with the double-hump kernel of Laibe & Price (2012a), optionally with the velocity
reconstruction of Price & Laibe (2020) -- and the drag heating to the gas (eq. 2.5f).

Time integration: ``explicit`` drag limits the step to :math:`C_{\\rm drag}\\min t_s` over the
interacting pairs (eq. 2.15); ``implicit`` uses the pairwise exponential average and has no drag
limit. With an adiabatic gas the heating of each kick is the work of the drag over the kick at the
mean of the old and new velocities, :math:`-\\Delta t\\sum_j m_j\\mathbf a^{\\rm drag}_j\\cdot(\\mathbf v^{\\rm old}_j + \\mathbf v^{\\rm new}_j)/2`
over both species, distributed over the gas particles in proportion to their heating rates. Where
only the drag acts (the dustybox) this is the kick's exact loss of kinetic energy, so kinetic plus
thermal energy is conserved to round-off and not only to the integrator's order.

**Resolution.** Laibe & Price (2012a) showed that the two-fluid drag over-damps sound waves
unless the gas smoothing length resolves the stopping length, :math:`h < c_s t_s`. Where a gas
particle with dust neighbours violates it, the module writes a log line (once, and again when
the state changes) and reports ``drag_unresolved_fraction`` (fraction of such gas particles)
and ``drag_resolution`` (largest :math:`h/(c_s t_s)`) in the history; the reconstruction is the
remedy (Price & Laibe 2020).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import SetupError
from ..modules import SPHModule
from ..neighbours import NeighbourFinder
from ..particles import DUST, GAS
from .drag_law import DragLaw
from .two_fluid_kernels import KERNEL_AVERAGE, KERNEL_OTHER, KERNEL_OWN, drag_pass, pack, velocity_gradient

__all__ = ["TwoFluidOptions", "TwoFluidDust", "RECONSTRUCTIONS", "DRAG_FORMS", "DRAG_INTEGRATIONS", "DRAG_KERNELS"]

RECONSTRUCTIONS = ("mc", "none", "unlimited", "gas")
DRAG_FORMS = ("projected", "non-projected")
DRAG_INTEGRATIONS = ("explicit", "implicit")
#: smoothing lengths of the drag kernel: the average of the pair's (Laibe & Price 2012a) or the gas
#: particle's alone, :math:`D_{ai}(h_a)` as thesis eq. 3.19 writes it
DRAG_KERNELS = ("average", "gas")
ACC, HEAT, TMIN = "drag_acc", "drag_heating", "drag_min_stopping_time"


@dataclass(frozen=True)
class TwoFluidOptions:
    """Choices of the two-fluid module (module docstring)."""

    drag: DragLaw = field(default_factory=DragLaw)
    form: str = "projected"
    reconstruction: str = "mc"
    integration: str = "explicit"
    c_drag: float = 0.9
    heating: bool = True
    drag_kernel: str = "average"

    def __post_init__(self) -> None:
        checks = [
            (self.form in DRAG_FORMS, f"form must be one of {', '.join(DRAG_FORMS)}"),
            (self.reconstruction in RECONSTRUCTIONS, f"reconstruction must be one of {', '.join(RECONSTRUCTIONS)}"),
            (self.integration in DRAG_INTEGRATIONS, f"integration must be one of {', '.join(DRAG_INTEGRATIONS)}"),
            (self.c_drag > 0, "c_drag must be > 0"),
            (self.drag_kernel in DRAG_KERNELS, f"drag_kernel must be one of {', '.join(DRAG_KERNELS)}"),
        ]
        for ok, msg in checks:
            if not ok:
                raise SetupError(f"two-fluid dust: {msg}")


class TwoFluidDust(SPHModule):
    """Drag between the gas and dust particles of an :class:`~dustygas.sph.SPHEngine` (module docstring).

    ``grain_size`` gives per-dust-particle radii for Epstein drag (default: the drag law's).
    """

    name = "two_fluid"

    def __init__(self, options: TwoFluidOptions, grain_size=None):
        self.options = options
        self._size0 = grain_size
        self.dt = 0.0
        self.unresolved = False
        self.unresolved_fraction = 0.0
        self.worst_resolution = 0.0
        self._messages: list[str] = []

    def attach(self, engine) -> None:
        p = engine.particles
        dust = p.ptype == DUST
        if not dust.any() or not (p.ptype == GAS).any():
            raise SetupError("two-fluid dust needs both gas and dust particles")
        if np.any(p.h[dust] <= 0):
            raise SetupError("dust particles need positive initial smoothing lengths")
        n = len(p)
        ex = p.extra
        ex.setdefault(ACC, np.zeros((n, 3)))
        ex.setdefault(HEAT, np.zeros(n))
        ex.setdefault(TMIN, np.full(n, math.inf))
        if self.options.drag.needs_sizes:
            s = np.full(n, self.options.drag.grain_size) if self._size0 is None else \
                np.array(np.broadcast_to(np.asarray(self._size0, dtype=np.float64), (n,)))
            ex.setdefault("grain_size", s)
        self.finder = NeighbourFinder(engine.box, engine.kernel.radius, method=engine.options.neighbour_search)
        if self.options.integration == "explicit":
            engine.timestep_limits.append(self.timestep)

    # ------------------------------------------------------------------ evaluation
    def predict(self, engine, dt: float) -> None:
        self.dt = dt

    def add_derivatives(self, engine, vel, u) -> None:
        p, o, k = engine.particles, self.options, engine.kernel
        ex = p.extra
        g = np.flatnonzero(p.ptype == GAS)
        d = np.flatnonzero(p.ptype == DUST)
        pos_g, pos_d = p.pos[g], p.pos[d]
        h_d = p.h[d]
        rho_d = np.empty(d.size)
        omega_d = np.empty(d.size)
        nl_dd = engine._smoothing_lengths(pos_d, p.mass[d], h_d, rho_d, omega_d)  # dust density (eq. 3.1)
        p.h[d] = h_d
        engine.rho[d] = rho_d
        engine.omega[d] = omega_d
        h_g = p.h[g]
        vel_g, vel_d = vel[g], vel[d]
        rho_g, cs_g = engine.rho[g], engine.cs[g]
        _, length, per = engine._box_arrays
        recon = o.reconstruction != "none"
        mass_g, mass_d = p.mass[g], p.mass[d]
        grad_g = np.zeros((g.size, 9))
        grad_d = np.zeros((d.size, 9))
        if recon:
            nl_gg = engine.last_neighbours
            velocity_gradient(pack(pos_g, vel_g, mass_g), h_g, rho_g, engine.omega[g], nl_gg.index, nl_gg.count,
                              k.shape, k.norm, k.ndim, length, per, grad_g)
            velocity_gradient(pack(pos_d, vel_d, mass_d), h_d, rho_d, omega_d, nl_dd.index, nl_dd.count,
                              k.shape, k.norm, k.ndim, length, per, grad_d)
        size = ex["grain_size"][d] if o.drag.needs_sizes else None
        kg, kd, c0 = o.drag.pair_factors(rho_g, cs_g, rho_d, size)
        implicit = o.integration == "implicit"
        dt_imp = self.dt if implicit else 0.0
        heat = engine.eos.evolves_energy and o.heating
        projected = o.form == "projected"
        limit = o.reconstruction == "mc"
        hinv_g, hinv_d = 1.0 / h_g, 1.0 / h_d
        cnorm = k.norm_drag if projected else k.norm
        other_g = engine.acc[g] if implicit else np.zeros((g.size, 0))  # non-drag accelerations
        other_d = engine.acc[d] if implicit else np.zeros((d.size, 0))
        table_g = pack(pos_g, vel_g, mass_g, hinv_g, cnorm * hinv_g**k.ndim, rho_g, kg, other_g)
        table_d = pack(pos_d, vel_d, mass_d, hinv_d, cnorm * hinv_d**k.ndim, rho_d, kd, other_d)
        acc_g = np.empty((g.size, 3))
        acc_d = np.empty((d.size, 3))
        q_g = np.empty(g.size)
        q_d = np.empty(d.size)
        t_g = np.empty(g.size)
        t_d = np.empty(d.size)
        nl_gd = self.finder.find(pos_d, h_d, query_pos=pos_g, query_h=h_g, allow_overlap=True)
        gas_kernel = o.drag_kernel == "gas"
        drag_pass(table_g, grad_g, table_d, grad_d, nl_gd.index, nl_gd.count, k.shape, k.ndim, length, per,
                  c0, projected, recon, limit, dt_imp, heat, acc_g, q_g, t_g, KERNEL_OWN if gas_kernel else KERNEL_AVERAGE,
                  1 if o.reconstruction == "gas" else 0)
        nl_dg = self.finder.find(pos_g, h_g, query_pos=pos_d, query_h=h_d, allow_overlap=True)
        drag_pass(table_d, grad_d, table_g, grad_g, nl_dg.index, nl_dg.count, k.shape, k.ndim, length, per,
                  c0, projected, recon, limit, dt_imp, False, acc_d, q_d, t_d, KERNEL_OTHER if gas_kernel else KERNEL_AVERAGE,
                  2 if o.reconstruction == "gas" else 0)
        drag_acc = ex[ACC]
        drag_acc[g] = acc_g
        drag_acc[d] = acc_d
        engine.acc += drag_acc
        heating = ex[HEAT]
        heating[:] = 0.0
        if heat:
            heating[g] = q_g
            engine.dudt[g] += q_g
        tmin = ex[TMIN]
        tmin[g] = t_g
        tmin[d] = t_d
        self._check_resolution(engine, g, h_g, cs_g, t_g)

    def _check_resolution(self, engine, g, h_g, cs_g, t_g) -> None:
        """Laibe & Price (2012a): the gas must resolve the stopping length, h < c_s t_s."""
        coupled = np.isfinite(t_g)
        ratio = np.where(coupled, h_g / (cs_g * np.where(coupled, t_g, 1.0)), 0.0)
        self.worst_resolution = float(ratio.max(initial=0.0))
        bad = ratio > 1.0
        self.unresolved_fraction = float(bad.sum() / max(coupled.sum(), 1))
        if bad.any() != self.unresolved:
            self.unresolved = bool(bad.any())
            if self.unresolved:
                self._messages.append(
                    f"warning: two-fluid drag not resolved at time={engine.t:.6g}: h > c_s t_s for "
                    f"{100 * self.unresolved_fraction:.3g}% of the gas particles with dust neighbours (largest "
                    f"h/(c_s t_s) = {self.worst_resolution:.3g}); sound waves are over-damped unless "
                    f"h < c_s t_s (Laibe & Price 2012){'' if self.options.reconstruction != 'none' else '; consider sph dust reconstruction'}")
            else:
                self._messages.append(f"two-fluid drag resolved again (h < c_s t_s) at time={engine.t:.6g}")

    # ------------------------------------------------------------------ time integration
    def kick(self, engine, dt: float, final: bool) -> None:
        ex = engine.particles.extra
        q = ex[HEAT]
        if not (engine.eos.evolves_energy and self.options.heating):
            return
        p = engine.particles
        a_d = ex[ACC]  # work of the drag over the kick at the mean of the old and new velocities
        lost = -dt * float(np.sum(p.mass * np.einsum("ij,ij->i", a_d, p.vel - 0.5 * dt * engine.acc)))
        given = dt * float(np.dot(p.mass, q))
        if given != 0.0 and lost != 0.0:
            p.u += (lost / given - 1.0) * dt * q  # heating of this kick = the kinetic energy the drag removed

    def timestep(self, engine) -> float:
        return self.options.c_drag * float(np.min(engine.particles.extra[TMIN], initial=math.inf))

    # ------------------------------------------------------------------ diagnostics
    def history(self, engine, out: dict[str, float]) -> None:
        p = engine.particles
        dust = p.ptype == DUST
        out["dust_mass"] = float(p.mass[dust].sum())
        out["drag_unresolved_fraction"] = self.unresolved_fraction
        out["drag_resolution"] = self.worst_resolution

    def messages(self) -> list[str]:
        out, self._messages = self._messages, []
        return out

    def state(self) -> dict[str, Any]:
        return {"dt": self.dt, "unresolved": int(self.unresolved), "unresolved_fraction": self.unresolved_fraction,
                "worst_resolution": self.worst_resolution}

    def restore_state(self, state: dict[str, Any]) -> None:
        if state:
            self.dt = float(state["dt"])
            self.unresolved = bool(state["unresolved"])
            self.unresolved_fraction = float(state["unresolved_fraction"])
            self.worst_resolution = float(state["worst_resolution"])
