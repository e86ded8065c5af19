"""Set-up of the two-species eigenmode box (``si-linC``): the state is the linear theory's mode.

The gas cells hold the cell averages of the eigenvector (their Fourier amplitude, divided by the
cell-average factor, is the point amplitude: to 1e-4); the particles of both species together
carry the total dust-density wave Σ_j μ_j δρ_j / Σ_j μ_j of the eigenvector, pre-compensated for
the TSC kernel (their raw mode is within 1 % of it at 32², measured 0.8 %).
"""

import numpy as np
import pytest

from dustygas.cli import main
from dustygas.linear import StreamingParams, fastest_mode
from dustygas.particles.diagnostics import MODE_FIELDS
from dustygas.problems import get_problem


def test_initial_state_is_the_two_species_eigenmode():
    prob = get_problem("si-linC")
    eng = prob.build(prob.config(overrides=["grid.nx=32", "grid.nz=32"]))
    got = dict(zip(MODE_FIELDS, eng.mode_amplitudes() / 1e-6))
    ev = fastest_mode(StreamingParams(taus=[0.0425, 0.1], mu=[1.0, 0.5], kx=50.0, kz=50.0)).eigenvector
    for key in ("ux", "uy", "uz"):
        assert abs(got[key] - 0.05 * ev[key]) <= 1e-4 * abs(0.05 * ev[key]) + 1e-9, key
    total = (1.0 * ev["drho_p"][0] + 0.5 * ev["drho_p"][1]) / 1.5
    assert abs(got["drho_p"] / total - 1) <= 0.01
    assert np.bincount(eng.particles.species).tolist() == [1024, 1024]
    assert eng.species.t_stop.tolist() == [0.0425, 0.1]


def test_species_lists_of_different_lengths_are_one_line_errors(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = main(["run", "si-linC", "--set", "problem.mu=[1.0]", "-o", "out"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "problem.taus" in err[0] and "problem.mu" in err[0], err
    assert not (tmp_path / "out").exists()
