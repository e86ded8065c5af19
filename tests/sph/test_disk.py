"""The protoplanetary-disk set-up, particle splitting and hierarchical individual time steps.

Analytic checks of the set-up (surface density, scale height, the pressure-supported rotation of
thesis eq. 3.25), exact conservation by the splitting (thesis §3.3.3) and by the pairwise block
time steps (momentum and angular momentum to round-off whatever the levels), agreement of the
individual-step and global-step integrations to second order, one-line errors for bad input, and a
disk run that restarts bit-identically and does not depend on the thread count.
"""

import math
import re
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

from dustygas import api
from dustygas.errors import ConfigError
from dustygas.io.schema import UNDOCUMENTED
from dustygas.physics.disk import eta_armitage, gas_azimuthal_velocity, pressure_exponent
from dustygas.problems import get_problem
from dustygas.sph import Box, EquationOfState, ParticleSet, SPHOptions
from dustygas.sph.disk import DiskModel, cylindrical
from dustygas.sph.particles import DUST
from dustygas.sph.splitting import split_band, split_generations
from dustygas.sph.timesteps import BlockStepEngine, BlockStepOptions

from _runs import assert_runs_identical, run_outputs

SRC = str(Path(__file__).resolve().parents[2] / "src")


def test_disk_setup_matches_the_analytic_disk():
    """Equal-mass particles sample Sigma ~ 1/R (mass per annulus within 1 %), the vertical Gaussian
    (rms z = H within 2 %), and rotate with v_phi = v_K sqrt(1 - eta) at the midplane (eq. 3.25)."""
    disk = DiskModel()
    p = disk.gas_particles(20000, 1.2)
    assert p.mass.sum() == pytest.approx(5e-3, rel=1e-12)
    R, _, vR, vphi = cylindrical(p.pos, p.vel)
    edges = np.array([5.0, 20.0, 50.0, 100.0, 200.0])
    counts = np.histogram(R, edges)[0]
    # Sigma ~ 1/R: equal mass per unit radius
    np.testing.assert_allclose(counts / counts.sum(), np.diff(edges) / 195.0, rtol=1e-2)
    for lo, hi in ((10, 12), (40, 44), (150, 160)):
        sel = (R > lo) & (R < hi)
        zrms = np.sqrt(np.mean((p.pos[sel, 2] / disk.scale_height(R[sel])) ** 2))
        assert zrms == pytest.approx(1.0, abs=0.02)
    mid = np.abs(p.pos[:, 2]) < 0.05 * disk.scale_height(R)
    eta = eta_armitage(pressure_exponent(1.0, 0.5), disk.sound_speed(R[mid]), disk.v_kepler(R[mid]))
    np.testing.assert_allclose(vphi[mid], gas_azimuthal_velocity(disk.v_kepler(R[mid]), eta), rtol=2e-5)
    assert np.abs(vR).max() < 1e-15
    assert float(disk.eta(20.0)) == pytest.approx(2.75 * 0.05**2, rel=1e-12)


def _mixed_particles(n=400, seed=3):
    rng = np.random.default_rng(seed)
    pos = rng.uniform(-60, 60, (n, 3))
    vel = rng.normal(0, 0.1, (n, 3))
    p = ParticleSet.create(pos, vel, mass=rng.uniform(0.5, 1.5, n), h=rng.uniform(0.5, 2.0, n))
    p.ptype[::3] = DUST
    return p


def test_splitting_conserves_mass_momentum_and_angular_momentum():
    """Pair splitting of gas and dust: mass and linear momentum exactly (sums taken exactly with
    math.fsum), centre of mass and angular momentum to round-off (1e-14 relative); 8, 4 and 2
    children in the band and its buffers."""
    p = _mixed_particles()
    q = split_band(p, 20.0, 40.0, (5.0, 5.0))
    assert math.fsum(q.mass) == math.fsum(p.mass) and len(np.unique(q.pid)) == len(q)
    for d in range(3):
        assert math.fsum(q.mass * q.vel[:, d]) == math.fsum(p.mass * p.vel[:, d])
    for f in (lambda s: (s.mass[:, None] * s.pos).sum(0), lambda s: (s.mass[:, None] * np.cross(s.pos, s.vel)).sum(0)):
        a, b = f(p), f(q)
        assert np.abs(a - b).max() < 1e-14 * np.abs(a).max()
    R = np.hypot(p.pos[:, 0], p.pos[:, 1])
    expect = np.where((R >= 20) & (R <= 40), 8, np.where((R >= 15) & (R <= 45), 4, np.where((R >= 10) & (R <= 50), 2, 1)))
    assert len(q) == expect.sum()
    assert (q.ptype == DUST).sum() == expect[p.ptype == DUST].sum()


