"""Start a run of one problem from another problem's checkpoint (``dustygas run PROBLEM --from RUN``).

A *branch* continues the state of a run with more physics switched on later: ``si3d-selfgravity``
is the ``si3d`` box whose particle self-gravity switches on at ``gravity.t_on``, so until then the
two runs are the same run step for step, and a ``si3d-selfgravity`` run may start from any
``si3d`` checkpoint written before ``t_on`` instead of recomputing those orbits. This is the
branching of a saturated state that the planetesimal studies do (Johansen et al. 2007, Nature
448, 1022; Simon et al. 2016, ApJ 822, 55: self-gravity switched on in a saturated
streaming-instability run).

Rules (each refused with one line, exit 2, before anything is written):

* the problem must declare the source's problem in :attr:`Problem.branches_from`;
* every section the two problems share, except ``[run]``, is the source's: it is inherited, and a
  ``-c`` file or ``--set`` that gives it another value is refused (the state belongs to that
  physics); the source may have no section the problem lacks;
* :meth:`Problem.check_branch` confirms that the problem's own physics is still off at the
  checkpoint's time (``gravity.t_on`` not before it), so the branch is bit-identical to a run from
  ``t = 0`` with the same configuration, when the checkpoint ends a step that run also takes
  (a checkpoint written by a signal, ``--walltime``, ``max_cycles`` or the wall clock; not one at
  the source's ``tlim``, whose last step was shortened to end there);
* the checkpoint must come from this dustygas version.

The new run directory holds the source's history rows up to the checkpoint (columns the source
did not have get the value the new run reports at the branch time: e.g. ``gravity_on = 0``), a
first snapshot at the branch time and everything after it; its log names the source.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, Iterable, Mapping

from ._version import __version__
from .config import Config, build_config, load_toml, parse_override
from .errors import ConfigError, UserError

__all__ = ["branch_config", "read_branch_source"]


def read_branch_source(problem: Any, source: str | Path):
    """The newest intact checkpoint of the run directory ``source``, checked for a branch of
    ``problem``; returns ``(checkpoint, stored configuration mapping)``."""
    from .io.checkpoint import newest_checkpoint
    from .io.rundir import RunDirectory
    from .runner import CHECKPOINT_ATTRS

    rundir = RunDirectory(source)
    if not str(source).strip() or not rundir.path.is_dir():
        raise UserError(f"--from {source}: no such run directory")
    found = newest_checkpoint(rundir, required=CHECKPOINT_ATTRS)
    attrs = found.attrs
    src_problem = str(attrs["problem"])
    allowed = tuple(getattr(problem, "branches_from", ()))
    if src_problem not in allowed:
        what = f"only from {', '.join(allowed)} runs" if allowed else "from no other problem's run"
        raise UserError(f"--from {source}: a {src_problem} run; {problem.name} can start {what}")
    if attrs["dustygas_version"] != __version__:
        raise UserError(f"--from {found.path}: written by dustygas {attrs['dustygas_version']}, this is "
                        f"{__version__}; branch with the version that wrote it")
    try:
        stored = tomllib.loads(str(attrs["config"]))
    except (tomllib.TOMLDecodeError, ValueError):
        raise UserError(f"--from {found.path}: the stored configuration cannot be read") from None
    return found, stored


def branch_config(schema: Mapping, stored: Mapping, files: Iterable[str | Path] = (), overrides: Iterable[str] = (),
                  problem_name: str = "", source: str = "the source run") -> Config:
    """The configuration of a branch: the source's physics, the new problem's own sections and run control.

    Layers defaults < ``files`` < the source's shared sections < ``overrides``, then refuses any
    value of a shared section (other than ``[run]``) that a file or an override sets differently
    from the source.
    """
    files, overrides = list(files), list(overrides)
    own = ("run", "dustygas")
    extra = [s for s in stored if s not in own and s not in schema]
    if extra:
        raise ConfigError(f"{source}: its section [{extra[0]}] has no place in {problem_name}; "
                          "a branch keeps all of its source's physics")
    shared = {s: dict(stored[s]) for s in stored if s not in own and s in schema}
    reference = build_config(schema, (), (), shared, problem_name).data
    cfg = build_config(schema, files, overrides, shared, problem_name)
    rule = f"a branch keeps the physics of {source} (only run.* and {problem_name}'s own sections may be set)"
    for path in files:
        given = load_toml(path)
        for section in shared:
            table = given.get(section, {})
            if not isinstance(table, Mapping):
                continue
            values = build_config(schema, [path], (), None, problem_name).data[section]
            for key in table:
                if key in reference[section] and values[key] != reference[section][key]:
                    raise ConfigError(f"{path}: {section}.{key} = {values[key]!r} differs from {source}'s "
                                      f"{reference[section][key]!r}; {rule}")
    for text in overrides:
        section, key, _ = parse_override(text)
        if section in shared and key in reference[section] and cfg.data[section][key] != reference[section][key]:
            raise ConfigError(f"--set {text}: {source} has {section}.{key} = {reference[section][key]!r}; {rule}")
    return cfg
