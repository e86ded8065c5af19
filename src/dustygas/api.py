"""The public Python API: what a script imports (``import dustygas as dg``).

==========================  =========================================================================
run a problem               :func:`run`, :func:`restart`, :func:`branch`, :func:`dry_run`, :func:`problem_names`,
                            :func:`get_problem`, :func:`problem_parameters`
read a run                  :func:`open_run` (xarray Datasets: ``.history``, ``.snapshot(i)``)
export for other tools      :func:`export` (Athena++ athdf + XDMF, yt particles, Phantom, CSV)
look at a run               :func:`plot_history`, :func:`plot_snapshot`, :func:`movie`
analyses                    :func:`measure_growth`, :func:`growth_theory`; the linear theory in
                            :mod:`dustygas.linear`; the formulas in :mod:`dustygas.physics`
thesis figures              :func:`figure_names`, :func:`reproduce_figures` (PNG, data, checks, index.html)
==========================  =========================================================================

Every function here has a complete type signature (checked by mypy in the test suite), and the
heavier modules (xarray, matplotlib, the engines) are imported only when a function needs them.

Examples
--------
>>> import dustygas as dg
>>> "si-linA" in dg.problem_names()
True
>>> dg.problem_parameters("si-linA")["run"]["tlim"].default
6.0
"""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Sequence

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from .analysis.growth import GrowthFit
    from .config import Param
    from .io.readers import Run
    from .problems import Problem
    from .reproduce.gallery import FigureRecord

from ._version import __version__
from .config import load_toml, restart_config
from .errors import UserError
from .io.checkpoint import newest_checkpoint
from .io.rundir import RunDirectory, check_output_path, default_run_path
from .parallel.comm import agreed, check_ranks
from .parallel.rundir import run_directory
from .preflight import build_engine, check_cadence, check_memory
from .problems import get_problem as _get_problem
from .problems import problem_names as _problem_names
from .runner import CHECKPOINT_ATTRS, RunResult, run_engine

__all__ = [
    "run", "restart", "branch", "dry_run", "get_problem", "problem_names", "problem_parameters",
    "open_run", "export", "plot_history", "plot_snapshot", "movie",
    "measure_growth", "growth_theory", "figure_names", "reproduce_figures",
]


def problem_names() -> list[str]:
    """Names of every registered problem (``dustygas problems``)."""
    return _problem_names()


def get_problem(name: str) -> "Problem":
    """The registered problem ``name`` (one-line error with a suggestion if unknown)."""
    return _get_problem(name)


def problem_parameters(name: str) -> dict[str, dict[str, "Param"]]:
    """The parameter schema of problem ``name``: section -> key -> :class:`~dustygas.config.Param`
    (default, units, description, allowed values)."""
    return {section: dict(params) for section, params in _get_problem(name).schema.items()}


def run(
    problem: str,
    output: str | Path | None = None,
    config: Iterable[str | Path] = (),
    set: Iterable[str] = (),
    data: Mapping[str, Any] | None = None,
    overwrite: bool = False,
    walltime: float | None = None,
    progress: bool | None = False,
) -> RunResult:
    """Run a registered problem.

    Parameters
    ----------
    problem
        Registered name (``dustygas problems`` lists them).
    output
        Run directory; default ``runs/<problem>``. A directory that holds another run is
        refused unless ``overwrite``; one that another process is writing is always refused.
    config
        TOML files layered over the problem's defaults.
    set
        ``section.key=value`` overrides layered last.
    data
        Nested mapping of overrides (Python alternative to ``set``).
    walltime
        Overrides ``run.walltime`` (seconds).
    progress
        ``False`` (default): no progress output; ``True``: a tqdm bar on stderr; ``None``: the
        bar on a terminal and ``cycle= time= dt=`` lines otherwise (what the CLI does).

    The configuration, the output path, the memory the set-up needs and the initial state are
    all validated before the run directory is created, so a bad input leaves nothing on disk.
    """
    prob = _get_problem(problem)
    overrides = list(set)
    if walltime is not None:
        overrides.append(f"run.walltime={float(walltime)!r}")
    cfg = prob.config(config, overrides, data)
    check_cadence(cfg.run)
    path = check_output_path(output) if output is not None else default_run_path(problem)
    rundir = run_directory(path)  # under MPI: rank 0 writes, the other ranks only read

    def prepare() -> Any:
        check_ranks(prob)
        rundir.check_new(overwrite)
        check_memory(prob, cfg)
        return build_engine(prob, cfg)

    engine = agreed(prepare)
    return run_engine(engine, cfg, rundir, overwrite=overwrite, progress=progress)


