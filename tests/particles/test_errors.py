"""Bad input is one line and exit status 2, before anything is allocated or written."""

import numpy as np
import pytest

from dustygas.errors import SetupError
from dustygas.grid import GridEngine, Mesh
from dustygas.particles import ParticleGridEngine, ParticleStore, VerticalGravity

from foundation._cli import cli_in_process


@pytest.mark.parametrize("args, fragment", [
    (["si-linA", "--set", "scheme.integrator=rk3"], "scheme.integrator = 'rk3' is not allowed: choose one of vl2"),
    (["si-linA", "--set", "particles.kernel=quartic"], "particles.kernel"),
    (["nsh", "--set", "problem.taus=[0.1, 1.0]"], "problem.taus has 2 species but problem.mu has 1"),
    (["si-settling", "--set", "problem.vz=down"], "problem.vz"),
    (["si-linA", "--set", "problem.kz=0"], "problem.kz = 0"),
    (["si3d", "--set", "problem.Hp=0"], "problem.Hp"),
    (["si3d", "--set", "problem.Hp=0.06"], "problem.Hp = 0.06: the layer"),
    (["si3d", "--set", "problem.per_cell=1e6"], "problem.per_cell = 1e+06"),
    (["si3d", "--set", "particles.boundary_x=outflow"], "particles.boundary_x = 'outflow'"),
    (["si3d", "--set", "particles.boundary_z=shear-periodic"], "particles.boundary_z = 'shear-periodic'"),
])
def test_bad_configuration_one_line_exit_2(tmp_path, args, fragment):
    res = cli_in_process("run", *args, "-o", "out", cwd=tmp_path)
    assert res.returncode == 2, res.stderr
    assert fragment in res.stderr and res.stderr.count("\n") == 1, res.stderr
    assert not (tmp_path / "out").exists()


def _gas(boundaries=("periodic", "periodic", "periodic"), integrator="vl2"):
    gas = GridEngine(Mesh((8, 1, 8), (1.0, 1.0, 1.0)), boundaries=boundaries, integrator=integrator)
    gas.set_primitive(1.0)
    return gas


def _store(x=0.0):
    return ParticleStore.create(np.array([[x], [0.0], [0.0]]), np.zeros((3, 1)))


@pytest.mark.parametrize("make, match", [
    (lambda: ParticleGridEngine(_gas(("outflow", "periodic", "periodic")), _store(), [0.1],
                                boundaries=("periodic", "periodic", "periodic")), "boundary_x = 'periodic'"),
    (lambda: ParticleGridEngine(_gas(integrator="rk2"), _store(), [0.1]), "vl2"),
    (lambda: ParticleGridEngine(_gas(), _store(0.7), [0.1]), r"must lie in \[-0.5, 0.5\)"),
    (lambda: ParticleGridEngine(_gas(), _store(), [0.0]), "stopping times"),
    (lambda: ParticleGridEngine(_gas(), ParticleStore.create(np.zeros((3, 1)), np.zeros((3, 1)), species=1), [0.1]),
     "species must be in 0 .. 0"),
    (lambda: ParticleGridEngine(_gas(), _store(), [0.1], cfl=1.5), "particle cfl"),
    (lambda: ParticleStore.create(np.full((3, 1), np.nan), np.zeros((3, 1))), "finite"),
    (lambda: ParticleGridEngine(GridEngine(Mesh((8, 1, 1), (1.0, 1.0, 1.0))), _store(), [0.1],
                                particle_terms=[VerticalGravity(1.0)]), "vertical gravity on the particles"),
])
def test_engine_refuses_what_it_cannot_do(make, match):
    with pytest.raises(SetupError, match=match):
        make()


PLANT_NAN = """
import sys
from dustygas.cli import main
from dustygas.particles.coupling import ParticleGridEngine

step = ParticleGridEngine.advance


def advance(self, dt):  # a particle position turns NaN in the second step
    step(self, dt)
    if self.cycle == 2:
        self.particles.pos[0, 5] = float("nan")


ParticleGridEngine.advance = advance
sys.exit(main(sys.argv[1:]))
"""


def test_nan_particle_position_stops_the_run_with_exit_3_and_a_crash_dump(tmp_path):
    """A NaN position would never find its cell (the stencil's search loops forever): the engine
    checks every particle before it sorts them, and the run loop stops like for a NaN in the gas --
    one line naming the particle, the field, time and cycle; exit 3; crash.h5 with the state."""
    import re
    import subprocess
    import sys

    import h5py

    from foundation._cli import env

    proc = subprocess.run([sys.executable, "-c", PLANT_NAN, "run", "nsh", "-q", "-o", "out", "--set", "grid.nx=8",
                           "--set", "grid.nz=8", "--set", "run.tlim=1", "--set", "run.dt_history=0"],
                          cwd=tmp_path, env=env(), capture_output=True, text=True, timeout=300)
    assert proc.returncode == 3, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "Traceback" not in proc.stderr, proc.stderr
    assert re.fullmatch(r"dustygas: simulation stopped: invalid particle state \(particle pid=5, species 0\) "
                        r"at time=0\.0099\d* cycle=2: x=nan", lines[0]), lines[0]
    assert "x=nan (state dumped to crash.h5)" in (tmp_path / "out" / "log.txt").read_text()
    with h5py.File(tmp_path / "out" / "crash.h5") as f:
        assert "invalid particle state" in f.attrs["error"]
        x = f["offending/particle_pos"][0]
        assert x.size == 64 and np.isnan(x).sum() == 1
