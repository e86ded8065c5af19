"""Thread counts in the engine tests.

``one_numba_thread`` is the autouse fixture of the engine test areas (grid, particles, sph,
dustysph): their kernels give results independent of the thread count, and one thread keeps
the many small kernel launches of short test runs cheap on a machine whose cores other jobs
share (numba's OpenMP threads spin-wait at the end of each parallel region).

``results_at_threads`` is how each of those areas checks that independence: it runs the same
case in a fresh interpreter per thread count, with ``NUMBA_NUM_THREADS`` set to that count
whatever the environment of the test run says (so the check is 1 thread against 2 threads
even under ``NUMBA_NUM_THREADS=1``, and the test process's own thread pool is never touched).
A case is a function ``module:name`` importable from ``tests/`` that returns a dict of arrays.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numba
import numpy as np
import pytest

TESTS = Path(__file__).resolve().parent
SRC = TESTS.parent / "src"

_CHILD = """
import importlib, json, sys
import numba, numpy as np
module, name = sys.argv[1].split(":")
threads = int(sys.argv[2])
assert numba.config.NUMBA_NUM_THREADS == threads and numba.get_num_threads() == threads
out = getattr(importlib.import_module(module), name)(**json.loads(sys.argv[3]))
assert numba.get_num_threads() == threads, "the case changed the thread count"
np.savez(sys.argv[4], threads=threads, **{k: np.asarray(v) for k, v in out.items()})
"""


@pytest.fixture(autouse=True)
def one_numba_thread():
    before = numba.get_num_threads()
    numba.set_num_threads(1)
    yield
    numba.set_num_threads(before)


def results_at_threads(case: str, tmp_path: Path, threads=(1, 2), timeout: float = 600, **kwargs) -> list[dict]:
    """``case(**kwargs)`` run once per thread count, each in its own interpreter with
    ``NUMBA_NUM_THREADS`` set to that count; returns the dicts of arrays in the same order."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(TESTS), str(SRC), env.get("PYTHONPATH", "")])
    results = []
    for n in threads:
        env["NUMBA_NUM_THREADS"] = str(n)
        out = tmp_path / f"threads_{n}.npz"
        proc = subprocess.run([sys.executable, "-c", _CHILD, case, str(n), json.dumps(kwargs), str(out)],
                              env=env, cwd=tmp_path, capture_output=True, text=True, timeout=timeout)
        assert proc.returncode == 0, proc.stderr[-3000:]
        with np.load(out) as data:
            result = {k: data[k] for k in data.files}
        assert int(result.pop("threads")) == n
        results.append(result)
    return results


def assert_identical(results: list[dict]) -> None:
    """Every result holds the same arrays, bit for bit."""
    first = results[0]
    for other in results[1:]:
        assert first.keys() == other.keys()
        for key in first:
            np.testing.assert_array_equal(first[key], other[key], err_msg=key)
