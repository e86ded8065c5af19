"""Typed run parameters: TOML files plus ``--set section.key=value`` overrides.

A problem declares a :data:`Schema` -- sections of :class:`Param` definitions, each with a
default, units and a one-line description. A :class:`Config` is built by layering, in order,
the schema's defaults, zero or more TOML files and command-line overrides, and validating
every value on the way in:

* an unknown section or key is refused with a did-you-mean suggestion;
* a value of the wrong type, outside its range or not among its choices is refused with a
  message naming the key and what is allowed;
* a bound that depends on other parameters (a :class:`Limit`, e.g. the Courant number's
  ``1/ndim`` of the grid) is checked once all layers are in; the engine that enforces it
  computes it with the same function, so what ``dustygas problems`` shows is what is enforced;
* malformed TOML is refused with the parser's line and column.

All refusals raise :class:`~dustygas.errors.ConfigError`, which the CLI prints as one line
and exits with status 2 before anything touches the disk.

Examples
--------
>>> from dustygas.config import Param, build_config
>>> schema = {"grid": {"nx": Param(64, "cells in x", min=1), "cfl": Param(0.4, "Courant number", min=0, max=1, min_open=True)}}
>>> cfg = build_config(schema, overrides=["grid.nx=128"])
>>> cfg.grid.nx, cfg.grid.cfl
(128, 0.4)
"""

from __future__ import annotations

import difflib
import math
import tomllib
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, Callable, Iterable, Mapping

from .errors import ConfigError

__all__ = [
    "Param",
    "Limit",
    "Schema",
    "Config",
    "build_config",
    "check_limits",
    "parse_override",
    "with_defaults",
    "dump_toml",
    "describe_schema",
]

_SCALAR_TYPES = ("float", "int", "bool", "str")
_LIST_TYPES = ("float_list", "int_list", "str_list")


@dataclass(frozen=True)
class Limit:
    """A bound of a parameter that depends on the rest of the configuration.

    Parameters
    ----------
    text
        How the bound reads in ``dustygas problems NAME`` (e.g. ``"1/ndim (0.5 in 2D, 1/3 in 3D)"``).
    value
        The bound for a configuration whose other values are validated, or ``None`` where it
        does not apply; the engine enforcing the bound must compute it with the same function.

    Examples
    --------
    >>> from dustygas.config import Limit, Param, build_config
    >>> half_n = Limit("nx/2", lambda cfg: cfg.grid.nx / 2)
    >>> schema = {"grid": {"nx": Param(8, "cells"), "width": Param(2, "stencil half-width", min=1, max=half_n)}}
    >>> build_config(schema, overrides=["grid.width=3"]).grid.width
    3
    >>> build_config(schema, overrides=["grid.width=5"])
    Traceback (most recent call last):
    ...
    dustygas.errors.ConfigError: grid.width = 5 is out of range: allowed 1 <= value <= nx/2, here 4
    """

    text: str
    value: Callable[["Config"], float | None]

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True)
class Param:
    """Definition of one run parameter.

    Parameters
    ----------
    default
        Default value; its Python type fixes the parameter type unless ``type`` is given.
    doc
        One-line description, shown by ``dustygas problems NAME``.
    units
        Units of the value ("" for dimensionless, e.g. "H", "Omega^-1", "cm", "eta v_K").
    type
        One of ``float, int, bool, str, float_list, int_list, str_list``; inferred if omitted.
    min, max
        Inclusive bounds (exclusive with ``min_open`` / ``max_open``); apply to each list item.
        A :class:`Limit` is a bound computed from the other parameters.
    choices
        Allowed values for strings (or numbers).
    length
        Required list length, if fixed.
    """

    default: Any
    doc: str
    units: str = ""
    type: str | None = None
    min: float | Limit | None = None
    max: float | Limit | None = None
    min_open: bool = False
    max_open: bool = False
    choices: tuple | None = None
    length: int | None = None

    def __post_init__(self) -> None:
        if self.type is None:
            object.__setattr__(self, "type", _infer_type(self.default))
        if self.type not in _SCALAR_TYPES + _LIST_TYPES:
            raise TypeError(f"unknown parameter type {self.type!r}")
        if self.choices is not None:
            object.__setattr__(self, "choices", tuple(self.choices))

    def allowed(self) -> str:
        """Human-readable description of the allowed values."""
        parts = []
        if self.choices is not None:
            parts.append("one of " + ", ".join(str(c) for c in self.choices))
        lo = hi = ""
        if self.min is not None:
            lo = f"{_bound_text(self.min)} {'<' if self.min_open else '<='} "
        if self.max is not None:
            hi = f" {'<' if self.max_open else '<='} {_bound_text(self.max)}"
        if lo or hi:
            parts.append(f"{lo}value{hi}")
        if self.length is not None:
            parts.append(f"{self.length} items")
        return "; ".join(parts) if parts else _TYPE_WORDS[self.type]


