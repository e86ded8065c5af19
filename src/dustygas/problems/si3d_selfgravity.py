"""``si3d-selfgravity``: the laptop stratified SI box with particle self-gravity (thesis §4.5).

The :mod:`~dustygas.problems.si3d` box (``τ_s = 1``, ``Z = 0.03``, ``Π = 0.05``, ``0.2 × 0.2 ×
0.3 H`` at 32 × 32 × 48 cells, one particle per cell) runs without gravity into the saturated
streaming instability, and at ``gravity.t_on`` the particles' self-gravity switches on
(:class:`~dustygas.particles.gravity.SelfGravity`, strength ``G̃ = 4πGρ_g0/Ω²``; Johansen et al.
2007, Nature 448, 1022; Simon et al. 2016, ApJ 822, 55): filaments denser than the Hill density
``ρ_H = 9/G̃`` (code units) collapse into bound clumps, which ``dustygas analyze clumps RUN``
catalogues and ``dustygas reproduce planetesimal-mass-function --from RUN`` fits.
``dustygas run si3d-selfgravity --from RUN`` starts it from the newest checkpoint of an ``si3d``
run written before ``gravity.t_on`` (:mod:`dustygas.branch`) instead of recomputing those orbits.

Defaults: ``G̃ = 0.5`` (``ρ_H = 18 ρ_g0``: at this resolution the filaments of the laptop box
reach a few tens of ``ρ_g0``, not the hundreds of the thesis's 256³ box, so the gravity is
stronger than Simon et al.'s 0.05 to reach the Hill density at all), switched on at 5 orbits,
run to 8. At ``τ_s = 1`` and ``Z = 0.03`` the layer settles and turns non-linear within two orbits
(the largest dust density is ~60 ``ρ_g0``, ~30 times the mean midplane density, from orbit 2 on),
so at 5 orbits the streaming instability is saturated and the run stays within about an hour of
the two-core laptop. The potential is shear-periodic in x and periodic in y; along z it follows the
particles (``gravity.boundary_z = "auto"``): periodic in the preset's periodic box (the mean density
subtracted), vacuum with open z faces (``problem.gas_boundary_z = "hydrostatic"``: isolated above
and below, as Simon et al. 2016; :mod:`dustygas.grid.gravity`).
"""

from __future__ import annotations

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..particles.gravity import GRAVITY_Z, SelfGravity, gravity_boundaries
from ..particles.params import particle_boundaries
from . import register
from .si3d import ORBIT, SI3D

__all__ = ["SI3DSelfGravity", "GRAVITY"]

#: the ``[gravity]`` section
GRAVITY = {
    "g_tilde": Param(0.5, "self-gravity strength G~ = 4 pi G rho_g0 / Omega^2 (Hill density 9/G~)", min=0.0,
                     min_open=True),
    "t_on": Param(5 * ORBIT, "time at which self-gravity switches on (the saturated streaming instability)",
                  "1/Omega", min=0.0),
    "boundary_z": Param("auto", "vertical boundary of the potential (auto: periodic with periodic particles, "
                        "else vacuum)", choices=GRAVITY_Z),
    "order": Param(2, "order of the centred differences of -grad(Phi)", choices=(2, 4)),
}


@register
class SI3DSelfGravity(SI3D):
    name = "si3d-selfgravity"
    runs_on_ranks = False  # self-gravity: the FFT Poisson solve needs the whole box (not decomposed yet)
    summary = ("si3d with particle self-gravity switched on in the saturated state (G~ = 0.5 at 5 orbits, to 8): "
               "bound clumps, planetesimals.")
    schema = {**SI3D.schema,
              "run": with_defaults(SI3D.schema["run"], tlim=8 * ORBIT, dt_snapshot=ORBIT / 4),
              "gravity": GRAVITY}
    smoke_overrides = ("grid.nx=16", "grid.ny=16", "grid.nz=24", "gravity.t_on=0")
    branches_from = ("si3d",)

    def check_branch(self, cfg, t: float) -> None:
        if cfg.gravity.t_on < t:
            raise ConfigError(f"gravity.t_on = {cfg.gravity.t_on:g} is before the checkpoint's time {t:g}: the "
                              "branch would differ from a run from t = 0; branch from an earlier checkpoint or "
                              "raise gravity.t_on")

    def validate(self, cfg) -> None:
        super().validate(cfg)
        if cfg.gravity.t_on >= cfg.run.tlim:
            raise ConfigError(f"gravity.t_on = {cfg.gravity.t_on:g}: the run ends before (run.tlim = "
                              f"{cfg.run.tlim:g}); lower gravity.t_on or raise run.tlim")
        g = cfg.grid
        kinds = particle_boundaries(cfg, ("shear-periodic", "periodic", cfg.problem.gas_boundary_z))
        gravity_boundaries((g.nx, g.ny, g.nz), kinds, cfg.gravity.boundary_z)

    def particle_terms(self, cfg) -> list:
        g = cfg.gravity
        return super().particle_terms(cfg) + [SelfGravity(g.g_tilde, g.t_on, g.boundary_z, g.order)]
