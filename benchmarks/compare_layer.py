"""The settled dust layer of the ``si3d`` physics in dustygas and in Athena 4.2, side by side.

Not a timing: a check of the physics that issue 11 point 4 asks of the ``si3d`` preset (a
steady particle scale height ``H_p``, dense filaments). Both codes run the preset's box
(0.2 × 0.2 × 0.3 H, τ_s = 1, Z = Σ_p/Σ_g = 0.03, Π = 0.05, a Gaussian layer of H_p = 0.02 H,
one particle per cell, the NSH drift as the start) at ``--cells-per-h`` cells per H, in 3D or
in its x–z plane (``--dims 2``); each code keeps its own scheme (dustygas: the preset's VL2 +
PPM-CS + HLLC at Courant 0.3 per axis, hydrostatic open z boundaries; Athena: its
``par_strat3d`` / ``par_strat2d`` problem, CTU + PPM + HLLC with FARGO at Courant 0.4 in 3D
and 0.8 in 2D, its input files' values, periodic z with a smoothed potential). Printed per two
orbits: the mean ``H_p`` (the standard deviation of the particles' z, in both codes) and the
largest particle density ``ρ_p/ρ_g0``; then the steady-layer check of ``dustygas reproduce
fig1.13`` (:mod:`dustygas.reproduce.si3d_checks`) applied to both series.

Athena 4.2 is built outside the repository (``--with-problem=par_strat3d`` or ``par_strat2d``,
``--with-particles=feedback --enable-shearing-box --enable-fargo --with-eos=isothermal
--with-order=3p``; ``--enable-mpi`` for ``--ranks`` > 1); give its binary with ``--athena``.
A finished dustygas run can be given with ``--from RUN`` instead of running one, and a finished
Athena run (its input as ``_athena.PAR_STRAT_INPUT``) with ``--athena-phst FILE``.

Usage::

    python benchmarks/compare_layer.py --athena ATHENA3D/bin/athena --dims 3 --ranks 2 --orbits 20
    python benchmarks/compare_layer.py --athena ATHENA2D/bin/athena --dims 2 --cells-per-h 320
"""

from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "src"))

from _athena import PAR_STRAT_INPUT  # noqa: E402
from dustygas.reproduce.si3d_checks import STEADY_RATIO, window_start  # noqa: E402

BOX = (0.2, 0.2, 0.3)  # H: the si3d preset's box


def cells(dims: int, per_h: int) -> tuple[int, int, int]:
    """(nx, ny, nz) of the preset's box at ``per_h`` cells per H (ny = 1 in 2D)."""
    nx, ny, nz = (round(per_h * side) for side in BOX)
    return nx, (ny if dims == 3 else 1), nz


