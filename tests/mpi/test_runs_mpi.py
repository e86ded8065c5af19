"""``mpiexec -n N dustygas run``: one set of files identical to the serial run's, checkpoints that
restart on another rank count, and one-line refusals (exit 2) of what MPI cannot run."""

import os
import shutil
import subprocess
import sys

import pytest

from _runs import assert_runs_identical, run_outputs

SOUND = ["soundwave-3d", "--set", "grid.nx=12", "--set", "grid.ny=12", "--set", "grid.nz=12",
         "--set", "run.tlim=0.2", "--set", "run.dt_snapshot=0.1", "--set", "run.dt_checkpoint=0.1"]


def serial(args, cwd):
    proc = subprocess.run([sys.executable, "-m", "dustygas", "run", *args], cwd=cwd, capture_output=True, text=True,
                          env={**os.environ, "NUMBA_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr[-2000:]


@pytest.mark.slow  # 40 s on the loaded two cores: five launches
def test_two_ranks_write_the_serial_files_and_restart_on_one_and_four(mpirun, tmp_path):
    serial([*SOUND, "-o", "one"], tmp_path)
    reference = run_outputs(tmp_path / "one")
    proc = mpirun(2, "-m", "dustygas", "run", *SOUND, "-o", "two", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stderr.count("finished:") == 1  # rank 0 reports
    assert_runs_identical(run_outputs(tmp_path / "two"), reference)
    # stopped after 3 of its 11 steps on 2 ranks (checkpoint written at the stop) ...
    proc = mpirun(2, "-m", "dustygas", "run", *SOUND, "--set", "run.max_cycles=3", "-o", "part", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-2000:]
    for n in (1, 4):  # ... and continued on 1 and on 4 ranks
        shutil.copytree(tmp_path / "part", tmp_path / f"part{n}")
        proc = mpirun(n, "-m", "dustygas", "run", "--restart", f"part{n}", "--set", "run.max_cycles=0",
                       cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr[-2000:]
        assert_runs_identical(run_outputs(tmp_path / f"part{n}"), reference)


@pytest.mark.parametrize("nranks, args, message", [
    (3, ["soundwave-2d"], "mpi ranks=3: the 64 x 64 x 1 mesh has no layout of 3 equal blocks"),
    pytest.param(2, ["shearing-wave"], "x not split (shear-periodic x boundaries)", marks=pytest.mark.slow),
    pytest.param(2, ["si3d-selfgravity"], "problem si3d-selfgravity does not run on several MPI ranks yet",
                 marks=pytest.mark.slow),
    pytest.param(2, ["nsh", "--set", "grid.nz=1"], "particles split the z axis only, and this mesh has nz = 1",
                 marks=pytest.mark.slow),
], ids=["indivisible", "shear-xy", "self-gravity", "particles-2d-xy"])
def test_bad_mpi_use_is_one_line_exit_2(nranks, args, message, mpirun, tmp_path):
    proc = mpirun(nranks, "-m", "dustygas", "run", *args, "-o", "bad", cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr[-2000:]
    lines = [line for line in proc.stderr.splitlines() if line.startswith("dustygas: error:")]
    assert len(lines) == 1 and message in lines[0], proc.stderr[-2000:]
    assert "Traceback" not in proc.stderr
    assert not (tmp_path / "bad").exists()  # nothing written


def test_info_shows_ranks_and_threads(mpirun, tmp_path):
    proc = mpirun(2, "-m", "dustygas", "info", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-2000:]
    rows = [line for line in proc.stdout.splitlines() if line.startswith("MPI ranks")]
    assert rows == [rows[0]] and "2, 1 numba thread(s) each" in rows[0]  # printed once, by rank 0


def test_progress_lines_come_from_one_rank(mpirun, tmp_path):
    """Every rank takes the same steps; only the writing rank prints a progress line per step."""
    proc = mpirun(2, "-m", "dustygas", "run", *SOUND[:7], "--set", "run.max_cycles=4", "--set", "run.log_every=1",
                  "-o", "lines", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr[-2000:]
    lines = [line for line in proc.stderr.splitlines() if line.startswith("cycle=")]
    assert [line.split()[0] for line in lines] == ["cycle=1", "cycle=2", "cycle=3", "cycle=4"], proc.stderr[-2000:]

def test_one_process_run_never_imports_mpi(tmp_path):
    code = ("import sys, dustygas.api as api; api.run('soundwave', output='r', set=['run.tlim=0.05']); "
            "print('mpi4py' in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True,
                          env={**os.environ, "NUMBA_NUM_THREADS": "1"})
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert proc.stdout.split() == ["False"]
