"""``dustygas linear``: output, the JSON contract, files written, one-line errors."""

import json
import re

import h5py
import numpy as np
import pytest

from dustygas.linear import StreamingParams, operator_matrix
from dustygas.linear.sweep_run import sweep

from foundation._cli import cli, cli_in_process


def _one_line_error(proc, fragment):
    assert proc.returncode == 2, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("dustygas: error:"), proc.stderr
    assert fragment in lines[0]


def test_mode_text_prints_linA(tmp_path):
    """With YJ07's drag linearisation the printed mode is Youdin & Johansen (2007) Table 1's linA to the
    seven digits they publish: omega = 0.3480127 + 0.4190204i (standard sign), u_x = -0.1691398 + 0.0361553i."""
    proc = cli("linear", "mode", "--taus", "0.1", "--eps", "3", "--kx", "30", "--kz", "30", "--drag", "yj07",
               cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    number = r"([+-]\d+\.\d+)"
    growth = float(re.search(r"s = Im omega = " + number, proc.stdout).group(1))
    frequency = float(re.search(r"Re omega = " + number, proc.stdout).group(1))
    ux = re.search(r"ux\s+" + number + r"\s*" + number + "i", proc.stdout)
    assert abs(growth - 0.4190204) <= 5e-8 and abs(frequency - 0.3480127) <= 5e-8, proc.stdout
    assert abs(float(ux.group(1)) + 0.1691398) <= 5e-8 and abs(float(ux.group(2)) - 0.0361553) <= 5e-8


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
    _one_line_error(cli_in_process("linear", "mode", *args, cwd=tmp_path), fragment)


def test_map_writes_hdf5_json_png(tmp_path):
    proc = cli("linear", "map", "--n", "6", "--kz", "30", "--kx-range", "1", "1000", "-o", "out", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    with h5py.File(tmp_path / "out" / "growth_map.h5") as f:
        assert list(f.attrs["kx_range"]) == [1.0, 1000.0] and f.attrs["kz"] == 30.0
        g, kx, taus, mu = (f[k][()] for k in ("growth_rate", "kx", "taus", "mu"))
    assert g.shape == (6, 6) and np.all(np.isfinite(g))
    # every cell is the fastest mode over K_x at K_z = 30: LAPACK's eigenvalues of the operator at the
    # reported K_x give the reported rate (1e-9), and K_x 1 % either side grows no faster (1e-9)
    def lapack(i, j, k):  # rows are tau_s, columns mu (the printed maximum: tau_s = 0.6049, mu = 10)
        params = StreamingParams(taus=float(taus[i]), mu=float(mu[j]), kx=float(k), kz=30.0, Pi=0.05)
        return np.linalg.eigvals(operator_matrix(params)).real.max()

    for i, j in [(0, 0), (2, 3), (4, 5), (5, 1)]:
        assert lapack(i, j, kx[i, j]) == pytest.approx(g[i, j], rel=1e-9, abs=1e-12)
        assert max(lapack(i, j, kx[i, j] * 0.99), lapack(i, j, kx[i, j] * 1.01)) <= g[i, j] * (1 + 1e-9)
    assert mu[0] == pytest.approx(0.01) and mu[-1] == pytest.approx(10.0) and taus[-1] == pytest.approx(3.0)
    assert (tmp_path / "out" / "growth_map.png").stat().st_size > 10_000
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
    rows = [ln.split(",") for ln in text if not ln.startswith("#")][1:]
    drho_p = np.array([float(r[names.index("abs_drho_p_0")]) for r in rows])
    assert amp == pytest.approx(drho_p[-1] / drho_p[0], rel=1e-7)  # the printed number is the file's
    r = sweep(mu=[3.0], taus=[0.1], kx=[-30.0], ky=[5.0], kz=30.0, t_end="swing", rtol=1e-9)
    assert amp == pytest.approx(r["dust_final"].item(), rel=1e-6)
    # k_y = 0: no shear of the wave, the linA eigenmode grows at Benitez-Llambay et al. (2019)'s s = 0.4190091323
    flat = cli("linear", "shear", "--taus", "0.1", "--eps", "3", "--kx", "30", "--ky", "0", "--kz", "30",
               "--t-end", "3", "-o", "sw0", cwd=tmp_path)
    assert flat.returncode == 0, flat.stderr
    assert float(flat.stdout.split()[2]) == pytest.approx(np.exp(3 * 0.4190091323), rel=1e-7)
    _one_line_error(cli("linear", "shear", "--taus", "0.1", "--eps", "3", "--kx", "30", "--ky", "5", cwd=tmp_path),
                    "t_span is needed")
