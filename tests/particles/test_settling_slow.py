"""Settling-enhanced streaming instability in the particle-gas engine (thesis Fig 4.6).

``dustygas reproduce fig4.6`` runs ``si-settling`` at four points of thesis Fig 4.3 (θ_k = 30°,
the faster sign K_z < 0, Π = 0.05, the vertical drift of eq. 4.19 held by constant forces,
fixed t_s), 32², one particle per cell, and measures their growth rates: each must lie within
5 % of the linear theory of exactly that background, with the eight fields agreeing within
1 %, and the figure must be written.
"""

import csv

import pytest


@pytest.mark.slow
def test_fig4_6_settling_growth_within_five_percent_at_four_points(tmp_path):
    from dustygas.reproduce import get_figure

    paths = get_figure("fig4.6").function(tmp_path, quick=True)
    assert [p.name for p in paths] == ["fig4_6.png", "fig4_6.csv", "fig4_6_points.csv"]
    assert all(p.stat().st_size > 1000 for p in paths[:2])
    with open(tmp_path / "fig4_6_points.csv") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    assert len(rows) == 4
    for r in rows:
        assert abs(float(r["error"])) < 0.05, r
        assert float(r["spread"]) < 0.01, r
