"""The default thread setting against fixed ones, on a quiet machine and with one core busy.

Each case is a whole ``dustygas run`` (the run loop with its automatic thread count,
:mod:`dustygas.threads`), timed by the loop's own wall clock (start-up and compilation
excluded: one untimed run compiles first). Cases:

* ``si-linA``   the default job to t = 0.5 (64^2 cells + 4096 particles; 12.9 s on one thread
                vs 40.6 s on two with one core busy, before the automatic setting);
* ``grid``      a 2D shearing box of gas, ``shearing-wave`` at 256^2 cells, 300 steps;
* ``sph``       a 3D SPH box, ``sph-soundwave-3d`` with 32 x 32 x 32 layers, 40 steps.

"busy" runs a pure-Python busy loop (one core) beside every timed run. For each case and
condition the script prints the wall time with ``--threads 1``, ``--threads 2`` and the
default, and the ratios default/1T (must be <= 1.10 when busy) and 1T/default (must be >= 1.8
on a quiet machine). Thread counts alternate within each repeat; the best of ``--repeat`` is
kept (the machine is shared).

Run alone::

    flock benchmarks/.lock python benchmarks/bench_threads.py [--cases si-linA grid sph] [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "si-linA": ["si-linA", "--set", "run.tlim=0.5"],
    "grid": ["shearing-wave", "--set", "grid.nx=256", "--set", "grid.ny=256", "--set", "run.max_cycles=300"],
    "sph": ["sph-soundwave-3d", "--set", "problem.layers=32", "--set", "run.max_cycles=40"],
}
SETTINGS = {"1T": ["--threads", "1"], "default": [], "2T": ["--threads", "2"]}


def run_once(case: list[str], setting: list[str], workdir: Path) -> tuple[float, str]:
    """Loop wall time of one ``dustygas run`` and the thread counts its tuner chose, in order."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = tempfile.mkdtemp(dir=workdir)
    proc = subprocess.run([sys.executable, "-m", "dustygas", "run", *case, "-q", "--overwrite", "-o", out, *setting],
                          env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"run failed: {' '.join(case + setting)}\n{proc.stderr}")
    wall = float(re.search(r"wall=([0-9.e+-]+)s", proc.stderr).group(1))
    decisions = re.findall(r"threads: (\d+) \(", (Path(out) / "log.txt").read_text())
    threads = ">".join(decisions) if decisions else re.search(r"threads=(\d+)", proc.stderr).group(1)
    return wall, threads


def load() -> str:
    return f"{os.getloadavg()[0]:.2f}" if hasattr(os, "getloadavg") else "?"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    parser.add_argument("--conditions", nargs="+", default=["busy", "quiet"], choices=["busy", "quiet"])
    parser.add_argument("--settings", nargs="+", default=list(SETTINGS), choices=list(SETTINGS),
                        help="thread settings to time (2T with a busy core can take many times 1T)")
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}  cores={os.cpu_count()}  load at start={load()}")
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name in args.cases:
            run_once(CASES[name], SETTINGS["1T"], work)  # compile (cached afterwards)
            for condition in args.conditions:
                best: dict[str, float] = {}
                chosen = set()
                loads = []
                for _ in range(args.repeat):
                    for label in args.settings:
                        setting = SETTINGS[label]
                        hog = None
                        if condition == "busy":
                            hog = subprocess.Popen([sys.executable, "-c", "while True: pass"])
                            time.sleep(0.5)
                        try:
                            loads.append(load())
                            wall, threads = run_once(CASES[name], setting, work)
                        finally:
                            if hog is not None:
                                hog.kill()
                                hog.wait()
                        best[label] = min(best.get(label, float("inf")), wall)
                        if label == "default":
                            chosen.add(threads)
                cells = [f"{label} {best[label]:7.2f} s" for label in args.settings]
                if "default" in best:
                    cells[-1] += f" (threads {' | '.join(sorted(chosen))})"
                if "default" in best and "1T" in best:
                    cells.append(f"default/1T {best['default'] / best['1T']:5.3f}  1T/default {best['1T'] / best['default']:5.3f}")
                if "2T" in best and "1T" in best:
                    cells.append(f"1T/2T {best['1T'] / best['2T']:5.3f}")
                print(f"{name:8s} {condition:5s}  " + "  ".join(cells) + f"  load {min(loads)}-{max(loads)}", flush=True)


if __name__ == "__main__":
    main()