def _bound_text(bound: float | Limit) -> str:
    return str(bound) if isinstance(bound, Limit) else f"{bound:g}"


#: A schema maps section name -> parameter name -> :class:`Param`.
Schema = Mapping[str, Mapping[str, Param]]

_TYPE_WORDS = {
    "float": "a number",
    "int": "an integer",
    "bool": "true or false",
    "str": "a string",
    "float_list": "a list of numbers",
    "int_list": "a list of integers",
    "str_list": "a list of strings",
}


def _infer_type(value: Any) -> str:
    if isinstance(value, bool):
        return "bool"
    if isinstance(value, int):
        return "int"
    if isinstance(value, float):
        return "float"
    if isinstance(value, str):
        return "str"
    if isinstance(value, (list, tuple)):
        if all(isinstance(v, str) for v in value) and value:
            return "str_list"
        if all(isinstance(v, int) and not isinstance(v, bool) for v in value) and value:
            return "int_list"
        return "float_list"
    raise TypeError(f"cannot infer parameter type of {value!r}")


def with_defaults(section: Mapping[str, Param], **defaults: Any) -> dict[str, Param]:
    """Copy a schema section replacing some defaults (e.g. a problem's own grid size)."""
    out = dict(section)
    for key, value in defaults.items():
        if key not in out:
            raise KeyError(f"no parameter {key!r} in section to override")
        out[key] = replace(out[key], default=value)
    return out


# --------------------------------------------------------------------------- validation


def _suggest(word: str, options: Iterable[str]) -> str:
    options = list(options)
    close = difflib.get_close_matches(word, options, n=1, cutoff=0.6)
    if close:
        return f"; did you mean '{close[0]}'?"
    return f" (allowed: {', '.join(sorted(options))})" if options else ""


def _fmt(value: Any) -> str:
    return repr(value) if isinstance(value, str) else str(value)


def _coerce_scalar(kind: str, value: Any, where: str) -> Any:
    if kind == "bool":
        if isinstance(value, bool):
            return value
    elif kind == "int":
        if isinstance(value, int) and not isinstance(value, bool):
            return value
        if isinstance(value, float) and value.is_integer():
            return int(value)
    elif kind == "float":
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            value = float(value)
            if math.isnan(value):
                raise ConfigError(f"{where} = nan: expected a number")
            return value
    elif kind == "str":
        if isinstance(value, str):
            return value
    raise ConfigError(f"{where} = {_fmt(value)}: expected {_TYPE_WORDS[kind]}")


def _check_range(p: Param, value: Any, where: str, cfg: "Config | None" = None) -> None:
    """Check the numeric bounds: the fixed ones without ``cfg``, the :class:`Limit` ones with it."""
    bad = False
    here = []
    for bound, is_min, is_open in ((p.min, True, p.min_open), (p.max, False, p.max_open)):
        if bound is None or isinstance(bound, Limit) != (cfg is not None):
            continue
        if isinstance(bound, Limit):
            bound = bound.value(cfg)
            if bound is None:
                continue
            here.append(f"{bound:g}")
        if (value < bound if is_min else value > bound) or (is_open and value == bound):
            bad = True
    if bad:
        context = f", here {' and '.join(here)}" if here else ""
        raise ConfigError(f"{where} = {_fmt(value)} is out of range: allowed {p.allowed()}{context}")


def check_limits(cfg: "Config") -> None:
    """Check every :class:`Limit` bound of ``cfg``'s schema against its values (one-line
    :class:`ConfigError` naming the key, the rule and its value here)."""
    for section, params in cfg.schema.items():
        for key, p in params.items():
            if isinstance(p.min, Limit) or isinstance(p.max, Limit):
                value = cfg.data[section][key]
                for item in value if isinstance(value, list) else [value]:
                    _check_range(p, item, f"{section}.{key}", cfg)


