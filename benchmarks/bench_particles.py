"""Throughput of the particle-gas engine against Athena 4.2 (reference figures of an earlier machine).

Main figure: the YJ07 linA run, 64², one particle per cell, t = 0 -> 6, exactly as
``dustygas run si-linA`` does it (VL2 + PPM + HLLC, Courant 0.4, TSC, semi-implicit drag),
timed over the whole run on one and on two threads: zone-cycles/s, particle-updates/s and
the ratio to Athena's 1.9e6 zone-cycles/s (CTU + PPM + HLLC at Courant 0.8, 45,923 cycles in
99 s; growth 0.4139, -1.2 %). The growth rate of the run is measured too
(:func:`dustygas.analysis.growth.measure_growth`, eight fields), so the speed is quoted at
the accuracy it buys. Our VL2 needs Courant <= 0.5 in 2D (0.4 here): 91,846 cycles for
Athena's 45,923, so the wall-clock ratio is the zone-cycle ratio / 2.

Other rows time a few thousand steps of the same engine (best of ``--repeat`` timings, after
warm-up) for Athena's other particle runs: linA with 4 particles per cell, linA 128², and
the 3D run "AB" (τ_s = 0.1, ε = 1, 32³, box 2 ηr, shear-periodic, 1 and 8 particles per
cell).

Side by side with Athena (``--athena PATH``): the path of an Athena 4.2 binary built outside the
repository for its ``streaming2d_single`` problem (``benchmarks/_athena.py`` says how it is
configured). Athena's linA (``ipert=1``, 64², one particle per cell, CTU at Courant 0.8, TSC,
semi-implicit drag, t = 0 -> 6, its mode-amplitude output every 0.02) and dustygas's si-linA
(each integrator of ``--integrators``, one thread, and two threads; by default CTU + HLLE + PPM at
Courant 1.0, the fastest setting for linA that is more accurate than Athena's run, then CTU + HLLE
(PPM-CS) at 1.0, the most accurate CTU setting, then CTU + HLLC at 0.8 as Athena, then VL2 at 0.4)
run interleaved,
``--rounds`` times; printed: wall time to t = 6, cycles, zone-cycles/s, growth rate and its
error against linear theory (Athena's from its largest-perturbation output, ours from the
Fourier amplitudes, both with the automatic window of ``dustygas analyze growth``), and the
ratios of the median wall times. ``--athena-ranks 1,2`` runs Athena (an MPI build) on one and
two processes in each round, so that each code's own gain from a second core is measured at the
same moments; ``--tlim 1`` shortens every run (no growth fit) for more rounds.

Usage::

    flock benchmarks/.lock python benchmarks/bench_particles.py            # everything
    python benchmarks/bench_particles.py --quick                                      # timed rows only
    flock benchmarks/.lock python benchmarks/bench_particles.py --athena /path/to/athena --rounds 3
    flock benchmarks/.lock python benchmarks/bench_particles.py --athena /path/to/mpi/athena --athena-ranks 1,2 \
        --integrators ctu,vl2 --tlim 1 --rounds 5                                 # each code's two-core gain
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numba  # noqa: E402
from _cores import describe, vector_gain  # noqa: E402

# Athena 4.2 anchors, one core (reference figures of an earlier machine)
ATHENA = {
    "linA 64^2 1ppc": dict(zone_cycles=1.9e6, cycles=45_923, wall=99.0, growth=0.4139),
    "linA 64^2 4ppc": dict(zone_cycles=8.9e5, particle_updates=3.6e6, growth=0.4142),
    "linA 128^2 1ppc": dict(zone_cycles=1.95e6, growth=0.4182),
    "linB 64^2 1ppc": dict(zone_cycles=1.87e6, cycles=229_500, wall=502.0, growth=0.01273),
    "AB 32^3 1ppc": dict(zone_cycles=4.9e5),
    "AB 32^3 8ppc": dict(zone_cycles=1.7e5, particle_updates=1.36e6),
}
LINA_GROWTH = 0.4190091323  # consistent linearisation (Benitez-Llambay et al. 2019)


def load() -> str:
    try:
        return " ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def si_engine(sets: list[str], name: str = "si-linA"):
    from dustygas.problems import get_problem

    prob = get_problem(name)
    return prob.build(prob.config(overrides=sets))


def ab_engine(lattice: int):
    """3D run "AB" of Johansen & Youdin (2007), Bai & Stone (2010a): τ_s = 0.1, ε = 1, 32³,
    box 2 ηr (Π = 0.05), shear-periodic, NSH drift plus 1e-3 noise, Courant 0.3."""
    from dustygas.grid import GridEngine, Mesh
    from dustygas.particles import ParticleGridEngine, ParticleStore
    from dustygas.particles.params import lattice_positions
    from dustygas.physics import nsh_velocities

    Pi, n = 0.05, 32
    L = 2 * Pi
    mesh = Mesh((n, n, n), (L, L, L))
    gas = GridEngine(mesh, reconstruction="ppm", riemann="hllc", cfl=0.3, omega=1.0, q=1.5,
                     boundaries=("shear-periodic", "periodic", "periodic"), orbital_advection=True, eta_vK=Pi)
    eq = nsh_velocities(0.1, 1.0, Pi)
    rng = np.random.default_rng(0)
    sh = tuple(reversed(mesh.shape))
    x = mesh.centers(0)[None, None, :]
    gas.set_primitive(1.0, float(eq.gas_vx) + 1e-3 * rng.standard_normal(sh), float(eq.gas_vy) - 1.5 * x, 0.0)
    pos = lattice_positions(mesh.shape, mesh.lower, mesh.dx, lattice)
    vel = np.zeros_like(pos)
    vel[0], vel[1] = float(eq.dust_vx), float(eq.dust_vy)
    vel += 1e-3 * rng.standard_normal(vel.shape)
    store = ParticleStore.create(pos, vel, 0, mesh.cell_volume / lattice**3)
    return ParticleGridEngine(gas, store, [0.1])


def time_steps(make, seconds: float, repeat: int, threads: int) -> tuple[float, float, int]:
    """Best and median steps/s of ``engine.advance(engine.timestep())`` over ``repeat`` timings."""
    numba.set_num_threads(threads)
    eng = make()
    for _ in range(20):
        eng.advance(eng.timestep())
    rates = []
    for _ in range(repeat):
        n, t0 = 0, time.perf_counter()
        while time.perf_counter() - t0 < seconds:
            for _ in range(20):
                eng.advance(eng.timestep())
            n += 20
        rates.append(n / (time.perf_counter() - t0))
    return max(rates), statistics.median(rates), eng.particles.n


#: the gas schemes of si-linA compared with Athena: VL2 at its 2D limit's 0.4, CTU at Athena's 0.8;
#: ``NAME@C`` in ``--integrators`` runs integrator NAME at Courant number C
SCHEMES = {"vl2": ["scheme.integrator=vl2", "scheme.cfl=0.4"], "ctu": ["scheme.integrator=ctu", "scheme.cfl=0.8"]}


def scheme_sets(name: str) -> list[str]:
    """The ``--set`` overrides of an ``--integrators`` entry: ``vl2``, ``ctu`` or
    ``NAME[+SOLVER][+RECONSTRUCTION][+unfiltered]@COURANT`` (e.g. ``ctu@0.8``, ``ctu+hlle@1.0``,
    ``ctu+hlle+ppm@1.0``: the Riemann solver and the face reconstruction, by default the
    problem's HLLC and PPM-CS; ``unfiltered``: the particles gather and deposit without the
    grid-scale filter, ``particles.smooth=false``)."""
    from dustygas.grid.reconstruct import RECONSTRUCTIONS
    from dustygas.grid.riemann import RIEMANN_SOLVERS

    if "@" in name:
        head, cfl = name.split("@")
        integrator, *options = head.split("+")
        sets = [f"scheme.integrator={integrator}", f"scheme.cfl={float(cfl)!r}"]
        for option in options:
            if option in RIEMANN_SOLVERS:
                sets.append(f"scheme.riemann={option}")
            elif option in RECONSTRUCTIONS:
                sets.append(f"scheme.reconstruction={option}")
            elif option == "unfiltered":
                sets.append("particles.smooth=false")
            else:
                raise SystemExit(f"--integrators: {option!r} in {name!r} is not a Riemann solver "
                                 f"({', '.join(RIEMANN_SOLVERS)}), a reconstruction ({', '.join(RECONSTRUCTIONS)}) "
                                 "or 'unfiltered'")
        return sets
    return SCHEMES[name]


#: shortest run whose growth is fitted: the linear window of linA starts near t = 0.3 and the fit
#: needs a few e-foldings (growth rate 0.42)
FIT_TLIM = 3.0


def full_lina(threads: int, sets: list[str] | None = None, tlim: float = 6.0) -> dict:
    """linA 64² 1 ppc, t = 0 -> ``tlim`` through the run loop; wall, throughput and (if
    ``tlim >= FIT_TLIM``) growth."""
    from dustygas import api
    from dustygas.analysis.growth import measure_growth

    sets = list(sets or [])
    si_engine(["grid.nx=8", "grid.nz=8", "run.tlim=0.001", *sets]).advance(1e-6)  # compile outside the timing
    with tempfile.TemporaryDirectory() as tmp:
        cpu0 = time.process_time()
        res = api.run("si-linA", output=Path(tmp) / "linA",
                      set=[*sets, f"run.threads={threads}", "run.checkpoint_wall=0", f"run.tlim={tlim!r}"])
        cpu = time.process_time() - cpu0
        fit = measure_growth(Path(tmp) / "linA") if tlim >= FIT_TLIM else None
    return dict(cycles=res.cycles, wall=res.wall, cpu=cpu, zone_cycles=res.throughput,
                particle_updates=res.throughput, fit=fit)


def athena_lina(binary: Path, athinput: Path, courant: float = 0.8, ranks: int = 1, tlim: float = 6.0) -> dict:
    """Athena's streaming2d_single linA: 64², 1 ppc, CTU at ``courant`` (its runs: 0.8), TSC,
    semi-implicit, t = 0 -> ``tlim``; on ``ranks`` MPI processes (the box cut along x). Its wall
    time includes the process start (and ``mpiexec``'s), about 0.1-0.2 s here."""
    from _athena import run_athena, streaming_growth

    overrides = [f"time/tlim={tlim!r}", f"time/cour_no={courant!r}", "time/nlim=10000000", "job/maxout=1", "output1/dt=0.02",
                 "domain1/Nx1=64", "domain1/Nx2=64", "particle/parnumcell=1", "particle/integrator=2",
                 "particle/interp=2", "particle/tsmode=3", "problem/ipert=1", "problem/nwave=1",
                 "problem/amp=1.0e-6"]
    overrides += [f"domain1/NGrid_x1={ranks}", "domain1/NGrid_x2=1"]  # the input file may ask for more grids
    res = run_athena(binary, athinput, overrides, ranks=ranks)
    (amp,) = [text for name, text in res["files"].items() if name.startswith("Streaming2d")]
    fit = streaming_growth(amp) if tlim >= FIT_TLIM else None
    return dict(cycles=res["cycles"], wall=res["wall"], cpu=res["cpu"], zone_cycles=res["cycles"] * 64 * 64 / res["wall"],
                fit=fit)


def _line(name: str, r: dict) -> str:
    fit = r["fit"]
    growth = "growth not fitted (short run)  " if fit is None else (
        f"growth {fit.growth_rate:.5f} ({100 * (fit.growth_rate / LINA_GROWTH - 1):+.2f} %, window "
        f"{fit.window[0]:.2f}-{fit.window[1]:.2f}, fields within {100 * fit.spread:.2f} %)  ")
    return (f"{name:<22} {r['cycles']:>7} cycles  wall {r['wall']:7.2f} s  CPU {r['cpu']:7.2f} s  "
            f"{r['zone_cycles']:.3g} zone-cycles/s  {growth}load {load()}")


def side_by_side(binary: Path, athinput: Path | None, integrators: list[str], rounds: int, two_threads: bool,
                 courant: float = 0.8, ranks: tuple[int, ...] = (1,), tlim: float = 6.0) -> None:
    """Athena (on each of ``ranks`` MPI process counts) and dustygas linA interleaved, ``rounds``
    times; medians and ratios, and each code's own gain from a second process or thread."""
    from _athena import find_input

    athinput = athinput or find_input(binary, "streaming2d_single", "particle")
    print(f"# Athena {binary} with {athinput}")
    runs: dict[str, list[dict]] = {}
    threads = [1, 2] if two_threads and numba.config.NUMBA_NUM_THREADS >= 2 else [1]
    for rnd in range(rounds):
        jobs = [("athena", None, r) for r in ranks] + [(name, scheme_sets(name), t) for name in integrators
                                                       for t in threads]
        if rnd % 2:  # alternate the order, so that a trend in the machine's load hits both codes alike
            jobs.reverse()
        for name, sets, t in jobs:
            key = (f"athena {t} rank{'s' if t > 1 else ''}" if len(ranks) > 1 else "athena") if name == "athena" \
                else f"dustygas {name} {t}T"
            cores = describe(vector_gain()) if t > 1 else ""  # benchmarks/_cores.py
            r = athena_lina(binary, athinput, courant, t, tlim) if name == "athena" else full_lina(t, sets, tlim)
            runs.setdefault(key, []).append(r)
            print(_line(key, r) + (f"  cores before: {cores}" if cores else ""), flush=True)
    anchor = next(key for key in runs if key.startswith("athena"))  # Athena on the first rank count
    ath = statistics.median(r["wall"] for r in runs[anchor])
    ath_cpu = statistics.median(r["cpu"] for r in runs[anchor])
    print(f"# medians over {rounds} round(s); {anchor}: {ath:.1f} s wall, {ath_cpu:.1f} s CPU")
    for key, rs in runs.items():
        if key.startswith("athena"):
            if key != anchor:
                wall = statistics.median(r["wall"] for r in rs)
                gains = "/".join(f"{a['wall'] / b['wall']:.2f}" for a, b in zip(runs[anchor], rs))
                print(f"{key:<22} median wall {wall:7.1f} s  gain over {anchor}: {ath / wall:.2f} (per round {gains})")
            continue
        wall = statistics.median(r["wall"] for r in rs)
        cpu = statistics.median(r["cpu"] for r in rs)
        print(f"{key:<22} median wall {wall:7.1f} s, CPU {cpu:7.1f} s  {anchor} / dustygas: wall {ath / wall:.2f}, "
              f"CPU {ath_cpu / cpu:.2f} (CPU counts a second thread's spin-waits: compare wall on a quiet machine)")
        one = runs.get(key.replace(" 2T", " 1T"))
        if key.endswith(" 2T") and one:
            gains = "/".join(f"{a['wall'] / b['wall']:.2f}" for a, b in zip(one, rs))
            print(f"{'':<22} gain of two threads over one: {statistics.median(r['wall'] for r in one) / wall:.2f} "
                  f"(per round {gains})")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="skip the two full linA runs")
    ap.add_argument("--seconds", type=float, default=3.0, help="length of one timing of the short rows")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--athena", type=Path, help="Athena 4.2 binary built for streaming2d_single: run it side by side")
    ap.add_argument("--athinput", type=Path, help="its input file (default: tst/particle/ of its source tree)")
    ap.add_argument("--athena-courant", type=float, default=0.8, help="Athena's Courant number (its linA runs: 0.8)")
    ap.add_argument("--athena-ranks", default="1",
                    help="run Athena on this many MPI ranks, or on each of a comma-separated list (e.g. 1,2: its own "
                         "gain from a second process; more than one rank needs a binary configured with --enable-mpi)")
    ap.add_argument("--integrators", default="ctu+hlle+ppm@1.0,ctu+hlle@1.0,ctu,vl2",
                    help="dustygas gas integrators for --athena (vl2, ctu or NAME[+SOLVER][+RECONSTRUCTION][+unfiltered]@COURANT, "
                         "e.g. ctu@0.9, ctu+hlle@1.0, ctu+hlle+ppm@1.0)")
    ap.add_argument("--rounds", type=int, default=1, help="interleaved rounds of --athena")
    ap.add_argument("--tlim", type=float, default=6.0,
                    help=f"--athena: end time of both codes' runs (growth fitted from {FIT_TLIM:g} on; shorter "
                         "runs time more rounds, e.g. 1 for the gain of a second process or thread)")
    ap.add_argument("--one-thread", action="store_true", help="--athena: dustygas on one thread only")
    args = ap.parse_args()
    maxthreads = numba.config.NUMBA_NUM_THREADS
    print(f"# bench_particles  {time.strftime('%Y-%m-%d %H:%M')}  numba {numba.__version__}  "
          f"threads available {maxthreads}  load {load()}")
    if args.athena is not None:
        side_by_side(args.athena, args.athinput, args.integrators.split(","), args.rounds, not args.one_thread,
                     args.athena_courant, tuple(int(r) for r in args.athena_ranks.split(",")), args.tlim)
        return
    if not args.quick:
        one = None
        for threads in (1, maxthreads):
            r = full_lina(threads)
            one = one or r
            a = ATHENA["linA 64^2 1ppc"]
            print(f"linA 64^2 1ppc t=0-6  threads={threads}: {r['cycles']} cycles in {r['wall']:.1f} s  "
                  f"{r['zone_cycles']:.3g} zone-cycles/s = {r['particle_updates']:.3g} particle-updates/s  "
                  f"x{r['zone_cycles'] / a['zone_cycles']:.2f} Athena  (wall x{a['wall'] / r['wall']:.2f})  "
                  f"growth {r['fit'].growth_rate:.5f} ({100 * (r['fit'].growth_rate / LINA_GROWTH - 1):+.2f} %, fields "
                  f"within {100 * r['fit'].spread:.2f} %; Athena {a['growth']} ({100 * (a['growth'] / LINA_GROWTH - 1):+.1f} %))"
                  f"  2 threads / 1: {r['zone_cycles'] / one['zone_cycles']:.2f}  load {load()}")
    rows = [
        ("linA 64^2 1ppc", lambda: si_engine([]), 64 * 64),
        ("linA 64^2 4ppc", lambda: si_engine(["particles.lattice=2"]), 64 * 64),
        ("linA 128^2 1ppc", lambda: si_engine(["grid.nx=128", "grid.nz=128"]), 128 * 128),
        ("AB 32^3 1ppc", lambda: ab_engine(1), 32**3),
        ("AB 32^3 8ppc", lambda: ab_engine(2), 32**3),
    ]
    for name, make, cells in rows:
        best = {}
        for threads in (1, maxthreads):
            rate, med, npart = time_steps(make, args.seconds, args.repeat, threads)
            best[threads] = rate
            a = ATHENA[name]
            line = (f"{name:<16} threads={threads}: {rate * cells:.3g} zone-cycles/s (median {med * cells:.3g})  "
                    f"{rate * npart:.3g} particle-updates/s  x{rate * cells / a['zone_cycles']:.2f} Athena")
            if "particle_updates" in a:
                line += f" (particle-updates x{rate * npart / a['particle_updates']:.2f})"
            if threads > 1:
                line += f"  2 threads / 1: {rate / best[1]:.2f}"
            print(line + f"  load {load()}")
    numba.set_num_threads(maxthreads)


if __name__ == "__main__":
    main()
