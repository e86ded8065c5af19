"""Run loop: outputs, energy of the toy engine, restart after SIGKILL, SIGTERM and walltime."""

import signal
import time

import numpy as np
import pytest

import _toyproblem  # noqa: F401  (registers toy-oscillator)
from _runs import assert_runs_identical, run_outputs
from dustygas import api
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory

from ._cli import cli, cli_popen


def test_leapfrog_energy_and_snapshot_times(tmp_path):
    res = api.run("toy-oscillator", output=tmp_path / "r", set=["run.tlim=2.0", "problem.cfl=0.01"])
    assert res.status == "finished" and res.cycles == 200
    hist, _ = read_h5(tmp_path / "r" / "history.h5")
    e = hist["energy"]
    # leapfrog: relative energy error bounded by ~ (omega dt)^2 / 4
    assert np.max(np.abs(e / e[0] - 1)) < 0.25 * 0.01**2 * 1.01
    times = [read_h5(f)[1]["time"] for f in RunDirectory(tmp_path / "r").snapshots()]
    assert times[0] == 0.0 and times[-1] == pytest.approx(2.0, abs=1e-12)
    assert len(times) == 5


def test_sigkill_after_checkpoint_restarts_bit_identically(tmp_path):
    # >= 10 ms steps: 2 s of run after the checkpoint the kill waits for, however starved this process
    args = ["--set", "run.tlim=3.0", "--set", "run.dt_checkpoint=0.5", "--set", "run.dt_snapshot=0.25",
            "--set", "problem.sleep=0.01"]
    ref = cli_popen("run", "toy-oscillator", "-o", "ref", *args, cwd=tmp_path)
    proc = cli_popen("run", "toy-oscillator", "-o", "killed", *args, cwd=tmp_path)
    chk = tmp_path / "killed" / "checkpoints"
    deadline = time.time() + 60
    while time.time() < deadline and not list(chk.glob("chk_00001.h5")):
        time.sleep(0.01)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    assert list(chk.glob("chk_*.h5")), "no checkpoint before the kill"
    assert ref.wait(timeout=120) == 0, ref.communicate()[1]
    snaps_before = len(RunDirectory(tmp_path / "killed").snapshots())
    assert snaps_before < len(RunDirectory(tmp_path / "ref").snapshots())

    again = cli("run", "--restart", "killed", cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    assert_runs_identical(run_outputs(tmp_path / "ref"), run_outputs(tmp_path / "killed"))


def test_sigterm_writes_checkpoint_and_restart_finishes(tmp_path):
    # 300 steps of >= 10 ms: the signal lands in the run even when this process is starved for a
    # second on the loaded CI machine (with 2 ms steps it once arrived after the run had finished)
    args = ["--set", "run.tlim=3.0", "--set", "problem.sleep=0.01"]
    ref = cli_popen("run", "toy-oscillator", "-o", "ref", *args, cwd=tmp_path)
    proc = cli_popen("run", "toy-oscillator", "-o", "term", *args, cwd=tmp_path)
    snaps = tmp_path / "term" / "snapshots"
    deadline = time.time() + 60
    while time.time() < deadline and not list(snaps.glob("snap_00000.h5")):
        time.sleep(0.01)
    # at once: the handler covers the initial outputs too, not only the stepping loop
    proc.send_signal(signal.SIGTERM)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 128 + signal.SIGTERM, err
    assert "dustygas run --restart" in err
    assert RunDirectory(tmp_path / "term").checkpoints()
    assert ref.wait(timeout=120) == 0, ref.communicate()[1]
    again = cli("run", "--restart", "term", cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    assert_runs_identical(run_outputs(tmp_path / "ref"), run_outputs(tmp_path / "term"))


def test_walltime_stops_with_checkpoint(tmp_path):
    res = api.run("toy-oscillator", output=tmp_path / "w", set=["run.tlim=100.0", "problem.sleep=0.001"],
                  walltime=0.3)
    assert res.status == "walltime" and res.engine.t < 100.0
    assert RunDirectory(tmp_path / "w").checkpoints()
    res2 = api.restart(tmp_path / "w", set=["run.tlim=0.5"] if res.engine.t < 0.5 else ["run.tlim=" + repr(res.engine.t + 0.1)])
    assert res2.status == "finished"


def test_finished_run_ends_with_a_checkpoint_and_restart_extends_it(tmp_path):
    """The default run ends with a checkpoint; ``--restart --set run.tlim=T`` continues it to T, and the
    extended run's state at T agrees with the leapfrog's exact phase to O(dt^2) like a run straight to T."""
    api.run("toy-oscillator", output=tmp_path / "r", set=["run.tlim=0.5"])
    assert [p.name for p in RunDirectory(tmp_path / "r").checkpoints()] == ["chk_00000.h5"]
    again = cli("run", "--restart", "r", "--set", "run.tlim=1.0", cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    hist, attrs = read_h5(tmp_path / "r" / "history.h5")
    assert attrs["time"] == pytest.approx(1.0, abs=1e-12) and np.all(np.diff(hist["time"]) > 0)
    # x0(t) = cos(omega t) for the first oscillator; leapfrog phase error ~ t (omega dt)^2 / 24 = 4e-6
    assert hist["x0"][-1] == pytest.approx(np.cos(1.0), abs=1e-5)
    gone = tmp_path / "gone"
    api.run("toy-oscillator", output=gone, set=["run.tlim=0.1"])
    for f in RunDirectory(gone).checkpoints():
        f.unlink()
    proc = cli("run", "--restart", "gone", cwd=tmp_path)
    assert proc.returncode == 2 and "no checkpoint" in proc.stderr
