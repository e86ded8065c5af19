"""The fastest streaming-instability mode of Youdin & Johansen (2007) linA, and a growth curve."""

import os
from pathlib import Path

import numpy as np

from dustygas.linear import StreamingParams, fastest_mode, growth_rate
from dustygas.plot import house_style, new_figure

out = Path(os.environ.get("DUSTYGAS_TUTORIAL_OUT", "."))

# linA: tau_s = 0.1, dust-to-gas ratio 3, K_x = K_z = 30 (wavenumbers in 1/(eta r))
mode = fastest_mode(StreamingParams(taus=0.1, mu=3.0, kx=30.0, kz=30.0, Pi=0.05))
print(f"linA: growth rate {mode.growth_rate:.7f} Omega, frequency {mode.frequency:.7f} Omega")

# growth along theta_k = 30 degrees for tau_s = 1, mu = 0.1 (thesis Figure 4.2)
k = np.geomspace(0.05, 100, 200)
th = np.radians(30.0)
s = np.array([growth_rate(taus=1.0, mu=0.1, kx=kk * np.sin(th), kz=kk * np.cos(th), Pi=0.05) for kk in k])
print(f"fastest growth {s.max():.4f} Omega at K = {k[np.argmax(s)]:.3f}")
with house_style():
    fig, ax = new_figure()
    ax.loglog(k, np.where(s > 0, s, np.nan))
    ax.set_xlabel(r"$|K| = |k|\eta r$")
    ax.set_ylabel(r"growth rate $s/\Omega$")
    fig.savefig(out / "growth_curve.png")
