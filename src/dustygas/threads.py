"""The default thread count: measured while the run goes on, not guessed.

numba's OpenMP threads wait for each other at the end of every parallel region. When another
process holds one of the cores, the thread sharing that core arrives late at every barrier and
the whole team waits: a 2-thread run on a 2-core machine with one busy core is then several
times *slower* than a 1-thread run, while on a quiet machine it is nearly twice as fast. The
machine's load average cannot tell the two cases apart in time (it lags by a minute and counts
our own threads), so :class:`ThreadTuner` measures instead, as FFTW's planner and GROMACS's
PME tuning do: every kernel gives bit-identical results for any thread count, so the run can
switch freely between steps.

Protocol, for the ``candidates`` (1, half, all-but-one and all of the threads the process may
use, without repeats):

1. ``warmup`` steps at one thread (the first steps compile kernels and fill caches);
2. a *trial*: blocks of at least ``block_steps`` steps and ``block_seconds`` of stepping per
   candidate, in the mirrored order ``a b .. b a`` so that a load that drifts linearly during
   the trial cancels; the step time per work unit of each candidate is the mean of its blocks;
3. the fewest threads within ``margin`` of the fastest candidate are used until the next trial,
   provided both halves of the mirrored trial pick the same count; if they disagree (a load
   that changes from one block to the next) the trial is repeated with blocks twice as long, and
   after ``max_rounds`` disagreeing rounds one thread is used;
4. the next trial comes ``recheck_seconds`` of stepping later; the interval doubles (up to
   ``max_recheck_seconds``) while the choice stays the same and starts again from
   ``recheck_seconds`` when it changes. Between trials the step cost is watched in windows of
   ``watch_seconds``: two windows in a row whose cost is off the first window after the decision
   by more than ``drift`` (another process started or stopped) bring the next trial forward.

5. where the operating system says how busy the CPUs are (Linux: ``/proc/stat``), the CPU time
   that *other* processes used on this process's CPUs during a trial (:class:`OtherLoad`: the
   CPUs' busy time less this process's own) rules out the counts that would share a core with
   them: ``n`` threads only while ``n <= cpus - others + 1/2``, where ``cpus`` counts the CPUs
   the reading covers (the affinity mask's; ``available`` unless the tuner is told), so
   that on a node of many CPUs a run limited to a few threads (``NUMBA_NUM_THREADS``, a
   container's CPU quota) is not held at one thread by work on CPUs it does not need: 16 CPUs,
   4 threads and 10 cores busy elsewhere leave 6 idle, and all 4 run. Timed blocks alone can be
   fooled: on a virtual machine whose single-thread speed swings by 2x within a second (the
   two-vCPU Intel host of 2026-12-07: 1.7-3.4 ms per si-linA step in 50 ms blocks), the two
   0.1 s blocks at two threads beside a busy core can both come out ahead, and the run then
   goes on at two threads, there 1.5x slower than one, until its next check (one default run
   of three did so in a busy set that day). Between trials the same count is read every
   ``watch_seconds``, and a change of the counts it rules out (the other process stopped, or
   one started) brings the next trial forward.

A trial spends half its blocks on the slower choice. With two candidates and the default
constants a trial takes about 0.4 s of stepping, of which about 0.13 s are lost when the slower
choice is 3 times slower: 3 % of a 4 s run, 0.4 % of the first 30 s, then less as the interval
grows; a load that changes is followed within the current interval.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
from typing import Callable

__all__ = ["ThreadTuner", "ThreadControl", "OtherLoad", "thread_candidates"]


def thread_candidates(available: int) -> list[int]:
    """1, half, all but one and all of ``available`` threads (sorted, without repeats)."""
    available = max(1, int(available))
    return sorted({1, max(1, available // 2), max(1, available - 1), available})


class OtherLoad:
    """Cores that other processes used on this process's CPUs since the previous reading.

    ``/proc/stat`` counts, per CPU, the time spent busy (user, nice, system, irq, softirq; not
    idle, I/O wait or steal) in clock ticks; this process's own CPU time, all its threads
    included, is ``os.times()``. Their difference over a wall-clock interval is the number of
    cores that other processes (and the kernel's work for them) kept busy on the CPUs in this
    process's affinity mask: about 1.0 beside one busy loop, 0.0-0.1 on a quiet machine. numba's
    threads that spin at a barrier count as this process's time, so the reading does not count
    our own threads, as the load average does.

    :meth:`cores` returns None where there is no ``/proc/stat`` (not Linux) or fewer than
    ``min_seconds`` have passed since the previous reading (clock ticks are 10 ms: over 0.2 s on
    two CPUs the reading is good to about 0.1 core), and then keeps the previous reading as the
    start of the next interval.
    """

    def __init__(self, min_seconds: float = 0.2):
        self.min_seconds = min_seconds
        try:
            self._cpus = {f"cpu{c}" for c in os.sched_getaffinity(0)}
        except (AttributeError, OSError):
            self._cpus = None
        #: the number of CPUs the reading covers (the affinity mask, else every CPU)
        self.cpus = len(self._cpus) if self._cpus is not None else (os.cpu_count() or 1)
        self._tick = os.sysconf("SC_CLK_TCK") if hasattr(os, "sysconf") else 100
        self._last = self._sample()

    def _sample(self) -> tuple[float, float, float] | None:
        """(wall clock, busy seconds of the CPUs, this process's CPU seconds), or None."""
        try:
            with open("/proc/stat", encoding="ascii") as f:
                lines = f.read().splitlines()
        except OSError:
            return None
        busy = 0
        for line in lines:
            if not (line.startswith("cpu") and line[3:4].isdigit()):
                continue
            name, *ticks = line.split()
            if self._cpus is not None and name not in self._cpus:
                continue
            try:  # user nice system idle iowait irq softirq (older kernels: fewer columns)
                v = [int(t) for t in ticks[:7]] + [0] * max(0, 7 - len(ticks))
            except ValueError:
                return None
            busy += v[0] + v[1] + v[2] + v[5] + v[6]
        own = os.times()
        return time.perf_counter(), busy / self._tick, own.user + own.system

    def cores(self) -> float | None:
        """Cores kept busy by other processes since the previous reading (None: unknown)."""
        if self._last is None:
            return None
        now = self._sample()
        if now is None or now[0] - self._last[0] < self.min_seconds:
            return None
        wall = now[0] - self._last[0]
        others = ((now[1] - self._last[1]) - (now[2] - self._last[2])) / wall
        self._last = now
        return max(others, 0.0)


@dataclass
class ThreadTuner:
    """Chooses the number of numba threads from measured step times (see module docstring).

    Call :meth:`threads_for_next_step` before each step, set that many threads, and report the
    step's wall time and work with :meth:`record`. With one candidate it always answers it.
    ``others`` reads the cores that other processes used since its previous call (None:
    unknown; :meth:`OtherLoad.cores`, or a stand-in in tests); without it only the timed
    blocks decide. ``cpus`` is the number of CPUs that reading covers (:attr:`OtherLoad.cpus`;
    None: ``available``).
    """

    available: int
    warmup: int = 3
    block_steps: int = 1
    block_seconds: float = 0.1
    recheck_seconds: float = 30.0
    max_recheck_seconds: float = 480.0
    margin: float = 0.03
    max_rounds: int = 3
    drift: float = 0.3
    watch_seconds: float = 2.0
    others: Callable[[], float | None] | None = None
    cpus: int | None = None
    candidates: list[int] = field(init=False)
    choice: int = field(init=False)
    decisions: list[str] = field(default_factory=list, init=False)

    def __post_init__(self) -> None:
        self.candidates = thread_candidates(self.available)
        if self.cpus is None:
            self.cpus = self.available
        self.choice = 1
        self._steps = 0
        self._interval = self.recheck_seconds
        self._since_trial = 0.0
        self._plan: list[int] = []  # remaining blocks of the current trial
        self._block = [0, 0.0, 0.0]  # steps, seconds, work of the block in progress
        self._results: dict[int, list[float]] = {}
        self._round = 0
        self._expected = 0.0  # cost per work unit of the choice in the first window after a decision
        self._watch = [0, 0.0, 0.0]  # steps, seconds, work of the current window
        self._off = 0  # windows in a row whose cost is off the reference
        self._all: dict[int, list[float]] = {}  # block costs of all rounds of the current trial
        self._ruled_out: set[int] = set()  # counts that would share a core with other processes
        self._others = 0.0  # the latest reading of the cores other processes used

    def threads_for_next_step(self) -> int:
        if len(self.candidates) == 1:
            return self.candidates[0]
        if not self._plan and self._steps >= self.warmup and self._since_trial >= self._due():
            self._round = 0
            self._start_trial()
        return self._plan[0] if self._plan else self.choice

    def _due(self) -> float:
        return 0.0 if not self.decisions else self._interval

    def _block_seconds(self) -> float:
        return self.block_seconds * 2**self._round

    def _start_trial(self) -> None:
        if self._round == 0 and self.others is not None:
            self.others()  # the reading at the decision covers the trial
        tried = [n for n in self.candidates if n not in self._ruled_out]
        order = sorted(tried, key=lambda n: (n != self.choice, n))  # current choice first
        self._plan = order + order[::-1]
        self._results = {n: [] for n in tried}
        self._block = [0, 0.0, 0.0]

    def _read_others(self) -> set[int] | None:
        """Read :attr:`others` (kept for the decision's log line); the counts it rules out, or None."""
        reading = self.others() if self.others is not None else None
        if reading is None:
            return None
        self._others = reading
        return self._rule_out(reading)

    def _rule_out(self, others: float) -> set[int]:
        """The counts that would share a core with ``others`` cores of other processes' work
        (more threads than the ``cpus - others`` CPUs they leave idle, give or take half a core)."""
        return {n for n in self.candidates if n > 1 and n > self.cpus - others + 0.5}

    def record(self, seconds: float, work: float) -> None:
        """Report the wall time and the work units of the step just taken."""
        self._steps += 1
        if len(self.candidates) == 1 or self._steps <= self.warmup:
            return
        work = max(work, 1e-300)
        if not self._plan:
            self._since_trial += seconds
            self._look(seconds, work)
            return
        block = self._block
        block[0] += 1
        block[1] += seconds
        block[2] += work
        if block[0] >= self.block_steps and block[1] >= self._block_seconds():
            self._results[self._plan.pop(0)].append(block[1] / block[2])
            self._block = [0, 0.0, 0.0]
            if not self._plan:
                self._decide()

    def _look(self, seconds: float, work: float) -> None:
        """Between trials: the step cost in windows of ``watch_seconds``; the first window after a
        decision is the reference, and two windows in a row off it by more than ``drift`` (another
        process started or stopped) bring the next trial forward to now, and so does a reading of
        :attr:`others` at the end of a window that rules out other counts than the last trial's."""
        watch = self._watch
        watch[0] += 1
        watch[1] += seconds
        watch[2] += work
        if watch[0] < self.block_steps or watch[1] < self.watch_seconds:
            return
        cost = watch[1] / watch[2]
        self._watch = [0, 0.0, 0.0]
        ruled = self._read_others()
        if ruled is not None and ruled != self._ruled_out:  # another process started or stopped:
            self._ruled_out = ruled
            self._since_trial = self._interval  # a trial now, of the counts that are not ruled out
        if self._expected <= 0:
            self._expected = cost
            return
        off = not (self._expected / (1 + self.drift) <= cost <= self._expected * (1 + self.drift))
        self._off = self._off + 1 if off else 0
        if self._off >= 2:
            self._since_trial = self._interval

    @staticmethod
    def _pick(cost: dict[int, float], margin: float) -> int:
        best = min(cost.values())
        return min(n for n, c in cost.items() if c <= best * (1.0 + margin))

    def _decide(self) -> None:
        """Both halves of the mirrored trial must agree; else again with blocks twice as long.
        Counts that the cores other processes used during the trial rule out are not chosen."""
        ruled = self._read_others()
        if ruled is not None:
            self._ruled_out = ruled
        if any(n not in self._ruled_out and n not in self._results for n in self.candidates):
            self._round = 0  # a count ruled out when the trial started is free now: try it too
            self._start_trial()
            return
        allowed = {n: v for n, v in self._results.items() if n not in self._ruled_out}
        halves = [self._pick({n: v[i] for n, v in allowed.items()}, self.margin) for i in (0, 1)]
        if self._round == 0:
            self._all = {}
        for n, v in self._results.items():
            self._all.setdefault(n, []).extend(v)
        if halves[0] != halves[1] and self._round + 1 < self.max_rounds:
            self._round += 1
            self._start_trial()
            return
        cost = {n: sum(v) / len(v) for n, v in self._all.items()}
        choice = halves[0] if halves[0] == halves[1] else min(self.candidates)  # still undecided: one thread
        if choice == self.choice and self.decisions:
            self._interval = min(2.0 * self._interval, self.max_recheck_seconds)
        else:
            self._interval = self.recheck_seconds
        self.choice = choice
        self._expected = 0.0
        self._off = 0
        self._since_trial = 0.0
        self._watch = [0, 0.0, 0.0]
        rates = ", ".join(f"{n} thread{'s' if n > 1 else ''}: {1.0 / c:.4g}/s" for n, c in sorted(cost.items()))
        agreed = "" if halves[0] == halves[1] else f", undecided after {self.max_rounds} rounds"
        if self._ruled_out:
            ruled = ", ".join(str(n) for n in sorted(self._ruled_out))
            agreed += f"; other processes kept {self._others:.2f} cores busy: {ruled} ruled out"
        self.decisions.append(f"threads: {choice} ({rates}{agreed}; next check in {self._interval:.0f} s of stepping)")


class ThreadControl:
    """numba's thread count during a run: fixed (``requested > 0``) or tuned; :meth:`restore` puts back
    the count found at the start (the tuner's largest candidate).

    During the run the BLAS library (OpenBLAS under numpy) is held at one thread. numba's OpenMP
    threads spin for a while at the end of every parallel region, and OpenBLAS's threads after every
    call; two pools on the same cores take turns instead of working. The run's BLAS calls are small
    sums of the diagnostics (``vel @ mass``), and the parallelism of a run is numba's: on the
    two-core machine, with 16384 particles, one history row took 7.7-9.2 ms on two numba threads
    with OpenBLAS at its two threads and 1.7-2.0 ms with it at one (2.2-2.6 ms on one numba thread;
    2026-12-05). :meth:`restore` gives BLAS its thread count back.
    """

    def __init__(self, requested: int):
        import numba
        from threadpoolctl import threadpool_limits

        self._numba = numba
        self._blas = threadpool_limits(limits=1, user_api="blas")
        self.before = numba.get_num_threads()
        self.tuner = None
        if requested > 0:
            self.current = min(requested, numba.config.NUMBA_NUM_THREADS)
            numba.set_num_threads(self.current)
        else:
            probe = OtherLoad()
            self.tuner = ThreadTuner(self.before, others=probe.cores, cpus=probe.cpus)
            self.current = self.before
        self._reported = 0

    def before_step(self) -> None:
        if self.tuner is not None:
            n = self.tuner.threads_for_next_step()
            if n != self.current:
                self._numba.set_num_threads(n)
                self.current = n

    def after_step(self, seconds: float, work: float) -> list[str]:
        if self.tuner is None:
            return []
        self.tuner.record(seconds, work)
        new = self.tuner.decisions[self._reported:]
        self._reported = len(self.tuner.decisions)
        return new

    @property
    def chosen(self) -> int:
        return self.tuner.choice if self.tuner is not None else self.current

    def restore(self) -> None:
        self._numba.set_num_threads(self.before)
        self._blas.restore_original_limits()
