"""Particles in yt's own dataset format, which ``yt.load`` opens without a plugin.

The file is what :meth:`yt.data_objects.data_containers.YTDataContainer.save_as_dataset` writes
for a region (yt's ``ytdata`` frontend, Turk et al. 2011, ApJS 192, 9): root attributes with
the domain, the current time and the unit system, and one group per particle type holding
datasets with yt's particle field names (``particle_position_x``, ``particle_velocity_x``,
``particle_mass``, ``particle_index``, and for SPH ``smoothing_length``, ``density``, ...), each
with a ``units`` attribute. After ``ds = yt.load(path)``, ``ds.all_data()["all",
"particle_mass"]`` holds the masses in ``code_mass``.

Particle types: the Lagrangian dust of a grid run is ``dust``; SPH particles are ``gas``,
``dust`` (two-fluid dust) and ``test`` after their ``ptype``.

Units: yt needs a cgs value for each code unit. Runs that define them (``length_unit_cgs``,
``mass_unit_cgs``, ``time_unit_cgs`` in the snapshot's attributes) get those; scale-free runs
(the shearing box) get 1 cm, 1 g and 1 s, i.e. yt's ``code_length`` *is* the run's length unit
and its cgs equivalent carries no meaning.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

import h5py
import numpy as np

from .atomic import atomic_path
from .schema import snapshot_quantity

__all__ = ["write_particles_ytdata", "particle_groups"]

_PTYPE_NAMES = {0: "gas", 1: "dust", 2: "test"}
_SCALAR_NAMES = {"mass": "particle_mass", "pid": "particle_index", "species": "particle_species",
                 "h": "smoothing_length", "rho": "density", "u": "specific_thermal_energy", "P": "pressure"}


def particle_groups(arrays: Mapping[str, np.ndarray]) -> dict[str, dict[str, tuple[np.ndarray, str]]]:
    """``{particle type: {yt field name: (values, units)}}`` of a snapshot (grid or SPH)."""
    groups: dict[str, dict[str, tuple[np.ndarray, str]]] = {}
    if "particles/pos" in arrays:  # grid engine: (3, N) vectors
        fields: dict[str, tuple[np.ndarray, str]] = {}
        for name, value in arrays.items():
            if not name.startswith("particles/"):
                continue
            leaf = name[len("particles/"):]
            units = snapshot_quantity(leaf).units
            value = np.asarray(value)
            if leaf in ("pos", "vel"):
                kind = "position" if leaf == "pos" else "velocity"
                for a, ax in enumerate("xyz"):
                    fields[f"particle_{kind}_{ax}"] = (value[a], units)
            elif value.ndim == 1:
                fields[_SCALAR_NAMES.get(leaf, leaf)] = (value, units)
        groups["dust"] = fields
    elif "pos" in arrays:  # SPH: (N, 3) vectors
        ptype = np.asarray(arrays.get("ptype", np.zeros(len(arrays["pos"]), dtype=np.int8)))
        for code in np.unique(ptype):
            sel = ptype == code
            fields = {}
            for name, value in arrays.items():
                leaf = name.rsplit("/", 1)[-1]
                value = np.asarray(value)
                if value.shape[:1] != ptype.shape or leaf == "ptype":
                    continue
                units = snapshot_quantity(leaf).units
                if value.ndim == 2 and value.shape[1] == 3:
                    stem = {"pos": "particle_position", "vel": "particle_velocity"}.get(leaf, leaf)
                    for a, ax in enumerate("xyz"):
                        fields[f"{stem}_{ax}"] = (value[sel, a], units)
                elif value.ndim == 1:
                    fields[_SCALAR_NAMES.get(leaf, leaf)] = (value[sel], units)
            groups[_PTYPE_NAMES.get(int(code), f"type{int(code)}")] = fields
    return groups


def _domain(arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    if "box_lo" in attrs:  # SPH box
        lo, hi = np.asarray(attrs["box_lo"], dtype=float), np.asarray(attrs["box_hi"], dtype=float)
        lo3, hi3 = np.full(3, -0.5), np.full(3, 0.5)
        lo3[: lo.size], hi3[: hi.size] = lo, hi
        if not (np.all(np.isfinite(lo3)) and np.all(np.isfinite(hi3))):  # open boundaries: the particles' extent
            pos = np.asarray(arrays["pos"])
            span = np.ptp(pos, axis=0) + 1e-12
            lo3 = np.where(np.isfinite(lo3), lo3, pos.min(axis=0) - 0.05 * span)
            hi3 = np.where(np.isfinite(hi3), hi3, pos.max(axis=0) + 0.05 * span)
        return lo3, hi3
    lo, hi = np.zeros(3), np.zeros(3)
    for a, ax in enumerate("xyz"):
        length = float(attrs.get(f"l{ax}", 1.0))
        c = np.asarray(arrays[ax])
        mid = 0.5 * (c[0] + c[-1])
        lo[a], hi[a] = mid - 0.5 * length, mid + 0.5 * length
    return lo, hi


def write_particles_ytdata(path: str | Path, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
    """Write the particles of one snapshot (``read_h5`` output) as a yt dataset at ``path``."""
    path = Path(path)
    groups = particle_groups(arrays)
    if not groups:
        raise ValueError("the snapshot holds no particles")
    lo, hi = _domain(arrays, attrs)
    units = {k: float(attrs.get(f"{k}_unit_cgs", 1.0)) for k in ("length", "mass", "time")}
    root: dict[str, Any] = {
        "data_type": "yt_data_container", "container_type": "region", "geometry": "cartesian",
        "dimensionality": 3, "domain_dimensions": np.ones(3, dtype=np.int32),
        "domain_left_edge": lo, "domain_right_edge": hi, "left_edge": lo, "right_edge": hi,
        "center": 0.5 * (lo + hi), "con_args": "('center', 'left_edge', 'right_edge')",
        "periodicity": np.array([bool(v) for v in attrs.get("periodic", [1, 1, 1])] + [True] * 3)[:3],
        "current_time": float(attrs.get("time", 0.0)), "current_time_units": "code_time",
        "length_unit": units["length"], "length_unit_units": "cm",
        "mass_unit": units["mass"], "mass_unit_units": "g",
        "time_unit": units["time"], "time_unit_units": "s",
        "velocity_unit": units["length"] / units["time"], "velocity_unit_units": "cm/s",
        "cosmological_simulation": 0, "current_redshift": 0.0, "omega_lambda": 0.0, "omega_matter": 0.0,
        "hubble_constant": 0.0,
    }
    for key in ("domain_left_edge", "domain_right_edge", "left_edge", "right_edge", "center"):
        root[f"{key}_units"] = "code_length"
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            for key, value in attrs.items():
                if isinstance(value, (list, tuple)):
                    value = np.array(value, dtype=h5py.string_dtype()) if value and isinstance(value[0], str) else np.asarray(value)
                f.attrs[f"dustygas_{key}" if key in root else key] = value
            for key, value in root.items():
                f.attrs[key] = value
            for ptype, fields in groups.items():
                g = f.create_group(ptype)
                g.attrs["num_elements"] = len(next(iter(fields.values()))[0])
                for name, (values, unit) in fields.items():
                    d = g.create_dataset(name, data=np.asarray(values))
                    d.attrs["units"] = "dimensionless" if unit == "dimensionless" else unit
    return path