def restart(
    path: str | Path,
    set: Iterable[str] = (),
    walltime: float | None = None,
    progress: bool | None = False,
) -> RunResult:
    """Continue the run in ``path`` from its newest intact checkpoint (``dustygas run --restart``).

    ``set`` (and an edited ``config.toml``) may change run-control parameters (``run.*``, e.g. a
    later ``run.tlim``); any other change is refused with one line naming the key, as is a
    checkpoint written by another dustygas version. A damaged newest checkpoint (checksum,
    truncation) is skipped with a warning for the one before it. ``run.walltime`` is not
    inherited: give ``walltime`` (``--walltime``) again for each continuation.
    """
    rundir = run_directory(path)
    if not str(path).strip() or not rundir.path.is_dir():
        raise UserError(f"{path}: no such run directory")
    if not rundir.config_file.is_file():
        raise UserError(f"{path}: not a run directory (no config.toml)")
    edited = load_toml(rundir.config_file)
    name = edited.get("dustygas", {}).get("problem") if isinstance(edited.get("dustygas"), Mapping) else None
    if not isinstance(name, str):
        raise UserError(f"{rundir.config_file}: no [dustygas] problem name")
    prob = _get_problem(name)
    agreed(rundir.lock)  # from here on no other process writes the directory
    try:
        found = newest_checkpoint(rundir, problem=name, required=CHECKPOINT_ATTRS)
        attrs = found.attrs
        if attrs["dustygas_version"] != __version__:
            raise UserError(
                f"{found.path}: written by dustygas {attrs['dustygas_version']}, this is {__version__}; "
                "continue the run with the version that wrote it (restarts are bit-identical within one version)"
            )
        try:
            stored = tomllib.loads(str(attrs["config"]))
        except (tomllib.TOMLDecodeError, ValueError):
            raise UserError(f"{found.path}: the stored configuration cannot be read") from None
        overrides = list(set)
        if walltime is not None:
            overrides.append(f"run.walltime={float(walltime)!r}")
        cfg = restart_config(prob.schema, stored, edited, overrides, problem_name=name,
                             source=str(rundir.config_file))
        prob.validate(cfg)
        check_cadence(cfg.run, float(attrs["engine_t"]))
        for line in found.skipped:
            message = (f"warning: skipping checkpoint {line}; restarting from {found.path.name} "
                       f"(time={float(attrs['engine_t']):.6g})")
            print(f"dustygas: {message}", file=sys.stderr, flush=True)
            rundir.log(message)
        check_ranks(prob)
        check_memory(prob, cfg)
        engine = build_engine(prob, cfg)
    except BaseException:
        rundir.unlock(discard=True)  # a refused restart leaves the directory as it was
        raise
    return run_engine(engine, cfg, rundir, progress=progress, restart_from=(found.arrays, attrs))


def branch(
    problem: str,
    source: str | Path,
    output: str | Path | None = None,
    config: Iterable[str | Path] = (),
    set: Iterable[str] = (),
    overwrite: bool = False,
    walltime: float | None = None,
    progress: bool | None = False,
) -> RunResult:
    """Run ``problem`` from the newest checkpoint of another problem's run ``source``
    (``dustygas run PROBLEM --from RUN``; rules in :mod:`dustygas.branch`), e.g.
    ``branch("si3d-selfgravity", "runs/si3d")`` switches self-gravity on in a saturated ``si3d``
    box. ``output``, ``config``, ``set``, ``overwrite``, ``walltime`` and ``progress`` as in
    :func:`run`; everything is checked before the new run directory is created.
    """
    from .branch import branch_config, read_branch_source

    prob = _get_problem(problem)
    found, stored = read_branch_source(prob, source)
    overrides = list(set)
    if walltime is not None:
        overrides.append(f"run.walltime={float(walltime)!r}")
    cfg = branch_config(prob.schema, stored, config, overrides, problem_name=problem, source=str(source))
    prob.validate(cfg)
    t0 = float(found.attrs["engine_t"])
    prob.check_branch(cfg, t0)
    check_cadence(cfg.run, t0)
    path = check_output_path(output) if output is not None else default_run_path(problem)
    RunDirectory(path).check_new(overwrite)
    check_memory(prob, cfg)
    engine = build_engine(prob, cfg)
    return run_engine(engine, cfg, path, overwrite=overwrite, progress=progress,
                      branch_from=(found.arrays, found.attrs, str(source)))


#: zone-cycles and particle-updates per second and core assumed by :func:`dry_run`'s cost (the
#: si3d laptop run on the project machine, one thread; benchmarks/RESULTS.md)
DRY_RUN_RATES: dict[str, float] = {"zone_cycles": 1.5e6}


