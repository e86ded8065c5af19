"""The default thread setting against fixed ones, on a quiet machine and with one core busy.

Each case is a whole ``dustygas run`` (the run loop with its automatic thread count,
:mod:`dustygas.threads`), timed by the loop's own wall clock (start-up and compilation
excluded: one short untimed run compiles first). Cases:

* ``si-linA``   the default job to t = 0.5 (64^2 cells + 4096 particles; 12.9 s on one thread
                vs 40.6 s on two with one core busy, before the automatic setting);
* ``grid``      a 2D shearing box of gas, ``shearing-wave`` at 256^2 cells, 1500 steps (about 5 s
                on one thread; until 2026-12-05 300 steps, 1.0 s, of which about 0.08 s are the
                run's fixed cost -- the snapshot, checkpoint and history written at its end, the
                same on any thread count -- which held the two-thread ratio of a run at 1.73
                where its steps gained 1.91-1.95);
* ``si-linA-128`` (only if asked for) the default job at 128^2 cells and 16384 particles, to t = 0.1
                (3062 steps, about 14 s on one thread): four times the work of a step and the same
                fixed cost per step (numba's dispatch ~35 µs, the Python between the kernels), so
                its two-thread ratio shows how much of the 64^2 job's shortfall is the box's size;
* ``sph``       a 3D SPH box, ``sph-soundwave-3d`` with 32 x 32 x 32 layers, 200 steps (about a
                minute on one thread; ``run.tlim`` raised so that the steps, not t = 1, end the run:
                the 40 steps used until 2026-12-03, 6-12 s, gave two-thread ratios of 1.29 and
                1.65 a minute apart; the work per step is the same).

"busy" runs a pure-Python busy loop (one core) beside every timed run. For each case and
condition the script prints the wall time with ``--threads 1``, ``--threads 2`` and the
default, as the median and the range over ``--repeat`` repeats (the thread settings alternate
within each repeat, so a repeat's runs see the same machine, in the reverse order every other
repeat since 2026-12-07, so that a host that slows down or speeds up over a repeat's minutes
favours neither), and the ratios default/1T (must
be <= 1.10 when busy) and 1T/default, 1T/2T (must be >= 1.8 on a quiet machine): the ratio of
the medians, the range of the per-repeat ratios and the ratio of the best times. 1T/2T is
given twice: over the loop's wall time and over it less the run's first step (``first_step=``
of the summary line), in which a new process loads the step's compiled kernels from numba's
cache -- about 0.1 s on any thread count, start-up like the import that no figure here
includes (until 2026-12-05 it was in every wall time). Since 2026-12-07 the engines of si-linA
and the grid box load their step before the loop's clock starts (``load_kernels()``,
:mod:`dustygas.runner`), so their first step is a step (2-5 ms) and the two figures nearly
agree; the SPH box still loads its kernels in its first step (about 0.04 s). Before each
repeat ``benchmarks/_cores.py`` probes whether the two CPUs are two cores or one core's two
hardware threads (the virtual machine moves between the two; printed per repeat as ``2`` or
``s``), and 1T/2T is also given over the two-core repeats alone when the repeats differ, and
per repeat in the order run, each with its ``2`` or ``s`` (since 2026-12-06: single repeats of
si-linA moved by about 0.1 minutes apart, and the two-core repeats were not the better ones, so a
set's median says more than any repeat). Since 2026-12-07 each repeat also prints the two-thread
gain of ``_cores.py``'s 3 MB streaming loop just before it (1.94-1.96 when the host leaves the two
vCPUs alone; it fell to 0.84-2.1 within a minute that night). Busy sets also print default/1T per repeat,
each with the thread counts the default's tuner decided in that run (``1>1``: two decisions).

Run alone::

    flock benchmarks/.lock python benchmarks/bench_threads.py [--cases si-linA grid sph] [--repeat 3]
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _cores import SHARED_BELOW, stream_gain, vector_gain

ROOT = Path(__file__).resolve().parents[1]
CASES = {
    "si-linA": ["si-linA", "--set", "run.tlim=0.5"],
    "grid": ["shearing-wave", "--set", "grid.nx=256", "--set", "grid.ny=256", "--set", "run.max_cycles=1500"],
    "sph": ["sph-soundwave-3d", "--set", "problem.layers=32", "--set", "run.max_cycles=200", "--set", "run.tlim=10"],
    "si-linA-128": ["si-linA", "--set", "grid.nx=128", "--set", "grid.nz=128", "--set", "run.tlim=0.1"],
}
#: the cases run when ``--cases`` is not given (``si-linA-128`` is on request)
DEFAULT_CASES = ["si-linA", "grid", "sph"]
#: the untimed run that compiles (or loads) the kernels first: the same case, three steps
WARMUP = ["--set", "run.max_cycles=3"]
SETTINGS = {"1T": ["--threads", "1"], "default": [], "2T": ["--threads", "2"]}


def run_once(case: list[str], setting: list[str], workdir: Path) -> tuple[float, float, str]:
    """Loop wall time of one ``dustygas run``, the wall time of its first step and the thread
    counts its tuner chose, in order."""
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    out = tempfile.mkdtemp(dir=workdir)
    proc = subprocess.run([sys.executable, "-m", "dustygas", "run", *case, "-q", "--overwrite", "-o", out, *setting],
                          env=env, capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit(f"run failed: {' '.join(case + setting)}\n{proc.stderr}")
    wall = float(re.search(r"wall=([0-9.e+-]+)s", proc.stderr).group(1))
    first = float(re.search(r"first_step=([0-9.e+-]+)s", proc.stderr).group(1))
    decisions = re.findall(r"threads: (\d+) \(", (Path(out) / "log.txt").read_text())
    threads = ">".join(decisions) if decisions else re.search(r"threads=(\d+)", proc.stderr).group(1)
    return wall, first, threads


def load() -> str:
    return f"{os.getloadavg()[0]:.2f}" if hasattr(os, "getloadavg") else "?"


def spread(values: list[float], fmt: str) -> str:
    """``median [min-max]`` of ``values``."""
    v = sorted(values)
    return f"{format(statistics.median(v), fmt)} [{format(v[0], fmt)}-{format(v[-1], fmt)}]"


def ratio(label: str, num: list[float], den: list[float]) -> str:
    """The ratio of the medians, the range of the per-repeat ratios and the ratio of the best times."""
    per_repeat = sorted(a / b for a, b in zip(num, den))
    return (f"{label} {statistics.median(num) / statistics.median(den):5.3f} "
            f"[{per_repeat[0]:5.3f}-{per_repeat[-1]:5.3f}] best {min(num) / min(den):5.3f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=DEFAULT_CASES, choices=list(CASES))
    parser.add_argument("--conditions", nargs="+", default=["busy", "quiet"], choices=["busy", "quiet"])
    parser.add_argument("--settings", nargs="+", default=list(SETTINGS), choices=list(SETTINGS),
                        help="thread settings to time (2T with a busy core can take many times 1T)")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}  cores={os.cpu_count()}  load at start={load()}  "
          f"repeats={args.repeat}: median [min-max]", flush=True)
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for name in args.cases:
            run_once(CASES[name] + WARMUP, SETTINGS["1T"], work)  # compile (cached afterwards)
            for condition in args.conditions:
                walls: dict[str, list[float]] = {label: [] for label in args.settings}
                later: dict[str, list[float]] = {label: [] for label in args.settings}  # after the first step
                chosen = set()
                picks = []  # the default's thread decisions, per repeat
                loads = []
                shared = []  # per repeat: do the two CPUs share one core right now (benchmarks/_cores.py)?
                streams = []  # per repeat: the 3 MB streaming loop's two-thread gain just before it
                for rep in range(args.repeat):
                    shared.append(vector_gain() < SHARED_BELOW)
                    streams.append(stream_gain())
                    # odd repeats in the reverse order (A B, B A, ...): a host that drifts within a
                    # repeat's minutes then favours neither setting
                    for label in (args.settings if rep % 2 == 0 else args.settings[::-1]):
                        setting = SETTINGS[label]
                        hog = None
                        if condition == "busy":
                            hog = subprocess.Popen([sys.executable, "-c", "while True: pass"])
                            time.sleep(0.5)
                        try:
                            loads.append(load())
                            wall, first, threads = run_once(CASES[name], setting, work)
                        finally:
                            if hog is not None:
                                hog.kill()
                                hog.wait()
                        walls[label].append(wall)
                        later[label].append(wall - first)
                        if label == "default":
                            chosen.add(threads)
                            picks.append(threads)
                cells = [f"{label} {spread(walls[label], '7.2f')} s" for label in args.settings]
                if "default" in walls:
                    cells[args.settings.index("default")] += f" (threads {' | '.join(sorted(chosen))})"
                if "default" in walls and "1T" in walls:
                    cells.append(ratio("default/1T", walls["default"], walls["1T"]))
                    cells.append(ratio("1T/default", walls["1T"], walls["default"]))
                if "2T" in walls and "1T" in walls:
                    cells.append(ratio("1T/2T", walls["1T"], walls["2T"]))
                    cells.append(ratio("1T/2T after the first step", later["1T"], later["2T"]))
                    two = [i for i, sh in enumerate(shared) if not sh]
                    if two and len(two) < len(shared):
                        cells.append(ratio("1T/2T on two cores", [walls["1T"][i] for i in two],
                                           [walls["2T"][i] for i in two]))
                cells.append("cores per repeat " + "".join("s" if sh else "2" for sh in shared))
                if "2T" in walls and "1T" in walls:  # each repeat's ratio with its cores, in order
                    cells.append("1T/2T per repeat " + " ".join(
                        f"{a / b:.3f}{'s' if sh else '2'}" for a, b, sh in zip(walls["1T"], walls["2T"], shared)))
                if "default" in walls and "1T" in walls:  # each repeat's ratio with the default's decisions
                    cells.append("default/1T per repeat " + " ".join(
                        f"{a / b:.3f}({t})" for a, b, t in zip(walls["default"], walls["1T"], picks)))
                cells.append("stream gain per repeat " + " ".join(f"{g:.2f}" for g in streams))
                print(f"{name:8s} {condition:5s}  " + "  ".join(cells) + f"  load {min(loads)}-{max(loads)}",
                      flush=True)

if __name__ == "__main__":
    main()
