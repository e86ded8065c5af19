"""Two MPI ranks against one on 3D boxes (issue 13: 2 ranks >= 1.7x one rank).

Each case is a whole ``dustygas run`` (the run loop's own wall clock: start-up and compilation
excluded; one untimed run compiles first), one numba thread per rank, ranks alternating
within each repeat, best of ``--repeat`` kept:

* ``sound``   ``soundwave-3d`` at 64^3 (periodic; 2 ranks split z), 40 steps;
* ``shear``   a 3D shearing box of gas, ``epicycle`` at 64^3 with orbital advection (shear-
              periodic x: 2 ranks split z), 40 steps;
* ``part``    a 3D particle box, ``si-AB-3d`` at 32^3 (Johansen & Youdin's run AB: uniform gas
              and 32,768 randomly placed particles, one per cell, periodic z), 40 steps;
* ``part64``  the same at 64^3 (262,144 particles);
* ``layer``   the settled layer of ``si3d`` at 32 x 32 x 48 (the particles within a few cells
              of the midplane, outflow z faces), 40 steps: the z cuts balance cells + particles.

Every case writes no history or snapshot between its first and last step (``run.dt_history`` and
``run.dt_snapshot`` = 1e3: until 2026-12-03 the gas cases kept their problems' cadences, and a
history row gathers the whole box to rank 0). ``--difference SHORT LONG`` times the steps alone
(runs of SHORT and LONG steps, work and wall differenced). The script prints zone-cycles/s of 1 and 2 ranks, the ratio, the particles per rank of the
2-rank run with max/mean (from its log), and ``uptime`` before and after (a 2-rank figure
needs both cores quiet). Run alone::

    flock benchmarks/.lock python benchmarks/bench_mpi.py [--cases sound shear part layer] [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
QUIET = ["--set", "run.dt_history=1e3", "--set", "run.dt_snapshot=1e3", "--set", "run.max_cycles=40"]
GRID = ["--set", "grid.nx=64", "--set", "grid.ny=64", "--set", "grid.nz=64", *QUIET]
CASES = {
    "sound": ["soundwave-3d", *GRID],
    "shear": ["epicycle", *GRID, "--set", "scheme.cfl=0.3", "--set", "shearing_box.orbital_advection=true"],
    "part": ["si-AB-3d", *QUIET],
    "part64": ["si-AB-3d", *GRID],
    "layer": ["si3d", *QUIET],
}


def run_once(case: list[str], ranks: int, workdir: Path) -> tuple[float, str]:
    """zone-cycles/s of one ``dustygas run`` on ``ranks`` ranks (the loop's throughput line), and
    its line of particles per rank (empty for gas)."""
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
    load = re.search(r"mpi: (z rows .*)", proc.stderr)
    run_once.wall = float(re.search(r"wall=([0-9.e+-]+)s", proc.stderr).group(1))
    return float(found.group(1)), load.group(1) if load else ""


def stepping_rate(case: list[str], ranks: int, workdir: Path, short: int, long: int) -> float:
    """zone-cycles/s of the steps alone: the work and the loop wall time of a run of ``long``
    steps minus those of ``short`` steps (the first steps' thread and cache warm-up, the final
    snapshot and checkpoint, gathered to rank 0, cancel)."""
    work, wall = [], []
    for cycles in (short, long):
        rate, _ = run_once([*case, "--set", f"run.max_cycles={cycles}"], ranks, workdir)
        wall.append(run_once.wall)
        work.append(rate * run_once.wall)
    return (work[1] - work[0]) / (wall[1] - wall[0])


def cpu_per_step(case: list[str], ranks: int, workdir: Path, short: int, long: int) -> float:
    """CPU seconds per step of all the ranks together: the CPU time of a run of ``long`` steps
    minus that of ``short`` steps (start-up, compilation and outputs cancel), over the difference."""
    cpu = []
    for cycles in (short, long):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        run_once([*case, "--set", f"run.max_cycles={cycles}"], ranks, workdir)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
    return (cpu[1] - cpu[0]) / (long - short)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--cpu", action="store_true",
                        help="(a loaded machine) CPU time per step of 1 rank and of 2 ranks together instead of "
                             "wall-clock rates: 20 and 60 steps, differenced")
    parser.add_argument("--difference", nargs=2, type=int, metavar=("SHORT", "LONG"),
                        help="wall-clock rate of the steps alone: runs of SHORT and LONG steps, differenced "
                             "(start-up and the final outputs cancel)")
    args = parser.parse_args()
    if args.difference:
        short, long = args.difference
        print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
        with tempfile.TemporaryDirectory() as tmp:
            for name in args.cases:
                case = CASES[name]
                run_once(case, 1, Path(tmp))  # compile
                rates = {1: [], 2: []}
                for _ in range(args.repeat):
                    for ranks in (1, 2):
                        rates[ranks].append(stepping_rate(case, ranks, Path(tmp), short, long))
                one, two = max(rates[1]), max(rates[2])
                pairs = [b / a for a, b in zip(rates[1], rates[2])]
                print(f"{name:6s} steps {short}->{long}: 1 rank {one:.4g}  2 ranks {two:.4g} zone-cycles/s  "
                      f"speed-up {two / one:.2f} of the best rates, median of the repeats {np.median(pairs):.2f} "
                      "(per repeat: " + ", ".join(f"{x:.2f}" for x in pairs) + ")", flush=True)
        print("uptime after:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
        return
    if args.cpu:
        print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
        with tempfile.TemporaryDirectory() as tmp:
            for name in args.cases:
                case = CASES[name]
                run_once(case, 1, Path(tmp))  # compile
                one, two = (cpu_per_step(case, r, Path(tmp), 20, 60) for r in (1, 2))
                print(f"{name:6s} CPU per step: 1 rank {1e3 * one:.1f} ms, 2 ranks together {1e3 * two:.1f} ms "
                      f"(CPU efficiency {one / two:.2f}: 2 ranks on two free cores at best {2 * one / two:.2f}x)",
                      flush=True)
        print("uptime after:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
        return
    print("uptime before:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name in args.cases:
            case = CASES[name]
            run_once(case, 1, work)  # compile
            best = {1: 0.0, 2: 0.0}
            load = ""
            for _ in range(args.repeat):
                for ranks in (1, 2):
                    rate, line = run_once(case, ranks, work)
                    best[ranks] = max(best[ranks], rate)
                    load = line or load
            print(f"{name:6s} 1 rank {best[1]:.4g}  2 ranks {best[2]:.4g} zone-cycles/s  "
                  f"speed-up {best[2] / best[1]:.2f}" + (f"  [{load}]" if load else ""), flush=True)
    print("uptime after:", subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())


if __name__ == "__main__":
    main()
