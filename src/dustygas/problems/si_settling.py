"""``si-settling``: the settling-enhanced streaming instability (thesis §4.1.4, §4.4, Fig 4.6).

The 2D x-z periodic box of :mod:`dustygas.problems.si_linear` with the global radial pressure
gradient, in which the dust also streams vertically through the gas at the steady speed
``v̄_z`` of the linear theory's settling variant (thesis eq. 4.19,
``v̄_z = -c_s τ_s/(2τ_s² + 1)``, downward, or a given value). The background is an *exact*
steady state of the equations integrated here: a constant vertical acceleration
``v̄_z/t_s`` on every particle balances its drag at ``v̄_z``, and the opposite constant
acceleration per unit gas mass, ``-μ v̄_z/t_s``, cancels the mean back-reaction on the gas
(total momentum is still conserved). Constant accelerations per unit mass do not enter the
linearised velocity equations, so :mod:`dustygas.linear` with ``vz`` computes the growth of
exactly this background (its operator documents the same forcing; the drag linearisation
is the "consistent" one of fixed-``t_s`` drag with momentum-conserving back-reaction).

``problem.frame = "dust"`` adds the uniform velocity ``W = (-V_x, 0, -v̄_z)`` to gas and
dust (``V_x`` the dust's NSH radial drift), so the particle lattice is at rest on the mesh and
the gas streams through it. With velocities relative to the shear and k_y = 0 the equations
have no explicit x or z, so this is a Galilean boost once the constant acceleration
``(2 - q) Ω W_x ŷ`` (on every particle and per unit gas mass) cancels the Coriolis force of
the radial part; the linear theory is the same with ``ω → ω + k·W``. It matters at small
τ_s: at τ_s = 0.001 (Fig 4.6) the lattice of the gas frame drifts radially through the cells
(half a cell in 4/Ω at 16²) and each half-cell passage feeds the inertial wave of the same
wave vector, which the dust damps at only 5.6e-5 Ω (:mod:`dustygas.reproduce.fig4_6`).

The wave vector is given as ``|K|`` and the angle ``θ_k = tan⁻¹(K_x/|K_z|)`` from the vertical
(thesis Fig 4.3 uses 30°), with the sign of ``K_z``: ``K_x = |K| sin θ_k``,
``K_z = ±|K| cos θ_k``. The box holds one wavelength along x and z.
"""

from __future__ import annotations

import math

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..particles.params import PARTICLES
from ..runner import RUN_SCHEMA
from . import Problem, register
from .si_linear import SI_AMPLITUDE, SI_GRID, SI_SCHEME, SI_TAUS, _scheme, streaming_box

__all__ = ["SISettling", "settling_drift", "frame_velocity"]


def settling_drift(taus: float, Pi: float, vz) -> float:
    """Vertical dust drift in ``η v_K``: thesis eq. 4.19 (downward) for ``"settling"``, else ``vz``.

    >>> round(settling_drift(0.1, 0.05, "settling"), 6)
    -1.960784
    """
    from ..linear.operator import resolve_vz

    return float(resolve_vz(vz, [taus], Pi)[0])


def frame_velocity(taus: float, mu: float, vz: float, frame: str) -> tuple[float, float]:
    """Velocity ``(W_x, W_z)`` in ``η v_K`` added to gas and dust by ``problem.frame``: zero for
    ``"gas"``; for ``"dust"`` minus the dust's NSH radial drift (thesis eq. 4.8) and minus ``v̄_z``,
    which holds the particle lattice at rest on the mesh. A mode of frequency ``ω`` in the gas
    frame has ``ω + k·W`` in the run."""
    if frame == "gas":
        return 0.0, 0.0
    from ..physics import nsh_velocities

    return -float(nsh_velocities(taus, mu).dust_vx), -float(vz)


@register
class SISettling(Problem):
    name = "si-settling"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "Settling-enhanced streaming instability: one eigenmode with a steady vertical dust drift (Fig 4.6)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=40.0, dt_history=0.05),
        "grid": with_defaults(SI_GRID, nx=32, nz=32),
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "taus": SI_TAUS,
            "mu": Param(0.1, "dust-to-gas density ratio", min=0.0, min_open=True),
            "k": Param(0.6, "wavenumber |K| = |k| eta r", "1/(eta r)", min=0.0, min_open=True),
            "theta": Param(30.0, "angle of k from the vertical, tan(theta) = K_x/|K_z|", "deg", min=0.0, max=90.0,
                           min_open=True, max_open=True),
            "kz_sign": Param(-1, "sign of K_z", choices=(1, -1)),
            "Pi": Param(0.05, "eta v_K / c_s", min=0.0, min_open=True),
            "vz": Param("settling", "vertical dust drift relative to the gas in eta v_K, or 'settling' for thesis "
                        "eq. 4.19 (downward)", type="str"),
            "amplitude": SI_AMPLITUDE,
            "frame": Param("gas", "frame of the box: 'gas' (the gas at rest, the particle lattice drifting through "
                           "the cells) or 'dust' (Galilean boost, with the constant force that cancels its Coriolis "
                           "force, that holds the particle lattice at rest on the mesh)", choices=("gas", "dust")),
        },
    }

    def validate(self, cfg) -> None:
        vz = cfg.problem.vz
        if vz != "settling":
            try:
                float(vz)
            except ValueError:
                raise ConfigError(f"problem.vz = {vz!r}: give a number (eta v_K) or 'settling'") from None

    def build(self, cfg):
        p = cfg.problem
        th = math.radians(p.theta)
        kx, kz = p.k * math.sin(th), p.kz_sign * p.k * math.cos(th)
        vz = settling_drift(p.taus, p.Pi, p.vz if p.vz == "settling" else float(p.vz))
        box = streaming_box(p.taus, p.mu, kx, kz, p.Pi, p.amplitude, (cfg.grid.nx, cfg.grid.nz), _scheme(cfg),
                            lattice=cfg.particles.lattice, kernel=cfg.particles.kernel, vz=vz, cfg=cfg,
                            frame_v=frame_velocity(p.taus, p.mu, vz, p.frame))
        return box.engine
