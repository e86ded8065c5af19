"""Thesis Figures 3.1 and 3.5: files written, and the saved numbers are the physics functions'."""

import numpy as np
import pytest

from dustygas.physics import drag, growth
from dustygas.plot import Column, new_figure, read_table, save_figure
from dustygas.reproduce import get_figure
from dustygas.reproduce.fig3_1 import DISKS, V_FRAG
from foundation._cli import cli

PNG_MAGIC = b"\x89PNG\r\n\x1a\n"


def _written(paths, stem):
    png, csv = paths
    assert png.name == f"{stem}.png" and csv.name == f"{stem}.csv"
    assert png.read_bytes()[:8] == PNG_MAGIC and png.stat().st_size > 20_000
    assert not [p for p in png.parent.iterdir() if p.name.startswith(".")]  # no temporary files left
    return read_table(csv)


def test_fig3_5_data_is_eq_3_23(tmp_path):
    """Columns equal -v_r/v_K of eq. 3.23 as the thesis prints it, (v_r,g/tau_s - eta v_K)/(tau_s + 1/tau_s),
    with eta = 7.5e-3, v_r,gas/v_K = -3.75e-5 (to 1e-13; the code evaluates the rearranged form); at
    the ends of the range it is -v_r,g + eta tau_s (tau_s << 1) and eta/tau_s (tau_s >> 1) to 1e-5,
    and the sampled maximum sits at the analytic peak tau* = 0.99501 within the grid spacing."""
    data = _written(get_figure("fig3.5").function(tmp_path), "fig3_5")
    taus = data["tau_s"]
    assert taus[0] == pytest.approx(1e-3) and taus[-1] == pytest.approx(1e3) and taus.size >= 200
    printed = -(-3.75e-5 / taus - 7.5e-3) / (taus + 1 / taus)  # thesis eq. 3.23, v_K = 1
    np.testing.assert_allclose(data["minus_vr_over_vK"], printed, rtol=1e-13)
    assert data["minus_vr_over_vK"][0] == pytest.approx(3.75e-5 + 7.5e-3 * 1e-3, rel=1e-5)
    assert data["minus_vr_over_vK"][-1] == pytest.approx(7.5e-3 / 1e3, rel=1e-5)
    np.testing.assert_allclose(data["minus_vr_gas_over_vK"], 3.75e-5, rtol=1e-15)
    a, b = 3.75e-5, 7.5e-3
    tau_star = (np.hypot(a, b) - a) / b
    step = np.log10(taus[1] / taus[0])
    assert abs(np.log10(taus[np.argmax(data["minus_vr_over_vK"])] / tau_star)) <= step


def test_fig3_1_data_are_the_roots_and_drift_sizes(tmp_path):
    """For both disks: s_drift = Sigma/(sqrt(2 pi) rho_grain) (eq. 3.10, general form), the Epstein
    size of unit Stokes number is sqrt(8/pi) s_drift, finite s_frag+- satisfy V_rel = V_frag to 1e-12,
    and NaN appears exactly where alpha_tilde c_s^2/V_frag^2 < 2."""
    data = _written(get_figure("fig3.1").function(tmp_path), "fig3_1")
    r = data["r"]
    assert r[0] == pytest.approx(4.0) and r[-1] == pytest.approx(120.0)
    for model in DISKS:
        lab = model.label
        s_drift = data[f"{lab}_s_drift"]
        np.testing.assert_allclose(s_drift, data[f"{lab}_Sigma"] / (np.sqrt(2 * np.pi) * model.rho_grain), rtol=1e-13)
        np.testing.assert_allclose(data[f"{lab}_s_unit_stokes"], np.sqrt(8 / np.pi) * s_drift, rtol=1e-13)
        np.testing.assert_allclose(s_drift * r ** model.p, s_drift[0] * r[0] ** model.p, rtol=1e-12)
        c_s = data[f"{lab}_c_s"]
        A_unit = growth.alpha_tilde(model.alpha, model.rossby) * c_s**2
        for v in V_FRAG:
            lo, hi = data[f"{lab}_s_frag_minus_v{v:g}"], data[f"{lab}_s_frag_plus_v{v:g}"]
            exists = A_unit / (100 * v) ** 2 >= 2
            assert np.array_equal(np.isfinite(lo), exists) and np.array_equal(np.isfinite(hi), exists)
            taus = np.concatenate([lo[exists], hi[exists]]) / np.tile(data[f"{lab}_s_unit_stokes"][exists], 2)
            v_rel = growth.relative_velocity(taus, np.tile(c_s[exists], 2), model.alpha, model.rossby)
            np.testing.assert_allclose(v_rel, 100 * v, rtol=1e-12)
    # the assumed model: flat-disk branches end inside the disk only for V_frag = 25 m/s (A = 2 at ~57 au)
    ends = r[np.isfinite(data["flat_s_frag_plus_v25"])][-1]
    assert 50 < ends < 65 and np.isfinite(data["flat_s_frag_plus_v20"][-1])


def test_epstein_unit_stokes_size_in_figure_matches_drag_law(tmp_path):
    """Cross-check one point of the figure with the drag module directly."""
    data = _written(get_figure("fig3.1").function(tmp_path), "fig3_1")
    model = DISKS[1]
    d = model.disk()
    from dustygas.units import au

    r = data["r"][100] * au
    taus = drag.stokes_number(drag.epstein_stopping_time(data["steep_s_unit_stokes"][100], model.rho_grain,
                                                         d.midplane_density(r), d.sound_speed(r)), d.omega(r))
    np.testing.assert_allclose(taus, 1.0, rtol=1e-12)


def test_reproduce_command_writes_both_figures(tmp_path):
    """The CLI writes the four files; Figure 3.5's peak is (sqrt(a^2+b^2)+a)/2 = 3.76880e-3
    (a = 3.75e-5, b = 7.5e-3: f(tau*) = b/(2 tau*)), sampled on a 0.01-dex grid (rtol 1e-3)."""
    proc = cli("reproduce", "fig3.1", "fig3.5", "--output", "figs", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    names = sorted(p.name for p in (tmp_path / "figs").iterdir())
    assert names == ["fig3_1.csv", "fig3_1.png", "fig3_5.csv", "fig3_5.png", "gallery", "index.html"]
    peak = read_table(tmp_path / "figs" / "fig3_5.csv")["minus_vr_over_vK"].max()
    np.testing.assert_allclose(peak, (np.hypot(3.75e-5, 7.5e-3) + 3.75e-5) / 2, rtol=1e-3)


def test_save_figure_round_trip_and_rejects_ragged_columns(tmp_path):
    fig, ax = new_figure()
    ax.plot([0, 1], [0, 1])
    x = np.array([0.1, 1 / 3, 2e-300, np.pi * 1e7, np.nan])
    paths = save_figure(fig, tmp_path / "f.png", [Column("x", x, "cm", "a length"), Column("y", 2 * x, "1")])
    back = read_table(paths[1])
    np.testing.assert_array_equal(back["x"], x)  # shortest repr: exact round trip
    np.testing.assert_array_equal(back["y"], 2 * x)
    text = paths[1].read_text()
    assert "# column x [cm]: a length" in text and "# column y [1]\n" in text
    with pytest.raises(ValueError, match="differ in length"):
        save_figure(fig, tmp_path / "g.png", [Column("x", x, "cm"), Column("y", x[:2], "cm")])
    assert not (tmp_path / "g.png").exists() and not (tmp_path / "g.csv").exists()
