"""``dustygas analyze clumps RUN``: bound clumps per snapshot and the mass function."""

from __future__ import annotations

import argparse
import json

DESCRIPTION = """Find the bound clumps (planetesimals) of a run's particle snapshots.

  dustygas analyze clumps runs/si3d-selfgravity             last snapshot
  dustygas analyze clumps runs/si3d-selfgravity --all       every snapshot
  dustygas analyze clumps RUN --g-tilde 0.05 --json         a run without gravity_G; JSON out

Each analysed snapshot snapshots/snap_NNNNN.h5 gets clumps/clumps_NNNNN.h5 (mass, position,
velocity, radius, half-mass radius, particle count, Hill radius, peak density, member ids).
Cells above the threshold (default the Hill density 9 Omega^2 / (4 pi G)) seed clumps; each
grows to its Hill sphere and keeps the particles bound in the rotating frame. With at least
--min-clumps clumps the last snapshot's masses are fitted by a power law and an exponentially
truncated power law (maximum likelihood, bootstrap errors, BIC to choose).

JSON keys: snapshots [{snapshot, catalogue, time, clumps, mass_in_clumps, masses}],
mass_function {power-law, truncated-power-law: {params, errors, aic, bic, n, m_min}, preferred}."""


def add_arguments(sub: argparse._SubParsersAction) -> None:
    c = sub.add_parser("clumps", help="bound clumps per snapshot and their mass function",
                       description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    c.add_argument("run", metavar="RUN", help="run directory with particle snapshots")
    c.add_argument("--all", action="store_true", help="every snapshot (default: the last)")
    c.add_argument("--g-tilde", type=float, help="G~ = 4 pi G rho_g0 / Omega^2 (default: the snapshot's gravity_G)")
    c.add_argument("--threshold", type=float, help="seed density (default: the Hill density)")
    c.add_argument("--min-particles", type=int, default=10, help="fewest bound particles of a clump")
    c.add_argument("--z", choices=("periodic", "open"), help="vertical boundary of the particles (default: the snapshot's)")
    c.add_argument("--no-vertical-tide", action="store_true", help="leave Omega^2 z^2 / 2 out of the Jacobi energy")
    c.add_argument("--min-clumps", type=int, default=5, help="fewest clumps for a mass-function fit")
    c.add_argument("--bootstrap", type=int, default=200, help="bootstrap resamples of the fits")
    c.add_argument("--json", action="store_true", help="print one JSON object")


def main(args: argparse.Namespace) -> int:
    from ..analysis.mass_function import fit_mass_function
    from ..analysis.planetesimals import run_clumps
    from ..errors import UserError

    if args.min_particles < 1:
        raise UserError(f"--min-particles {args.min_particles}: must be at least 1")
    results = run_clumps(args.run, "all" if args.all else "last", g_tilde=args.g_tilde, threshold=args.threshold,
                         min_particles=args.min_particles,
                         periodic_z=None if args.z is None else args.z == "periodic",
                         vertical_tide=not args.no_vertical_tide)
    rows = [dict(snapshot=str(r.snapshot), catalogue=str(r.catalogue_file), time=r.time, clumps=len(r.catalogue),
                 mass_in_clumps=float(r.catalogue.mass.sum()), masses=r.catalogue.mass.tolist()) for r in results]
    last = results[-1].catalogue
    fits = None
    if len(last) >= max(args.min_clumps, 3):
        fits = fit_mass_function(last.mass, bootstrap=args.bootstrap)
    if args.json:
        mf = None
        if fits:
            mf = {k: {kk: v for kk, v in fits[k].to_dict().items() if kk != "model"}
                  for k in ("power-law", "truncated-power-law")}
            mf["preferred"] = fits["preferred"]
        print(json.dumps({"snapshots": rows, "mass_function": mf}, indent=1))
        return 0
    print(f"threshold {last.attrs['threshold']:.6g} (code density), G = {last.attrs['G']:.6g}")
    for r in rows:
        top = max(r["masses"]) if r["masses"] else 0.0
        print(f"{r['snapshot']}  t = {r['time']:.6g}  {r['clumps']} clumps, mass {r['mass_in_clumps']:.6g} "
              f"(largest {top:.6g}) -> {r['catalogue']}")
    if fits:
        pl, tr = fits["power-law"], fits["truncated-power-law"]
        print(f"power law           p = {pl.params['p']:.4f} +- {pl.errors['p']:.4f}  (n = {pl.n}, BIC {pl.bic:.2f})")
        print(f"truncated power law p = {tr.params['p']:.4f} +- {tr.errors['p']:.4f}, M_e = {tr.params['M_e']:.4g} "
              f"+- {tr.errors['M_e']:.3g}  (BIC {tr.bic:.2f})")
        print(f"preferred (BIC): {fits['preferred']}")
    elif len(last):
        print(f"mass function: {len(last)} clumps, fewer than --min-clumps {args.min_clumps}: not fitted")
    return 0
