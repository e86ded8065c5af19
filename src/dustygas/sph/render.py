"""SPH interpolation of particle fields onto grids (rendered maps).

A field :math:`A` carried by the particles is interpolated to a point :math:`\\mathbf x` with the
standard SPH estimate (Monaghan 1992; Price 2007, *SPLASH*)

.. math:: A(\\mathbf x) = \\sum_b \\frac{m_b}{\\rho_b} A_b\\, W(|\\mathbf x - \\mathbf x_b|, h_b),

evaluated on the pixels of a 2D map: the plane of a 2D simulation, or a cross-section
:math:`z = z_0` through a 3D one. With :math:`A = \\rho` this is the density estimate of thesis
eq. 3.1 evaluated off the particles ("scatter" form, each particle with its own :math:`h_b`).
:func:`render_column` integrates a 3D field along the line of sight instead, with the
column-integrated kernel :math:`\\int W\\,dz = (C_3/h^2)\\,F(R/h)`,
:math:`F(R) = \\int f(\\sqrt{R^2+s^2})\\,ds` (tabulated once per kernel; Price 2007).

Examples
--------
>>> import numpy as np
>>> pos = np.array([[0.0, 0.0, 0.0]]); one = np.ones(1)
>>> img = render_plane(pos, one, one, one, one, "cubic", 2, (-1, 1, -1, 1), 5)
>>> round(float(img[2, 2]), 6)  # W(0, h=1) in 2D = 10/(7 pi)
0.454728
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import get_kernel, kernel_shape

__all__ = ["render_plane", "render_column"]


@njit(cache=True, inline="always")
def _pixel_window(xb, yb, rs, x0, y0, dx, dy, nx, ny):
    """Pixel index ranges ``[i0, i1) x [j0, j1)`` that a kernel of radius ``rs`` at ``(xb, yb)`` touches."""
    i0 = max(int(math.floor((xb - rs - x0) / dx)), 0)
    i1 = min(int(math.floor((xb + rs - x0) / dx)) + 1, nx)
    j0 = max(int(math.floor((yb - rs - y0) / dy)), 0)
    j1 = min(int(math.floor((yb + rs - y0) / dy)) + 1, ny)
    return i0, i1, j0, j1


@njit(cache=True)
def _render(pos, weight, h, shape, norm, radius, ndim, x0, x1, y0, y1, z0, nx, ny, ax, ay, az, img):
    dx = (x1 - x0) / nx
    dy = (y1 - y0) / ny
    for b in range(pos.shape[0]):
        hb = h[b]
        rs = radius * hb
        dz2 = 0.0
        if ndim == 3:
            dz = pos[b, az] - z0
            dz2 = dz * dz
            if dz2 >= rs * rs:
                continue
        xb = pos[b, ax]
        yb = pos[b, ay]
        i0, i1, j0, j1 = _pixel_window(xb, yb, rs, x0, y0, dx, dy, nx, ny)
        c = weight[b] * norm / hb**ndim
        for i in range(i0, i1):
            px = x0 + (i + 0.5) * dx - xb
            for j in range(j0, j1):
                py = y0 + (j + 0.5) * dy - yb
                q = math.sqrt(px * px + py * py + dz2) / hb
                img[j, i] += c * kernel_shape(shape, q)[0]


def render_plane(pos: np.ndarray, mass: np.ndarray, rho: np.ndarray, h: np.ndarray, field: np.ndarray,
                 kernel: str, ndim: int, extent: tuple[float, float, float, float], npix: int,
                 axes: tuple[int, int] = (0, 1), z0: float = 0.0) -> np.ndarray:
    """Interpolate ``field`` onto an ``npix``-wide map (rows: second axis) over ``extent``
    ``(xmin, xmax, ymin, ymax)``; in 3D on the plane where the third axis equals ``z0``."""
    if ndim not in (2, 3):
        raise ValueError("maps need 2D or 3D data")
    k = get_kernel(kernel, ndim)
    x0, x1, y0, y1 = (float(v) for v in extent)
    ny = max(1, int(round(npix * (y1 - y0) / (x1 - x0))))
    img = np.zeros((ny, npix))
    az = 3 - axes[0] - axes[1]
    weight = np.ascontiguousarray(mass / rho * field, dtype=np.float64)
    _render(np.ascontiguousarray(pos, dtype=np.float64), weight, np.ascontiguousarray(h, dtype=np.float64),
            k.shape, k.norm, k.radius, ndim, x0, x1, y0, y1, float(z0), npix, ny, axes[0], axes[1], az, img)
    return img


def column_table(kernel: str, n: int = 512) -> tuple[np.ndarray, float, float]:
    """``F(R) = ∫ f(sqrt(R² + s²)) ds`` of the 3D ``kernel`` on ``n`` points of ``[0, radius]``,
    the radius and :math:`C_3` (so that the column of ``W(r, h)`` is ``C_3 F(R/h)/h²``)."""
    k = get_kernel(kernel, 3)
    R = np.linspace(0.0, k.radius, n)
    s = np.linspace(0.0, k.radius, 2001)
    table = np.empty(n)
    for i, r in enumerate(R):
        q = np.sqrt(r * r + s * s)
        f = np.array([kernel_shape(k.shape, float(v))[0] for v in q])
        table[i] = 2.0 * np.trapezoid(f, s)
    return table, k.radius, k.norm


@njit(cache=True)
def _column(pos, weight, h, table, radius, norm, x0, x1, y0, y1, nx, ny, ax, ay, img):
    dx = (x1 - x0) / nx
    dy = (y1 - y0) / ny
    nt = table.size - 1
    for b in range(pos.shape[0]):
        hb = h[b]
        xb = pos[b, ax]
        yb = pos[b, ay]
        i0, i1, j0, j1 = _pixel_window(xb, yb, radius * hb, x0, y0, dx, dy, nx, ny)
        c = weight[b] * norm / (hb * hb)
        for i in range(i0, i1):
            px = x0 + (i + 0.5) * dx - xb
            for j in range(j0, j1):
                py = y0 + (j + 0.5) * dy - yb
                u = math.sqrt(px * px + py * py) / hb / radius * nt
                if u < nt:
                    k = int(u)
                    w = u - k
                    img[j, i] += c * ((1.0 - w) * table[k] + w * table[k + 1])


def render_column(pos: np.ndarray, mass: np.ndarray, rho: np.ndarray, h: np.ndarray, field: np.ndarray,
                  kernel: str, extent: tuple[float, float, float, float], npix: int,
                  axes: tuple[int, int] = (0, 1)) -> np.ndarray:
    """Line-of-sight integral of ``field`` of a 3D snapshot along the axis not in ``axes``, on an
    ``npix``-wide map over ``extent`` (rows: second axis)."""
    table, radius, norm = column_table(kernel)
    x0, x1, y0, y1 = (float(v) for v in extent)
    ny = max(1, int(round(npix * (y1 - y0) / (x1 - x0))))
    img = np.zeros((ny, npix))
    weight = np.ascontiguousarray(mass / rho * field, dtype=np.float64)
    _column(np.ascontiguousarray(pos, dtype=np.float64), weight, np.ascontiguousarray(h, dtype=np.float64), table,
            radius, norm, x0, x1, y0, y1, npix, ny, axes[0], axes[1], img)
    return img