def test_three_generations_make_a_box_of_eight():
    """One particle split three times: eight of mass m/8 at the corners of a box of edges
    h, h/2^(1/3), h/2^(2/3) along the three axes of its frame, each with h/2."""
    p = ParticleSet.create(np.array([[10.0, 0.0, 0.0]]), np.array([[0.0, 0.3, 0.0]]), mass=1.0, h=0.8)
    q = split_generations(p, np.array([3]), seed=5)
    assert len(q) == 8 and np.all(q.mass == 0.125)
    np.testing.assert_allclose(q.h, 0.4, rtol=1e-14)
    d = q.pos - q.pos.mean(0)
    edges = np.sort(np.linalg.svd(d, compute_uv=False))
    np.testing.assert_allclose(edges / np.sqrt(8) * 2, 0.8 * 2.0 ** (-np.arange(3)[::-1] / 3), rtol=1e-12)


def _box_engine(individual, c_cour=0.3, steps_kw=None):
    """A periodic 3D box with an isothermal overdense blob moving through it: the blob's particles
    take shorter steps than the rest, so several levels are in use."""
    rng = np.random.default_rng(1)
    n = 8
    g = (np.arange(n) + 0.5) / n
    pos = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    pos += rng.uniform(-0.1, 0.1, pos.shape) / n
    blob = np.linalg.norm(pos - 0.5, axis=1) < 0.25
    pos[blob] = 0.5 + 0.6 * (pos[blob] - 0.5)  # denser
    vel = np.where(blob[:, None], [0.6, 0.2, 0.0], 0.0) + rng.normal(0, 0.05, pos.shape)
    p = ParticleSet.create(pos, vel, mass=1.0 / n**3, h=1.2 / n, alpha=0.1)
    opts = SPHOptions(switch="none", alpha=0.1, c_cour=c_cour, neighbour_search="tree", reorder_every=0)
    return BlockStepEngine(p, Box.periodic_box(3, (0.0,) * 3, (1.0,) * 3), EquationOfState.isothermal(1.0), opts,
                           steps=BlockStepOptions(individual=individual, dt_max=0.02, **(steps_kw or {})))


def test_block_steps_conserve_momentum_to_round_off():
    """Pairwise kicks: the total momentum of the box after five blocks on several levels (with
    wake-ups) equals the initial one to 1e-15 of the momentum of the moving blob."""
    eng = _box_engine(True)
    h0 = eng.history()
    scale = np.abs(eng.particles.mass[:, None] * eng.particles.vel).sum()
    levels = set()
    for _ in range(5):
        eng.advance(eng.timestep())
        levels |= set(np.unique(eng.level).tolist())
    h1 = eng.history()
    assert len(levels) >= 3
    for ax in "xyz":
        assert abs(h1[f"momentum_{ax}"] - h0[f"momentum_{ax}"]) < 1e-15 * scale


def _box_run(individual, c_cour, tend=0.06):
    e = _box_engine(individual, c_cour)
    while e.t < tend * (1 - 1e-12):
        e.advance(min(e.timestep(), tend - e.t))
    return e.particles.pos


def test_individual_steps_are_second_order():
    """Positions after the same time against a run with an eight times smaller Courant factor: the
    error of the individual-step run falls by about four when the factor is halved (measured 3.64),
    and at equal Courant factor it is within a factor two of the global-step run's (measured 1.8)."""
    ref = _box_run(True, 0.0375)
    err = [np.sqrt(np.mean((_box_run(True, c) - ref) ** 2)) for c in (0.3, 0.15)]
    assert 3.2 < err[0] / err[1] < 4.5
    ref_global = _box_run(False, 0.0375)
    err_global = np.sqrt(np.mean((_box_run(False, 0.3) - ref_global) ** 2))
    assert err[0] < 2.0 * err_global


