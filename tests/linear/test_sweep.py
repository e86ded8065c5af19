"""The shearing-wave sweep (thesis §4.6.2): analytic limits, executors, resuming, files, errors.

Limits checked at every grid point:

* k_y = 0: the wave is the axisymmetric eigenmode, so the time-averaged growth over the
  integration equals the growth rate of :func:`dustygas.linear.growth_rate` (to 1e-6; measured
  ≤ 3e-9 with rtol = 1e-9);
* pure gas, incompressible, k_z = 0: the Kelvin (1887) / Goldreich & Lynden-Bell (1965) vortical
  shearing wave keeps its vorticity, |u| ∝ 1/|k(t)|, so E(t)/E(0) = k(0)²/k(t)²: over a swing
  the peak amplification is (1 + k_x0²/k_y²)^{1/2} at t = −k_x0/(1.5 k_y) and the net
  amplification 1 (to 1e-6; measured ≤ 1e-9).
"""

import hashlib
import math
import os
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import h5py
import numpy as np
import pytest

from dustygas.cli import build_parser, main
from dustygas.cli._linear_sweep import build_spec
from dustygas.errors import UserError
from dustygas.linear import StreamingParams, growth_rate
from dustygas.linear.shearing_wave import shearing_wave
from dustygas.linear.sweep import SweepResult, SweepSpec
from dustygas.linear.sweep_run import run_sweep, sweep

TESTS = Path(__file__).resolve().parents[1]
SRC = TESTS.parent / "src"


def _env(**extra) -> dict:
    e = dict(os.environ, **extra)
    e["PYTHONPATH"] = os.pathsep.join([str(SRC), e.get("PYTHONPATH", "")])
    return e


def _cli(*args, cwd, timeout=600):
    return subprocess.run([sys.executable, "-m", "dustygas", "linear", "sweep", *args, "--no-progress"], cwd=cwd,
                          env=_env(), capture_output=True, text=True, timeout=timeout)


def _one_line_error(proc, fragment):
    assert proc.returncode == 2, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("dustygas: error:"), proc.stderr
    assert fragment in lines[0], lines[0]


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


# ---------------------------------------------------------------------------- analytic limits


def test_ky_zero_is_the_axisymmetric_growth_rate_at_every_point():
    mu, taus, kx = [0.2, 1.0, 3.0], [0.03, 0.1, 1.0], [3.0, 10.0, 30.0, 100.0]
    r = sweep(mu=mu, taus=taus, kx=kx, ky=[0.0], kz=30.0, t_end=1.0, rtol=1e-9, atol=1e-14)
    M, T, KX = np.meshgrid(mu, taus, kx, indexing="ij")
    s = growth_rate(taus=T, mu=M, kx=KX, kz=30.0)
    assert np.max(np.abs(r["mean_growth"][..., 0] - s)) <= 1e-6
    # and E(t) = E(0) e^{2st}: the net energy amplification is e^{s t_end}
    assert np.max(np.abs(np.log(r["energy_final"][..., 0]) - s)) <= 1e-6
    assert not r["failed"].any()


def test_small_ky_tends_to_the_axisymmetric_limit_at_every_point():
    """k_y = 1e-6 over the grid of the k_y = 0 test (and k_x of both signs): over t = 1 k_x moves by
    1.5e-6, and the growth is the axisymmetric one to 1e-6 at every point; at linA it is Benitez-Llambay
    et al. (2019)'s s = 0.4190091323."""
    mu, taus, kx = [0.2, 1.0, 3.0], [0.03, 0.1, 1.0], [-30.0, 3.0, 10.0, 30.0, 100.0]
    r = sweep(mu=mu, taus=taus, kx=kx, ky=[1e-6], kz=30.0, t_end=1.0, rtol=1e-9, atol=1e-14)
    M, T, KX = np.meshgrid(mu, taus, kx, indexing="ij")
    s = growth_rate(taus=T, mu=M, kx=np.abs(KX), kz=30.0)
    assert np.max(np.abs(r["mean_growth"][..., 0] - s)) <= 1e-6
    assert abs(r["mean_growth"][2, 1, 0, 0] - 0.4190091323) <= 1e-6 and not r["failed"].any()


