"""Bad set-ups stop with one line and a dump; run loop, restarts and the CLI."""

import numpy as np
import pytest

from dustygas import api
from dustygas.errors import SetupError, SimulationError
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory
from dustygas.runner import run_engine
from dustygas.sph import Box, EquationOfState, ParticleSet, SPHEngine

from foundation._cli import cli
from ._run import build


def _crash(path):
    arrays, attrs = read_h5(RunDirectory(path).crash_file)
    return arrays, attrs


def test_overlapping_particles_stop_with_a_dump(tmp_path):
    """Two particles moved onto each other: SimulationError naming them, crash.h5 holds their indices."""
    prob, cfg, eng = build("sph-sod", "problem.nx=32")
    eng.particles.pos[7] = eng.particles.pos[3]
    with pytest.raises(SimulationError, match=r"sit exactly on top of another \(first: 3 and 7\)") as err:
        run_engine(eng, cfg, tmp_path / "run")
    assert "\n" not in str(err.value)
    arrays, attrs = _crash(tmp_path / "run")
    assert sorted(arrays["offending/overlapping"].tolist()) == [3, 7]
    assert "on top of another" in attrs["error"] and "state/particles/pos" in arrays


def test_nan_in_the_state_stops_with_a_dump(tmp_path):
    """A NaN thermal energy is caught before it spreads; the dump names the particle."""
    prob, cfg, eng = build("sph-sod", "problem.nx=32")
    eng.particles.u[11] = np.nan
    with pytest.raises(SimulationError, match="thermal energy for 1 particles"):
        run_engine(eng, cfg, tmp_path / "run")
    arrays, _ = _crash(tmp_path / "run")
    assert arrays["offending/particles"].tolist() == [11]


def test_unstable_time_step_stops_instead_of_continuing(tmp_path):
    """A fixed step 30x the Courant limit: the run stops on the first invalid state (one line, dump)
    rather than writing NaNs (the last snapshot before the stop is finite)."""
    with pytest.raises(SimulationError) as err:
        api.run("sph-sod", output=tmp_path / "run", set=["problem.nx=64", "sph.fixed_dt=0.01", "run.tlim=0.2"])
    assert "\n" not in str(err.value)
    assert RunDirectory(tmp_path / "run").crash_file.exists()
    for snap in RunDirectory(tmp_path / "run").snapshots():
        arrays, _ = read_h5(snap)
        assert np.all(np.isfinite(arrays["vel"])) and np.all(np.isfinite(arrays["u"]))


def test_h_iteration_failure_via_cli(tmp_path):
    """CLI: a smoothing-length iteration that cannot converge exits with status 3, one line on
    stderr, and crash.h5 in the run directory."""
    res = cli("run", "sph-sod", "-o", "run", "--set", "problem.nx=16", "--set", "sph.h_max_iterations=1",
              "--set", "sph.h_tolerance=1e-12", cwd=tmp_path)
    assert res.returncode == 3, res.stderr
    lines = [l for l in res.stderr.splitlines() if l.strip()]
    assert len(lines) == 1 and "did not converge" in lines[0]
    assert (tmp_path / "run" / "crash.h5").exists()


def test_bad_configuration_writes_nothing(tmp_path):
    res = cli("run", "sph-soundwave", "-o", "run", "--set", "sph.kernel=gaussian", cwd=tmp_path)
    assert res.returncode == 2 and "sph.kernel" in res.stderr and not (tmp_path / "run").exists()


def test_non_finite_initial_conditions_are_a_setup_error():
    pos = np.zeros((4, 1))
    pos[:, 0] = [0.1, 0.3, np.inf, 0.7]
    with pytest.raises(SetupError, match="initial pos of particle 2 is not finite"):
        SPHEngine(ParticleSet.create(pos, mass=0.25, h=0.3), Box.periodic_box(1, (0.0,), (1.0,)),
                  EquationOfState.isothermal(1.0))


def test_restart_is_bit_identical(tmp_path):
    """A Sod run stopped after 15 steps and restarted from its checkpoint ends with snapshots and
    history identical, bit for bit, to an uninterrupted run."""
    args = ["problem.nx=32", "run.tlim=0.1", "run.dt_snapshot=0.025"]
    api.run("sph-sod", output=tmp_path / "ref", set=args)
    stopped = api.run("sph-sod", output=tmp_path / "cut", set=args + ["run.max_cycles=15"])
    assert stopped.status == "max_cycles"
    api.restart(tmp_path / "cut", set=["run.max_cycles=0"])
    ref, cut = RunDirectory(tmp_path / "ref"), RunDirectory(tmp_path / "cut")
    for a, b in zip(ref.snapshots() + [ref.history_file], cut.snapshots() + [cut.history_file]):
        xa, _ = read_h5(a)
        xb, _ = read_h5(b)
        assert xa.keys() == xb.keys()
        for key in xa:
            np.testing.assert_array_equal(xa[key], xb[key], err_msg=f"{a.name}:{key}")
    hist, _ = read_h5(ref.history_file)
    assert {"mass", "momentum_x", "angular_momentum_z", "kinetic_energy", "total_energy"} <= set(hist)


def test_run_reports_particle_updates(tmp_path):
    res = api.run("sph-soundwave", output=tmp_path / "r", set=["run.tlim=0.05"])
    assert res.status == "finished" and res.work_label == "particle-updates" and res.throughput > 0
    assert res.engine.work_units == 64
