"""Runs nobody can corrupt: restarts that refuse changed physics, checkpoints that survive damage,
locked run directories, disk full, wall-clock history, the wall-time exit status."""

import shutil
import signal
import time

import h5py
import numpy as np
import pytest

import _toyproblem  # noqa: F401  (registers toy-oscillator)
from _runs import assert_runs_identical, run_outputs
from dustygas import api, runner
from dustygas.errors import EXIT_WALLTIME, ConfigError, SimulationError, UserError
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory

from ._cli import cli, cli_popen

ARGS = ["run.tlim=1.0", "run.dt_checkpoint=0.25", "run.dt_snapshot=0.25"]


@pytest.fixture
def finished(tmp_path):
    """A toy run to t = 1 keeping its checkpoints at 0.5, 0.75 and the final one at 1."""
    api.run("toy-oscillator", output=tmp_path / "r", set=[*ARGS, "run.keep_checkpoints=3"])
    return tmp_path / "r"


def _edit(path, old, new):
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new))


def test_restart_refuses_changed_physics_naming_the_key(finished):
    with pytest.raises(ConfigError, match=r"--set 'problem.omega=2': a restart may change only run\.\*.*"
                                          r"problem.omega stays 1.0"):
        api.restart(finished, set=["problem.omega=2"])
    config = finished / "config.toml"
    _edit(config, "n = 16", "n = 17")
    with pytest.raises(ConfigError, match=r"problem.n = 17 differs from the checkpoint's 16"):
        api.restart(finished, set=["run.tlim=2"])
    _edit(config, "n = 17\n", "")
    with pytest.raises(ConfigError, match=r"problem.n is missing \(the checkpoint has 16\)"):
        api.restart(finished, set=["run.tlim=2"])
    _edit(config, "[problem]\n", "[problem]\nn = 16\n")
    res = api.restart(finished, set=["run.tlim=1.5"])  # run.* may change: the run goes on
    assert res.status == "finished" and res.engine.t == pytest.approx(1.5, abs=1e-12)


def test_checkpoint_of_another_version_is_refused(tmp_path, monkeypatch):
    monkeypatch.setattr(runner, "__version__", "0.0.1")
    api.run("toy-oscillator", output=tmp_path / "old", set=["run.tlim=0.1"])
    monkeypatch.undo()
    with pytest.raises(UserError, match=r"written by dustygas 0.0.1, this is"):
        api.restart(tmp_path / "old", set=["run.tlim=0.2"])


def _flip_data_bit(path, dataset="engine/x"):
    with h5py.File(path, "r") as f:
        offset = f[dataset].id.get_offset()
    data = bytearray(path.read_bytes())
    data[offset + 5] ^= 0x04  # one bit of the stored float64 values
    path.write_bytes(bytes(data))


def test_damaged_newest_checkpoint_falls_back_to_the_previous_one(tmp_path, finished, capsys):
    """Flipped bit, truncation, a directory and another run's file in place of the newest
    checkpoints: each is skipped with a warning; the run continues from chk_00001 (t = 0.5) and
    ends identical to an undamaged restart from the same checkpoint."""
    ref = tmp_path / "ref"
    shutil.copytree(finished, ref)
    for f in RunDirectory(ref).checkpoints()[1:]:
        f.unlink()
    chk = RunDirectory(finished).checkpoints()
    assert [f.name for f in chk] == ["chk_00001.h5", "chk_00002.h5", "chk_00003.h5"]
    _flip_data_bit(chk[2])
    chk[1].write_bytes(chk[1].read_bytes()[:3000])
    api.restart(finished, set=["run.tlim=1.5"])
    err = capsys.readouterr().err
    assert "skipping checkpoint chk_00003.h5: checksum mismatch" in err
    assert "skipping checkpoint chk_00002.h5: unreadable" in err and "restarting from chk_00001.h5 (time=0.5)" in err
    api.restart(ref, set=["run.tlim=1.5"])
    assert_runs_identical(run_outputs(ref), run_outputs(finished))

    # nothing usable at all: one line naming every file and why
    for f in RunDirectory(finished).checkpoints():
        f.unlink()
    (finished / "checkpoints" / "chk_00009.h5").mkdir()
    (finished / "checkpoints" / "chk_00008.h5").write_bytes(b"")
    shutil.copy(RunDirectory(finished).snapshots()[0], finished / "checkpoints" / "chk_00007.h5")
    with pytest.raises(UserError) as err:
        api.restart(finished, set=["run.tlim=2"])
    text = str(err.value)
    assert "no usable checkpoint" in text and "\n" not in text
    assert "chk_00009.h5: not a file" in text and "chk_00008.h5: unreadable" in text
    assert "chk_00007.h5: no checksum stored" in text  # a snapshot copied in: not a checkpoint


def test_live_run_directory_is_locked_and_a_dead_writer_is_taken_over(tmp_path):
    args = ["--set", "run.tlim=100", "--set", "problem.sleep=0.005", "--set", "run.dt_checkpoint=0.05"]
    proc = cli_popen("run", "toy-oscillator", "-o", "live", *args, cwd=tmp_path)
    live = tmp_path / "live"
    deadline = time.time() + 60
    while time.time() < deadline and not RunDirectory(live).checkpoints():
        time.sleep(0.02)
    assert RunDirectory(live).checkpoints(), "the live run wrote no checkpoint"
    for attempt in (lambda: api.run("toy-oscillator", output=live, overwrite=True),
                    lambda: api.restart(live)):
        with pytest.raises(UserError, match=rf"run directory {live} is being written by process {proc.pid} "):
            attempt()
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    stale = live / "snapshots" / ".snap_00099.h5.tmp4242"
    stale.write_bytes(b"half a file")
    res = api.restart(live, set=["run.tlim=" + repr(read_h5(RunDirectory(live).checkpoints()[-1])[1]["time"] + 0.05)])
    assert res.status == "finished" and not stale.exists()
    log = (live / "log.txt").read_text()
    assert f"lock of a writer that did not finish ({proc.pid} " in log, log
    assert "temporary file(s) of a dead writer: " in log and ".snap_00099.h5.tmp4242" in log, log


