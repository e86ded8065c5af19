"""Thesis Figure 3.5: radial drift speed of dust versus stopping time (eq. 3.23).

:math:`-v_r/v_K` against :math:`\\tau_s` from :func:`dustygas.physics.disk.radial_drift_velocity`
with the thesis's values :math:`\\eta = 7.5\\times10^{-3}` (definition 3.24) and
:math:`v_{r,g}/v_K = -3.75\\times10^{-5}`; the dashed line is :math:`-v_{r,g}/v_K`, which the
dust follows for :math:`\\tau_s \\ll 1`. The curve peaks near :math:`\\tau_s = 1` at
:math:`\\approx\\eta/2` (Armitage 2013, Figure 4.2; Takeuchi & Lin 2002).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..physics.disk import radial_drift_velocity
from ..plot import Column, house_style, new_figure, save_figure
from . import figure

ETA = 7.5e-3
V_R_GAS_OVER_V_K = -3.75e-5
TAU_RANGE = (1e-3, 1e3)


def drift_curve(n: int = 601) -> tuple[np.ndarray, np.ndarray]:
    """:math:`\\tau_s` on a log grid over :data:`TAU_RANGE` and :math:`-v_r/v_K` there."""
    taus = np.geomspace(*TAU_RANGE, n)
    return taus, -radial_drift_velocity(taus, ETA, 1.0, V_R_GAS_OVER_V_K)


@figure("fig3.5", "Radial drift velocity -v_r/v_K versus tau_s (thesis eq. 3.23, Fig. 3.5)", cost="1 s")
def fig3_5(output: Path, quick: bool = True) -> list[Path]:
    """Write ``fig3_5.png`` and ``fig3_5.csv`` into ``output``; ``quick`` does not matter here."""
    taus, minus_vr = drift_curve()
    gas = np.full_like(taus, -V_R_GAS_OVER_V_K)
    with house_style():
        fig, ax = new_figure(width=5.0, height=3.6)
        ax.loglog(taus, minus_vr, color="C0", label=r"dust, eq. 3.23")
        ax.loglog(taus, gas, color="0.3", ls="--", lw=1.2, label=r"gas, $-v_{r,\mathrm{gas}}/v_K$")
        ax.set_xlim(*TAU_RANGE)
        ax.set_ylim(1e-6, 1e-2)
        ax.set_xlabel(r"stopping time $\tau_s = t_s\Omega$")
        ax.set_ylabel(r"inward drift speed $-v_r/v_K$")
        ax.set_title(rf"$\eta = {ETA * 1e3:g}\times10^{{-3}}$ (eq. 3.24), "
                     rf"$v_{{r,\mathrm{{gas}}}}/v_K = {V_R_GAS_OVER_V_K * 1e5:g}\times10^{{-5}}$", fontsize=10)
        ax.legend(loc="upper left")
        return save_figure(
            fig, Path(output) / "fig3_5.png",
            [
                Column("tau_s", taus, "1", "dimensionless stopping time t_s Omega"),
                Column("minus_vr_over_vK", minus_vr, "1", "-v_r/v_K of the dust, thesis eq. 3.23"),
                Column("minus_vr_gas_over_vK", gas, "1", "-v_r,gas/v_K, the dashed line"),
            ],
            title="dustygas: thesis Figure 3.5, radial dust drift versus stopping time",
            description=f"eta = {ETA!r} (thesis eq. 3.24), v_r,gas/v_K = {V_R_GAS_OVER_V_K!r}",
        )
