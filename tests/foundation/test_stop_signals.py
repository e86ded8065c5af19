"""Stop signals of an MPI rank (:mod:`dustygas._launch`): held by every thread, taken by the run
loop at its agreement point.

Delivered at an arbitrary moment, a SIGTERM sent to one rank of a two-rank run left the ranks one
exchange apart and waiting for each other (2 hangs in 8 signals sent in the first steps of
si-linA, 2026-12-03; ``tests/mpi/test_particles_mpi.py`` sends them). These tests check the
mechanism in one process with a launcher's environment faked, so that no MPI is started: after
``import dustygas`` every thread of the process (the BLAS threads included) blocks SIGTERM and
SIGINT, and a signal that arrived meanwhile is pending until ``_StopFlag.take_held`` takes it.
"""

from __future__ import annotations

import subprocess
import sys

from foundation._cli import env

#: a rank of two under MPICH's Hydra, as far as the environment tells
RANK_ENV = {"PMI_RANK": "1", "PMI_SIZE": "2"}

THREADS_BLOCK = """
import os, signal
import dustygas
import numpy as np
np.ones((300, 300)) @ np.ones((300, 300))  # the BLAS threads exist and have worked
masks = []
for task in os.listdir("/proc/self/task"):
    for line in open(f"/proc/self/task/{task}/status"):
        if line.startswith("SigBlk:"):
            masks.append(int(line.split()[1], 16))
bits = (1 << (signal.SIGTERM - 1)) | (1 << (signal.SIGINT - 1))
print(len(masks), sum(m & bits == bits for m in masks))
"""

TAKE_HELD = """
import os, signal
import dustygas
from dustygas.runner import _StopFlag
with _StopFlag() as stop:
    os.kill(os.getpid(), signal.SIGTERM)  # held: no handler runs, nothing is killed
    before = stop.signum
    taken = stop.take_held()
    print(before, taken, int(signal.SIGTERM in signal.sigpending()))
"""


def _python(code: str, extra_env: dict) -> str:
    proc = subprocess.run([sys.executable, "-c", code], env={**env(), **extra_env}, capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout.split()


def test_every_thread_of_a_rank_blocks_the_stop_signals():
    nthreads, blocking = map(int, _python(THREADS_BLOCK, {**RANK_ENV, "OPENBLAS_NUM_THREADS": "2"}))
    assert nthreads >= 2 and blocking == nthreads


def test_a_plain_process_keeps_its_stop_signals():
    nthreads, blocking = map(int, _python(THREADS_BLOCK, {"OPENBLAS_NUM_THREADS": "2"}))
    assert nthreads >= 2 and blocking == 0


def test_the_run_loop_takes_a_held_signal_at_its_agreement_point():
    before, taken, still_pending = map(int, _python(TAKE_HELD, RANK_ENV))
    assert (before, taken, still_pending) == (0, 15, 0)
