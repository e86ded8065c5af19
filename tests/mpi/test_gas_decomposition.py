"""The grid engine on 2 and 4 MPI ranks gives the serial run bit for bit.

Each case is stepped serially in this process and on N ranks by ``mpiexec`` (``_box.py``); the
final density and velocities and every history row must be identical, except the boundary
budgets (``radial_boundary_mass``, ``momentum_y_source``: sums over blocks, added in rank
order), which agree to round-off: measured 2e-19 on values of 1e-3 after 6 steps, asserted to
1e-14 relative.
"""

import numpy as np
import pytest

from . import _box

BUDGETS = {"radial_boundary_mass", "momentum_y_source"}

CASES = [
    pytest.param("periodic2d", 2, None, marks=pytest.mark.slow),  # chosen layout: y split
    ("periodic2d", 4, (2, 2, 1)),  # x and y split, corners through two exchanges
    ("shear3d", 2, None),  # z split under shear-periodic x
    pytest.param("shear3d", 4, (1, 1, 4), marks=pytest.mark.slow),
    ("shear3d-open", 2, None),  # orbital advection, vertical gravity, outflow z: physical ends
    ("walls3d", 4, (2, 2, 1)),  # reflecting x walls and outflow y on split axes
    # hydrostatic z faces on the end blocks, a middle block between two neighbours (the si3d tests split them too)
    pytest.param("strat3d", 3, None, marks=pytest.mark.slow),
]


IDS = ["periodic2d-2", "periodic2d-4", "shear3d-2", "shear3d-4", "shear3d-open-2", "walls3d-4", "strat3d-3"]


@pytest.mark.parametrize("case, nranks, layout", CASES, ids=IDS)
def test_ranks_reproduce_serial(case, nranks, layout, mpirun, tmp_path):
    steps = 8
    serial = _box.run(case, steps)
    out = tmp_path / "ranks.npz"
    args = [_box.__file__, case, steps, out] + (list(layout) if layout else [])
    proc = mpirun(nranks, *args)
    assert proc.returncode == 0, proc.stderr[-2000:]
    ranks = np.load(out)
    assert float(ranks["t"]) == serial["t"]
    for field in ("rho", "vx", "vy", "vz"):
        np.testing.assert_array_equal(ranks[field], serial[field], err_msg=field)
    assert list(ranks["names"]) == list(serial["names"])
    for col, name in enumerate(serial["names"]):
        a, b = serial["history"][:, col], ranks["history"][:, col]
        if name in BUDGETS:
            np.testing.assert_allclose(b, a, rtol=1e-14, atol=1e-14 * np.max(np.abs(a)), err_msg=name)
        else:
            np.testing.assert_array_equal(b, a, err_msg=name)
