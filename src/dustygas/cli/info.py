"""``dustygas info``: versions, threads and optional capabilities of this installation."""

from __future__ import annotations

import argparse
import importlib
import os
import platform
import shutil

HELP = "versions, numba threads and MPI availability"


def add_arguments(p: argparse.ArgumentParser) -> None:
    pass


def _version(name: str) -> str:
    try:
        return importlib.import_module(name).__version__
    except Exception:
        return "not installed"


def main(args: argparse.Namespace) -> int:
    import numba

    from .._version import __version__

    rows = [
        ("dustygas", __version__),
        ("python", platform.python_version()),
        ("platform", f"{platform.system()} {platform.machine()}"),
        ("cpu cores", str(os.cpu_count())),
    ]
    rows += [(m, _version(m)) for m in ("numpy", "scipy", "numba", "h5py", "matplotlib", "astropy", "tqdm")]
    rows.append(("numba threads", f"{numba.get_num_threads()} of {numba.config.NUMBA_NUM_THREADS} "
                 f"(layer: {numba.config.THREADING_LAYER})"))
    if hasattr(os, "getloadavg"):
        load = os.getloadavg()[0]
        advice = ""
        if numba.get_num_threads() > 1 and load >= 0.9:  # about one core busy elsewhere
            # numba's OpenMP threads wait for each other at the end of every parallel region: a
            # thread sharing a core with another busy process slows the whole team (CONTRIBUTING.md)
            advice = "  (other work is running: parallel runs may be faster with --threads 1)"
        rows.append(("load average", f"{load:.2f} (1 min){advice}"))
    try:
        from mpi4py import MPI

        mpi = f"mpi4py {_version('mpi4py')}, {MPI.Get_library_version().splitlines()[0].strip()}"
    except Exception:
        mpi = "not available (pip install 'dustygas[mpi]')"
    rows.append(("MPI", mpi))
    rows.append(("mpiexec", shutil.which("mpiexec") or "not found"))
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")
    return 0
