"""Helpers shared by the name registries (problems, figures): discovery and lookup errors."""

from __future__ import annotations

import difflib
import importlib
import pkgutil
from typing import Iterable

from .errors import UserError

__all__ = ["import_submodules", "Discovery", "unknown_name"]


def import_submodules(package: str, path: Iterable[str]) -> None:
    """Import every public module of ``package`` (so that its decorators register names)."""
    for mod in pkgutil.iter_modules(path):
        if not mod.name.startswith("_"):
            importlib.import_module(f"{package}.{mod.name}")


class Discovery:
    """``discover()`` imports every public module of ``package`` the first time it is called (so
    that a new problem or figure only needs a new file); later calls do nothing."""

    def __init__(self, package: str, path: Iterable[str]):
        self.package, self.path, self.done = package, path, False

    def __call__(self) -> None:
        if not self.done:
            self.done = True  # before importing: a module that queries the registry must not recurse
            import_submodules(self.package, self.path)


def unknown_name(kind: str, name: str, known: Iterable[str], see: str) -> UserError:
    """The one-line error for an unregistered name, with a did-you-mean suggestion."""
    close = difflib.get_close_matches(name, list(known), n=1, cutoff=0.5)
    hint = f"; did you mean '{close[0]}'?" if close else ""
    return UserError(f"unknown {kind} '{name}'{hint} (see: {see})")
