"""The linear operator of gas + N dust species in the unstratified shearing sheet.

Conventions are those of :mod:`dustygas.linear` (x radial, y azimuthal, z vertical, Ω = 1,
velocities in ηv_K, lengths in ηr, perturbations ∝ exp(i k·x − i ω t)). A state vector holds,
in this order (``4 + 4N`` entries)::

    [δρ_g/ρ_g0, u_x, u_y, u_z,  δρ_0/ρ_00, w_x0, w_y0, w_z0,  δρ_1/ρ_01, w_x1, ...]

(u: gas velocity perturbation, w_j: dust velocity perturbation of species j, densities relative
to each fluid's own background). The linearised equations are written ``dX/dt = L X`` and the
mode frequency is ``ω = i λ`` for an eigenvalue λ of ``L``, so the growth rate is ``s = Re λ``.

Derivation
----------
Background (uniform): gas velocity U = (U_x, U_y, 0), dust V_j = (V_xj, V_yj, V_zj) from the
Nakagawa-Sekiya-Hayashi drift (:func:`dustygas.physics.nsh_velocities_multi`, thesis eq. 4.8);
V_zj is an optional steady vertical drift (thesis §4.1.4). Perturbations of every field ∝
exp(i k·x) with k = (k_x, k_y, k_z) give, with c = c_s = 1/Π, μ_j = ρ_j0/ρ_g0 and τ_j = t_s,j Ω,

.. math::

    \\dot{δρ}_g &= -i k·U\\,δρ_g - i k·u \\\\
    \\dot u &= -i k·U\\,u + (2u_y, -u_x/2, 0) - i c^2 k\\,δρ_g
              + \\sum_j \\frac{μ_j}{τ_j}\\big[(w_j - u) + (δρ_j - γ\\,δρ_g)(V_j - U)\\big] \\\\
    \\dot{δρ}_j &= -i k·V_j\\,δρ_j - i k·w_j \\\\
    \\dot w_j &= -i k·V_j\\,w_j + (2w_{yj}, -w_{xj}/2, 0)
              - \\frac{1}{τ_j}\\big[(w_j - u) + β\\,δρ_g (V_j - U)\\big]

(the Coriolis + tidal terms of thesis eq. 4.2 on the velocity relative to the shear flow
−(3/2)x ŷ; with k_y ≠ 0 the shear advection is absorbed into k_x(t), see
:mod:`dustygas.linear.shearing_wave`). The drag linearisations differ only in (γ, β):

``"consistent"`` (γ = 1, β = 0)
    fixed t_s, the back-reaction μ(1+δρ_j)/(1+δρ_g)(v−u)/t_s linearised in full
    (Benítez-Llambay, Krapp & Pessah 2019 Table 4: linA s = 0.4190091323).
``"yj07"`` (γ = 0, β = 0)
    the back-reaction without its gas-density term; this reproduces the digits of Youdin &
    Johansen (2007) Table 1 (linA s = 0.4190204).
``"epstein"`` (γ = 0, β = 1)
    t_s ∝ 1/ρ_g (Epstein drag at fixed grain size, as in psitools): the perturbed stopping time
    t_s/(1+δρ_g) cancels the 1/(1+δρ_g) of the back-reaction, and puts δρ_g(V_j−U)/τ_j into
    the dust equation.

A vertical drift V_zj is held steady by constant external forces (vertical gravity on the dust;
on the gas, the part of the hydrostatic pressure gradient that balances the dust's drag). They
are not perturbed, so the perturbations feel the drift through advection (k·V_j) and the
density-weighted drag terms (δρ_j − γ δρ_g) V_zj; the gas has no background vertical velocity.
What this gives (the SH18 resonance, the large-k plateau and its drag-law dependence, the
(μk)^{1/3} branch) is derived in :mod:`dustygas.linear.resonance`.

The incompressible limit Π → 0 is taken exactly: δρ_g → 0 with c² δρ_g finite (a pressure that
enforces k·u = 0). The gas velocity is then u = a_1 e_1 + a_2 e_2 on an orthonormal basis of
the plane ⟂ k and the gas momentum equation is projected onto that plane; the state has
``2 + 4N`` entries ``[a_1, a_2, δρ_0, w_x0, ...]`` and the two sound waves are gone.

Numerics: the gas density enters the operator as h = c δρ_g (a similarity transform that makes
the sound-wave block symmetric, so both eigensolvers see a balanced matrix); eigenvectors are
converted back to δρ_g/ρ_g0 before they are returned.

Where the thesis differs (and this derivation is trusted)
---------------------------------------------------------
* eqs. 4.13f-g and the matrices C_g, F of 4.14 write the drift difference as
  (v̄_x − v̄_x), (v̄_y − v̄_y), which is identically zero; the derivation (4.12d) gives
  (v̄_x − ū_x), (v̄_y − ū_y). With the typo the YJ07 numbers are not reproduced.
* eq. 4.17h writes −(Ωμ/τ_s) v̄_z δρ_d + (Ωμ/τ_s) v̄_y δρ_g; the derivation gives
  −(Ωμ/τ_s)(v̄_z − ū_z)(δρ_d − δρ_g) with ū_z = 0, i.e. v̄_z in both terms (for the
  "consistent" linearisation; the YJ07 form drops the δρ_g term altogether).
* eqs. 4.11b/d write δw for δv and drop μ from the gas drag; 4.12d is right: the gas feels
  −(Ωμ/τ_s)[δu − δv − (δρ_d − δρ_g)(v̄ − ū)], i.e. the "consistent" linearisation, not the one
  behind the YJ07 table (γ = 0 above).
* eq. 4.2d writes ∂ρ_d/∂y for ∂ρ_d/∂t.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence, Union

import numba
import numpy as np

from ..errors import UserError
from ..physics import nsh_velocities_multi, steady_settling_velocity

__all__ = ["StreamingParams", "DRAG_MODELS", "drag_code", "float_tuple", "operator_matrix", "state_labels"]

#: drag linearisation name -> (gamma, beta) of the module docstring
DRAG_MODELS: dict[str, tuple[float, float]] = {
    "consistent": (1.0, 0.0),
    "yj07": (0.0, 0.0),
    "epstein": (0.0, 1.0),
}
_DRAG_CODES = {name: i for i, name in enumerate(DRAG_MODELS)}

Number = Union[float, int]


def drag_code(name: str) -> int:
    """Integer code of a drag linearisation, for the numba kernels (one-line error if unknown)."""
    try:
        return _DRAG_CODES[name]
    except (KeyError, TypeError):
        raise UserError(f"unknown drag linearisation {name!r}: choose one of {', '.join(DRAG_MODELS)}") from None


def float_tuple(value, name: str) -> tuple[float, ...]:
    """``value`` (a number or a 1D list of numbers) as a tuple of finite floats, or a one-line
    :class:`~dustygas.errors.UserError` naming ``name`` and what is wrong.

    >>> float_tuple([0.1, 1], "taus")
    (0.1, 1.0)
    """
    try:
        arr = np.atleast_1d(np.asarray(value, dtype=np.float64))
    except (TypeError, ValueError):
        raise UserError(f"{name} = {value!r}: expected a number or a list of numbers") from None
    if arr.ndim != 1:
        raise UserError(f"{name}: expected a number or a 1D list of numbers")
    if arr.size == 0:
        raise UserError(f"{name} is empty: give at least one value")
    if not np.all(np.isfinite(arr)):
        raise UserError(f"{name} = {value!r}: values must be finite")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True, kw_only=True)
class StreamingParams:
    """Parameters of one linear streaming-instability problem.

    Every field is keyword-only (``taus`` and ``mu`` are both array-like: a swap must not run).

    Parameters
    ----------
    taus
        Stopping time(s) τ_s = t_s Ω (> 0); a sequence gives N dust species.
    mu
        Dust-to-gas density ratio(s) μ = ρ_p0/ρ_g0 (YJ07's ε; >= 0), one per species.
    kx, kz
        Wavenumbers in units of 1/(ηr) (K = kηr); |k| must be > 0.
    ky
        Azimuthal wavenumber (0: axisymmetric; only the shearing-wave module uses k_y ≠ 0).
    Pi
        Π = ηv_K/c_s (>= 0); the sound speed is 1/Π in these units; Π = 0 is the exact
        incompressible limit.
    drag
        ``"consistent"`` (default), ``"yj07"`` or ``"epstein"`` (see :mod:`dustygas.linear.operator`).
    vz
        Steady vertical dust velocity relative to the gas, in ηv_K, one per species or one for
        all; negative is downward (a patch above the midplane settling towards it). The string
        ``"settling"`` gives thesis eq. 4.19 pointing down: v̄_z = −(1/Π) τ_s/(2τ_s² + 1).

    Examples
    --------
    >>> p = StreamingParams(taus=0.1, mu=3.0, kx=30.0, kz=30.0, drag="yj07")
    >>> p.nspecies, p.cs
    (1, 20.0)
    >>> StreamingParams(taus=[0.1, 1.0], mu=[0.5, 0.5], kx=10, kz=10, Pi=0.05, vz="settling").vz_array
    array([-1.96078431, -6.66666667])
    """

    taus: Union[Number, Sequence[Number]]
    mu: Union[Number, Sequence[Number]]
    kx: float
    kz: float
    ky: float = 0.0
    Pi: float = 0.05
    drag: str = "consistent"
    vz: Union[Number, Sequence[Number], str] = 0.0
    multi: bool = field(default=False, init=False, repr=False)

    def __post_init__(self) -> None:
        multi = not np.isscalar(self.taus) or not np.isscalar(self.mu)
        taus = float_tuple(self.taus, "taus")
        mu = float_tuple(self.mu, "mu")
        if len(taus) == 1 and len(mu) > 1:
            taus = taus * len(mu)
        if len(mu) == 1 and len(taus) > 1:
            mu = mu * len(taus)
        if len(taus) != len(mu):
            raise UserError(f"taus has {len(taus)} species but mu has {len(mu)}")
        if min(taus) <= 0:
            raise UserError(f"taus = {self.taus!r}: stopping times must be > 0")
        if min(mu) < 0:
            raise UserError(f"mu = {self.mu!r}: dust-to-gas ratios must be >= 0")
        for name in ("kx", "ky", "kz", "Pi"):
            v = getattr(self, name)
            if not isinstance(v, (int, float, np.floating, np.integer)) or not math.isfinite(v):
                raise UserError(f"{name} = {v!r}: expected a finite number")
            object.__setattr__(self, name, float(v))
        if self.Pi < 0:
            raise UserError(f"Pi = {self.Pi!r}: must be >= 0 (0 is the incompressible limit)")
        if self.kx == 0 and self.ky == 0 and self.kz == 0:
            raise UserError("k = 0: give a non-zero wavenumber (kx, kz)")
        drag_code(self.drag)
        if isinstance(self.vz, str):
            if self.vz != "settling":
                raise UserError(f"vz = {self.vz!r}: give a number (ηv_K, negative = downward) or 'settling'")
            if self.Pi == 0:
                raise UserError("vz='settling' (thesis eq. 4.19, speed ~ c_s) needs Pi > 0")
        else:
            vz = float_tuple(self.vz, "vz")
            if len(vz) not in (1, len(taus)):
                raise UserError(f"vz has {len(vz)} entries for {len(taus)} species")
            object.__setattr__(self, "vz", vz[0] if len(vz) == 1 and np.isscalar(self.vz) else vz)
        object.__setattr__(self, "taus", taus if multi else taus[0])
        object.__setattr__(self, "mu", mu if multi else mu[0])
        object.__setattr__(self, "multi", multi)

    # ------------------------------------------------------------------ derived quantities
    @property
    def nspecies(self) -> int:
        return len(self.taus_array)

    @property
    def taus_array(self) -> np.ndarray:
        return np.atleast_1d(np.asarray(self.taus, dtype=np.float64))

    @property
    def mu_array(self) -> np.ndarray:
        return np.atleast_1d(np.asarray(self.mu, dtype=np.float64))

    @property
    def cs(self) -> float:
        """Sound speed in ηv_K (``inf`` in the incompressible limit)."""
        return math.inf if self.Pi == 0 else 1.0 / self.Pi

    @property
    def incompressible(self) -> bool:
        return self.Pi == 0

    @property
    def vz_array(self) -> np.ndarray:
        """Vertical dust drift per species in ηv_K (resolves ``"settling"``)."""
        return resolve_vz(self.vz, self.taus_array, self.Pi)

    @property
    def k(self) -> float:
        return math.sqrt(self.kx**2 + self.ky**2 + self.kz**2)

    def background(self):
        """NSH drift (gas_vx, gas_vy, dust_vx[N], dust_vy[N]) in ηv_K (thesis eq. 4.8)."""
        return nsh_velocities_multi(self.taus_array, self.mu_array)

    @property
    def size(self) -> int:
        """Number of unknowns: 4 + 4N, or 2 + 4N in the incompressible limit."""
        return (2 if self.incompressible else 4) + 4 * self.nspecies

    def matrix(self) -> np.ndarray:
        """The operator L (dX/dt = L X) in the internal variables (h = c_s δρ_g)."""
        return operator_matrix(self)


def resolve_vz(vz, taus: np.ndarray, Pi: float) -> np.ndarray:
    """Vertical dust drift per species: numbers as given, ``"settling"`` from thesis eq. 4.19."""
    taus = np.asarray(taus, dtype=np.float64)
    if isinstance(vz, str):
        return -steady_settling_velocity(taus, c_s=1.0 / Pi)
    return np.broadcast_to(np.asarray(vz, dtype=np.float64), taus.shape).copy()


def state_labels(nspecies: int, incompressible: bool = False, indexed: bool = False) -> list[str]:
    """Names of the state-vector entries (``drho_p_0`` style when ``indexed``)."""
    gas = ["a1", "a2"] if incompressible else ["drho_g", "ux", "uy", "uz"]
    dust = []
    for j in range(nspecies):
        suffix = f"_{j}" if indexed else ""
        dust += [f"drho_p{suffix}", f"wx{suffix}", f"wy{suffix}", f"wz{suffix}"]
    return gas + dust


# ---------------------------------------------------------------------------- numba builders


@numba.njit(cache=True, inline="always")
def _plane_basis(kx, ky, kz):
    """Orthonormal e1, e2 spanning the plane ⟂ k (e1 = ŷ for an axisymmetric k)."""
    k = math.sqrt(kx * kx + ky * ky + kz * kz)
    kh = math.sqrt(kx * kx + ky * ky)
    if kh > 1e-300 * k:
        # e1 = ẑ × k / |ẑ × k| = (−ky, kx, 0)/kh ; e2 = k̂ × e1
        e1x, e1y, e1z = -ky / kh, kx / kh, 0.0
    else:
        e1x, e1y, e1z = 0.0, 1.0, 0.0
    e2x = (ky * e1z - kz * e1y) / k
    e2y = (kz * e1x - kx * e1z) / k
    e2z = (kx * e1y - ky * e1x) / k
    return e1x, e1y, e1z, e2x, e2y, e2z


@numba.njit(cache=True)
def fill_operator(L, G, kx, ky, kz, cs, Ux, Uy, taus, mus, Vx, Vy, Vz, gamma, beta):
    """Write the operator of the module docstring into ``L`` and return its size n.

    ``cs = inf`` selects the incompressible operator (n = 2 + 4N); otherwise n = 4 + 4N with
    the scaled gas density h = c_s δρ_g as first unknown. ``L`` (complex, at least n × n) has
    its leading n × n block overwritten; ``G`` is complex work space of shape (3, >= 3 + 4N)
    that receives the gas momentum rows (columns: u_x, u_y, u_z, then the dust block).
    """
    nsp = taus.shape[0]
    incompressible = not math.isfinite(cs)
    g0 = 2 if incompressible else 4  # index of the first dust unknown
    n = g0 + 4 * nsp
    ng = 3 + 4 * nsp
    for i in range(n):
        for j in range(n):
            L[i, j] = 0.0
    for i in range(3):
        for j in range(ng):
            G[i, j] = 0.0
    # gas momentum: Doppler shift, Coriolis + tidal, drag from every species
    dopp_g = -1j * (kx * Ux + ky * Uy)
    G[0, 0] = dopp_g
    G[1, 1] = dopp_g
    G[2, 2] = dopp_g
    G[0, 1] = 2.0
    G[1, 0] = -0.5
    if incompressible:
        e1x, e1y, e1z, e2x, e2y, e2z = _plane_basis(kx, ky, kz)
    else:
        e1x = e1y = e1z = e2x = e2y = e2z = 0.0
        L[0, 0] = dopp_g  # gas continuity, h = c_s drho_g
        L[0, 1] = -1j * cs * kx
        L[0, 2] = -1j * cs * ky
        L[0, 3] = -1j * cs * kz
        L[1, 0] = -1j * cs * kx  # pressure
        L[2, 0] = -1j * cs * ky
        L[3, 0] = -1j * cs * kz
    for j in range(nsp):
        inv_t = 1.0 / taus[j]
        f = mus[j] * inv_t
        dvx = Vx[j] - Ux
        dvy = Vy[j] - Uy
        dvz = Vz[j]
        d = 3 + 4 * j  # species j in G's columns
        G[0, 0] -= f
        G[1, 1] -= f
        G[2, 2] -= f
        G[0, d] += f * dvx  # (mu/tau) drho_j (V_j - U)
        G[1, d] += f * dvy
        G[2, d] += f * dvz
        G[0, d + 1] += f  # (mu/tau) w_j
        G[1, d + 2] += f
        G[2, d + 3] += f
        r = g0 + 4 * j  # species j in L
        if not incompressible and gamma != 0.0:  # -(gamma mu/tau) drho_g (V_j - U)
            L[1, 0] -= gamma * f * dvx / cs
            L[2, 0] -= gamma * f * dvy / cs
            L[3, 0] -= gamma * f * dvz / cs
        dopp_d = -1j * (kx * Vx[j] + ky * Vy[j] + kz * dvz)
        L[r, r] = dopp_d  # dust continuity
        L[r, r + 1] = -1j * kx
        L[r, r + 2] = -1j * ky
        L[r, r + 3] = -1j * kz
        L[r + 1, r + 1] = dopp_d - inv_t  # dust momentum: Doppler, drag, Coriolis + tidal
        L[r + 2, r + 2] = dopp_d - inv_t
        L[r + 3, r + 3] = dopp_d - inv_t
        L[r + 1, r + 2] = 2.0
        L[r + 2, r + 1] = -0.5
        if incompressible:  # drag towards u = a1 e1 + a2 e2
            L[r + 1, 0] = e1x * inv_t
            L[r + 1, 1] = e2x * inv_t
            L[r + 2, 0] = e1y * inv_t
            L[r + 2, 1] = e2y * inv_t
            L[r + 3, 0] = e1z * inv_t
            L[r + 3, 1] = e2z * inv_t
        else:
            L[r + 1, 1] = inv_t
            L[r + 2, 2] = inv_t
            L[r + 3, 3] = inv_t
            if beta != 0.0:  # Epstein: -(beta/tau) drho_g (V_j - U)
                L[r + 1, 0] = -beta * dvx * inv_t / cs
                L[r + 2, 0] = -beta * dvy * inv_t / cs
                L[r + 3, 0] = -beta * dvz * inv_t / cs
    if incompressible:
        # rows projected on (e1, e2), gas-velocity columns expressed on (e1, e2)
        for col in range(3, ng):
            L[0, col - 1] = e1x * G[0, col] + e1y * G[1, col] + e1z * G[2, col]
            L[1, col - 1] = e2x * G[0, col] + e2y * G[1, col] + e2z * G[2, col]
        for a in range(2):
            ax = e1x if a == 0 else e2x
            ay = e1y if a == 0 else e2y
            az = e1z if a == 0 else e2z
            for b in range(2):
                bx = e1x if b == 0 else e2x
                by = e1y if b == 0 else e2y
                bz = e1z if b == 0 else e2z
                L[a, b] = (ax * (G[0, 0] * bx + G[0, 1] * by + G[0, 2] * bz)
                           + ay * (G[1, 0] * bx + G[1, 1] * by + G[1, 2] * bz)
                           + az * (G[2, 0] * bx + G[2, 1] * by + G[2, 2] * bz))
    else:
        for c in range(3):
            for col in range(3):
                L[1 + c, 1 + col] += G[c, col]
            for col in range(3, ng):
                L[1 + c, col + 1] += G[c, col]
    return n


def _background_arrays(p: StreamingParams):
    eq = p.background()
    return (
        float(eq.gas_vx),
        float(eq.gas_vy),
        kernel_array(eq.dust_vx),
        kernel_array(eq.dust_vy),
        kernel_array(p.vz_array),
    )


def kernel_array(a) -> np.ndarray:
    """``a`` as a writable C-contiguous float64 array (a copy only if it is not one): kernels get one
    compiled signature, not one per combination of read-only inputs (2 CPU-s each for fill_operator)."""
    return np.require(a, np.float64, ("C", "W"))


def operator_matrix(p: StreamingParams) -> np.ndarray:
    """The operator L of ``p`` (dX/dt = L X) with h = c_s δρ_g as the gas-density unknown."""
    Ux, Uy, Vx, Vy, Vz = _background_arrays(p)
    gamma, beta = DRAG_MODELS[p.drag]
    L = np.zeros((p.size, p.size), dtype=np.complex128)
    G = np.zeros((3, 3 + 4 * p.nspecies), dtype=np.complex128)
    fill_operator(L, G, p.kx, p.ky, p.kz, p.cs, Ux, Uy, kernel_array(p.taus_array), kernel_array(p.mu_array), Vx, Vy,
                  Vz, gamma, beta)
    return L
