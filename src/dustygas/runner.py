"""The run loop, written once for every engine.

An *engine* (grid gas, grid gas + particles, SPH, ...) owns the simulation state and knows how
to advance it; a *problem* (see :mod:`dustygas.problems`) owns the parameters and builds an
engine holding the initial state. The loop here does everything else: time-step control,
snapshots, history, checkpoints, wall-time limits, signals, progress output, restarts, the
thread count and the final throughput line.

The engine protocol (:class:`Engine`) is deliberately small::

    engine.t, engine.cycle          simulated time and step count
    engine.timestep() -> float      largest stable dt now
    engine.advance(dt)              one step; must update t and cycle
    engine.history() -> dict        scalar diagnostics for history.h5
    engine.snapshot() -> (arrays, attrs)
    engine.checkpoint() -> (arrays, attrs)   everything needed to continue bit-identically
    engine.restore(arrays, attrs)   inverse of checkpoint() on a freshly built engine
    engine.work_units, engine.work_label     e.g. (64*64, "zone-cycles")

Optional hooks, with the default used when they are absent:

* ``engine.messages() -> list[str]``: log lines (warnings, events) produced since the last
  call, which the loop writes to ``log.txt`` and stderr after every step [none];
* ``engine.load_kernels()``: load (or compile) the compiled code of a step before the loop's
  clock starts, so that the loop's wall time and throughput are the steps' [the first step
  loads them];
* ``problem.memory_estimate(cfg) -> int | None``: bytes the engine will need, checked against
  the machine's available memory before ``build`` allocates anything
  (:mod:`dustygas.preflight`) [grid cells and particles counted from the ``grid`` and
  ``particles`` sections; None: not checked, ``build`` runs under an address-space limit].

When things are written (all files atomically; the directory is locked while a process writes):

* snapshots at the start, every ``dt_snapshot`` and at the end;
* a history row every ``dt_history`` (every step for 0); ``history.h5`` is rewritten every
  ``history_wall`` seconds of wall clock, with every checkpoint and at every stop (finished,
  wall-time limit, signal, invalid state, failed output, unexpected error);
* checkpoints every ``dt_checkpoint`` of simulated time, every ``checkpoint_wall`` seconds,
  and at every stop -- a finished run too, so that ``--restart --set run.tlim=T`` extends it.
  Each holds the configuration, the dustygas version and a checksum
  (:mod:`dustygas.io.checkpoint`).

``run.threads = 0`` (the default) lets :class:`~dustygas.threads.ThreadTuner` choose the thread
count from measured step times, between one and numba's current setting (and, on Linux, never one
that would share a core with another process's work: :class:`~dustygas.threads.OtherLoad`); the kernels give
bit-identical results for any thread count. Exit statuses are listed in :mod:`dustygas.errors`.

Restarting (:func:`dustygas.api.restart`) rebuilds the engine from the configuration stored in
the newest intact checkpoint with the problem's ``build`` and then calls ``restore``, so a run
killed at any moment continues to outputs identical to an uninterrupted run.
"""

from __future__ import annotations

import contextlib
import math
import os
import signal
import sys
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol, runtime_checkable

import numpy as np

from ._launch import STOP_SIGNALS
from ._version import __version__
from .config import Config, Param, dump_toml
from .errors import EXIT_WALLTIME, OutputError, SimulationError, UserError
from .io.rundir import RunDirectory
from .parallel.comm import agreed, is_writer, launched_under_mpi
from .threads import ThreadControl

__all__ = ["Engine", "RUN_SCHEMA", "RunLoop", "RunResult", "run_engine", "config_text", "CHECKPOINT_ATTRS"]

#: Parameters of the run loop; problems copy this section with their own defaults
#: (``with_defaults(RUN_SCHEMA, tlim=6.0)``). A restart may change any of them.
RUN_SCHEMA: dict[str, Param] = {
    "tlim": Param(1.0, "simulated time at which the run stops", "code time", min=0.0),
    "max_cycles": Param(0, "stop after this many steps of this invocation (0: no limit)", min=0),
    "dt_snapshot": Param(0.0, "simulated time between snapshots (0: first and last only)", "code time", min=0.0),
    "dt_history": Param(0.0, "simulated time between history rows (0: every step)", "code time", min=0.0),
    "dt_checkpoint": Param(0.0, "simulated time between checkpoints (0: by wall clock only)", "code time", min=0.0),
    "checkpoint_wall": Param(600.0, "wall-clock seconds between checkpoints (0: never by wall clock)", "s", min=0.0),
    "history_wall": Param(60.0, "wall-clock seconds between rewrites of history.h5 (also written with every "
                          "checkpoint and at every stop)", "s", min=0.0, min_open=True),
    "keep_checkpoints": Param(2, "number of newest checkpoints kept (>= 2 survives a damaged newest one)", min=1),
    "walltime": Param(0.0, "checkpoint and stop (exit status 75) after this many wall-clock seconds of this "
                      "invocation (0: no limit; a restart does not inherit it)", "s", min=0.0),
    "log_every": Param(100, "steps between progress lines when not on a terminal", min=1),
    "threads": Param(0, "numba threads (0: automatic, chosen from measured step times)", min=0),
}

