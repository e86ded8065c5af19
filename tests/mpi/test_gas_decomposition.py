"""The grid engine on 2, 3 and 4 MPI ranks gives the serial run bit for bit.

Each case is stepped serially in this process and on N ranks by ``mpiexec`` (``_box.py``); the
final density and velocities and every history row must be identical -- the boundary budgets
(``radial_boundary_mass``, ``momentum_y_source``, ``gas_mass_lost_*``) too: they are running
totals per z plane, row of cells or face cell (:mod:`dustygas.grid.budget`), each added to by
the one block that holds it, whatever the layout splits (z under shear-periodic x; y and z in
``rotating3d``). A checkpoint written on 2 ranks continues on 1 and on 4 as the uninterrupted
serial run does, budgets included.
"""

import numpy as np
import pytest

from . import _box

CASES = [
    pytest.param("periodic2d", 2, None, marks=pytest.mark.slow),  # chosen layout: y split
    ("periodic2d", 4, (2, 2, 1)),  # x and y split, corners through two exchanges
    ("shear3d", 2, None),  # z split under shear-periodic x
    pytest.param("shear3d", 4, (1, 1, 4), marks=pytest.mark.slow),
    ("shear3d-open", 2, None),  # orbital advection, vertical gravity, outflow z: physical ends
    ("walls3d", 4, (2, 2, 1)),  # reflecting x walls and outflow y on split axes
    ("rotating3d", 4, (1, 2, 2)),  # the y-momentum source and z-face budgets with y and z split
    # hydrostatic z faces on the end blocks, a middle block between two neighbours (the si3d tests split them too)
    pytest.param("strat3d", 3, None, marks=pytest.mark.slow),
]


IDS = ["periodic2d-2", "periodic2d-4", "shear3d-2", "shear3d-4", "shear3d-open-2", "walls3d-4", "rotating3d-4",
       "strat3d-3"]


def assert_same(ranks, serial, first_row: int = 0) -> None:
    """Final fields and history rows ``first_row ..`` of the serial run, bit for bit."""
    assert float(ranks["t"]) == serial["t"]
    for field in ("rho", "vx", "vy", "vz"):
        np.testing.assert_array_equal(ranks[field], serial[field], err_msg=field)
    assert list(ranks["names"]) == list(serial["names"])
    for col, name in enumerate(serial["names"]):
        np.testing.assert_array_equal(ranks["history"][:, col], serial["history"][first_row:, col], err_msg=name)


@pytest.mark.parametrize("case, nranks, layout", CASES, ids=IDS)
def test_ranks_reproduce_serial(case, nranks, layout, mpirun, tmp_path):
    steps = 8
    serial = _box.run(case, steps)
    out = tmp_path / "ranks.npz"
    args = [_box.__file__, case, steps, out] + (list(layout) if layout else [])
    proc = mpirun(nranks, *args)
    assert proc.returncode == 0, proc.stderr[-2000:]
    ranks = np.load(out)
    assert_same(ranks, serial)
    if case in ("shear3d-open", "rotating3d"):  # the budgets this test is about are there, and not 0
        h = dict(zip(serial["names"], serial["history"][-1]))
        assert h["momentum_y_source"] != 0 and h["gas_mass_lost_z_lower"] != 0 and h["gas_mass_lost_z_upper"] != 0


@pytest.mark.slow  # ~30 s: three launches
def test_checkpoint_of_two_ranks_continues_on_one_and_four(mpirun, tmp_path):
    """The open shearing box (radial, y-momentum and z-face budgets): 4 steps on 2 ranks, its
    checkpoint continued for 4 steps in one process and on 4 ranks (other z cuts), against 8
    serial steps."""
    serial = _box.run("shear3d-open", 8)
    chk = tmp_path / "chk.npz"
    proc = mpirun(2, _box.__file__, "shear3d-open", 4, tmp_path / "part.npz", "--checkpoint", chk)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert_same(_box.run("shear3d-open", 4, restart=str(chk)), serial, first_row=4)
    proc = mpirun(4, _box.__file__, "shear3d-open", 4, tmp_path / "four.npz", "1", "1", "4", "--restart", chk)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert_same(np.load(tmp_path / "four.npz"), serial, first_row=4)
