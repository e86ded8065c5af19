"""One-fluid dust settling in SPH: run, look at the dust fraction, export for sarracen."""

import os
from pathlib import Path

import numpy as np

import dustygas as dg

out = Path(os.environ.get("DUSTYGAS_TUTORIAL_OUT", "."))

dg.run("dust-settle", output="settle", set=["run.tlim=1.0", "run.dt_snapshot=0.5"])
run = dg.open_run("settle")
first, last = run.snapshot(0), run.snapshot(-1)
# the dust mass sum(m eps) is conserved by the upwind exchange (thesis eq. 3.17)
m0 = float((first["mass"] * first["dust_fraction"]).sum())
m1 = float((last["mass"] * last["dust_fraction"]).sum())
print(f"{last.sizes['particle']} particles; dust mass change {m1 / m0 - 1:.1e}")
print("dust fraction at |z| < 0.5 H:", float(last["dust_fraction"].where(abs(last["x"]) < 0.5).mean()))

dg.plot_snapshot("settle", field="dust_fraction", output=out / "settle_eps.png")
files = dg.export("settle", format="phantom", snapshots=[-1])
print("Phantom dump:", files[0].name)
try:
    import sarracen

    sdf = sarracen.read_phantom(str(files[0]))
    print("sarracen columns:", ", ".join(sdf.columns[:8]), "...")
    print("max |dustfrac - eps| =", float(np.abs(sdf["dustfrac"].to_numpy() - last["dust_fraction"].values).max()))
except ImportError:
    print("(install dustygas[outputs] for sarracen)")
