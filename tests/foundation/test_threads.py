"""The automatic thread count (dustygas.threads): its choice, its cost, and bit-identical results.

The tuner is driven with a synthetic machine: a step of ``work`` units takes ``cost[n] * work``
seconds at ``n`` threads. Quiet 2-core machine: two threads 1.8x faster; one core busy
elsewhere: two threads 3.1x slower (the 12.9 s vs 40.6 s measured for si-linA).
"""

import os
import random
import subprocess
import sys
import time

import pytest

from _runs import assert_runs_identical, run_outputs
from dustygas.threads import OtherLoad, ThreadTuner, thread_candidates

from ._cli import env

QUIET = {1: 1.0, 2: 1.0 / 1.8}
BUSY = {1: 1.0, 2: 40.6 / 12.9}
_rng = random.Random(16)


def noisy(machine):
    """Every step's cost scattered by a log-normal factor (sigma 0.5): a machine shared with many jobs."""
    return lambda t: {n: c * _rng.lognormvariate(0.0, 0.5) for n, c in machine.items()}


def _drive(tuner, cost_at, seconds):
    """Step a tuner for ``seconds`` of simulated wall time; time spent per thread count."""
    clock, spent = 0.0, {}
    while clock < seconds:
        n = tuner.threads_for_next_step()
        dt = cost_at(clock)[n] * 0.05  # steps of 0.05 work units: 50 ms at one thread
        tuner.record(dt, 0.05)
        spent[n] = spent.get(n, 0.0) + dt
        clock += dt
    return spent


@pytest.mark.parametrize("machine, best, scatter", [(QUIET, 2, False), (BUSY, 1, False), (QUIET, 2, True),
                                                   (BUSY, 1, True)])
def test_tuner_picks_the_faster_count_at_a_cost_below_two_percent(machine, best, scatter):
    tuner = ThreadTuner(available=2)
    spent = _drive(tuner, noisy(machine) if scatter else (lambda t: machine), 600.0)
    assert tuner.choice == best
    # work done in 600 s against the best fixed setting: trials cost at most 2 % (0.08-0.44 % here)
    work = sum(s / machine[n] for n, s in spent.items())
    assert work >= 0.98 * 600.0 / machine[best]


def test_tuner_follows_a_load_that_changes():
    """Quiet for 100 s, then a core is taken: within seconds the run is on one thread again."""
    tuner = ThreadTuner(available=2)
    _drive(tuner, lambda t: QUIET, 100.0)
    assert tuner.choice == 2
    spent = _drive(tuner, lambda t: BUSY, 300.0)
    assert tuner.choice == 1
    assert spent[2] < 8.0  # two 2-s windows off the reference bring the next trial forward


def test_candidates():
    assert thread_candidates(1) == [1] and thread_candidates(2) == [1, 2]
    assert thread_candidates(16) == [1, 8, 15, 16]


def test_another_process_on_a_core_rules_out_two_threads_whatever_the_blocks_say():
    """Timed blocks that favour two threads (a host whose speed swings fools a pair of 0.1 s blocks
    now and then) cannot choose them while another process keeps a core busy; once it stops, the
    next reading (every 2 s of stepping) brings a trial that returns to two threads."""
    load = {"others": 1.0}
    tuner = ThreadTuner(available=2, others=lambda: load["others"])
    spent = _drive(tuner, lambda t: QUIET, 100.0)
    assert tuner.choice == 1
    assert spent[2] < 0.3  # only the first trial's two blocks of >= 0.1 s (0.22 s here)
    assert "1.00 cores busy: 2 ruled out" in tuner.decisions[0]
    load["others"] = 0.05  # the other process stopped (the kernel's own work remains)
    spent = _drive(tuner, lambda t: QUIET, 10.0)
    assert tuner.choice == 2 and spent[1] < 3.0  # a 2 s window, then the trial


@pytest.mark.parametrize("others, allowed", [(0.0, [1, 8, 15, 16]), (0.6, [1, 8, 15]), (1.0, [1, 8, 15]),
                                             (8.0, [1, 8]), (8.6, [1]), (15.0, [1])])
def test_counts_ruled_out_by_other_processes_leave_them_their_cores(others, allowed):
    """``n`` threads only while ``n <= cpus - others + 1/2`` (one thread always); the CPUs the
    reading covers are the ``available`` threads' unless the tuner is told otherwise."""
    tuner = ThreadTuner(available=16)
    assert sorted(set(tuner.candidates) - tuner._rule_out(others)) == allowed


