"""Registered problem set-ups.

A problem is a class with a ``name``, a one-line ``summary``, a parameter ``schema`` (sections
of :class:`~dustygas.config.Param`, always including ``run``) and a ``build(cfg)`` method that
returns an engine holding the initial state. Register it with :func:`register`; a *preset* is
the same problem under another name with different defaults (``si-linA`` is ``si-linear`` with
the Youdin & Johansen 2007 linA parameters)::

    @register
    class SoundWave(Problem):
        name = "soundwave"
        summary = "Linear sound wave in a periodic box; exact solution for comparison."
        schema = {"run": with_defaults(RUN_SCHEMA, tlim=1.0), "grid": ..., "problem": ...}

        def build(self, cfg):
            ...

    preset("soundwave-3d", SoundWave, "Oblique 3D sound wave.", grid={"nx": 32, "ny": 32, "nz": 32},
           scheme={"cfl": 0.3})

Every module in this package is imported the first time the registry is queried, so a new
problem only needs a new file here. ``tests/problems`` runs every registered problem and
preset for a few cycles with its own defaults (or, for one too large for a laptop, with its
:attr:`Problem.smoke_overrides`), so defaults that the engine refuses fail the default suite.
"""

from __future__ import annotations

from typing import Any, ClassVar, Mapping

from ..config import Config, Param, Schema, build_config, with_defaults
from .._registry import Discovery, unknown_name

__all__ = ["Problem", "register", "preset", "get_problem", "problem_names", "all_problems"]


class Problem:
    """Base class of a registered problem (see module docstring)."""

    name: ClassVar[str] = ""
    summary: ClassVar[str] = ""
    schema: ClassVar[Schema] = {}
    #: ``--set`` overrides that shrink a problem too large for a laptop (e.g. a 3D production run)
    #: for the test that runs every registered problem a few cycles (``tests/problems``): its
    #: defaults are still validated in full, and it runs with these overrides. Empty (the rule):
    #: the test runs the defaults themselves.
    smoke_overrides: ClassVar[tuple[str, ...]] = ()
    #: problems whose checkpoints this one may start from (``dustygas run NAME --from RUN``,
    #: :mod:`dustygas.branch`): their physics plus this problem's own, switched on later
    branches_from: ClassVar[tuple[str, ...]] = ()

    def validate(self, cfg: Config) -> None:
        """Cross-parameter checks; raise :class:`~dustygas.errors.ConfigError` on failure."""

    def check_branch(self, cfg: Config, t: float) -> None:
        """Refuse (:class:`~dustygas.errors.ConfigError`) a branch at time ``t`` from a
        :attr:`branches_from` run if this problem's own physics would already have acted by then."""
        if self.branches_from:
            raise NotImplementedError(f"{self.name} lists branches_from but does not check a branch")

    def build(self, cfg: Config) -> Any:
        """Return an engine holding the initial state for ``cfg``."""
        raise NotImplementedError

    def memory_estimate(self, cfg: Config) -> int | None:
        """Bytes the engine will need for ``cfg``, estimated before anything is allocated.

        ``dustygas run`` refuses a set-up that needs more than the machine has available (one
        line, exit 2). The default counts grid cells and particles from the ``grid`` and
        ``particles`` sections (:func:`dustygas.preflight.grid_memory_estimate`); a problem
        whose size is set otherwise overrides it, or returns None (then an address-space limit
        during ``build`` still turns an impossible allocation into a one-line error).
        """
        from ..preflight import grid_memory_estimate

        return grid_memory_estimate(cfg)

    def config(self, files=(), overrides=(), data: Mapping | None = None) -> Config:
        """Defaults < files < data < overrides, validated against :attr:`schema`."""
        cfg = build_config(self.schema, files, overrides, data, problem_name=self.name)
        self.validate(cfg)
        return cfg


_REGISTRY: dict[str, Problem] = {}


def register(cls: type[Problem]) -> type[Problem]:
    """Class decorator: register a problem under ``cls.name``."""
    if not cls.name:
        raise ValueError(f"{cls.__name__} has no name")
    if cls.name in _REGISTRY and type(_REGISTRY[cls.name]) is not cls:
        raise ValueError(f"problem {cls.name!r} registered twice")
    if "run" not in cls.schema:
        raise ValueError(f"problem {cls.name!r} has no 'run' section in its schema")
    _REGISTRY[cls.name] = cls()
    return cls


def preset(name: str, base: type[Problem], summary: str, *, smoke_overrides: tuple[str, ...] | None = None,
           **defaults: Mapping[str, Any]) -> type[Problem]:
    """Register ``base`` again as ``name`` with different defaults per section (and, for a preset
    too large for a laptop, its own :attr:`Problem.smoke_overrides`)."""
    schema = {s: dict(params) for s, params in base.schema.items()}
    for section, values in defaults.items():
        if section not in schema:
            raise ValueError(f"preset {name!r}: {base.name!r} has no section {section!r}")
        schema[section] = with_defaults(schema[section], **values)
    attrs = {"name": name, "summary": summary, "schema": schema}
    if smoke_overrides is not None:
        attrs["smoke_overrides"] = tuple(smoke_overrides)
    cls = type(base.__name__ + "_" + name.replace("-", "_"), (base,), attrs)
    return register(cls)


_discover = Discovery(__name__, __path__)


def problem_names() -> list[str]:
    """Names of all registered problems, sorted."""
    _discover()
    return sorted(_REGISTRY)


def all_problems() -> dict[str, Problem]:
    _discover()
    return dict(sorted(_REGISTRY.items()))


def get_problem(name: str) -> Problem:
    """The problem registered as ``name``; a one-line error with a suggestion otherwise."""
    _discover()
    try:
        return _REGISTRY[name]
    except KeyError:
        raise unknown_name("problem", name, _REGISTRY, "dustygas problems") from None
