"""xarray: ``dustygas.open_run`` and ``xarray.open_dataset(..., engine="dustygas")`` give the right
dimensions, coordinates and units (acceptance 1, last clause)."""

import importlib.metadata
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import h5py
import numpy as np
import xarray as xr

import dustygas as dg
from dustygas.io.xarray_backend import DustygasBackendEntrypoint

ROOT = Path(__file__).resolve().parents[2]


def test_history_has_time_as_dimension(grid_run):
    hist = dg.open_run(grid_run).history
    with h5py.File(grid_run / "history.h5") as f:
        np.testing.assert_array_equal(hist["time"].values, f["time"][()])
        np.testing.assert_array_equal(hist["mass"].values, f["mass"][()])
    assert hist["mass"].dims == ("time",) and hist["time"].attrs["units"] == "code_time"
    assert hist["kinetic_energy"].attrs["units"] == "code_mass*code_length**2/code_time**2"
    assert np.all(np.diff(hist["time"].values) > 0)
    assert tomllib.loads(hist.attrs["config"])["grid"]["nx"] == 16


def test_grid_snapshot_dimensions_coordinates_and_probe(grid_run):
    """16 x 8 cells: rho(z, y, x) with the cell centres as coordinates; at t = 0 the density at a
    probed cell is the exact wave 1 + A sin(k.x) (A = 0.1, k = 2 pi (1, 1)) at its centre (1e-12)."""
    run = dg.open_run(grid_run)
    snap = run.snapshot(0)
    assert snap["rho"].dims == ("z", "y", "x") and snap.sizes == {"z": 1, "y": 8, "x": 16}
    np.testing.assert_allclose(snap["x"].values, -0.5 + (np.arange(16) + 0.5) / 16, atol=1e-15)
    np.testing.assert_allclose(snap["y"].values, -0.5 + (np.arange(8) + 0.5) / 8, atol=1e-15)
    assert snap["x"].attrs["units"] == "code_length" and snap["rho"].attrs["units"] == "code_mass/code_length**3"
    x0, y0 = 0.21875, -0.3125  # centres of cell (ix, iy) = (11, 1)
    value = float(snap["rho"].sel(x=x0, y=y0, method="nearest").squeeze())
    assert abs(value - (1 + 0.1 * np.sin(2 * np.pi * (x0 + y0)))) < 1e-12
    assert float(snap["time"]) == 0.0 and len(run) == 3
    times = run.snapshot_times  # the loop writes the first step at or after each multiple of dt_snapshot
    assert times[0] == 0.0 and 0.025 <= times[1] < 0.05 and abs(times[2] - 0.05) < 1e-12
    assert [float(s["time"]) for s in run.snapshots()] == list(times)


def test_particle_snapshot_has_particles_and_grid(particle_run):
    snap = dg.open_run(particle_run).snapshot(-1)
    with h5py.File(sorted((particle_run / "snapshots").glob("*.h5"))[-1]) as f:
        pos, mass = f["particles/pos"][()], f["particles/mass"][()]
    assert snap["particle_position_x"].dims == ("particle",) and snap.sizes["particle"] == pos.shape[1] == 256
    np.testing.assert_array_equal(snap["particle_position_z"].values, pos[2])
    np.testing.assert_array_equal(snap["particle_mass"].values, mass)
    assert snap["particle_mass"].attrs["units"] == "code_mass"
    assert snap["rho_p"].dims == ("z", "y", "x") and snap.sizes["x"] == snap.sizes["z"] == 16


def test_sph_snapshot_has_particle_coordinates(sph_run):
    snap = dg.open_run(sph_run).snapshot(-1)
    with h5py.File(sorted((sph_run / "snapshots").glob("*.h5"))[-1]) as f:
        pos, eps = f["pos"][()], f["extra/dust_fraction"][()]
    np.testing.assert_array_equal(snap["x"].values, pos[:, 0])
    np.testing.assert_array_equal(snap["dust_fraction"].values, eps)
    assert snap["dust_fraction"].dims == ("particle",) and snap["dust_fraction"].attrs["units"] == "dimensionless"
    assert snap["h"].attrs["units"] == "code_length" and snap.attrs["layout"] == "sph"


def test_backend_class_opens_files_and_run_directories(grid_run):
    snap = xr.open_dataset(sorted((grid_run / "snapshots").glob("*.h5"))[1], engine=DustygasBackendEntrypoint)
    assert snap["vx"].dims == ("z", "y", "x")
    hist = xr.open_dataset(grid_run, engine=DustygasBackendEntrypoint)
    assert hist["mass"].dims == ("time",)
    backend = DustygasBackendEntrypoint()
    assert backend.guess_can_open(grid_run / "history.h5") and not backend.guess_can_open(grid_run / "config.toml")


def _entry_point_env(tmp_path: Path) -> dict:
    """PYTHONPATH for a subprocess in which ``engine="dustygas"`` resolves: the installed package
    metadata if it declares the entry point, else a dist-info made from pyproject.toml's declaration."""
    env = dict(os.environ)
    paths = [str(ROOT / "src")]
    installed = {ep.name for ep in importlib.metadata.entry_points(group="xarray.backends")}
    if "dustygas" not in installed:  # an install older than the entry point: register pyproject's
        declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["entry-points"]["xarray.backends"]
        info = tmp_path / "dustygas_xarray_entry-0.dist-info"
        info.mkdir()
        (info / "METADATA").write_text("Metadata-Version: 2.1\nName: dustygas-xarray-entry\nVersion: 0\n")
        (info / "entry_points.txt").write_text("[xarray.backends]\n" + "".join(f"{k} = {v}\n" for k, v in declared.items()))
        paths.append(str(tmp_path))
    env["PYTHONPATH"] = os.pathsep.join(paths + [env.get("PYTHONPATH", "")])
    return env


def test_xarray_engine_name_resolves_through_the_entry_point(grid_run, tmp_path):
    code = ("import sys, xarray as xr; ds = xr.open_dataset(sys.argv[1], engine='dustygas'); "
            "print(ds['rho'].dims, dict(ds.sizes)); h = xr.open_dataset(sys.argv[2], engine='dustygas'); "
            "print(h['mass'].dims, h['time'].attrs['units'])")
    snap = sorted((grid_run / "snapshots").glob("*.h5"))[0]
    out = subprocess.run([sys.executable, "-c", code, str(snap), str(grid_run / "history.h5")], capture_output=True,
                         text=True, env=_entry_point_env(tmp_path), timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == ["('z', 'y', 'x') {'z': 1, 'y': 8, 'x': 16}", "('time',) code_time"]
