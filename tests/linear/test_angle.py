"""Dominant wavevector angle of a run's dust surface density, on synthetic run directories.

A sheared wave Σ_d = 1 + A cos(k_x(t) x + k_y y), k_x(t) = k_x0 + 1.5 k_y t, in a shear-periodic
box (snapshot attribute ``shear_offset`` = 1.5 L_x t mod L_y) has θ_k(t) = arctan(k_y/k_x(t))
exactly; the measurement must return it (to 1e-9 degrees) from a ``rho_p`` field, and from
particle masses binned on the cells of a periodic box.
"""

import math

import numpy as np
import pytest

from dustygas.analysis.wavevector import angle_history
from dustygas.cli import main
from dustygas.errors import UserError
from dustygas.io.hdf5 import write_h5
from dustygas.linear.sweep import SweepSpec
from dustygas.linear.sweep_run import run_sweep

LX, LY, NX, NY = 2.0, 4.0, 32, 24
KX0, KY = -3 * 2 * math.pi / LX, 2 * 2 * math.pi / LY


def _centres(n, length):
    return -0.5 * length + (np.arange(n) + 0.5) * length / n


def _sheared_run(path, times, with_particles=False):
    x, y = _centres(NX, LX), _centres(NY, LY)
    (path / "snapshots").mkdir(parents=True)
    (path / "config.toml").write_text('[dustygas]\nproblem = "synthetic"\n[problem]\nmu = 0.5\ntaus = 0.3\n')
    for i, t in enumerate(times):
        d = (1.5 * LX * t) % LY
        kx = KX0 + 1.5 * KY * t
        X, Y = np.meshgrid(x, y, indexing="xy")  # (ny, nx)
        sigma = 1.0 + 0.01 * np.cos(kx * X + KY * Y)
        attrs = {"time": t, "lx": LX, "ly": LY, "lz": 1.0, "shear_offset": d}
        arrays = {"x": x, "y": y, "z": np.zeros(1)}
        if with_particles:  # one particle per cell, mass proportional to the density
            arrays["particles/pos"] = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
            arrays["particles/mass"] = sigma.ravel()
        else:
            arrays["rho_p"] = np.stack([0.4 * sigma, 0.6 * sigma])  # two z layers
        write_h5(path / "snapshots" / f"snap_{i:05d}.h5", arrays, attrs)


def test_angle_of_a_sheared_wave_in_a_shear_periodic_box(tmp_path):
    times = [0.0, 0.5, 1.0, 1.7, 3.0]
    _sheared_run(tmp_path / "run", times)
    h = angle_history(tmp_path / "run")
    for t, kx, ang in zip(times, h["kx"], h["angle_deg"]):
        expected = KX0 + 1.5 * KY * t
        assert kx == pytest.approx(expected, abs=1e-9)
        assert ang == pytest.approx(math.degrees(math.atan(KY / expected)), abs=1e-9)
    assert np.allclose(h["amplitude"], 0.01, rtol=1e-9)


def test_angle_from_particle_masses(tmp_path):
    _sheared_run(tmp_path / "run", [0.0], with_particles=True)
    h = angle_history(tmp_path / "run")
    assert h["angle_deg"][0] == pytest.approx(math.degrees(math.atan(KY / KX0)), abs=1e-9)


def test_cli_prints_the_sweep_prediction_next_to_the_run(tmp_path, capsys):
    _sheared_run(tmp_path / "run", [2.0, 3.0, 4.0])
    run_sweep(SweepSpec(mu=[0.5], taus=[0.3], kx=[-30.0, -10.0], ky=[2.0, 6.0], t_end=2.0, times=2),
              tmp_path / "s.h5")
    code = main(["linear", "angle", str(tmp_path / "run"), "--sweep", str(tmp_path / "s.h5"), "-o", str(tmp_path / "o")])
    out = capsys.readouterr().out
    assert code == 0, out
    rows = [ln.split() for ln in out.splitlines() if not ln.startswith("#") and ln.strip()][1:]
    assert len(rows) == 3 and len(rows[0]) == 5 and len(rows[1]) == 6  # t = t0: nothing predicted yet
    from dustygas.linear.sweep import SweepResult

    ser = SweepResult.load(tmp_path / "s.h5").preferred_series()
    assert float(rows[2][5]) == pytest.approx(ser["angle_deg"][0, 0, 1], abs=0.01)  # t - t0 = 2 = t_end
    assert (tmp_path / "o" / "angle_comparison.png").is_file()


def test_errors_name_what_is_missing(tmp_path):
    (tmp_path / "empty" / "snapshots").mkdir(parents=True)
    with pytest.raises(UserError, match="no snapshots"):
        angle_history(tmp_path / "empty")
    write_h5(tmp_path / "empty" / "snapshots" / "snap_00000.h5", {"rho": np.ones((1, 4, 4))}, {"lx": 1.0, "ly": 1.0})
    with pytest.raises(UserError, match="holds no dust"):
        angle_history(tmp_path / "empty")
