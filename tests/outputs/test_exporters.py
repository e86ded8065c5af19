"""yt, ParaView/VisIt (XDMF) and sarracen read what ``dustygas export`` writes (acceptance 1)."""

import xml.etree.ElementTree as ET

import h5py
import numpy as np
import pytest
import sarracen
import yt

from dustygas.io.export import export_run
from dustygas.io.hdf5 import read_h5
from dustygas.io.phantom import write_phantom
from foundation._cli import cli

yt.set_log_level(40)


def _snap(run, i):
    return sorted((run / "snapshots").glob("*.h5"))[i]


def test_yt_loads_grid_snapshot_with_the_right_density(grid_run, tmp_path):
    """yt's athena_pp frontend, no plugin: at t = 0 the density yt returns at a probed point is the
    exact wave 1 + A sin(k.x) at the centre of the cell holding it (A = 0.1; 1e-12), and the domain,
    dimensions and velocities are the run's."""
    files = export_run(grid_run, "athdf", tmp_path, snapshots=[0])
    ds = yt.load(str(files[0]))
    assert list(ds.domain_dimensions) == [16, 8, 1] and ds.dimensionality == 2
    np.testing.assert_allclose(ds.domain_left_edge.d[:2], [-0.5, -0.5])
    x0, y0 = 0.22, -0.30  # inside cell (11, 1), centre (0.21875, -0.3125)
    rho = float(ds.point([x0, y0, 0.5])["gas", "density"][0])
    assert abs(rho - (1 + 0.1 * np.sin(2 * np.pi * (0.21875 - 0.3125)))) < 1e-12
    arrays, _ = read_h5(_snap(grid_run, 0))
    assert float(ds.point([x0, y0, 0.5])["gas", "velocity_y"][0]) == arrays["vy"][0, 1, 11]
    assert str(ds.r[:]["gas", "density"].units) == "code_mass/code_length**3"
    ad = ds.all_data()
    assert ad["gas", "density"].size == 128


def test_yt_radial_vertical_box_keeps_x_and_z(particle_run, tmp_path):
    """An x-z box (one cell in y) is written with x1 = x, x2 = z as Athena++ does; the dust density
    yt returns at (x, z) is the snapshot's rho_p in that cell (z, 0, x), which varies with z."""
    files = export_run(particle_run, "athdf", tmp_path, snapshots=[-1])
    ds = yt.load(str(files[0]))
    arrays, _ = read_h5(_snap(particle_run, -1))
    x, z = arrays["x"], arrays["z"]
    assert list(ds.domain_dimensions) == [16, 16, 1]
    for ix, iz in ((3, 12), (12, 3), (7, 7)):
        value = float(ds.point([x[ix], z[iz], 0.5])["athena_pp", "rho_p"][0])
        assert value == arrays["rho_p"][iz, 0, ix]
    assert np.ptp(arrays["rho_p"]) > 0


def test_yt_loads_particles_with_positions_and_masses(particle_run, tmp_path):
    files = export_run(particle_run, "ytdata", tmp_path, snapshots=[-1])
    ds = yt.load(str(files[0]))
    arrays, attrs = read_h5(_snap(particle_run, -1))
    ad = ds.all_data()
    for a, axis in enumerate("xyz"):
        np.testing.assert_array_equal(ad["all", f"particle_position_{axis}"].d, arrays["particles/pos"][a])
    np.testing.assert_array_equal(ad["all", "particle_mass"].d, arrays["particles/mass"])
    assert str(ad["all", "particle_mass"].units) == "code_mass"
    assert str(ad["dust", "particle_velocity_x"].units) == "code_length/code_time"
    assert float(ds.current_time) == attrs["time"]


def test_xdmf_sidecar_points_at_the_athdf_datasets(grid_run, tmp_path):
    """The XDMF (what ParaView and VisIt open) is well-formed, names the mesh of the athdf file and
    addresses each variable's slab of /prim with the file's shape."""
    files = export_run(grid_run, "athdf", tmp_path, snapshots=[-1])
    athdf, xdmf = files
    root = ET.parse(xdmf).getroot()
    grid = root.find("Domain/Grid")
    assert grid.find("Topology").get("NumberOfElements") == "2 9 17"  # nodes along x3, x2, x1
    with h5py.File(athdf) as f:
        names = [v.decode() for v in f.attrs["VariableNames"]]
        nvar = f["prim"].shape[0]
        assert f["prim"].shape == (nvar, 1, 1, 8, 16)
        for item in grid.iter("DataItem"):
            if item.get("Format") == "HDF":
                path = item.text.strip().split(":")[1]
                assert tuple(int(v) for v in item.get("Dimensions").split()) == f[path].shape
    assert [a.get("Name") for a in grid.findall("Attribute")] == names == ["rho", "vel1", "vel2", "vel3"]


def test_sarracen_reads_phantom_export(sph_run, tmp_path):
    """Positions, masses, smoothing lengths and dust fractions as written; time and hfact in params."""
    files = export_run(sph_run, "phantom", tmp_path, snapshots=[-1])
    sdf = sarracen.read_phantom(str(files[0]))
    arrays, attrs = read_h5(_snap(sph_run, -1))
    np.testing.assert_array_equal(sdf["x"].to_numpy(), arrays["pos"][:, 0])
    np.testing.assert_array_equal(sdf["h"].to_numpy(), arrays["h"])
    np.testing.assert_array_equal(sdf["dustfrac"].to_numpy(), arrays["extra/dust_fraction"])
    assert sdf.params["mass"] == arrays["mass"][0] and np.all(arrays["mass"] == arrays["mass"][0])
    assert sdf.params["time"] == attrs["time"] and sdf.params["hfact"] == attrs["hfact"]
    assert sdf.params["nparttot"] == len(arrays["pos"]) and (sdf["itype"] == 1).all()
    assert sdf.xcol == "x" and sdf.hcol == "h"


def test_phantom_refinement_levels_and_refused_masses(sph_run, tmp_path):
    """Masses differing by powers of two become Phantom's apr_level (sarracen rebuilds the masses);
    other mixtures are refused with one line (exit 2) and nothing written."""
    arrays, attrs = read_h5(_snap(sph_run, -1))
    m = arrays["mass"].copy()
    m[::3] /= 4.0
    write_phantom(tmp_path / "dump_apr", {**arrays, "mass": m}, attrs)
    sdf = sarracen.read_phantom(str(tmp_path / "dump_apr"))
    np.testing.assert_allclose(sdf["mass"].to_numpy(), m, rtol=1e-15)
    m[1] *= 1.5
    with pytest.raises(ValueError, match="one mass per particle type"):
        write_phantom(tmp_path / "dump_bad", {**arrays, "mass": m}, attrs)
    assert not (tmp_path / "dump_bad").exists()


def test_sarracen_reads_csv_export_and_cli_errors(sph_run, tmp_path):
    proc = cli("export", str(sph_run), "--format", "csv", "--snapshot", "-1", "-o", str(tmp_path / "csv"), cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    sdf = sarracen.read_csv(proc.stdout.strip(), comment="#")
    arrays, _ = read_h5(_snap(sph_run, -1))
    np.testing.assert_array_equal(sdf["dust_fraction"].to_numpy(), arrays["extra/dust_fraction"])
    assert sdf.mcol == "mass" and sdf.hcol == "h"
    bad = cli("export", str(sph_run), "--format", "athdf", cwd=tmp_path)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "SPH snapshot" in bad.stderr
    bad = cli("export", str(sph_run), "--snapshot", "7", cwd=tmp_path)
    assert bad.returncode == 2 and "the run has 2 snapshots" in bad.stderr
