"""``dustygas linear``: output, the JSON contract, files written, one-line errors."""

import json

import h5py
import numpy as np
import pytest

from dustygas.linear import growth_rate
from dustygas.linear.sweep_run import sweep

from foundation._cli import cli


def _one_line_error(proc, fragment):
    assert proc.returncode == 2, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("dustygas: error:"), proc.stderr
    assert fragment in lines[0]


def test_mode_text_prints_linA(tmp_path):
    """The printed growth rate, frequency and u_x against Youdin & Johansen (2007) Table 1 (7 digits),
    with YJ07's epsilon given as --eps (the alias of --mu)."""
    proc = cli("linear", "mode", "--taus", "0.1", "--eps", "3", "--kx", "30", "--kz", "30", "--drag", "yj07",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    growth = float(next(ln for ln in lines if ln.startswith("growth rate")).split("=")[-1].split()[0])
    freq = float(next(ln for ln in lines if ln.startswith("frequency")).split("=")[-1].split()[0])
    ux = next(ln for ln in lines if ln.strip().startswith("ux ")).split()
    assert abs(growth - 0.4190204) <= 1e-7 and abs(freq - 0.3480127) <= 1e-7
    assert abs(complex(float(ux[1]), float(ux[2][:-1])) - (-0.1691398 + 0.0361553j)) <= 1e-7


def test_mode_json_contract(tmp_path):
    proc = cli("linear", "mode", "--taus", "0.1", "--mu", "3", "--kx", "30", "--kz", "30", "--json", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert abs(out["growth_rate"] - 0.4190091323) <= 1e-9
    assert out["omega"] == [out["frequency"], out["growth_rate"]]
    assert set(out["eigenvector"]) == {"drho_g", "ux", "uy", "uz", "drho_p", "wx", "wy", "wz"}
    assert out["eigenvector"]["drho_p"] == [1.0, 0.0]
    assert all(len(v) == 2 for v in out["eigenvector"].values())


def test_mode_json_two_species_is_bkp19_linC(tmp_path):
    """Benítez-Llambay, Krapp & Pessah (2019) Table 4 linC: s = 0.3027262829, Re ω = 0.3242790653."""
    proc = cli("linear", "mode", "--taus", "0.0425", "0.1", "--mu", "1", "0.5", "--kx", "50", "--kz", "50", "--json",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert abs(out["growth_rate"] - 0.3027262829) <= 5e-11 and abs(out["frequency"] - 0.3242790653) <= 5e-11
    ev = out["eigenvector"]
    assert {"drho_p_0", "wz_0", "drho_p_1", "wx_1", "drho_g"} <= set(ev)
    assert ev["drho_p_0"] == [1.0, 0.0]


def test_mode_help_documents_json_keys(tmp_path):
    proc = cli("linear", "mode", "--help", cwd=tmp_path)
    for word in ("growth_rate", "frequency", "eigenvector", "drho_p_0", "--mu"):
        assert word in proc.stdout


@pytest.mark.parametrize("args, fragment", [
    (["--taus", "-0.1", "--mu", "3", "--kx", "30", "--kz", "30"], "stopping times must be > 0"),
    (["--taus", "0.1", "--mu", "-3", "--kx", "30", "--kz", "30"], "dust-to-gas ratios must be >= 0"),
    (["--taus", "0.1", "--mu", "3", "--kx", "0", "--kz", "0"], "k = 0"),
    (["--taus", "0.1", "--mu", "3", "--kx", "30", "--kz", "30", "--drag", "stokes"], "unknown drag"),
    (["--taus", "0.1", "--mu", "3", "--kx", "30", "--kz", "30", "--vz", "fast"], "--vz"),
    (["--taus", "0.1", "--kx", "30", "--kz", "30"], "--mu is required"),
])
def test_mode_bad_input_is_one_line_exit_2(tmp_path, args, fragment):
    _one_line_error(cli("linear", "mode", *args, cwd=tmp_path), fragment)


def test_map_writes_hdf5_json_png(tmp_path):
    proc = cli("linear", "map", "--n", "6", "--kz", "30", "--kx-range", "1", "1000", "-o", "out", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    with h5py.File(tmp_path / "out" / "growth_map.h5") as f:
        assert list(f.attrs["kx_range"]) == [1.0, 1000.0] and f.attrs["kz"] == 30.0
        g, kx, mu, taus = (f[k][()] for k in ("growth_rate", "kx", "mu", "taus"))
    # every written maximum is the growth rate at the written K_x (at K_z = 30), and the default
    # grid is log-spaced over mu in [0.01, 10], taus in [1e-3, 3]
    T, M = np.meshgrid(taus, mu, indexing="ij")
    assert np.max(np.abs(growth_rate(taus=T, mu=M, kx=kx, kz=30.0) - g)) <= 1e-12
    assert mu[0] == pytest.approx(0.01) and mu[-1] == pytest.approx(10.0) and taus[-1] == pytest.approx(3.0)
    assert (tmp_path / "out" / "growth_map.png").is_file()
    assert json.loads((tmp_path / "out" / "growth_map.json").read_text())["attrs"]["kz"] == 30.0
    _one_line_error(cli("linear", "map", "--method", "spiral", "-o", "o2", cwd=tmp_path), "method")
    assert not (tmp_path / "o2").exists()


def test_shear_writes_csv_png(tmp_path):
    proc = cli("linear", "shear", "--taus", "0.1", "--mu", "3", "--kx", "-30", "--ky", "5", "--kz", "30",
               "-o", "sw", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "sw" / "shearing_wave.csv").read_text().splitlines()
    assert text[0].startswith("# shearing wave")
    names = [ln for ln in text if not ln.startswith("#")][0].split(",")
    assert names[:2] == ["t", "kx"] and "abs_drho_p_0" in names
    # the scipy (LSODA) swing against the compiled Dormand-Prince integration of the sweep: 1e-6
    amp = float(proc.stdout.split()[2])
    r = sweep(mu=[3.0], taus=[0.1], kx=[-30.0], ky=[5.0], kz=30.0, t_end="swing", rtol=1e-9)
    assert amp == pytest.approx(r["dust_final"].item(), rel=1e-6)
    _one_line_error(cli("linear", "shear", "--taus", "0.1", "--mu", "3", "--kx", "30", "--ky", "5", cwd=tmp_path),
                    "t_span is needed")
