"""Bad input is one line and exit status 2, before anything is written."""

import numpy as np
import pytest

from dustygas.errors import SetupError
from dustygas.grid import GridEngine, Mesh
from dustygas.particles import ParticleGridEngine, ParticleStore

from foundation._cli import cli


@pytest.mark.parametrize("args, fragment", [
    (["si-linA", "--set", "scheme.integrator=rk3"], "scheme.integrator = 'rk3' is not allowed: choose one of vl2"),
    (["si-linA", "--set", "particles.kernel=quartic"], "particles.kernel"),
    (["nsh", "--set", "problem.taus=[0.1, 1.0]"], "problem.taus has 2 species but problem.mu has 1"),
    (["si-settling", "--set", "problem.vz=down"], "problem.vz"),
    (["si-linA", "--set", "problem.kz=0"], "problem.kz = 0"),
])
def test_bad_configuration_one_line_exit_2(tmp_path, args, fragment):
    res = cli("run", *args, "-o", "out", cwd=tmp_path)
    assert res.returncode == 2
    assert fragment in res.stderr and res.stderr.count("\n") == 1
    assert not (tmp_path / "out").exists()


def _gas(boundaries=("periodic", "periodic", "periodic"), integrator="vl2"):
    gas = GridEngine(Mesh((8, 1, 8), (1.0, 1.0, 1.0)), boundaries=boundaries, integrator=integrator)
    gas.set_primitive(1.0)
    return gas


def _store(x=0.0):
    return ParticleStore.create(np.array([[x], [0.0], [0.0]]), np.zeros((3, 1)))


def test_engine_refuses_what_it_cannot_do():
    with pytest.raises(SetupError, match="periodic or shear-periodic"):
        ParticleGridEngine(_gas(("outflow", "periodic", "periodic")), _store(), [0.1])
    with pytest.raises(SetupError, match="vl2"):
        ParticleGridEngine(_gas(integrator="rk2"), _store(), [0.1])
    with pytest.raises(SetupError, match=r"must lie in \[-0.5, 0.5\)"):
        ParticleGridEngine(_gas(), _store(0.7), [0.1])
    with pytest.raises(SetupError, match="stopping times"):
        ParticleGridEngine(_gas(), _store(), [0.0])
    with pytest.raises(SetupError, match="species must be in 0 .. 0"):
        ParticleGridEngine(_gas(), ParticleStore.create(np.zeros((3, 1)), np.zeros((3, 1)), species=1), [0.1])
    with pytest.raises(SetupError, match="particle cfl"):
        ParticleGridEngine(_gas(), _store(), [0.1], cfl=1.5)
    with pytest.raises(SetupError, match="finite"):
        ParticleStore.create(np.full((3, 1), np.nan), np.zeros((3, 1)))
