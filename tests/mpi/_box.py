"""A gas box stepped on however many ranks launched it; rank 0 writes the result (``.npz``).

``python _box.py CASE STEPS OUT [PX PY PZ] [--checkpoint FILE] [--restart FILE]``: without
``mpiexec`` the plain serial :class:`~dustygas.grid.engine.GridEngine`; under ``mpiexec -n N``
the :class:`~dustygas.parallel.gas.DistributedGridEngine` (layout PX PY PZ, or chosen).
``--checkpoint`` writes the engine's checkpoint after the last step, ``--restart`` starts from
one (instead of the initial state) and takes STEPS more steps.
"""

from __future__ import annotations

import sys

import numpy as np

from dustygas.grid.engine import GridEngine
from dustygas.grid.mesh import Mesh
from dustygas.parallel import launched_under_mpi

CASES = {
    # a periodic 2D box: two oblique sound waves and a shear flow
    "periodic2d": dict(shape=(24, 24, 1), size=(1.0, 1.0, 1.0), options=dict(cfl=0.4)),
    # a 3D shearing box (shear-periodic x, periodic y and z), non-axisymmetric perturbations
    "shear3d": dict(shape=(12, 12, 24), size=(1.0, 2.0, 1.0), options=dict(
        boundaries=("shear-periodic", "periodic", "periodic"), omega=1.0, q=1.5, cfl=0.3)),
    # a rotating box with periodic x and y and outflow z faces, split in y and z (the y-momentum
    # source and the z faces' mass budgets on split axes)
    "rotating3d": dict(shape=(8, 12, 12), size=(1.0, 1.0, 1.0), options=dict(
        boundaries=("periodic", "periodic", "outflow"), omega=1.0, q=1.5, cfl=0.3)),
    # the same with orbital advection, vertical gravity and outflow z faces
    "shear3d-open": dict(shape=(12, 12, 24), size=(1.0, 2.0, 1.0), options=dict(
        boundaries=("shear-periodic", "periodic", "outflow"), omega=1.0, q=1.5, cfl=0.3,
        orbital_advection=True, vertical_gravity=True, reconstruction="ppm", integrator="rk3")),
    # a stratified column: vertical gravity, hydrostatic z faces (split in z: the end blocks fill them)
    "strat3d": dict(shape=(8, 8, 24), size=(1.0, 1.0, 3.0), options=dict(
        boundaries=("shear-periodic", "periodic", "hydrostatic"), omega=1.0, q=1.5, cfl=0.3,
        orbital_advection=True, vertical_gravity=True)),
    # reflecting x walls and outflow y on a 3D box split in x and y
    "walls3d": dict(shape=(12, 12, 6), size=(1.0, 1.0, 0.5), options=dict(
        boundaries=("reflecting", "outflow", "periodic"), cfl=0.3)),
}


def initial(mesh: Mesh) -> tuple[np.ndarray, ...]:
    x, y, z = mesh.meshgrid()
    lx, ly, lz = mesh.size
    phase = 2 * np.pi * (x / lx + 2 * y / ly + z / lz)
    rho = 1.0 + 0.1 * np.sin(phase) + 0.05 * np.cos(2 * np.pi * (x / lx - z / lz)) + 0 * (x + y + z)
    vx = 0.1 * np.sin(phase) + 0.02 * np.cos(2 * np.pi * y / ly)
    vy = 0.05 * np.cos(2 * np.pi * (x / lx + z / lz))
    vz = 0.03 * np.sin(2 * np.pi * (y / ly + x / lx)) if mesh.shape[2] > 1 else 0 * rho
    return rho, vx, vy, vz


def run(case: str, steps: int, layout: tuple[int, int, int] | None = None, checkpoint: str | None = None,
        restart: str | None = None) -> dict | None:
    """``steps`` steps of ``case`` (from the checkpoint file ``restart`` if given; the engine's
    checkpoint written to ``checkpoint`` after them); the final primitive fields and the history
    rows (None on ranks other than 0)."""
    spec = CASES[case]
    mesh = Mesh(spec["shape"], spec["size"])
    if launched_under_mpi():
        from dustygas.parallel.gas import DistributedGridEngine

        engine = DistributedGridEngine(mesh, layout=layout, **spec["options"])
    else:
        engine = GridEngine(mesh, **spec["options"])
    if restart is None:
        engine.set_primitive(*initial(mesh))
    else:
        with np.load(restart) as saved:
            arrays = {k: saved[k] for k in saved.files}
        engine.restore(arrays, {})
        engine.t, engine.cycle = float(arrays["t"]), int(arrays["cycle"])
    rows = []
    for _ in range(steps):
        engine.advance(engine.timestep())
        rows.append(engine.history())
    if checkpoint is not None:
        arrays, _ = engine.checkpoint()
        if arrays:
            np.savez(checkpoint, t=engine.t, cycle=engine.cycle, **arrays)
    arrays, _ = engine.snapshot()
    if not arrays:
        return None
    names = sorted(rows[0])
    return dict(history=np.array([[r[n] for n in names] for r in rows]), names=np.array(names), t=engine.t,
                **{k: v for k, v in arrays.items() if k in ("rho", "vx", "vy", "vz")})


def main() -> None:
    args = sys.argv[1:]
    files = {}
    for flag in ("--checkpoint", "--restart"):
        if flag in args:
            i = args.index(flag)
            files[flag[2:]] = args[i + 1]
            del args[i:i + 2]
    case, steps, out = args[0], int(args[1]), args[2]
    layout = tuple(int(p) for p in args[3:6]) if len(args) > 3 else None
    result = run(case, steps, layout, **files)
    if result is not None:
        np.savez(out, **result)


if __name__ == "__main__":
    main()
