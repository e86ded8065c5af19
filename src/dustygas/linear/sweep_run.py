"""Running a shearing-wave sweep: executors, resumable output, the keyword API (thesis §4.6.2).

:func:`run_sweep` computes the chunks of a :class:`~dustygas.linear.sweep.SweepSpec` through a
:class:`concurrent.futures.Executor` (:func:`open_executor`: a process pool, ``mpi4py.futures``,
a Dask cluster's executor) or in this process. A chunk's result does not depend on where it
runs (the same compiled code on the same inputs), so every executor writes the same file.
With an output path each finished chunk is written atomically into a work directory next to
it, and a re-run with the same parameters computes only the missing chunks.
"""

from __future__ import annotations

import contextlib
import math
import os
import shutil
import sys
from concurrent.futures import Executor, as_completed
from dataclasses import fields
from pathlib import Path
from typing import Any, Iterator, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._version import __version__
from ..errors import UserError
from ..io.atomic import atomic_path
from .sweep import DIMENSIONS, SweepResult, SweepSpec, compute_chunk
from .sweep_kernel import RESULT_FIELDS

__all__ = ["EXECUTORS", "open_executor", "run_sweep", "sweep", "spec_from_mapping", "grid_from_range"]

#: executor names of :func:`open_executor`
EXECUTORS = ("process", "serial", "mpi", "dask")


@contextlib.contextmanager
def open_executor(kind: str = "process", *, workers: int | None = None, scheduler: str | None = None,
                  timeout: float = 10.0) -> Iterator[Executor | None]:
    """A :class:`concurrent.futures.Executor` for :func:`run_sweep` (None: this process).

    ``"process"``: a :class:`~concurrent.futures.ProcessPoolExecutor` of ``workers`` processes
    (default: the CPU count), started with ``spawn``; ``"serial"``: none; ``"mpi"``:
    :class:`mpi4py.futures.MPIPoolExecutor` (run under ``mpiexec -n N python -m mpi4py.futures``);
    ``"dask"``: the executor of a :class:`distributed.Client` connected to ``scheduler``
    (one-line error if nothing answers within ``timeout`` seconds).
    """
    if kind not in EXECUTORS:
        raise UserError(f"executor {kind!r}: choose one of {', '.join(EXECUTORS)}")
    if workers is not None and (isinstance(workers, bool) or int(workers) < 1):
        raise UserError(f"workers = {workers!r}: expected a positive integer")
    if scheduler is not None and kind != "dask":
        raise UserError("--scheduler is only used with --executor dask")
    if kind == "serial":
        yield None
    elif kind == "process":
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        with ProcessPoolExecutor(max_workers=workers or os.cpu_count() or 1,
                                 mp_context=multiprocessing.get_context("spawn")) as ex:
            yield ex
    elif kind == "mpi":
        try:
            from mpi4py.futures import MPIPoolExecutor
        except ImportError:
            raise UserError("executor 'mpi' needs mpi4py (pip install 'dustygas[mpi]')") from None
        with MPIPoolExecutor(max_workers=workers) as ex:
            yield ex
    else:
        if not scheduler:
            raise UserError("executor 'dask' needs --scheduler ADDRESS (e.g. tcp://127.0.0.1:8786)")
        try:
            from distributed import Client
        except ImportError:
            raise UserError("executor 'dask' needs Dask distributed (pip install 'dustygas[sweep]')") from None
        try:
            client = Client(scheduler, timeout=timeout, set_as_default=False)
        except (OSError, TimeoutError, ValueError) as exc:
            raise UserError(f"--scheduler {scheduler}: no Dask scheduler answered within {timeout:g} s "
                            f"({type(exc).__name__})") from None
        try:
            yield client.get_executor(pure=False)
        finally:
            client.close()


# ---------------------------------------------------------------------------- running


