"""Growth-rate maps of the streaming instability (thesis Figs 4.1-4.3 and eq. 4.20).

* :func:`growth_map` -- over a (μ, τ_s) grid, the fastest growth maximised over wavenumber,
  either over k_x at fixed k_z (Youdin & Goodman 2005, thesis Fig 4.1), over a bounded
  2D (k_x, k_z) box, or over |k| along a fixed angle θ_k = tan⁻¹(k_x/k_z);
* :func:`growth_vs_k` -- growth versus |k| at fixed θ_k (thesis Figs 4.2, 4.3);
* :func:`settling_ratio` -- t_growth/t_settle of thesis eq. 4.20
  (:func:`dustygas.physics.growth_to_settling_ratio`) for a growth-rate map.

In this inviscid model the growth rate does not decay at large k for every parameter set, so
a maximum over an unbounded k-range does not converge: every result carries the k-range it
was maximised over (``GrowthMap.attrs``, written into every file) and flags the points whose
optimum lies on the edge of that range (``at_edge``).

The optimiser runs compiled and in parallel over map points: a coarse logarithmic grid in k,
then golden-section refinement in ln k around the best coarse point (alternating k_x and k_z
for 2D boxes). The coarse grid decides which local maximum is refined, so a narrow resonance
between coarse points can be missed; ``coarse`` sets the grid density.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numba
import numpy as np
from numpy.typing import ArrayLike

from ..errors import UserError
from ..physics import growth_to_settling_ratio, nsh_velocities_multi
from .eigensolver import hessenberg_eigvals
from .modes import growth_rate
from .operator import DRAG_MODELS, drag_code, fill_operator, resolve_vz

__all__ = ["GrowthMap", "growth_map", "growth_vs_k", "settling_ratio"]

_GOLDEN = 0.3819660112501051  # 2 - golden ratio
_MODES = {"kx": 0, "box": 1, "angle": 2}


@numba.njit(cache=True)
def _growth_at(kx, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, w, work):
    n = fill_operator(L, G, kx, 0.0, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta)
    if not hessenberg_eigvals(L, n, w, work):
        return -math.inf
    best = w[0].real
    for i in range(1, n):
        if w[i].real > best:
            best = w[i].real
    return best


@numba.njit(cache=True)
def _k_of(mode, u, v, kfix, sin_t, cos_t):
    """(kx, kz) from log-wavenumbers: mode 0: kx=e^u, kz=kfix; 1: kx=e^u, kz=e^v; 2: |k|=e^u at angle."""
    if mode == 0:
        return math.exp(u), kfix
    if mode == 1:
        return math.exp(u), math.exp(v)
    k = math.exp(u)
    return k * sin_t, k * cos_t


@numba.njit(cache=True)
def _objective(mode, mirror, u, v, kfix, sin_t, cos_t, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, w, work):
    """Growth at log-wavenumbers (u, v); with ``mirror`` the larger of k_z and −k_z (sign returned)."""
    kx, kz = _k_of(mode, u, v, kfix, sin_t, cos_t)
    s = _growth_at(kx, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, w, work)
    sign = 1.0
    if mirror:
        s2 = _growth_at(kx, -kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, w, work)
        if s2 > s:
            s = s2
            sign = -1.0
    return s, sign


@numba.njit(cache=True, parallel=True)
def _optimise(mode, mirror, lo_u, hi_u, lo_v, hi_v, kfix, sin_t, cos_t, ncoarse, nrefine, cs, Ux, Uy, T, M, Vx, Vy,
              Vz, gamma, beta, s_out, kx_out, kz_out):
    npts, nsp = T.shape
    nmax = 4 + 4 * nsp
    nv = ncoarse if mode == 1 else 1
    du = (hi_u - lo_u) / (ncoarse - 1)
    dv = (hi_v - lo_v) / (ncoarse - 1) if mode == 1 else 0.0
    for p in numba.prange(npts):
        L = np.empty((nmax, nmax), dtype=np.complex128)
        G = np.empty((3, 3 + 4 * nsp), dtype=np.complex128)
        w = np.empty(nmax, dtype=np.complex128)
        work = np.empty(nmax, dtype=np.complex128)
        args = (cs[p], Ux[p], Uy[p], T[p], M[p], Vx[p], Vy[p], Vz[p], gamma, beta, L, G, w, work)
        best = -math.inf
        bu = lo_u
        bv = lo_v
        bsign = 1.0
        for i in range(ncoarse):
            for j in range(nv):
                u = lo_u + i * du
                v = lo_v + j * dv
                s, sg = _objective(mode, mirror, u, v, kfix, sin_t, cos_t, *args)
                if s > best:
                    best, bu, bv, bsign = s, u, v, sg
        # golden-section refinement in each log-coordinate (alternating for the 2D box)
        naxes = 2 if mode == 1 else 1
        for r in range(naxes):
            for axis in range(naxes):
                c0 = bu if axis == 0 else bv
                h = du if axis == 0 else dv
                a = max(lo_u if axis == 0 else lo_v, c0 - h)
                b = min(hi_u if axis == 0 else hi_v, c0 + h)
                x1 = a + _GOLDEN * (b - a)
                x2 = b - _GOLDEN * (b - a)
                f1, g1 = _objective(mode, mirror, x1 if axis == 0 else bu, x1 if axis == 1 else bv, kfix, sin_t,
                                    cos_t, *args)
                f2, g2 = _objective(mode, mirror, x2 if axis == 0 else bu, x2 if axis == 1 else bv, kfix, sin_t,
                                    cos_t, *args)
                for it in range(nrefine):
                    if f1 > f2:
                        b = x2
                        x2, f2, g2 = x1, f1, g1
                        x1 = a + _GOLDEN * (b - a)
                        f1, g1 = _objective(mode, mirror, x1 if axis == 0 else bu, x1 if axis == 1 else bv, kfix,
                                            sin_t, cos_t, *args)
                    else:
                        a = x1
                        x1, f1, g1 = x2, f2, g2
                        x2 = b - _GOLDEN * (b - a)
                        f2, g2 = _objective(mode, mirror, x2 if axis == 0 else bu, x2 if axis == 1 else bv, kfix,
                                            sin_t, cos_t, *args)
                xb, fb, gb = (x1, f1, g1) if f1 > f2 else (x2, f2, g2)
                if fb > best:
                    best, bsign = fb, gb
                    if axis == 0:
                        bu = xb
                    else:
                        bv = xb
        kx, kz = _k_of(mode, bu, bv, kfix, sin_t, cos_t)
        s_out[p] = best
        kx_out[p] = kx
        kz_out[p] = kz * bsign


@dataclass
class GrowthMap:
    """Fastest growth over a (τ_s, μ) grid; arrays have shape (len(taus), len(mu)).

    Attributes
    ----------
    growth
        Maximal growth rate s/Ω over the stated k-range.
    kx, kz
        Wavenumber (units 1/(ηr)) of that maximum.
    at_edge
        True where the maximum sits on the boundary of the k-range (the true maximum may lie
        outside it).
    attrs
        Everything needed to reproduce the map: method, k-range, Π, drag, v_z, units.
    """

    mu: np.ndarray
    taus: np.ndarray
    growth: np.ndarray
    kx: np.ndarray
    kz: np.ndarray
    at_edge: np.ndarray
    attrs: dict[str, Any] = field(default_factory=dict)

    def save(self, path: str | Path) -> Path:
        """Write the map to HDF5 (``.h5``) with every attribute, or to JSON (``.json``)."""
        path = Path(path)
        if path.suffix == ".json":
            data = {"attrs": self.attrs, "mu": self.mu.tolist(), "taus": self.taus.tolist(),
                    "growth_rate": self.growth.tolist(), "kx": self.kx.tolist(), "kz": self.kz.tolist(),
                    "at_edge": self.at_edge.tolist()}
            path.write_text(json.dumps(data, indent=1))
            return path
        import h5py

        tmp = path.with_name(path.name + ".tmp")
        with h5py.File(tmp, "w") as f:
            for name, arr in (("mu", self.mu), ("taus", self.taus), ("growth_rate", self.growth), ("kx", self.kx),
                              ("kz", self.kz), ("at_edge", self.at_edge)):
                f.create_dataset(name, data=arr)
            for key, value in self.attrs.items():
                f.attrs[key] = value if not isinstance(value, (list, tuple)) else np.asarray(value)
        tmp.replace(path)
        return path


def _check_range(name: str, rng) -> tuple[float, float]:
    try:
        lo, hi = (float(v) for v in rng)
    except (TypeError, ValueError):
        raise UserError(f"{name} = {rng!r}: expected (min, max)") from None
    if not (0 < lo < hi < math.inf):
        raise UserError(f"{name} = {rng!r}: expected 0 < min < max")
    return lo, hi


def growth_map(
    *,
    mu: ArrayLike,
    taus: ArrayLike,
    method: str = "kx",
    kz: float = 1000.0,
    kx_range: tuple[float, float] = (1.0, 1e5),
    kz_range: tuple[float, float] = (1.0, 1e4),
    k_range: tuple[float, float] = (1e-2, 1e5),
    theta_deg: float = 30.0,
    Pi: float = 0.05,
    drag: str = "consistent",
    vz: float | str = 0.0,
    mirror: bool = False,
    coarse: int | None = None,
    refine: int = 14,
) -> GrowthMap:
    """Maximal growth rate over wavenumbers for every (τ_s, μ) of a grid.

    Parameters
    ----------
    mu, taus
        1D grids of dust-to-gas ratio and stopping time (keyword-only, like every
        array-like parameter of :mod:`dustygas.linear`).
    method
        ``"kx"``: maximise over k_x in ``kx_range`` at fixed ``kz`` (YG05, thesis Fig 4.1);
        ``"box"``: maximise over (k_x, k_z) in ``kx_range`` × ``kz_range``;
        ``"angle"``: maximise over |k| in ``k_range`` along θ_k = ``theta_deg``
        (k_x = |k| sin θ_k, k_z = |k| cos θ_k).
    Pi, drag, vz
        As in :class:`dustygas.linear.StreamingParams` (``vz="settling"`` per species).
    mirror
        Also try −k_z at every wavevector and keep the faster (the fastest mode at |θ_k|;
        with a vertical drift the two differ). ``kz`` of the result carries the sign used.
    coarse, refine
        Coarse log-grid points per k-axis (default 12; 8 per axis for ``"box"``) and
        golden-section steps per refinement (14 narrow the bracket 830-fold).

    Examples
    --------
    linA's τ_s and μ at the linA k_z: the fastest k_x is 43.1/(ηr), inside the range; in a
    2D box the maximum sits on the k_z edge (it keeps growing with k):

    >>> m = growth_map(mu=[3.0], taus=[0.1], method="kx", kz=30.0, kx_range=(1, 1e3))
    >>> round(float(m.growth[0, 0]), 4), round(float(m.kx[0, 0]), 1), bool(m.at_edge[0, 0])
    (0.4496, 43.1, False)
    >>> bool(growth_map(mu=[3.0], taus=[0.1], method="box", kx_range=(1, 100), kz_range=(1, 100)).at_edge[0, 0])
    True
    """
    mode = _MODES.get(method)
    if mode is None:
        raise UserError(f"method {method!r}: choose one of {', '.join(_MODES)}")
    mu = np.atleast_1d(np.asarray(mu, dtype=np.float64))
    taus = np.atleast_1d(np.asarray(taus, dtype=np.float64))
    if mu.ndim != 1 or taus.ndim != 1 or np.any(mu < 0) or np.any(taus <= 0):
        raise UserError("growth_map: mu (>= 0) and taus (> 0) must be 1D grids")
    if coarse is None:
        coarse = 8 if method == "box" else 12
    if coarse < 3 or refine < 0:
        raise UserError("growth_map: coarse >= 3 and refine >= 0")
    code = drag_code(drag)
    gamma, beta = DRAG_MODELS[list(DRAG_MODELS)[code]]
    if Pi < 0:
        raise UserError("Pi must be >= 0")
    attrs: dict[str, Any] = {"method": method, "Pi": float(Pi), "drag": drag, "vz": str(vz) if isinstance(vz, str)
                             else float(vz), "units": "growth rate in Omega; wavenumbers in 1/(eta r)",
                             "time_convention": "exp(i k.x - i omega t), growth = Im omega"}
    lo_v = hi_v = 0.0
    kfix = 0.0
    sin_t = cos_t = 0.0
    if mode == 0:
        lo, hi = _check_range("kx_range", kx_range)
        if not kz > 0:
            raise UserError("kz must be > 0")
        kfix = float(kz)
        attrs.update(kx_range=[lo, hi], kz=kfix)
    elif mode == 1:
        lo, hi = _check_range("kx_range", kx_range)
        lo_z, hi_z = _check_range("kz_range", kz_range)
        lo_v, hi_v = math.log(lo_z), math.log(hi_z)
        attrs.update(kx_range=[lo, hi], kz_range=[lo_z, hi_z])
    else:
        lo, hi = _check_range("k_range", k_range)
        th = math.radians(theta_deg)
        sin_t, cos_t = math.sin(th), math.cos(th)
        attrs.update(k_range=[lo, hi], theta_deg=float(theta_deg))
    T2, M2 = np.meshgrid(taus, mu, indexing="ij")
    T = np.ascontiguousarray(T2.reshape(-1, 1))
    M = np.ascontiguousarray(M2.reshape(-1, 1))
    eq = nsh_velocities_multi(T, M)
    if isinstance(vz, str):
        if Pi == 0:
            raise UserError("vz='settling' needs Pi > 0")
        VZ = resolve_vz(vz, T, Pi)
    else:
        VZ = np.full_like(T, float(vz))
    cs = np.full(T.shape[0], math.inf if Pi == 0 else 1.0 / Pi)
    s = np.empty(T.shape[0])
    kxo = np.empty_like(s)
    kzo = np.empty_like(s)
    _optimise(mode, bool(mirror), math.log(lo), math.log(hi), lo_v, hi_v, kfix, sin_t, cos_t, int(coarse), int(refine), cs,
              np.ascontiguousarray(eq.gas_vx), np.ascontiguousarray(eq.gas_vy), T, M,
              np.ascontiguousarray(eq.dust_vx), np.ascontiguousarray(eq.dust_vy), np.ascontiguousarray(VZ),
              gamma, beta, s, kxo, kzo)
    shape = T2.shape
    if mode == 2:
        kk = np.hypot(kxo, kzo)
        edge = np.isclose(kk, lo, rtol=1e-6) | np.isclose(kk, hi, rtol=1e-6)
    else:
        edge = np.isclose(kxo, lo, rtol=1e-6) | np.isclose(kxo, hi, rtol=1e-6)
        if mode == 1:
            az = np.abs(kzo)
            edge |= np.isclose(az, math.exp(lo_v), rtol=1e-6) | np.isclose(az, math.exp(hi_v), rtol=1e-6)
    attrs.update(coarse=int(coarse), refine=int(refine), mirror=bool(mirror))
    return GrowthMap(mu, taus, s.reshape(shape), kxo.reshape(shape), kzo.reshape(shape), edge.reshape(shape), attrs)


def growth_vs_k(
    *,
    taus: ArrayLike,
    mu: ArrayLike,
    k: ArrayLike,
    theta_deg: float = 30.0,
    mirror: bool = False,
    Pi: float = 0.05,
    drag: str = "consistent",
    vz: float | str = 0.0,
) -> np.ndarray:
    """Growth rate versus |k| along θ_k = tan⁻¹(k_x/k_z) (thesis Figs 4.2, 4.3).

    ``taus``, ``mu`` and ``k`` broadcast (e.g. ``taus[:, None]`` against ``k[None, :]``).
    With ``mirror=True`` the result is the larger of the growth rates at (k_x, +k_z) and
    (k_x, −k_z), i.e. the fastest mode at |θ_k|; with a vertical drift the two differ.
    """
    k = np.asarray(k, dtype=np.float64)
    th = math.radians(theta_deg)
    kx, kz = k * math.sin(th), k * math.cos(th)
    s = growth_rate(taus=taus, mu=mu, kx=kx, kz=kz, Pi=Pi, drag=drag, vz=vz)
    if mirror:
        s = np.maximum(s, growth_rate(taus=taus, mu=mu, kx=kx, kz=-kz, Pi=Pi, drag=drag, vz=vz))
    return s


def settling_ratio(*, growth: ArrayLike, taus: ArrayLike) -> np.ndarray:
    """t_growth/t_settle = (Ω/s) τ_s/(2τ_s² + 1) (thesis eq. 4.20); < 1: growth beats settling.

    Non-positive growth rates give ``inf`` (the mode never outgrows settling).
    """
    s = np.asarray(growth, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        r = growth_to_settling_ratio(np.where(s > 0, s, np.nan), taus)
    return np.where(s > 0, r, np.inf)
