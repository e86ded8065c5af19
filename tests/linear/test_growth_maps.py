"""Vectorised growth rates and growth-rate maps."""

import json
import math

import h5py
import numpy as np
import pytest

from dustygas.errors import UserError
from dustygas.linear import StreamingParams, fastest_mode, growth_rate
from dustygas.linear.maps import growth_map, growth_vs_k, settling_ratio
from dustygas.physics import growth_settling_threshold


def test_growth_rate_broadcasts_and_matches_fastest_mode():
    taus = np.array([0.01, 0.1, 1.0])[:, None]
    kx = np.array([3.0, 30.0, 300.0])[None, :]
    s, f = growth_rate(taus=taus, mu=2.0, kx=kx, kz=20.0, drag="epstein", vz=-0.5, return_frequency=True)
    assert s.shape == (3, 3)
    for i, t in enumerate([0.01, 0.1, 1.0]):
        for j, k in enumerate([3.0, 30.0, 300.0]):
            m = fastest_mode(StreamingParams(taus=t, mu=2.0, kx=k, kz=20.0, drag="epstein", vz=-0.5))
            assert abs(s[i, j] - m.growth_rate) <= 1e-11 * max(1, abs(m.growth_rate)) + 1e-13
            assert abs(f[i, j] - m.frequency) <= 1e-10 * max(1, abs(m.frequency))


def test_growth_rate_species_axis_and_incompressible():
    s = growth_rate(taus=[[0.1, 1.0], [0.2, 0.3]], mu=[[1.0, 0.5], [0.1, 0.2]], kx=30.0, kz=30.0, Pi=0.0, species_axis=-1)
    for i, (t, m) in enumerate([([0.1, 1.0], [1.0, 0.5]), ([0.2, 0.3], [0.1, 0.2])]):
        assert abs(s[i] - fastest_mode(StreamingParams(taus=t, mu=m, kx=30, kz=30, Pi=0.0)).growth_rate) <= 1e-12


@pytest.mark.parametrize("kw, fragment", [
    (dict(taus=-1.0), "taus"), (dict(mu=-0.1), "mu"), (dict(kx=0.0, kz=0.0), "k = 0"),
    (dict(drag="stokes"), "unknown drag"), (dict(Pi=-1.0), "Pi"),
])
def test_growth_rate_rejects_bad_input(kw, fragment):
    args = dict(taus=0.1, mu=1.0, kx=1.0, kz=1.0)
    args.update(kw)
    with pytest.raises(UserError, match=fragment):
        growth_rate(taus=args.pop("taus"), mu=args.pop("mu"), kx=args.pop("kx"), kz=args.pop("kz"), **args)


def test_map_kx_method_matches_a_brute_force_scan():
    """Max over Kx at fixed Kz: the optimiser equals a 20,000-point scan to 1e-7 (relative)."""
    mu = [0.2, 3.0]
    taus = [0.01, 0.1, 1.0]
    gm = growth_map(mu=mu, taus=taus, method="kx", kz=100.0, kx_range=(1.0, 1e4), Pi=0.05)
    kx = np.logspace(0, 4, 20000)
    for i, t in enumerate(taus):
        for j, m in enumerate(mu):
            s = growth_rate(taus=t, mu=m, kx=kx, kz=100.0)
            best = s.max()
            assert gm.growth[i, j] >= best * (1 - 1e-7) - 1e-12
            assert gm.growth[i, j] <= best * (1 + 1e-6) + 1e-12  # the scan itself is discrete
            assert abs(gm.growth[i, j] - float(growth_rate(taus=t, mu=m, kx=gm.kx[i, j], kz=gm.kz[i, j]))) <= 1e-13


def test_map_box_and_angle_methods_and_edges():
    gm = growth_map(mu=[3.0], taus=[0.1], method="box", kx_range=(1, 100), kz_range=(1, 100))
    assert gm.at_edge[0, 0]  # inviscid: growth keeps rising with k, the max sits on the edge
    assert abs(gm.kz[0, 0] - 100.0) <= 1e-6
    kx = np.logspace(0, 2, 400)[:, None]
    kz = np.logspace(0, 2, 400)[None, :]
    assert gm.growth[0, 0] >= growth_rate(taus=0.1, mu=3.0, kx=kx, kz=kz).max() - 1e-9
    ga = growth_map(mu=[0.1], taus=[0.01], method="angle", theta_deg=30.0, k_range=(0.1, 1e3), vz="settling",
                    mirror=True, coarse=60)
    k = np.logspace(-1, 3, 8000)
    ref = growth_vs_k(taus=0.01, mu=0.1, k=k, theta_deg=30.0, vz="settling", mirror=True)
    assert ga.growth[0, 0] >= ref.max() * (1 - 1e-6)
    assert math.isclose(math.degrees(math.atan2(ga.kx[0, 0], abs(ga.kz[0, 0]))), 30.0, rel_tol=1e-12)


def test_map_files_state_the_k_range(tmp_path):
    gm = growth_map(mu=[0.5, 1.0], taus=[0.1, 0.3], method="kx", kz=50.0, kx_range=(2.0, 500.0))
    h5 = gm.save(tmp_path / "m.h5")
    with h5py.File(h5) as f:
        assert list(f.attrs["kx_range"]) == [2.0, 500.0]
        assert f.attrs["kz"] == 50.0
        assert np.array_equal(f["growth_rate"][()], gm.growth)
    data = json.loads(gm.save(tmp_path / "m.json").read_text())
    assert data["attrs"]["kx_range"] == [2.0, 500.0]


def test_settling_ratio_is_eq_4_20():
    s = np.array([0.5, 0.05, -0.1])
    r = settling_ratio(growth=s, taus=0.1)
    assert r[0] == pytest.approx(growth_settling_threshold(0.1) / 0.5, rel=1e-15)
    assert r[1] > 1 > r[0]
    assert np.isinf(r[2])


def test_settling_enhances_small_grain_growth():
    """SH18's settling instability: at μ = 0.1 the peak growth with settling is ~0.1 Ω for
    τ_s = 0.01 and 0.001 alike, ≫ the unsettled peak; t_growth/t_settle ≈ 0.01 at τ_s = 0.001
    (thesis §4.1.5)."""
    peaks = {}
    for taus in (0.01, 0.001):
        gs = growth_map(mu=[0.1], taus=[taus], method="angle", k_range=(1e-2, 1e5), vz="settling", mirror=True,
                        coarse=200).growth[0, 0]
        g0 = growth_map(mu=[0.1], taus=[taus], method="angle", k_range=(1e-2, 1e5), coarse=200).growth[0, 0]
        assert gs > 30 * g0
        peaks[taus] = gs
    assert 0.08 < peaks[0.01] < 0.16
    assert abs(peaks[0.01] - peaks[0.001]) / peaks[0.01] < 0.05  # independent of grain size
    assert 0.005 < float(settling_ratio(growth=peaks[0.001], taus=0.001)) < 0.02