#: Root attributes every checkpoint written by the loop holds (checked before a restart).
CHECKPOINT_ATTRS = ("engine_t", "engine_cycle", "loop_snapshot_index", "loop_next_snapshot", "loop_next_history",
                    "loop_next_checkpoint", "loop_checkpoint_index", "loop_last_snapshot_time", "config",
                    "dustygas_version")


@runtime_checkable
class Engine(Protocol):
    """What the run loop needs from an engine (see module docstring)."""

    t: float
    cycle: int
    work_units: int
    work_label: str

    def timestep(self) -> float: ...

    def advance(self, dt: float) -> None: ...

    def history(self) -> dict[str, float]: ...

    def snapshot(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]: ...

    def checkpoint(self) -> tuple[dict[str, np.ndarray], dict[str, Any]]: ...

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None: ...


@dataclass
class RunResult:
    """What a finished (or stopped) run reports."""

    path: Path
    engine: Any
    status: str  # "finished", "max_cycles", "walltime", "signal"
    cycles: int
    wall: float
    throughput: float
    work_label: str
    exit_code: int = 0
    threads: int = 1
    #: wall time of the loop's first step (in ``wall``): numba loads the step's compiled kernels
    #: from its cache when they are first called (about 0.1 s for si-linA), or compiles them,
    #: unless the engine loaded them before the clock started (its optional ``load_kernels()``)
    first_step: float = 0.0


@dataclass
class _LoopState:
    snapshot_index: int = 0
    next_snapshot: float = math.inf
    next_history: float = 0.0
    next_checkpoint: float = math.inf
    checkpoint_index: int = 0
    last_snapshot_time: float = -math.inf
    history: dict[str, list] = field(default_factory=dict)


class _StopFlag:
    """Turns SIGTERM/SIGINT into a flag the loop checks after every step (an MPI rank holds the
    signals blocked, :mod:`dustygas._launch`, and :meth:`take_held` takes them at the step's
    agreement point)."""

    def __init__(self) -> None:
        self.signum = 0
        self._old: dict[int, Any] = {}

    def __enter__(self) -> "_StopFlag":
        for sig in (signal.SIGTERM, signal.SIGINT):
            try:
                self._old[sig] = signal.signal(sig, self._handler)
            except ValueError:  # not in the main thread
                pass
        return self

    def _handler(self, signum: int, frame: Any) -> None:
        if self.signum:  # second signal: give up immediately
            raise KeyboardInterrupt
        self.signum = signum

    def take_held(self) -> int:
        """Take the stop signals held pending in this thread (an MPI rank blocks them:
        :func:`~dustygas.parallel.comm.hold_stop_signals`) as if they had arrived now; returns
        :attr:`signum`."""
        for sig in sorted(signal.sigpending() & STOP_SIGNALS):
            signal.sigtimedwait([sig], 0)
            self._handler(int(sig), None)
        return self.signum

    def __exit__(self, *exc: Any) -> None:
        for sig, handler in self._old.items():
            signal.signal(sig, handler)


def _next_time(next_t: float, interval: float, t: float) -> float:
    """The first output time after ``t`` on the grid ``next_t + k interval`` (no loop: any ``interval``)."""
    if next_t > t or interval <= 0:
        return next_t
    k = math.floor((t - next_t) / interval) + 1
    out = next_t + k * interval
    while out <= t:  # rounding: at most a step or two
        out = max(out + interval, math.nextafter(t, math.inf))
    return out