def test_disk_with_dust_conserves_angular_momentum_with_individual_steps():
    """A small disk with a dust ring, individual steps and accretion: total angular momentum (gas,
    dust and the star's accreted share) constant to 1e-13 relative over four blocks."""
    prob = get_problem("drift-ring")
    cfg = prob.config(overrides=["disk.n_gas=800", "dust.n_ring=50", "disk.relax=none"])
    eng = prob.build(cfg)
    h0 = eng.history()
    for _ in range(4):
        eng.advance(eng.timestep())
    h1 = eng.history()
    assert h1["levels"] >= 3 and (eng.particles.ptype == DUST).sum() == 150
    assert abs(h1["angular_momentum_z"] / h0["angular_momentum_z"] - 1) < 1e-13
    assert h1["mass"] == pytest.approx(h0["mass"], rel=1e-14)


@pytest.mark.parametrize("override, message", [
    ("disk.r_in=250", "disk.r_in = 250 must be smaller than disk.r_out = 200"),
    ("split.r1=1", "split.r1 = 1, split.r2 = 70: the splitting band must lie inside the disk"),
    ("dust.ring_taus=5000", "dust.ring_taus = 5000.0 is out of range: allowed 0.001 <= value <= 1000"),
    ("dust.ring_taus=[1,2]", "dust.ring_taus has 2 values for 1 dust.ring_radii"),
    ("dust.ring_radii=300", "dust.ring_radii = 300 au lies outside the disk"),
])
def test_bad_disk_input_is_a_one_line_error(tmp_path, override, message):
    extra = ["split.enabled=true"] if override.startswith("split") else ["dust.enabled=true"]
    with pytest.raises(ConfigError, match=re.escape(message)) as info:
        api.run("sph-disk", output=tmp_path / "r", set=[override, *extra])
    assert "\n" not in str(info.value)
    assert not (tmp_path / "r").exists()


def test_grains_outside_the_epstein_regime_are_refused():
    """In a 0.1 M_sun disk the gas mean free path at 6 au is about 1.4 m; tau_s = 100 there needs
    grains of about 26 m, beyond 9/4 of it (Stokes drag): a one-line error, as is tau_s > 1000."""
    prob = get_problem("sph-disk")
    with pytest.raises(ConfigError, match="dust.ring_taus = 100 at 6 au needs grains of .* beyond the Epstein regime"):
        prob.config(overrides=["dust.enabled=true", "disk.disk_mass=0.1", "dust.ring_radii=6", "dust.ring_taus=100"])
    prob.config(overrides=["dust.enabled=true", "dust.ring_radii=6", "dust.ring_taus=100"])  # 5e-3 M_sun: fine


_RUN = ["disk.n_gas=600", "dust.n_ring=30", "run.tlim=160", "run.dt_snapshot=80", "steps.dt_max=0.02"]


def _undocumented(path):
    names = []
    with h5py.File(path, "r") as f:
        f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset)
                     and o.attrs.get("units") == UNDOCUMENTED else None)
    return names


def test_disk_run_restarts_bit_identically(tmp_path):
    """A drift-ring run stopped after four blocks and restarted from its checkpoint ends identical,
    bit for bit, to an uninterrupted run (snapshots and history); every dataset it writes (ring,
    track and level fields, ring / track / block-step history columns) has documented units."""
    api.run("drift-ring", output=tmp_path / "ref", set=_RUN)
    for path in [tmp_path / "ref" / "history.h5", *sorted((tmp_path / "ref" / "snapshots").glob("*.h5"))]:
        assert _undocumented(path) == [], path
    cut = api.run("drift-ring", output=tmp_path / "cut", set=_RUN + ["run.max_cycles=4"])
    assert cut.status == "max_cycles"
    api.restart(tmp_path / "cut", set=["run.max_cycles=0"])
    assert_runs_identical(run_outputs(tmp_path / "ref"), run_outputs(tmp_path / "cut"))


@pytest.mark.slow
def test_disk_run_independent_of_thread_count(tmp_path):
    """The same drift-ring run on one and on two numba threads (separate processes) gives identical
    histories and final snapshots. (Slow: two fresh interpreters load every kernel, ~45 s.)"""
    outs = []
    for threads in (1, 2):
        env = {**os.environ, "NUMBA_NUM_THREADS": str(threads), "PYTHONPATH": SRC}
        cmd = [sys.executable, "-m", "dustygas", "run", "drift-ring", "-o", str(tmp_path / f"t{threads}"), "-q",
               *[x for a in _RUN for x in ("--set", a)], "--set", f"run.threads={threads}"]
        proc = subprocess.run(cmd, env=env, capture_output=True, text=True)
        assert proc.returncode == 0, proc.stderr
        outs.append(run_outputs(tmp_path / f"t{threads}"))
    assert_runs_identical(*outs)