class _WorkDir:
    """Finished chunks of one sweep, each an atomically written ``.npy`` file, plus its spec."""

    def __init__(self, output: Path, spec: SweepSpec, overwrite: bool):
        self.path = output.with_name(output.name + ".parts")
        self.spec = spec
        spec_file = self.path / "spec.json"
        if self.path.exists():
            old = spec_file.read_text() if spec_file.exists() else ""
            if old != spec.to_json() + "\n" + spec.digest():
                if not overwrite:
                    raise UserError(f"{self.path} holds an unfinished sweep with other parameters: remove it, "
                                    "or pass --overwrite to start again")
                shutil.rmtree(self.path)
        self.path.mkdir(parents=True, exist_ok=True)
        if not spec_file.exists():
            with atomic_path(spec_file) as tmp:
                tmp.write_text(spec.to_json() + "\n" + spec.digest())

    def file(self, i: int) -> Path:
        return self.path / f"chunk_{i:06d}.npy"

    def done(self) -> set[int]:
        out = set()
        for i in range(self.spec.nchunks):
            if self.file(i).exists():
                out.add(i)
        return out

    def write(self, i: int, values: np.ndarray) -> None:
        with atomic_path(self.file(i)) as tmp:
            with open(tmp, "wb") as fh:
                np.save(fh, np.ascontiguousarray(values, dtype=np.float64), allow_pickle=False)

    def read(self, i: int) -> np.ndarray:
        return np.load(self.file(i), allow_pickle=False)

    def remove(self) -> None:
        shutil.rmtree(self.path, ignore_errors=True)


def run_sweep(spec: SweepSpec, output: str | Path | None = None, *, executor: Executor | None = None,
              progress: bool = False, overwrite: bool = False, log=None) -> SweepResult:
    """Compute ``spec`` (through ``executor`` if given) and, with ``output``, write it resumably.

    With ``output`` (an ``.h5`` path) finished chunks go to ``OUTPUT.parts/``; a run killed at any
    moment and started again with the same spec computes only the chunks that are missing, and
    the final file is written atomically (and the work directory removed) at the end. An existing
    ``output`` is an error unless ``overwrite``.
    """
    from tqdm import tqdm

    work = None
    if output is not None:
        output = Path(output)
        if output.exists() and not overwrite:
            raise UserError(f"{output} exists: choose another output or pass --overwrite")
        if output.parent and not output.parent.exists():
            raise UserError(f"output directory {output.parent} does not exist")
        work = _WorkDir(output, spec, overwrite)
    spec_json = spec.to_json()
    results: dict[int, np.ndarray] = {}
    done = work.done() if work else set()
    for i in done:
        results[i] = work.read(i)
    todo = [i for i in range(spec.nchunks) if i not in done]
    if log is not None and done:
        log(f"resuming {output}: {len(done)} of {spec.nchunks} chunks already done")
    initial = sum(spec.chunk_range(i)[1] - spec.chunk_range(i)[0] for i in done)
    bar = tqdm(total=spec.size, initial=initial, unit="wave",
               disable=not progress, file=sys.stderr, desc="sweep", dynamic_ncols=True)
    try:
        def finish(i: int, values: np.ndarray) -> None:
            results[i] = values
            if work:
                work.write(i, values)
            bar.update(values.shape[1])

        if executor is None:
            for i in todo:
                finish(i, compute_chunk(spec_json, *spec.chunk_range(i)))
        else:
            futures = {executor.submit(compute_chunk, spec_json, *spec.chunk_range(i)): i for i in todo}
            for fut in as_completed(futures):
                finish(futures[fut], fut.result())
    finally:
        bar.close()
    flat = np.concatenate([results[i] for i in range(spec.nchunks)], axis=1)
    data = {name: flat[k].reshape(spec.shape) for k, name in enumerate(RESULT_FIELDS)}
    if spec.times:
        nf, nt = len(RESULT_FIELDS), spec.times
        data["dust_t"] = np.moveaxis(flat[nf:nf + nt], 0, -1).reshape(spec.shape + (nt,))
        data["energy_t"] = np.moveaxis(flat[nf + nt:nf + 2 * nt], 0, -1).reshape(spec.shape + (nt,))
    data["steps"] = data["steps"].astype(np.int64)
    data["failed"] = data["failed"].astype(np.int8)
    result = SweepResult(spec, data, {"dustygas_version": __version__})
    if output is not None:
        result.save(output)  # atomic: an old file is replaced only by the complete new one
        work.remove()
    return result


