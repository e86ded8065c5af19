"""Minimal HDF5 helpers: a flat or nested dict of arrays + attributes in, the same out.

Layout: datasets at ``/name`` (or ``/group/name`` for keys ``"group/name"``), attributes on
the root group. Strings and numbers are stored as attributes; numpy arrays as datasets.

With ``checksum=True`` the file also holds the root attribute ``sha256``: a SHA-256 over every
dataset (name, dtype, shape, bytes) and every other root attribute, which
``read_h5(..., verify=True)`` recomputes from what it read, so a flipped bit anywhere in the
stored values, a truncated or substituted dataset is detected (checkpoints use it).
"""

from __future__ import annotations

import hashlib
import io
from pathlib import Path
from typing import Any, Callable, Mapping

import h5py
import numpy as np

from .atomic import atomic_path

__all__ = ["write_h5", "read_h5", "checksum", "ChecksumError", "CHECKSUM_ATTR"]

#: Root attribute holding the SHA-256 of a file written with ``checksum=True``.
CHECKSUM_ATTR = "sha256"


class ChecksumError(ValueError):
    """The values read from a file do not match the checksum stored in it."""


def _attr(value: Any) -> Any:
    if isinstance(value, (list, tuple)):
        if value and all(isinstance(v, str) for v in value):
            return np.array(value, dtype=h5py.string_dtype())
        return np.asarray(value)
    return value


def _canonical(value: Any) -> bytes:
    """Bytes that identify a stored value, equal for what is written and what is read back."""
    if isinstance(value, bytes):
        value = value.decode("utf-8", "surrogateescape")
    if isinstance(value, str):
        return b"s" + value.encode("utf-8", "surrogateescape")
    a = np.asarray(value)
    if a.dtype.kind in "OSU":
        items = [x.decode("utf-8", "surrogateescape") if isinstance(x, bytes) else str(x) for x in a.ravel()]
        return b"S" + repr(a.shape).encode() + "\0".join(items).encode("utf-8", "surrogateescape")
    return a.dtype.str.encode() + repr(a.shape).encode() + np.ascontiguousarray(a).tobytes()


def checksum(arrays: Mapping[str, Any], attrs: Mapping[str, Any]) -> str:
    """SHA-256 (hex) of datasets and attributes, independent of the HDF5 layout."""
    digest = hashlib.sha256()
    for kind, table in ((b"D", arrays), (b"A", attrs)):
        for key in sorted(table):
            if kind == b"A" and key == CHECKSUM_ATTR:
                continue
            digest.update(kind + key.encode() + b"\0")
            digest.update(hashlib.sha256(_canonical(table[key])).digest())
    return digest.hexdigest()


_checksum = checksum  # write_h5's keyword argument shadows the name


def write_h5(
    path: str | Path,
    arrays: Mapping[str, np.ndarray],
    attrs: Mapping[str, Any] | None = None,
    compression: str | None = None,
    checksum: bool = False,
    annotate: Callable[[h5py.File], None] | None = None,
) -> None:
    """Write ``arrays`` (datasets) and ``attrs`` (root attributes) to ``path`` atomically.

    ``annotate(file)``, if given, is called on the open file after the datasets are written (e.g.
    :func:`dustygas.io.schema.annotate_snapshot`, which adds units, dimension labels and scales);
    the checksum, if asked for, is computed afterwards over everything the file then holds.

    The HDF5 image is assembled in memory and then written with plain file I/O, so a failing
    disk (full, quota, EFBIG) never reaches the HDF5 library -- whose clean-up after a failed
    write can crash the process -- but raises :class:`~dustygas.errors.OutputError` after
    removing the temporary file; ``path`` keeps its previous content. The price is one copy of
    the file in memory while it is written.
    """
    attrs = {key: _attr(value) for key, value in (attrs or {}).items()}
    arrays = {key: np.asarray(value) for key, value in arrays.items()}
    image = io.BytesIO()
    with h5py.File(image, "w") as f:
        for key, value in attrs.items():
            f.attrs[key] = value
        for key, value in arrays.items():
            kwargs = {}
            if compression and value.size > 1024:
                kwargs = {"compression": compression, "shuffle": True}
            f.create_dataset(key, data=value, **kwargs)
        if annotate is not None:
            annotate(f)
        if checksum:
            stored, raw = _contents(f)
            f.attrs[CHECKSUM_ATTR] = _checksum(stored, raw)
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(image.getbuffer())


def _contents(f: h5py.File) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """Every dataset (by full path) and the raw root attributes of an open file."""
    arrays: dict[str, np.ndarray] = {}

    def visit(name: str, obj: Any) -> None:
        if isinstance(obj, h5py.Dataset):
            arrays[name] = obj[()]

    f.visititems(visit)
    return arrays, dict(f.attrs.items())


def _read(path: str | Path) -> tuple[dict[str, np.ndarray], dict[str, Any], dict[str, Any]]:
    with h5py.File(path, "r") as f:
        arrays, raw = _contents(f)
    attrs = {}
    for k, v in raw.items():
        if isinstance(v, bytes):
            v = v.decode()
        elif isinstance(v, np.ndarray) and v.dtype.kind == "O":
            v = [x.decode() if isinstance(x, bytes) else x for x in v]
        elif isinstance(v, np.generic):
            v = v.item()
        attrs[k] = v
    return arrays, attrs, raw


def read_h5(path: str | Path, verify: bool = False) -> tuple[dict[str, np.ndarray], dict[str, Any]]:
    """Read every dataset (by full path without the leading slash) and the root attributes.

    With ``verify=True`` the file must hold a checksum (``write_h5(..., checksum=True)``) that
    matches what was read, else :class:`ChecksumError`.
    """
    arrays, attrs, raw = _read(path)
    if verify:
        stored = attrs.get(CHECKSUM_ATTR)
        if not isinstance(stored, str):
            raise ChecksumError("no checksum stored")
        if checksum(arrays, raw) != stored:
            raise ChecksumError("checksum mismatch (altered or damaged)")
    return arrays, attrs
