"""Checkpoints hold everything: a stopped and restarted particle run is bit-identical.

The engine's checkpoint has the gas state, every particle array in its sorted order and the
back-reaction carried from one step to the next; the fast test stops a small si-linA run
with ``run.max_cycles`` (the run loop checkpoints), restarts it, and compares every snapshot
and history array with an uninterrupted run, exactly. (The SIGKILL version on the full linA
run is in ``test_streaming_slow.py``.)
"""

from _runs import assert_runs_identical, run_outputs

from dustygas import api
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory


def test_stopped_and_restarted_run_is_bit_identical(tmp_path):
    sets = ["grid.nx=16", "grid.nz=16", "run.tlim=0.12", "run.dt_snapshot=0.03", "run.dt_history=0.005",
            "problem.amplitude=0.01"]
    ref = api.run("si-linA", output=tmp_path / "ref", set=sets)
    assert ref.status == "finished"
    first = api.run("si-linA", output=tmp_path / "stopped", set=sets + ["run.max_cycles=140"])
    assert first.status == "max_cycles" and RunDirectory(tmp_path / "stopped").checkpoints()
    again = api.restart(tmp_path / "stopped", set=["run.max_cycles=0"])
    assert again.status == "finished" and again.cycles == ref.cycles - 140
    out_ref, out = run_outputs(tmp_path / "ref"), run_outputs(tmp_path / "stopped")
    assert len(out_ref) == 6  # five snapshots and the history
    assert_runs_identical(out_ref, out)
    snap, _ = read_h5(RunDirectory(tmp_path / "ref").snapshots()[-1])
    assert snap["particles/pos"].shape == (3, 256) and snap["rho_p"].shape == (16, 1, 16)