def test_kelvin_swing_amplification_at_every_point():
    kx, ky = [-40.0, -12.0, -3.0, -0.5], [0.25, 1.0, 4.0]
    r = sweep(mu=[0.0], taus=[0.1], kx=kx, ky=ky, Pi=0.0, initial="vortical", t_end="swing", rtol=1e-10,
              atol=1e-14, metric="energy_peak")
    KX, KY = np.meshgrid(kx, ky, indexing="ij")
    peak = np.sqrt(1.0 + KX**2 / KY**2)
    assert np.max(np.abs(r["energy_peak"][0, 0] / peak - 1)) <= 1e-6
    assert np.max(np.abs(r["t_peak"][0, 0] / (-KX / (1.5 * KY)) - 1)) <= 1e-6
    assert np.max(np.abs(r["energy_final"][0, 0] - 1)) <= 1e-6


def test_kelvin_wave_over_a_fixed_time():
    """E(t)/E(0) = k(0)²/k(t)² at any t, leading or trailing (t_end = 5)."""
    kx, ky = [-20.0, 7.0], [1.0, 3.0]
    r = sweep(mu=[0.0], taus=[0.1], kx=kx, ky=ky, Pi=0.0, initial="vortical", t_end=5.0, rtol=1e-10, atol=1e-14)
    KX, KY = np.meshgrid(kx, ky, indexing="ij")
    k0, k1 = np.hypot(KX, KY), np.hypot(KX + 7.5 * KY, KY)
    assert np.max(np.abs(r["energy_final"][0, 0] / (k0 / k1) - 1)) <= 1e-6


def test_compiled_integrator_matches_scipy_on_dusty_waves():
    """Against the independent scipy (LSODA, exact Jacobian) integration of the same waves: 1e-6."""
    cases = [(3.0, 0.1, -30.0, 3.0, 0.0), (0.5, 1.0, -60.0, 10.0, 0.0), (1.0, 0.01, -100.0, 20.0, 30.0)]
    for mu, taus, kx, ky, kz in cases:
        r = sweep(mu=[mu], taus=[taus], kx=[kx], ky=[ky], kz=kz, t_end=3.0, rtol=1e-9)
        w = shearing_wave(StreamingParams(taus=taus, mu=mu, kx=kx, ky=ky, kz=kz), (0.0, 3.0), n_out=2, rtol=1e-11,
                          atol=1e-14)
        assert r["energy_final"].item() == pytest.approx(w.energy_amplification, rel=1e-6)
        assert r["dust_final"].item() == pytest.approx(w.amplification, rel=1e-6)


# ---------------------------------------------------------------------------- executors, files

GRID = dict(mu=[0.3, 2.0], taus=[0.1, 1.0], kx=[-40.0, -10.0, 20.0], ky=[2.0, 8.0, 20.0], t_end=3.0, chunk=5)


def test_process_pool_writes_the_same_file_as_serial(tmp_path):
    spec = SweepSpec(**GRID)
    serial = run_sweep(spec, tmp_path / "serial.h5")
    with ProcessPoolExecutor(2) as ex:
        pooled = run_sweep(spec, tmp_path / "pool.h5", executor=ex)
    for name, arr in serial.data.items():
        assert np.array_equal(arr, pooled.data[name], equal_nan=True), name
    assert _digest(tmp_path / "serial.h5") == _digest(tmp_path / "pool.h5")
    assert not (tmp_path / "serial.h5.parts").exists()


