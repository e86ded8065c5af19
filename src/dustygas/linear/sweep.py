"""Brute-force sweep of the non-axisymmetric shearing-wave system over (μ, τ_s, k_x0, k_y).

Thesis §4.6.2 proposes to integrate eqs. 4.35 "by brute force" over the parameter space
(μ, τ_s, k_x, k_y) and to identify preferred wavevectors. Every point of the 4D grid is one
shearing wave (:mod:`dustygas.linear.shearing_wave`: k_x(t) = k_x0 + (3/2) k_y t, gas + one dust
species in the NSH drift, optional fixed k_z), integrated by the compiled Dormand–Prince
integrator of :mod:`dustygas.linear.sweep_kernel` from t = 0 to t_end.

Quantities (arrays of shape (n_mu, n_taus, n_kx, n_ky); E is the wave energy of
:mod:`dustygas.linear.shearing_wave`, Σ_d = δρ_p/ρ_p0 the dust-density perturbation)

``energy_peak``
    G_peak = max_{0≤t≤t_end} [E(t)/E(0)]^{1/2}: the transient (swing) amplification;
``t_peak``
    the time of that maximum;
``energy_final``
    G_E = [E(t_end)/E(0)]^{1/2}: the net amplification;
``dust_final``
    G_Σ = |Σ_d(t_end)|/|Σ_d(0)|: what the dust surface density of a run shows;
``mean_growth``
    s̄ = ln[E(t_b)/E(t_a)] / (2 (t_b − t_a)): the time-averaged growth rate over the window
    (t_a, t_b) = (w_0, w_1) t_end (default the whole integration); for k_y = 0 it is the
    axisymmetric growth rate of the starting eigenmode;
``steps``, ``failed``
    accepted steps of each integration, and the points where it failed (their values NaN);
``dust_t``, ``energy_t`` (with ``times = n``)
    G_Σ and G_E at the n times t_end·i/n, i = 1 … n (an extra trailing dimension ``time``).

``t_end = "swing"`` integrates each *leading* wave (k_x0 k_y < 0) over its symmetric swing
(0, 2 t_swing), from k_x0 to −k_x0; other points are NaN (not failures).

The **preferred wavevector** of each (μ, τ_s) is the (k_x0, k_y) that maximises ``metric``
(default ``dust_final``); it is reported with the angle θ = arctan(k_y/k_x) ∈ (−90°, 90°] of the
wavevector it has at t_end, k_x(t_end) = k_x0 + (3/2) k_y t_end -- the wave a Fourier transform
of Σ_d(x, y) taken at t_end shows when every wave started with the same amplitude. With
``times``, :meth:`SweepResult.preferred_series` gives the same at every sample time: the
predicted angle θ(t) of a run whose waves all started at t = 0.

The grid is cut into chunks of consecutive points (k_y fastest), each computed by
:func:`compute_chunk`; :mod:`dustygas.linear.sweep_run` runs them through any executor and
resumably (:func:`~dustygas.linear.sweep_run.sweep`, :func:`~dustygas.linear.sweep_run.run_sweep`).
"""

from __future__ import annotations

import hashlib
import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .._version import __version__
from ..errors import UserError
from ..io.atomic import atomic_path
from ..physics import nsh_velocities_multi
from .operator import DRAG_MODELS, drag_code, float_tuple
from .shearing_wave import SHEAR_RATE
from .sweep_kernel import INITIAL_STATES, RESULT_FIELDS, integrate_chunk

__all__ = ["SweepSpec", "SweepResult", "compute_chunk", "METRICS", "DIMENSIONS"]

#: quantities a preferred wavevector can maximise
METRICS = ("dust_final", "energy_final", "energy_peak", "mean_growth")
DIMENSIONS = ("mu", "taus", "kx0", "ky")

DESCRIPTIONS = {
    "energy_peak": "max over 0 <= t <= t_end of sqrt(E(t)/E(0)) (transient swing amplification)",
    "t_peak": "time of energy_peak [1/Omega]",
    "energy_final": "sqrt(E(t_end)/E(0)) (net energy amplification)",
    "dust_final": "|Sigma_d(t_end)|/|Sigma_d(0)|, Sigma_d = drho_p/rho_p0 (dust-density amplification)",
    "mean_growth": "ln(E(t_b)/E(t_a)) / (2 (t_b - t_a)), (t_a, t_b) = window * t_end [Omega]",
    "steps": "accepted Dormand-Prince steps",
    "failed": "1 where the integration failed (values NaN)",
    "dust_t": "|Sigma_d(t)|/|Sigma_d(0)| at the sample times",
    "energy_t": "sqrt(E(t)/E(0)) at the sample times",
}


