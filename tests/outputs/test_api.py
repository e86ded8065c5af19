"""The public API module has complete, resolvable type signatures (and mypy accepts it)."""

import inspect
import subprocess
import sys
import typing
from pathlib import Path

import pytest

import dustygas
from dustygas import api

ROOT = Path(__file__).resolve().parents[2]


def test_public_functions_are_fully_annotated_and_exported():
    assert set(api.__all__) <= set(dustygas.__all__)
    for name in api.__all__:
        fn = getattr(api, name)
        sig = inspect.signature(fn)
        hints = typing.get_type_hints(fn, globalns={**vars(api), **_checking_names()})
        missing = [p for p in sig.parameters if p not in hints]
        assert not missing and "return" in hints, (name, missing)
        assert fn.__doc__, name


def _checking_names():
    """The names api.py imports only for type checking."""
    from matplotlib.figure import Figure

    from dustygas.analysis.growth import GrowthFit
    from dustygas.config import Param
    from dustygas.io.readers import Run
    from dustygas.problems import Problem
    from dustygas.reproduce.gallery import FigureRecord

    return {"Figure": Figure, "GrowthFit": GrowthFit, "Param": Param, "Run": Run, "Problem": Problem,
            "FigureRecord": FigureRecord}


@pytest.mark.slow
def test_mypy_accepts_the_public_api():
    """mypy, with untyped or incompletely typed definitions disallowed, finds no error in dustygas.api."""
    proc = subprocess.run([sys.executable, "-m", "mypy", "--follow-imports=silent", "--ignore-missing-imports",
                           "--disallow-untyped-defs", "--disallow-incomplete-defs", "--no-error-summary",
                           str(ROOT / "src" / "dustygas" / "api.py")], capture_output=True, text=True, timeout=900,
                          cwd=ROOT)
    assert proc.returncode == 0, proc.stdout + proc.stderr
