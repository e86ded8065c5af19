"""Two MPI ranks against one on a 3D 64^3 gas-only box (issue: 2 ranks >= 1.7x one rank).

Each case is a whole ``dustygas run`` (the run loop's own wall clock: start-up and compilation
excluded; one untimed run compiles first), one numba thread per rank, ranks alternating
within each repeat, best of ``--repeat`` kept:

* ``sound``   ``soundwave-3d`` at 64^3 (periodic; 2 ranks split z), 40 steps;
* ``shear``   a 3D shearing box of gas, ``epicycle`` at 64^3 with orbital advection (shear-
              periodic x: 2 ranks split z), 40 steps.

The script prints zone-cycles/s of 1 and 2 ranks, the ratio, and ``uptime`` before and after
(a 2-rank figure needs both cores quiet). Run alone::

    flock benchmarks/.lock python benchmarks/bench_mpi.py [--cases sound shear] [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GRID = ["--set", "grid.nx=64", "--set", "grid.ny=64", "--set", "grid.nz=64", "--set", "run.max_cycles=40"]
CASES = {
    "sound": ["soundwave-3d", *GRID],
    "shear": ["epicycle", *GRID, "--set", "scheme.cfl=0.3", "--set", "shearing_box.orbital_advection=true"],
}


def run_once(case: list[str], ranks: int, workdir: Path) -> float:
    """zone-cycles/s of one ``dustygas run`` on ``ranks`` ranks (the loop's throughput line)."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src"), "NUMBA_NUM_THREADS": "1"}
    out = tempfile.mkdtemp(dir=workdir)
    launch = [] if ranks == 1 else [shutil.which("mpiexec") or "mpiexec", "-n", str(ranks)]
    proc = subprocess.run([*launch, sys.executable, "-m", "dustygas", "run", *case, "-q", "--overwrite", "-o", out,
                           "--threads", "1"], env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"run failed on {ranks} rank(s): {' '.join(case)}\n{proc.stderr}")
    found = re.search(r"throughput=([0-9.e+-]+) zone-cycles/s", proc.stderr)
    if found is None:
        raise SystemExit(f"no throughput line:\n{proc.stderr}")
    return float(found.group(1))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name in args.cases:
            case = CASES[name]
            run_once(case, 1, work)  # compile
            best = {1: 0.0, 2: 0.0}
            for _ in range(args.repeat):
                for ranks in (1, 2):
                    best[ranks] = max(best[ranks], run_once(case, ranks, work))
            print(f"{name:6s} 1 rank {best[1]:.4g}  2 ranks {best[2]:.4g} zone-cycles/s  "
                  f"speed-up {best[2] / best[1]:.2f}")
    print("uptime after:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
