"""Helpers of the MPI tests: ``mpiexec -n N`` in a subprocess with one numba thread per rank."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"


@pytest.fixture(scope="session")
def mpirun():
    """``mpirun(n, *args, cwd=...)``: run ``python *args`` on ``n`` ranks; returns the CompletedProcess."""
    mpiexec = shutil.which("mpiexec")
    if mpiexec is None:
        pytest.fail("mpiexec not found: install the dev extra (mpich and mpi4py from PyPI)")

    def run(n, *args, cwd=None, timeout=600):
        env = {**os.environ, "NUMBA_NUM_THREADS": "1", "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
        return subprocess.run([mpiexec, "-n", str(n), sys.executable, *map(str, args)], cwd=cwd, env=env,
                              capture_output=True, text=True, timeout=timeout)

    return run
