"""Linear theory of the streaming instability (thesis §4.1 and §4.6).

Conventions (stated once here; every module of :mod:`dustygas.linear` refers to them)
------------------------------------------------------------------------------------
* Unstratified shearing sheet: x radial (outward), y azimuthal (along the rotation),
  z vertical; Ω = 1; background shear flow −(3/2)Ω x ŷ. Velocities are perturbations
  relative to that shear flow.
* Perturbations ∝ exp(i k·x − i ω t): the growth rate is s = Im ω and the frequency Re ω
  ("standard" convention; Youdin & Johansen 2007 print Re ω with the opposite sign).
* Units: velocities in ηv_K, lengths in ηr (so K = kηr), times in 1/Ω. τ_s = Ω t_s is the
  stopping time, ``mu`` = μ = ρ_p0/ρ_g0 the dust-to-gas density ratio (YJ07's ε; in dustygas
  ``mu`` always means the dust-to-gas ratio) and Π = ηv_K/c_s (default 0.05), so the sound
  speed is c_s = 1/Π; Π = 0 is the exact incompressible limit.
* Densities are relative perturbations (δρ_g/ρ_g0, δρ_p/ρ_p0); eigenvectors are normalised so
  that δρ_p/ρ_p0 = 1 for dust species 0.
* An optional steady vertical dust drift ``vz`` (relative to the gas, in ηv_K) is positive
  upwards; ``vz="settling"`` is thesis eq. 4.19 pointing down, −(1/Π) τ_s/(2τ_s² + 1).
* Drag linearisations ``"consistent"`` (default; fixed t_s), ``"yj07"`` (the YJ07 table's) and
  ``"epstein"`` (t_s ∝ 1/ρ_g) are defined in :mod:`dustygas.linear.operator`.

Public API
----------
>>> from dustygas.linear import StreamingParams, fastest_mode, growth_rate
>>> m = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, drag="yj07"))   # YJ07 linA
>>> round(m.growth_rate, 7), round(m.frequency, 7)
(0.4190204, 0.3480127)
>>> float(growth_rate(taus=0.1, mu=3.0, kx=30.0, kz=30.0)).__round__(10)      # consistent drag
0.4190091323

Array-like physical parameters are keyword-only everywhere (``growth_rate(taus=..., mu=...)``,
``growth_map(mu=..., taus=...)``, ``sweep(mu=..., taus=..., kx=..., ky=...)``): a swap cannot run.

Modules: :mod:`~dustygas.linear.operator` (the equations), :mod:`~dustygas.linear.modes`
(eigenmodes, growth rates), :mod:`~dustygas.linear.eigensolver` (compiled QR),
:mod:`~dustygas.linear.maps` (growth-rate maps), :mod:`~dustygas.linear.resonance` (analytic
growth rates with a settling drift: the SH18 resonance, the large-k plateau, the (μk)^{1/3}
branch), :mod:`~dustygas.linear.polydisperse` (size distributions as N species),
:mod:`~dustygas.linear.shearing_wave` (one non-axisymmetric shearing wave, scipy),
:mod:`~dustygas.linear.sweep`, :mod:`~dustygas.linear.sweep_kernel`,
:mod:`~dustygas.linear.sweep_run` (compiled shearing-wave sweeps over (μ, τ_s, k_x0, k_y),
preferred wavevectors; thesis §4.6.2).
"""

from .modes import Eigenmodes, Mode, eigenmodes, fastest_mode, growth_rate
from .operator import DRAG_MODELS, StreamingParams, operator_matrix, state_labels

__all__ = [
    "StreamingParams",
    "DRAG_MODELS",
    "Mode",
    "Eigenmodes",
    "eigenmodes",
    "fastest_mode",
    "growth_rate",
    "operator_matrix",
    "state_labels",
]
