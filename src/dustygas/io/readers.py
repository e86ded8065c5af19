"""Read run directories as xarray Datasets: ``dustygas.open_run(RUN)``.

>>> run = open_run("runs/si-linA")                      # doctest: +SKIP
>>> run.history["mode_drho_p_re"].plot()                 # doctest: +SKIP
>>> snap = run.snapshot(-1)                              # doctest: +SKIP
>>> snap["rho"].sel(y=0, method="nearest").plot()        # doctest: +SKIP

The history has dimension ``time``; a grid snapshot ``rho(z, y, x)`` with coordinates.

Grid snapshots become Datasets with dimensions ``z, y, x`` and the cell-centre coordinates
``x, y, z``; the Lagrangian particles of a grid run sit along a ``particle`` dimension with
yt's names (``particle_position_x``, ``particle_velocity_x``, ``particle_mass``, ...). SPH
snapshots have one ``particle`` dimension with the positions as coordinates ``x, y, z`` and
every per-particle field (vectors split into ``_x, _y, _z``). Each variable carries ``units``
and ``long_name`` (from the file, or from :mod:`dustygas.io.schema` for files written before
the schema), the Dataset the run's configuration, version, problem, time and cycle.

The same readers back the xarray engine: ``xarray.open_dataset(path, engine="dustygas")``
opens a snapshot file, ``history.h5`` or a run directory (its history).
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, Iterator

import numpy as np

from ..errors import UserError
from .hdf5 import read_h5
from .rundir import RunDirectory
from .schema import history_quantity, layout_of, numeric_attrs, snapshot_quantity

__all__ = ["Run", "open_run", "history_dataset", "snapshot_dataset", "read_dataset_file"]

_AXES = "xyz"
#: grid-engine particle arrays -> yt's particle field names
_PARTICLE_NAMES = {"mass": "particle_mass", "species": "particle_species", "pid": "particle_index"}


def _xr() -> Any:
    try:
        import xarray
    except ImportError:  # pragma: no cover - xarray is in the dev and outputs extras
        raise UserError("reading runs as Datasets needs xarray: pip install 'dustygas[outputs]'") from None
    return xarray


def _read_units(path: Path) -> dict[str, dict[str, str]]:
    """Per-dataset ``units``/``long_name`` attributes stored in the file (empty for old files)."""
    import h5py

    out: dict[str, dict[str, str]] = {}
    with h5py.File(path, "r") as f:
        def visit(name: str, obj: Any) -> None:
            if isinstance(obj, h5py.Dataset):
                out[name] = {k: (v.decode() if isinstance(v, bytes) else str(v))
                             for k, v in obj.attrs.items() if k in ("units", "long_name")}
        f.visititems(visit)
    return out


def _var_attrs(stored: dict[str, dict[str, str]], name: str, history: bool = False) -> dict[str, str]:
    q = history_quantity(name) if history else snapshot_quantity(name)
    attrs = {"units": q.units, "long_name": q.description}
    attrs.update(stored.get(name, {}))
    return attrs


def _global_attrs(attrs: dict[str, Any]) -> dict[str, Any]:
    return numeric_attrs({k: v for k, v in attrs.items() if not k.startswith("DIMENSION")})


def history_dataset(path: str | Path) -> Any:
    """``history.h5`` as an :class:`xarray.Dataset` with dimension ``time`` (``cycle`` a coordinate)."""
    xr = _xr()
    path = Path(path)
    arrays, attrs = read_h5(path)
    stored = _read_units(path)
    if "time" not in arrays:
        raise UserError(f"{path}: not a dustygas history (no time column)")
    time = np.asarray(arrays["time"])
    coords = {"time": ("time", time, _var_attrs(stored, "time", True))}
    if "cycle" in arrays:
        coords["cycle"] = ("time", np.asarray(arrays["cycle"]).astype(np.int64), _var_attrs(stored, "cycle", True))
    data = {name: ("time", np.asarray(v), _var_attrs(stored, name, True))
            for name, v in arrays.items() if name not in ("time", "cycle") and np.ndim(v) == 1}
    return xr.Dataset(data, coords=coords, attrs=_global_attrs(attrs))


def snapshot_dataset(path: str | Path) -> Any:
    """A snapshot file (grid or SPH) as an :class:`xarray.Dataset` (module docstring)."""
    xr = _xr()
    path = Path(path)
    arrays, attrs = read_h5(path)
    stored = _read_units(path)
    layout = layout_of(arrays)
    gattrs = _global_attrs(attrs)
    gattrs.setdefault("layout", layout)
    scalar_coords = {"time": ((), float(attrs.get("time", np.nan)), _var_attrs(stored, "time", True))}
    if layout.startswith("grid"):
        ds = _grid_dataset(xr, arrays, stored)
    elif layout == "sph":
        ds = _sph_dataset(xr, arrays, stored)
    else:
        raise UserError(f"{path}: not a dustygas snapshot (no grid fields, no SPH particles)")
    return ds.assign_coords({"time": scalar_coords["time"]}).assign_attrs(gattrs)


def _grid_dataset(xr: Any, arrays: dict[str, np.ndarray], stored: dict) -> Any:
    shape = np.shape(arrays["rho"])
    coords: dict[str, Any] = {ax: (ax, np.asarray(arrays[ax]), _var_attrs(stored, ax)) for ax in _AXES}
    data: dict[str, Any] = {}
    for name, value in arrays.items():
        if name.startswith("particles/") or name in _AXES:
            continue
        if np.shape(value) == shape:
            data[name] = (("z", "y", "x"), np.asarray(value), _var_attrs(stored, name))
        elif np.ndim(value) == 4 and np.shape(value)[1:] == shape:  # e.g. one field per particle species
            data[name] = ((f"{name}_component", "z", "y", "x"), np.asarray(value), _var_attrs(stored, name))
    for name, value in arrays.items():
        if not name.startswith("particles/"):
            continue
        leaf = name[len("particles/"):]
        attrs = _var_attrs(stored, name)
        value = np.asarray(value)
        if leaf in ("pos", "vel") and value.ndim == 2:
            kind = "position" if leaf == "pos" else "velocity"
            for a, ax in enumerate(_AXES):
                data[f"particle_{kind}_{ax}"] = ("particle", value[a], attrs)
        elif value.ndim == 1:
            data[_PARTICLE_NAMES.get(leaf, f"particle_{leaf}")] = ("particle", value, attrs)
    return xr.Dataset(data, coords=coords)


def _sph_dataset(xr: Any, arrays: dict[str, np.ndarray], stored: dict) -> Any:
    pos = np.asarray(arrays["pos"])
    coords: dict[str, Any] = {ax: ("particle", pos[:, a], {**_var_attrs(stored, "pos"), "long_name": f"particle position, {ax}"})
                              for a, ax in enumerate(_AXES)}
    data: dict[str, Any] = {}
    for name, value in arrays.items():
        if name == "pos":
            continue
        leaf = name.rsplit("/", 1)[-1]
        value = np.asarray(value)
        attrs = _var_attrs(stored, name)
        if value.ndim == 2 and value.shape[1] == 3:
            stem = "v" if leaf == "vel" else f"{leaf}_"
            for a, ax in enumerate(_AXES):
                data[f"{stem}{ax}"] = ("particle", value[:, a], attrs)
        elif value.ndim == 1:
            data[leaf] = ("particle", value, attrs)
    return xr.Dataset(data, coords=coords)


def read_dataset_file(path: str | Path) -> Any:
    """Open a snapshot, a ``history.h5`` or a run directory (its history) as a Dataset."""
    path = Path(path)
    if path.is_dir():
        return history_dataset(RunDirectory(path).history_file)
    import h5py

    with h5py.File(path, "r") as f:
        is_history = f.attrs.get("layout") == "history" or ("time" in f and "rho" not in f and "pos" not in f)
    return history_dataset(path) if is_history else snapshot_dataset(path)


class Run:
    """A run directory opened for analysis (:func:`open_run`).

    Attributes
    ----------
    path
        The run directory.
    config
        Every parameter of the run (``config.toml`` as nested dicts, ``[dustygas]`` included).
    problem
        The registered problem's name.
    """

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self._dir = RunDirectory(self.path)
        if not self._dir.config_file.exists():
            raise UserError(f"{self.path}: not a run directory (no config.toml)")
        self.config: dict[str, Any] = tomllib.loads(self._dir.config_file.read_text(encoding="utf-8"))
        self.problem: str = str(self.config.get("dustygas", {}).get("problem", ""))

    def __repr__(self) -> str:
        return f"Run({str(self.path)!r}, problem={self.problem!r}, snapshots={len(self)})"

    @property
    def snapshot_files(self) -> list[Path]:
        """Snapshot files in order."""
        return self._dir.snapshots()

    def __len__(self) -> int:
        return len(self.snapshot_files)

    @property
    def history(self) -> Any:
        """``history.h5`` as a Dataset with dimension ``time``."""
        if not self._dir.history_file.exists():
            raise UserError(f"{self.path}: no history.h5")
        return history_dataset(self._dir.history_file)

    def snapshot(self, index: int = -1) -> Any:
        """Snapshot ``index`` (position in :attr:`snapshot_files`; -1 the last) as a Dataset."""
        return snapshot_dataset(self._dir.snapshot_at(index))

    def snapshots(self) -> Iterator[Any]:
        """Every snapshot as a Dataset, in order."""
        for path in self.snapshot_files:
            yield snapshot_dataset(path)

    @property
    def snapshot_times(self) -> np.ndarray:
        """Simulated time of every snapshot."""
        import h5py

        times = []
        for path in self.snapshot_files:
            with h5py.File(path, "r") as f:
                times.append(float(f.attrs["time"]))
        return np.asarray(times)


def open_run(path: str | Path) -> Run:
    """Open the run directory ``path``: ``.history`` and ``.snapshot(i)`` as xarray Datasets."""
    return Run(path)
