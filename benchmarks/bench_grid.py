"""Throughput of the grid engine (zone-cycles per second) against Athena's gas-only anchors.

Every case is an isothermal shearing box with everything of a production run switched on:
Coriolis and tidal source terms (Omega = 1, q = 3/2), shear-periodic radial boundaries with
the conservative ghost remap and the radial flux correction, periodic other axes, and a flow
perturbed by 1 % noise. A measurement times ``engine.advance(engine.timestep())`` (one call
into compiled code per step, Courant reduction included) for a few seconds after warm-up and
keeps the best of ``--repeat`` runs (the machine is shared; the median is printed too); the
thread counts alternate within each repeat, so the 2T/1T ratio compares runs taken together.

Athena 4.2 anchors (one core of an earlier reference machine, gas only; problems hb3 in 2D
x-z and hgb in 3D). Athena has no VL+PPM figures, so our VL2+PPM rows are compared with its CTU
rows of the same reconstruction and solver (its default, Courant 0.8 in 2D, 0.4 in 3D); VL2
needs Courant <= 0.5 in 2D and (in our Courant convention) <= 1/3 in 3D, so per unit of
simulated time it takes 1.6x (2D) and 1.2x (3D, against 0.4) the cycles of CTU.

Usage::

    flock benchmarks/.lock python benchmarks/bench_grid.py            # everything
    python benchmarks/bench_grid.py --cases 2d64xz 3d32 --threads 1 --seconds 2
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import numba  # noqa: E402

from dustygas.grid import GridEngine, Mesh  # noqa: E402

# Athena 4.2, one core, zone-cycles/s (reference figures of an earlier machine): (case size, integrator, reconstruction, solver)
ATHENA = {
    ("2d64", "ctu", "ppm", "hllc"): 3.2e6, ("2d64", "ctu", "ppm", "hlle"): 3.5e6,
    ("2d64", "ctu", "plm", "hllc"): 4.4e6, ("2d64", "ctu", "plm", "hlle"): 4.8e6,
    ("2d64", "vl", "plm", "hllc"): 5.6e6, ("2d64", "vl", "plm", "hlle"): 6.2e6,
    ("2d128", "ctu", "ppm", "hllc"): 3.4e6,
    ("3d32", "ctu", "ppm", "hllc"): 1.0e6, ("3d32", "ctu", "ppm", "hlle"): 1.2e6,
    ("3d32", "ctu", "plm", "hllc"): 1.6e6, ("3d32", "ctu", "plm", "hlle"): 1.8e6,
    ("3d32", "vl", "plm", "hllc"): 1.9e6, ("3d32", "vl", "plm", "hlle"): 2.4e6,
    ("3d64", "ctu", "ppm", "hllc"): 1.0e6,
}

#: name -> (cells, anchor size key)
CASES = {
    "2d64xz": ((64, 1, 64), "2d64"),
    "2d64xy": ((64, 64, 1), "2d64"),
    "2d128xz": ((128, 1, 128), "2d128"),
    "2d128xy": ((128, 128, 1), "2d128"),
    "3d32": ((32, 32, 32), "3d32"),
    "3d64": ((64, 64, 64), "3d64"),
}

SCHEMES = [("vl2", "plm", "hlle"), ("vl2", "plm", "hllc"), ("vl2", "ppm", "hlle"), ("vl2", "ppm", "hllc"),
           ("rk3", "ppm-cs", "hllc")]


def anchor(size: str, integrator: str, reconstruction: str, riemann: str) -> tuple[float | None, str]:
    """Athena's figure for the same scheme (VL2+PPM -> CTU+PPM) and its label."""
    if integrator != "vl2" or reconstruction not in ("plm", "ppm"):
        return None, ""
    for athena_int in (("vl", "ctu") if reconstruction == "plm" else ("ctu",)):
        value = ATHENA.get((size, athena_int, reconstruction, riemann))
        if value is not None:
            return value, f"{athena_int.upper()}/{reconstruction.upper()}/{riemann.upper()}"
    return None, ""


