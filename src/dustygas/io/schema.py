"""The output schema: units, dimension names and descriptions of every dataset dustygas writes.

Snapshots and histories are plain HDF5 (:mod:`dustygas.io.hdf5`); this module says what is in
them, and :func:`annotate_snapshot` / :func:`annotate_history` write that description into each
file as it is created, so a file read without dustygas still explains itself:

* every dataset has ``units`` (a `unyt <https://unyt.readthedocs.io>`_/yt expression in the
  run's *code units*, ``code_length``, ``code_mass``, ``code_time``; ``dimensionless`` for pure
  numbers) and ``long_name``;
* the dimensions are labelled (``z, y, x`` for grid fields, ``particle`` and ``component`` for
  particles, ``time`` for history columns), and the coordinate datasets ``x, y, z`` of a grid
  snapshot and ``time`` of a history are HDF5 *dimension scales* attached to the datasets they
  label (what netCDF-4 readers and ``h5py``'s ``dims`` use);
* the root carries the run's full configuration (``config``, the TOML text of ``config.toml``),
  ``dustygas_version``, ``problem``, ``time``, ``cycle``, the ``layout`` (``grid``,
  ``grid+particles`` or ``sph``) and ``schema_version``.

Code units
----------
Every engine works in code units. The shearing-box problems use :math:`c_s = \\Omega = H = 1`
and the mean gas density :math:`\\rho_{g,0} = 1` (so the mass unit is :math:`\\rho_{g,0}H^3`);
the problems of Youdin & Johansen (2007) keep :math:`c_s = \\Omega = 1` and state their wave
numbers in units of :math:`1/(\\eta r)`. The SPH test problems are dimensionless (unit sound
speed or density of the set-up); the global-disk problems use au, M_sun and yr/(2π)
(:data:`dustygas.units.DISK_UNITS`, so that G = 1). Where an engine knows the cgs value of its
units it adds ``length_unit_cgs``, ``mass_unit_cgs`` and ``time_unit_cgs`` to the snapshot's
attributes; scale-free runs (the shearing box, where only ratios matter) have none.

The tables :data:`SNAPSHOT_FIELDS` and :data:`HISTORY_COLUMNS` are the single source of the
units; the documentation's output-schema page is generated from them.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

__all__ = [
    "Quantity",
    "SCHEMA_VERSION",
    "SNAPSHOT_FIELDS",
    "HISTORY_COLUMNS",
    "HISTORY_PATTERNS",
    "UNDOCUMENTED",
    "layout_of",
    "snapshot_quantity",
    "history_quantity",
    "snapshot_dims",
    "annotate_snapshot",
    "annotate_history",
    "root_attributes",
    "numeric_attrs",
]

#: version of the layout described here (stored as the ``schema_version`` root attribute)
SCHEMA_VERSION = 1

#: units written for a dataset this schema does not know (a test keeps every engine's fields known)
UNDOCUMENTED = "undocumented"

LENGTH = "code_length"
TIME = "code_time"
MASS = "code_mass"
DENSITY = "code_mass/code_length**3"
VELOCITY = "code_length/code_time"
ACCELERATION = "code_length/code_time**2"
SPECIFIC_ENERGY = "code_length**2/code_time**2"
PRESSURE = "code_mass/(code_length*code_time**2)"
MOMENTUM = "code_mass*code_length/code_time"
ANGULAR_MOMENTUM = "code_mass*code_length**2/code_time"
ENERGY = "code_mass*code_length**2/code_time**2"
RATE = "1/code_time"
ONE = "dimensionless"


@dataclass(frozen=True)
class Quantity:
    """Units (yt/unyt syntax, code units) and a one-line description of a dataset."""

    units: str
    description: str


#: Snapshot datasets by name (``particles/`` and ``extra/`` prefixes stripped for the lookup).
SNAPSHOT_FIELDS: dict[str, Quantity] = {
    # grid engines
    "rho": Quantity(DENSITY, "gas density (cell average; SPH: at the particle)"),
    "vx": Quantity(VELOCITY, "gas velocity, x (radial) component, full velocity in the rotating frame"),
    "vy": Quantity(VELOCITY, "gas velocity, y (azimuthal) component, full velocity in the rotating frame"),
    "vz": Quantity(VELOCITY, "gas velocity, z (vertical) component"),
    "x": Quantity(LENGTH, "cell-centre coordinate along x (radial)"),
    "y": Quantity(LENGTH, "cell-centre coordinate along y (azimuthal)"),
    "z": Quantity(LENGTH, "cell-centre coordinate along z (vertical)"),
    "rho_p": Quantity(DENSITY, "dust (particle) mass density deposited on the mesh with the run's kernel"),
    "rho_p_species": Quantity(DENSITY, "dust density of each particle species (species, z, y, x; runs with "
                                       "several species)"),
    "phi_p": Quantity(SPECIFIC_ENERGY, "self-gravitational potential of the particles (solution of "
                      "lap(Phi) = G~ rho_p; written once self-gravity is on)"),
    # Lagrangian particles of the grid engine (prefix particles/) and SPH particles
    "pos": Quantity(LENGTH, "particle position"),
    "vel": Quantity(VELOCITY, "particle velocity (grid engine: in the gas's frame, see the problem)"),
    "mass": Quantity(MASS, "particle mass"),
    "species": Quantity(ONE, "index of the particle's species (stopping-time table t_stop)"),
    "pid": Quantity(ONE, "particle identifier (unique, preserved through the run)"),
    # SPH particles
    "h": Quantity(LENGTH, "smoothing length"),
    "u": Quantity(SPECIFIC_ENERGY, "specific internal energy"),
    "P": Quantity(PRESSURE, "gas pressure"),
    "alpha": Quantity(ONE, "artificial-viscosity parameter"),
    "ptype": Quantity(ONE, "particle type: 0 gas, 1 dust (two-fluid), 2 test particle"),
    # SPH dust modules (prefix extra/)
    "dust_fraction": Quantity(ONE, "dust mass fraction eps = rho_d/rho (one-fluid dust, thesis eq. 3.2)"),
    "ddust_dt": Quantity(RATE, "time derivative of the dust fraction (thesis eqs. 3.4, 3.17)"),
    "sqrt_rho_eps": Quantity("sqrt(code_mass/code_length**3)", "sqrt(rho eps), the evolved dust variable"),
    "stopping_time": Quantity(TIME, "dust stopping time t_s"),
    "dust_inflow": Quantity(RATE, "dust-fraction rate received from neighbours (grain-size advection)"),
    "dust_inflow_size": Quantity(f"{LENGTH}/{TIME}", "size-weighted dust-fraction inflow rate (thesis eq. 3.12)"),
    "dust_outflow": Quantity(RATE, "dust-fraction rate given to neighbours (grain-size advection)"),
    "grain_size": Quantity(LENGTH, "grain size s"),
    "dgrain_size_dt": Quantity(VELOCITY, "growth rate of the grain size ds/dt (thesis eqs. 3.6-3.7)"),
    "delta_v": Quantity(VELOCITY, "dust-gas velocity difference (full one-fluid model)"),
    "ddelta_v_dt": Quantity(ACCELERATION, "time derivative of the dust-gas velocity difference"),
    "drag_ddelta_v_dt": Quantity(ACCELERATION, "drag part of d(delta_v)/dt"),
    "drag_heating": Quantity(f"{SPECIFIC_ENERGY}/{TIME}", "frictional heating rate per unit mass"),
    "drag_acc": Quantity(ACCELERATION, "drag acceleration (two-fluid dust)"),
    "drag_min_stopping_time": Quantity(TIME, "shortest stopping time among the particle's drag pairs"),
    # block individual time steps and disk runs (extra/)
    "level": Quantity(ONE, "time-step level of the particle: its step is the block step / 2^level"),
    "ring": Quantity(ONE, "index of the dust ring the particle belongs to (-1: none)"),
    "track": Quantity(ONE, "index of the tracked gas particle (-1: not tracked)"),
}

#: History columns by exact name.
HISTORY_COLUMNS: dict[str, Quantity] = {
    "time": Quantity(TIME, "simulated time"),
    "cycle": Quantity(ONE, "number of steps taken"),
    "mass": Quantity(MASS, "total gas mass (2D/1D grids: per unit length of the inactive axes)"),
    "dust_mass": Quantity(MASS, "total dust mass"),
    "particle_mass": Quantity(MASS, "total mass of the Lagrangian particles"),
    "radial_boundary_mass": Quantity(MASS, "gas mass that left through the radial boundaries"),
    "gas_mass_lost": Quantity(MASS, "gas mass that left through the open z faces (time integral of their mass "
                                    "fluxes; negative: inflow)"),
    "particle_mass_lost": Quantity(MASS, "mass of the particles that left through outflow faces"),
    "rho_p_max": Quantity(DENSITY, "largest dust (particle) density on the mesh"),
    "kinetic_energy": Quantity(ENERGY, "total kinetic energy"),
    "thermal_energy": Quantity(ENERGY, "total thermal energy"),
    "potential_energy": Quantity(ENERGY, "total potential energy of external gravity"),
    "total_energy": Quantity(ENERGY, "kinetic + thermal + potential energy"),
    "rho_max": Quantity(DENSITY, "largest gas density"),
    "rho_min": Quantity(DENSITY, "smallest gas density"),
    "momentum_y_source": Quantity(MOMENTUM, "azimuthal momentum added by the shearing-box sources"),
    "n_particles": Quantity(ONE, "number of particles"),
    "max_dust_fraction": Quantity(ONE, "largest dust fraction"),
    "min_dust_fraction": Quantity(ONE, "smallest dust fraction"),
    "mean_grain_size": Quantity(LENGTH, "dust-mass-weighted mean grain size"),
    "min_grain_size": Quantity(LENGTH, "smallest grain size"),
    "drag_resolution": Quantity(ONE, "smallest stopping time over the time step (two-fluid drag resolution)"),
    "drag_unresolved_fraction": Quantity(ONE, "fraction of dust particles whose stopping time is unresolved"),
    "gas_vx": Quantity(VELOCITY, "mean gas velocity, x"),
    "gas_vy": Quantity(VELOCITY, "mean gas velocity, y"),
    "dust_vx": Quantity(VELOCITY, "mean particle velocity, x"),
    "gravity_on": Quantity(ONE, "1 once particle self-gravity acts (t >= gravity.t_on), else 0"),
    "gravity_energy": Quantity(ENERGY, "self-gravitational energy of the particles, W = 1/2 sum rho_p Phi V "
                               "(0 before gravity.t_on; vacuum z: the planar mode's Phi = 2 pi G Sigma |z| makes "
                               "a uniform layer's W positive)"),
    "accreted_mass": Quantity(MASS, "mass accreted by the central star (sink)"),
    "block_dt": Quantity(TIME, "longest (block) step of the individual time-step hierarchy"),
    "levels": Quantity(ONE, "number of occupied time-step levels"),
    "substeps": Quantity(ONE, "sub-steps of the finest level taken so far"),
    "updates": Quantity(ONE, "particle updates of the last block step"),
    "total_updates": Quantity(ONE, "particle updates since the start of the run"),
}

#: History columns by pattern (first match wins): per-axis and per-species families.
HISTORY_PATTERNS: list[tuple[str, Quantity]] = [
    (r"(particle_|total_)?momentum_[xyz]", Quantity(MOMENTUM, "total momentum component")),
    (r"angular_momentum_[xyz]", Quantity(ANGULAR_MOMENTUM, "total angular momentum component")),
    (r"species_\d+_v[xyz]", Quantity(VELOCITY, "mean velocity of one particle species")),
    (r"species_\d+_mass", Quantity(MASS, "total mass of one particle species")),
    (r"species_\d+_z_mean", Quantity(LENGTH, "mass-weighted mean height of one particle species")),
    (r"species_\d+_scale_height", Quantity(LENGTH, "particle scale height H_p (mass-weighted rms of z about its "
                                                  "mean) of one species")),
    (r"species_\d+_sigma_[xyz]", Quantity(VELOCITY, "mass-weighted velocity dispersion of one particle species")),
    (r"gas_mass_lost_z_(lower|upper)", Quantity(MASS, "gas mass that left through one z face")),
    (r"particle_mass_lost_[xyz]_(lower|upper)", Quantity(MASS, "mass of the particles that left through one face")),
    (r"particle_momentum_lost_[xyz]", Quantity(MOMENTUM, "momentum carried out by the particles that left")),
    (r"(particle|gas)_terms_impulse_[xyz]", Quantity(MOMENTUM, "impulse of the external force terms on the "
                                                              "particles or the gas (time integral)")),
    (r"ring\d+(_gas)?_n", Quantity(ONE, "number of dust particles of ring k (_gas: gas particles in its annulus)")),
    (r"ring\d+(_gas)?_(mean|std)_(R|z)", Quantity(LENGTH, "mean / standard deviation of cylindrical R or height z "
                                                 "of ring k's dust (_gas: of the gas in its annulus)")),
    (r"ring\d+(_gas)?_(mean|std)_(vR|vz|dvphi|vphi)", Quantity(VELOCITY, "mean / standard deviation of v_R, v_z, "
                                                               "v_phi - v_K or v_phi of ring k's dust (_gas: of the "
                                                               "gas in its annulus)")),
    (r"track\d+_[Rz]", Quantity(LENGTH, "cylindrical R or height z of tracked gas particle j (0: accreted)")),
    (r"mode_drho_[gp]_(re|im)", Quantity(ONE, "Fourier amplitude of the relative density perturbation (real/imaginary part)")),
    (r"mode_[uw][xyz]_(re|im)", Quantity(VELOCITY, "Fourier amplitude of the gas (u) or dust (w) velocity (real/imaginary part)")),
]


def _leaf(name: str) -> str:
    return name.rsplit("/", 1)[-1]


def snapshot_quantity(name: str) -> Quantity:
    """Units and description of snapshot dataset ``name`` (``undocumented`` if unknown)."""
    return SNAPSHOT_FIELDS.get(_leaf(name), Quantity(UNDOCUMENTED, ""))


def history_quantity(name: str) -> Quantity:
    """Units and description of history column ``name`` (``undocumented`` if unknown)."""
    if name in HISTORY_COLUMNS:
        return HISTORY_COLUMNS[name]
    for pattern, q in HISTORY_PATTERNS:
        if re.fullmatch(pattern, name):
            return q
    return Quantity(UNDOCUMENTED, "")


def layout_of(names: Mapping[str, Any] | list[str]) -> str:
    """``grid``, ``grid+particles`` or ``sph`` from the dataset names of a snapshot."""
    keys = set(names)
    if "pos" in keys and "h" in keys:
        return "sph"
    if {"rho", "x", "y", "z"} <= keys:
        return "grid+particles" if any(k.startswith("particles/") for k in keys) else "grid"
    return "unknown"


def snapshot_dims(name: str, shape: tuple[int, ...], layout: str, grid_shape: tuple[int, ...] | None) -> tuple[str, ...]:
    """Dimension names of snapshot dataset ``name`` of ``shape`` in a snapshot of ``layout``.

    Grid fields ``(nz, ny, nx)`` have ``(z, y, x)``; the coordinates ``x, y, z`` are their own
    dimension; particle vectors are ``(component, particle)`` in the grid engine (its store is
    ``(3, N)``) and ``(particle, component)`` in SPH (``(N, 3)``); per-particle scalars ``(particle,)``.
    """
    if layout.startswith("grid") and not name.startswith("particles/"):
        if name in ("x", "y", "z") and len(shape) == 1:
            return (name,)
        if grid_shape is not None and tuple(shape) == tuple(grid_shape):
            return ("z", "y", "x")
        if name == "rho_p_species" and len(shape) == 4:
            return ("species", "z", "y", "x")
        if grid_shape is not None and len(shape) == 4 and tuple(shape[1:]) == tuple(grid_shape):
            return (f"{name}_component", "z", "y", "x")
    if name.startswith("particles/"):
        if len(shape) == 2 and shape[0] == 3:
            return ("component", "particle")
        if len(shape) == 1:
            return ("particle",)
    if layout == "sph":
        if len(shape) == 2 and shape[1] == 3:
            return ("particle", "component")
        if len(shape) == 1:
            return ("particle",)
    return tuple(f"dim_{i}" for i in range(len(shape)))


def root_attributes(layout: str) -> dict[str, Any]:
    """Root attributes the annotators add (layout, schema version, the meaning of code units)."""
    return {
        "layout": layout,
        "schema_version": SCHEMA_VERSION,
        "units_system": "code units: see the problem's documentation (shearing box: c_s = Omega = H = 1, "
                        "rho_g0 = 1; global disks: au, M_sun, yr/2pi); cgs factors in "
                        "length_unit_cgs, mass_unit_cgs, time_unit_cgs where the run defines them",
    }


def annotate_snapshot(f: Any) -> None:
    """Write units, descriptions, dimension labels and scales into an open snapshot file ``f``
    (an ``h5py.File`` in write mode holding the snapshot's datasets).

    Each dataset is looked up once: an h5py lookup by name costs tens of microseconds, and looking
    each one up again per attribute made the annotation most of a snapshot's write."""
    datasets: dict[str, Any] = {}
    f.visititems(lambda name, obj: datasets.__setitem__(name, obj) if hasattr(obj, "shape") else None)
    layout = layout_of(datasets)
    grid_shape = tuple(datasets["rho"].shape) if layout.startswith("grid") else None
    for key, value in root_attributes(layout).items():
        f.attrs[key] = value
    if grid_shape is not None:
        for axis in ("x", "y", "z"):
            datasets[axis].make_scale(axis)
    for name, ds in datasets.items():
        q = snapshot_quantity(name)
        ds.attrs["units"] = q.units
        ds.attrs["long_name"] = q.description
        dims = snapshot_dims(name, ds.shape, layout, grid_shape)
        for i, dim in enumerate(dims):
            axis = ds.dims[i]
            axis.label = dim
            if grid_shape is not None and dim in ("x", "y", "z") and name not in ("x", "y", "z"):
                axis.attach_scale(datasets[dim])


def annotate_history(f: Any) -> None:
    """Units, descriptions and the ``time`` dimension scale in an open ``history.h5`` ``f``
    (each column looked up once, as in :func:`annotate_snapshot`)."""
    f.attrs["layout"] = "history"
    f.attrs["schema_version"] = SCHEMA_VERSION
    columns = {name: obj for name, obj in f.items() if hasattr(obj, "shape")}
    time = columns.get("time")
    if time is not None:
        time.make_scale("time")
    for name, ds in columns.items():
        q = history_quantity(name)
        ds.attrs["units"] = q.units
        ds.attrs["long_name"] = q.description
        if ds.ndim == 1:
            axis = ds.dims[0]
            axis.label = "time"
            if time is not None and name != "time" and ds.shape == time.shape:
                axis.attach_scale(time)


def numeric_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    """``attrs`` with numpy scalars turned into Python numbers (for JSON and xarray attributes)."""
    out: dict[str, Any] = {}
    for k, v in attrs.items():
        if isinstance(v, np.generic):
            v = v.item()
        elif isinstance(v, np.ndarray):
            v = v.tolist()
        out[k] = v
    return out
