"""A random particle–gas box with outflow x and z faces stepped on however many ranks launched it.

``python _pbox.py STEPS OUT``: two species (fixed and Epstein drag), random gas and particles
with velocities of 0.3 c_s, so that particles leave through the x and z faces (the box of
``tests/particles/test_conservation.py``), and a constant acceleration on the particles and on
the gas; without ``mpiexec`` the serial engine, under ``mpiexec -n N`` its
:func:`~dustygas.parallel.coupled.distribute`. Rank 0 writes the history rows and the final
particles (``.npz``).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "particles"))

from test_conservation import random_box  # noqa: E402

from dustygas.parallel import launched_under_mpi  # noqa: E402
from dustygas.particles import ConstantAcceleration, GasConstantAcceleration, VerticalGravity  # noqa: E402


def main() -> None:
    steps, out = int(sys.argv[1]), sys.argv[2]
    eng = random_box("tsc", shape=(12, 1, 24), terms=[VerticalGravity(1.0), ConstantAcceleration(0.05, 0.0, 0.02)],
                     gas_terms=[GasConstantAcceleration(0.01, 0.0, -0.02)], z_kind="outflow", particle_z="outflow",
                     x_kind="outflow", particle_x="outflow")
    if launched_under_mpi():
        from dustygas.parallel.coupled import distribute

        eng = distribute(eng)
    rows = []
    for _ in range(steps):
        eng.advance(eng.timestep())
        rows.append(eng.history())
    arrays, _ = eng.snapshot()
    if arrays:
        names = sorted(rows[0])
        np.savez(out, names=np.array(names), history=np.array([[r[k] for k in names] for r in rows]),
                 **{k.replace("/", "_"): v for k, v in arrays.items()})


if __name__ == "__main__":
    main()
