"""Checks made before a run writes anything: memory, the built state, the output cadence.

``dustygas run`` (:mod:`dustygas.api`) calls, in order:

1. :func:`check_memory` -- the problem's :meth:`~dustygas.problems.Problem.memory_estimate`
   against the memory the machine has available (``MemAvailable`` + free swap), so that
   ``grid.nx = 1e9`` is one line instead of an allocation that takes the machine down;
2. :func:`build_engine` -- the problem's ``build`` under an address-space limit of the memory
   available (a set-up with no estimate that still asks for too much gets a ``MemoryError``
   at once, reported as one line), with arithmetic failures and floating-point overflows of
   absurd parameter magnitudes (``Pi = 1e-300``) reported as one line too, then
   :func:`check_initial_state`: every history diagnostic and the first time step must be finite;
3. :func:`check_cadence` -- output intervals that would ask for more outputs than any run can
   use (``dt_snapshot = 1e-12``) are refused.

All refusals are :class:`~dustygas.errors.SetupError` / :class:`~dustygas.errors.ConfigError`
(exit status 2, nothing written).
"""

from __future__ import annotations

import contextlib
import math
import os
import sys
import warnings
from pathlib import Path
from typing import Any, Iterator

from .errors import ConfigError, SetupError, SimulationError

__all__ = [
    "available_memory",
    "check_memory",
    "grid_memory_estimate",
    "build_engine",
    "check_initial_state",
    "check_cadence",
    "MAX_OUTPUTS",
    "GRID_BYTES_PER_CELL",
    "BYTES_PER_PARTICLE",
]

#: Largest number of snapshots or checkpoints (by simulated time) a run may ask for, and of
#: history rows by ``dt_history``: more cannot be meant and would loop on the time resolution.
MAX_OUTPUTS = {"dt_snapshot": 100_000, "dt_checkpoint": 100_000, "dt_history": 100_000_000}

#: Peak bytes per cell of the grid engine and per Lagrangian particle: the slopes of the peak
#: resident size of si-linA (build, two steps, history, snapshot and checkpoint arrays) between
#: 256^2 and 512^2 cells at one particle per cell (457 B per cell and particle) and between one
#: and four particles per cell at 512^2 (197 B per particle), rounded up by about 10 %.
GRID_BYTES_PER_CELL = 290
BYTES_PER_PARTICLE = 220


