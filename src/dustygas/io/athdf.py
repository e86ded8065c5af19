"""Grid snapshots in Athena++'s ``.athdf`` layout, with the XDMF sidecar ParaView and VisIt read.

yt opens these files with its built-in ``athena_pp`` frontend (``yt.load("snap_00000.athdf")``;
no plugin), and ParaView/VisIt open the ``.athdf.xdmf`` file next to it. The layout is Athena++'s
(Stone et al. 2020, ApJS 249, 4; ``outputs/athena_hdf5.cpp``): one uniform mesh block holding the
whole domain,

* root attributes ``Coordinates`` (``cartesian``), ``RootGridX1..3`` (``[min, max, ratio]``),
  ``RootGridSize``, ``MeshBlockSize``, ``NumMeshBlocks``, ``MaxLevel``, ``Time``, ``NumCycles``,
  ``DatasetNames``, ``NumVariables``, ``VariableNames``;
* datasets ``x1f, x2f, x3f`` (cell faces) and ``x1v, x2v, x3v`` (centres), each ``(1, n+1)`` or
  ``(1, n)``, ``Levels`` and ``LogicalLocations``, and ``prim`` of shape
  ``(nvar, 1, nx3, nx2, nx1)`` with ``rho``, ``vel1..3`` and every other cell field of the
  snapshot (``rho_p``, ...) in float64.

Athena++ (and yt) take the first active axes as ``x1, x2``: a radial-vertical (x-z) box, whose
``y`` has one cell, is written with ``x1 = x``, ``x2 = z``, ``x3 = y`` (``vel2`` is then
``v_z``). The attribute ``dustygas_axes`` names the dustygas axis of ``x1, x2, x3`` and the
snapshot's own attributes (``config``, ``dustygas_version``, ``problem``, ...) are copied to the
root, with ``units`` and ``long_name`` of every variable in ``VariableUnits`` and
``VariableDescriptions``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Mapping

import h5py
import numpy as np

from .atomic import atomic_path, atomic_write_text
from .schema import snapshot_quantity

__all__ = ["write_athdf", "write_xdmf", "athdf_axes"]

_VELOCITY = {"vx": 0, "vy": 1, "vz": 2}


def athdf_axes(shape_zyx: tuple[int, int, int]) -> tuple[int, int, int]:
    """dustygas axes (0 = x, 1 = y, 2 = z) written as Athena++'s ``x1, x2, x3``: active ones first."""
    n = (shape_zyx[2], shape_zyx[1], shape_zyx[0])
    active = [a for a in range(3) if n[a] > 1]
    return tuple(active + [a for a in range(3) if n[a] == 1])  # type: ignore[return-value]


def _faces(centres: np.ndarray, length: float, n: int) -> np.ndarray:
    if n == 1:
        c = float(centres[0])
        return np.array([c - 0.5 * length, c + 0.5 * length])
    d = (centres[-1] - centres[0]) / (n - 1)
    return np.concatenate([centres - 0.5 * d, [centres[-1] + 0.5 * d]])


def _attr(value: Any) -> Any:
    if isinstance(value, str):
        return value.encode()
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, str) for v in value):
        return np.array([v.encode() for v in value])
    if isinstance(value, (list, tuple)):
        return np.asarray(value)
    return value


def write_athdf(path: str | Path, arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any]) -> Path:
    """Write the grid fields of one snapshot (``read_h5`` output) as an Athena++ ``.athdf`` file."""
    path = Path(path)
    rho = np.asarray(arrays["rho"])
    if rho.ndim != 3:
        raise ValueError("athdf export needs a grid snapshot with rho(z, y, x)")
    order = athdf_axes(rho.shape)
    perm = tuple(2 - a for a in reversed(order))  # array axes (z, y, x) -> (x3, x2, x1)
    n_xyz = (rho.shape[2], rho.shape[1], rho.shape[0])
    lengths = [float(attrs.get(f"l{ax}", 1.0)) for ax in "xyz"]
    faces = [_faces(np.asarray(arrays[ax]), lengths[a], n_xyz[a]) for a, ax in enumerate("xyz")]
    centres = [np.asarray(arrays[ax], dtype=np.float64) for ax in "xyz"]

    names, fields = [], []
    velocity: list[tuple[int, np.ndarray]] = []
    for name, value in arrays.items():
        if name in _VELOCITY and np.shape(value) == rho.shape:
            velocity.append((_VELOCITY[name], np.asarray(value)))
    velocity.sort(key=lambda item: order.index(item[0]))
    names.append("rho")
    fields.append(rho)
    for axis, value in velocity:
        names.append(f"vel{order.index(axis) + 1}")
        fields.append(value)
    for name, value in arrays.items():
        if name not in ("rho", *_VELOCITY) and np.shape(value) == rho.shape:
            names.append(name)
            fields.append(np.asarray(value))
    prim = np.stack([np.transpose(f, perm) for f in fields])[:, None].astype(np.float64)
    size = [n_xyz[a] for a in order]
    schema_names = {f"vel{i + 1}": name for i, name in enumerate(("v" + "xyz"[a] for a in order))}

    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            for key, value in attrs.items():
                if key.startswith(("DIMENSION", "CLASS", "NAME", "REFERENCE")):
                    continue
                f.attrs[key] = _attr(value)
            f.attrs["Coordinates"] = np.bytes_("cartesian")
            for i, a in enumerate(order):
                f.attrs[f"RootGridX{i + 1}"] = np.array([faces[a][0], faces[a][-1], 1.0])
            f.attrs["RootGridSize"] = np.array(size, dtype=np.int32)
            f.attrs["MeshBlockSize"] = np.array(size, dtype=np.int32)
            f.attrs["NumMeshBlocks"] = np.int32(1)
            f.attrs["MaxLevel"] = np.int32(0)
            f.attrs["Time"] = float(attrs.get("time", 0.0))
            f.attrs["NumCycles"] = np.int32(attrs.get("cycle", 0))
            f.attrs["DatasetNames"] = np.array([b"prim"])
            f.attrs["NumVariables"] = np.array([len(names)], dtype=np.int32)
            f.attrs["VariableNames"] = np.array([n.encode() for n in names])
            f.attrs["VariableUnits"] = np.array(
                [snapshot_quantity(schema_names.get(n, n)).units.encode() for n in names])
            f.attrs["VariableDescriptions"] = np.array(
                [snapshot_quantity(schema_names.get(n, n)).description.encode() for n in names])
            f.attrs["dustygas_axes"] = np.array(["xyz"[a].encode() for a in order])
            for i, a in enumerate(order):
                f.create_dataset(f"x{i + 1}f", data=faces[a][None, :])
                f.create_dataset(f"x{i + 1}v", data=centres[a][None, :])
                f[f"x{i + 1}f"].attrs["units"] = "code_length"
                f[f"x{i + 1}v"].attrs["units"] = "code_length"
            f.create_dataset("Levels", data=np.zeros(1, dtype=np.int32))
            f.create_dataset("LogicalLocations", data=np.zeros((1, 3), dtype=np.int64))
            f.create_dataset("prim", data=prim)
    return path