@pytest.mark.slow
def test_local_dask_cluster_writes_the_same_file_as_serial(tmp_path):
    """Through the CLI: --executor dask --scheduler ADDRESS of a LocalCluster started here."""
    distributed = pytest.importorskip("distributed", reason="Dask is in the dev extra: pip install -e '.[dev]'")
    args = ["--mu", "0.3", "2", "--taus", "0.1", "1", "--kx", "-40", "-10", "20", "--ky", "2", "8", "20", "--t-end", "3",
            "--chunk", "5", "--no-plots"]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cl:
        proc = _cli(*args, "--executor", "dask", "--scheduler", cl.scheduler_address, "-o", "dask", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    run_sweep(SweepSpec(**GRID), tmp_path / "serial.h5")
    assert _digest(tmp_path / "dask" / "sweep.h5") == _digest(tmp_path / "serial.h5")


@pytest.mark.slow
@pytest.mark.mpi
def test_mpiexec_two_ranks_write_the_same_file_as_serial(tmp_path):
    mpiexec = shutil.which("mpiexec")
    assert mpiexec is not None, "mpiexec not found (pip install 'dustygas[mpi]')"
    args = ["--mu", "0.3", "2", "--taus", "0.1", "1", "--kx", "-40", "-10", "20", "--ky", "2", "8", "20", "--t-end", "3",
            "--chunk", "5", "--no-plots", "--no-progress"]
    proc = subprocess.run([mpiexec, "-n", "2", sys.executable, "-m", "mpi4py.futures", "-m", "dustygas", "linear",
                           "sweep", *args, "--executor", "mpi", "-o", "mpi"], cwd=tmp_path, env=_env(),
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    run_sweep(SweepSpec(**GRID), tmp_path / "serial.h5")
    assert _digest(tmp_path / "mpi" / "sweep.h5") == _digest(tmp_path / "serial.h5")


def test_file_has_labelled_dimensions_parameters_and_the_preferred_angle(tmp_path):
    r = run_sweep(SweepSpec(**GRID), tmp_path / "s.h5")
    with h5py.File(tmp_path / "s.h5") as f:
        d = f["dust_final"]
        assert [dim.label for dim in d.dims] == ["mu", "taus", "kx0", "ky"]
        assert list(d.dims[2][0][()]) == GRID["kx"]
        assert f.attrs["t_end"] == 3.0 and f.attrs["kz"] == 0.0 and f.attrs["drag"] == "consistent"
        assert SweepSpec.from_json(f.attrs["parameters"]) == SweepSpec(**GRID)
        angle = f["preferred/angle_deg"][()]
    back = SweepResult.load(tmp_path / "s.h5")
    assert all(np.array_equal(back[n], r[n], equal_nan=True) for n in r.data)
    # the preferred wave: the largest dust amplification, seen at k_x(t_end) = k_x0 + 1.5 k_y t_end
    for i in range(2):
        for j in range(2):
            a, b = np.unravel_index(np.argmax(r["dust_final"][i, j]), (3, 3))
            kx_end = GRID["kx"][a] + 1.5 * GRID["ky"][b] * 3.0
            assert angle[i, j] == pytest.approx(math.degrees(math.atan(GRID["ky"][b] / kx_end)), abs=1e-12)


def test_sampled_times_are_the_amplification_up_to_each_time(tmp_path):
    """``times = 4``: dust_t at t_end/2 equals a sweep integrated to t_end/2 (to 1e-6), the last
    sample is dust_final itself, and the predicted angle at t_end is that of :meth:`preferred`."""
    grid = dict(mu=[0.5], taus=[0.3], kx=[-30.0, -10.0], ky=[2.0, 6.0])
    r = run_sweep(SweepSpec(**grid, t_end=4.0, times=4), tmp_path / "t.h5")
    half = sweep(**grid, t_end=2.0)
    assert np.max(np.abs(r["dust_t"][..., 1] / half["dust_final"] - 1)) <= 1e-6
    assert np.array_equal(r["dust_t"][..., -1], r["dust_final"])
    series, final = r.preferred_series(), r.preferred()
    assert series["angle_deg"][..., -1] == pytest.approx(final["angle_deg"], abs=1e-12)
    assert list(series["time"]) == [1.0, 2.0, 3.0, 4.0]
    with h5py.File(tmp_path / "t.h5") as f:
        assert [d.label for d in f["dust_t"].dims] == ["mu", "taus", "kx0", "ky", "time"]
        assert f["preferred_t/angle_deg"].shape == (1, 1, 4)
    back = SweepResult.load(tmp_path / "t.h5")
    assert np.array_equal(back["dust_t"], r["dust_t"])


def test_killed_sweep_resumes_and_writes_the_same_file(tmp_path):
    args = ["--mu", "0.5", "2", "--taus", "0.05", "0.2", "--kx-range", "-60", "-10", "6", "--ky-range", "2", "12",
            "6", "--t-end", "6.283", "--chunk", "4", "--executor", "serial", "--no-plots", "-o", "out"]
    cmd = [sys.executable, "-m", "dustygas", "linear", "sweep", *args, "--no-progress"]
    proc = subprocess.Popen(cmd, cwd=tmp_path, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    parts = tmp_path / "out" / "sweep.h5.parts"
    nchunks = 2 * 2 * 6 * 6 // 4
    deadline = time.time() + 900
    while time.time() < deadline and proc.poll() is None and len(list(parts.glob("chunk_*.npy"))) < nchunks // 3:
        time.sleep(0.05)
    proc.send_signal(signal.SIGKILL)
    proc.wait(timeout=60)
    assert proc.returncode == -signal.SIGKILL, proc.stderr.read()
    done = len(list(parts.glob("chunk_*.npy")))
    assert 0 < done < nchunks and not (tmp_path / "out" / "sweep.h5").exists()
    again = subprocess.run(cmd, cwd=tmp_path, env=_env(), capture_output=True, text=True, timeout=900)
    assert again.returncode == 0, again.stderr
    assert f"{done} of {nchunks} chunks already done" in again.stderr
    assert not parts.exists()
    spec = SweepSpec(mu=[0.5, 2], taus=[0.05, 0.2], kx=np.linspace(-60, -10, 6), ky=np.linspace(2, 12, 6),
                     t_end=6.283, chunk=4)
    run_sweep(spec, tmp_path / "fresh.h5")
    assert _digest(tmp_path / "out" / "sweep.h5") == _digest(tmp_path / "fresh.h5")


def test_cli_writes_file_and_figures_from_toml(tmp_path):
    (tmp_path / "s.toml").write_text("[sweep]\nmu = [0.5, 2.0]\ntaus_range = [0.1, 1.0, 2]\nkx_range = [-30, -5, 3]\n"
                                     "ky = [3.0, 9.0]\nt_end = 2.0\n")
    proc = _cli("-c", "s.toml", "--ky", "3", "9", "12", "--executor", "serial", "-o", "out", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "36 waves (2 x 2 x 3 x 3 in mu, taus, kx0, ky)" in proc.stdout
    for name in ("sweep.h5", "sweep_amplification.png", "sweep_amplification.csv", "sweep_angle.png",
                 "sweep_angle.csv"):
        assert (tmp_path / "out" / name).is_file(), name
    with h5py.File(tmp_path / "out" / "sweep.h5") as f:
        assert list(f["ky"][()]) == [3.0, 9.0, 12.0]  # the command line overrides the TOML grid
        assert list(f["taus"][()]) == pytest.approx([0.1, 1.0], rel=1e-15)


# ---------------------------------------------------------------------------- bad input


@pytest.mark.parametrize("args, fragment", [
    (["--mu", "1", "--taus", "0.1", "--kx", "-10", "--ky", "0", "1", "--t-end", "swing"], "ky contains 0"),
    (["--mu-range", "0.1", "1", "0", "--taus", "0.1", "--kx", "-10", "--ky", "1"], "n must be >= 1"),
    (["--mu", "1", "--taus", "0.1", "--kx", "-10", "--kx-range", "-1", "1", "3", "--ky", "1"], "not both"),
    (["--mu", "1", "--taus", "-0.1", "--kx", "-10", "--ky", "1"], "stopping times must be > 0"),
    (["--mu", "1", "--taus", "0.1", "--kx", "0", "--ky", "0"], "k = 0"),
    (["--mu", "1", "--taus", "0.1", "--kx", "-10", "--ky", "1", "--executor", "dask", "--scheduler",
      "tcp://127.0.0.1:9", "--scheduler-timeout", "2"], "no Dask scheduler answered"),
    (["--mu", "1", "--taus", "0.1", "--kx", "-10", "--ky", "1", "--window", "0.5", "0.2"], "window"),
])
def test_bad_input_is_one_line_and_writes_nothing(tmp_path, args, fragment, capsys, monkeypatch):
    if "dask" in args:
        pytest.importorskip("distributed", reason="Dask is in the dev extra: pip install -e '.[dev]'")
    monkeypatch.chdir(tmp_path)
    code = main(["linear", "sweep", *args, "-o", "out", "--no-progress"])
    err = capsys.readouterr().err
    _one_line_error(subprocess.CompletedProcess([], code, "", err), fragment)
    assert not (tmp_path / "out").exists()


def test_bad_input_from_the_shell_exits_2(tmp_path):
    _one_line_error(_cli("--mu", "1", "--taus", "0.1", "--kx", "-10", "--ky", "0", "--t-end", "swing", "-o", "out",
                         cwd=tmp_path, timeout=300), "ky contains 0")
    assert not (tmp_path / "out").exists()


def test_unknown_toml_key_and_changed_parameters(tmp_path):
    (tmp_path / "bad.toml").write_text("[sweep]\nmu = [1.0]\ntaus = [0.1]\nkx = [-5.0]\nky = [1.0]\nkz_sign = 1\n")
    with pytest.raises(UserError, match="sweep.kz_sign: unknown key"):
        build_spec(build_parser().parse_args(["linear", "sweep", "-c", str(tmp_path / "bad.toml")]))
    with pytest.raises(UserError, match="unknown option 'kx0'"):
        sweep(mu=[1.0], taus=[0.1], kx=[-5.0], ky=[1.0], kx0=[1.0])
    # unfinished parts of another sweep are not silently mixed in
    spec = SweepSpec(mu=[1.0], taus=[0.1], kx=[-5.0, -3.0], ky=[1.0], chunk=1)
    (tmp_path / "s.h5.parts").mkdir()
    (tmp_path / "s.h5.parts" / "spec.json").write_text("{}")
    with pytest.raises(UserError, match="other parameters"):
        run_sweep(spec, tmp_path / "s.h5")
