"""Inputs of the weak-scaling model of ``docs/scaling.rst``: MPI latency and bandwidth on this
machine, and the messages and bytes one rank exchanges per coupled step.

Run under two ranks (one numba thread each)::

    NUMBA_NUM_THREADS=1 flock benchmarks/.lock mpiexec -n 2 python benchmarks/bench_mpi_model.py

1. **Ping-pong** between the two ranks, ``Sendrecv`` of float64 buffers of 8 B .. 8 MB, 200
   round trips each (fewer for the largest): the time of one message is half a round trip;
   the smallest over ``--repeat`` passes is kept (on a loaded machine a rank may be descheduled
   during a pass). A least-squares fit ``t(m) = alpha + m / beta`` over the sizes gives the
   latency ``alpha`` and the bandwidth ``beta``.
2. **Traffic of a step**: a particle run of ``--case`` (default ``si-AB-3d`` at 32³, one particle
   per cell; ``si3d`` for the settled layer) stepped ``--steps`` times with every point-to-point
   call and collective of the engines counted (messages, bytes: a pickled message counts its
   pickle), per rank and per step, by phase (gas halo, particle halo, drag deposits of the halo,
   field halos, migration, collectives).
3. **Compute time per cell** of the same run on one rank (CPU time per step / cells).

It prints one ``key = value`` line per figure (what ``docs/scaling.rst`` quotes).
"""

from __future__ import annotations

import argparse
import collections
import pickle
import time

import numpy as np


def pingpong(comm, repeat: int) -> list[tuple[int, float]]:
    """(bytes, seconds per message) for the sizes 8 B .. 8 MB (rank 0's view)."""
    rank = comm.Get_rank()
    other = 1 - rank
    out = []
    for size in [8 * 4**k for k in range(11)]:
        buf = np.zeros(size // 8)
        recv = np.empty_like(buf)
        trips = 200 if size < 1 << 20 else 20
        best = np.inf
        for _ in range(repeat):
            comm.Barrier()
            t0 = time.perf_counter()
            for _ in range(trips):
                if rank == 0:
                    comm.Send(buf, dest=other)
                    comm.Recv(recv, source=other)
                else:
                    comm.Recv(recv, source=other)
                    comm.Send(buf, dest=other)
            best = min(best, (time.perf_counter() - t0) / (2 * trips))
        out.append((size, best))
    return out


class CountingComm:
    """A communicator that counts the messages and bytes this rank sends, by phase."""

    def __init__(self, comm, counts, phase):
        self._comm, self._counts, self._phase = comm, counts, phase

    def __getattr__(self, name):
        attr = getattr(self._comm, name)
        if not callable(attr):
            return attr

        def counted(*args, **kwargs):
            data = args[0] if args else kwargs.get("sendbuf", kwargs.get("obj"))
            if name in ("Sendrecv", "Isend", "Send", "Allreduce"):
                nbytes = np.asarray(data).nbytes if data is not None else 0
            elif name in ("sendrecv", "allreduce", "bcast", "gather"):
                nbytes = len(pickle.dumps(data, protocol=pickle.HIGHEST_PROTOCOL)) if data is not None else 0
            else:
                nbytes = None
            if nbytes is not None:
                dest = kwargs.get("dest")
                from mpi4py import MPI

                if dest != MPI.PROC_NULL:
                    key = self._phase[0] + (" (collective)" if name[0].lower() in "ab" else "")
                    self._counts[key][0] += 1
                    self._counts[key][1] += nbytes
            return attr(*args, **kwargs)

        return counted


def traffic(case: list[str], steps: int):
    """Messages and bytes per step of this rank, by phase; CPU seconds per step."""
    from mpi4py import MPI

    from dustygas.parallel.particles import BlockParticleEngine
    from dustygas.problems import get_problem

    prob = get_problem(case[0])
    cfg = prob.config([], case[1:], None)
    eng = prob.build(cfg)
    counts = collections.defaultdict(lambda: [0, 0])
    phase = ["step"]
    if hasattr(eng, "local"):
        comm = CountingComm(eng.comm, counts, phase)
        eng.comm = eng.local.comm = comm
        eng.gas.comm = eng.gas.halo.comm = CountingComm(eng.gas.comm, counts, phase)
        for meth, label in (("_exchange", "migration"), ("_add_halo", "particle halo"), ("_kicked", "halo drag deposits"),
                            ("_field_halo", "field halos")):
            def wrap(f, label=label):
                def g(self, *a, **k):
                    phase[0] = label
                    try:
                        return f(self, *a, **k)
                    finally:
                        phase[0] = "gas halo and time step"
                return g
            setattr(BlockParticleEngine, meth, wrap(getattr(BlockParticleEngine, meth)))
        phase[0] = "gas halo and time step"
    for _ in range(3):
        eng.advance(eng.timestep())
    counts.clear()
    c0 = time.process_time()
    for _ in range(steps):
        eng.advance(eng.timestep())
    cpu = (time.process_time() - c0) / steps
    return {k: (v[0] / steps, v[1] / steps) for k, v in counts.items()}, cpu, eng


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", nargs="+", default=["si-AB-3d"])
    parser.add_argument("--steps", type=int, default=10)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    from dustygas.parallel import launched_under_mpi

    if not launched_under_mpi():
        _, cpu, eng = traffic(args.case, args.steps)
        print(f"one rank: cpu_per_step_s = {cpu:.4g}; cells = {eng.work_units}; "
              f"cpu_per_cell_s = {cpu / eng.work_units:.4g}")
        return
    from mpi4py import MPI

    comm = MPI.COMM_WORLD
    rank = comm.Get_rank()
    sizes = pingpong(comm, args.repeat)
    if rank == 0:
        print("uptime:", open("/proc/loadavg").read().split()[:3])
        m = np.array([s for s, _ in sizes], dtype=np.float64)
        t = np.array([x for _, x in sizes])
        for s, x in sizes:
            print(f"pingpong bytes = {s:9d}  seconds = {x:.3e}")
        A = np.stack([np.ones_like(m), m], axis=1)
        alpha, inv_beta = np.linalg.lstsq(A, t, rcond=None)[0]
        print(f"alpha_s = {alpha:.3e}; beta_bytes_per_s = {1 / inv_beta:.3e}")
    per, cpu, eng = traffic(args.case, args.steps)
    rows = comm.gather((rank, per, cpu, eng.local.particles.n), root=0)
    if rank == 0:
        for r, p, c, n in rows:
            print(f"rank {r}: particles = {n}; cpu_per_step_s = {c:.4g}")
            for k, (msgs, nbytes) in sorted(p.items()):
                print(f"   {k:40s} messages_per_step = {msgs:6.1f}  bytes_per_step = {nbytes:10.0f}")


if __name__ == "__main__":
    main()
