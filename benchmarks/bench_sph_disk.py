"""Throughput of the disk step with individual time steps, side by side with Phantom on the same disk.

The disk is the thesis's (``sph-disk``): 1 M_sun star (fixed point mass, accretion radius 2.5 au),
5e-3 M_sun of gas with Sigma ~ 1/R from 5 to 200 au, c_s ~ R^-1/4 with H/R = 0.05 at 20 au, locally
isothermal, cubic kernel with h_fact = 1.2, artificial viscosity alpha = 0.1 (constant), beta = 2 (as
Phantom's disc set-up; the ``sph-disk`` default is beta = 0),
C_cour = 0.3, C_force = 0.25, blocks (Phantom: dtmax) of 0.05 orbits at 20 au. Both codes run the
same number of blocks from their own set-up of this disk (Phantom's ``setup_disc`` with ``ismoothgas
= F``; ours without the rotation relaxation, as Phantom has none). Throughput is particle-updates
per second: active particles summed over the sub-steps of the blocks, divided by the time of those
steps -- Phantom's own count (``moved N in T cpu-s`` lines of its log with ``iverbose = 1``).

Phantom is not part of this repository: pass ``--phantom DIR``, a directory holding a Phantom
binary built with ``SETUP=disc`` and a ``disc.in`` / initial dump written by its ``phantomsetup`` for
this disk (see benchmarks/RESULTS.md); the script copies the input, sets ``dtmax``, ``tmax`` and
``iverbose`` and runs it with ``OMP_NUM_THREADS`` = the thread count. Without ``--phantom`` only
dustygas runs.

Run alone: ``flock benchmarks/.lock python benchmarks/bench_sph_disk.py [--n 10000] [--blocks 10]``.
"""

from __future__ import annotations

import argparse
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numba

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "src"))

from dustygas.problems import get_problem  # noqa: E402

BLOCK = 0.05 * 2 * math.pi * 20.0**1.5  # dt_max: 0.05 orbits at 20 au
TARGET_VS_PHANTOM = 2.0


def ours(n: int, blocks: int, threads: int, individual: bool = True) -> dict:
    """Particle-updates, CPU and wall time of ``blocks`` blocks after a first (warm-up) block."""
    numba.set_num_threads(threads)
    prob = get_problem("sph-disk")
    cfg = prob.config(overrides=[f"disk.n_gas={n}", "disk.relax=none", "sph.beta=2.0",
                                 f"steps.individual={str(individual).lower()}"])
    eng = prob.build(cfg)
    eng.advance(eng.timestep())
    u0, c0, w0, t0 = eng.total_updates, time.process_time(), time.perf_counter(), eng.t
    target = t0 + blocks * BLOCK
    while eng.t < target * (1 - 1e-12):
        eng.advance(min(eng.timestep(), target - eng.t))
    return {"updates": eng.total_updates - u0, "cpu": time.process_time() - c0, "wall": time.perf_counter() - w0,
            "time": eng.t - t0}


def phantom(directory: Path, blocks: int, threads: int) -> dict:
    """Run Phantom on its disc set-up for ``blocks`` dumps and sum its per-step counts and timings."""
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        for f in directory.iterdir():
            if f.is_file():
                shutil.copy(f, work / f.name)
        text = (work / "disc.in").read_text()
        for key, value in (("tmax", f"{blocks * BLOCK:.10g}"), ("dtmax", f"{BLOCK:.10g}"), ("iverbose", "1"),
                           ("dumpfile", "disc_00000.tmp"), ("alpha", "0.1")):
            text = re.sub(rf"^(\s*{key}\s*=\s*)\S+", rf"\g<1>{value}", text, count=1, flags=re.M)
        (work / "disc.in").write_text(text)
        env = {**os.environ, "OMP_NUM_THREADS": str(threads)}
        w0 = time.perf_counter()
        out = subprocess.run(["./phantom", "disc.in"], cwd=work, env=env, capture_output=True, text=True, check=True)
        wall = time.perf_counter() - w0
    moved = [(int(a), float(b)) for a, b in re.findall(r"moved\s+(\d+)\s+in\s+([0-9.Ee+-]+)\s+cpu-s", out.stdout)]
    return {"updates": sum(m for m, _ in moved), "cpu": sum(c for _, c in moved), "wall": wall, "steps": len(moved)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=10000, help="gas particles (default 10000)")
    ap.add_argument("--blocks", type=int, default=10, help="blocks of 0.05 orbits at 20 au (default 10)")
    ap.add_argument("--threads", type=int, nargs="*", default=[1])
    ap.add_argument("--phantom", type=Path, default=None, help="directory with Phantom's disc set-up")
    ap.add_argument("--global-step", action="store_true", help="also time one global step for comparison")
    args = ap.parse_args()
    print(f"load average (1 min) before: {os.getloadavg()[0]:.2f}; cores: {os.cpu_count()}")
    for threads in args.threads:
        a = ours(args.n, args.blocks, threads)
        rate = a["updates"] / a["cpu"]
        print(f"dustygas, {threads} thread(s): {a['updates']:,} particle-updates in {a['cpu']:.2f} s CPU "
              f"({a['wall']:.2f} s wall): {rate:,.0f}/s per CPU second, {a['updates'] / a['wall']:,.0f}/s wall")
        if args.global_step:
            g = ours(args.n, args.blocks, threads, individual=False)
            print(f"  global step: {g['updates']:,} particle-updates ({g['updates'] / a['updates']:.1f}x), "
                  f"{g['wall']:.2f} s wall ({g['wall'] / a['wall']:.1f}x)")
        if args.phantom is not None:
            ph = phantom(args.phantom, args.blocks, threads)
            prate = ph["updates"] / ph["cpu"]
            print(f"Phantom, {threads} thread(s): {ph['updates']:,} particle-updates in {ph['cpu']:.2f} s CPU over "
                  f"{ph['steps']} steps ({ph['wall']:.2f} s wall incl. start-up): {prate:,.0f}/s")
            print(f"  dustygas / Phantom per thread: {rate / prate:.2f} (target >= {TARGET_VS_PHANTOM}); to the same "
                  f"simulated time ({args.blocks} blocks): {ph['cpu'] / a['cpu']:.2f}x less CPU time")
    print(f"load average (1 min) after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