@pytest.mark.parametrize("others, allowed", [(0.0, [1, 2, 3, 4]), (10.0, [1, 2, 3, 4]), (12.0, [1, 2, 3, 4]),
                                             (12.6, [1, 2, 3]), (13.6, [1, 2]), (15.0, [1])])
def test_only_the_cpus_other_work_leaves_idle_limit_the_threads(others, allowed):
    """16 CPUs in the affinity mask, 4 threads allowed (``NUMBA_NUM_THREADS=4``): 10 or 12 cores
    busy elsewhere leave 6 or 4 idle and all 4 threads may run; 13.6 leave 2.4."""
    tuner = ThreadTuner(available=4, cpus=16)
    assert tuner.candidates == [1, 2, 3, 4]
    assert sorted(set(tuner.candidates) - tuner._rule_out(others)) == allowed


def test_the_cpus_of_the_reading_are_the_affinity_mask():
    assert OtherLoad().cpus == (len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count())


def test_other_load_reads_a_busy_loop_in_another_process():
    """/proc/stat's busy ticks less this process's CPU time: about one core beside one busy loop
    (more if the machine runs other work meanwhile, never more than its CPUs)."""

    if not os.path.exists("/proc/stat"):  # not Linux: no reading, and the tuner times blocks only
        assert OtherLoad(min_seconds=0.0).cores() is None
        return
    hog = subprocess.Popen([sys.executable, "-c", "while True: pass"])
    try:
        time.sleep(0.3)
        probe = OtherLoad()
        assert probe.cores() is None  # under 0.2 s: no reading yet
        time.sleep(1.0)
        cores = probe.cores()
    finally:
        hog.kill()
        hog.wait()
    assert 0.9 <= cores <= len(os.sched_getaffinity(0)) + 0.05


FORCED = """
import sys
import dustygas.threads as threads
# a trial at every step: the thread count changes between 1 and 2 all the time (the CPUs' load
# not read: another test's process on the other core would otherwise rule out two threads)
_Tuner = threads.ThreadTuner
def forced(available, **kw):
    kw.update(warmup=1, block_steps=1, block_seconds=0.0, recheck_seconds=0.0, max_recheck_seconds=0.0, others=None)
    return _Tuner(available, **kw)
threads.ThreadTuner = forced
from dustygas.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_switching_threads_every_step_is_bit_identical_to_one_thread(tmp_path):
    common = ["run", "si-linA", "-q", "--set", "grid.nx=16", "--set", "grid.nz=16", "--set", "run.tlim=0.03",
              "--set", "run.dt_snapshot=0.01"]
    e = {**env(), "NUMBA_NUM_THREADS": "2"}
    one = subprocess.run([sys.executable, "-c", FORCED, *common, "-o", "one", "--threads", "1"], cwd=tmp_path, env=e,
                         capture_output=True, text=True, timeout=600)
    auto = subprocess.run([sys.executable, "-c", FORCED, *common, "-o", "auto"], cwd=tmp_path, env=e,
                          capture_output=True, text=True, timeout=600)
    assert one.returncode == 0 and auto.returncode == 0, (one.stderr, auto.stderr)
    log = (tmp_path / "auto" / "log.txt").read_text()
    assert log.count("threads: ") > 10 and "2 threads: " in log
    assert_runs_identical(run_outputs(tmp_path / "one"), run_outputs(tmp_path / "auto"))


def test_fixed_threads_are_not_tuned(tmp_path):
    from dustygas import api

    import _toyproblem  # noqa: F401

    res = api.run("toy-oscillator", output=tmp_path / "r", set=["run.threads=1", "run.tlim=0.2"])
    assert res.threads == 1 and "threads: " not in (tmp_path / "r" / "log.txt").read_text()


def test_a_run_holds_blas_at_one_thread_and_gives_its_count_back():
    """numba owns a run's threads: BLAS (OpenBLAS under numpy) works on one thread during it, so that
    its spinning threads do not take the cores from numba's (dustygas.threads.ThreadControl), and
    has its own count again afterwards."""
    from threadpoolctl import threadpool_info, threadpool_limits

    from dustygas.threads import ThreadControl

    def blas_threads():
        return sorted({pool["num_threads"] for pool in threadpool_info() if pool["user_api"] == "blas"})

    with threadpool_limits(limits=2, user_api="blas"):  # a known count before the run, on any machine
        assert blas_threads() == [2]
        control = ThreadControl(1)
        assert blas_threads() == [1]
        control.restore()
        assert blas_threads() == [2]
