"""Linear streaming-instability growth of linA in the particle-gas engine at 64² (slow; linB is in
test_linb_slow.py, a file of its own so that the two long runs go to different CI workers).

linA (Youdin & Johansen 2007): τ_s = 0.1, ε = 3, K = 30, 64², one particle per cell, t = 0 → 6.
Linear theory (consistent linearisation of fixed-t_s drag, what the engine integrates):
s = 0.4190091. Tolerance 1 % (Athena on this machine: -1.2 %), fields agreeing within 0.5 %.

The linA run is shared: the growth test reads it, and the restart test kills a second linA
run with SIGKILL right after its checkpoint at t = 3, restarts it with ``dustygas run
--restart`` and compares every snapshot and history array with the uninterrupted one.
"""

import pytest

from _runs import assert_runs_identical, kill_after_first_checkpoint_and_restart, run_outputs

from dustygas import api
from dustygas.analysis.growth import measure_growth

LINA = 0.4190091323
LINA_SETS = ["run.dt_checkpoint=3.0", "run.checkpoint_wall=0", "run.dt_snapshot=1.0", "run.threads=0"]


@pytest.fixture(scope="module")
def lina_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("lina") / "ref"
    res = api.run("si-linA", output=path, set=LINA_SETS)
    assert res.status == "finished"
    return path


@pytest.mark.slow
def test_lina_growth_within_one_percent(lina_run):
    fit = measure_growth(lina_run)
    assert fit.growth_rate == pytest.approx(LINA, rel=0.01), fit
    assert fit.spread < 0.005, fit.fields
    assert fit.frequency == pytest.approx(0.3480, rel=0.01)


@pytest.mark.slow
def test_lina_killed_at_t3_and_restarted_is_bit_identical(lina_run, tmp_path):
    killed = kill_after_first_checkpoint_and_restart("si-linA", LINA_SETS, tmp_path, lina_run)
    assert_runs_identical(run_outputs(lina_run), run_outputs(killed))