def dry_run(problem: str, config: Iterable[str | Path] = (), set: Iterable[str] = (),
            data: Mapping[str, Any] | None = None) -> list[str]:
    """Validate a configuration and describe what the run would need, without building it.

    Returns lines: the problem, cells and particles, memory, steps and the cost in core-hours
    at :data:`DRY_RUN_RATES` (problems without an ``estimate`` report only that they validate).
    """
    prob = _get_problem(problem)
    cfg = prob.config(config, list(set), data)
    lines = [f"{problem}: configuration valid"]
    estimate = getattr(prob, "estimate", None)
    if estimate is None:
        return lines + ["no resource estimate for this problem"]
    r = estimate(cfg)
    hours = r["zone_cycles"] / DRY_RUN_RATES["zone_cycles"] / 3600.0
    lines += [f"cells {r['cells']:,}  particles {r['particles']:,}",
              f"memory {r['memory_bytes'] / 2**30:.2f} GiB",
              f"steps ~{r['steps']:,} to t = {cfg.run.tlim:g}: {r['zone_cycles']:.3g} zone-cycles, "
              f"{r['particle_updates']:.3g} particle-updates",
              f"cost ~{hours:,.0f} core-hours at {DRY_RUN_RATES['zone_cycles']:.2g} zone-cycles/s per core "
              f"(~{hours / 24 / 64:,.1f} days on 64 cores)"]
    return lines
# ------------------------------------------------------------------------------------ reading


def open_run(path: str | Path) -> "Run":
    """Open a run directory: ``.history`` (Dataset over ``time``), ``.snapshot(i)`` (Dataset with
    ``x, y, z`` coordinates; SPH: particles), ``.config``, ``.snapshot_times``."""
    from .io.readers import open_run as _open_run

    return _open_run(path)


def export(run: str | Path, format: str = "auto", output: str | Path | None = None,
           snapshots: Iterable[int] | None = None) -> list[Path]:
    """Write the snapshots of ``run`` for yt, ParaView/VisIt, sarracen/splash or pandas
    (``format``: auto, athdf, ytdata, phantom, csv; see :mod:`dustygas.io.export`)."""
    from .io.export import export_run

    return export_run(run, format, output, snapshots)


# ------------------------------------------------------------------------------------ figures


def _save(fig: "Figure", output: str | Path | None) -> None:
    if output is not None:
        from .io.atomic import atomic_path

        with atomic_path(output) as tmp:
            with open(tmp, "wb") as fh:
                fig.savefig(fh, format=Path(output).suffix.lstrip(".") or "png")


def plot_history(run: str | Path, columns: Sequence[str] | None = None,
                 output: str | Path | None = None) -> "Figure":
    """The history curves of ``run`` (all columns, or ``columns``), saved to ``output`` if given."""
    from .plot.run import history_figure

    fig = history_figure(run, columns)
    _save(fig, output)
    return fig


def plot_snapshot(run: str | Path, index: int = -1, field: str = "rho", kind: str = "slice",
                  axis: str | None = None, at: float | None = None, log: bool = False,
                  output: str | Path | None = None) -> "Figure":
    """Snapshot ``index`` of ``run``: a slice or projection of a grid field, a kernel-rendered SPH
    field, or a line for 1D runs (:mod:`dustygas.plot.maps`); saved to ``output`` if given."""
    from .plot.run import plot_snapshot as _plot

    fig = _plot(run, index, field, kind, axis, at, log)
    _save(fig, output)
    return fig


def movie(run: str | Path, output: str | Path, field: str = "rho", kind: str = "slice",
          axis: str | None = None, at: float | None = None, log: bool = False, fps: int = 5) -> Path:
    """Animate ``field`` over every snapshot of ``run`` into ``output`` (``.mp4`` or ``.gif``)."""
    from .plot.run import write_movie

    return write_movie(run, output, field, kind, axis, at, log, fps)


# ------------------------------------------------------------------------------------ analyses


def measure_growth(run: str | Path, window: Sequence[float] | None = None,
                   fields: Sequence[str] | None = None) -> "GrowthFit":
    """Growth rate and frequency of the linear mode recorded by a particle-gas run
    (``dustygas analyze growth``; :mod:`dustygas.analysis.growth`)."""
    from .analysis.growth import MODE_FIELDS
    from .analysis.growth import measure_growth as _measure

    return _measure(run, window=window, fields=MODE_FIELDS if fields is None else fields)


def growth_theory(run: str | Path) -> dict[str, float]:
    """Linear-theory growth rate and frequency of a ``si-linear``/``si-settling`` run (empty otherwise)."""
    from .analysis.growth import theory_for_run

    return theory_for_run(run)


def figure_names() -> list[str]:
    """The registered thesis figures, in thesis order (``dustygas reproduce --list``)."""
    from .reproduce import figure_names as _names

    return _names()


def reproduce_figures(figures: Iterable[str] | None = None, output: str | Path = "figures",
              quick: bool = True) -> list["FigureRecord"]:
    """Make ``figures`` (default: all) into ``output`` with their checks and ``output/index.html``."""
    from .reproduce.gallery import make_figures

    names = figure_names() if figures is None else list(figures)
    Path(output).mkdir(parents=True, exist_ok=True)
    return make_figures(names, output, quick)
