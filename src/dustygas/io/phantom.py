"""SPH snapshots as Phantom dump files, the format splash, sarracen and plonk read.

The binary layout is Phantom's (Price et al. 2018, PASA 35, e031, and its documentation of the
dump file): Fortran unformatted sequential records, each framed by its length in bytes as a
4-byte integer.

1. the capture pattern ``i1 = 60769`` (default int), ``r1 = 60878.0`` (default real),
   ``i2 = 60878``, ``iversion = 1``, ``i3 = 690706`` (int32);
2. the 100-character file identifier (``FT:Phantom:dustygas ...``: full dump, tagged);
3. the global header: for each of the eight types (default int, int8, int16, int32, int64,
   default real, real4, real8) a record with the count, then records with the 16-character
   tags and the values;
4. the number of array blocks (2: particles and sink particles, none here), one record per block
   with its length (int64) and the number of arrays of each type (8 int32), then for each array
   a tag record and a data record.

Written here: default int int32 and default real float64; the header holds ``nparttot``,
``ntypes``, ``npartoftype`` (one per type), ``nblocks``, ``massoftype`` (one per type),
``time``, ``gamma``, ``hfact``, ``udist``, ``umass``, ``utime``, ``umagfd``; the arrays are
``x, y, z, h`` (and ``vx, vy, vz, u``, ``itype``, ``dustfrac`` for one-fluid dust, every other
scalar field under its dustygas name cut to 16 characters, the identifiers as ``iorig``).

Particle types follow Phantom: gas 1 (``igas``), dust 7 (``idust``, two-fluid dust), test
particles 5 (collisionless, Phantom's ``idarkmatter``). Phantom stores one mass per type; runs
whose masses differ within a type by powers of two are written with Phantom's ``apr_level``
(adaptive particle refinement: ``m = massoftype/2^(apr_level-1)``); other mixtures of masses
cannot be expressed and are refused (export as CSV instead).
"""

from __future__ import annotations

import time as _time
from pathlib import Path
from typing import Any, BinaryIO, Mapping

import numpy as np

from .._version import __version__
from .atomic import atomic_path

__all__ = ["write_phantom", "PHANTOM_TYPES"]

#: dustygas ptype -> Phantom particle type
PHANTOM_TYPES = {0: 1, 1: 7, 2: 5}
NTYPES = 8  # Phantom's maxtypes in its default build (gas, ..., dust)

_HEADER_TYPES = (np.int32, np.int8, np.int16, np.int32, np.int64, np.float64, np.float32, np.float64)


def _record(fh: BinaryIO, payload: bytes) -> None:
    tag = np.int32(len(payload)).tobytes()
    fh.write(tag + payload + tag)


def _tags(names: list[str]) -> bytes:
    return b"".join(n[:16].ljust(16).encode("ascii") for n in names)


def _masses(mass: np.ndarray, itype: np.ndarray) -> tuple[dict[int, float], np.ndarray | None]:
    """Mass per Phantom type, and ``apr_level`` (or None) when masses differ by powers of two."""
    per_type: dict[int, float] = {}
    levels = np.ones(mass.size, dtype=np.int8)
    need_levels = False
    for t in np.unique(itype):
        sel = itype == t
        m = mass[sel]
        top = float(m.max())
        per_type[int(t)] = top
        if np.all(m == top):
            continue
        ratio = np.log2(top / m)
        k = np.rint(ratio)
        if not np.allclose(ratio, k, rtol=0, atol=1e-9) or k.max() > 100:
            raise ValueError("Phantom dumps hold one mass per particle type (or powers-of-two refinement "
                             f"levels); the particles of type {int(t)} have {np.unique(m).size} other masses: "
                             "export as csv")
        levels[sel] = (k + 1).astype(np.int8)
        need_levels = True
    return per_type, levels if need_levels else None


