"""Images of one snapshot: slices and projections of grid fields, kernel-smoothed SPH fields.

Grid runs
    A *slice* is the plane of a 2D run, or the plane through the cell nearest ``at`` (default the
    box centre) normal to ``axis`` in 3D; a *projection* integrates the field along ``axis``
    (:math:`\\int f\\,dl`, so density becomes surface density, with units times ``code_length``).
    1D runs are drawn as a line. ``field="particles"`` draws the Lagrangian particles' positions
    in the plane (projected along ``axis``).
SPH runs
    The field is interpolated with the run's kernel (thesis eq. 3.1; Price 2007, *SPLASH*):
    :math:`A(\\mathbf x) = \\sum_b (m_b/\\rho_b) A_b W(|\\mathbf x-\\mathbf x_b|, h_b)` on the pixels
    of the plane of a 2D run or a cross-section of a 3D run (:func:`dustygas.sph.render.render_plane`);
    a 3D *projection* integrates it along the line of sight with the column-integrated kernel
    (:func:`dustygas.sph.render.render_column`). 1D runs are drawn particle by particle.

Every function returns a :class:`matplotlib.figure.Figure` (Agg, no pyplot) whose first axes
holds the image, with the axes and the colour bar labelled with the units of
:mod:`dustygas.io.schema`. Colour scales: ``viridis`` (``log`` optional) between ``vmin`` and
``vmax`` (default the data's range).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from ..io.schema import layout_of, snapshot_quantity
from .style import house_style, new_figure

__all__ = ["MapImage", "grid_image", "sph_image", "snapshot_figure", "image_figure", "units_label", "axis_label",
           "times_length"]

_AXES = "xyz"
CMAP = "viridis"


@dataclass
class MapImage:
    """A 2D image and what it shows: ``values[row, col]`` over ``extent`` (x0, x1, y0, y1)."""

    values: np.ndarray
    extent: tuple[float, float, float, float]
    axes: tuple[str, str]
    label: str
    units: str
    title: str


def units_label(units: str) -> str:
    """``code_mass/code_length**3`` -> mathtext ``code mass / code length³`` for axis labels."""
    if units in ("dimensionless", ""):
        return ""
    text = units.replace("**", "^").replace("*", r"\,")
    text = text.replace("code_length", r"\mathrm{code\ length}").replace("code_mass", r"\mathrm{code\ mass}")
    text = text.replace("code_time", r"\mathrm{code\ time}")
    import re

    text = re.sub(r"\^\((-?[0-9/]+)\)", r"^{\1}", text)
    text = re.sub(r"\^(-?[0-9]+)", r"^{\1}", text)
    return f"[${text}$]"


def times_length(units: str) -> str:
    """Units of the integral of a field of ``units`` along a line (``code_mass/code_length**3``
    -> ``code_mass/code_length**2``)."""
    import re

    if units in ("dimensionless", ""):
        return "code_length"
    m = re.fullmatch(r"(.*)/code_length\*\*(\d+)", units)
    if m and "/" not in m.group(1):
        n = int(m.group(2)) - 1
        return f"{m.group(1)}/code_length" + (f"**{n}" if n > 1 else "")
    if units == "code_length":
        return "code_length**2"
    return f"({units})*code_length"


def axis_label(name: str, units: str) -> str:
    """``name [units]`` for an axis or a colour bar."""
    return f"{name} {units_label(units)}".strip()


def _inactive(shape_zyx: tuple[int, ...]) -> list[int]:
    n = (shape_zyx[2], shape_zyx[1], shape_zyx[0])
    return [a for a in range(3) if n[a] == 1]


def grid_image(arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], field: str = "rho",
               kind: str = "slice", axis: str | None = None, at: float | None = None) -> MapImage:
    """The image a grid snapshot shows for ``field`` (see module docstring); 2D or 3D runs."""
    rho = np.asarray(arrays["rho"])
    inactive = _inactive(rho.shape)
    if len(inactive) >= 2:
        raise ValueError("a 1D run has no image (it is drawn as a line)")
    if axis is None:
        a_norm = inactive[0] if inactive else 2
    else:
        a_norm = _AXES.index(axis)
    if inactive and a_norm != inactive[0]:
        raise ValueError(f"the run is 2D: its plane is normal to {_AXES[inactive[0]]}")
    if field not in arrays or np.shape(arrays[field]) != rho.shape:
        choices = sorted(k for k, v in arrays.items() if np.shape(v) == rho.shape)
        raise ValueError(f"no grid field {field!r}; choose one of {', '.join(choices)}")
    values = np.asarray(arrays[field], dtype=np.float64)  # (z, y, x)
    plane = [a for a in range(3) if a != a_norm]  # image axes (horizontal, vertical)
    centres = [np.asarray(arrays[ax], dtype=np.float64) for ax in _AXES]
    q = snapshot_quantity(field)
    units, title = q.units, ""
    arr_axis = 2 - a_norm
    if kind == "slice" or inactive:
        c = centres[a_norm]
        index = int(np.argmin(np.abs(c - (0.5 * (c[0] + c[-1]) if at is None else at))))
        img = np.take(values, index, axis=arr_axis)
        if not inactive:
            title = f"{_AXES[a_norm]} = {c[index]:.4g}"
    elif kind == "projection":
        length = float(attrs.get(f"l{_AXES[a_norm]}", 1.0))
        img = values.sum(axis=arr_axis) * (length / values.shape[arr_axis])
        units = times_length(units)
        title = f"integrated along {_AXES[a_norm]}"
    else:
        raise ValueError(f"kind {kind!r}: choose slice or projection")
    # np.take / sum keep the other array axes in (z, y, x) order: rows = plane[1], columns = plane[0]
    img = np.asarray(img)
    ext = []
    for a in plane:
        c = centres[a]
        d = (c[-1] - c[0]) / (c.size - 1) if c.size > 1 else float(attrs.get(f"l{_AXES[a]}", 1.0))
        ext += [c[0] - 0.5 * d, c[-1] + 0.5 * d]
    return MapImage(img, tuple(ext), (_AXES[plane[0]], _AXES[plane[1]]), field, units, title)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------------------- SPH


def _sph_field(arrays: Mapping[str, np.ndarray], field: str) -> np.ndarray:
    if field in ("vx", "vy", "vz"):
        return np.asarray(arrays["vel"])[:, _AXES.index(field[1])]
    for key in (field, f"extra/{field}"):
        if key in arrays and np.ndim(arrays[key]) == 1:
            return np.asarray(arrays[key], dtype=np.float64)
    choices = ["vx", "vy", "vz"] + sorted(k.rsplit("/", 1)[-1] for k, v in arrays.items() if np.ndim(v) == 1)
    raise ValueError(f"no particle field {field!r}; choose one of {', '.join(choices)}")


def sph_image(arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], field: str = "rho",
              kind: str = "slice", axis: str = "z", at: float = 0.0, npix: int = 256,
              extent: tuple[float, float, float, float] | None = None) -> MapImage:
    """Kernel-smoothed image of an SPH field (2D plane; 3D slice at ``axis = at`` or projection)."""
    from ..sph.render import render_column, render_plane

    ndim = int(attrs["ndim"])
    if ndim == 1:
        raise ValueError("a 1D run has no image (it is drawn particle by particle)")
    a_norm = 2 if ndim == 2 else _AXES.index(axis)
    plane = tuple(a for a in range(3) if a != a_norm)
    pos = np.asarray(arrays["pos"], dtype=np.float64)
    gas = np.asarray(arrays.get("ptype", np.zeros(len(pos))))
    sel = gas == 0  # the gas (mixture) particles carry the fields
    pos, mass = pos[sel], np.asarray(arrays["mass"])[sel]
    rho, h = np.asarray(arrays["rho"])[sel], np.asarray(arrays["h"])[sel]
    values = _sph_field(arrays, field)[sel]
    if extent is None:
        lo, hi = np.asarray(attrs.get("box_lo", [-np.inf] * 3), float), np.asarray(attrs.get("box_hi", [np.inf] * 3), float)
        ext = []
        for a in plane:
            l_ = lo[a] if a < lo.size and np.isfinite(lo[a]) else pos[:, a].min()
            h_ = hi[a] if a < hi.size and np.isfinite(hi[a]) else pos[:, a].max()
            ext += [float(l_), float(h_)]
        extent = tuple(ext)  # type: ignore[assignment]
    q = snapshot_quantity(field if field not in ("vx", "vy", "vz") else "vel")
    units, title = q.units, ""
    kernel = str(attrs["kernel"])
    if ndim == 2 or kind == "slice":
        img = render_plane(pos, mass, rho, h, values, kernel, ndim, extent, npix, axes=plane, z0=at)  # type: ignore[arg-type]
        if ndim == 3:
            title = f"{_AXES[a_norm]} = {at:.4g}"
    elif kind == "projection":
        img = render_column(pos, mass, rho, h, values, kernel, extent, npix, axes=plane)  # type: ignore[arg-type]
        units = times_length(units)
        title = f"integrated along {_AXES[a_norm]}"
    else:
        raise ValueError(f"kind {kind!r}: choose slice or projection")
    return MapImage(img, extent, (_AXES[plane[0]], _AXES[plane[1]]), field, units, title)  # type: ignore[arg-type]


# ---------------------------------------------------------------------------------------- figures


def _line_figure(x: np.ndarray, y: np.ndarray, field: str, units: str, t: float, style: str) -> Any:
    fig, ax = new_figure(width=5.2, height=3.6)
    ax.plot(x, y, style, ms=2)
    ax.set_xlabel(axis_label("x", "code_length"))
    ax.set_ylabel(axis_label(field, units))
    ax.set_title(f"t = {t:.4g}", loc="left", fontsize=9)
    return fig


def image_figure(image: MapImage, t: float, log: bool = False, vmin: float | None = None,
                 vmax: float | None = None) -> Any:
    """The figure of ``image`` with labelled axes and colour bar (first axes: the image)."""
    import matplotlib.colors as mcolors

    shown = image.values
    norm = (mcolors.LogNorm(vmin=vmin, vmax=vmax) if log else mcolors.Normalize(vmin=vmin, vmax=vmax))
    x0, x1, y0, y1 = image.extent
    aspect = (y1 - y0) / (x1 - x0) if x1 > x0 else 1.0
    fig, ax = new_figure(width=5.6, height=max(2.5, min(8.0, 4.4 * aspect + 0.8)))
    im = ax.imshow(shown, origin="lower", extent=image.extent, cmap=CMAP, norm=norm, aspect="equal",
                   interpolation="nearest")
    ax.grid(False)
    fig.colorbar(im, ax=ax, label=axis_label(image.label, image.units))
    ax.set_xlabel(axis_label(image.axes[0], "code_length"))
    ax.set_ylabel(axis_label(image.axes[1], "code_length"))
    ax.set_title(f"t = {t:.4g}" + (f", {image.title}" if image.title else ""), loc="left", fontsize=9)
    return fig


def snapshot_figure(arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], field: str = "rho",
                    kind: str = "slice", axis: str | None = None, at: float | None = None, log: bool = False,
                    vmin: float | None = None, vmax: float | None = None, npix: int = 256) -> Any:
    """The figure of one snapshot of any engine (module docstring)."""
    t = float(attrs.get("time", 0.0))
    layout = layout_of(arrays)
    with house_style():
        if layout.startswith("grid"):
            rho = np.asarray(arrays["rho"])
            inactive = _inactive(rho.shape)
            if field == "particles":
                return _particles_figure(arrays, attrs, axis, t)
            if len(inactive) >= 2:
                if field not in arrays:
                    raise ValueError(f"no grid field {field!r}")
                return _line_figure(np.asarray(arrays["x"]), np.asarray(arrays[field]).ravel(), field,
                                    snapshot_quantity(field).units, t, "-")
            return image_figure(grid_image(arrays, attrs, field, kind, axis, at), t, log, vmin, vmax)
        if layout == "sph":
            if int(attrs["ndim"]) == 1:
                return _line_figure(np.asarray(arrays["pos"])[:, 0], _sph_field(arrays, field), field,
                                    snapshot_quantity(field if field[0] != "v" else "vel").units, t, ".")
            image = sph_image(arrays, attrs, field, kind, axis or "z", 0.0 if at is None else at, npix)
            return image_figure(image, t, log, vmin, vmax)
    raise ValueError("not a dustygas snapshot")


def _particles_figure(arrays: Mapping[str, np.ndarray], attrs: Mapping[str, Any], axis: str | None, t: float) -> Any:
    if "particles/pos" not in arrays:
        raise ValueError("the snapshot holds no particles")
    pos = np.asarray(arrays["particles/pos"])
    inactive = _inactive(np.shape(arrays["rho"]))
    a_norm = inactive[0] if inactive else _AXES.index(axis or "z")
    plane = [a for a in range(3) if a != a_norm]
    fig, ax = new_figure(width=5.2, height=4.6)
    ax.plot(pos[plane[0]], pos[plane[1]], ",", color="k", alpha=0.6)
    for a, setter in zip(plane, (ax.set_xlim, ax.set_ylim)):
        c, length = np.asarray(arrays[_AXES[a]]), float(attrs.get(f"l{_AXES[a]}", 1.0))
        mid = 0.5 * (c[0] + c[-1])
        setter(mid - 0.5 * length, mid + 0.5 * length)
    ax.set_aspect("equal")
    ax.set_xlabel(axis_label(_AXES[plane[0]], "code_length"))
    ax.set_ylabel(axis_label(_AXES[plane[1]], "code_length"))
    ax.set_title(f"t = {t:.4g}, particles projected along {_AXES[a_norm]}", loc="left", fontsize=9)
    return fig
