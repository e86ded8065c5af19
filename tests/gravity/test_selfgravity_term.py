"""Particle self-gravity as a term of the particle-gas engine (:mod:`dustygas.particles.gravity`).

* Momentum: a random 3D box of gas and two particle species (fixed and Epstein drag, back-reaction
  on), no rotation, self-gravity G~ = 2 (forces comparable with the drag): the deposit and the
  gather share their weights and the mesh force is antisymmetric, so the total momentum of gas +
  particles may change only by round-off -- tolerance 1e-10 relative per orbit (2 pi), relative
  to sum |rho u| V + sum |m v| (measured 8.2e-16 periodic, 3.5e-15 vacuum z, per orbit). The net
  impulse of the self-gravity alone (the history's particle terms impulse, the only term) is
  round-off too, while the same box without gravity ends with particle velocities 1e-2 away.
* The gathered acceleration of a particle lattice carrying a density wave 1 + A cos(k x) equals the
  analytic -grad(Phi) = -(G~ A / k) sin(k x) times the transfer function of the scheme: TSC
  deposit and gather sinc^6(k dx/2), the filter 1 - sin^4(k dx/2), the centred difference
  sin(k dx)/(k dx) (0.936 at 16 cells per wavelength) -- to 1e-3 of the amplitude (measured 4.7e-4).
* One-line errors (exit 2, nothing written) for G~ <= 0 and an axis the potential cannot support;
  a si3d-selfgravity run stopped and restarted across the switch-on is bit-identical, and every
  column and dataset it writes is in the output schema.
"""

import math

import numpy as np
import pytest
from _runs import assert_runs_identical, run_outputs

from dustygas import api
from dustygas.errors import SetupError
from dustygas.grid import GridEngine, Mesh
from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory
from dustygas.io.schema import UNDOCUMENTED, history_quantity, snapshot_quantity
from dustygas.particles import ParticleGridEngine, ParticleStore
from dustygas.particles.gravity import SelfGravity, gravity_boundaries
from dustygas.particles.params import lattice_positions

from foundation._cli import cli_in_process


def random_box(gravity: bool, boundary_z: str, seed: int = 3) -> ParticleGridEngine:
    rng = np.random.default_rng(seed)
    shape = (12, 12, 12)
    mesh = Mesh(shape, (1.0, 1.0, 1.0))
    gas = GridEngine(mesh, cs=1.0, reconstruction="ppm", riemann="hllc", cfl=0.3)
    sh = tuple(reversed(shape))
    gas.set_primitive(1 + 0.3 * rng.random(sh), 0.1 * rng.standard_normal(sh), 0.1 * rng.standard_normal(sh),
                      0.1 * rng.standard_normal(sh))
    n = 2 * mesh.ncells
    pos = np.asarray(mesh.lower)[:, None] + rng.random((3, n))
    if boundary_z == "vacuum":  # a layer well inside the box (vacuum z: nothing near the faces)
        pos[2] = -0.15 + 0.3 * rng.random(n)
    store = ParticleStore.create(pos, 0.1 * rng.standard_normal((3, n)), rng.integers(0, 2, n),
                                 mesh.cell_volume * rng.uniform(0.5, 1.5, n))
    terms = [SelfGravity(2.0, 0.0, boundary_z)] if gravity else []
    return ParticleGridEngine(gas, store, [0.05, 0.2], drag_law=["fixed", "epstein"], particle_terms=terms)


def _scale(eng) -> float:
    rho, vx, vy, vz = eng.gas.primitive()
    return float(np.sum(rho * (np.abs(vx) + np.abs(vy) + np.abs(vz))) * eng.mesh.cell_volume
                 + np.sum(eng.particles.mass * np.abs(eng.particles.vel).sum(axis=0)))


@pytest.mark.parametrize("boundary_z", ["periodic", "vacuum"])
def test_self_gravity_conserves_total_momentum(boundary_z):
    eng, ref = random_box(True, boundary_z), random_box(False, boundary_z)
    p0 = np.array([eng.history()[f"total_momentum_{a}"] for a in "xyz"])
    t_end = 0.25
    for e in (eng, ref):
        while e.t < t_end * (1 - 1e-14):
            e.advance(min(e.timestep(), t_end - e.t))
    h = eng.history()
    drift = np.abs(np.array([h[f"total_momentum_{a}"] for a in "xyz"]) - p0).max() / _scale(eng)
    impulse = np.abs([h[f"particle_terms_impulse_{a}"] for a in "xyz"]).max() / _scale(eng)
    print(f"{boundary_z}: momentum drift {drift * 2 * math.pi / t_end:.3g} per orbit, gravity impulse {impulse:.3g}")
    assert drift * (2 * math.pi / t_end) < 1e-10, drift
    assert impulse < 1e-12, impulse
    assert h["gravity_on"] == 1.0 and eng.cycle > 10
    # gravity did act: the particles are far from where they are without it (same ids, same order)
    by_id = lambda e: e.particles.vel[:, np.argsort(e.particles.pid)]  # noqa: E731
    assert np.abs(by_id(eng) - by_id(ref)).max() > 1e-2