def sweep(
    *,
    mu: ArrayLike,
    taus: ArrayLike,
    kx: ArrayLike,
    ky: ArrayLike,
    executor: Executor | None = None,
    output: str | Path | None = None,
    progress: bool = False,
    **options: Any,
) -> SweepResult:
    """Shearing-wave amplification over the grid (μ, τ_s, k_x0, k_y) (module docstring).

    Grids are keyword-only (two array-like physical parameters must not be swappable);
    ``options`` are the other fields of :class:`SweepSpec`. ``executor`` is any
    :class:`concurrent.futures.Executor` (None: this process); ``output`` an HDF5 path
    (resumable, see :func:`run_sweep`).

    Examples
    --------
    k_y = 0: the linA eigenmode's time-averaged growth is its growth rate (consistent drag):

    >>> r = sweep(mu=[3.0], taus=[0.1], kx=[30.0], ky=[0.0], kz=30.0, t_end=2.0)
    >>> round(float(r["mean_growth"][0, 0, 0, 0]), 6)
    0.419009
    """
    names = {f.name for f in fields(SweepSpec)}
    unknown = sorted(set(options) - names)
    if unknown:
        raise UserError(f"sweep: unknown option {unknown[0]!r} (allowed: {', '.join(sorted(names - set(DIMENSIONS)))})")
    spec = SweepSpec(mu=mu, taus=taus, kx=kx, ky=ky, **options)
    return run_sweep(spec, output, executor=executor, progress=progress)


def spec_from_mapping(values: dict[str, Any], source: str = "sweep") -> SweepSpec:
    """A :class:`SweepSpec` from a TOML-like mapping (``mu = [...]`` or ``mu_range = [min, max, n]``)."""
    allowed = {f.name for f in fields(SweepSpec)} | {f"{g}_range" for g in ("mu", "taus", "kx", "ky")}
    kw: dict[str, Any] = {}
    for key, value in values.items():
        if key not in allowed:
            raise UserError(f"{source}.{key}: unknown key (allowed: {', '.join(sorted(allowed))})")
        if key.endswith("_range"):
            grid = key[:-6]
            kw[grid] = grid_from_range(value, f"{source}.{key}", log=grid in ("mu", "taus"))
        else:
            kw[key] = tuple(value) if key == "window" and isinstance(value, list) else value
    missing = [g for g in ("mu", "taus", "kx", "ky") if g not in kw]
    if missing:
        raise UserError(f"{source}: no grid for {missing[0]} (give {missing[0]} = [...] or {missing[0]}_range = "
                        "[min, max, n])")
    return SweepSpec(**kw)


def grid_from_range(value: Sequence, name: str, log: bool) -> np.ndarray:
    """``[min, max, n]`` -> n points, log-spaced (μ, τ_s; min > 0) or evenly spaced (k)."""
    try:
        lo, hi, n = value
        lo, hi = float(lo), float(hi)
        if isinstance(n, bool) or int(n) != n:
            raise ValueError
        n = int(n)
    except (TypeError, ValueError):
        raise UserError(f"{name} = {value!r}: expected [min, max, n]") from None
    if n < 1:
        raise UserError(f"{name} = {value!r}: n must be >= 1 (an empty grid has nothing to sweep)")
    if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi) or (n > 1 and lo == hi):
        raise UserError(f"{name} = {value!r}: expected min < max (or n = 1)")
    if log:
        if lo <= 0:
            raise UserError(f"{name} = {value!r}: a log-spaced grid needs min > 0")
        return np.logspace(math.log10(lo), math.log10(hi), n)
    return np.linspace(lo, hi, n)
