"""Run a 2D sound wave on the grid, read it with xarray and draw it."""

import os
from pathlib import Path

import numpy as np

import dustygas as dg

out = Path(os.environ.get("DUSTYGAS_TUTORIAL_OUT", "."))

# 32 x 32 cells, one wavelength along the diagonal, three snapshots
dg.run("soundwave-2d", output="wave", set=["grid.nx=32", "grid.ny=32", "problem.amplitude=0.01",
                                          "run.tlim=0.5", "run.dt_snapshot=0.25"])
run = dg.open_run("wave")
print(run)
snap = run.snapshot(-1)
print(snap["rho"].dims, dict(snap.sizes), snap["rho"].attrs["units"])

# the wave travels at c_s = 1 along k = 2 pi (1, 1): compare with the exact solution at t
t = float(snap["time"])
x, y = np.meshgrid(snap["x"], snap["y"])
exact = 1 + 0.01 * np.sin(2 * np.pi * (x + y) - 2 * np.pi * np.sqrt(2) * t)
print(f"t = {t:.3f}: max |rho - exact| = {np.abs(snap['rho'][0] - exact).max().item():.2e}")

hist = run.history
print("mass conserved to", float(abs(hist["mass"] / hist["mass"][0] - 1).max()))
dg.plot_snapshot("wave", field="rho", output=out / "wave_rho.png")
dg.plot_history("wave", ["mass", "kinetic_energy"], output=out / "wave_history.png")
