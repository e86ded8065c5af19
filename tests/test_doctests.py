"""Every example in a docstring of dustygas is executed and must print what it claims.

Only modules whose source holds an example (``>>>``) are collected: a module without examples
would be a test that cannot fail. Each collected module must run at least one example.
"""

import doctest
import importlib
import importlib.util
import pkgutil
from pathlib import Path

import pytest

import dustygas


def _modules_with_examples():
    for info in pkgutil.walk_packages(dustygas.__path__, "dustygas."):
        if info.name.endswith("__main__"):
            continue
        origin = importlib.util.find_spec(info.name).origin
        if origin and ">>>" in Path(origin).read_text(encoding="utf-8"):
            yield info.name


@pytest.mark.parametrize("name", sorted(_modules_with_examples()))
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0, f"{name} has '>>>' in its source but no docstring example doctest finds"
    assert result.failed == 0, f"{result.failed} docstring example(s) failed in {name}"
