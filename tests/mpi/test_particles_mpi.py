"""The particle–gas engine on 2, 3 and 4 MPI ranks gives the serial run's files.

``mpiexec -n N python -m dustygas run`` of si-linA (2D x-z, periodic, 32², one particle per cell)
and si3d (8 x 8 x 16, a settled layer, with open z faces that gas and particles leave through and
in the preset's periodic box; uneven z blocks on 3 and 4 ranks) against the same run in one
process (``-n 1``): every snapshot array (gas, every particle array, the dust density) and
every history column is identical bit for bit -- the budgets too (the particle and gas terms'
impulse, the gas's radial mass, y-momentum and z-face budgets, the particles' losses): each is a
running total per row of cells held by one block and summed in a fixed order, and the
checkpoint holds the rows, so a restart on another rank count is bit for bit as well. On the
ranks' run the budgets hold to the serial tests' tolerances (``tests/particles/test_conservation.py``):
mass (with what left through the open faces) to 1e-13 (periodic) and 1e-12, the z momentum
of the unforced periodic box to 1e-12 of ``(M_gas + M_dust) η v_K``.
"""

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from _runs import run_outputs

#: the budget columns of the runs below (every one must be there: the test is about them)
BUDGETS = {"momentum_y_source", "radial_boundary_mass", "particle_terms_impulse_x", "particle_terms_impulse_y",
           "particle_terms_impulse_z"}

LINA_BOX = ["si-linA", "--set", "grid.nx=32", "--set", "grid.nz=32"]
LINA = LINA_BOX + ["--set", "run.max_cycles=30", "--set", "run.dt_history=0", "--set", "run.dt_snapshot=0.001"]
SI3D_BOX = ["si3d", "--set", "grid.nx=8", "--set", "grid.ny=8", "--set", "grid.nz=16", "--set",
            "problem.gas_boundary_z=hydrostatic"]  # open z faces: the particles leave (particles.boundary_z = auto)
SI3D_STEPS = ["--set", "run.max_cycles=30", "--set", "run.dt_history=0", "--set", "run.dt_snapshot=0.05"]
SI3D = SI3D_BOX + SI3D_STEPS


def launch(mpirun, n, args, out, cwd):
    proc = mpirun(n, "-m", "dustygas", "run", *args, "-o", out, cwd=cwd)
    assert proc.returncode == 0, proc.stderr[-3000:]
    return proc


def assert_same_run(ranks: dict, serial: dict, budgets=BUDGETS) -> None:
    """Snapshots and history bit for bit, the ``budgets`` columns among them (module doc)."""
    assert ranks.keys() == serial.keys() and len(serial) >= 3
    assert budgets <= serial["history"][0].keys()
    for key in serial:
        (a, _), (b, _) = serial[key], ranks[key]
        assert a.keys() == b.keys(), key
        for name in a:
            np.testing.assert_array_equal(np.asarray(b[name]), np.asarray(a[name]), err_msg=f"{key}:{name}")


@pytest.fixture(scope="module")
def lina_serial(mpirun, tmp_path_factory):
    cwd = tmp_path_factory.mktemp("lina")
    launch(mpirun, 1, LINA, "one", cwd)
    return cwd


@pytest.mark.parametrize("nranks", [2, pytest.param(3, marks=pytest.mark.slow), 4])
def test_si_lina_on_ranks_is_the_serial_run(nranks, mpirun, lina_serial):
    proc = launch(mpirun, nranks, LINA, f"n{nranks}", lina_serial)
    if nranks != 3:  # 32 rows in 3 blocks: uneven
        assert f"particles per rank: {' '.join([str(1024 // nranks)] * nranks)} (max/mean 1.000" in proc.stderr
    ranks = run_outputs(lina_serial / f"n{nranks}")
    assert_same_run(ranks, run_outputs(lina_serial / "one"))
    h = ranks["history"][0]
    total = h["mass"] + h["particle_mass"]
    assert np.max(np.abs(total - total[0])) <= 1e-13 * total[0]
    pz = h["total_momentum_z"]  # no force along z in linA: conserved to round-off
    assert np.max(np.abs(pz - pz[0])) <= 1e-12 * total[0] * 0.05


@pytest.mark.slow  # ~40 s on the loaded two cores per box: four launches, 4 ranks oversubscribed
@pytest.mark.parametrize("faces", ["open", "periodic"])
def test_si3d_on_two_three_and_four_ranks_is_the_serial_run(faces, mpirun, tmp_path):
    args = SI3D if faces == "open" else SI3D_BOX[:-2] + SI3D_STEPS  # the preset's default: periodic z
    lost = {"gas_mass_lost", "particle_mass_lost"} if faces == "open" else set()  # periodic: nothing leaves
    launch(mpirun, 1, args, "one", tmp_path)
    serial = run_outputs(tmp_path / "one")
    for n in (2, 3, 4):
        proc = launch(mpirun, n, args, f"n{n}", tmp_path)
        assert "mpi: z rows 0 " in proc.stderr
        ranks = run_outputs(tmp_path / f"n{n}")
        assert_same_run(ranks, serial, BUDGETS | lost)
        h = ranks["history"][0]
        total = h["mass"] + h["particle_mass"] + sum(h[key] for key in lost)
        tol = 1e-12 if lost else 1e-13
        assert np.max(np.abs(total - total[0])) <= tol * total[0]