def athena_series(binary: Path, dims: int, per_h: int, orbits: float, ranks: int) -> dict[str, np.ndarray]:
    """Run Athena's par_strat{dims}d on the box; time (orbits), H_p and max ρ_p from its particle history."""
    nx, ny, nz = cells(dims, per_h)
    vertical = (-BOX[2] / 2, BOX[2] / 2)
    if dims == 3:  # x1 radial, x2 azimuthal, x3 vertical
        n2, (lo2, hi2), n3, (lo3, hi3), courant = ny, (-BOX[1] / 2, BOX[1] / 2), nz, vertical, 0.4
    else:  # par_strat2d: x1 radial, x2 vertical
        n2, (lo2, hi2), n3, (lo3, hi3), courant = nz, vertical, 1, (0.0, 0.0), 0.8
    text = PAR_STRAT_INPUT.format(problem_id="Layer", out_fmt="phst", out_dt=0.5, courant=courant, nlim=100000000,
                                  tlim=2 * math.pi * orbits, n1=nx, lo1=-BOX[0] / 2, hi1=BOX[0] / 2, n2=n2, lo2=lo2,
                                  hi2=hi2, n3=n3, lo3=lo3, hi3=hi3, ranks=ranks, per_grid=nx * ny * nz // ranks)
    with tempfile.TemporaryDirectory() as tmp:
        (Path(tmp) / "athinput").write_text(text)
        launcher = ["mpiexec", "-n", str(ranks)] if ranks > 1 else []
        subprocess.run([*launcher, str(binary), "-i", "athinput"], cwd=tmp, check=True, capture_output=True)
        return read_phst(Path(tmp) / "Layer.phst", vertical_column=8 if dims == 3 else 7)


def read_phst(path: Path, vertical_column: int) -> dict[str, np.ndarray]:
    """Athena's particle history: a row of global scalars (time, max particle density, ...) and a
    row per particle type (averages, then standard deviations of x1, x2, x3 at columns 6, 7, 8)."""
    rows = [line.split() for line in path.read_text().splitlines() if line.strip() and not line.startswith("#")]
    scalars = np.array(rows[0::2], dtype=float)
    typed = np.array(rows[1::2], dtype=float)
    n = min(len(scalars), len(typed))
    return {"t_orbits": scalars[:n, 0] / (2 * math.pi), "Hp": typed[:n, vertical_column], "rho_p_max": scalars[:n, 1]}


def dustygas_series(run: Path | None, dims: int, per_h: int, orbits: float, ranks: int) -> dict[str, np.ndarray]:
    """Run (or read, ``run`` given) the si3d preset on the box; the same three columns from its history."""
    from dustygas.analysis.stratified import read_series

    if run is None:
        run = Path(tempfile.mkdtemp(prefix="layer-"))
        nx, ny, nz = cells(dims, per_h)
        launcher = ["mpiexec", "-n", str(ranks)] if ranks > 1 else []
        cmd = [*launcher, sys.executable, "-m", "dustygas", "run", "si3d", "-q", "--overwrite", "-o", str(run),
               "--threads", "1", "--set", f"grid.nx={nx}", "--set", f"grid.ny={ny}", "--set", f"grid.nz={nz}",
               "--set", f"run.tlim={2 * math.pi * orbits}"]
        env = {**os.environ, "PYTHONPATH": str(Path(__file__).resolve().parents[1] / "src"), "NUMBA_NUM_THREADS": "1"}
        subprocess.run(cmd, check=True, env=env)
    cols = read_series(run)
    return {"t_orbits": cols["time"] / (2 * math.pi), "Hp": cols["species_0_scale_height"],
            "rho_p_max": cols["rho_p_max"]}


def steady_ratio(series: dict[str, np.ndarray]) -> float:
    """Mean H_p over the second half of the window of :func:`window_start` over the first half's."""
    t = series["t_orbits"]
    w = t >= window_start(float(t[-1])) * (1 - 1e-12)
    mid = 0.5 * (t[w][0] + t[w][-1])
    return float(np.mean(series["Hp"][w & (t >= mid)]) / np.mean(series["Hp"][w & (t < mid)]))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--athena", type=Path, help="Athena 4.2 binary built for par_strat3d/par_strat2d")
    ap.add_argument("--athena-phst", type=Path,
                    help="instead of --athena: the .phst file of a finished Athena run of the box")
    ap.add_argument("--dims", type=int, choices=(2, 3), default=3)
    ap.add_argument("--cells-per-h", type=int, default=160, help="160: the si3d preset (32 x 32 x 48)")
    ap.add_argument("--orbits", type=float, default=20.0)
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks of each code")
    ap.add_argument("--from", dest="run", type=Path, help="a finished dustygas run of the same box")
    args = ap.parse_args()
    if (args.athena is None) == (args.athena_phst is None):
        ap.error("give one of --athena and --athena-phst")
    nx, ny, nz = cells(args.dims, args.cells_per_h)
    dz = BOX[2] / nz
    print(f"# {time.strftime('%Y-%m-%d %H:%M')}  {args.dims}D  {nx} x {ny} x {nz} cells ({args.cells_per_h}/H, "
          f"dz = {dz:.5f} H), {args.orbits:g} orbits, {args.ranks} rank(s)", flush=True)
    series = {"dustygas": dustygas_series(args.run, args.dims, args.cells_per_h, args.orbits, args.ranks),
              "athena": (read_phst(args.athena_phst, vertical_column=8 if args.dims == 3 else 7) if args.athena_phst
                         else athena_series(args.athena, args.dims, args.cells_per_h, args.orbits, args.ranks))}
    print("orbits    " + "  ".join(f"{name + ' H_p/H (cells) / max rho_p':>40s}" for name in series))
    for o in range(0, int(round(args.orbits)), 2):
        cells_ = []
        for s in series.values():
            m = (s["t_orbits"] >= o) & (s["t_orbits"] < o + 2)
            hp = float(np.mean(s["Hp"][m]))
            cells_.append(f"{hp:.4f} ({hp / dz:4.1f}) / {np.max(s['rho_p_max'][m]):6.1f}")
        print(f"{o:2d}-{o + 2:<2d}     " + "  ".join(f"{c:>40s}" for c in cells_))
    for name, s in series.items():
        r = steady_ratio(s)
        ok = 1 / STEADY_RATIO <= r <= STEADY_RATIO
        print(f"{name}: H_p second half / first half of the window {r:.3f} ({'pass' if ok else 'fail'}, "
              f"[{1 / STEADY_RATIO:.2f}, {STEADY_RATIO:.2f}])")
    return 0


if __name__ == "__main__":
    sys.exit(main())
