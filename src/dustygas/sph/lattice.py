"""Initial particle arrangements: lattices, and density profiles by mass-coordinate mapping.

Equal-mass particles represent a density profile :math:`\\rho(x)` along one axis when their
cumulative mass :math:`M(x) = \\int_{x_0}^{x}\\rho\\,dx'` takes equally spaced values. For the
sine profile of a linear wave, :math:`\\rho = \\rho_0[1 + A\\sin(kx)]`,
:math:`M(x) = \\rho_0[x - x_0 - (A/k)(\\cos kx - \\cos kx_0)]`, and each lattice coordinate is
moved to the root of :math:`M(x) = M_{\\rm lattice}` by Newton's method (exact to round-off,
unlike the linear displacement :math:`\\xi = (A/k)\\cos kx`).

Examples
--------
>>> import numpy as np
>>> pos = cubic_lattice((4, 2), (0.0, 0.0), (1.0, 0.5))
>>> pos.shape, pos[:3, :2].tolist()
((8, 3), [[0.125, 0.125], [0.125, 0.375], [0.375, 0.125]])
"""

from __future__ import annotations

import numpy as np

__all__ = ["cubic_lattice", "close_packed_lattice", "sine_density_positions"]


def cubic_lattice(n: tuple[int, ...], lo: tuple[float, ...], hi: tuple[float, ...]) -> np.ndarray:
    """Cell-centred lattice of ``prod(n)`` points filling ``[lo, hi)``, as ``(N, 3)`` positions.

    ``len(n)`` is the number of dimensions; the last axis varies fastest.
    """
    axes = [lo[d] + (np.arange(n[d]) + 0.5) * (hi[d] - lo[d]) / n[d] for d in range(len(n))]
    grids = np.meshgrid(*axes, indexing="ij")
    pos = np.zeros((int(np.prod(n)), 3))
    for d, g in enumerate(grids):
        pos[:, d] = g.ravel()
    return pos


def close_packed_lattice(n: tuple[int, ...], spacing: float, lo: tuple[float, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Hexagonal (2D) or hexagonal-close-packed (3D, ABAB stacking) lattice of nearest-neighbour
    distance ``spacing``; ``n`` points per row, rows per layer and layers (rows and layers even
    so that the lattice is periodic). Returns ``(positions (N, 3), box upper corner)``.

    Rows are :math:`\\sqrt3/2` spacings apart and shifted by half a spacing every other row;
    layers are :math:`\\sqrt{2/3}` spacings apart and shifted by :math:`(1/2, \\sqrt3/6)` spacings
    every other layer. The number density is :math:`2/(\\sqrt3 a^2)` in 2D and :math:`\\sqrt2/a^3` in 3D.
    """
    ndim = len(n)
    if ndim == 1:
        return cubic_lattice(n, lo, (lo[0] + n[0] * spacing,)), np.array([lo[0] + n[0] * spacing])
    if any(k % 2 for k in n[1:]):
        raise ValueError("close-packed lattices need even numbers of rows and layers")
    a = spacing
    dy = a * np.sqrt(3.0) / 2.0
    dz = a * np.sqrt(2.0 / 3.0)
    i, j = np.meshgrid(np.arange(n[0]), np.arange(n[1]), indexing="ij")
    layer = []
    for kz in range(n[2] if ndim == 3 else 1):
        sx = 0.5 * a * (kz % 2)
        sy = dy / 3.0 * (kz % 2)
        x = (i + 0.25 + 0.5 * (j % 2)) * a + sx
        y = (j + 0.25) * dy + sy
        z = np.full(x.shape, (kz + 0.25) * dz)
        layer.append(np.stack([x.ravel(), y.ravel(), z.ravel()], 1))
    pos = np.concatenate(layer)
    hi = np.array([n[0] * a, n[1] * dy] + ([n[2] * dz] if ndim == 3 else []))
    pos[:, 0] %= hi[0]
    pos[:, 1] %= hi[1]
    for d in range(ndim):
        pos[:, d] += lo[d]
    if ndim == 2:
        pos[:, 2] = 0.0
    return pos, hi + np.asarray(lo[:ndim])


def sine_density_positions(x: np.ndarray, amplitude: float, k: float, x0: float) -> np.ndarray:
    """Map uniformly spaced coordinates ``x`` (origin ``x0``) to :math:`\\rho \\propto 1 + A\\sin(kx)`.

    Over whole wavelengths the mapping keeps the end points and the total mass fixed.
    """
    x = np.asarray(x, dtype=np.float64)
    target = x - x0  # cumulative mass of the uniform lattice, in units of rho_0
    y = x.copy()
    for _ in range(50):
        m = y - x0 - amplitude / k * (np.cos(k * y) - np.cos(k * x0))
        step = (m - target) / (1.0 + amplitude * np.sin(k * y))
        y -= step
        if np.max(np.abs(step)) < 1e-15 * max(1.0, float(np.max(np.abs(y)))):
            break
    return y
