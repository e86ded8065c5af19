"""One function per computational figure of the thesis.

Register a figure with :func:`figure`; the function receives the output directory and a
``quick`` flag (laptop-scale defaults when True, thesis-scale when False), writes the PNG and
the numbers behind it next to it (CSV or HDF5), and returns the written paths::

    @figure("fig3.5", "Radial drift velocity -v_r/v_K versus tau_s (thesis eq. 3.23)")
    def fig3_5(output: Path, quick: bool = True) -> list[Path]:
        ...

Every module of this package is imported on first use, so a new figure only needs a new file.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from .._registry import Discovery, unknown_name

__all__ = ["figure", "figure_names", "get_figure", "FigureSpec"]


@dataclass(frozen=True)
class FigureSpec:
    name: str
    summary: str
    function: Callable[..., list[Path]]
    cost: str  # rough wall time at quick scale, e.g. "1 s", "5 min"


_FIGURES: dict[str, FigureSpec] = {}


def figure(name: str, summary: str, cost: str = "seconds") -> Callable:
    """Decorator registering a figure function under ``name`` (e.g. ``"fig3.5"``)."""

    def deco(fn: Callable[..., list[Path]]) -> Callable[..., list[Path]]:
        if name in _FIGURES and _FIGURES[name].function is not fn:
            raise ValueError(f"figure {name!r} registered twice")
        _FIGURES[name] = FigureSpec(name, summary, fn, cost)
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
