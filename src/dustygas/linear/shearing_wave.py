"""Non-axisymmetric shearing waves of gas + N dust species (thesis §4.6, eqs. 4.26-4.35).

Frame and sign (conventions of :mod:`dustygas.linear`): the background shear is −(3/2)Ω x ŷ,
as in §4.1 (the thesis flips it to +(3/2)Ω x ŷ in §4.6; we do not). A perturbation
∝ exp[i(k_x(t) x + k_y y + k_z z)] is carried by that shear, so that

.. math:: k_x(t) = k_{x0} + \\tfrac32 Ω k_y t ,

and in the sheared frame its amplitudes obey dX/dt = L(k(t)) X, with L the operator of
:mod:`dustygas.linear.operator` evaluated at the instantaneous wavevector k(t) =
(k_x(t), k_y, k_z) (the shear advection is entirely in k_x(t); Coriolis + tidal terms are
(2u_y, −u_x/2)). With k_y = 0 the operator is constant and the solution is the axisymmetric
eigenmode growth. A wave with k_x0 k_y < 0 is *leading* and swings through k_x = 0 at
t_swing = −k_x0/(1.5 k_y).

In the incompressible limit (Π = 0) the gas velocity lives on the plane ⟂ k(t), spanned by
e_1 = ẑ × k/|ẑ × k| and e_2 = k̂ × e_1; writing u = a_1 e_1 + a_2 e_2 adds the rotation of
that basis, ȧ_1 ⊃ −r a_2, ȧ_2 ⊃ +r a_1 with r = (3/2) k_y² k_z / (k_h² |k|), k_h² = k_x² + k_y².

Where the thesis differs: eqs. 4.26b/d and 4.35b-c,e-f keep +2Ω u_y x̂ while flipping the
shear (their tidal/Coriolis pair is (2Ω u_y, +Ω u_x/2)), which makes epicycles grow as
e^{Ωt}; the mirror image y → −y of our equations has (−2Ω u_y, +Ω u_x/2). Eq. 4.30d lacks
the minus sign of the divergence and writes ∂(δρ_d)/∂y for ∂(δρ_g)/∂y; 4.26c writes ∇·δu.
The thesis sets k_z = 0 (eq. 4.35); here k_z is general.

Definitions used by the results:

* *dust-density amplification* G_ρ = |δρ_p(t_1)| / |δρ_p(t_0)| (species 0);
* *energy amplification* G_E = [E(t_1)/E(t_0)]^{1/2}, E = ½(|u|² + c_s²|δρ_g|² + Σ_j μ_j|w_j|²)
  (kinetic + acoustic energy per unit gas density; in the incompressible limit the acoustic
  term is absent);
* *net amplification over a swing*: these ratios with t_0 = 0 (k_x = k_x0, leading) and
  t_1 = 2 t_swing (k_x = −k_x0, the mirror trailing wave), starting from the fastest
  eigenmode of the instantaneous operator L(k(t_0)) (unless another initial state is given);
* *potential vorticity* (gas, linear): δq = i(k_x u_y − k_y u_x) − (Ω/2) δρ_g/ρ_g0, conserved
  up to the Doppler phase for μ = 0 and k_z = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numba
import numpy as np
from numpy.typing import ArrayLike

from ..errors import UserError
from .modes import eigenmodes
from .operator import DRAG_MODELS, StreamingParams, _plane_basis, fill_operator, state_labels

__all__ = ["ShearingWave", "shearing_wave", "swing_time", "SHEAR_RATE"]

SHEAR_RATE = 1.5  # q Ω for a Keplerian disk, Ω = 1


@numba.njit(cache=True)
def _build(t, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G):
    kx = kx0 + SHEAR_RATE * ky * t
    n = fill_operator(L, G, kx, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta)
    if not math.isfinite(cs):
        kh2 = kx * kx + ky * ky
        if kh2 > 0.0 and kz != 0.0:
            r = SHEAR_RATE * ky * ky * kz / (kh2 * math.sqrt(kh2 + kz * kz))
            L[0, 1] -= r
            L[1, 0] += r
    return n


@numba.njit(cache=True)
def _rhs(t, y, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, out):
    n = _build(t, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    for i in range(n):
        ar = 0.0
        ai = 0.0
        for j in range(n):
            lr = L[i, j].real
            li = L[i, j].imag
            ar += lr * y[j] - li * y[n + j]
            ai += lr * y[n + j] + li * y[j]
        out[i] = ar
        out[n + i] = ai
    return out


@numba.njit(cache=True)
def _jac(t, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, J):
    n = _build(t, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    for i in range(n):
        for j in range(n):
            J[i, j] = L[i, j].real
            J[i, n + j] = -L[i, j].imag
            J[n + i, j] = L[i, j].imag
            J[n + i, n + j] = L[i, j].real
    return J


@dataclass
class ShearingWave:
    """Result of :func:`shearing_wave`.

    Attributes
    ----------
    t, kx
        Output times and the radial wavenumber k_x(t).
    state
        Complex amplitudes, shape (len(t), 4 + 4N), columns named by ``labels``
        (δρ_g/ρ_g0, u_x, u_y, u_z, then δρ_p/ρ_p0, w_x, w_y, w_z per species; ηv_K units).
    amplification, energy_amplification
        G_ρ and G_E between the first and last output time (module docstring).
    """

    params: StreamingParams
    t: np.ndarray
    kx: np.ndarray
    state: np.ndarray
    labels: list[str]
    amplification: float
    energy_amplification: float
    attrs: dict[str, Any] = field(default_factory=dict)

    def amplitude(self, name: str) -> np.ndarray:
        """|field|(t) for one label (e.g. ``"drho_p_0"``, ``"ux"``)."""
        return np.abs(self.state[:, self.labels.index(name)])

    @property
    def energy(self) -> np.ndarray:
        """E(t) = ½(|u|² + c_s²|δρ_g|² + Σ μ_j |w_j|²) (module docstring)."""
        return _energy(self.state, self.params)

    @property
    def potential_vorticity(self) -> np.ndarray:
        """Linear gas PV δq(t) = i(k_x u_y − k_y u_x) − δρ_g/2 (complex)."""
        s = self.state
        return 1j * (self.kx * s[:, 2] - self.params.ky * s[:, 1]) - 0.5 * s[:, 0]


def _energy(state: np.ndarray, p: StreamingParams) -> np.ndarray:
    e = np.sum(np.abs(state[:, 1:4]) ** 2, axis=1)
    if not p.incompressible:
        e = e + p.cs**2 * np.abs(state[:, 0]) ** 2
    for j, mu in enumerate(p.mu_array):
        e = e + mu * np.sum(np.abs(state[:, 4 + 4 * j + 1:4 + 4 * j + 4]) ** 2, axis=1)
    return 0.5 * e


def _arrays(p: StreamingParams):
    eq = p.background()
    gamma, beta = DRAG_MODELS[p.drag]
    return (p.cs, float(eq.gas_vx), float(eq.gas_vy), p.taus_array, p.mu_array,
            np.ascontiguousarray(eq.dust_vx, dtype=np.float64), np.ascontiguousarray(eq.dust_vy, dtype=np.float64),
            np.ascontiguousarray(p.vz_array, dtype=np.float64), gamma, beta)


def _to_internal(state: np.ndarray, p: StreamingParams, kx: float) -> np.ndarray:
    if p.incompressible:
        e1x, e1y, e1z, e2x, e2y, e2z = _plane_basis(kx, p.ky, p.kz)
        u = state[1:4]
        return np.concatenate([[u @ np.array([e1x, e1y, e1z]), u @ np.array([e2x, e2y, e2z])], state[4:]])
    out = state.astype(np.complex128).copy()
    out[0] *= p.cs
    return out


def _to_physical(x: np.ndarray, p: StreamingParams, kx: np.ndarray) -> np.ndarray:
    """Internal states (n_t, n) -> physical (n_t, 4 + 4N)."""
    nt = x.shape[0]
    out = np.zeros((nt, 4 + 4 * p.nspecies), dtype=np.complex128)
    if p.incompressible:
        for i in range(nt):
            e1x, e1y, e1z, e2x, e2y, e2z = _plane_basis(kx[i], p.ky, p.kz)
            out[i, 1:4] = x[i, 0] * np.array([e1x, e1y, e1z]) + x[i, 1] * np.array([e2x, e2y, e2z])
        out[:, 4:] = x[:, 2:]
    else:
        out[:, 0] = x[:, 0] / p.cs
        out[:, 1:] = x[:, 1:]
    return out


def swing_time(kx0: float, ky: float) -> float:
    """Time at which k_x(t) = 0: t_swing = −k_x0/(1.5 k_y) (needs k_y ≠ 0)."""
    return -kx0 / (SHEAR_RATE * ky)


def shearing_wave(
    params: StreamingParams,
    t_span: tuple[float, float] | None = None,
    *,
    initial: ArrayLike | str = "fastest",
    n_out: int = 201,
    method: str = "LSODA",
    rtol: float = 1e-9,
    atol: float = 1e-12,
) -> ShearingWave:
    """Integrate one shearing wave of gas + dust from ``t_span[0]`` to ``t_span[1]``.

    Parameters
    ----------
    params
        :class:`StreamingParams` with the *initial* wavevector (``kx`` = k_x0 at t = 0, ``ky``,
        ``kz``); Π = 0 is the incompressible limit.
    t_span
        Start and end time (units 1/Ω). Default for a leading wave (k_x0 k_y < 0): the
        symmetric swing (0, 2 t_swing), from k_x0 to −k_x0.
    initial
        ``"fastest"``: the fastest eigenmode of L(k(t_0)), normalised to δρ_p/ρ_p0 = 1;
        ``"dust"``: δρ_p/ρ_p0 = 1 and nothing else; or a complex state vector of length
        4 + 4N in the order of :func:`~dustygas.linear.operator.state_labels`.
    method, rtol, atol
        :func:`scipy.integrate.solve_ivp` settings; ``LSODA`` (default), ``BDF`` and ``Radau``
        use the exact Jacobian and handle the stiff small-τ_s drag.

    Examples
    --------
    With k_y = 0 the wave is the axisymmetric eigenmode (YJ07 linA; consistent drag):

    >>> w = shearing_wave(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30), (0.0, 2.0))
    >>> round(float(np.log(w.amplification) / 2.0), 6)
    0.419009
    """
    from scipy.integrate import solve_ivp

    p = params
    if t_span is None:
        if p.ky == 0 or p.kx * p.ky >= 0:
            raise UserError("t_span is needed unless the wave is leading (kx * ky < 0)")
        t_span = (0.0, 2.0 * swing_time(p.kx, p.ky))
    t0, t1 = (float(v) for v in t_span)
    if not (math.isfinite(t0) and math.isfinite(t1) and t1 > t0):
        raise UserError(f"t_span = {t_span!r}: expected (t0, t1) with t1 > t0")
    if method not in ("LSODA", "BDF", "Radau", "RK45", "DOP853"):
        raise UserError(f"method {method!r}: choose LSODA, BDF, Radau, RK45 or DOP853")
    kx_t0 = p.kx + SHEAR_RATE * p.ky * t0
    if isinstance(initial, str):
        if initial == "fastest":
            x0 = eigenmodes(replace(p, kx=kx_t0)).vectors[:, 0]
        elif initial == "dust":
            x0 = np.zeros(4 + 4 * p.nspecies, dtype=np.complex128)
            x0[4] = 1.0
        else:
            raise UserError(f"initial = {initial!r}: 'fastest', 'dust' or a state vector")
    else:
        x0 = np.asarray(initial, dtype=np.complex128)
        if x0.shape != (4 + 4 * p.nspecies,):
            raise UserError(f"initial state must have {4 + 4 * p.nspecies} entries")
    xi = _to_internal(x0, p, kx_t0)
    n = xi.size
    args = _arrays(p)
    L = np.zeros((n, n), dtype=np.complex128)
    G = np.zeros((3, 3 + 4 * p.nspecies), dtype=np.complex128)
    buf = np.zeros(2 * n)
    J = np.zeros((2 * n, 2 * n))
    kx0, ky, kz = p.kx, p.ky, p.kz

    def f(t, y):
        return _rhs(t, y, kx0, ky, kz, *args, L, G, buf).copy()

    def jac(t, y):
        return _jac(t, kx0, ky, kz, *args, L, G, J).copy()

    t_eval = np.linspace(t0, t1, int(n_out))
    kw = {"jac": jac} if method in ("LSODA", "BDF", "Radau") else {}
    sol = solve_ivp(f, (t0, t1), np.concatenate([xi.real, xi.imag]), method=method, t_eval=t_eval,
                    rtol=rtol, atol=atol, **kw)
    if not sol.success:
        raise UserError(f"shearing-wave integration failed: {sol.message}")
    x = (sol.y[:n] + 1j * sol.y[n:]).T
    kx_t = p.kx + SHEAR_RATE * p.ky * sol.t
    state = _to_physical(x, p, kx_t)
    e = _energy(state, p)
    rho0 = abs(state[0, 4])
    amp = abs(state[-1, 4]) / rho0 if rho0 > 0 else math.nan
    eamp = math.sqrt(e[-1] / e[0]) if e[0] > 0 else math.nan
    attrs = {"t_span": [t0, t1], "method": method, "rtol": rtol, "atol": atol,
             "initial": initial if isinstance(initial, str) else "given", "shear": "-(3/2) Omega x y_hat",
             "kx_of_t": "kx0 + 1.5 ky t"}
    return ShearingWave(p, sol.t, kx_t, state, state_labels(p.nspecies, indexed=True), amp, eamp, attrs)
