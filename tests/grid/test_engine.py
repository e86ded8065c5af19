"""Engine plumbing: restarts, thread-count independence, the particle hook, geometry, errors."""

import numpy as np
import pytest

from dustygas import api
from dustygas.errors import SetupError, SimulationError
from dustygas.grid import GridEngine, Mesh

from _runs import assert_runs_identical, run_outputs
from _threads import assert_identical, results_at_threads
from foundation._cli import cli_in_process

from ._helpers import run_to


@pytest.mark.parametrize("problem, extra", [
    ("shearing-wave", ["grid.nx=16", "grid.ny=16", "shearing_box.orbital_advection=true"]),
    ("shearing-wave", ["grid.nx=16", "grid.ny=16", "scheme.integrator=rk3", "scheme.reconstruction=ppm-cs"]),
])
def test_restart_from_checkpoint_is_bit_identical(tmp_path, problem, extra):
    common = [*extra, "run.tlim=0.5", "run.dt_snapshot=0.1", "run.log_every=1000000"]
    full = api.run(problem, output=tmp_path / "full", set=common)
    assert full.status == "finished"
    part = api.run(problem, output=tmp_path / "part", set=[*common, f"run.max_cycles={full.cycles // 2}"])
    assert part.status == "max_cycles"
    again = api.restart(tmp_path / "part", set=["run.max_cycles=0"])
    assert again.status == "finished" and again.cycles == full.cycles - full.cycles // 2
    assert_runs_identical(run_outputs(tmp_path / "full"), run_outputs(tmp_path / "part"))


def _shearing_box(oa: bool, integrator: str = "vl2", shape=(24, 20, 1)) -> GridEngine:
    eng = GridEngine(Mesh(shape, (1.0, 1.0, 1.0)), boundaries=("shear-periodic", "periodic", "periodic"),
                     omega=1.0, orbital_advection=oa, reconstruction="ppm", riemann="hllc", integrator=integrator,
                     cfl=0.3)
    x, y, z = eng.mesh.meshgrid()
    eng.set_primitive(1 + 0.2 * np.sin(2 * np.pi * (x + y)) + 0 * z, 0.1 * np.cos(2 * np.pi * y) + 0 * x + 0 * z,
                      -1.5 * x + 0.05 * np.sin(2 * np.pi * x) + 0 * y + 0.01 * np.cos(2 * np.pi * z), 0.0)
    return eng


#: (8, 128, 1) and 3D take the parallel ghost-remap and flux-correction paths; 3D without orbital
#: advection measures its Courant rate in the z sweep, which two threads run in two slabs of 4 and 5 planes
THREAD_CASES = (((24, 20, 1), True), ((8, 128, 1), False), ((12, 10, 8), True), ((12, 10, 9), False))


def thread_case() -> dict:
    """Ten steps of each shearing box of :data:`THREAD_CASES` (run by :func:`results_at_threads`)."""
    out = {}
    for shape, oa in THREAD_CASES:
        eng = _shearing_box(oa, shape=shape)
        for _ in range(10):
            eng.advance(eng.timestep())
        tag = "x".join(map(str, shape))
        history = eng.history()
        out |= {f"state_{tag}": eng.state, f"budget_{tag}": eng.budget,
                f"history_{tag}": np.array([history[k] for k in sorted(history)])}
    return out


def test_results_do_not_depend_on_the_thread_count(tmp_path):
    """One and two threads (each in its own interpreter) give bit-identical states, budgets and
    history rows."""
    results = results_at_threads("grid.test_engine:thread_case", tmp_path)
    assert_identical(results)
    assert np.ptp(results[0]["state_24x20x1"][0]) > 0.1  # the boxes did evolve a non-trivial flow


@pytest.mark.parametrize("integrator", ["vl2", "rk3"])
def test_stage_hook_without_source_is_bit_identical_to_advance(integrator):
    a, b = _shearing_box(False, integrator), _shearing_box(False, integrator)
    seen = []
    for _ in range(5):
        dt = a.timestep()
        a.advance(dt)
        b.advance_with_sources(dt, lambda s, u, t, h: seen.append((s, t, h)))
    np.testing.assert_array_equal(a.state, b.state)
    np.testing.assert_array_equal(a.budget, b.budget)
    stages = 2 if integrator == "vl2" else 3
    assert [s for s, _, _ in seen] == list(range(stages)) * 5


@pytest.mark.parametrize("integrator", ["vl2", "rk2", "rk3"])
def test_external_momentum_source_enters_with_the_step_weight(integrator):
    """A uniform force density f on uniform gas: total momentum grows as f V t (to round-off)."""
    eng = GridEngine(Mesh((16, 8, 1), (2.0, 1.0, 1.0)), integrator=integrator)
    eng.set_primitive(1.0, 0.1, 0.0, 0.0)
    f = np.array([0.3, -0.2, 0.1])
    src = np.broadcast_to(f[:, None, None, None], (3, 1, 8, 16)).copy()
    stages = []

    def hook(stage, u, t, dt_stage):
        stages.append(stage)
        return src

    while eng.t < 1.0 - 1e-14:
        eng.advance_with_sources(min(eng.timestep(), 1.0 - eng.t), hook)
    h = eng.history()
    volume = 2.0
    assert h["momentum_x"] == pytest.approx((0.1 + f[0] * 1.0) * volume, rel=1e-13)
    assert h["momentum_y"] == pytest.approx(f[1] * volume, rel=1e-13)
    assert h["momentum_z"] == pytest.approx(f[2] * volume, rel=1e-13)
    assert set(stages) == set(range({"vl2": 2, "rk2": 2, "rk3": 3}[integrator]))