_XDMF = """<?xml version="1.0" ?>
<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>
<Xdmf Version="2.0">
<!-- written by dustygas {version}: {problem}, time {time!r}; axes x1 x2 x3 = dustygas {axes} -->
<Domain>
<Grid Name="MeshBlock0" GridType="Uniform">
 <Time Value="{time!r}"/>
 <Topology TopologyType="3DRectMesh" NumberOfElements="{n3p} {n2p} {n1p}"/>
 <Geometry GeometryType="VXVYVZ">
  <DataItem ItemType="HyperSlab" Dimensions="{n1p}">
   <DataItem Dimensions="3 2" NumberType="Int"> 0 0 1 1 1 {n1p} </DataItem>
   <DataItem Dimensions="1 {n1p}" Format="HDF" Precision="8"> {name}:/x1f </DataItem>
  </DataItem>
  <DataItem ItemType="HyperSlab" Dimensions="{n2p}">
   <DataItem Dimensions="3 2" NumberType="Int"> 0 0 1 1 1 {n2p} </DataItem>
   <DataItem Dimensions="1 {n2p}" Format="HDF" Precision="8"> {name}:/x2f </DataItem>
  </DataItem>
  <DataItem ItemType="HyperSlab" Dimensions="{n3p}">
   <DataItem Dimensions="3 2" NumberType="Int"> 0 0 1 1 1 {n3p} </DataItem>
   <DataItem Dimensions="1 {n3p}" Format="HDF" Precision="8"> {name}:/x3f </DataItem>
  </DataItem>
 </Geometry>
{attributes}</Grid>
</Domain>
</Xdmf>
"""

_XDMF_ATTRIBUTE = """ <Attribute Name="{var}" Center="Cell">
  <DataItem ItemType="HyperSlab" Dimensions="{n3} {n2} {n1}">
   <DataItem Dimensions="3 5" NumberType="Int"> {index} 0 0 0 0 1 1 1 1 1 1 1 {n3} {n2} {n1} </DataItem>
   <DataItem Dimensions="{nvar} 1 {n3} {n2} {n1}" Format="HDF" Precision="8"> {name}:/prim </DataItem>
  </DataItem>
 </Attribute>
"""


def write_xdmf(athdf: str | Path) -> Path:
    """Write ``<athdf>.xdmf`` describing the mesh and every variable of ``athdf`` (XDMF 2)."""
    athdf = Path(athdf)
    with h5py.File(athdf, "r") as f:
        n1, n2, n3 = (int(v) for v in f.attrs["RootGridSize"])
        names = [v.decode() for v in f.attrs["VariableNames"]]
        time = float(f.attrs["Time"])
        version = f.attrs.get("dustygas_version", "")
        problem = f.attrs.get("problem", "")
        axes = " ".join(v.decode() for v in f.attrs["dustygas_axes"])
    version = version.decode() if isinstance(version, bytes) else version
    problem = problem.decode() if isinstance(problem, bytes) else problem
    attributes = "".join(
        _XDMF_ATTRIBUTE.format(var=var, index=i, n1=n1, n2=n2, n3=n3, nvar=len(names), name=athdf.name)
        for i, var in enumerate(names))
    text = _XDMF.format(version=version, problem=problem, time=time, axes=axes, n1p=n1 + 1, n2p=n2 + 1,
                        n3p=n3 + 1, name=athdf.name, attributes=attributes)
    out = athdf.with_name(athdf.name + ".xdmf")
    atomic_write_text(out, text)
    return out
