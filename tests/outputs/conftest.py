"""Small runs of each engine, made once per session, for the output tests.

The engines run on one numba thread (``run.threads = 1``, restored afterwards), like the engine
test areas (``tests/_threads.py``).
"""

import numba
import pytest

from _threads import one_numba_thread  # noqa: F401  (autouse fixture)

#: soundwave-2d: 16 x 8 cells (x and y must not be confused), a large amplitude to see
GRID = ("soundwave-2d", ["grid.nx=16", "grid.ny=8", "problem.amplitude=0.1", "run.tlim=0.05",
                         "run.dt_snapshot=0.025", "run.threads=1"])
#: si-linA in a 16 x 16 radial-vertical box: gas + Lagrangian particles
PARTICLES = ("si-linA", ["grid.nx=16", "grid.nz=16", "run.tlim=0.002", "run.threads=1", "problem.amplitude=0.01"])
#: the one-fluid dust settling column (1D SPH, dust fraction on every particle)
SPH = ("dust-settle", ["run.tlim=0.01", "run.threads=1"])
#: 2D SPH sound wave (kernel rendering)
SPH2D = ("sph-soundwave-2d", ["run.tlim=0.01", "run.threads=1"])


def _make(tmp_path_factory, spec):
    from dustygas import api

    name, overrides = spec
    before = numba.get_num_threads()
    try:
        path = tmp_path_factory.mktemp(name) / "run"
        api.run(name, output=path, set=overrides)
    finally:
        numba.set_num_threads(before)
    return path


def _session_run(spec):
    @pytest.fixture(scope="session")
    def fixture(tmp_path_factory):
        return _make(tmp_path_factory, spec)

    return fixture


grid_run = _session_run(GRID)
particle_run = _session_run(PARTICLES)
sph_run = _session_run(SPH)
sph2d_run = _session_run(SPH2D)
