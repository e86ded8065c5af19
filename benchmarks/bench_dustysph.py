"""Throughput of dusty SPH on Phantom's 3D dustywave: two-fluid and one-fluid.

The problem is ``dustywave-3d``, Phantom's default dustywave set-up: a linear sound wave along x in
a periodic 3D box of 64 x 12 x 12 hexagonal-close-packed gas particles with a dust particle on each
(9216 gas + 9216 dust), rho_g = rho_d = 1, isothermal c_s = 1, K = 1000, quintic kernel with
h_fact = 1, explicit drag (dt <= 0.9 t_s), projected drag with the Price & Laibe (2020) velocity
reconstruction (MC limiter, Phantom's default). A step is everything ``SPHEngine.timestep()`` and
``SPHEngine.advance()`` do: gas and dust neighbour searches and densities, pressure forces, both
species' velocity gradients, both drag sums, time-step criteria, kicks and drift. Throughput =
particles (gas + dust) x steps / wall time.

The one-fluid line is the same wave with mixture particles (9216, terminal-velocity dust,
upwind exchange), for comparison: its steps are limited by the Courant condition instead of
t_s, so per unit of simulated time it is far cheaper.

Anchors (the project's reference figures: Phantom v2026.0.1, gfortran -O3 -fopenmp, an earlier machine): the
two-fluid dustywave at 31.4k particle-updates/s on one thread and 62.3k on two. Target:
>= 2x Phantom on one thread (62.8k/s); aim 4x (125.6k/s).

Run alone: ``flock benchmarks/.lock python benchmarks/bench_dustysph.py``.
"""

from __future__ import annotations

import os
import sys

import numba
from _timing import interleaved_step_rates

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "src"))

from dustygas.problems import get_problem  # noqa: E402

# Phantom, two-fluid dustywave, particle-updates/s (reference figures of an earlier machine)
PHANTOM = {1: 31_400.0, 2: 62_300.0}
TARGET_VS_PHANTOM = 2.0
AIM_VS_PHANTOM = 4.0


def build(*overrides):
    prob = get_problem("dustywave-3d")
    return prob.build(prob.config(overrides=list(overrides)))


def throughput(overrides: tuple[str, ...], thread_counts: tuple[int, ...], steps: int, repeats: int):
    """Particle count and particle-updates/s (best, median) per thread count."""
    eng = build(*overrides)
    n = len(eng.particles)
    return n, interleaved_step_rates(eng, thread_counts, steps, repeats, updates_per_step=n)


def main() -> None:
    print(f"load average (1 min) before: {os.getloadavg()[0]:.2f}; cores: {os.cpu_count()}; "
          f"numba threads available: {numba.config.NUMBA_NUM_THREADS}")
    counts = tuple(t for t in (1, 2) if t <= numba.config.NUMBA_NUM_THREADS)
    n, rates = throughput(("dust.method=two-fluid",), counts, steps=5, repeats=7)
    print(f"two-fluid dustywave-3d ({n} particles, MC reconstruction, explicit drag):")
    for threads, (best, median) in rates.items():
        ratio = best / PHANTOM[threads]
        print(f"  {threads} thread(s): best {best:,.0f} particle-updates/s, median {median:,.0f} "
              f"({1e3 * n / best:.0f} ms/step); {ratio:.2f}x Phantom ({PHANTOM[threads]:,.0f}/s)")
    one = rates[1][0] / PHANTOM[1]
    verdict = "met" if one >= TARGET_VS_PHANTOM else "NOT met"
    print(f"  target >= {TARGET_VS_PHANTOM:g}x Phantom on one thread: {verdict} ({one:.2f}x; aim {AIM_VS_PHANTOM:g}x)")
    if 2 in rates:
        print(f"  two threads / one: {rates[2][0] / rates[1][0]:.2f} best, {rates[2][1] / rates[1][1]:.2f} median")
    n1, rates1 = throughput(("dust.method=one-fluid", "dust.model=terminal-velocity"), counts, steps=10, repeats=5)
    print(f"one-fluid dustywave-3d ({n1} mixture particles, terminal velocity, upwind):")
    for threads, (best, median) in rates1.items():
        print(f"  {threads} thread(s): best {best:,.0f} particle-updates/s, median {median:,.0f}")
    eng2, eng1 = build("dust.method=two-fluid"), build("dust.method=one-fluid", "dust.model=terminal-velocity")
    dt2, dt1 = eng2.timestep(), eng1.timestep()
    cost = (n / rates[1][0] / dt2) / (n1 / rates1[1][0] / dt1)
    print(f"  steps: two-fluid dt = {dt2:.3g} (0.9 t_s), one-fluid dt = {dt1:.3g} (Courant); one thread, "
          f"per unit simulated time the one-fluid run is {cost:.0f}x cheaper (Phantom: about 20x)")
    print(f"load average (1 min) after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