@dataclass(frozen=True, kw_only=True)
class SweepSpec:
    """Everything that defines a sweep (validated on construction; one-line errors name the key).

    Grids ``mu`` (>= 0), ``taus`` (> 0), ``kx`` (k_x0) and ``ky`` are 1D lists (units of the
    linear theory: K = k ηr, τ_s = Ω t_s). ``kz`` is fixed (0: the thesis's planar system 4.35);
    ``Pi``, ``drag`` as in :class:`~dustygas.linear.StreamingParams`. ``t_end`` (1/Ω) or
    ``"swing"``; ``window`` the averaging window of ``mean_growth`` as fractions of t_end;
    ``initial``: ``"fastest"`` (eigenmode of L(k(0)) with the largest growth rate),
    ``"vortical"`` (gas velocity along ẑ × k̂, nothing else: the Kelvin wave) or ``"dust"``
    (δρ_p/ρ_p0 = 1 only). ``rtol``, ``atol``, ``max_step`` (fraction of t_end) and
    ``max_steps`` control the integrator; ``chunk`` is the number of points per task;
    ``times`` > 0 also samples the dust and energy amplifications at ``times`` equally spaced
    times (needs a numeric ``t_end``).
    """

    mu: tuple[float, ...]
    taus: tuple[float, ...]
    kx: tuple[float, ...]
    ky: tuple[float, ...]
    kz: float = 0.0
    Pi: float = 0.05
    drag: str = "consistent"
    t_end: float | str = 2.0 * math.pi
    window: tuple[float, float] = (0.0, 1.0)
    initial: str = "fastest"
    metric: str = "dust_final"
    rtol: float = 1e-6
    atol: float = 1e-12
    max_step: float = 0.05
    max_steps: int = 10_000_000
    chunk: int = 64
    times: int = 0

    def __post_init__(self) -> None:
        for name in ("mu", "taus", "kx", "ky"):
            object.__setattr__(self, name, float_tuple(getattr(self, name), name))
        if min(self.mu) < 0:
            raise UserError(f"mu = {list(self.mu)}: dust-to-gas ratios must be >= 0")
        if min(self.taus) <= 0:
            raise UserError(f"taus = {list(self.taus)}: stopping times must be > 0")
        for name in ("kz", "Pi", "rtol", "atol", "max_step"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise UserError(f"{name} = {v!r}: expected a finite number")
            object.__setattr__(self, name, float(v))
        if self.Pi < 0:
            raise UserError(f"Pi = {self.Pi!r}: must be >= 0 (0 is the incompressible limit)")
        drag_code(self.drag)
        if isinstance(self.t_end, str):
            if self.t_end != "swing":
                raise UserError(f"t_end = {self.t_end!r}: a positive time (1/Omega) or 'swing'")
            if 0.0 in self.ky:
                raise UserError("ky contains 0, but t_end = 'swing' needs k_y != 0 at every point "
                                "(the swing time is -kx0/(1.5 ky))")
            if not any(a * b < 0 for a in self.kx for b in self.ky):
                raise UserError("t_end = 'swing': no leading wave (kx * ky < 0) in the grid")
        else:
            if isinstance(self.t_end, bool) or not isinstance(self.t_end, (int, float)) or not (
                    math.isfinite(self.t_end) and self.t_end > 0):
                raise UserError(f"t_end = {self.t_end!r}: a positive time (1/Omega) or 'swing'")
            object.__setattr__(self, "t_end", float(self.t_end))
        try:
            w0, w1 = (float(v) for v in self.window)
        except (TypeError, ValueError):
            raise UserError(f"window = {self.window!r}: expected two fractions of t_end [w0, w1]") from None
        if not 0.0 <= w0 < w1 <= 1.0:
            raise UserError(f"window = {self.window!r}: expected 0 <= w0 < w1 <= 1 (fractions of t_end)")
        object.__setattr__(self, "window", (w0, w1))
        if self.initial not in INITIAL_STATES:
            raise UserError(f"initial = {self.initial!r}: choose one of {', '.join(INITIAL_STATES)}")
        if self.metric not in METRICS:
            raise UserError(f"metric = {self.metric!r}: choose one of {', '.join(METRICS)}")
        if self.initial == "vortical" and 0.0 in self.ky and 0.0 in self.kx:
            raise UserError("initial = 'vortical' needs k_x0 or k_y != 0 at every point (kx and ky both contain 0)")
        if self.kz == 0.0 and 0.0 in self.kx and 0.0 in self.ky:
            raise UserError("k = 0 at kx = ky = 0 with kz = 0: remove 0 from kx or ky, or give kz != 0")
        if not (0 < self.rtol < 1 and self.atol > 0 and 0 < self.max_step <= 1):
            raise UserError("rtol must be in (0, 1), atol > 0 and max_step in (0, 1]")
        for name, least in (("max_steps", 1), ("chunk", 1), ("times", 0)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < least:
                raise UserError(f"{name} = {v!r}: expected an integer >= {least}")
            object.__setattr__(self, name, int(v))
        if self.times and self.t_end == "swing":
            raise UserError("times needs a fixed t_end (every swing has its own length)")

    # ------------------------------------------------------------------ derived
    @property
    def shape(self) -> tuple[int, int, int, int]:
        return (len(self.mu), len(self.taus), len(self.kx), len(self.ky))

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    @property
    def nchunks(self) -> int:
        return -(-self.size // self.chunk)

    def chunk_range(self, i: int) -> tuple[int, int]:
        return i * self.chunk, min(self.size, (i + 1) * self.chunk)

    def to_dict(self) -> dict[str, Any]:
        d = asdict(self)
        for k, v in d.items():
            if isinstance(v, tuple):
                d[k] = list(v)
        return d

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> "SweepSpec":
        return cls(**json.loads(text))

    def digest(self) -> str:
        """Hash of everything that changes the results (chunk size included: it defines the work files)."""
        return hashlib.sha256((self.to_json() + __version__).encode()).hexdigest()[:16]

    @property
    def sample_times(self) -> np.ndarray:
        """The ``times`` sample times t_end·i/n (empty without ``times``)."""
        if not self.times:
            return np.zeros(0)
        return float(self.t_end) * np.arange(1, self.times + 1) / self.times

    def end_times(self, kx0: np.ndarray, ky: np.ndarray) -> np.ndarray:
        if self.t_end == "swing":
            with np.errstate(divide="ignore", invalid="ignore"):
                t = -2.0 * kx0 / (SHEAR_RATE * ky)
            return np.where(kx0 * ky < 0, t, np.nan)
        return np.full(kx0.shape, float(self.t_end))


# ---------------------------------------------------------------------------- one chunk


def compute_chunk(spec_json: str, start: int, stop: int) -> np.ndarray:
    """Results of points ``start .. stop-1`` (flat C order of the grid), shape (7 + 2 times, stop - start):
    the :data:`RESULT_FIELDS`, then ``dust_t`` and ``energy_t`` at each sample time.

    A module-level function of plain arguments, so that every executor can ship it.
    """
    spec = SweepSpec.from_json(spec_json)
    idx = np.unravel_index(np.arange(start, stop), spec.shape)
    mu = np.asarray(spec.mu)[idx[0]]
    taus = np.asarray(spec.taus)[idx[1]]
    kx0 = np.ascontiguousarray(np.asarray(spec.kx)[idx[2]])
    ky = np.ascontiguousarray(np.asarray(spec.ky)[idx[3]])
    T = np.ascontiguousarray(taus[:, None])
    M = np.ascontiguousarray(mu[:, None])
    eq = nsh_velocities_multi(T, M)
    gamma, beta = DRAG_MODELS[spec.drag]
    t1 = spec.end_times(kx0, ky)
    w0, w1 = spec.window
    out = np.empty((len(RESULT_FIELDS), stop - start))
    series = np.empty((2, stop - start, spec.times))
    tfrac = np.arange(1, spec.times + 1) / spec.times if spec.times else np.zeros(0)
    cs = math.inf if spec.Pi == 0 else 1.0 / spec.Pi
    integrate_chunk(INITIAL_STATES[spec.initial], T, M, np.ascontiguousarray(eq.gas_vx, dtype=np.float64).reshape(-1),
                    np.ascontiguousarray(eq.gas_vy, dtype=np.float64).reshape(-1),
                    np.ascontiguousarray(eq.dust_vx, dtype=np.float64), np.ascontiguousarray(eq.dust_vy, dtype=np.float64),
                    np.zeros_like(T), kx0, ky, spec.kz, cs, gamma, beta, t1, w0 * t1, w1 * t1, tfrac, spec.rtol,
                    spec.atol, spec.max_step, spec.max_steps, out, series)
    return np.concatenate([out, series[0].T, series[1].T], axis=0)


# ---------------------------------------------------------------------------- results


@dataclass
class SweepResult:
    """The sweep's arrays (module docstring), shape (n_mu, n_taus, n_kx, n_ky), and its spec."""

    spec: SweepSpec
    data: dict[str, np.ndarray]
    attrs: dict[str, Any] = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[name]

    def preferred(self, metric: str | None = None) -> dict[str, np.ndarray]:
        """Preferred wavevector per (μ, τ_s): arrays of shape (n_mu, n_taus).

        Keys: ``angle_deg`` = arctan(k_y / k_x(t_end)) in degrees, ``kx0``, ``ky``, ``kx_end``,
        ``value`` (the maximised ``metric``), ``angle0_deg`` = arctan(k_y/k_x0) and ``at_edge``
        (1 where the maximum lies on the edge of the (k_x0, k_y) grid: the true preferred wave may
        lie outside it). NaN where every point of that (μ, τ_s) is NaN.
        """
        metric = metric or self.spec.metric
        if metric not in METRICS:
            raise UserError(f"metric = {metric!r}: choose one of {', '.join(METRICS)}")
        a = self.data[metric]
        nm, nt = a.shape[:2]
        flat = a.reshape(nm, nt, -1)
        ok = np.isfinite(flat).any(axis=-1)
        idx = np.argmax(np.where(np.isfinite(flat), flat, -np.inf), axis=-1)
        i, j = np.unravel_index(idx, a.shape[2:])
        kx0 = np.asarray(self.spec.kx)[i]
        ky = np.asarray(self.spec.ky)[j]
        t1 = self.spec.end_times(kx0, ky)
        kx_end = kx0 + SHEAR_RATE * ky * t1
        nx, ny = a.shape[2:]
        edge = ((nx > 1) & ((i == 0) | (i == nx - 1))) | ((ny > 1) & ((j == 0) | (j == ny - 1)))
        out = {"angle_deg": _angle(kx_end, ky), "angle0_deg": _angle(kx0, ky), "kx0": kx0, "ky": ky,
               "kx_end": kx_end, "value": np.take_along_axis(flat, idx[..., None], -1)[..., 0]}
        out = {k: np.where(ok, v, np.nan) for k, v in out.items()}
        out["at_edge"] = (edge & ok).astype(np.int8)
        return out

    def preferred_series(self) -> dict[str, np.ndarray]:
        """The preferred wave at every sample time (needs ``times``): arrays (n_mu, n_taus, n_times).

        Keys as :meth:`preferred` for the metric ``dust_t`` (the dust amplification since t = 0);
        ``angle_deg`` = arctan(k_y/k_x(t)) of the most amplified wave at each time t, plus ``time``.
        """
        if "dust_t" not in self.data:
            raise UserError("this sweep has no sampled times (run it with times > 0)")
        a = self.data["dust_t"]
        nm, nt, nx, ny, ns = a.shape
        flat = np.moveaxis(a, -1, 2).reshape(nm, nt, ns, nx * ny)
        ok = np.isfinite(flat).any(axis=-1)
        idx = np.argmax(np.where(np.isfinite(flat), flat, -np.inf), axis=-1)
        i, j = np.unravel_index(idx, (nx, ny))
        kx0 = np.asarray(self.spec.kx)[i]
        ky = np.asarray(self.spec.ky)[j]
        t = self.spec.sample_times
        kx_t = kx0 + SHEAR_RATE * ky * t
        out = {"angle_deg": _angle(kx_t, ky), "kx0": kx0, "ky": ky, "kx_t": kx_t,
               "value": np.take_along_axis(flat, idx[..., None], -1)[..., 0]}
        out = {k: np.where(ok, v, np.nan) for k, v in out.items()}
        out["time"] = t
        return out

    # ------------------------------------------------------------------ files
    def save(self, path: str | Path) -> Path:
        """One HDF5 file: labelled dimensions (dimension scales), every parameter as attributes."""
        import h5py

        path = Path(path)
        pref = self.preferred()
        with atomic_path(path) as tmp:
            with h5py.File(tmp, "w", track_order=True) as f:
                scales = {}
                for name, values, unit, desc in (
                        ("mu", self.spec.mu, "1", "dust-to-gas density ratio rho_p0/rho_g0"),
                        ("taus", self.spec.taus, "1", "stopping time tau_s = Omega t_s"),
                        ("kx0", self.spec.kx, "1/(eta r)", "initial radial wavenumber K_x0 = k_x0 eta r"),
                        ("ky", self.spec.ky, "1/(eta r)", "azimuthal wavenumber K_y = k_y eta r")):
                    d = f.create_dataset(name, data=np.asarray(values, dtype=np.float64), track_times=False)
                    d.attrs["unit"] = unit
                    d.attrs["description"] = desc
                    d.make_scale(name)
                    scales[name] = d
                if self.spec.times:
                    d = f.create_dataset("time", data=self.spec.sample_times, track_times=False)
                    d.attrs["unit"] = "1/Omega"
                    d.attrs["description"] = "sample times t_end * i / times"
                    d.make_scale("time")
                    scales["time"] = d
                for name in [*RESULT_FIELDS, *(("dust_t", "energy_t") if self.spec.times else ())]:
                    d = f.create_dataset(name, data=self.data[name], track_times=False)
                    d.attrs["description"] = DESCRIPTIONS[name]
                    for axis, dim in enumerate(DIMENSIONS + (("time",) if name.endswith("_t") else ())):
                        d.dims[axis].label = dim
                        d.dims[axis].attach_scale(scales[dim])
                g = f.create_group("preferred", track_order=True)
                g.attrs["metric"] = self.spec.metric
                g.attrs["description"] = ("per (mu, taus): the (kx0, ky) maximising the metric; angle_deg = "
                                          "arctan(ky / kx(t_end)), kx(t_end) = kx0 + 1.5 ky t_end")
                for name, arr in pref.items():
                    d = g.create_dataset(name, data=arr, track_times=False)
                    for axis, dim in enumerate(DIMENSIONS[:2]):
                        d.dims[axis].label = dim
                        d.dims[axis].attach_scale(scales[dim])
                if self.spec.times:
                    g = f.create_group("preferred_t", track_order=True)
                    g.attrs["description"] = ("per (mu, taus, time): the (kx0, ky) of the largest dust amplification "
                                              "dust_t; angle_deg = arctan(ky / kx(t)), kx(t) = kx0 + 1.5 ky t")
                    for name, arr in self.preferred_series().items():
                        if name == "time":
                            continue
                        d = g.create_dataset(name, data=arr, track_times=False)
                        for axis, dim in enumerate(("mu", "taus", "time")):
                            d.dims[axis].label = dim
                            d.dims[axis].attach_scale(scales[dim])
                f.attrs["dustygas_version"] = __version__
                f.attrs["parameters"] = self.spec.to_json()
                for key, value in self.spec.to_dict().items():
                    f.attrs[key] = np.asarray(value) if isinstance(value, list) else value
                f.attrs["conventions"] = ("shearing sheet, shear -(3/2) Omega x y_hat, kx(t) = kx0 + 1.5 ky t; "
                                          "perturbations ~ exp(i k.x - i omega t); velocities in eta v_K, "
                                          "K = k eta r, Omega = 1 (thesis eqs. 4.26-4.35, sign conventions of "
                                          "dustygas.linear.shearing_wave)")
                f.attrs["energy"] = "E = (|u|^2 + c_s^2 |drho_g|^2 + sum_j mu_j |w_j|^2) / 2"
        return path

    @classmethod
    def load(cls, path: str | Path) -> "SweepResult":
        import h5py

        with h5py.File(path, "r") as f:
            spec = SweepSpec.from_json(f.attrs["parameters"])
            data = {name: f[name][()] for name in (*RESULT_FIELDS, "dust_t", "energy_t") if name in f}
            attrs = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in f.attrs.items()}
        return cls(spec, data, attrs)


def _angle(kx: np.ndarray, ky: np.ndarray) -> np.ndarray:
    """arctan(k_y/k_x) in degrees, in (−90°, 90°] (k and −k are the same wave)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.degrees(np.arctan2(ky, kx))
    a = np.where(a > 90.0, a - 180.0, a)
    return np.where(a <= -90.0, a + 180.0, a)
