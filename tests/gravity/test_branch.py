"""``dustygas run si3d-selfgravity --from RUN``: a branch from an ``si3d`` checkpoint before the
gravity switches on is bit-identical to the run from t = 0 (history rows, the snapshots both
runs write, the final state), and every inconsistent branch is one line with exit status 2 and
writes nothing."""

import subprocess
import sys

import numpy as np
import pytest

from dustygas import api
from dustygas.cli import main
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory

GRID = ["grid.nx=8", "grid.ny=8", "grid.nz=12"]
RUN = ["run.tlim=0.08", "run.dt_snapshot=0.02", "run.dt_history=0.01", "run.threads=1"]


@pytest.fixture(scope="module")
def source(tmp_path_factory):
    """An si3d run stopped after 4 steps (its checkpoint ends a step the full run also takes)."""
    path = tmp_path_factory.mktemp("branch") / "si3d"
    res = api.run("si3d", output=path, set=GRID + RUN + ["run.max_cycles=4"])
    assert res.status == "max_cycles" and 0 < res.engine.t < 0.04
    return path


def test_branch_before_the_switch_on_equals_the_run_from_zero(source, tmp_path):
    sets = RUN + ["gravity.t_on=0.04"]
    ref = api.run("si3d-selfgravity", output=tmp_path / "ref", set=GRID + sets)
    got = api.branch("si3d-selfgravity", source, output=tmp_path / "branch", set=sets)  # grid inherited
    assert got.status == ref.status == "finished" and got.engine.cycle == ref.engine.cycle
    h_ref, _ = read_h5(RunDirectory(tmp_path / "ref").history_file)
    h_got, _ = read_h5(RunDirectory(tmp_path / "branch").history_file)
    assert h_got.keys() == h_ref.keys()
    for name in h_ref:  # the source's rows, then the branch's: every row the run from zero has
        np.testing.assert_array_equal(h_got[name], h_ref[name], err_msg=name)
    assert h_got["gravity_on"][0] == 0.0 and h_got["gravity_on"][-1] == 1.0
    ref_snaps = {float(read_h5(f)[1]["time"]): f for f in RunDirectory(tmp_path / "ref").snapshots()}
    got_snaps = RunDirectory(tmp_path / "branch").snapshots()
    t0 = float(read_h5(got_snaps[0])[1]["time"])
    assert t0 == float(read_h5(RunDirectory(source).checkpoints()[-1])[1]["engine_t"])  # the branch point
    later = got_snaps[1:]
    assert len(later) >= 2
    for f in later:  # every later snapshot is the run from zero's at the same time, bit for bit
        arrays, attrs = read_h5(f)
        ref_arrays, _ = read_h5(ref_snaps[float(attrs["time"])])
        assert arrays.keys() == ref_arrays.keys()
        for name in arrays:
            np.testing.assert_array_equal(arrays[name], ref_arrays[name], err_msg=f"{f.name}:{name}")
    assert "branched from" in (tmp_path / "branch" / "log.txt").read_text()


@pytest.mark.parametrize("args, message", [
    (["si3d-selfgravity", "--set", "gravity.t_on=0.001"], "gravity.t_on = 0.001 is before the checkpoint's time"),
    (["si3d-selfgravity", "--set", "grid.nx=16"], "--set grid.nx=16: SRC has grid.nx = 8; a branch keeps the physics"),
    (["si-linA"], "a si3d run; si-linA can start from no other problem's run"),
    (["--restart", "SRC"], "--restart DIR and --from RUN exclude each other"),
])
def test_inconsistent_branches_are_one_line_errors(source, tmp_path, capsys, args, message):
    out = tmp_path / "out"
    argv = ["run", *[a.replace("SRC", str(source)) for a in args], "--from", str(source), "-q"]
    assert main(argv + ([] if "--restart" in args else ["-o", str(out)])) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and message.replace("SRC", str(source)) in lines[0], lines
    assert not out.exists()


def test_missing_source_is_one_line_from_the_command_line(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "dustygas", "run", "si3d-selfgravity", "--from",
                           str(tmp_path / "nothing"), "-o", str(tmp_path / "out")], capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.strip().count("\n") == 0
    assert "no such run directory" in proc.stderr and not (tmp_path / "out").exists()