def test_geometry_interface_and_ghost_corners_of_a_shearing_box():
    eng = GridEngine(Mesh((8, 12, 1), (2.0, 3.0, 1.0)), boundaries=("shear-periodic", "periodic", "periodic"),
                     omega=1.0, q=1.5)
    g = eng.geometry
    assert g.shape == (8, 12, 1) and g.nghost == (3, 3, 0)
    assert g.lower == (-1.0, -1.5, 0.0) and g.dx == (0.25, 0.25, 1.0) and g.box == (2.0, 3.0, 1.0)
    assert g.shear_periodic and not g.velocity_relative_to_shear
    assert g.shear_velocity_jump == 3.0  # q Omega Lx
    assert g.shear_offset(0.7 / 3.0) == pytest.approx(0.7)  # q Omega Lx t
    assert g.shear_offset(1.0) == pytest.approx(0.0, abs=1e-12)  # 3 = Ly: back in register
    rng = np.random.default_rng(0)
    rho = 1 + 0.1 * rng.random((1, 12, 8))
    my = rng.standard_normal((1, 12, 8))
    eng.set_primitive(rho, 0.0, my / rho, 0.0)
    u = eng.fill_ghosts(t=0.25)  # offset 0.75 = 3 cells exactly: the remap is a copy
    gx, gy = 3, 3
    for i_ghost, i_src, shift, jump in ((0, 5, 3, 3.0), (11, 0, -3, -3.0)):
        for jg in range(12 + 2 * gy):  # every row, ghost rows (corners) included
            j_src = (jg - gy - shift) % 12
            assert u[0, 0, jg, i_ghost] == rho[0, j_src, i_src]
            assert u[2, 0, jg, i_ghost] == pytest.approx(my[0, j_src, i_src] + jump * rho[0, j_src, i_src], rel=1e-15)


def test_reflecting_and_outflow_walls():
    """A pulse between reflecting walls keeps its mass exactly; outflow lets it leave."""
    masses = {}
    for kind in ("reflecting", "outflow"):
        eng = GridEngine(Mesh((64, 1, 1), (1.0, 1.0, 1.0)), boundaries=(kind, "periodic", "periodic"))
        x = eng.mesh.centers(0)
        eng.set_primitive(1 + 0.5 * np.exp(-(x / 0.05) ** 2), 0.3, 0.0, 0.0)
        m0 = eng.history()["mass"]
        run_to(eng, 2.0)
        masses[kind] = eng.history()["mass"] / m0 - 1
    assert abs(masses["reflecting"]) < 1e-14
    assert masses["outflow"] < -0.01


def test_invalid_state_raises_simulation_error_with_the_state():
    eng = GridEngine(Mesh((16, 1, 1), (1.0, 1.0, 1.0)))
    eng.set_primitive(1.0, 0.0, 0.0, 0.0)
    eng.state[0, 0, 0, 3 + 5] = np.nan
    eng.advance(0.01)
    with pytest.raises(SimulationError, match=r"invalid gas state in cell \(i=\d+") as err:
        eng.timestep()
    assert set(err.value.state) == {"rho", "vx", "vy", "vz"}


@pytest.mark.parametrize("kwargs, message", [
    ({"boundaries": ("periodic", "shear-periodic", "periodic")}, "only the x axis"),
    ({"reconstruction": "weno"}, "reconstruction 'weno' unknown"),
    ({"orbital_advection": True}, "needs a rotating frame"),
    ({"cfl": 0.6}, "stable for 0 < cfl <= 0.5"),
])
def test_bad_setup_is_a_one_line_error(kwargs, message):
    with pytest.raises(SetupError, match=message):
        GridEngine(Mesh((8, 8, 1), (1.0, 1.0, 1.0)), **kwargs)


@pytest.mark.parametrize("args, message", [
    (["soundwave-3d", "--set", "scheme.cfl=0.4"], "scheme.cfl = 0.4 is out of range: allowed 0 < value <= 1/ndim"),
    (["soundwave", "--set", "problem.waves=[1, 1, 0]"], "inactive axis"),
    (["epicycle", "--set", "shearing_box.omega=0"], "needs a rotating frame"),
    (["shocktube", "--set", "scheme.riemann=roe"], "scheme.riemann"),
])
def test_cli_refuses_bad_input_without_writing(tmp_path, args, message):
    proc = cli_in_process("run", *args, "-o", "out", cwd=tmp_path)
    assert proc.returncode == 2
    assert message in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("shape, oa, bx", [((24, 20, 1), False, "shear-periodic"), ((24, 20, 1), True, "shear-periodic"),
                                           ((16, 1, 12), False, "shear-periodic"), ((12, 10, 8), False, "periodic"),
                                           ((32, 1, 1), False, "outflow")])
def test_time_step_from_the_fused_reduction_equals_a_separate_pass(shape, oa, bx):
    """The Courant rate is reduced inside the last sweep (or the remap) of a step; it must equal
    a separate pass over the new state, which is what a restart computes."""
    from dustygas.grid.diagnostics import max_signal_rate

    eng = GridEngine(Mesh(shape, (1.0, 1.0, 1.0)), boundaries=(bx, "periodic", "periodic"), omega=1.0,
                     orbital_advection=oa, cfl=0.3)
    x, y, z = eng.mesh.meshgrid()
    rng = np.random.default_rng(3)
    full = tuple(reversed(shape))
    eng.set_primitive(1 + 0.3 * rng.random(full), 0.5 * rng.standard_normal(full), -1.5 * x + rng.standard_normal(full),
                      0.2 * rng.standard_normal(full))
    for _ in range(3):
        eng.advance(eng.timestep())
        rate, bad = max_signal_rate(eng.state, eng.mesh.layout, eng.mesh.spacing, eng.cs)
        assert bad == -1
        assert eng.timestep() == eng.cfl / rate
