"""Growth rate and frequency of a linear mode from a run's history (thesis §4.4, Fig 4.6).

The particle engine writes, at every history row, the complex Fourier amplitudes of one wave
vector for the eight fields of the linear theory (gas ``δρ_g/ρ_g0, u_x, u_y, u_z``, dust
``δρ_p/ρ_p0, w_x, w_y, w_z``; see :mod:`dustygas.particles.diagnostics`), as the history
columns ``mode_<field>_re`` and ``mode_<field>_im``. For a mode ``∝ exp(i k·x - i ω t)``
each amplitude is ``A(t) = A_0 e^{-i ω t}``: ``ln|A|`` grows at ``s = Im ω`` and the phase
turns at ``-Re ω``. :func:`fit_growth` fits both by least squares, field by field.

Choosing the linear window (automatic; :func:`linear_window`)
-------------------------------------------------------------
* **End**: the first time a relative density amplitude (gas or dust) exceeds ``nonlinear``
  (default 0.01; the linear theory's terms of second order are then ~1 % of the first-order
  ones), else the end of the run.
* **Start**: a run starts from the continuum eigenvector, which is not exactly the discrete
  system's, so other modes are excited too and decay relative to the fastest; while they
  matter, the eight fields grow at visibly different rates. Candidate starts are
  ``t_0 + j (t_end - t_0)/20`` for ``j = 0 .. 10`` (the window keeps at least half the run);
  the start is the earliest candidate at which the growth rates of the eight fields over
  ``[start, end]`` agree within ``agree`` (default 0.5 %, relative to their mean), or the
  candidate with the smallest disagreement if none does.

The growth rate and frequency reported are the means over the fields, with each field's own
values alongside.

Modal projection (:func:`measure_modal_growth`)
-----------------------------------------------
Where two eigenvectors of the operator at the run's wave vector are nearly parallel, a
per-field fit is a poor estimator: at τ_s = 0.001 (thesis Fig 4.6, μ = 0.1, ``|K|`` = 59.7) the
growing mode and its decaying partner (ω = 0.9769 ± 0.124i) have eigenvectors at
``|cos|`` = 0.95 (condition number of the eigenbasis 3.3e3), so a 1-2 % admixture of the partner,
which any discrete initial state carries, moves the eight fields' fitted rates apart by ±7 %
while the growing mode itself grows at the theory's rate. The modal fit solves, at every
history row, ``X(t) = Σ_j c_j(t) e_j`` for the amplitudes ``c_j`` of all eigenvectors ``e_j`` of the
operator (eight fields, velocities in ηv_K: the run's ``u/Π``) and fits ``ln|c_0|`` and
``arg c_0`` of the fastest mode like :func:`fit_growth`. The rate is measured from the run's
time evolution; the theory enters only through the basis, and a run that did not follow
the growing eigenvector would show a large remainder ``|X - c_0 e_0|/|X|`` (reported as
``fields["remainder"]``). Window: the end as above; the start where the strongly damped
modes (``Im ω < -1``) have decayed below ``1e-3 |c_0|``.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import UserError

__all__ = ["MODE_FIELDS", "GrowthFit", "read_modes", "fit_growth", "linear_window", "measure_growth",
           "measure_modal_growth", "modal_amplitudes", "run_params", "theory_for_run"]

#: the fields whose mode amplitudes the particle engine records (gas, then dust)
MODE_FIELDS = ("drho_g", "ux", "uy", "uz", "drho_p", "wx", "wy", "wz")
DENSITY_FIELDS = ("drho_g", "drho_p")


@dataclass
class GrowthFit:
    """Result of :func:`measure_growth` (growth rate ``s = Im ω``, frequency ``Re ω``)."""

    growth_rate: float
    frequency: float
    window: tuple[float, float]
    fields: dict[str, dict[str, float]]
    spread: float  # (max - min)/mean of the fields' growth rates
    samples: int
    window_rule: str = ""
    theory: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict:
        return asdict(self)


def read_modes(run: str | Path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """Times and complex mode amplitudes ``{field: A(t)}`` from ``RUN/history.h5``."""
    from ..io.rundir import RunDirectory

    hist, _ = RunDirectory(run).read_history()
    missing = [f for f in MODE_FIELDS if f"mode_{f}_re" not in hist]
    if missing:
        raise UserError(f"{run}: history.h5 has no mode amplitudes ({', '.join(missing)}); "
                        "it was not written by the particle engine with a mode")
    t = np.asarray(hist["time"], dtype=np.float64)
    modes = {f: np.asarray(hist[f"mode_{f}_re"]) + 1j * np.asarray(hist[f"mode_{f}_im"]) for f in MODE_FIELDS}
    # a restart can repeat a row at the checkpoint time: keep the last of equal times
    keep = np.r_[t[1:] > t[:-1], True]
    return t[keep], {f: a[keep] for f, a in modes.items()}


def fit_growth(t: np.ndarray, amplitude: np.ndarray) -> tuple[float, float]:
    """Least-squares ``(s, Re ω)`` of ``A(t) ∝ e^{-i ω t}``: slopes of ``ln|A|`` and of ``-arg A``.

    >>> t = np.linspace(0, 2, 50)
    >>> s, f = fit_growth(t, 3e-6 * np.exp((0.4 - 0.35j) * t + 0.2j))
    >>> round(s, 12), round(f, 12)
    (0.4, 0.35)
    """
    t = np.asarray(t, dtype=np.float64)
    a = np.asarray(amplitude)
    if t.size < 3:
        raise UserError("fewer than three samples in the fit window")
    if np.any(a == 0) or not np.all(np.isfinite(a)):
        raise UserError("a mode amplitude is zero or not finite in the fit window")
    s = np.polyfit(t, np.log(np.abs(a)), 1)[0]
    phase = np.unwrap(np.angle(a))
    return float(s), float(-np.polyfit(t, phase, 1)[0])


def _rates(t: np.ndarray, modes: dict[str, np.ndarray], lo: float, hi: float) -> dict[str, tuple[float, float]]:
    sel = (t >= lo) & (t <= hi)
    return {f: fit_growth(t[sel], a[sel]) for f, a in modes.items()}


def _spread(rates: dict[str, tuple[float, float]]) -> float:
    s = np.array([v[0] for v in rates.values()])
    return float(np.ptp(s) / abs(s.mean())) if s.mean() != 0 else math.inf


def linear_window(t: np.ndarray, modes: dict[str, np.ndarray], nonlinear: float = 0.01,
                  agree: float = 0.005) -> tuple[float, float]:
    """The automatic fit window (module docstring)."""
    t0 = float(t[0])
    big = np.zeros(t.shape, dtype=bool)
    for f in DENSITY_FIELDS:
        if f in modes:
            big |= np.abs(modes[f]) > nonlinear
    end = float(t[np.argmax(big) - 1]) if big.any() and np.argmax(big) > 2 else float(t[-1])
    if big.any() and np.argmax(big) <= 2:
        raise UserError(f"the mode is non-linear from the start (relative density amplitude > {nonlinear:g})")
    best, best_start = math.inf, t0
    for j in range(11):
        start = t0 + j * (end - t0) / 20.0
        if np.count_nonzero((t >= start) & (t <= end)) < 3:
            break
        spread = _spread(_rates(t, modes, start, end))
        if spread < agree:
            return start, end
        if spread < best:
            best, best_start = spread, start
    return best_start, end


def measure_growth(run_or_data, window: Sequence[float] | None = None, fields: Sequence[str] = MODE_FIELDS,
                   nonlinear: float = 0.01, agree: float = 0.005) -> GrowthFit:
    """Growth rate and frequency of the recorded mode of a run (module docstring).

    Parameters
    ----------
    run_or_data
        A run directory, or ``(t, {field: complex amplitudes})``.
    window
        ``(t_start, t_end)``; default: :func:`linear_window`.
    fields
        The fields to fit and average.
    """
    if isinstance(run_or_data, (str, Path)):
        t, modes = read_modes(run_or_data)
    else:
        t, modes = run_or_data
    unknown = [f for f in fields if f not in modes]
    if unknown:
        raise UserError(f"unknown mode field(s) {', '.join(unknown)}: choose from {', '.join(modes)}")
    modes = {f: modes[f] for f in fields}
    if window is None:
        lo, hi = linear_window(t, modes, nonlinear, agree)
        rule = (f"auto: end where |drho| > {nonlinear:g} (or the run's end); start = earliest of 11 candidates at "
                f"which the fields' growth rates agree within {agree:g}")
    else:
        lo, hi = (float(w) for w in window)
        if not hi > lo:
            raise UserError(f"window {lo:g} {hi:g}: the end must be after the start")
        rule = "given"
    rates = _rates(t, modes, lo, hi)
    s = float(np.mean([v[0] for v in rates.values()]))
    freq = float(np.mean([v[1] for v in rates.values()]))
    per_field = {f: {"growth_rate": v[0], "frequency": v[1]} for f, v in rates.items()}
    samples = int(np.count_nonzero((t >= lo) & (t <= hi)))
    return GrowthFit(s, freq, (lo, hi), per_field, _spread(rates), samples, rule)


def run_params(run: str | Path):
    """``(StreamingParams, problem name)`` of a ``si-linear``/``si-settling`` run, or ``(None, name)``
    if the run is of another problem. The run's frame velocity (``si-settling``'s ``problem.frame``)
    is in :func:`run_frame_shift`."""
    from ..config import load_toml
    from ..io.rundir import RunDirectory

    cfg = load_toml(RunDirectory(run).config_file)
    p = cfg.get("problem", {})
    name = cfg.get("dustygas", {}).get("problem", "")
    if not {"taus", "mu", "Pi"} <= set(p):
        return None, name
    from ..linear import StreamingParams

    if "kx" in p:
        kx, kz, vz = p["kx"], p["kz"], 0.0
    elif {"k", "theta"} <= set(p):
        th = math.radians(p["theta"])
        kx, kz = p["k"] * math.sin(th), p["kz_sign"] * p["k"] * math.cos(th)
        vz = p.get("vz", 0.0)
        vz = vz if vz == "settling" else float(vz)
    else:
        return None, name
    return StreamingParams(taus=p["taus"], mu=p["mu"], kx=kx, kz=kz, Pi=p["Pi"], vz=vz), name


def theory_for_run(run: str | Path) -> dict[str, float]:
    """Linear-theory growth rate and frequency of a ``si-linear``/``si-settling`` run (empty if
    the run is of another problem)."""
    from ..linear import fastest_mode

    params, name = run_params(run)
    if params is None:
        return {}
    mode = fastest_mode(params)
    return {"growth_rate": mode.growth_rate, "frequency": mode.frequency + run_frame_shift(run, params),
            "problem": name}


def run_frame_shift(run: str | Path, params) -> float:
    """``k·W``: the Doppler shift of every mode frequency in a run whose box moves at ``-W``
    relative to the gas frame of the linear theory (``si-settling`` with ``problem.frame = "dust"``)."""
    from ..config import load_toml
    from ..io.rundir import RunDirectory

    p = load_toml(RunDirectory(run).config_file).get("problem", {})
    if p.get("frame", "gas") == "gas":
        return 0.0
    from ..problems.si_settling import frame_velocity

    wx, wz = frame_velocity(p["taus"], p["mu"], float(params.vz_array[0]), p["frame"])
    return params.kx * wx + params.kz * wz


def modal_amplitudes(modes: dict[str, np.ndarray], params) -> tuple[np.ndarray, np.ndarray]:
    """``(ω_j, c_j(t))``: the amplitudes of every eigenvector of the operator of ``params`` in the
    recorded eight-field state (module docstring; one species, compressible gas). Velocities
    of the run (units of ``c_s``) are divided by ``Π`` (the theory's ``η v_K``)."""
    from ..linear import eigenmodes

    if params.nspecies != 1 or params.incompressible:
        raise UserError("the modal fit needs one dust species and a compressible gas (Pi > 0)")
    em = eigenmodes(params)
    X = np.array([modes[f] * (1.0 if f in DENSITY_FIELDS else 1.0 / params.Pi) for f in MODE_FIELDS])
    return em.omega, np.linalg.solve(em.vectors, X)


def measure_modal_growth(run_or_data, params=None, window: Sequence[float] | None = None, nonlinear: float = 0.01,
                         settled: float = 1e-3) -> GrowthFit:
    """Growth rate and frequency of the amplitude of the fastest eigenvector of the linear
    operator in the recorded state of a ``si-linear``/``si-settling`` run (module docstring).

    ``run_or_data`` is a run directory (the operator from its configuration) or
    ``(t, {field: complex amplitudes})`` with ``params`` (a
    :class:`~dustygas.linear.StreamingParams`) given.

    ``spread`` is the relative difference of the growth rates fitted over the two halves of the
    window; ``fields`` holds those (``first_half``, ``second_half``) and the largest remainder
    ``|X - c_0 e_0|/|X|`` over the window (``remainder``, in ``growth_rate``'s slot).
    """
    from ..linear import eigenmodes

    if isinstance(run_or_data, (str, Path)):
        params, _ = run_params(run_or_data)
        if params is None:
            raise UserError(f"{run_or_data}: not a si-linear/si-settling run: no linear operator to project on")
        t, modes = read_modes(run_or_data)
    else:
        if params is None:
            raise UserError("measure_modal_growth of (t, modes) needs params (the linear problem)")
        t, modes = run_or_data
    omega, c = modal_amplitudes(modes, params)
    if window is None:
        _, hi = linear_window(t, modes, nonlinear, agree=math.inf)
        damped = omega.imag < -1.0
        fast = np.sqrt(np.sum(np.abs(c[damped]) ** 2, axis=0))
        ok = np.nonzero((fast < settled * np.abs(c[0])) & (t < hi))[0]
        lo = float(t[ok[0]]) if ok.size else float(t[0])
        rule = (f"modal: end where |drho| > {nonlinear:g} (or the run's end); start where the modes damped faster "
                f"than 1/Omega are below {settled:g} of the growing mode")
    else:
        lo, hi = (float(w) for w in window)
        if not hi > lo:
            raise UserError(f"window {lo:g} {hi:g}: the end must be after the start")
        rule = "given"
    sel = (t >= lo) & (t <= hi)
    s, f = fit_growth(t[sel], c[0, sel])
    mid = 0.5 * (lo + hi)
    halves = [fit_growth(t[sel & (t <= mid)], c[0, sel & (t <= mid)]),
              fit_growth(t[sel & (t >= mid)], c[0, sel & (t >= mid)])]
    vectors = eigenmodes(params).vectors
    X = vectors @ c
    rest = X[:, sel] - np.outer(vectors[:, 0], c[0, sel])
    remainder = np.linalg.norm(rest, axis=0) / np.linalg.norm(X[:, sel], axis=0)
    fields = {"first_half": {"growth_rate": halves[0][0], "frequency": halves[0][1]},
              "second_half": {"growth_rate": halves[1][0], "frequency": halves[1][1]},
              "remainder": {"growth_rate": float(remainder.max()), "frequency": math.nan}}
    spread = abs(halves[1][0] - halves[0][0]) / abs(s) if s != 0 else math.inf
    return GrowthFit(s, f, (lo, hi), fields, float(spread), int(np.count_nonzero(sel)), rule)