class RunLoop:
    """Drive ``engine`` from its current time to ``cfg.run.tlim`` writing into ``rundir``."""

    def __init__(self, engine: Engine, cfg: Config, rundir: RunDirectory, progress: bool | None = None):
        self.engine = engine
        self.cfg = cfg
        self.run = cfg.run
        self.rundir = rundir
        self.state = _LoopState()
        self.config_toml = config_text(cfg)  # the ``config`` attribute of every file (restarts read it)
        # progress: True -> tqdm bar; None -> the bar on a terminal, ``cycle= time= dt=`` lines
        # otherwise (the CLI); False -> no progress output (the Python API's default). Under MPI
        # only the writing rank shows it (every rank takes the same steps)
        writer = is_writer()
        self.progress = writer and (sys.stderr.isatty() if progress is None else bool(progress))
        self.progress_lines = writer and progress is None and not self.progress
        self._last_history_wall = time.perf_counter()
        # entered by run_engine around the whole run (initial outputs and restore included): a stop
        # signal that arrives before the first step stops the run after that step with a checkpoint
        self.stop = _StopFlag()

    # ----------------------------------------------------------------- outputs
    def _attrs(self) -> dict[str, Any]:
        return {
            "time": float(self.engine.t),
            "cycle": int(self.engine.cycle),
            "problem": self.cfg.problem_name,
            "dustygas_version": __version__,
            "config": self.config_toml,  # the full configuration (config.toml) in every file
        }

    def _where(self) -> str:
        return f"time={self.engine.t:.6g} cycle={self.engine.cycle}"

    def _write_snapshot(self) -> None:
        arrays, attrs = self.engine.snapshot()
        self.rundir.write_snapshot(self.state.snapshot_index, arrays, {**attrs, **self._attrs()})
        self.state.snapshot_index += 1
        self.state.last_snapshot_time = float(self.engine.t)

    def _record_history(self, diagnostics: dict[str, float]) -> None:
        row = {"time": float(self.engine.t), "cycle": float(self.engine.cycle)}
        row.update({k: float(v) for k, v in diagnostics.items()})
        hist = self.state.history
        n = len(hist.get("time", []))
        for key, value in row.items():
            hist.setdefault(key, [math.nan] * n).append(value)
        for key, col in hist.items():  # a diagnostic that disappeared keeps its column aligned
            if len(col) < n + 1:
                col.append(math.nan)

    def _write_history(self) -> None:
        cols = {k: np.asarray(v, dtype=np.float64) for k, v in self.state.history.items()}
        self.rundir.write_history(cols, self._attrs())
        self._last_history_wall = time.perf_counter()

    def write_checkpoint(self) -> Path:
        arrays, attrs = self.engine.checkpoint()
        out = {f"engine/{k}": v for k, v in arrays.items()}
        out.update({f"history/{k}": np.asarray(v, dtype=np.float64) for k, v in self.state.history.items()})
        s = self.state
        loop = {
            "loop_snapshot_index": s.snapshot_index,
            "loop_next_snapshot": s.next_snapshot,
            "loop_next_history": s.next_history,
            "loop_next_checkpoint": s.next_checkpoint,
            "loop_checkpoint_index": s.checkpoint_index + 1,
            "loop_last_snapshot_time": s.last_snapshot_time,
            "engine_t": float(self.engine.t),
            "engine_cycle": int(self.engine.cycle),
        }
        eattrs = {f"engine_attr_{k}": v for k, v in attrs.items()}
        path = self.rundir.write_checkpoint(
            s.checkpoint_index, out, {**loop, **eattrs, **self._attrs()}, keep=self.run.keep_checkpoints
        )
        self._write_history()
        s.checkpoint_index += 1
        self.rundir.log(f"checkpoint {path.name} at {self._where()}")
        return path

    def restore(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any]) -> None:
        """Restore loop and engine state from a checkpoint read with :func:`read_h5`."""
        eng = {k[len("engine/"):]: v for k, v in arrays.items() if k.startswith("engine/")}
        eattrs = {k[len("engine_attr_"):]: v for k, v in attrs.items() if k.startswith("engine_attr_")}
        self.engine.restore(eng, eattrs)
        self.engine.t = float(attrs["engine_t"])
        self.engine.cycle = int(attrs["engine_cycle"])
        s = self.state
        s.snapshot_index = int(attrs["loop_snapshot_index"])
        s.next_snapshot = float(attrs["loop_next_snapshot"])
        s.next_history = float(attrs["loop_next_history"])
        s.next_checkpoint = float(attrs["loop_next_checkpoint"])
        s.checkpoint_index = int(attrs["loop_checkpoint_index"])
        s.last_snapshot_time = float(attrs["loop_last_snapshot_time"])
        s.history = {k[len("history/"):]: list(v) for k, v in arrays.items() if k.startswith("history/")}

    def branch(self, arrays: dict[str, np.ndarray], attrs: dict[str, Any], source: str) -> None:
        """Start from another problem's checkpoint (:mod:`dustygas.branch`): its engine state and
        history rows, this run's output cadence on the grid from ``t = 0``, a snapshot now."""
        eng = {k[len("engine/"):]: v for k, v in arrays.items() if k.startswith("engine/")}
        eattrs = {k[len("engine_attr_"):]: v for k, v in attrs.items() if k.startswith("engine_attr_")}
        self.engine.restore(eng, eattrs)
        self.engine.t = float(attrs["engine_t"])
        self.engine.cycle = int(attrs["engine_cycle"])
        run, s, t0 = self.run, self.state, float(attrs["engine_t"])
        source_run = tomllib.loads(str(attrs["config"])).get("run", {})
        same_rows = run.dt_history == source_run.get("dt_history")
        s.next_history = float(attrs["loop_next_history"]) if same_rows else (
            _next_time(0.0, run.dt_history, t0) if run.dt_history > 0 else t0)
        s.next_snapshot = _next_time(0.0, run.dt_snapshot, t0) if run.dt_snapshot > 0 else math.inf
        s.next_checkpoint = _next_time(0.0, run.dt_checkpoint, t0) if run.dt_checkpoint > 0 else math.inf
        diagnostics = self._finite_diagnostics()
        s.history = {k[len("history/"):]: list(v) for k, v in arrays.items() if k.startswith("history/")}
        rows = len(s.history.get("time", []))
        for key, value in diagnostics.items():  # columns of this problem's own physics, still off
            s.history.setdefault(key, [float(value)] * rows)
        self._write_snapshot()
        self._write_history()
        self.rundir.log(f"branched from {source} at time={t0:.6g} cycle={self.engine.cycle} "
                        f"(problem {attrs['problem']})")
        self._log_messages()

    # ----------------------------------------------------------------- loop
    def start(self) -> None:
        """Outputs at the initial time of a fresh run."""
        run, s = self.run, self.state
        t0 = float(self.engine.t)
        s.next_snapshot = t0 + run.dt_snapshot if run.dt_snapshot > 0 else math.inf
        s.next_history = t0 + run.dt_history if run.dt_history > 0 else t0
        s.next_checkpoint = t0 + run.dt_checkpoint if run.dt_checkpoint > 0 else math.inf
        diagnostics = self._finite_diagnostics()
        self._write_snapshot()
        self._record_history(diagnostics)
        self._write_history()
        self._log_messages()

    def _log_messages(self, extra: list[str] = ()) -> None:
        messages = getattr(self.engine, "messages", None)
        for line in messages() if messages is not None else ():
            self.rundir.log(line)
            print(f"dustygas: {line}", file=sys.stderr, flush=True)
        for line in extra:
            self.rundir.log(line)

    def _finite_diagnostics(self) -> dict[str, float]:
        """``engine.history()``, once per history row; a non-finite value stops the run."""
        values = self.engine.history()
        bad = [k for k, v in values.items() if not np.isfinite(v)]
        if bad:
            raise SimulationError(f"non-finite diagnostics ({', '.join(bad)}) at {self._where()}")
        return values

    def loop(self) -> RunResult:
        """Advance to ``tlim``; return how the run ended."""
        run, s, eng = self.run, self.state, self.engine
        tlim = run.tlim
        start_cycle = eng.cycle
        status = "finished"
        bar = None
        if self.progress:
            from tqdm import tqdm

            bar = tqdm(total=tlim, initial=min(eng.t, tlim), unit="t", file=sys.stderr,
                       bar_format="{l_bar}{bar}| t={n:.4g}/{total:.4g} [{elapsed}<{remaining}]")
        work = 0.0
        step_wall = 0.0
        agree = getattr(eng, "agree", None)  # several ranks: combine the per-rank decisions
        stop = self.stop
        first_step = 0.0
        # the run's parameters as plain locals: every step reads them (a section's attribute
        # lookup is a Python call, and the serial time of a step is what two threads cannot halve)
        max_cycles, dt_history, dt_snapshot, dt_checkpoint = run.max_cycles, run.dt_history, run.dt_snapshot, \
            run.dt_checkpoint
        checkpoint_wall, walltime, history_wall, log_every = run.checkpoint_wall, run.walltime, run.history_wall, \
            run.log_every
        t_end = tlim * (1 - 1e-14)
        messages = getattr(eng, "messages", None)
        t = eng.t
        threads = ThreadControl(run.threads)  # numba's count and BLAS's, both put back in ``finally``
        load_kernels = getattr(eng, "load_kernels", None)
        if load_kernels is not None:  # start-up: numba's cache load (or compilation) of the step, off the clock
            load_kernels()
        start_wall = time.perf_counter()  # (after ThreadControl: its look at the loaded libraries takes ~10 ms)
        last_ckpt_wall = start_wall
        try:
            while t < t_end:
                if max_cycles and eng.cycle - start_cycle >= max_cycles:
                    status = "max_cycles"
                    break
                threads.before_step()
                t_step = time.perf_counter()
                dt = float(eng.timestep())
                if not (dt > 0 and math.isfinite(dt)):
                    raise SimulationError(f"invalid time step dt={dt!r} at {self._where()}")
                dt = min(dt, tlim - t)
                eng.advance(dt)
                t = eng.t
                work += eng.work_units
                diagnostics = None
                if dt_history <= 0 or t >= s.next_history:
                    diagnostics = self._finite_diagnostics()
                now = time.perf_counter()
                if not first_step:
                    first_step = now - t_step
                step_wall = max(step_wall * 0.9, now - t_step)
                decisions = threads.after_step(now - t_step, eng.work_units)
                if decisions or messages is not None:
                    self._log_messages(decisions)
                if diagnostics is not None:
                    self._record_history(diagnostics)
                    s.next_history = _next_time(s.next_history, dt_history, t)
                if t >= s.next_snapshot:
                    self._write_snapshot()
                    s.next_snapshot = _next_time(s.next_snapshot, dt_snapshot, t)
                if bar is not None:
                    bar.n = min(t, tlim)
                    bar.set_postfix_str(f"cycle={eng.cycle} dt={dt:.3g}", refresh=False)
                    bar.update(0)
                elif self.progress_lines and eng.cycle % log_every == 0:
                    print(f"cycle={eng.cycle} time={t:.6g} dt={dt:.6g}", file=sys.stderr, flush=True)
                wall_ckpt = checkpoint_wall > 0 and now - last_ckpt_wall >= checkpoint_wall
                out_of_time = walltime > 0 and (now - start_wall) + 2 * step_wall >= walltime
                if agree is not None:  # every rank takes the same wall-clock and signal decisions
                    stop.signum, wall_ckpt, out_of_time = agree((stop.take_held(), wall_ckpt, out_of_time))
                want_ckpt = t >= s.next_checkpoint or wall_ckpt
                if t >= s.next_checkpoint:
                    s.next_checkpoint = _next_time(s.next_checkpoint, dt_checkpoint, t)
                if want_ckpt and t < t_end:
                    self.write_checkpoint()
                    last_ckpt_wall = time.perf_counter()
                elif now - self._last_history_wall >= history_wall:
                    self._write_history()
                if stop.signum:
                    status = "signal"
                    break
                if out_of_time:
                    status = "walltime"
                    break
            if status == "finished" and s.last_snapshot_time < eng.t:
                self._write_snapshot()
            self.write_checkpoint()
        except SimulationError as exc:
            self._dump_crash(exc)
            raise
        except OutputError as exc:
            raise self._output_failed(exc) from None
        except MemoryError:
            exc = SimulationError(f"out of memory at {self._where()}")
            self._dump_crash(exc)
            raise exc from None
        except BaseException:
            with contextlib.suppress(Exception):  # keep the diagnostics of an unexpected stop
                self._write_history()
            raise
        finally:
            if bar is not None:
                bar.close()
            threads.restore()
        wall = time.perf_counter() - start_wall
        cycles = eng.cycle - start_cycle
        throughput = work / wall if wall > 0 else 0.0
        exit_code = {"signal": 128 + stop.signum, "walltime": EXIT_WALLTIME}.get(status, 0)
        return RunResult(self.rundir.path, eng, status, cycles, wall, throughput, eng.work_label, exit_code,
                         threads.chosen, first_step)

    def _output_failed(self, exc: OutputError) -> OutputError:
        """After a failed write: a checkpoint if one can still be written; the one-line error."""
        try:
            path = self.write_checkpoint()
            saved = f"checkpoint {path.name} written"
        except Exception:
            saved = "no checkpoint could be written"
        message = f"{exc} at {self._where()}; run stopped, {saved}"
        with contextlib.suppress(Exception):
            self.rundir.log(f"stopped: {message}")
        return OutputError(message)

    def _dump_crash(self, exc: SimulationError) -> None:
        message = str(exc)
        if "time=" not in message:
            exc.args = (f"{message} at {self._where()}", *exc.args[1:])
        with contextlib.suppress(Exception):
            self._write_history()
        try:
            arrays, attrs = self.engine.checkpoint()
        except Exception:  # the state may be too broken to serialise; the diagnostic still matters
            arrays, attrs = {}, {}
        arrays = {**{f"state/{k}": v for k, v in arrays.items()}, **{f"offending/{k}": v for k, v in exc.state.items()}}
        try:
            self.rundir.write_crash(
                arrays, {**{f"engine_attr_{k}": v for k, v in attrs.items()}, **self._attrs(), "error": str(exc)}
            )
            dumped = f"state dumped to {self.rundir.crash_file.name}"
        except OutputError as err:
            dumped = f"no dump: {err}"
        with contextlib.suppress(Exception):
            self.rundir.log(f"stopped: {exc} ({dumped})")


