"""The public Python API: what a script imports (``import dustygas as dg``).

==========================  =========================================================================
run a problem               :func:`run`, :func:`restart`, :func:`problem_names`, :func:`get_problem`,
                            :func:`problem_parameters`
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

from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Sequence

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from .analysis.growth import GrowthFit
    from .config import Param
    from .io.readers import Run
    from .problems import Problem
    from .reproduce.gallery import FigureRecord

from .config import build_config, load_toml
from .errors import UserError
from .io.hdf5 import read_h5
from .io.rundir import RunDirectory, default_run_path
from .problems import get_problem as _get_problem
from .problems import problem_names as _problem_names
from .runner import RunResult, run_engine

__all__ = [
    "run", "restart", "get_problem", "problem_names", "problem_parameters",
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
        Run directory; default ``runs/<problem>`` (numbered if it exists).
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

    The configuration and the initial state are fully validated before the run directory is
    created, so a bad input leaves nothing on disk.
    """
    prob = _get_problem(problem)
    overrides = list(set)
    if walltime is not None:
        overrides.append(f"run.walltime={float(walltime)!r}")
    cfg = prob.config(config, overrides, data)
    path = Path(output) if output is not None else default_run_path(problem)
    RunDirectory(path).check_new(overwrite)
    engine = prob.build(cfg)
    return run_engine(engine, cfg, path, overwrite=overwrite, progress=progress)


def restart(
    path: str | Path,
    set: Iterable[str] = (),
    walltime: float | None = None,
    progress: bool | None = False,
) -> RunResult:
    """Continue the run in ``path`` from its newest checkpoint (``dustygas run --restart``).

    ``set`` may change run-control parameters (e.g. ``run.tlim``) for the continuation.
    """
    rundir = RunDirectory(path)
    if not rundir.config_file.exists():
        raise UserError(f"{path}: not a run directory (no config.toml)")
    saved = load_toml(rundir.config_file)
    name = saved.get("dustygas", {}).get("problem")
    if not isinstance(name, str):
        raise UserError(f"{rundir.config_file}: no problem name")
    prob = _get_problem(name)
    overrides = list(set)
    if walltime is not None:
        overrides.append(f"run.walltime={float(walltime)!r}")
    cfg = prob.config(overrides=overrides, data=saved)
    checkpoints = rundir.checkpoints()
    if not checkpoints:
        raise UserError(f"{path}: no checkpoint to restart from")
    state = read_h5(checkpoints[-1])
    engine = prob.build(cfg)
    return run_engine(engine, cfg, path, progress=progress, restart_from=state)


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
