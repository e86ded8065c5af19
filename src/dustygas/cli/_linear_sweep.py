"""``dustygas linear sweep``: the shearing-wave sweep over (μ, τ_s, k_x0, k_y) (thesis §4.6.2)."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from ..errors import UserError

SWEEP_DESCRIPTION = """Integrate the non-axisymmetric shearing wave (thesis eqs. 4.35; kx(t) = kx0 + 1.5 ky t) at every
point of a (mu, tau_s, kx0, ky) grid and write DIR/sweep.h5 (labelled dimensions, every parameter as
attributes) and the figures DIR/sweep_amplification.png and DIR/sweep_angle.png (each with a CSV).

Grids: --mu 0.1 1 3 (a list) or --mu-range MIN MAX N (log-spaced; also --taus-range); --kx-range and
--ky-range are evenly spaced. A TOML file (-c) holds the same keys in a [sweep] table (mu = [..] or
mu_range = [min, max, n], kz, Pi, drag, t_end, window, initial, metric, rtol, atol, chunk, times);
the command line overrides it.

Quantities per point: energy_peak (max_t sqrt(E(t)/E(0)), the swing amplification), energy_final
(sqrt(E(t_end)/E(0))), dust_final (|Sigma_d(t_end)/Sigma_d(0)|), mean_growth (ln(E(t_b)/E(t_a))/(2 (t_b-t_a))
over --window W0 W1, fractions of t_end), t_peak. Per (mu, tau_s): the preferred wavevector (maximum of
--metric) and its angle arctan(ky / kx(t_end)).

Execution: --executor process (default; --workers N), serial, mpi (run under
  mpiexec -n N python -m mpi4py.futures -m dustygas linear sweep --executor mpi ...)