def write_phantom(path: str | Path, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
    """Write one SPH snapshot (``read_h5`` output) as a Phantom dump at ``path``."""
    path = Path(path)
    pos = np.asarray(arrays["pos"], dtype=np.float64)
    n = pos.shape[0]
    ptype = np.asarray(arrays.get("ptype", np.zeros(n, dtype=np.int8)))
    itype = np.array([PHANTOM_TYPES.get(int(t), 5) for t in ptype], dtype=np.int8) if n else np.zeros(0, np.int8)
    per_type, levels = _masses(np.asarray(arrays["mass"], dtype=np.float64), itype)

    ints: dict[str, list[int]] = {"nparttot": [n], "ntypes": [NTYPES],
                                  "npartoftype": [int(np.sum(itype == t)) for t in range(1, NTYPES + 1)],
                                  "nblocks": [1]}
    units = {k: float(attrs.get(f"{k}_unit_cgs", 1.0)) for k in ("length", "mass", "time")}
    reals = {"time": [float(attrs.get("time", 0.0))], "gamma": [float(attrs.get("gamma", 1.0))],
             "hfact": [float(attrs.get("hfact", 1.2))],
             "massoftype": [per_type.get(t, 0.0) for t in range(1, NTYPES + 1)]}
    real8 = {"udist": [units["length"]], "umass": [units["mass"]], "utime": [units["time"]], "umagfd": [1.0]}

    columns: list[tuple[str, np.ndarray]] = []
    for a, ax in enumerate("xyz"):
        columns.append((ax, pos[:, a]))
    columns.append(("h", np.asarray(arrays["h"], dtype=np.float64)))
    vel = np.asarray(arrays.get("vel", np.zeros((n, 3))), dtype=np.float64)
    for a, ax in enumerate("xyz"):
        columns.append((f"v{ax}", vel[:, a]))
    renamed = {"extra/dust_fraction": "dustfrac", "extra/grain_size": "grainsize", "pid": "iorig"}
    skip = {"pos", "vel", "h", "mass", "ptype"}
    int64_columns: list[tuple[str, np.ndarray]] = []
    for name, value in arrays.items():
        value = np.asarray(value)
        if name in skip or value.shape != (n,):
            continue
        tag = renamed.get(name, name.rsplit("/", 1)[-1])
        if np.issubdtype(value.dtype, np.integer):
            int64_columns.append((tag, value.astype(np.int64)))
        else:
            columns.append((tag, value.astype(np.float64)))
    int8_columns = [("itype", itype)] + ([("apr_level", levels)] if levels is not None else [])

    ident = f"FT:Phantom:dustygas {__version__}: {attrs.get('problem', '')} {_time.strftime('%d/%m/%Y %H:%M:%S')}"
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            _record(fh, np.int32(60769).tobytes() + np.float64(60878.0).tobytes() + np.int32(60878).tobytes()
                    + np.int32(1).tobytes() + np.int32(690706).tobytes())
            _record(fh, ident[:100].ljust(100).encode("ascii", "replace"))
            header: list[dict[str, list]] = [ints, {}, {}, {}, {}, reals, {}, real8]
            for kind, values in zip(_HEADER_TYPES, header):
                names = [k for k, vs in values.items() for _ in vs]
                flat = [v for vs in values.values() for v in vs]
                _record(fh, np.int32(len(flat)).tobytes())
                if flat:
                    _record(fh, _tags(names))
                    _record(fh, np.asarray(flat, dtype=kind).tobytes())
            _record(fh, np.int32(2).tobytes())
            counts = [0, len(int8_columns), 0, 0, len(int64_columns), len(columns), 0, 0]
            _record(fh, np.int64(n).tobytes() + np.asarray(counts, dtype=np.int32).tobytes())
            _record(fh, np.int64(0).tobytes() + np.zeros(8, dtype=np.int32).tobytes())  # no sink particles
            for tag, values in int8_columns:
                _record(fh, _tags([tag]))
                _record(fh, np.ascontiguousarray(values, dtype=np.int8).tobytes())
            for tag, values in int64_columns:
                _record(fh, _tags([tag]))
                _record(fh, np.ascontiguousarray(values, dtype=np.int64).tobytes())
            for tag, values in columns:
                _record(fh, _tags([tag]))
                _record(fh, np.ascontiguousarray(values, dtype=np.float64).tobytes())
    return path