def test_gathered_acceleration_of_a_density_wave():
    """rho_p = 1 + A cos(k x), G~ = 1: g_x = -dPhi/dx = -(G~ A / k) sin(k x) T at every particle."""
    n, A, g_tilde = 16, 0.1, 1.0
    mesh = Mesh((n, 1, 1), (1.0, 1.0, 1.0))
    gas = GridEngine(mesh, cs=1.0)
    gas.set_primitive(1.0)
    k = 2 * math.pi
    s0 = lattice_positions(mesh.shape, mesh.lower, mesh.dx, 8, 0.5)[0]
    x = s0.copy()
    for _ in range(50):  # Lagrangian map of the wave: x + (A/k) sin(k x) = s0 (uniform lattice)
        x -= (x + A / k * np.sin(k * x) - s0) / (1 + A * np.cos(k * x))
    x = (x - mesh.lower[0]) % 1.0 + mesh.lower[0]
    pos = np.stack([x, np.zeros_like(x), np.zeros_like(x)])
    store = ParticleStore.create(pos, np.zeros_like(pos), 0, np.full(x.size, 1.0 / x.size))
    term = SelfGravity(g_tilde)
    eng = ParticleGridEngine(gas, store, [1e6], feedback=False, particle_terms=[term])
    eng.advance(1e-6)
    xp = eng.particles.pos[0]
    g = eng.particles.vel[0] / 1e-6
    theta = k * mesh.dx[0]
    transfer = (np.sin(theta / 2) / (theta / 2)) ** 6 * (1 - np.sin(theta / 2) ** 4) * np.sin(theta) / theta
    exact = -g_tilde * A / k * np.sin(k * xp) * transfer
    err = np.abs(g - exact).max() / (g_tilde * A / k)
    print(f"density-wave acceleration: max error {err:.3g} of G~A/k (transfer {transfer:.6f})")
    assert err < 1e-3, err


@pytest.mark.parametrize("args, fragment", [
    (["--set", "gravity.g_tilde=0"], "gravity.g_tilde"),
    (["--set", "gravity.g_tilde=-0.1"], "gravity.g_tilde"),
    (["--set", "problem.gas_boundary_z=hydrostatic", "--set", "gravity.boundary_z=periodic"],  # open z faces
     "gravity.boundary_z = 'periodic' with particles.boundary_z = 'outflow'"),
    (["--set", "gravity.t_on=1000"], "gravity.t_on = 1000: the run ends before"),
])
def test_bad_gravity_input_one_line_exit_2(tmp_path, args, fragment):
    res = cli_in_process("run", "si3d-selfgravity", *args, "-o", "out", cwd=tmp_path)
    assert res.returncode == 2, res.stderr
    assert fragment in res.stderr and res.stderr.count("\n") == 1, res.stderr
    assert not (tmp_path / "out").exists()


def test_axes_the_potential_cannot_support():
    with pytest.raises(SetupError, match="particles.boundary_x = 'outflow' is not supported"):
        gravity_boundaries((8, 8, 8), ("outflow", "periodic", "periodic"))
    with pytest.raises(SetupError, match="only x can be shear-periodic"):
        gravity_boundaries((8, 8, 8), ("periodic", "shear-periodic", "periodic"))
    with pytest.raises(SetupError, match="gravity.g_tilde = 0.0: must be positive"):
        SelfGravity(0.0)


def test_restart_across_the_switch_on_is_bit_identical_and_documented(tmp_path):
    sets = ["grid.nx=8", "grid.ny=8", "grid.nz=12", "gravity.t_on=0.03", "run.tlim=0.08", "run.dt_snapshot=0.02",
            "run.dt_history=0.01", "run.threads=1"]
    ref = api.run("si3d-selfgravity", output=tmp_path / "ref", set=sets)
    assert ref.status == "finished" and ref.cycles > 8
    first = api.run("si3d-selfgravity", output=tmp_path / "stopped", set=sets + ["run.max_cycles=5"])
    assert first.status == "max_cycles"
    again = api.restart(tmp_path / "stopped", set=["run.max_cycles=0"])
    assert again.status == "finished"
    out_ref, out = run_outputs(tmp_path / "ref"), run_outputs(tmp_path / "stopped")
    assert_runs_identical(out_ref, out)
    hist = out_ref["history"][0]
    assert hist["gravity_on"][0] == 0.0 and hist["gravity_on"][-1] == 1.0
    for name in hist:
        assert history_quantity(name).units != UNDOCUMENTED, name
    arrays, attrs = read_h5(RunDirectory(tmp_path / "ref").snapshots()[-1])
    assert "phi_p" in arrays and attrs["gravity_G"] == pytest.approx(0.5 / (4 * math.pi), rel=1e-15)
    for name in arrays:
        assert snapshot_quantity(name).units != UNDOCUMENTED, name
