"""Formulas of the thesis as pure, vectorised functions (no state; imports only dustygas.units).

Each function's docstring names the thesis equation and the paper it comes from, and states
units: cgs for dimensional quantities, dimensionless where the thesis is. Engines and tests
call these functions; no formula is written twice. Constants come from :mod:`dustygas.units`.

Naming: ``mu`` is always the dust-to-gas ratio :math:`\\rho_d/\\rho_g` (thesis eq. 2.8; the
":math:`\\epsilon`" of Youdin & Johansen 2007); ``dust_fraction``/``eps`` is
always :math:`\\rho_d/(\\rho_d+\\rho_g)` (eq. 2.7). ``eta_armitage`` is the :math:`\\eta` of
thesis eq. 3.24, ``eta_nakagawa`` the streaming-instability :math:`\\eta` (half of it).

Modules
-------
drag
    Epstein drag coefficient and stopping time (eqs. 2.3, 2.6, corrected), Stokes number
    (1.1), Stokes-regime drag and the Epstein/Stokes switch, ε <-> μ (2.7, 2.8).
disk
    Power-law disks: Σ, T, c_s, Ω, v_K, H, midplane ρ, pressure exponent, η (3.24), v_θ,gas
    (3.25), α viscosity (3.8), viscous gas velocity (3.22), radial dust drift (3.23).
equilibrium
    Nakagawa-Sekiya-Hayashi steady drift, one and N species (thesis eq. 4.8).
settling
    Settling time, steady settling speed, growth-versus-settling criterion (eqs. 4.18-4.20).
growth
    Turbulent relative velocity (3.7), local growth/fragmentation rate (3.6), drift size
    (3.9-3.10), fragmentation sizes (3.9), Vericel et al. (2021) analytic growth.
timestep
    Courant, acceleration and drag time-step criteria (eqs. 2.12-2.15).
gravity
    Self-gravity in the shearing box: G~ = 4πGρ/Ω², Hill density, radius and energy, Toomre's
    Q and dispersion relation.
exact, riemann, exact_riemann, shearing_sheet
    Exact solutions of the test problems: sound wave, dusty box and dusty wave (Laibe & Price
    2011), dust diffusion (Price & Laibe 2015), the hydrostatic dusty column; isothermal and
    ideal-gas Riemann problems (Toro 2009); Kelvin's shearing wave. Not re-exported here.

Every public name of the formula modules (``drag, disk, equilibrium, growth, settling,
timestep``) is available from :mod:`dustygas.physics` itself.
"""

from . import disk, drag, equilibrium, growth, settling, timestep
from .disk import *  # noqa: F401,F403
from .drag import *  # noqa: F401,F403
from .equilibrium import *  # noqa: F401,F403
from .growth import *  # noqa: F401,F403
from .settling import *  # noqa: F401,F403
from .timestep import *  # noqa: F401,F403

__all__ = [*equilibrium.__all__, *settling.__all__, *drag.__all__, *disk.__all__, *growth.__all__, *timestep.__all__]
