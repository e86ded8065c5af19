"""Throughput of the SPH engine: a 3D periodic box of gas, whole step counted.

The problem is the one Phantom runs with its uniform-box set-up (``setup_unifdis``, cubic lattice,
no dust), so the two codes can be timed side by side: N = n^3 equal-mass particles on a cubic
lattice in the unit box, rho = 1, adiabatic gamma = 5/3 with c_s = 1 (u = 0.9), cubic M4 kernel
with h_fact = 1.2, artificial viscosity with a switch (beta = 2, alpha_max = 1) and artificial
conductivity alpha_u = 1, Courant factor 0.3. Ours adds velocities of 1e-3 c_s so that nothing
is trivially zero. A step is one kick-drift-kick leapfrog step: neighbour search, smoothing-length
iteration, equation of state, pressure/viscosity/conductivity forces, energy equation, switch,
time-step criteria and the kicks and drift -- everything :meth:`SPHEngine.advance` and
:meth:`SPHEngine.timestep` do. Throughput is particle-updates per second = N x steps / wall.

Anchors (Phantom v2026.0.1, gfortran -O3 -fopenmp, measured on this machine; see
benchmarks/RESULTS.md for how): the same 32^3 box at 130k particle-updates/s on one thread and 267k on two;
64^3 at 134k and 242k (``PHANTOM`` below).
Targets: >= 300k particle-updates/s per thread at 32^3; two threads >= 1.8x one;
>= 2x Phantom per thread.

Run alone: ``flock benchmarks/.lock python benchmarks/bench_sph.py [n ...]``.
"""

from __future__ import annotations

import argparse
import os
import sys

import numba
import numpy as np
from _timing import interleaved_step_rates

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "src"))

from dustygas.sph import Box, EquationOfState, ParticleSet, SPHEngine, SPHOptions  # noqa: E402
from dustygas.sph.lattice import cubic_lattice  # noqa: E402

# Phantom, same box, particle-updates/s (benchmarks/RESULTS.md, 2026-11-22)
PHANTOM = {(32, 1): 130_000.0, (32, 2): 267_000.0, (64, 1): 134_000.0, (64, 2): 242_000.0}
TARGET_PER_THREAD = 300_000.0
TARGET_SPEEDUP = 1.8
TARGET_VS_PHANTOM = 2.0


def box_engine(n: int) -> SPHEngine:
    """The benchmark box with n^3 particles (module docstring)."""
    rng = np.random.default_rng(1)
    pos = cubic_lattice((n, n, n), (-0.5,) * 3, (0.5,) * 3)
    vel = rng.normal(0.0, 1e-3, pos.shape)
    p = ParticleSet.create(pos, vel, mass=1.0 / n**3, h=1.2 / n, u=0.9, alpha=0.1)
    return SPHEngine(p, Box.periodic_box(3, (-0.5,) * 3, (0.5,) * 3), EquationOfState.adiabatic(5.0 / 3.0),
                     SPHOptions(kernel="cubic", hfact=1.2))


def throughput(n: int, thread_counts: tuple[int, ...], steps: int, repeats: int = 9) -> dict[int, tuple[float, float]]:
    """Particle-updates/s (best, median) of the n^3 box for each thread count."""
    return interleaved_step_rates(box_engine(n), thread_counts, steps, repeats, updates_per_step=n**3)


def main(sizes: list[int]) -> None:
    print(f"load average (1 min) before: {os.getloadavg()[0]:.2f}; cores: {os.cpu_count()}; "
          f"numba threads available: {numba.config.NUMBA_NUM_THREADS}")
    counts = tuple(t for t in (1, 2) if t <= numba.config.NUMBA_NUM_THREADS)
    for n in sizes:
        rates = throughput(n, counts, 5 if n <= 32 else 1)
        for threads, (best, median) in rates.items():
            anchor = PHANTOM.get((n, threads))
            vs = f"{best / anchor:.2f}x Phantom" if anchor else "no Phantom anchor"
            print(f"{n}^3 box, {threads} thread(s): best {best:,.0f} particle-updates/s, median {median:,.0f} "
                  f"({best / threads:,.0f} per thread; {1e3 * n**3 / best:.1f} ms/step; {vs})")
        if n == 32:
            print(f"  target >= {TARGET_PER_THREAD:,.0f}/s per thread at 32^3: "
                  f"{'met' if rates[1][0] >= TARGET_PER_THREAD else 'NOT met'}")
        if 2 in rates:
            print(f"  two threads / one: {rates[2][0] / rates[1][0]:.2f} best, {rates[2][1] / rates[1][1]:.2f} median "
                  f"(target >= {TARGET_SPEEDUP})")
    print(f"load average (1 min) after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("sizes", nargs="*", type=int, default=[32, 64], help="lattice sizes n (n^3 particles)")
    main(parser.parse_args().sizes)
