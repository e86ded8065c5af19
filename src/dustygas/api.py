"""The Python entry points behind ``dustygas run``."""

from __future__ import annotations

import sys
import tomllib
from pathlib import Path
from typing import Iterable, Mapping

from ._version import __version__
from .config import load_toml, restart_config
from .errors import UserError
from .io.checkpoint import newest_checkpoint
from .io.rundir import RunDirectory, check_output_path, default_run_path
from .preflight import build_engine, check_cadence, check_memory
from .problems import get_problem, problem_names
from .runner import CHECKPOINT_ATTRS, RunResult, run_engine

__all__ = ["run", "restart", "get_problem", "problem_names"]


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
    prob = get_problem(problem)
    overrides = list(set)
    if walltime is not None:
        overrides.append(f"run.walltime={float(walltime)!r}")
    cfg = prob.config(config, overrides, data)
    check_cadence(cfg.run)
    path = check_output_path(output) if output is not None else default_run_path(problem)
    RunDirectory(path).check_new(overwrite)
    check_memory(prob, cfg)
    engine = build_engine(prob, cfg)
    return run_engine(engine, cfg, path, overwrite=overwrite, progress=progress)


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
    rundir = RunDirectory(path)
    if not str(path).strip() or not rundir.path.is_dir():
        raise UserError(f"{path}: no such run directory")
    if not rundir.config_file.is_file():
        raise UserError(f"{path}: not a run directory (no config.toml)")
    edited = load_toml(rundir.config_file)
    name = edited.get("dustygas", {}).get("problem") if isinstance(edited.get("dustygas"), Mapping) else None
    if not isinstance(name, str):
        raise UserError(f"{rundir.config_file}: no [dustygas] problem name")
    prob = get_problem(name)
    rundir.lock()  # from here on no other process writes the directory
    try:
        found = newest_checkpoint(rundir, problem=name, required=CHECKPOINT_ATTRS)
        attrs = found.attrs
        if attrs["dustygas_version"] != __version__:
            raise UserError(
                f"{found.path}: written by dustygas {attrs['dustygas_version']}, this is {__version__}; "
                "continue the run with the version that wrote it (restarts are bit-identical within one version)"
            )
        try:
            stored = tomllib.loads(str(attrs["config_toml"]))
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
        check_memory(prob, cfg)
        engine = build_engine(prob, cfg)
    except BaseException:
        rundir.unlock(discard=True)  # a refused restart leaves the directory as it was
        raise
    return run_engine(engine, cfg, rundir, progress=progress, restart_from=(found.arrays, attrs))

