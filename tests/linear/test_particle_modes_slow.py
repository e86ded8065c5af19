"""Linear modes of the linear theory grown in the particle-gas engine (``-m slow``).

* two dust species: Benítez-Llambay, Krapp & Pessah (2019) linC (τ_s = 0.0425, 0.1; μ = 1, 0.5;
  K = 50), preset ``si-linC``: 48², one particle per cell and species, t = 0 → 7. Linear theory
  s = 0.3027262829; measured −1.38 % (fields within 0.45 %); tolerance 2 %. Cost ≈ 230 CPU-s.
"""

import pytest

from dustygas import api
from dustygas.analysis.growth import measure_growth, theory_for_run

LINC = 0.3027262829


@pytest.mark.slow
def test_two_species_linC_grows_within_two_percent(tmp_path):
    res = api.run("si-linC", output=tmp_path / "linc", set=["run.threads=0", "run.checkpoint_wall=0"])
    assert res.status == "finished"
    assert theory_for_run(tmp_path / "linc")["growth_rate"] == pytest.approx(LINC, abs=5e-11)
    fit = measure_growth(tmp_path / "linc")
    assert fit.growth_rate == pytest.approx(LINC, rel=0.02), fit
    assert fit.spread < 0.01, fit.fields
