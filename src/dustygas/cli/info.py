"""``dustygas info``: versions, threads and optional capabilities of this installation."""

from __future__ import annotations

import argparse
import importlib
import os
import platform
import shutil
from pathlib import Path

HELP = "versions, numba threads, the kernel-cache stamp and MPI availability"


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
    rows += [(m, _version(m)) for m in ("numpy", "scipy", "numba", "h5py", "matplotlib", "astropy", "tqdm",
                                        "threadpoolctl")]
    from threadpoolctl import threadpool_info

    blas = [f"{pool['internal_api']} {pool['version']}, {pool['num_threads']} threads"
            for pool in threadpool_info() if pool["user_api"] == "blas"]
    rows.append(("BLAS", f"{'; '.join(blas) or 'none found'} (held at 1 thread during runs: numba's threads do the work)"))
    rows.append(("numba threads", f"{numba.get_num_threads()} of {numba.config.NUMBA_NUM_THREADS} "
                 f"(layer: {numba.config.THREADING_LAYER}); runs choose between 1 and "
                 f"{numba.get_num_threads()} from measured step times unless --threads N"))
    if hasattr(os, "getloadavg"):
        rows.append(("load average", f"{os.getloadavg()[0]:.2f} (1 min)"))
    from .._numba_cache import source_stamp

    rows.append(("kernel sources", f"{source_stamp(Path(__file__).resolve().parents[1] / '__init__.py')[:16]} "
                 "(numba cache stamp)"))
    try:
        from mpi4py import MPI

        mpi = f"mpi4py {_version('mpi4py')}, {MPI.Get_library_version().splitlines()[0].strip()}"
    except Exception:
        mpi = "not available (pip install 'dustygas[mpi]')"
    rows.append(("MPI", mpi))
    rows.append(("mpiexec", shutil.which("mpiexec") or "not found"))
    from ..parallel.comm import rank_and_size

    rank, size = rank_and_size()
    rows.append(("MPI ranks", f"{size}, {numba.get_num_threads()} numba thread(s) each" if size > 1 else
                 "1 (not launched by mpiexec; gas-only grid problems run on N ranks with mpiexec -n N)"))
    if rank != 0:  # under mpiexec: rank 0 speaks for the run
        return 0
    width = max(len(k) for k, _ in rows)
    for key, value in rows:
        print(f"{key:<{width}}  {value}")
    return 0
