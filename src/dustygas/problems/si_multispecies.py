"""``si-multispecies``: one linear streaming-instability eigenmode of gas + N particle species.

The 2D radial-vertical box of :mod:`dustygas.problems.si_linear` (one wavelength per side,
global pressure gradient, particles displaced on a lattice to realise the eigenmode) with N dust
species of stopping times τ_j and dust-to-gas ratios μ_j in their N-species NSH drift
(Benítez-Llambay, Krapp & Pessah 2019, eqs. 79-84); every species has its own lattice of
particles, displaced by its own density wave of the eigenvector of :mod:`dustygas.linear`.

Preset ``si-linC``: the two-species test "linC" of Benítez-Llambay, Krapp & Pessah (2019,
Table 4): τ_s = (0.0425, 0.1), μ = (1, 0.5), K_x = K_z = 50, Π = 0.05; growth rate
0.3027262829 Ω (consistent linearisation of fixed-t_s drag, what the engine integrates).
Measured (one particle per cell and species, t = 0 → 7, ``dustygas analyze growth``): 32²
−3.2 %, 48² −1.38 % (the preset; eight fields within 0.45 %).
"""

from __future__ import annotations

from ..config import Param, with_defaults
from ..errors import ConfigError
from ..particles.params import PARTICLES
from ..runner import RUN_SCHEMA
from . import Problem, preset, register
from .si_linear import SI_GRID, SI_PRESSURE_FRAME, SI_SCHEME, _scheme, streaming_box

__all__ = ["SIMultiSpecies"]


@register
class SIMultiSpecies(Problem):
    name = "si-multispecies"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "One linear streaming-instability eigenmode of gas + N particle species in a 2D x-z box (BKP19 linC)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=8.0, dt_history=0.01),
        "grid": SI_GRID,
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "taus": Param([0.0425, 0.1], "stopping time of each species, tau_s = Omega t_s (fixed)", "1/Omega",
                          type="float_list", min=0.0, min_open=True),
            "mu": Param([1.0, 0.5], "dust-to-gas density ratio of each species", type="float_list", min=0.0,
                        min_open=True),
            "kx": Param(50.0, "radial wavenumber K_x = k_x eta r", "1/(eta r)", min=0.0, min_open=True),
            "kz": Param(50.0, "vertical wavenumber K_z = k_z eta r (sign picks the mode)", "1/(eta r)"),
            "Pi": Param(0.05, "eta v_K / c_s", min=0.0, min_open=True),
            "amplitude": Param(1e-6, "amplitude of delta rho_p / rho_p0 of species 0", min=0.0, min_open=True,
                               max=0.1),
            "pressure_frame": SI_PRESSURE_FRAME,
        },
    }

    def validate(self, cfg) -> None:
        p = cfg.problem
        if len(p.taus) != len(p.mu) or not p.taus:
            raise ConfigError(f"problem.taus has {len(p.taus)} species but problem.mu has {len(p.mu)}: give one "
                              "stopping time and one dust-to-gas ratio per species")
        if p.kz == 0:
            raise ConfigError("problem.kz = 0: the 2D box needs a vertical wavenumber")

    def build(self, cfg):
        p = cfg.problem
        box = streaming_box(list(p.taus), list(p.mu), p.kx, p.kz, p.Pi, p.amplitude, (cfg.grid.nx, cfg.grid.nz),
                            _scheme(cfg), lattice=cfg.particles.lattice, kernel=cfg.particles.kernel,
                            pressure_frame=p.pressure_frame, cfg=cfg)
        return box.engine


preset("si-linC", SIMultiSpecies, "Benitez-Llambay, Krapp & Pessah (2019) linC: two species tau_s = 0.0425, 0.1, "
       "mu = 1, 0.5, K = 50; growth 0.3027 (48^2, 1 ppc per species: -1.4 %).",
       run={"tlim": 7.0, "dt_history": 0.01}, grid={"nx": 48, "nz": 48})
