"""Minimal HDF5 helpers: a flat or nested dict of arrays + attributes in, the same out.

Layout: datasets at ``/name`` (or ``/group/name`` for keys ``"group/name"``), attributes on
the root group. Strings and numbers are stored as attributes; numpy arrays as datasets.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Callable, Mapping

import h5py
import numpy as np

from .atomic import atomic_path

__all__ = ["write_h5", "read_h5"]


def _attr(value: Any) -> Any:
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(v, str) for v in value):
            return np.array(value, dtype=h5py.string_dtype())
        return np.asarray(value)
    return value


def write_h5(
    path: str | Path,
    arrays: Mapping[str, np.ndarray],
    attrs: Mapping[str, Any] | None = None,
    compression: str | None = None,
    annotate: Callable[[h5py.File], None] | None = None,
) -> None:
    """Write ``arrays`` (datasets) and ``attrs`` (root attributes) to ``path`` atomically.

    ``annotate(file)``, if given, is called on the open file after the datasets are written and
    before it is renamed into place (e.g. :func:`dustygas.io.schema.annotate_snapshot`, which adds
    units, dimension labels and scales).
    """
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            for key, value in (attrs or {}).items():
                f.attrs[key] = _attr(value)
            for key, value in arrays.items():
                value = np.asarray(value)
                kwargs = {}
                if compression and value.size > 1024:
                    kwargs = {"compression": compression, "shuffle": True}
                f.create_dataset(key, data=value, **kwargs)
            if annotate is not None:
                annotate(f)


def read_h5(path: str | Path) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """Read every dataset (by full path without the leading slash) and the root attributes."""
    arrays: dict[str, np.ndarray] = {}
    with h5py.File(path, "r") as f:
        attrs = {}
        for k, v in f.attrs.items():
            if isinstance(v, bytes):
                v = v.decode()
            elif isinstance(v, np.ndarray) and v.dtype.kind == "O":
                v = [x.decode() if isinstance(x, bytes) else x for x in v]
            elif isinstance(v, np.generic):
                v = v.item()
            attrs[k] = v

        def visit(name: str, obj: Any) -> None:
            if isinstance(obj, h5py.Dataset):
                arrays[name] = obj[()]

        f.visititems(visit)
    return arrays, attrs
