"""Formulas of the thesis as pure, vectorised functions (no state; imports only dustygas.units).

Each function's docstring names the thesis equation and the paper it comes from, and states
units: cgs for dimensional quantities, dimensionless where the thesis is. Engines and tests
call these functions; no formula is written twice. Constants come from :mod:`dustygas.units`.

Naming: ``mu`` is always the dust-to-gas ratio :math:`\\rho_d/\\rho_g` (thesis eq. 2.8; the
":math:`\\epsilon`" of Youdin & Johansen 2007 and ``numbers.md``); ``dust_fraction``/``eps`` is
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
"""

from .disk import (
    PowerLawDisk,
    alpha_viscosity,
    eta_armitage,
    eta_nakagawa,
    gas_azimuthal_velocity,
    isothermal_sound_speed,
    keplerian_angular_velocity,
    keplerian_velocity,
    midplane_density,
    pressure_exponent,
    radial_drift_velocity,
    scale_height,
    surface_density,
    temperature,
    viscous_radial_velocity,
    viscous_radial_velocity_power_law,
)
from .drag import (
    dust_fraction,
    dust_to_gas_ratio,
    epstein_drag_coefficient,
    epstein_grain_size,
    epstein_stopping_time,
    fraction_to_ratio,
    mean_free_path,
    mixture_stopping_time,
    ratio_to_fraction,
    stokes_number,
    stopping_time,
    thermal_speed,
)
from .equilibrium import NSHEquilibrium, nsh_velocities, nsh_velocities_moments, nsh_velocities_multi
from .growth import (
    alpha_tilde,
    drift_size,
    drift_size_midplane,
    fragmentation_sizes,
    fragmentation_stokes_numbers,
    growth_rate,
    growth_timescale,
    relative_velocity,
    stokes_number_growth,
)
from .settling import (
    growth_settling_threshold,
    growth_to_settling_ratio,
    settling_time,
    steady_settling_velocity,
)
from .timestep import acceleration_timestep, courant_timestep, drag_timestep, min_timestep

__all__ = [
    # equilibrium
    "NSHEquilibrium",
    "nsh_velocities",
    "nsh_velocities_multi",
    "nsh_velocities_moments",
    # settling
    "settling_time",
    "steady_settling_velocity",
    "growth_settling_threshold",
    "growth_to_settling_ratio",
    # drag
    "thermal_speed",
    "epstein_drag_coefficient",
    "epstein_stopping_time",
    "epstein_grain_size",
    "stokes_number",
    "mean_free_path",
    "mixture_stopping_time",
    "stopping_time",
    "dust_fraction",
    "dust_to_gas_ratio",
    "ratio_to_fraction",
    "fraction_to_ratio",
    # disk
    "PowerLawDisk",
    "surface_density",
    "temperature",
    "isothermal_sound_speed",
    "keplerian_angular_velocity",
    "keplerian_velocity",
    "scale_height",
    "midplane_density",
    "pressure_exponent",
    "eta_armitage",
    "eta_nakagawa",
    "gas_azimuthal_velocity",
    "alpha_viscosity",
    "viscous_radial_velocity",
    "viscous_radial_velocity_power_law",
    "radial_drift_velocity",
    # growth
    "alpha_tilde",
    "relative_velocity",
    "growth_rate",
    "drift_size",
    "drift_size_midplane",
    "fragmentation_stokes_numbers",
    "fragmentation_sizes",
    "growth_timescale",
    "stokes_number_growth",
    # timestep
    "courant_timestep",
    "acceleration_timestep",
    "drag_timestep",
    "min_timestep",
]
