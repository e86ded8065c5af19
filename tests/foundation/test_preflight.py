"""Checks before anything is written (dustygas.preflight): memory, the built state, cadences."""

import pytest

import _toyproblem  # noqa: F401  (registers toy-oscillator)
from dustygas import api
from dustygas.errors import ConfigError, SetupError
from dustygas.preflight import BYTES_PER_PARTICLE, GRID_BYTES_PER_CELL, grid_memory_estimate
from dustygas.problems import get_problem


def test_memory_estimate_counts_cells_and_particles():
    prob = get_problem("si-linA")
    cfg = prob.config(overrides=["grid.nx=512", "grid.nz=256", "particles.lattice=2"])
    cells = 512 * 256
    assert prob.memory_estimate(cfg) == cells * GRID_BYTES_PER_CELL + 4 * cells * BYTES_PER_PARTICLE
    assert grid_memory_estimate(get_problem("toy-oscillator").config()) is None


def test_a_grid_too_large_is_refused_before_allocation(tmp_path):
    # 1e9 x 64 cells, one particle each: 6.4e10 x (290 + 220) B = 3.26e13 B
    with pytest.raises(SetupError, match=r"si-linA: the set-up needs about 3.26e\+04 GB of memory and .* GB are "
                                         r"available: reduce the resolution"):
        api.run("si-linA", output=tmp_path / "r", set=["grid.nx=1e9"])
    assert not (tmp_path / "r").exists()


def test_a_set_up_without_estimate_still_fails_cleanly(tmp_path):
    """toy-oscillator has no estimate: 1e13 oscillators (80 TB) hit the address-space limit at once."""
    with pytest.raises(SetupError, match="needs more memory than is available"):
        api.run("toy-oscillator", output=tmp_path / "r", set=["problem.n=10000000000000"])
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("problem, override, error, message", [
    # absurd magnitudes: set-up errors
    ("si-linA", "problem.taus=1e300", SetupError, r"the set-up overflowed for these parameters \(overflow encountered"),
    ("si-linA", "problem.mu=1e300", SetupError, r"the set-up overflowed for these parameters \(overflow encountered"),
    ("si-linA", "problem.Pi=1e-300", SetupError, r"particle positions and velocities must be finite"),
    # cadences that would loop on the time resolution, and a run that never ends
    ("toy-oscillator", "run.dt_snapshot=1e-12", ConfigError,
     r"run.dt_snapshot = 1e-12 asks for 2e\+12 snapshots before tlim = 2 \(at most 100000\)"),
    ("toy-oscillator", "run.dt_history=1e-15", ConfigError, r"asks for 2e\+15 history rows"),
    ("toy-oscillator", "run.dt_checkpoint=1e-9", ConfigError, r"asks for 2e\+09 checkpoints"),
    ("toy-oscillator", "run.tlim=inf", ConfigError, r"run.tlim = inf: expected a finite number"),
])
def test_refused_before_anything_is_written(tmp_path, problem, override, error, message):
    with pytest.raises(error, match=message):
        api.run(problem, output=tmp_path / "r", set=[override])
    assert not (tmp_path / "r").exists()


class _Broken:
    """An engine whose initial state has a NaN diagnostic or an invalid time step."""

    def __init__(self, energy, dt):
        self.energy, self.dt = energy, dt

    def history(self):
        return {"mass": 1.0, "energy": self.energy}

    def timestep(self):
        return self.dt


@pytest.mark.parametrize("energy, dt, message", [
    (float("nan"), 0.1, r"the initial state is not finite \(energy=nan\)"),
    (1.0, 0.0, r"the initial time step is 0.0"),
    (1.0, float("inf"), r"the initial time step is inf"),
])
def test_initial_state_must_be_finite(energy, dt, message):
    from dustygas.preflight import check_initial_state

    with pytest.raises(SetupError, match="toy: " + message):
        check_initial_state(_Broken(energy, dt), "toy")


def test_an_invalid_gas_cell_is_reported_by_the_field_that_is_invalid():
    import numpy as np

    from dustygas.errors import SimulationError
    from dustygas.grid import GridEngine, Mesh

    eng = GridEngine(Mesh((8, 1, 1), (1.0, 1.0, 1.0)))
    eng.set_primitive(1.0, np.where(np.arange(8) == 5, np.nan, 0.1), 0.0, 0.0)
    with pytest.raises(SimulationError, match=r"cell \(i=5, j=0, k=0\) at time=0 cycle=0: vx=nan$"):
        eng.timestep()
