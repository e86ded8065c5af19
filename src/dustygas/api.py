"""The Python entry points behind ``dustygas run``."""

from __future__ import annotations

from pathlib import Path
from typing import Iterable, Mapping

from .config import build_config, load_toml
from .errors import UserError
from .io.hdf5 import read_h5
from .io.rundir import RunDirectory, default_run_path
from .problems import get_problem, problem_names
from .runner import RunResult, run_engine

__all__ = ["run", "restart", "dry_run", "get_problem", "problem_names"]


def run(
    problem: str,
    output: str | Path | None = None,
    config: Iterable[str | Path] = (),
    set: Iterable[str] = (),
    data: Mapping | None = None,
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
    prob = get_problem(problem)
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
    prob = get_problem(name)
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


#: zone-cycles and particle-updates per second and core assumed by :func:`dry_run`'s cost (the
#: si3d laptop run on the project machine, one thread; benchmarks/RESULTS.md)
DRY_RUN_RATES = {"zone_cycles": 1.5e6}


def dry_run(problem: str, config: Iterable[str | Path] = (), set: Iterable[str] = (),
            data: Mapping | None = None) -> list[str]:
    """Validate a configuration and describe what the run would need, without building it.

    Returns lines: the problem, cells and particles, memory, steps and the cost in core-hours
    at :data:`DRY_RUN_RATES` (problems without an ``estimate`` report only that they validate).
    """
    prob = get_problem(problem)
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
