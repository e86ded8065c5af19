"""``si-linear``: one linear streaming-instability eigenmode, gas + particles (thesis §4.4).

The 2D radial-vertical (x-z) shearing box of Youdin & Johansen (2007) and Bai & Stone (2010a,
§4.3): uniform gas and dust in the Nakagawa-Sekiya-Hayashi drift (thesis eq. 4.8) plus one
eigenmode of :mod:`dustygas.linear` (one source of truth: the "consistent" linearisation of
fixed-``t_s`` drag with momentum-conserving back-reaction is what this simulation integrates)
with ``δρ_p/ρ_p0`` of amplitude ``amplitude``. The box holds one wavelength along each axis:
``L_x = 2π/k_x``, ``L_z = 2π/|k_z|``.

Units: ``Ω = c_s = H = 1`` for the gas and ``ρ_g0 = 1``; with ``Π = η v_K / c_s`` the velocity
unit of the linear theory is ``η v_K = Π`` and its length unit ``η r = Π`` (so ``k = K/Π``).
The global pressure gradient is the force ``2 η v_K Ω x̂`` on the gas, or with
``problem.pressure_frame = "particles"`` the opposite force on the particles (velocities then
shifted by ``+η v_K ŷ``, as in Bai & Stone 2010a). Orbital advection stores velocities relative to the
shear (in the x-z plane it only removes the velocity jump of the radial images).

Particles (as in Athena's set-up, Bai & Stone 2010a) start on a lattice of ``lattice^2``
particles per cell and are *displaced* along ``k̂`` to realise the density wave: the map from
lattice coordinate ``s_0`` to position ``s`` (both along ``k̂``) solves mass conservation
``ρ(s) ds = ρ_0 ds_0`` exactly, ``s + (a/k) sin(k s + φ) = s_0`` (Newton), so there is no
second-order density error; and the amplitude is scaled by ``S/T``, where ``T`` is the
measured ratio of the deposited (kernel) density wave to the particles' one and ``S`` the cell
average of the wave (``Π sinc(k_d Δx_d/2)``), so that the gas sees the cell-averaged density of
the eigenmode (the kernel's transfer function compensated). Velocities are the eigenvector's
at each particle's displaced position; gas cells get the cell averages of the eigenmode.

Presets ``si-linA`` and ``si-linB``: Youdin & Johansen (2007) Table 1 in Athena's set-up
(Bai & Stone 2010a): τ_s = 0.1, ε = 3 resp. 0.2, K_x = K_z = 30 resp. 6, Π = 0.05, 64², one
particle per cell, amplitude 1e-6, run to t = 6 resp. 150. Growth: 0.4190091 resp. 0.0154862
(consistent linearisation; Benítez-Llambay, Krapp & Pessah 2019, Table 4); the mode amplitudes of all eight fields go to ``history.h5`` for
``dustygas analyze growth``.

The gas integrator is VL2 at Courant 0.4 by default (stable to 1/2 in 2D; linA grows −0.36 %
too slowly at 64², the same at Courant 0.2 and 0.5 and with either solver). The single-step
corner-transport-upwind integrator (:mod:`dustygas.grid.ctu`) is stable to Courant 1, as in
Athena's runs (CTU + HLLC at 0.8; Bai & Stone 2010a). With the HLLC solver its growth error grows
about linearly with the Courant number (linA: −0.61 % at 0.2, −0.83 % at 0.4, −1.35 % at 0.8,
−1.72 % at 1.0; Athena's −1.38 % at 0.8); with HLLE it does not (−0.64 % at 0.4, −0.53 % at 0.8,
−0.44 % at 1.0; measured 2026-12-04). CTU + HLLE at Courant 1 reaches t = 6 in 36,739 cycles
instead of 91,846, in about half the wall time of the default (one thread, two runs at a time: 79 s
against 156 s), at −0.44 %; with plain PPM (Colella & Woodward 1984) instead of PPM-CS its gas step
is ~20 % cheaper, at −0.50 % (the fastest setting that beats Athena's accuracy on linA)::

    dustygas run si-linA --set scheme.integrator=ctu --set scheme.riemann=hlle --set scheme.cfl=1
    dustygas run si-linA --set scheme.integrator=ctu --set scheme.riemann=hlle --set scheme.cfl=1 --set scheme.reconstruction=ppm

Neither is a general setting: linB with CTU + HLLE + PPM-CS at Courant 1 grows +20.9 % too fast (its
fields 31 % apart; with plain PPM not measured), where the default VL2 gives −2.1 %.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Sequence

import numpy as np

from ..config import Param, with_defaults
from ..errors import ConfigError, SetupError
from ..grid import GridEngine, Mesh
from ..grid.mesh import cell_average_factor
from ..grid.params import SCHEME
from ..particles import ConstantAcceleration, GasConstantAcceleration, ParticleStore, RotatingFrame
from ..particles.boundaries import wrap_positions
from ..particles.coupling import GAS_INTEGRATORS
from ..particles.density import deposit_density
from ..particles.params import PARTICLES, lattice_positions, particle_engine_from_config
from ..runner import RUN_SCHEMA
from . import Problem, preset, register

__all__ = ["SILinear", "StreamingBox", "streaming_box", "SI_GRID", "SI_SCHEME"]

#: the scheme section of the particle problems: VL2 or CTU, PPM with the Colella & Sekora (2008) limiter,
#: which leaves smooth extrema alone (the classic CW84 limiter clips them at any amplitude:
#: linB at 64² then grows 6.2 % too slowly instead of 2.1 %), and HLLC
#: (:mod:`dustygas.particles.coupling` lists what mattered)
SI_SCHEME = {**with_defaults(SCHEME, reconstruction="ppm-cs", riemann="hllc"),
             "integrator": replace(SCHEME["integrator"], choices=GAS_INTEGRATORS,
                                   doc="time integrator (the particles' drag needs a predictor and a corrector: VL2, "
                                       "Stone & Gardiner 2009; or CTU, Colella 1990; Bai & Stone 2010a)")}


#: the sections and parameters the one-eigenmode problems share (``si-linear``, ``si-settling``)
SI_GRID = {
    "nx": Param(64, "cells along x (radial); the box holds one wavelength, L_x = 2 pi Pi / K_x", min=4),
    "nz": Param(64, "cells along z (vertical); one wavelength, L_z = 2 pi Pi / |K_z|", min=4),
}
SI_TAUS = Param(0.1, "stopping time tau_s = Omega t_s (fixed)", "1/Omega", min=0.0, min_open=True)
SI_AMPLITUDE = Param(1e-6, "amplitude of delta rho_p / rho_p0", min=0.0, min_open=True, max=0.1)
SI_PRESSURE_FRAME = Param("gas", "global pressure gradient as a force on the gas, or the opposite force on the "
                          "particles", choices=("gas", "particles"))


@dataclass
class StreamingBox:
    """What :func:`streaming_box` built: the engine and the mode it holds."""

    engine: object
    k: np.ndarray  # wave vector in code units
    mode_numbers: tuple[int, int, int]
    eigenvector: dict
    omega: complex  # linear-theory frequency (standard convention), units of Omega


def _displace(pos0: np.ndarray, k: np.ndarray, amp: complex) -> np.ndarray:
    """Positions realising ``δρ/ρ = Re(amp e^{i k·x})`` from the lattice ``pos0`` (exact map)."""
    kk = float(np.linalg.norm(k))
    khat = k / kk
    a, phi = abs(amp), math.atan2(amp.imag, amp.real)
    s0 = khat @ pos0
    s = s0 - (a / kk) * np.sin(kk * s0 + phi)
    for _ in range(50):
        f = s + (a / kk) * np.sin(kk * s + phi) - s0
        s -= f / (1.0 + a * np.cos(kk * s + phi))
        if np.max(np.abs(f)) < 1e-15 * max(1.0, np.max(np.abs(s0))):
            break
    return pos0 + np.outer(khat, s - s0)


def streaming_box(
    taus: float | Sequence[float],
    mu: float | Sequence[float],
    kx: float,
    kz: float,
    Pi: float,
    amplitude: float,
    shape: tuple[int, int],
    scheme: dict,
    lattice: int = 1,
    kernel: str = "tsc",
    vz: float = 0.0,
    pressure_frame: str = "gas",
    cfg=None,
    linearisation: str = "consistent",
    frame_v: tuple[float, float] = (0.0, 0.0),
) -> StreamingBox:
    """A 2D x-z box holding one eigenmode of the streaming instability (module docstring).

    ``taus, mu, kx, kz, Pi, vz`` are those of :class:`~dustygas.linear.StreamingParams` (K in
    units of 1/(ηr), ``vz`` in ηv_K: a steady vertical dust drift relative to the gas, held by
    constant accelerations ``vz/t_s`` on the dust and ``-mu vz/t_s`` on the gas). Sequences
    ``taus``, ``mu`` give N dust species (N-species NSH drift, Benítez-Llambay, Krapp & Pessah
    2019, eqs. 79-84), each on its own lattice of ``lattice^2`` particles per cell displaced by
    its own density wave (``vz`` must then be 0). ``shape`` is
    ``(nx, nz)``; ``scheme`` the gas scheme (``integrator, reconstruction, limiter, riemann,
    cfl``); ``cfg`` a configuration with a ``[particles]`` section (else the defaults).
    ``frame_v = (W_x, W_z)`` (ηv_K) adds a uniform velocity to gas and dust, with the constant
    acceleration ``(2 - q) Ω W_x ŷ`` on both that cancels the Coriolis force of ``W_x`` (a
    Galilean boost of the axisymmetric box under orbital advection; modes shift by ``k·W``; see
    :mod:`dustygas.problems.si_settling`'s ``problem.frame``).
    """
    from ..linear import StreamingParams, fastest_mode
    from ..physics import nsh_velocities, nsh_velocities_multi

    if kx == 0 or kz == 0:
        raise SetupError("the 2D box holds one wavelength along x and z: kx and kz must be non-zero")
    multi = not np.isscalar(taus) or not np.isscalar(mu)
    if multi and vz != 0.0:
        raise SetupError("several dust species: a vertical drift (vz != 0) is not supported")
    if multi:
        taus, mu = list(np.atleast_1d(taus).astype(float)), list(np.atleast_1d(mu).astype(float))
    mode = fastest_mode(StreamingParams(taus=taus, mu=mu, kx=kx, kz=kz, Pi=Pi, drag=linearisation, vz=vz))
    ev = mode.eigenvector
    k = np.array([kx / Pi, 0.0, kz / Pi])  # code units: length unit eta r = Pi H
    nx, nz = shape
    mesh = Mesh((nx, 1, nz), (2 * math.pi / abs(k[0]), 1.0, 2 * math.pi / abs(k[2])))
    eta_vk = Pi  # velocity unit of the linear theory in units of c_s
    gas_frame = pressure_frame == "gas"
    gas = GridEngine(mesh, cs=1.0, boundaries=("periodic", "periodic", "periodic"), omega=1.0, q=1.5,
                     orbital_advection=True, eta_vK=eta_vk if gas_frame else 0.0, **scheme)
    taus_j, mu_j = np.atleast_1d(taus).astype(float), np.atleast_1d(mu).astype(float)
    eq = nsh_velocities_multi(taus_j, mu_j) if multi else nsh_velocities(taus, mu)
    boost = 0.0 if gas_frame else 1.0  # particle frame: every velocity + eta v_K y^
    wx, wz = frame_v
    U = np.array([float(eq.gas_vx) + wx, float(eq.gas_vy) + boost, wz]) * eta_vk
    V_j = [np.array([float(np.atleast_1d(eq.dust_vx)[j]) + wx, float(np.atleast_1d(eq.dust_vy)[j]) + boost, vz + wz])
           * eta_vk for j in range(len(taus_j))]
    ay = 0.5 * wx * eta_vk  # (2 - q) Omega w_x: cancels the Coriolis force of the radial boost
    # ---- gas: cell averages of the eigenmode
    x, y, z = mesh.meshgrid()
    phase = np.exp(1j * (k[0] * x + k[2] * z)) * np.ones((nz, 1, nx))
    S = cell_average_factor(k, mesh.dx)
    A = amplitude
    drho_g = (A * ev["drho_g"] * phase).real * S
    rho = 1.0 + drho_g
    mom = []
    for a, key in enumerate(("ux", "uy", "uz")):
        du = (A * (ev[key] * eta_vk + U[a] * ev["drho_g"]) * phase).real * S
        mom.append(U[a] + du)
    xc = mesh.centers(0)[None, None, :]
    gas.set_primitive(rho, mom[0] / rho, mom[1] / rho - 1.5 * xc, mom[2] / rho)
    # ---- particles: lattice displaced by the compensated density wave
    lower, dx, box = mesh.lower, mesh.dx, mesh.size
    pos0 = lattice_positions(mesh.shape, lower, dx, lattice, 0.0 if kernel == "cic" and lattice % 2 else 0.5)
    npart = pos0.shape[1]
    eps = 1e-4  # a small wave measures the kernel's transfer function T (linear in eps)
    probe = wrap_positions(_displace(pos0, k, complex(eps)), lower, box, mesh.shape)
    m0 = mu_j[0] * 1.0 * mesh.cell_volume / lattice**2
    rho_p = deposit_density(mesh, probe, np.full(npart, m0), kernel)
    T = (2.0 * np.mean(rho_p * np.conj(phase)) / mu_j[0]).real / eps
    parts = []
    for j in range(len(taus_j)):  # every species on its own lattice, displaced by its own wave
        pick = (lambda key: ev[key][j]) if multi else (lambda key: ev[key])  # noqa: E731
        pos = wrap_positions(_displace(pos0, k, A * pick("drho_p") * S / T), lower, box, mesh.shape)
        ph = np.exp(1j * (k[0] * pos[0] + k[2] * pos[2]))
        vel = np.empty((3, npart))
        for a, key in enumerate(("wx", "wy", "wz")):
            vel[a] = V_j[j][a] + (A * pick(key) * eta_vk * ph).real  # relative to the shear (orbital advection)
        parts.append((pos, vel, np.full(npart, j), np.full(npart, mu_j[j] * mesh.cell_volume / lattice**2)))
    store = ParticleStore.create(*(np.concatenate([p[i] for p in parts], axis=-1) for i in range(4)))
    mode_numbers = (1, 0, 1 if k[2] > 0 else -1)
    terms = [RotatingFrame(1.0, 1.5, relative_to_shear=True),
             ConstantAcceleration(0.0 if gas_frame else -2.0 * eta_vk, ay, vz * eta_vk / taus_j[0])]
    gas_terms = ([GasConstantAcceleration(ay=ay, az=-mu_j[0] * vz * eta_vk / taus_j[0])]
                 if vz != 0.0 or ay != 0.0 else [])
    kwargs = dict(particle_terms=terms, gas_terms=gas_terms, mode=mode_numbers)
    if cfg is not None:
        engine = particle_engine_from_config(cfg, gas, store, list(taus_j), **kwargs)
    else:
        from ..particles import ParticleGridEngine

        engine = ParticleGridEngine(gas, store, list(taus_j), kernel=kernel, **kwargs)
    return StreamingBox(engine, k, mode_numbers, ev, mode.omega)


def _scheme(cfg) -> dict:
    s = cfg.scheme
    return dict(integrator=s.integrator, reconstruction=s.reconstruction, limiter=s.limiter, riemann=s.riemann,
                cfl=s.cfl)


@register
class SILinear(Problem):
    name = "si-linear"
    runs_on_ranks = True  # particles + gas: split along z under mpiexec (dustygas.parallel.coupled)
    summary = "One linear streaming-instability eigenmode in a 2D x-z box of gas + particles (YJ07, BS10)."
    schema = {
        "run": with_defaults(RUN_SCHEMA, tlim=6.0, dt_history=0.01),
        "grid": SI_GRID,
        "scheme": SI_SCHEME,
        "particles": PARTICLES,
        "problem": {
            "taus": SI_TAUS,
            "mu": Param(3.0, "dust-to-gas density ratio (YJ07's epsilon)", min=0.0, min_open=True),
            "kx": Param(30.0, "radial wavenumber K_x = k_x eta r", "1/(eta r)", min=0.0, min_open=True),
            "kz": Param(30.0, "vertical wavenumber K_z = k_z eta r (sign picks the mode)", "1/(eta r)"),
            "Pi": Param(0.05, "eta v_K / c_s (velocity unit eta v_K = Pi, length unit eta r = Pi H)", min=0.0,
                        min_open=True),
            "amplitude": SI_AMPLITUDE,
            "pressure_frame": SI_PRESSURE_FRAME,
        },
    }

    def validate(self, cfg) -> None:
        if cfg.problem.kz == 0:
            raise ConfigError("problem.kz = 0: the 2D box needs a vertical wavenumber")

    def build(self, cfg):
        p = cfg.problem
        box = streaming_box(p.taus, p.mu, p.kx, p.kz, p.Pi, p.amplitude, (cfg.grid.nx, cfg.grid.nz), _scheme(cfg),
                            lattice=cfg.particles.lattice, kernel=cfg.particles.kernel,
                            pressure_frame=p.pressure_frame, cfg=cfg)
        return box.engine


preset("si-linA", SILinear, "Youdin & Johansen (2007) linA: tau_s = 0.1, eps = 3, K = 30; growth 0.4190 (64^2, 1 ppc).",
       run={"tlim": 6.0, "dt_history": 0.01}, problem={"taus": 0.1, "mu": 3.0, "kx": 30.0, "kz": 30.0})
preset("si-linB", SILinear, "Youdin & Johansen (2007) linB: tau_s = 0.1, eps = 0.2, K = 6; growth 0.01549 (64^2, 1 ppc).",
       run={"tlim": 150.0, "dt_history": 0.25}, problem={"taus": 0.1, "mu": 0.2, "kx": 6.0, "kz": 6.0})
