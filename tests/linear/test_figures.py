"""The linear-theory figures regenerate at laptop scale, with the numbers behind them."""

import csv
import json

import numpy as np

from dustygas.reproduce import get_figure


def test_fig4_1_to_4_3_and_settling_map(tmp_path):
    for name in ("fig4.1", "fig4.2", "fig4.3", "fig4.3-settling"):
        paths = get_figure(name).function(tmp_path, quick=True)
        assert paths[0].suffix == ".png" and paths[0].stat().st_size > 20_000
    # Fig 4.2: the unsettled τ_s = 1, μ = 0.1 curve peaks near s = 0.1 Ω at K ~ 2 (Fig 4.2/SH18)
    with open(tmp_path / "fig4_2.csv") as fh:
        rows = list(csv.reader(ln for ln in fh if not ln.startswith("#")))
    names, values = rows[0], np.array(rows[1:], dtype=float)
    s = values[:, names.index("taus=1 mu=0.1")]
    assert 0.08 < np.nanmax(s) < 0.12
    assert 1.0 < values[np.nanargmax(s), names.index("K")] < 4.0
    # Fig 4.3: the large-K plateau of §4.1.4 (τ_s = 1, μ = 0.1): flat to 1 % over the last decade (K = 1e4 .. 1e5)
    plateau = json.loads((tmp_path / "fig4_3.json").read_text())["plateau"]["taus=1 mu=0.1"]
    assert plateau["s_at_Kmax"] > 0.01
    assert plateau["relative_spread_last_decade"] < 1e-2