def validate_value(p: Param, value: Any, where: str) -> Any:
    """Return ``value`` converted to the parameter's type, or raise :class:`ConfigError`."""
    if p.type in _LIST_TYPES:
        if not isinstance(value, (list, tuple)):
            value = [value]  # a scalar is a one-item list
        item_kind = p.type.removesuffix("_list")
        out = [_coerce_scalar(item_kind, v, where) for v in value]
        if p.length is not None and len(out) != p.length:
            raise ConfigError(f"{where} has {len(out)} items: expected {p.length}")
        if not out:
            raise ConfigError(f"{where} is empty: expected {_TYPE_WORDS[p.type]}")
        items = out
    else:
        out = _coerce_scalar(p.type, value, where)
        items = [out]
    for item in items:
        if p.choices is not None and item not in p.choices:
            raise ConfigError(
                f"{where} = {_fmt(item)} is not allowed: choose one of "
                + ", ".join(str(c) for c in p.choices)
            )
        if p.type not in ("str", "str_list", "bool"):
            _check_range(p, item, where)
    return out


# --------------------------------------------------------------------------- Config


class Section(Mapping[str, Any]):
    """Read-only view of one configuration section with attribute access."""

    def __init__(self, name: str, values: dict[str, Any]):
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_values", values)

    def __getattr__(self, key: str) -> Any:
        try:
            return self._values[key]
        except KeyError:
            raise AttributeError(
                f"configuration section '{self._name}' has no key '{key}'"
            ) from None

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError("configuration is read-only")

    def __getitem__(self, key: str) -> Any:
        return self._values[key]

    def __iter__(self):
        return iter(self._values)

    def __len__(self) -> int:
        return len(self._values)

    def __repr__(self) -> str:
        return f"Section({self._name!r}, {self._values!r})"


class Config(Mapping[str, Section]):
    """Validated parameters: ``cfg.grid.nx`` or ``cfg["grid"]["nx"]``.

    Attributes
    ----------
    data
        Section name -> key -> validated value (use :meth:`to_dict` for a copy).
    schema
        The schema the values were validated against.
    problem_name
        Name of the problem the configuration belongs to (may be empty).
    """

    def __init__(self, data: dict[str, dict[str, Any]], schema: Schema, problem_name: str = ""):
        self.data = data
        self.schema = schema
        self.problem_name = problem_name

    def __repr__(self) -> str:
        return f"Config(problem_name={self.problem_name!r}, {self.data!r})"

    def __getattr__(self, name: str) -> Section:
        if name.startswith("_") or name in ("data", "schema", "problem_name"):
            raise AttributeError(name)
        try:
            return Section(name, self.data[name])
        except KeyError:
            raise AttributeError(f"configuration has no section '{name}'") from None

    def __getitem__(self, name: str) -> Section:
        return Section(name, self.data[name])

    def __iter__(self):
        return iter(self.data)

    def __len__(self) -> int:
        return len(self.data)

    def to_dict(self) -> dict[str, dict[str, Any]]:
        """Deep copy of the values as plain dictionaries."""
        return {s: dict(v) for s, v in self.data.items()}

    def updated(self, overrides: Iterable[str] = (), data: Mapping | None = None) -> "Config":
        """A new config with more TOML-like ``data`` and ``section.key=value`` overrides."""
        values = self.to_dict()
        if data:
            _merge(self.schema, values, data, "configuration")
        for text in overrides:
            section, key, value = parse_override(text)
            _merge(self.schema, values, {section: {key: value}}, "--set")
        out = Config(values, self.schema, self.problem_name)
        check_limits(out)
        return out


def _merge(schema: Schema, values: dict, data: Mapping, source: str) -> None:
    for section, table in data.items():
        if section == "dustygas":
            continue  # metadata written by the run directory (problem name, version)
        if section not in schema:
            raise ConfigError(f"{source}: unknown section '{section}'{_suggest(section, schema)}")
        if not isinstance(table, Mapping):
            raise ConfigError(f"{source}: '{section}' must be a table ([{section}]), got {_fmt(table)}")
        params = schema[section]
        for key, value in table.items():
            where = f"{section}.{key}"
            if key not in params:
                dotted = [f"{section}.{k}" for k in params]
                others = [f"{s}.{k}" for s, t in schema.items() for k in t if s != section]
                hint = _suggest(where, dotted + others)
                raise ConfigError(f"{source}: unknown key '{where}'{hint}")
            values[section][key] = validate_value(params[key], value, where)


