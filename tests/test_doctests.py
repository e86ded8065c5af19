"""Every example in a docstring of dustygas is executed and must print what it claims."""

import doctest
import importlib
import pkgutil

import pytest

import dustygas


def _modules():
    for info in pkgutil.walk_packages(dustygas.__path__, "dustygas."):
        if ".tests" in info.name or info.name.endswith("__main__"):
            continue
        yield info.name


@pytest.mark.parametrize("name", sorted(_modules()))
def test_docstring_examples(name):
    module = importlib.import_module(name)
    result = doctest.testmod(module, optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.failed == 0, f"{result.failed} docstring example(s) failed in {name}"
