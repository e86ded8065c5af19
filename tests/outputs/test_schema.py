"""Every snapshot and history file describes itself: units, dimension labels and scales, the
configuration and the version (acceptance: 'every file carries units, dimension labels/scales,
the full configuration and the version')."""

import tomllib

import h5py
import numpy as np
import pytest
import unyt
from unyt import Unit, UnitRegistry, dimensions

from dustygas import __version__
from dustygas.io.schema import UNDOCUMENTED

REGISTRY = UnitRegistry()
for _name, _dim in (("code_length", dimensions.length), ("code_mass", dimensions.mass), ("code_time", dimensions.time)):
    REGISTRY.add(_name, 1.0, _dim)

#: the dimension each key quantity must have (a wrong entry of the schema table fails here)
EXPECTED_DIMENSIONS = {
    "rho": dimensions.density, "rho_p": dimensions.density, "vx": dimensions.velocity, "x": dimensions.length,
    "particles/pos": dimensions.length, "particles/vel": dimensions.velocity, "particles/mass": dimensions.mass,
    "pos": dimensions.length, "h": dimensions.length, "mass": dimensions.mass, "u": dimensions.velocity**2,
    "P": dimensions.pressure, "extra/dust_fraction": dimensions.dimensionless,
}
HISTORY_DIMENSIONS = {"time": dimensions.time, "mass": dimensions.mass, "kinetic_energy": dimensions.energy,
                      "momentum_x": dimensions.momentum, "rho_max": dimensions.density}


def _datasets(f):
    names = []
    f.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
    return names


def _check_root(f, run):
    config = f.attrs["config"]
    assert tomllib.loads(config) == tomllib.loads((run / "config.toml").read_text())
    assert f.attrs["dustygas_version"] == __version__
    assert f.attrs["schema_version"] == 1


@pytest.mark.parametrize("which", ["grid_run", "particle_run", "sph_run"])
def test_snapshot_datasets_carry_units_and_dimensions(which, request):
    run = request.getfixturevalue(which)
    with h5py.File(sorted((run / "snapshots").glob("*.h5"))[-1], "r") as f:
        _check_root(f, run)
        layout = {"grid_run": "grid", "particle_run": "grid+particles", "sph_run": "sph"}[which]
        assert f.attrs["layout"] == layout
        for name in _datasets(f):
            ds = f[name]
            units = ds.attrs["units"]
            assert units != UNDOCUMENTED, f"{name} has no documented units"
            dim = Unit(units, registry=REGISTRY).dimensions  # parses with unyt (what yt uses)
            if name in EXPECTED_DIMENSIONS:
                assert dim == EXPECTED_DIMENSIONS[name], name
            assert ds.attrs["long_name"]
            labels = [d.label for d in ds.dims]
            if layout.startswith("grid") and ds.shape == f["rho"].shape:
                assert labels == ["z", "y", "x"]
                for i, axis in enumerate("zyx"):  # the coordinate datasets are attached dimension scales
                    assert ds.dims[i][0] == f[axis]
            elif name.startswith("particles/"):
                assert labels == (["component", "particle"] if ds.ndim == 2 else ["particle"])
            elif layout == "sph":
                assert labels == (["particle", "component"] if ds.ndim == 2 else ["particle"])


def test_grid_dimensions_are_distinct_and_sized(grid_run):
    """16 x 8 cells: the x and y scales keep their own lengths (nothing collapses)."""
    with h5py.File(sorted((grid_run / "snapshots").glob("*.h5"))[0], "r") as f:
        assert f["rho"].shape == (1, 8, 16)
        assert f["x"].shape == (16,) and f["y"].shape == (8,)
        np.testing.assert_allclose(f["x"][()], -0.5 + (np.arange(16) + 0.5) / 16, rtol=0, atol=1e-15)
        assert [len(d[0]) for d in f["rho"].dims] == [1, 8, 16]


@pytest.mark.parametrize("which", ["grid_run", "particle_run", "sph_run"])
def test_history_columns_carry_units_and_the_time_scale(which, request):
    run = request.getfixturevalue(which)
    with h5py.File(run / "history.h5", "r") as f:
        _check_root(f, run)
        for name in _datasets(f):
            ds = f[name]
            assert ds.attrs["units"] != UNDOCUMENTED, name
            dim = Unit(ds.attrs["units"], registry=REGISTRY).dimensions
            if name in HISTORY_DIMENSIONS:
                assert dim == HISTORY_DIMENSIONS[name], name
            assert ds.dims[0].label == "time"
            if name != "time":
                assert ds.dims[0][0] == f["time"]


def test_unyt_registry_is_the_one_yt_uses():
    """The unit strings are yt's code-unit names (yt datasets define exactly these)."""
    assert unyt.__version__ and {"code_length", "code_mass", "code_time"} <= set(REGISTRY.keys())
