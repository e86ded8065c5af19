"""Growth fitting: exact on synthetic modes, and the automatic window.

Synthetic data: eight fields carrying the same fastest mode, plus a damped mode (the start-up
transient of a run, like the drag-relaxation modes of the linear theory) in different
proportions per field, so the fields' growth rates over the whole run disagree and agree once
the transient has decayed. The command line on a real run: ``particles/test_streaming.py``.
"""

import numpy as np
import pytest

from dustygas.analysis.growth import MODE_FIELDS, fit_growth, linear_window, measure_growth
from dustygas.errors import UserError

S, W = 0.419, 0.348  # the mode: A ~ exp(-i (W + i S) t)
S2, W2 = -3.0, 2.0


def synthetic(t, contamination):
    modes = {}
    for i, f in enumerate(MODE_FIELDS):
        a = (1 + 0.3 * i) * np.exp(1j * i) * 1e-6
        b = contamination * (i - 3.5) / 3.5 * abs(a) * np.exp(0.5j * i)
        modes[f] = a * np.exp(-1j * (W + 1j * S) * t) + b * np.exp(-1j * (W2 + 1j * S2) * t)
    return modes


def test_fit_of_a_pure_mode_is_exact():
    t = np.linspace(0, 6, 601)
    fit = measure_growth((t, synthetic(t, 0.0)))
    assert fit.growth_rate == pytest.approx(S, rel=1e-12)
    assert fit.frequency == pytest.approx(W, rel=1e-12)
    assert fit.window == (0.0, 6.0) and fit.spread < 1e-12
    for v in fit.fields.values():
        assert v["growth_rate"] == pytest.approx(S, rel=1e-12)


def test_window_skips_the_transient_and_recovers_the_rate():
    t = np.linspace(0, 6, 601)
    modes = synthetic(t, 0.5)
    whole = measure_growth((t, modes), window=(0.0, 6.0))
    assert whole.spread > 0.01  # the transient spoils the whole-run fit
    fit = measure_growth((t, modes))
    lo, hi = fit.window
    assert 0.0 < lo <= 3.0 and hi == 6.0
    assert fit.spread < 0.005
    assert fit.growth_rate == pytest.approx(S, rel=1e-3)


def test_window_ends_before_the_mode_turns_non_linear():
    t = np.linspace(0, 30, 3001)
    modes = synthetic(t, 0.0)
    start, end = linear_window(t, modes, nonlinear=0.01)
    # |drho_g| = 1e-6 exp(S t) and |drho_p| = 2.2e-6 exp(S t) reach 0.01 first for drho_p
    assert end == pytest.approx(np.log(0.01 / 2.2e-6) / S, abs=0.02)
    with pytest.raises(UserError, match="fewer than three"):
        fit_growth(t[:2], modes["ux"][:2])


def test_modal_fit_removes_a_near_parallel_partner_and_an_undamped_wave():
    """Thesis Fig 4.6 at tau_s = 0.001 (mu = 0.1, |K| = 59.7, theta_k = 30 deg, K_z < 0): the growing
    mode's decaying partner has a nearly parallel eigenvector and the inertial wave is damped at
    only 5.6e-5 Omega. A state made of the growing mode plus 3 % of the partner and an inertial wave
    of 30 % of the growing mode's velocity (run units: velocities times Pi) spreads the eight
    fields' fitted rates by more than 5 %; the modal fit recovers LAPACK's eigenvalue of the
    operator to 1e-9."""
    from dustygas.analysis.growth import measure_modal_growth
    from dustygas.linear import StreamingParams, operator_matrix
    from dustygas.linear.modes import eigenmodes

    th = np.radians(30.0)
    p = StreamingParams(taus=0.001, mu=0.1, kx=59.7 * np.sin(th), kz=-59.7 * np.cos(th), Pi=0.05, vz="settling")
    s_lapack = float(np.linalg.eigvals(operator_matrix(p)).real.max())
    em = eigenmodes(p)
    assert abs(em.omega[1].imag) < 1e-4 < abs(em.omega[2].imag)  # the wave; the partner
    t = np.linspace(0.0, 6.0, 401)
    v = em.vectors
    ratio = np.linalg.norm(v[1:4, 0]) / np.linalg.norm(v[1:4, 1])
    amp = (1e-6 * np.outer(v[:, 0], np.exp(-1j * em.omega[0] * t))
           + 3e-8 * np.outer(v[:, 2], np.exp(-1j * em.omega[2] * t))
           + 0.3e-6 * ratio * np.outer(v[:, 1], np.exp(-1j * em.omega[1] * t)))
    modes = {f: amp[i] * (1.0 if f.startswith("drho") else p.Pi) for i, f in enumerate(MODE_FIELDS)}
    assert measure_growth((t, modes)).spread > 0.05
    fit = measure_modal_growth((t, modes), params=p)
    assert fit.growth_rate == pytest.approx(s_lapack, rel=1e-9)
    assert fit.frequency == pytest.approx(em.omega[0].real, rel=1e-9)
    assert fit.spread < 1e-9
    assert fit.fields["remainder"]["growth_rate"] > 0.1  # what is not the growing mode is reported