def config_text(cfg: Config) -> str:
    """The run directory's ``config.toml``: every parameter, then ``[dustygas]`` problem and version."""
    return dump_toml({**cfg.data, "dustygas": {"problem": cfg.problem_name, "version": __version__}})


def run_engine(
    engine: Engine,
    cfg: Config,
    path: str | Path | RunDirectory,
    overwrite: bool = False,
    progress: bool | None = None,
    restart_from: tuple[dict, dict] | None = None,
    branch_from: tuple[dict, dict, str] | None = None,
) -> RunResult:
    """Run ``engine`` (already holding its initial state) into the run directory ``path``.

    A fresh run creates and locks the directory (refused if another process writes it or it
    holds another run and ``overwrite`` is false). With ``restart_from=(arrays, attrs)`` of a
    checkpoint the directory must exist; it is locked (if the caller has not already) and the
    run continues from that state. With ``branch_from=(arrays, attrs, source)`` a fresh directory
    starts from another problem's checkpoint (:meth:`RunLoop.branch`). The lock is released when
    the run returns or raises.
    """
    rundir = path if isinstance(path, RunDirectory) else RunDirectory(path)
    if launched_under_mpi() and not getattr(engine, "distributed", False):
        raise UserError(f"problem {cfg.problem_name} does not run on several MPI ranks yet "
                        "(the grid and particle-grid problems do): run it with one process")
    loop = RunLoop(engine, cfg, rundir, progress)
    with loop.stop:  # from the first output on, SIGTERM/Ctrl-C stop the run with a checkpoint
        try:
            if restart_from is None:
                agreed(lambda: rundir.create(overwrite))
                rundir.write_config(config_text(cfg))
                rundir.log(f"dustygas {__version__} problem={cfg.problem_name} pid={os.getpid()}")
                _log_takeover(rundir)
                try:
                    if branch_from is None:
                        loop.start()
                    else:
                        loop.branch(*branch_from)
                except SimulationError as exc:  # e.g. an invalid initial state: dump it like any other
                    loop._dump_crash(exc)
                    raise
            else:
                rundir.lock()
                loop.restore(*restart_from)
                rundir.write_config(config_text(cfg))
                rundir.log(f"restart at time={engine.t:.6g} cycle={engine.cycle} pid={os.getpid()}")
                _log_takeover(rundir)
            result = loop.loop()
            label = result.work_label or "updates"
            rundir.log(
                f"{result.status}: time={engine.t:.6g} cycles={result.cycles} wall={result.wall:.4g}s "
                f"first_step={result.first_step:.3g}s throughput={result.throughput:.4g} {label}/s "
                f"threads={result.threads}"
            )
            return result
        finally:
            rundir.unlock()


def _log_takeover(rundir: RunDirectory) -> None:
    lock = rundir.lock()
    if lock.previous and not lock.previous.startswith(f"{os.getpid()} "):
        rundir.log(f"lock of a writer that did not finish ({lock.previous}) taken over")
    if rundir.stale_removed:
        rundir.log(f"removed {len(rundir.stale_removed)} temporary file(s) of a dead writer: "
                   + ", ".join(p.name for p in rundir.stale_removed[:5]))
