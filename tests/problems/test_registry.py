"""Every registered problem and preset runs with its own defaults, and shows the ranges the engine enforces.

A new problem is covered the moment it is registered: each one runs three cycles through the
run loop (:func:`dustygas.api.run`, as ``dustygas run NAME`` does) with nothing but its defaults
and run-control overrides, or -- for one too large for a laptop -- with its declared
``smoke_overrides`` after its full-size defaults have been validated. Cost: about 15 s of CPU
for the 27 problems of today (the 3D SPH presets dominate).
"""

import math

import numpy as np
import pytest

from dustygas import api
from dustygas.config import describe_schema, load_toml
from dustygas.errors import ConfigError, SetupError
from dustygas.grid import GridEngine, Mesh
from dustygas.grid.integrator import courant_limit
from dustygas.grid.params import grid_ndim
from dustygas.io.rundir import RunDirectory
from dustygas.problems import get_problem, problem_names

#: cells or particles above which a problem must declare ``smoke_overrides`` (a 64^3 box)
LAPTOP_SIZE = 64**3
RUN_CONTROL = ["run.max_cycles=3", "run.checkpoint_wall=0", "run.dt_snapshot=0", "run.threads=1"]


@pytest.mark.parametrize("name", problem_names())
def test_runs_three_cycles_with_its_own_defaults(name, tmp_path):
    """The defaults validate (every bound, the ones that depend on other parameters included), the
    engine accepts them, and three steps advance the time with finite diagnostics at every step."""
    prob = get_problem(name)
    defaults = prob.config()
    res = api.run(name, output=tmp_path / "run", set=[*prob.smoke_overrides, *RUN_CONTROL, "run.dt_history=0"])
    assert res.status == "max_cycles" and res.cycles == 3, (res.status, res.cycles)
    if not prob.smoke_overrides:
        assert res.engine.work_units <= LAPTOP_SIZE, f"{name}: {res.engine.work_units} cells/particles by " \
            "default; declare smoke_overrides that shrink it for this test"
        saved = RunDirectory(res.path)
        hist, _ = saved.read_history()
        assert hist["time"].size == 4 and np.all(np.diff(hist["time"]) > 0), hist["time"]
        for key, column in hist.items():
            assert np.all(np.isfinite(column)), key
        written = load_toml(saved.config_file)
        for section in defaults:
            if section != "run":
                assert written[section] == dict(defaults[section]), section  # the run used the defaults


def _grid_problems():
    return [n for n in problem_names() if "scheme" in get_problem(n).schema and "cfl" in get_problem(n).schema["scheme"]]


def test_courant_bound_is_declared_once_and_shown():
    """``dustygas problems NAME`` shows the Courant bound the engine enforces: 1/ndim."""
    for name in _grid_problems():
        text = describe_schema(get_problem(name).schema)
        line = next(ln for ln in text.splitlines() if ln.strip().startswith("cfl "))
        assert "0 < value <= 1/ndim" in line and "<= 1)" not in line, line
    assert [courant_limit(n) for n in (1, 2, 3)] == [1.0, 0.5, 1.0 / 3.0]


@pytest.mark.parametrize("name", _grid_problems())
def test_courant_bound_is_the_one_the_engine_enforces(name):
    """At its default grid every grid problem accepts cfl = 1/ndim (configuration and engine) and
    refuses 1.001/ndim in the configuration (one line naming the key and the bound) and in the
    engine."""
    prob = get_problem(name)
    ndim = grid_ndim(prob.config())
    limit = courant_limit(ndim)
    assert prob.config(overrides=[f"scheme.cfl={limit!r}"]).scheme.cfl == limit
    with pytest.raises(ConfigError, match=rf"scheme.cfl = .* is out of range: allowed 0 < value <= 1/ndim.*here "
                                          rf"{limit:g}"):
        prob.config(overrides=[f"scheme.cfl={1.001 * limit!r}"])
    shape = (8,) * ndim + (1,) * (3 - ndim)
    GridEngine(Mesh(shape, (1.0,) * 3), cfl=limit)
    with pytest.raises(SetupError, match="stable for 0 < cfl"):
        GridEngine(Mesh(shape, (1.0,) * 3), cfl=math.nextafter(limit, 2.0))