def test_history_is_flushed_by_wall_clock_before_any_checkpoint(tmp_path):
    """Killed after ~1 s (no checkpoint yet: checkpoint_wall = 600 s): history.h5 holds the rows
    up to the last flush (history_wall = 0.2 s), times increasing from 0."""
    proc = cli_popen("run", "toy-oscillator", "-o", "h", "--set", "run.tlim=100", "--set", "problem.sleep=0.01",
                     "--set", "run.history_wall=0.2", cwd=tmp_path)
    time.sleep(0.5)
    deadline = time.time() + 60
    hist = tmp_path / "h" / "history.h5"
    while time.time() < deadline:
        if hist.exists() and read_h5(hist)[0]["time"].size > 20:
            break
        time.sleep(0.1)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=30)
    assert not RunDirectory(tmp_path / "h").checkpoints()
    cols, _ = read_h5(hist)
    assert cols["time"][0] == 0.0 and cols["time"].size > 20 and np.all(np.diff(cols["time"]) > 0)


def test_walltime_exit_status_and_not_inherited(tmp_path, monkeypatch, capsys):
    from dustygas.cli import main

    monkeypatch.chdir(tmp_path)
    rc = main(["run", "toy-oscillator", "-q", "-o", "w", "--set", "run.tlim=0.5", "--set", "problem.sleep=0.01",
               "--walltime", "0.2"])
    assert rc == EXIT_WALLTIME == 75
    assert "stopped at the wall-clock limit (exit status 75)" in capsys.readouterr().err
    assert main(["run", "--restart", "w", "-q"]) == 0  # no --walltime: runs to tlim
    assert "finished:" in capsys.readouterr().err
    assert "walltime = 0.0" in (tmp_path / "w" / "config.toml").read_text()


DISK_FULL = """
import resource, signal, sys, _toyproblem
from dustygas.cli import main
signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past the limit fails with EFBIG, like a full disk
resource.setrlimit(resource.RLIMIT_FSIZE, (12000, 12000))
sys.exit(main(sys.argv[1:]))
"""


def test_disk_full_is_one_line_exit_3_and_leaves_no_temporary_file(tmp_path):
    """Snapshots of 2 x 16 floats fit under a 12 kB file-size limit; history.h5, written every step
    (history_wall ~ 0), outgrows it after a few hundred rows: the write fails, the run stops with
    one line naming the file, and every file left is complete."""
    import subprocess
    import sys

    from ._cli import env

    proc = subprocess.run([sys.executable, "-c", DISK_FULL, "run", "toy-oscillator", "-q", "-o", "full", "--set",
                           "run.tlim=40", "--set", "run.history_wall=1e-9"],
                          cwd=tmp_path, env=env(), capture_output=True, text=True, timeout=120)
    assert proc.returncode == 3, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in proc.stderr
    assert lines[0].startswith("dustygas: output failed: cannot write full/history.h5: File too large at time=")
    assert not [p for p in (tmp_path / "full").rglob(".*.tmp*")]
    for snap in RunDirectory(tmp_path / "full").snapshots():
        assert read_h5(snap)[0]["x"].size == 16


class _FailingEngine:
    """Raises a SimulationError that names neither time nor cycle at its third step."""

    work_units, work_label = 1, "updates"

    def __init__(self):
        self.t, self.cycle = 0.0, 0

    def timestep(self):
        return 0.1

    def advance(self, dt):
        if self.cycle == 2:
            raise SimulationError("the solver diverged")
        self.t += dt
        self.cycle += 1

    def history(self):
        return {"x": float(self.cycle)}

    def snapshot(self):
        return {"x": np.zeros(2)}, {}

    checkpoint = snapshot

    def restore(self, arrays, attrs):
        pass


def test_crash_message_carries_time_and_cycle_and_history_is_kept(tmp_path):
    from dustygas.runner import run_engine

    cfg = api.get_problem("toy-oscillator").config()
    with pytest.raises(SimulationError, match=r"^the solver diverged at time=0.2 cycle=2$"):
        run_engine(_FailingEngine(), cfg, tmp_path / "r")
    cols, _ = read_h5(tmp_path / "r" / "history.h5")
    assert cols["x"].tolist() == [0.0, 1.0, 2.0]
    assert "the solver diverged at time=0.2 cycle=2" in read_h5(tmp_path / "r" / "crash.h5")[1]["error"]


def test_compile_notice_reports_a_compilation(capsys):
    import io

    from numba import njit

    from dustygas.cli._compile_notice import compile_notice

    stream = io.StringIO()
    with compile_notice(stream=stream, every=0.01):
        njit(lambda x: x + 1)(1)  # not cached: compiled here
    text = stream.getvalue()
    assert text.startswith("dustygas: compiling numba kernels (first run of this code")
    assert "dustygas: compiled 1 kernel in" in text
