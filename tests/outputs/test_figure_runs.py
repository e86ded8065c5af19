"""The runs behind the figures (:mod:`dustygas.reproduce._runs`): a run stopped before its end is
continued from its checkpoint (not started again), a finished one is reused as it is."""

import pytest

import _toyproblem  # noqa: F401  (registers toy-oscillator)

from dustygas.errors import UserError
from dustygas.io.rundir import RunDirectory
from dustygas.reproduce._runs import finished_run, is_finished


def _end_time(path):
    cols, _ = RunDirectory(path).read_history()
    return float(cols["time"][-1])


def test_a_stopped_run_is_continued_and_a_finished_one_reused(tmp_path):
    path = tmp_path / "runs" / "toy"
    # omega dt = 0.01: 50 cycles reach t = 0.5 of tlim = 2; the stop is an error, the run is kept
    with pytest.raises(UserError, match=r"stopped \(max_cycles\) at time 0.5;"):
        finished_run("toy-oscillator", path, ["run.max_cycles=50"])
    assert not is_finished(path) and _end_time(path) == pytest.approx(0.5, abs=1e-12)
    # the next call continues it from its checkpoint: t = 1.0 (started again, it would stop at 0.5)
    with pytest.raises(UserError, match=r"at time 1;"):
        finished_run("toy-oscillator", path, ["run.max_cycles=50"])
    config = RunDirectory(path).config_file
    config.write_text(config.read_text().replace("max_cycles = 50", "max_cycles = 0"))
    assert finished_run("toy-oscillator", path) == path and is_finished(path)
    assert _end_time(path) == pytest.approx(2.0, abs=1e-12)
    log = RunDirectory(path).log_file.read_text()
    assert finished_run("toy-oscillator", path, ["run.max_cycles=50"]) == path  # reused: nothing runs
    assert RunDirectory(path).log_file.read_text() == log


def test_a_finished_run_whose_history_ends_before_tlim_is_reused(tmp_path):
    """History rows come at the run.dt_history cadence: a run to t = 1.005 with rows every 0.1 has
    its last row at t = 1.0, but ended at 1.005 with a checkpoint; it is reused, not restarted."""
    path = tmp_path / "runs" / "toy"
    finished_run("toy-oscillator", path, ["run.tlim=1.005", "run.dt_history=0.1"])
    assert _end_time(path) == pytest.approx(1.0, abs=1e-12)  # the history alone says "not there"
    assert is_finished(path)
    log, checkpoints = RunDirectory(path).log_file.read_text(), RunDirectory(path).checkpoints()
    assert finished_run("toy-oscillator", path) == path
    assert RunDirectory(path).log_file.read_text() == log and RunDirectory(path).checkpoints() == checkpoints
