"""``dustygas linear``: streaming-instability eigenmodes, growth-rate maps and shearing waves."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

from ..errors import UserError

HELP = "linear streaming-instability theory: eigenmodes, growth-rate maps, shearing waves and their sweeps"
DESCRIPTION = """Linear theory of the streaming instability (thesis §4.1, §4.6).

  dustygas linear mode --taus 0.1 --mu 3 --kx 30 --kz 30 --drag yj07      YJ07 linA
  dustygas linear mode --taus 0.0425 0.1 --mu 1 0.5 --kx 50 --kz 50       two species (BKP19 linC)
  dustygas linear map -o out --n 60                                        YG05-style map
  dustygas linear shear --taus 0.1 --mu 3 --kx -30 --ky 1 --kz 30 -o out   one swing
  dustygas linear sweep --mu 0.1 1 --taus 0.1 1 --kx -100 -1 --ky 1 100 -o out   (mu, tau_s, kx, ky) sweep
  dustygas linear angle runs/si3d --sweep out/sweep.h5                     theta_k(t) of a run vs the sweep

Conventions: x radial, y azimuthal, z vertical, Omega = 1, shear -(3/2) x y_hat;
perturbations ~ exp(i k.x - i omega t), growth rate = Im omega. Velocities in eta v_K,
wavenumbers K = k eta r, tau_s = Omega t_s, mu = rho_p0/rho_g0 the dust-to-gas ratio (YJ07's
epsilon; --eps is an alias of --mu), Pi = eta v_K / c_s (0: incompressible limit)."""

MODE_EPILOG = """JSON output (--json): an object with
  growth_rate   Im omega (units of Omega)
  frequency     Re omega (standard convention; YJ07 print the opposite sign)
  omega         [Re, Im]
  eigenvector   {name: [Re, Im]} with names drho_g, ux, uy, uz (gas) and drho_p, wx, wy, wz
                (dust; with several species drho_p_0, wx_0, ..., drho_p_1, ...), densities
                relative to their background, velocities in eta v_K, normalised so that
                drho_p (species 0) = 1
  params        taus, mu, kx, ky, kz, Pi, drag, vz as used
  conventions   the line above"""


def _species(values, name):
    if values is None:
        raise UserError(f"--{name} is required")
    return values[0] if len(values) == 1 else values


def _common(p: argparse.ArgumentParser, ky: bool = False) -> None:
    p.add_argument("--taus", type=float, nargs="+", metavar="TAU", help="stopping time(s) tau_s = Omega t_s (> 0)")
    p.add_argument("--mu", "--eps", dest="mu", type=float, nargs="+", metavar="MU",
                   help="dust-to-gas ratio(s) mu = rho_p/rho_g, one per species (YJ07's epsilon; --eps is an alias)")
    p.add_argument("--drag", default="consistent", metavar="NAME",
                   help="drag linearisation: consistent (default), yj07, epstein")
    p.add_argument("--pi", type=float, default=0.05, metavar="PI", help="Pi = eta v_K/c_s (default 0.05; 0: incompressible)")


def add_arguments(p: argparse.ArgumentParser) -> None:
    sub = p.add_subparsers(dest="linear_command", metavar="SUBCOMMAND")
    m = sub.add_parser("mode", help="fastest eigenmode for one parameter set", epilog=MODE_EPILOG,
                       formatter_class=argparse.RawDescriptionHelpFormatter,
                       description="Growth rate, frequency and labelled eigenvector of the fastest-growing mode.")
    _common(m)
    m.add_argument("--kx", type=float, required=True, help="radial wavenumber K_x = k_x eta r")
    m.add_argument("--kz", type=float, required=True, help="vertical wavenumber K_z = k_z eta r")
    m.add_argument("--vz", default="0", metavar="V",
                   help="vertical dust drift in eta v_K (negative = down), or 'settling' (thesis eq. 4.19)")
    m.add_argument("--all", action="store_true", help="also list every eigenvalue")
    m.add_argument("--json", action="store_true", help="machine-readable output (keys below)")

    g = sub.add_parser("map", help="growth-rate map over (mu, tau_s), maximised over k; writes HDF5 + PNG",
                       description="Fastest growth over a log grid of (mu, tau_s), maximised over wavenumber; "
                       "writes DIR/growth_map.h5, DIR/growth_map.json and DIR/growth_map.png.")
    g.add_argument("--method", default="kx", help="kx (max over K_x at fixed K_z), box (2D), angle (|K| at theta)")
    g.add_argument("--mu-range", type=float, nargs=2, default=(0.01, 10.0), metavar=("MIN", "MAX"))
    g.add_argument("--taus-range", type=float, nargs=2, default=(1e-3, 3.0), metavar=("MIN", "MAX"))
    g.add_argument("--n", type=int, default=60, help="grid points per axis (default 60)")
    g.add_argument("--kz", type=float, default=1000.0, help="fixed K_z for --method kx (default 1000)")
    g.add_argument("--kx-range", type=float, nargs=2, default=(1.0, 1e5), metavar=("MIN", "MAX"))
    g.add_argument("--kz-range", type=float, nargs=2, default=(1.0, 1e4), metavar=("MIN", "MAX"))
    g.add_argument("--k-range", type=float, nargs=2, default=(1e-2, 1e5), metavar=("MIN", "MAX"))
    g.add_argument("--theta", type=float, default=30.0, help="theta_k = atan(K_x/K_z) in degrees for --method angle")
    g.add_argument("--vz", default="0", metavar="V", help="vertical dust drift (eta v_K) or 'settling'")
    g.add_argument("--mirror", action="store_true", help="also try -K_z and keep the faster mode")
    g.add_argument("--drag", default="consistent", metavar="NAME", help="consistent (default), yj07, epstein")
    g.add_argument("--pi", type=float, default=0.05, metavar="PI", help="Pi = eta v_K/c_s (default 0.05)")
    g.add_argument("-o", "--output", default="linear_map", metavar="DIR", help="output directory")

    s = sub.add_parser("shear", help="integrate one non-axisymmetric shearing wave; writes CSV + PNG",
                       description="Integrate a shearing wave with k_x(t) = k_x0 + 1.5 k_y t; writes "
                       "DIR/shearing_wave.csv and DIR/shearing_wave.png and prints the amplification.")
    _common(s)
    s.add_argument("--kx", type=float, required=True, help="initial radial wavenumber K_x0")
    s.add_argument("--ky", type=float, required=True, help="azimuthal wavenumber K_y")
    s.add_argument("--kz", type=float, default=0.0, help="vertical wavenumber K_z (default 0)")
    s.add_argument("--t-end", default="swing", metavar="T",
                   help="end time in 1/Omega, or 'swing' (default: until K_x = -K_x0 for a leading wave)")
    s.add_argument("--initial", default="fastest", help="fastest (instantaneous eigenmode) or dust")
    s.add_argument("--method", default="LSODA", help="solve_ivp method (LSODA, BDF, Radau, RK45, DOP853)")
    s.add_argument("-o", "--output", default="linear_shear", metavar="DIR", help="output directory")

    from ._linear_sweep import SWEEP_DESCRIPTION, add_sweep_arguments

    w = sub.add_parser("sweep", help="shearing-wave amplification over a (mu, tau_s, kx0, ky) grid; HDF5 + PNG",
                       description=SWEEP_DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_sweep_arguments(w)

    from ._linear_angle import ANGLE_DESCRIPTION, add_angle_arguments

    a = sub.add_parser("angle", help="theta_k(t) of a run's dust surface density next to a sweep's prediction",
                       description=ANGLE_DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_angle_arguments(a)


def _vz(text: str):
    if text == "settling":
        return "settling"
    try:
        return float(text)
    except ValueError:
        raise UserError(f"--vz {text!r}: a number (eta v_K, negative = down) or 'settling'") from None


def _params(args, **k):
    from ..linear import StreamingParams

    return StreamingParams(taus=_species(args.taus, "taus"), mu=_species(args.mu, "mu"), Pi=args.pi,
                           drag=args.drag, **k)


def _pair(z: complex) -> list[float]:
    return [float(z.real), float(z.imag)]


def _mode(args) -> int:
    from ..linear import eigenmodes

    p = _params(args, kx=args.kx, kz=args.kz, vz=_vz(args.vz))
    modes = eigenmodes(p)
    m = modes.mode(0)
    names = ["drho_g", "ux", "uy", "uz"]
    for j in range(p.nspecies):
        sfx = f"_{j}" if p.multi else ""
        names += [f"drho_p{sfx}", f"wx{sfx}", f"wy{sfx}", f"wz{sfx}"]
    vec = dict(zip(names, m.vector))
    if args.json:
        out = {
            "growth_rate": m.growth_rate,
            "frequency": m.frequency,
            "omega": _pair(m.omega),
            "eigenvector": {k: _pair(v) for k, v in vec.items()},
            "params": {"taus": p.taus, "mu": p.mu, "kx": p.kx, "ky": p.ky, "kz": p.kz, "Pi": p.Pi, "drag": p.drag,
                       "vz": p.vz_array.tolist()},
            "conventions": "exp(i k.x - i omega t); growth_rate = Im omega; velocities in eta v_K; "
                           "K = k eta r; densities relative, drho_p(species 0) = 1",
        }
        if args.all:
            out["all_omega"] = [_pair(w) for w in modes.omega]
        print(json.dumps(out, indent=1))
        return 0
    print(f"growth rate  s = Im omega = {m.growth_rate:+.10f} Omega")
    print(f"frequency      Re omega = {m.frequency:+.10f} Omega  (standard convention)")
    print(f"drag: {p.drag}, Pi = {p.Pi:g}, vz = {', '.join(f'{v:g}' for v in p.vz_array)} eta v_K")
    print("eigenvector (densities relative to background, velocities in eta v_K):")
    for k, v in vec.items():
        print(f"  {k:<9} {v.real:+.7f} {v.imag:+.7f}i")
    if args.all:
        print("all eigenvalues omega (fastest first):")
        for w in modes.omega:
            print(f"  {w.real:+.8e} {w.imag:+.8e}i")
    return 0


def _map(args) -> int:
    import numpy as np

    from ..linear.maps import growth_map
    from ..reproduce._linear_plots import plot_growth_map

    if args.n < 2:
        raise UserError("--n must be >= 2")
    for name, (lo, hi) in (("--mu-range", args.mu_range), ("--taus-range", args.taus_range)):
        if not (0 < lo < hi):
            raise UserError(f"{name} {lo:g} {hi:g}: expected 0 < MIN < MAX")
    mu = np.logspace(math.log10(args.mu_range[0]), math.log10(args.mu_range[1]), args.n)
    taus = np.logspace(math.log10(args.taus_range[0]), math.log10(args.taus_range[1]), args.n)
    gm = growth_map(mu=mu, taus=taus, method=args.method, kz=args.kz, kx_range=args.kx_range, kz_range=args.kz_range,
                    k_range=args.k_range, theta_deg=args.theta, Pi=args.pi, drag=args.drag, vz=_vz(args.vz),
                    mirror=args.mirror)
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    out.mkdir(parents=True, exist_ok=True)
    paths = [gm.save(out / "growth_map.h5"), gm.save(out / "growth_map.json"),
             plot_growth_map(gm, out / "growth_map.png", "Fastest streaming-instability growth")]
    i, j = np.unravel_index(np.nanargmax(gm.growth), gm.growth.shape)
    print(f"max growth {gm.growth[i, j]:.6g} Omega at mu = {mu[j]:.4g}, taus = {taus[i]:.4g} "
          f"(Kx = {gm.kx[i, j]:.4g}, Kz = {gm.kz[i, j]:.4g})")
    print("wrote " + ", ".join(str(p) for p in paths), file=sys.stderr)
    return 0


def _shear(args) -> int:
    from ..linear.shearing_wave import shearing_wave
    from ..reproduce._linear_plots import pyplot, write_csv

    p = _params(args, kx=args.kx, kz=args.kz, ky=args.ky)
    if args.t_end == "swing":
        span = None
    else:
        try:
            span = (0.0, float(args.t_end))
        except ValueError:
            raise UserError(f"--t-end {args.t_end!r}: a time in 1/Omega or 'swing'") from None
    w = shearing_wave(p, span, initial=args.initial, method=args.method)
    out = Path(args.output)
    if out.exists() and not out.is_dir():
        raise UserError(f"--output {out}: exists and is not a directory")
    out.mkdir(parents=True, exist_ok=True)
    cols = {"t": w.t, "kx": w.kx}
    for name in w.labels:
        cols[f"abs_{name}"] = w.amplitude(name)
    cols["energy"] = w.energy
    header = [f"shearing wave: taus={p.taus}, mu={p.mu}, kx0={p.kx:g}, ky={p.ky:g}, kz={p.kz:g}, Pi={p.Pi:g}, "
              f"drag={p.drag}", "kx(t) = kx0 + 1.5 ky t (shear -(3/2) Omega x y_hat); times in 1/Omega",
              f"dust-density amplification {w.amplification:.8g}, energy amplification {w.energy_amplification:.8g}"]
    csv_path = write_csv(out / "shearing_wave.csv", cols, header)
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.4), constrained_layout=True)
    for name in ("drho_p_0", "drho_g", "ux", "uy"):
        ax.semilogy(w.t, w.amplitude(name), label=name)
    ax.set_xlabel(r"time $t\,\Omega$")
    ax.set_ylabel("amplitude (relative density, velocity in $\\eta v_K$)")
    ax.legend()
    ax.set_title(f"shearing wave $K_{{x0}}$={p.kx:g}, $K_y$={p.ky:g}, $K_z$={p.kz:g}; "
                 f"$G_\\rho$={w.amplification:.4g}", fontsize=9)
    png = out / "shearing_wave.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    print(f"dust-density amplification {w.amplification:.8g}  energy amplification {w.energy_amplification:.8g}  "
          f"t = {w.t[0]:g} .. {w.t[-1]:g}")
    print(f"wrote {csv_path}, {png}", file=sys.stderr)
    return 0


def main(args: argparse.Namespace) -> int:
    cmd = getattr(args, "linear_command", None)
    if cmd == "mode":
        return _mode(args)
    if cmd == "map":
        return _map(args)
    if cmd == "shear":
        return _shear(args)
    if cmd == "sweep":
        from ._linear_sweep import main as sweep_main

        return sweep_main(args)
    if cmd == "angle":
        from ._linear_angle import main as angle_main

        return angle_main(args)
    raise UserError("linear: choose a subcommand: mode, map, shear, sweep or angle (see dustygas linear --help)")
