"""Reading and comparing run directories in tests (restart tests of every engine).

``run_outputs(path)`` returns ``{snapshot file name or "history": (arrays, attrs)}``;
``assert_runs_identical(a, b)`` requires the same files, the same arrays bit for bit and the same
attributes -- what "a killed and restarted run finishes identical to an uninterrupted one" means.
The ``config`` attribute (the configuration in force when the file was written) must agree in
every section but ``[run]``: a restart may change run control (``run.tlim``, ``run.max_cycles``).
"""

import tomllib

import numpy as np

from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory


def run_outputs(path) -> dict:
    rd = RunDirectory(path)
    out = {f.name: read_h5(f) for f in rd.snapshots()}
    out["history"] = read_h5(rd.history_file)
    return out


def assert_runs_identical(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key in a:
        (arrays_a, attrs_a), (arrays_b, attrs_b) = a[key], b[key]
        assert arrays_a.keys() == arrays_b.keys(), key
        for name in arrays_a:
            np.testing.assert_array_equal(arrays_a[name], arrays_b[name], err_msg=f"{key}:{name}")
        assert attrs_a.keys() == attrs_b.keys(), key
        for name in attrs_a:
            if name == "config":
                physics_a, physics_b = tomllib.loads(attrs_a[name]), tomllib.loads(attrs_b[name])
                physics_a.pop("run"), physics_b.pop("run")
                assert physics_a == physics_b, (key, name)
                continue
            assert np.array_equal(attrs_a[name], attrs_b[name]), (key, name)


def kill_after_first_checkpoint_and_restart(problem: str, sets: list[str], cwd, reference, name: str = "killed"):
    """``dustygas run problem`` (with ``--set`` ``sets``) into ``cwd/name``, killed with SIGKILL as
    soon as its first checkpoint exists, then continued with ``dustygas run --restart``; returns
    the run directory. Fails unless the run was killed before it had written all the snapshots
    of the uninterrupted run ``reference``."""
    import signal
    import subprocess
    import sys
    import time

    from foundation._cli import PRELUDE, cli_popen, env

    args = [a for s in sets for a in ("--set", s)]
    proc = cli_popen("run", problem, "-o", name, *args, cwd=cwd)
    chk = cwd / name / "checkpoints"
    deadline = time.time() + 1800
    while time.time() < deadline and not list(chk.glob("chk_*.h5")) and proc.poll() is None:
        time.sleep(0.02)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=60)
    assert proc.returncode == -signal.SIGKILL, proc.stderr.read()
    killed = RunDirectory(cwd / name)
    assert len(killed.checkpoints()) == 1 and len(killed.snapshots()) < len(RunDirectory(reference).snapshots())
    again = subprocess.run([sys.executable, "-c", PRELUDE, "run", "--restart", name], cwd=cwd, env=env(),
                           capture_output=True, text=True, timeout=1800)
    assert again.returncode == 0, again.stderr
    return cwd / name
