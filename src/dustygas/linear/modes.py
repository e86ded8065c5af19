"""Eigenmodes of the axisymmetric streaming-instability operator, and fast growth rates.

* :func:`eigenmodes` -- every eigenvalue ω and eigenvector of one parameter set (LAPACK);
* :func:`fastest_mode` -- the fastest-growing mode, normalised like Youdin & Johansen (2007)
  (δρ_p/ρ_p0 = 1 for species 0, velocities in ηv_K);
* :func:`growth_rate` -- max Im ω over broadcast arrays of parameters, compiled (numba QR of
  :mod:`dustygas.linear.eigensolver`), no eigenvectors.

Conventions: :mod:`dustygas.linear`; the operator: :mod:`dustygas.linear.operator`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np
from numpy.typing import ArrayLike

from ..errors import UserError
from ..physics import nsh_velocities_multi
from .eigensolver import hessenberg_eigvals
from .operator import DRAG_MODELS, StreamingParams, drag_code, fill_operator, kernel_array, operator_matrix, resolve_vz

__all__ = ["Mode", "Eigenmodes", "eigenmodes", "fastest_mode", "growth_rate"]

GAS_KEYS = ("drho_g", "ux", "uy", "uz")
DUST_KEYS = ("drho_p", "wx", "wy", "wz")


@dataclass(frozen=True)
class Mode:
    """One eigenmode.

    Attributes
    ----------
    omega
        Complex frequency ω (standard convention: perturbations ∝ exp(i k·x − i ω t)).
    growth_rate, frequency
        Im ω and Re ω (units of Ω).
    eigenvector
        ``drho_g, ux, uy, uz, drho_p, wx, wy, wz`` → complex amplitude (densities relative to
        each fluid's background, velocities in ηv_K), normalised so that δρ_p/ρ_p0 = 1 for
        species 0. For N species (``params.multi``) the dust entries are arrays over species.
    vector
        The same amplitudes as one state vector in the order of
        :func:`dustygas.linear.operator.state_labels` (gas velocities (u_x, u_y, u_z) and
        δρ_g = 0 also in the incompressible limit).
    params
        The :class:`StreamingParams` of the mode.
    """

    omega: complex
    eigenvector: dict[str, Any]
    vector: np.ndarray
    params: StreamingParams

    @property
    def growth_rate(self) -> float:
        return float(self.omega.imag)

    @property
    def frequency(self) -> float:
        return float(self.omega.real)


@dataclass(frozen=True)
class Eigenmodes:
    """All eigenmodes of one parameter set, sorted by decreasing growth rate.

    ``omega`` has 4 + 4N entries (2 + 4N in the incompressible limit); ``vectors[:, i]`` is the
    normalised state vector (4 + 4N entries, see :class:`Mode`) of ``omega[i]``.
    """

    omega: np.ndarray
    vectors: np.ndarray
    params: StreamingParams

    def __len__(self) -> int:
        return len(self.omega)

    def mode(self, i: int = 0) -> Mode:
        """Mode ``i`` (0 is the fastest growing)."""
        vec = self.vectors[:, i]
        return Mode(complex(self.omega[i]), _labelled(vec, self.params), vec.copy(), self.params)


def _full_state(vec: np.ndarray, p: StreamingParams) -> np.ndarray:
    """Internal eigenvector -> physical state (δρ_g, u, dust...) of length 4 + 4N."""
    n_d = 4 * p.nspecies
    out = np.zeros(4 + n_d, dtype=np.complex128)
    if p.incompressible:
        from .operator import _plane_basis

        e1x, e1y, e1z, e2x, e2y, e2z = _plane_basis(p.kx, p.ky, p.kz)
        out[1:4] = vec[0] * np.array([e1x, e1y, e1z]) + vec[1] * np.array([e2x, e2y, e2z])
        out[4:] = vec[2:]
    else:
        out[0] = vec[0] / p.cs
        out[1:] = vec[1:]
    return out


def _normalise(state: np.ndarray) -> np.ndarray:
    i = 4
    if abs(state[i]) <= 1e-300 * max(np.abs(state).max(), 1e-300):
        i = int(np.argmax(np.abs(state)))  # dust density not excited (e.g. mu = 0): largest entry
    out = state / state[i]
    out[i] = 1.0  # exactly
    return out


def _labelled(vec: np.ndarray, p: StreamingParams) -> dict[str, Any]:
    out: dict[str, Any] = {key: complex(vec[i]) for i, key in enumerate(GAS_KEYS)}
    dust = vec[4:].reshape(p.nspecies, 4)
    for i, key in enumerate(DUST_KEYS):
        out[key] = dust[:, i].copy() if p.multi else complex(dust[0, i])
    return out


def eigenmodes(p: StreamingParams) -> Eigenmodes:
    """Every eigenvalue and eigenvector of the linear operator of ``p`` (LAPACK ``zgeev``).

    Examples
    --------
    >>> modes = eigenmodes(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, drag="yj07"))
    >>> len(modes), round(float(modes.omega[0].imag), 7)
    (8, 0.4190204)
    """
    L = operator_matrix(p)
    lam, vecs = np.linalg.eig(L)
    omega = 1j * lam
    order = np.lexsort((-omega.real, -omega.imag))
    omega = omega[order]
    states = np.empty((4 + 4 * p.nspecies, len(omega)), dtype=np.complex128)
    for col, i in enumerate(order):
        states[:, col] = _normalise(_full_state(vecs[:, i], p))
    return Eigenmodes(omega, states, p)


def fastest_mode(p: StreamingParams) -> Mode:
    """The fastest-growing eigenmode of ``p`` (largest Im ω), normalised to δρ_p/ρ_p0 = 1.

    Examples
    --------
    Youdin & Johansen (2007) linA, in the standard time convention:

    >>> m = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30, kz=30, drag="yj07"))
    >>> f"{m.omega:.7f}", f"{m.eigenvector['ux']:.7f}"
    ('0.3480127+0.4190204j', '-0.1691398+0.0361553j')
    """
    return eigenmodes(p).mode(0)


# ---------------------------------------------------------------------------- fast path


@numba.njit(cache=True, parallel=True)
def _growth_kernel(kx, ky, kz, cs, Ux, Uy, taus, mus, Vx, Vy, Vz, gamma, beta, s_out, f_out, ok):
    npts, nsp = taus.shape
    nmax = 4 + 4 * nsp
    chunk = 256  # points per task: work arrays are allocated once per chunk
    nchunks = (npts + chunk - 1) // chunk
    for c in numba.prange(nchunks):
        L = np.empty((nmax, nmax), dtype=np.complex128)
        G = np.empty((3, 3 + 4 * nsp), dtype=np.complex128)
        w = np.empty(nmax, dtype=np.complex128)
        work = np.empty(nmax, dtype=np.complex128)
        for p in range(c * chunk, min(npts, (c + 1) * chunk)):
            n = fill_operator(L, G, kx[p], ky[p], kz[p], cs[p], Ux[p], Uy[p], taus[p], mus[p], Vx[p], Vy[p],
                              Vz[p], gamma, beta)
            ok[p] = hessenberg_eigvals(L, n, w, work)
            best = 0
            for i in range(1, n):
                if w[i].real > w[best].real:
                    best = i
            s_out[p] = w[best].real  # growth rate Im(omega) = Re(lambda)
            f_out[p] = -w[best].imag  # frequency Re(omega) = -Im(lambda)


def _species_arrays(taus, mu, vz, Pi, species_axis):
    """Broadcast inputs to (points..., N) species arrays."""
    taus = np.asarray(taus, dtype=np.float64)
    mu = np.asarray(mu, dtype=np.float64)
    if species_axis is None:
        taus = taus[..., None]
        mu = mu[..., None]
        vz = vz if isinstance(vz, str) else np.asarray(vz, dtype=np.float64)[..., None]
    else:
        taus = np.moveaxis(taus, species_axis, -1)
        mu = np.moveaxis(mu, species_axis, -1)
        if not isinstance(vz, str):
            vz = np.asarray(vz, dtype=np.float64)
            vz = np.moveaxis(vz, species_axis, -1) if vz.ndim else vz
    return taus, mu, vz


def growth_rate(
    *,
    taus: ArrayLike,
    mu: ArrayLike,
    kx: ArrayLike,
    kz: ArrayLike,
    ky: ArrayLike = 0.0,
    Pi: ArrayLike = 0.05,
    drag: str = "consistent",
    vz: ArrayLike | str = 0.0,
    species_axis: int | None = None,
    return_frequency: bool = False,
):
    """Growth rate s = max Im ω of the fastest mode, vectorised over broadcast arrays.

    Parameters are those of :class:`StreamingParams`, all by keyword (two array-like physical
    parameters must not be swappable by position); all broadcast against each other. With
    ``species_axis`` set, that axis of ``taus``, ``mu`` (and ``vz``) runs over dust species
    and is reduced away. The eigenvalues come from the compiled Hessenberg-QR kernel
    (:mod:`dustygas.linear.eigensolver`), parallel over points; a point where QR does not
    converge is recomputed with LAPACK.

    Returns
    -------
    s, or (s, frequency) with ``return_frequency``: arrays of the broadcast shape (Re ω of the
    fastest mode is its frequency).

    Examples
    --------
    >>> s = growth_rate(taus=0.1, mu=[3.0, 0.2], kx=[30.0, 6.0], kz=[30.0, 6.0], drag="yj07")
    >>> [f"{v:.7f}" for v in s]
    ['0.4190204', '0.0154764']
    """
    code = drag_code(drag)
    gamma, beta = DRAG_MODELS[list(DRAG_MODELS)[code]]
    taus_s, mu_s, vz_s = _species_arrays(taus, mu, vz, Pi, species_axis)
    kx, ky, kz, Pi = (np.asarray(a, dtype=np.float64) for a in (kx, ky, kz, Pi))
    vz_arr = np.zeros(()) if isinstance(vz_s, str) else vz_s
    pts_shape = np.broadcast_shapes(taus_s.shape[:-1], mu_s.shape[:-1], vz_arr.shape[:-1] if vz_arr.ndim else (),
                                    kx.shape, ky.shape, kz.shape, Pi.shape)
    nsp = np.broadcast_shapes(taus_s.shape[-1:], mu_s.shape[-1:], vz_arr.shape[-1:] if vz_arr.ndim else (1,))[0]
    full = pts_shape + (nsp,)
    T = np.ascontiguousarray(np.broadcast_to(taus_s, full)).reshape(-1, nsp)
    M = np.ascontiguousarray(np.broadcast_to(mu_s, full)).reshape(-1, nsp)
    Pi_f = np.broadcast_to(Pi, pts_shape).reshape(-1)
    if np.any(T <= 0) or not np.all(np.isfinite(T)):
        raise UserError("taus: stopping times must be finite and > 0")
    if np.any(M < 0) or not np.all(np.isfinite(M)):
        raise UserError("mu: dust-to-gas ratios must be finite and >= 0")
    if np.any(Pi_f < 0):
        raise UserError("Pi must be >= 0 (0 is the incompressible limit)")
    if isinstance(vz_s, str):
        if np.any(Pi_f == 0):
            raise UserError("vz='settling' needs Pi > 0")
        VZ = resolve_vz("settling", T, Pi_f[:, None])
    else:
        VZ = np.ascontiguousarray(np.broadcast_to(vz_s, full)).reshape(-1, nsp)
    KX, KY, KZ = (np.ascontiguousarray(np.broadcast_to(a, pts_shape)).reshape(-1) for a in (kx, ky, kz))
    if np.any((KX == 0) & (KY == 0) & (KZ == 0)):
        raise UserError("k = 0: every point needs a non-zero wavenumber")
    eq = nsh_velocities_multi(T, M)
    with np.errstate(divide="ignore"):
        CS = np.where(Pi_f > 0, 1.0 / np.where(Pi_f > 0, Pi_f, 1.0), math.inf)
    npts = T.shape[0]
    s = np.empty(npts)
    f = np.empty(npts)
    ok = np.empty(npts, dtype=np.bool_)
    # writable C arrays whatever the caller's broadcasting left read-only: one compiled signature
    # instead of up to nine (each 4-8 CPU-s of compilation on a fresh cache)
    args = (kernel_array(a) for a in (KX, KY, KZ, CS, eq.gas_vx, eq.gas_vy, T, M, eq.dust_vx, eq.dust_vy, VZ))
    _growth_kernel(*args, gamma, beta, s, f, ok)
    for i in np.flatnonzero(~ok):
        p = StreamingParams(taus=tuple(T[i]), mu=tuple(M[i]), kx=KX[i], kz=KZ[i], ky=KY[i], Pi=Pi_f[i],
                            drag=drag, vz=tuple(VZ[i]))
        lam = np.linalg.eigvals(operator_matrix(p))
        j = np.argmax(lam.real)
        s[i], f[i] = lam[j].real, -lam[j].imag
    s = s.reshape(pts_shape)
    f = f.reshape(pts_shape)
    return (s, f) if return_frequency else s