def available_memory() -> int | None:
    """Bytes of memory available to a new allocation (``MemAvailable`` + ``SwapFree``), or None."""
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            info = {line.split(":")[0]: int(line.split()[1]) * 1024 for line in fh if line.split()[1:]}
        return info["MemAvailable"] + info.get("SwapFree", 0)
    except (OSError, KeyError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_AVPHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (ValueError, OSError, AttributeError):
        return None


def _int(section: Any, key: str, default: int = 1) -> int:
    try:
        value = section[key]
    except (KeyError, TypeError):
        return default
    return value if isinstance(value, int) and not isinstance(value, bool) else default


def grid_memory_estimate(cfg: Any) -> int | None:
    """Bytes of a grid (+ particle) set-up from its ``grid`` and ``particles`` sections, or None.

    Cells are ``grid.nx * ny * nz``; particles ``lattice^d`` per cell along the ``d`` active
    axes when the configuration has a ``particles`` section with a ``lattice``.
    """
    data = getattr(cfg, "data", cfg)
    grid = data.get("grid") if hasattr(data, "get") else None
    if not grid or "nx" not in grid:
        return None
    shape = [_int(grid, k) for k in ("nx", "ny", "nz")]
    cells = math.prod(shape)
    total = cells * GRID_BYTES_PER_CELL
    particles = data.get("particles")
    if particles and "lattice" in particles:
        active = sum(n > 1 for n in shape) or 1
        total += cells * _int(particles, "lattice") ** active * BYTES_PER_PARTICLE
    return total


def _gb(n: float) -> str:
    return f"{n / 1e9:.3g} GB" if n < 1e15 else f"{n:.2e} bytes"


def check_memory(problem: Any, cfg: Any) -> int | None:
    """Refuse (one line) a set-up whose estimated memory exceeds what is available."""
    estimate = getattr(problem, "memory_estimate", lambda cfg: None)(cfg)
    available = available_memory()
    if estimate is not None and available is not None and estimate > available:
        raise SetupError(
            f"{getattr(problem, 'name', 'this problem')}: the set-up needs about {_gb(estimate)} of memory "
            f"and {_gb(available)} are available: reduce the resolution"
        )
    return estimate


@contextlib.contextmanager
def _address_space_limit() -> Iterator[None]:
    """Limit the address space to what it is now plus the memory available, then restore it."""
    try:
        import resource

        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        available = available_memory()
        with open("/proc/self/statm", encoding="ascii") as fh:
            used = int(fh.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
    except (ImportError, OSError, ValueError, AttributeError):
        yield
        return
    if available is None:
        yield
        return
    limit = used + available
    if hard != resource.RLIM_INFINITY:
        limit = min(limit, hard)
    if soft != resource.RLIM_INFINITY and soft < limit:
        yield
        return
    try:
        resource.setrlimit(resource.RLIMIT_AS, (limit, hard))
    except (ValueError, OSError):
        yield
        return
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def build_engine(problem: Any, cfg: Any) -> Any:
    """``problem.build(cfg)`` with memory and arithmetic failures as one-line errors, then checked."""
    name = getattr(problem, "name", "problem")
    try:
        with _address_space_limit(), warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            engine = problem.build(cfg)
    except MemoryError:
        raise SetupError(f"{name}: the set-up needs more memory than is available: reduce the resolution") from None
    except ArithmeticError as exc:  # ZeroDivisionError, OverflowError, FloatingPointError
        raise SetupError(f"{name}: the set-up failed for these parameters ({type(exc).__name__}: {exc}); "
                         "check their magnitudes") from None
    for w in caught:
        if issubclass(w.category, RuntimeWarning) and "overflow" in str(w.message):
            raise SetupError(f"{name}: the set-up overflowed for these parameters ({w.message} at "
                             f"{Path(w.filename).name}:{w.lineno}); check their magnitudes")
    check_initial_state(engine, name)
    seen = set()
    for w in caught:  # the set-up worked: its warnings are worth a line each (a failure shows one line only)
        text = f"{w.category.__name__}: {w.message} ({Path(w.filename).name}:{w.lineno})"
        if text not in seen:
            seen.add(text)
            print(f"dustygas: warning: set-up: {text}", file=sys.stderr)
    return engine


def check_initial_state(engine: Any, name: str = "problem") -> None:
    """Every history diagnostic and the first time step of a freshly built engine are finite."""
    import numpy as np

    with np.errstate(all="ignore"):
        try:
            values = engine.history()
            bad = [k for k, v in values.items() if not np.all(np.isfinite(v))]
            dt = float(engine.timestep())
        except ArithmeticError as exc:
            raise SetupError(f"{name}: the initial state cannot be evaluated ({type(exc).__name__}: {exc}); "
                             "check the parameters' magnitudes") from None
        except SimulationError as exc:
            raise SetupError(f"{name}: the initial state is invalid: {exc}; check the parameters' magnitudes") from None
    if bad:
        shown = ", ".join(f"{k}={values[k]}" for k in bad[:4])
        raise SetupError(f"{name}: the initial state is not finite ({shown}); check the parameters' magnitudes")
    if not (dt > 0 and math.isfinite(dt)):
        raise SetupError(f"{name}: the initial time step is {dt!r}; check the parameters' magnitudes")


def check_cadence(run: Any, t0: float = 0.0) -> None:
    """Refuse output intervals that would ask for more than :data:`MAX_OUTPUTS` outputs."""
    tlim = float(run["tlim"])
    span = max(tlim - t0, 0.0)
    for key, most in MAX_OUTPUTS.items():
        dt = float(run.get(key, 0.0)) if hasattr(run, "get") else float(run[key])
        if dt <= 0 or span == 0:
            continue
        count = span / dt
        if count > most or t0 + dt == t0 or tlim + dt == tlim:
            what = {"dt_snapshot": "snapshots", "dt_checkpoint": "checkpoints", "dt_history": "history rows"}[key]
            zero = {"dt_snapshot": "first and last only", "dt_checkpoint": "by wall clock only",
                    "dt_history": "every step"}[key]
            raise ConfigError(f"run.{key} = {dt!r} asks for {count:.3g} {what} before tlim = {tlim:g} "
                              f"(at most {most}): use a larger interval, or 0 for {zero}")