or dask (--scheduler tcp://HOST:PORT). Every executor writes the same file. Finished chunks are
kept in DIR/sweep.h5.parts/: run the same command again after a kill and only the missing chunks
are computed."""


def add_sweep_arguments(s: argparse.ArgumentParser) -> None:
    for name, what, scale in (("mu", "dust-to-gas ratios mu", "log"), ("taus", "stopping times tau_s", "log"),
                              ("kx", "initial radial wavenumbers K_x0", "even"),
                              ("ky", "azimuthal wavenumbers K_y", "even")):
        flags = ("--mu", "--eps") if name == "mu" else (f"--{name}",)  # --eps: alias of --mu (YJ07's epsilon)
        s.add_argument(*flags, dest=name, type=float, nargs="+", metavar="V", help=f"{what} (a list)")
        s.add_argument(f"--{name}-range", type=float, nargs=3, metavar=("MIN", "MAX", "N"),
                       help=f"{what}: N points from MIN to MAX ({scale}-spaced)")
    # the options below default to the TOML value, then to SweepSpec's default
    s.add_argument("--kz", type=float, help="fixed vertical wavenumber K_z (default 0: the planar system 4.35)")
    s.add_argument("--pi", dest="Pi", type=float, help="Pi = eta v_K/c_s (default 0.05; 0: incompressible)")
    s.add_argument("--drag", help="drag linearisation: consistent (default), yj07, epstein")
    s.add_argument("--t-end", dest="t_end", metavar="T", help="end time in 1/Omega (default 2 pi), or 'swing'")
    s.add_argument("--window", type=float, nargs=2, metavar=("W0", "W1"),
                   help="averaging window of mean_growth, fractions of t_end (default 0 1)")
    s.add_argument("--initial", help="fastest (default), vortical or dust")
    s.add_argument("--metric", help="quantity the preferred wavevector maximises: dust_final (default), "
                   "energy_final, energy_peak, mean_growth")
    s.add_argument("--rtol", type=float, help="relative tolerance of the integrator (default 1e-6)")
    s.add_argument("--atol", type=float, help="absolute tolerance (default 1e-12)")
    s.add_argument("--chunk", type=int, help="points per task (default 64)")
    s.add_argument("--times", type=int, metavar="N", help="also sample the amplifications at N times t_end*i/N "
                   "(the predicted preferred angle versus time; default 0)")
    s.add_argument("-c", "--config", metavar="FILE.toml", help="TOML file with a [sweep] table")
    s.add_argument("--executor", default="process", help="process (default), serial, mpi, dask")
    s.add_argument("--workers", type=int, help="worker processes of --executor process (default: CPU count)")
    s.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address for --executor dask")
    s.add_argument("--scheduler-timeout", type=float, default=10.0, metavar="S",
                   help="seconds to wait for the Dask scheduler (default 10)")
    s.add_argument("-o", "--output", default="linear_sweep", metavar="DIR", help="output directory")
    s.add_argument("--overwrite", action="store_true", help="replace an existing sweep.h5 (or unfinished parts)")
    s.add_argument("--no-progress", action="store_true", help="no progress bar")
    s.add_argument("--no-plots", action="store_true", help="write sweep.h5 only")


def _toml(path: str) -> dict:
    import tomllib

    p = Path(path)
    if not p.is_file():
        raise UserError(f"--config {path}: no such file")
    try:
        data = tomllib.loads(p.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise UserError(f"--config {path}: not valid TOML ({exc})") from None
    unknown = sorted(set(data) - {"sweep"})
    if unknown:
        raise UserError(f"--config {path}: unknown table or key {unknown[0]!r} (expected a [sweep] table)")
    table = data.get("sweep", {})
    if not isinstance(table, dict):
        raise UserError(f"--config {path}: 'sweep' must be a table")
    return dict(table)


def _t_end(text):
    if text is None or text == "swing":
        return text
    try:
        return float(text)
    except ValueError:
        raise UserError(f"--t-end {text!r}: a time in 1/Omega or 'swing'") from None


def build_spec(args):
    from ..linear.sweep_run import spec_from_mapping

    values = _toml(args.config) if args.config else {}
    for grid in ("mu", "taus", "kx", "ky"):
        given, rng = getattr(args, grid), getattr(args, f"{grid}_range")
        if given is not None and rng is not None:
            raise UserError(f"give --{grid} or --{grid}-range, not both")
        if given is not None or rng is not None:
            values.pop(grid, None)
            values.pop(f"{grid}_range", None)
        if given is not None:
            values[grid] = given
        if rng is not None:
            values[f"{grid}_range"] = [rng[0], rng[1], int(rng[2]) if float(rng[2]).is_integer() else rng[2]]
    for key in ("kz", "Pi", "drag", "window", "initial", "metric", "rtol", "atol", "chunk", "times"):
        v = getattr(args, key)
        if v is not None:
            values[key] = tuple(v) if key == "window" else v
    if args.t_end is not None:
        values["t_end"] = _t_end(args.t_end)
    return spec_from_mapping(values, "sweep")


def main(args) -> int:
    from ..linear.sweep_run import open_executor, run_sweep

    spec = build_spec(args)  # every input checked before anything is written
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    h5 = out / "sweep.h5"
    if h5.exists() and not args.overwrite:
        raise UserError(f"{h5} exists: choose another --output or pass --overwrite")
    log = lambda msg: print(msg, file=sys.stderr)  # noqa: E731
    with open_executor(args.executor, workers=args.workers, scheduler=args.scheduler,
                       timeout=args.scheduler_timeout) as ex:
        out.mkdir(parents=True, exist_ok=True)
        t0 = time.perf_counter()
        result = run_sweep(spec, h5, executor=ex, progress=not args.no_progress, overwrite=args.overwrite, log=log)
        wall = time.perf_counter() - t0
    paths = [h5]
    if not args.no_plots:
        from ..reproduce._linear_plots import plot_sweep

        paths += plot_sweep(result, out)
    pref = result.preferred()
    failed = int(result["failed"].sum())
    print(f"{spec.size} waves ({' x '.join(map(str, spec.shape))} in mu, taus, kx0, ky) in {wall:.1f} s "
          f"({args.executor}); failed: {failed}")
    import numpy as np

    v = pref["value"]
    if np.isfinite(v).any():
        i, j = np.unravel_index(np.nanargmax(v), v.shape)
        print(f"largest {spec.metric} {v[i, j]:.6g} at mu = {spec.mu[i]:g}, taus = {spec.taus[j]:g}: "
              f"K_x0 = {pref['kx0'][i, j]:g}, K_y = {pref['ky'][i, j]:g}, angle arctan(K_y/K_x(t_end)) = "
              f"{pref['angle_deg'][i, j]:.2f} deg" + (" -- on the edge of the (K_x0, K_y) grid: the preferred wave may "
                                                     "lie outside it" if pref["at_edge"][i, j] else ""))
    edges = int(pref["at_edge"].sum())
    if edges:
        print(f"{edges} of {pref['at_edge'].size} (mu, taus) have their maximum on the edge of the (K_x0, K_y) grid",
              file=sys.stderr)
    print("wrote " + ", ".join(str(p) for p in paths), file=sys.stderr)
    return 0
