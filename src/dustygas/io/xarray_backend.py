"""The ``dustygas`` engine of :func:`xarray.open_dataset` (registered in ``pyproject.toml``).

>>> import xarray as xr                                                    # doctest: +SKIP
>>> xr.open_dataset("runs/si-linA/snapshots/snap_00001.h5", engine="dustygas")  # doctest: +SKIP
>>> xr.open_dataset("runs/si-linA", engine="dustygas")   # the run's history    # doctest: +SKIP

Datasets are read eagerly (snapshots of the laptop-scale runs fit in memory); see
:mod:`dustygas.io.readers` for their layout.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Iterable

from xarray.backends import BackendEntrypoint

from .readers import read_dataset_file

__all__ = ["DustygasBackendEntrypoint"]


class DustygasBackendEntrypoint(BackendEntrypoint):
    """Open dustygas snapshots, histories and run directories with xarray."""

    description = "dustygas snapshots (grid or SPH), history.h5 and run directories"
    open_dataset_parameters = ("filename_or_obj", "drop_variables")

    def open_dataset(self, filename_or_obj: Any, *, drop_variables: Iterable[str] | None = None) -> Any:
        ds = read_dataset_file(Path(os.fspath(filename_or_obj)))
        if drop_variables:
            ds = ds.drop_vars(list(drop_variables), errors="ignore")
        return ds

    def guess_can_open(self, filename_or_obj: Any) -> bool:
        try:
            path = Path(os.fspath(filename_or_obj))
        except TypeError:
            return False
        if path.is_dir():
            return (path / "config.toml").exists() and (path / "history.h5").exists()
        if path.suffix != ".h5" or not path.exists():
            return False
        import h5py

        try:
            with h5py.File(path, "r") as f:
                return "dustygas_version" in f.attrs
        except OSError:
            return False
