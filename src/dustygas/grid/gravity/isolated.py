"""Green's function of an isolated system (vacuum along every axis; Hockney & Eastwood 1981, §6-5).

The potential of a density that vanishes outside the box is the aperiodic convolution
``Φ_i = Σ_j G(x_i - x_j) ρ_j``. On a grid of twice the size (plus the ghost layers the
gradient needs), zero-padded, the circular convolution that the FFT computes equals it: each
pair separation appears once. :func:`cell_green` is the kernel: ``-G`` times the integral of
``1/|x_i - x'|`` over the source cell (the *integrated* Green's function), so the potential is
exact at cell centres for a density constant in each cell, and the self-cell term is finite.
"""

from __future__ import annotations

import numpy as np

__all__ = ["box_integral_inverse_distance", "cell_green", "isolated_green_transform"]


def _antiderivative(x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """``F`` with ``∂³F/∂x∂y∂z = 1/r`` (the potential of a homogeneous box; MacMillan 1930,
    *The Theory of the Potential*), at corners none of whose coordinates vanish."""
    r = np.sqrt(x * x + y * y + z * z)
    return (y * z * np.log(x + r) + x * z * np.log(y + r) + x * y * np.log(z + r)
            - 0.5 * x * x * np.arctan(y * z / (x * r)) - 0.5 * y * y * np.arctan(x * z / (y * r))
            - 0.5 * z * z * np.arctan(x * y / (z * r)))


def box_integral_inverse_distance(offset: tuple[np.ndarray, np.ndarray, np.ndarray],
                                  size: tuple[float, float, float]) -> np.ndarray:
    """``∫ dV' / |d - x'|`` over a box of ``size`` centred at ``x' = 0``, for offsets ``d``.

    The box integral is the alternating sum of :func:`_antiderivative` over its eight corners.
    By symmetry it depends on ``|d_x|, |d_y|, |d_z|``; corners then lie at ``|d| ± size/2``,
    which never vanish for offsets that are whole numbers of cells.

    >>> round(float(box_integral_inverse_distance((np.zeros(1),) * 3, (1.0, 1.0, 1.0))[0]), 10)
    2.380077364
    """
    out = 0.0
    for sx in (-1, 1):
        for sy in (-1, 1):
            for sz in (-1, 1):
                corner = [np.abs(d) + s * 0.5 * h for d, s, h in zip(offset, (sx, sy, sz), size)]
                out = out + sx * sy * sz * _antiderivative(*corner)
    return out


def cell_green(shape: tuple[int, int, int], dx: tuple[float, float, float], G: float) -> np.ndarray:
    """``-G ∫_cell dV'/|d - x'|`` on the circular grid ``shape = (Nz, Ny, Nx)``.

    Index ``m`` along an axis of ``N`` cells is the offset ``m`` for ``m < N/2`` and ``m - N``
    above (``numpy.fft.fftfreq`` times ``N``).
    """
    # the kernel depends on |m| only: evaluate one octant and index it
    index = [np.abs(np.fft.fftfreq(n, 1.0 / n)).astype(np.int64) for n in shape]
    octant = [np.arange(n // 2 + 1) * d for n, d in zip(shape, (dx[2], dx[1], dx[0]))]
    dz, dy, dxx = np.meshgrid(*octant, indexing="ij")
    kernel = -G * box_integral_inverse_distance((dxx, dy, dz), dx)
    return kernel[np.ix_(*index)]


def isolated_green_transform(shape: tuple[int, int, int], dx: tuple[float, float, float], G: float,
                             workers: int = 1) -> np.ndarray:
    """Real FFT of :func:`cell_green` on the doubled grid ``shape`` (computed once per solver)."""
    from scipy import fft

    return fft.rfftn(cell_green(shape, dx, G), workers=workers)