def build(shape, integrator, reconstruction, riemann) -> GridEngine:
    mesh = Mesh(shape, (1.0, 1.0, 1.0))
    eng = GridEngine(mesh, integrator=integrator, reconstruction=reconstruction, riemann=riemann,
                     cfl=0.4 if mesh.ndim < 3 else 0.3, boundaries=("shear-periodic", "periodic", "periodic"),
                     omega=1.0, q=1.5)
    rng = np.random.default_rng(42)
    full = tuple(reversed(shape))
    x = mesh.centers(0)[None, None, :]
    eng.set_primitive(1.0 + 0.01 * rng.standard_normal(full), 0.01 * rng.standard_normal(full),
                      -1.5 * x + 0.01 * rng.standard_normal(full), 0.01 * rng.standard_normal(full))
    return eng


def rate(eng: GridEngine, threads: int, seconds: float) -> float:
    """Zone-cycles per second of ``eng`` on ``threads`` threads, timed for ``seconds``."""
    numba.set_num_threads(threads)
    eng.advance(eng.timestep())
    steps = 0
    start = time.perf_counter()
    while True:
        for _ in range(5):
            eng.advance(eng.timestep())
        steps += 5
        elapsed = time.perf_counter() - start
        if elapsed >= seconds:
            return steps * eng.work_units / elapsed


def measure(shape, scheme, threads: list[int], seconds: float, repeat: int) -> dict[int, list[float]]:
    """Rates for each thread count; the thread counts alternate within each repeat, so that a
    change of the machine's load hits all of them alike."""
    eng = build(shape, *scheme)
    for _ in range(5):  # compile (cached after the first run) and warm caches
        eng.advance(eng.timestep())
    rates: dict[int, list[float]] = {t: [] for t in threads}
    for _ in range(repeat):
        for t in threads:
            rates[t].append(rate(eng, t, seconds))
    return rates


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="+", default=list(CASES), choices=list(CASES))
    ap.add_argument("--schemes", nargs="+", default=[f"{i}/{r}/{s}" for i, r, s in SCHEMES],
                    help="integrator/reconstruction/riemann")
    ap.add_argument("--threads", default="1,2", help="comma-separated thread counts")
    ap.add_argument("--seconds", type=float, default=2.0, help="timed seconds per measurement")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args(argv)
    threads = [int(t) for t in args.threads.split(",")]
    load = os.getloadavg()
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}  load {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}  "
          f"numba {numba.__version__} ({numba.config.NUMBA_NUM_THREADS} threads max, "
          f"layer {numba.config.THREADING_LAYER})")
    header = f"{'case':9} {'scheme':18} {'thr':>3} {'best':>9} {'median':>9}  {'Athena':>8} {'ratio':>6} {'2T/1T':>6}"
    print(header)
    print("-" * len(header))
    for case in args.cases:
        shape, size = CASES[case]
        for text in args.schemes:
            scheme = tuple(text.split("/"))
            ref, label = anchor(size, *scheme)
            rates = measure(shape, scheme, threads, args.seconds, args.repeat)
            best1 = max(rates[1]) if 1 in rates else None
            for t in threads:
                best = max(rates[t])
                ratio = f"{best / ref:6.2f}" if ref and t == 1 else ""
                speedup = f"{best / best1:6.2f}" if best1 and t > 1 else ""
                ath = f"{ref:8.2g}" if ref and t == 1 else ""
                print(f"{case:9} {text:18} {t:3d} {best:9.3g} {statistics.median(rates[t]):9.3g}  {ath:>8} {ratio:>6} "
                      f"{speedup:>6}  {label if t == 1 else ''}", flush=True)
    load = os.getloadavg()
    print(f"# done {time.strftime('%H:%M')}  load {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
