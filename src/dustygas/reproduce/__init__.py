"""One function per computational figure of the thesis.

Register a figure with :func:`figure`; the function receives the output directory and a
``quick`` flag (laptop-scale defaults when True, thesis-scale when False), writes the PNG and
the numbers behind it next to it (CSV or HDF5), and returns the written paths::

    @figure("fig3.5", "Radial drift velocity -v_r/v_K versus tau_s (thesis eq. 3.23)", checks=fig3_5_checks)
    def fig3_5(output: Path, quick: bool = True) -> list[Path]:
        ...

Every module of this package is imported on first use, so a new figure only needs a new file,
and it appears in the gallery (``dustygas reproduce --all -o DIR`` writes ``DIR/index.html``,
:mod:`dustygas.reproduce.gallery`) with

* its caption: ``caption=`` if given, else the thesis's caption of figure N.M for a figure named
  exactly ``figN.M`` (:data:`~dustygas.reproduce.captions.THESIS_CAPTIONS`), else the summary;
* its checks: ``checks=`` a function ``(output: Path) -> list[Check]`` that reads what the figure
  wrote and compares numbers with published or analytic values
  (:mod:`dustygas.reproduce.checks`: :func:`~dustygas.reproduce.checks.compare`, ``within``), or
  such a function decorated with ``@register_checks(name)`` in any module of this package;
* the numbers behind it: every CSV/HDF5/JSON file the function returned.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable

from .._registry import Discovery, unknown_name
from .captions import THESIS_CAPTIONS

if TYPE_CHECKING:
    from .checks import Check

__all__ = ["figure", "register_checks", "figure_names", "get_figure", "FigureSpec"]


@dataclass(frozen=True)
class FigureSpec:
    """A registered figure: its function, one-line summary, cost, caption and checks."""

    name: str
    summary: str
    function: Callable[..., list[Path]]
    cost: str  # rough wall time at quick scale, e.g. "1 s", "5 min"
    caption: str | None = None
    checks: Callable[[Path], list["Check"]] | None = None

    @property
    def thesis_number(self) -> str | None:
        """``"3.5"`` for ``fig3.5``; None for variants (``fig4.3-settling``) and other names."""
        m = re.fullmatch(r"fig(\d+\.\d+)", self.name)
        return m.group(1) if m else None

    @property
    def all_checks(self) -> Callable[[Path], list["Check"]] | None:
        """``checks=`` of the decorator, else the function registered with :func:`register_checks`."""
        return self.checks or _CHECKS.get(self.name)

    @property
    def full_caption(self) -> str:
        """The declared caption, else the thesis's for ``figN.M``, else the summary."""
        if self.caption:
            return self.caption
        number = self.thesis_number
        return THESIS_CAPTIONS.get(number, self.summary) if number else self.summary


_FIGURES: dict[str, FigureSpec] = {}
_CHECKS: dict[str, Callable[[Path], list["Check"]]] = {}


def figure(name: str, summary: str, cost: str = "seconds", caption: str | None = None,
           checks: Callable[[Path], list["Check"]] | None = None) -> Callable:
    """Decorator registering a figure function under ``name`` (e.g. ``"fig3.5"``); ``caption``
    and ``checks`` as in the module docstring."""

    def deco(fn: Callable[..., list[Path]]) -> Callable[..., list[Path]]:
        if name in _FIGURES and _FIGURES[name].function is not fn:
            raise ValueError(f"figure {name!r} registered twice")
        _FIGURES[name] = FigureSpec(name, summary, fn, cost, caption, checks)
        return fn

    return deco


def register_checks(name: str) -> Callable:
    """Decorator registering ``fn(output) -> list[Check]`` as the checks of figure ``name``
    (for checks kept apart from the figure's module; ``figure(..., checks=fn)`` does the same)."""

    def deco(fn: Callable[[Path], list["Check"]]) -> Callable[[Path], list["Check"]]:
        _CHECKS[name] = fn
        return fn

    return deco


_discover = Discovery(__name__, __path__)


def _key(name: str) -> tuple:
    """Thesis order: fig3.5 < fig4.1 < fig4.3 < fig4.3-settling < fig4.6 (numbers first, then the name)."""
    parts = name.removeprefix("fig").replace("-", ".").split(".")
    numbers = [int(p) if p.isdigit() else 10**6 for p in parts]
    return tuple(numbers + [-1] * (8 - len(numbers))), name


def figure_names() -> list[str]:
    _discover()
    return sorted(_FIGURES, key=_key)


def get_figure(name: str) -> FigureSpec:
    _discover()
    if name not in _FIGURES:
        raise unknown_name("figure", name, _FIGURES, "dustygas reproduce --list")
    return _FIGURES[name]
