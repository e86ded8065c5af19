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
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Sequence

import numpy as np

from ..errors import UserError

__all__ = ["MODE_FIELDS", "GrowthFit", "read_modes", "fit_growth", "linear_window", "measure_growth"]

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


def theory_for_run(run: str | Path) -> dict[str, float]:
    """Linear-theory growth rate and frequency of a ``si-linear``/``si-settling`` run (empty if
    the run is of another problem)."""
    from ..config import load_toml
    from ..io.rundir import RunDirectory

    cfg = load_toml(RunDirectory(run).config_file)
    p = cfg.get("problem", {})
    name = cfg.get("dustygas", {}).get("problem", "")
    if not {"taus", "mu", "Pi"} <= set(p):
        return {}
    from ..linear import StreamingParams, fastest_mode

    if "kx" in p:
        kx, kz, vz = p["kx"], p["kz"], 0.0
    elif {"k", "theta"} <= set(p):
        th = math.radians(p["theta"])
        kx, kz = p["k"] * math.sin(th), p["kz_sign"] * p["k"] * math.cos(th)
        vz = p.get("vz", 0.0)
        vz = vz if vz == "settling" else float(vz)
    else:
        return {}
    mode = fastest_mode(StreamingParams(taus=p["taus"], mu=p["mu"], kx=kx, kz=kz, Pi=p["Pi"], vz=vz))
    return {"growth_rate": mode.growth_rate, "frequency": mode.frequency, "problem": name}
