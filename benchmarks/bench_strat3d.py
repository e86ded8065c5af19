"""The 3D stratified particle-gas box side by side with Athena 4.2's ``par_strat3d``, in one run.

Both codes run the same box on this machine, one after the other: 32³ cells, 0.2 H on a side,
one particle per cell (32,768 particles of τ_s = 1), Z = Σ_p/Σ_g = 0.03 in a Gaussian layer
of H_p = 0.02 H, Π = 0.05, the multi-species NSH drift as the start (Athena's ``ipert = 0``),
shear-periodic x, periodic y. Each code keeps its own stratified set-up along z: dustygas
the ``si3d`` problem (hydrostatic gas column, outflowing particles; VL2 + PPM + HLLC, Courant
0.3 per axis, TSC, the exact local drag solution), Athena its ``par_strat3d`` problem
(CTU + third-order PPM + HLLC at Courant 0.4, FARGO, TSC, the semi-implicit particle
integrator). Figures:

* (a) zone-cycles per CPU-second on one thread (Athena's own figure, which leaves out its
  set-up; ours from ``time.process_time`` around the timed steps -- CPU time, because the
  machine is shared), and the CPU time per unit of simulated time (the two codes' steps
  differ: Courant numbers and their definitions);
* (c) two threads against one on the *settled* state: the newest checkpoint of a ``si3d`` run
  given with ``--settled RUN`` (the laptop preset: 32 × 32 × 48, the layer settled), thread
  counts interleaved in one process so that both see the same machine.

Athena 4.2 is built outside the repository (``--with-problem=par_strat3d --with-particles=feedback
--enable-shearing-box --enable-fargo --with-eos=isothermal --with-order=3p``; serial); give its
binary with ``--athena``. The machine is shared: the figures are the best of ``--repeat``
timings, with the load average printed next to them.

Usage::

    flock benchmarks/.lock python benchmarks/bench_strat3d.py \\
        --athena /path/to/athena/bin/athena --settled /path/to/runs/si3d
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

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

import numba  # noqa: E402
from _athena import PAR_STRAT_INPUT  # noqa: E402

N = 32
SIDE = 0.2
SETS = [f"grid.nx={N}", f"grid.ny={N}", f"grid.nz={N}", f"grid.lx={SIDE}", f"grid.ly={SIDE}", f"grid.lz={SIDE}",
        "problem.Z=0.03", "problem.Hp=0.02", "problem.Pi=0.05", "problem.taus=[1.0]", "problem.per_cell=1"]



def load() -> str:
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def athena(binary: str, cycles: int) -> dict:
    """Run Athena for ``cycles`` cycles; its own zone-cycles/cpu-second and the simulated time."""
    with tempfile.TemporaryDirectory() as tmp:
        inp = Path(tmp) / "athinput.bench"
        box = dict(lo1=-SIDE / 2, hi1=SIDE / 2, lo2=-SIDE / 2, hi2=SIDE / 2, lo3=-SIDE / 2, hi3=SIDE / 2)
        inp.write_text(PAR_STRAT_INPUT.format(problem_id="Par_Strat3d", out_fmt="hst", out_dt=1000.0, courant=0.4,
                                              nlim=cycles, tlim=1000.0, n1=N, n2=N, n3=N, ranks=1, per_grid=N**3,
                                              **box))
        t0 = time.perf_counter()
        out = subprocess.run([binary, "-i", str(inp), "-d", tmp], capture_output=True, text=True, check=True,
                             cwd=tmp, timeout=3600)
        wall = time.perf_counter() - t0
    text = out.stdout + out.stderr
    rate = float(re.search(r"zone-cycles/cpu-second\s*=\s*([0-9.eE+-]+)", text).group(1))
    tend = float(re.findall(r"time=\s*([0-9.eE+-]+)", text)[-1])
    return {"zone_cycles": rate, "time": tend, "cycles": cycles, "wall": wall}


def dustygas_engine(sets: list[str]):
    from dustygas.problems import get_problem

    prob = get_problem("si3d")
    return prob.build(prob.config(overrides=sets))


def settled_engine(run: Path):
    """The engine of ``run`` restored from its newest checkpoint."""
    from dustygas.config import load_toml
    from dustygas.io import read_h5
    from dustygas.io.rundir import RunDirectory
    from dustygas.problems import get_problem

    rd = RunDirectory(run)
    saved = load_toml(rd.config_file)
    prob = get_problem(saved["dustygas"]["problem"])
    eng = prob.build(prob.config(data=saved))
    arrays, attrs = read_h5(rd.checkpoints()[-1])
    eng.restore({k[7:]: v for k, v in arrays.items() if k.startswith("engine/")},
                {k[12:]: v for k, v in attrs.items() if k.startswith("engine_attr_")})
    eng.t = float(attrs["engine_t"])
    eng.cycle = int(attrs["engine_cycle"])
    return eng


def step_times(eng, threads: tuple[int, ...], steps: int, repeats: int) -> dict[int, tuple[float, float]]:
    """Best wall time and best CPU time (all threads) of ``steps`` steps per thread count (one
    untimed step each first; the thread counts alternate within every repeat)."""
    for t in threads:
        numba.set_num_threads(t)
        eng.advance(eng.timestep())
    best = {t: (float("inf"), float("inf")) for t in threads}
    for _ in range(repeats):
        for t in threads:
            numba.set_num_threads(t)
            t0, c0 = time.perf_counter(), time.process_time()
            for _ in range(steps):
                eng.advance(eng.timestep())
            wall, cpu = time.perf_counter() - t0, time.process_time() - c0
            best[t] = (min(best[t][0], wall), min(best[t][1], cpu))
    return best


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--athena", required=True, help="Athena 4.2 binary built for par_strat3d (serial)")
    ap.add_argument("--settled", type=Path, help="si3d run directory whose newest checkpoint is the settled state")
    ap.add_argument("--initial-layer", action="store_true",
                    help="without --settled: time (c) on the si3d preset's initial layer (H_p = 0.02 H)")
    ap.add_argument("--cycles", type=int, default=300, help="cycles per timing (default 300)")
    ap.add_argument("--repeat", type=int, default=3, help="timings per code, the best counts (default 3)")
    args = ap.parse_args()
    print(f"date {time.strftime('%Y-%m-%d %H:%M:%S %Z')}  numba threads {numba.config.NUMBA_NUM_THREADS}  "
          f"load {load()}")
    # (a) one thread, 32^3, from the initial layer
    runs = [athena(args.athena, args.cycles) for _ in range(args.repeat)]
    a = max(runs, key=lambda r: r["zone_cycles"])
    a_dt = a["time"] / a["cycles"]
    print(f"athena   32^3 1ppc: {a['zone_cycles']:.4g} zone-cycles/s (best of {args.repeat}, its cpu-second "
          f"figure), dt = {a_dt:.4g}, {1 / a_dt / a['zone_cycles'] * N**3:.3g} s per unit time  load {load()}")
    eng = dustygas_engine(SETS)
    wall, cpu = step_times(eng, (1,), args.cycles, args.repeat)[1]
    d_dt = eng.t / eng.cycle
    rate, cpu_rate = N**3 * args.cycles / wall, N**3 * args.cycles / cpu
    print(f"dustygas 32^3 1ppc: {cpu_rate:.4g} zone-cycles/cpu-s ({rate:.4g} per wall-s; 1 thread, best of "
          f"{args.repeat}), dt = {d_dt:.4g}, {1 / d_dt / cpu_rate * N**3:.3g} cpu-s per unit time  load {load()}")
    print(f"ratio (a): zone-cycles per cpu-second x{cpu_rate / a['zone_cycles']:.2f}; cpu time per unit "
          f"simulated time x{(1 / a_dt / a['zone_cycles']) / (1 / d_dt / cpu_rate):.2f} in dustygas's favour")
    # (c) two threads against one on the settled state
    if args.settled is not None or args.initial_layer:
        eng = settled_engine(args.settled) if args.settled is not None else dustygas_engine([])
        cells = eng.work_units
        steps = max(args.cycles // 3, 20)
        t_settled = eng.t
        best = step_times(eng, (1, 2), steps, args.repeat)
        print(f"{'settled ' + args.settled.name if args.settled else 'si3d initial layer'} t = {t_settled:.4g} ({cells} cells, {eng.particles.n} particles): "
              f"1 thread {cells * steps / best[1][0]:.4g}, 2 threads {cells * steps / best[2][0]:.4g} "
              f"zone-cycles/wall-s, ratio (c) x{best[1][0] / best[2][0]:.2f}  load {load()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