@pytest.mark.slow  # ~45 s: five launches
def test_checkpoint_of_two_ranks_restarts_on_one_and_four(mpirun, tmp_path):
    args = SI3D_BOX + ["--set", "run.tlim=0.15", "--set", "run.dt_history=0.01", "--set", "run.dt_snapshot=0.05"]
    launch(mpirun, 1, args, "one", tmp_path)
    reference = run_outputs(tmp_path / "one")
    launch(mpirun, 2, args + ["--set", "run.max_cycles=12"], "part", tmp_path)
    for n in (1, 4):
        shutil.copytree(tmp_path / "part", tmp_path / f"part{n}")
        proc = mpirun(n, "-m", "dustygas", "run", "--restart", f"part{n}", "--set", "run.max_cycles=0", cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr[-3000:]
        assert_same_run(run_outputs(tmp_path / f"part{n}"), reference)


def _rank_pid(root: int, rank: int, timeout: float = 60.0) -> int:
    """The pid of MPI rank ``rank`` among the descendants of process ``root`` (Linux /proc)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        children: dict[int, list[int]] = {}
        for entry in Path("/proc").iterdir():
            if entry.name.isdigit():
                try:
                    ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
                except (OSError, IndexError, ValueError):
                    continue
                children.setdefault(ppid, []).append(int(entry.name))
        todo, seen = [root], []
        while todo:
            pid = todo.pop()
            seen.append(pid)
            todo += children.get(pid, [])
        for pid in seen:
            try:
                env = (Path("/proc") / str(pid) / "environ").read_bytes().split(b"\0")
            except OSError:
                continue
            if f"PMI_RANK={rank}".encode() in env and b"dustygas" in (Path("/proc") / str(pid) / "cmdline").read_bytes():
                return pid
        time.sleep(0.2)
    raise AssertionError(f"rank {rank} not found under pid {root}")


def test_sigterm_on_one_rank_stops_every_rank_with_a_checkpoint(tmp_path):
    """SIGTERM to rank 1 alone: both ranks stop at the same step (the run loop agrees its signals
    every step), rank 0 writes the checkpoint of that step, and the run continues from it."""
    env = {**os.environ, "NUMBA_NUM_THREADS": "1",
           "PYTHONPATH": f"{Path(__file__).resolve().parents[2] / 'src'}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    args = LINA_BOX + ["--set", "run.tlim=100", "--set", "run.dt_snapshot=0.002"]
    proc = subprocess.Popen([shutil.which("mpiexec"), "-n", "2", sys.executable, "-m", "dustygas", "run", *args,
                             "-o", "sig"], cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    try:
        pid = _rank_pid(proc.pid, 1)
        deadline = time.time() + 300
        while time.time() < deadline and len(list((tmp_path / "sig").glob("snapshots/*.h5"))) < 2:
            time.sleep(0.1)
        os.kill(pid, signal.SIGTERM)
        _, err = proc.communicate(timeout=300)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 128 + signal.SIGTERM, err[-3000:]
    checkpoints = sorted((tmp_path / "sig" / "checkpoints").glob("chk_*.h5"))
    assert len(checkpoints) == 1, err[-3000:]
    assert "Traceback" not in err


def test_particles_leaving_through_x_and_z_faces_on_two_ranks(mpirun, tmp_path):
    """The random box of ``tests/particles/test_conservation.py`` with outflow x and z faces and
    gas terms (``_pbox.py``), 30 steps: 6.5 % of the particle mass leaves through the faces (4.6 %
    through x); on 2 ranks every history column (the particle and gas terms' impulse and the mass
    and momentum lost at each face among them: the end blocks add up the z faces', rank 0 the x
    faces' of every block) and every final array are the serial run's bit for bit."""
    from . import _pbox

    for n, name in ((1, "one.npz"), (2, "two.npz")):
        proc = mpirun(n, _pbox.__file__, 30, tmp_path / name)
        assert proc.returncode == 0, proc.stderr[-3000:]
    one, two = np.load(tmp_path / "one.npz"), np.load(tmp_path / "two.npz")
    names = list(one["names"])
    lost, mass = one["history"][-1, names.index("particle_mass_lost")], one["history"][0, names.index("particle_mass")]
    assert 0.03 < lost / mass < 0.13
    for name in ("particle_terms_impulse_z", "gas_terms_impulse_z", "particle_mass_lost_x_lower",
                 "particle_mass_lost_x_upper", "particle_mass_lost_z_lower", "particle_mass_lost_z_upper"):
        assert one["history"][-1, names.index(name)] != 0, name
    for col, name in enumerate(names):
        np.testing.assert_array_equal(two["history"][:, col], one["history"][:, col], err_msg=name)
    for key in one.files:
        if key not in ("names", "history"):
            np.testing.assert_array_equal(two[key], one[key], err_msg=key)