def load_toml(path: str | Path) -> dict:
    """Read a TOML file, turning every failure into a one-line :class:`ConfigError`."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such configuration file") from None
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read ({exc.strerror})") from None
    except UnicodeDecodeError:
        raise ConfigError(f"{path}: not a UTF-8 text file") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: invalid TOML: {exc}") from None


def parse_override(text: str) -> tuple[str, str, Any]:
    """Parse ``section.key=value``; the value is read as TOML, else taken as a bare string.

    >>> parse_override("grid.nx=64")
    ('grid', 'nx', 64)
    >>> parse_override("grid.riemann=hllc")
    ('grid', 'riemann', 'hllc')
    >>> parse_override("particles.taus=[0.1, 1.0]")
    ('particles', 'taus', [0.1, 1.0])
    """
    if "=" not in text:
        raise ConfigError(f"--set {text!r}: expected section.key=value")
    name, raw = text.split("=", 1)
    name, raw = name.strip(), raw.strip()
    if name.count(".") != 1 or not all(name.split(".")):
        raise ConfigError(f"--set {text!r}: expected section.key=value (one dot in the name)")
    section, key = name.split(".")
    try:
        value = tomllib.loads(f"v = {raw}")["v"]
    except tomllib.TOMLDecodeError:
        if raw.startswith(("[", "{", '"', "'")):
            raise ConfigError(f"--set {text!r}: value is not valid TOML") from None
        value = raw
    return section, key, value


def build_config(
    schema: Schema,
    files: Iterable[str | Path] = (),
    overrides: Iterable[str] = (),
    data: Mapping | None = None,
    problem_name: str = "",
) -> Config:
    """Layer defaults < TOML files < ``data`` < ``overrides`` and validate every value."""
    values = {s: {k: p.default for k, p in params.items()} for s, params in schema.items()}
    for s, params in schema.items():  # defaults must themselves be valid
        for k, p in params.items():
            values[s][k] = validate_value(p, p.default, f"{s}.{k}")
    for path in files:
        _merge(schema, values, load_toml(path), str(path))
    if data:
        _merge(schema, values, data, "configuration")
    for text in overrides:
        section, key, value = parse_override(text)
        _merge(schema, values, {section: {key: value}}, "--set")
    cfg = Config(values, schema, problem_name)
    check_limits(cfg)
    return cfg


# --------------------------------------------------------------------------- output


def _toml_value(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, str):
        escaped = value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")
        return f'"{escaped}"'
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    raise TypeError(f"cannot write {value!r} as TOML")


def dump_toml(tables: Mapping[str, Mapping[str, Any]], top: Mapping[str, Any] | None = None) -> str:
    """Serialise ``{section: {key: value}}`` (scalars and lists) as TOML text.

    Floats are written with :func:`repr`, so reading the file back gives bit-identical values.
    """
    lines = []
    for key, value in (top or {}).items():
        lines.append(f"{key} = {_toml_value(value)}")
    for section, table in tables.items():
        if lines:
            lines.append("")
        lines.append(f"[{section}]")
        for key, value in table.items():
            lines.append(f"{key} = {_toml_value(value)}")
    return "\n".join(lines) + "\n"


def describe_schema(schema: Schema) -> str:
    """Aligned table of every parameter: key, default, units, description and allowed values."""
    rows = []
    for section, params in schema.items():
        rows.append(f"[{section}]")
        table = []
        for key, p in params.items():
            limits = p.allowed() if (p.choices is not None or p.min is not None or p.max is not None
                                     or p.length is not None) else ""
            doc = p.doc + (f"  ({limits})" if limits else "")
            table.append((key, _toml_value(p.default), p.units, doc))
        widths = [max((len(r[i]) for r in table), default=0) for i in range(3)]
        for key, default, units, doc in table:
            rows.append(f"  {key:<{widths[0]}} = {default:<{widths[1]}}  {units:<{widths[2]}}  {doc}".rstrip())
        rows.append("")
    return "\n".join(rows).rstrip() + "\n"
