"""SPH smoothing kernels: cubic M4, quintic M6, Wendland C2/C4, and the double-hump drag kernels.

A kernel is written :math:`W(r, h) = C_d\\, f(q) / h^d` with :math:`q = r/h`, a dimensionless
shape :math:`f` of compact support :math:`q < R` and a normalisation :math:`C_d` such that
:math:`\\int W\\, dV = 1` in :math:`d` = 1, 2 or 3 dimensions (thesis eq. 3.1 needs "a positive,
properly normalised, spherically symmetric and spatially localised" kernel). Then

.. math::

    \\nabla_a W(r_{ab}, h) = \\frac{C_d}{h^{d+1}} f'(q)\\, \\hat r_{ab}, \\qquad
    \\frac{\\partial W}{\\partial h} = -\\frac{C_d}{h^{d+1}} \\left[d\\, f(q) + q f'(q)\\right].

Shapes (Monaghan & Lattanzio 1985; Schoenberg 1946; Wendland 1995; Dehnen & Aly 2012; Price 2012,
Table 1 and eqs. 6-7), support radius :math:`R` in units of :math:`h`:

=============  ===  =====================================================================
cubic M4        2   :math:`1 - \\tfrac32 q^2 + \\tfrac34 q^3` (q<1), :math:`\\tfrac14 (2-q)^3` (q<2)
quintic M6      3   :math:`(3-q)^5 - 6(2-q)^5_+ + 15(1-q)^5_+`
Wendland C2     2   :math:`(1-q/2)^4 (1+2q)` in 2D/3D; :math:`(1-q/2)^3 (1+\\tfrac32 q)` in 1D
Wendland C4     2   :math:`(1-q/2)^6 (1+3q+\\tfrac{35}{12}q^2)` in 2D/3D; :math:`(1-q/2)^5 (1+\\tfrac52 q+2q^2)` in 1D
=============  ===  =====================================================================

The *double-hump* drag kernels of Laibe & Price (2012a, Sect. 3.2) are
:math:`D(r, h) = C^D_d\\, q^2 f(q) / h^d`, normalised so that :math:`\\int D\\, dV = 1`. Used in the
projected drag sums of thesis eq. 3.19 they satisfy :math:`d\\int \\hat r \\hat r\\, D\\, dV = I`,
which is why those sums carry the factor :math:`\\nu = d`.

In numba kernels a kernel is an integer *shape id* (``KernelSpec.shape``) passed to
:func:`kernel_shape` / :func:`kernel_dshape`; the branch on it is perfectly predictable, keeps
every loop cacheable and maps directly onto a GPU ``switch``.

Examples
--------
>>> k = get_kernel("cubic", 3)
>>> k.radius, round(k.norm * 3.141592653589793, 12), k.default_hfact
(2.0, 1.0, 1.2)
>>> round(float(k.w(0.0, 1.0)), 12)  # W(0, h=1) = 1/pi
0.318309886184
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

__all__ = [
    "CUBIC",
    "QUINTIC",
    "WENDLAND_C2",
    "WENDLAND_C4",
    "WENDLAND_C2_1D",
    "WENDLAND_C4_1D",
    "KERNEL_NAMES",
    "KernelSpec",
    "get_kernel",
    "kernel_shape",
    "kernel_dshape",
]

# shape ids used inside numba kernels
CUBIC = 0
QUINTIC = 1
WENDLAND_C2 = 2
WENDLAND_C4 = 3
WENDLAND_C2_1D = 4
WENDLAND_C4_1D = 5

KERNEL_NAMES = ("cubic", "quintic", "wendland-c2", "wendland-c4")

_PI = math.pi
# name -> (shape id for 2D/3D, shape id in 1D, support radius, default h_fact (Price et al. 2018, Phantom),
#          {d: C_d}, {d: C^D_d})
_TABLE = {
    "cubic": (CUBIC, CUBIC, 2.0, 1.2,
              {1: 2.0 / 3.0, 2: 10.0 / (7.0 * _PI), 3: 1.0 / _PI},
              {1: 2.0, 2: 70.0 / (31.0 * _PI), 3: 10.0 / (9.0 * _PI)}),
    "quintic": (QUINTIC, QUINTIC, 3.0, 1.0,
                {1: 1.0 / 120.0, 2: 7.0 / (478.0 * _PI), 3: 1.0 / (120.0 * _PI)},
                {1: 1.0 / 60.0, 2: 42.0 / (2771.0 * _PI), 3: 1.0 / (168.0 * _PI)}),
    "wendland-c2": (WENDLAND_C2, WENDLAND_C2_1D, 2.0, 1.3,
                    {1: 5.0 / 8.0, 2: 7.0 / (4.0 * _PI), 3: 21.0 / (16.0 * _PI)},
                    {1: 105.0 / 64.0, 2: 63.0 / (20.0 * _PI), 3: 105.0 / (64.0 * _PI)}),
    "wendland-c4": (WENDLAND_C4, WENDLAND_C4_1D, 2.0, 1.5,
                    {1: 3.0 / 4.0, 2: 9.0 / (4.0 * _PI), 3: 495.0 / (256.0 * _PI)},
                    {1: 45.0 / 16.0, 2: 297.0 / (56.0 * _PI), 3: 6435.0 / (2048.0 * _PI)}),
}


@njit(cache=True)
def kernel_shape(shape: int, q: float) -> tuple[float, float]:
    """Dimensionless shape :math:`f(q)` and its derivative :math:`f'(q)` (both zero for q >= R).

    Written with truncated powers :math:`(x)_+ = \\max(x, 0)`, e.g. M4 as
    :math:`\\tfrac14(2-q)_+^3 - (1-q)_+^3`, so that the evaluation has no data-dependent branch.
    """
    if shape == CUBIC:
        t2 = max(2.0 - q, 0.0)
        t1 = max(1.0 - q, 0.0)
        return 0.25 * t2 * t2 * t2 - t1 * t1 * t1, 3.0 * t1 * t1 - 0.75 * t2 * t2
    if shape == QUINTIC:
        t3 = max(3.0 - q, 0.0)
        t2 = max(2.0 - q, 0.0)
        t1 = max(1.0 - q, 0.0)
        t3_4 = t3 * t3 * t3 * t3
        t2_4 = t2 * t2 * t2 * t2
        t1_4 = t1 * t1 * t1 * t1
        return t3_4 * t3 - 6.0 * t2_4 * t2 + 15.0 * t1_4 * t1, -5.0 * t3_4 + 30.0 * t2_4 - 75.0 * t1_4
    t = max(1.0 - 0.5 * q, 0.0)
    if shape == WENDLAND_C2:
        t3 = t * t * t
        return t3 * t * (1.0 + 2.0 * q), -5.0 * q * t3
    if shape == WENDLAND_C4:
        t5 = t * t * t * t * t
        return t5 * t * (1.0 + 3.0 * q + 35.0 / 12.0 * q * q), -7.0 / 3.0 * q * (2.0 + 5.0 * q) * t5
    if shape == WENDLAND_C2_1D:
        t2 = t * t
        return t2 * t * (1.0 + 1.5 * q), -3.0 * q * t2
    if shape == WENDLAND_C4_1D:
        t4 = t * t * t * t
        return t4 * t * (1.0 + 2.5 * q + 2.0 * q * q), -3.5 * q * (1.0 + 2.0 * q) * t4
    return 0.0, 0.0


@njit(cache=True)
def kernel_dshape(shape: int, q: float) -> float:
    """Derivative :math:`f'(q)` alone (what force loops need)."""
    return kernel_shape(shape, q)[1]


@njit(cache=True)
def _eval_w(shape, norm, ndim, r, h, drag):
    out = np.empty(r.shape[0])
    for i in range(r.shape[0]):
        q = r[i] / h[i]
        f = kernel_shape(shape, q)[0]
        if drag:
            f *= q * q
        out[i] = norm * f / h[i] ** ndim
    return out


@njit(cache=True)
def _eval_dw(shape, norm, ndim, r, h):
    out = np.empty(r.shape[0])
    for i in range(r.shape[0]):
        out[i] = norm * kernel_shape(shape, r[i] / h[i])[1] / h[i] ** (ndim + 1)
    return out


@njit(cache=True)
def _eval_dwdh(shape, norm, ndim, r, h):
    out = np.empty(r.shape[0])
    for i in range(r.shape[0]):
        q = r[i] / h[i]
        f, df = kernel_shape(shape, q)
        out[i] = -norm * (ndim * f + q * df) / h[i] ** (ndim + 1)
    return out


@dataclass(frozen=True)
class KernelSpec:
    """A kernel in a given number of dimensions.

    Attributes
    ----------
    name
        One of :data:`KERNEL_NAMES`.
    ndim
        Number of spatial dimensions (1, 2 or 3).
    shape
        Integer shape id passed to the numba functions.
    radius
        Support radius :math:`R` in units of :math:`h`.
    norm, norm_drag
        :math:`C_d` of :math:`W` and :math:`C^D_d` of the double-hump kernel :math:`D`.
    default_hfact
        Usual :math:`h_{\\rm fact}` for this kernel (about 58 neighbours for M4 in 3D).
    """

    name: str
    ndim: int
    shape: int
    radius: float
    norm: float
    norm_drag: float
    default_hfact: float

    def _args(self, r, h):
        r, h = np.broadcast_arrays(np.asarray(r, dtype=np.float64), np.asarray(h, dtype=np.float64))
        return np.ascontiguousarray(r.ravel()), np.ascontiguousarray(h.ravel()), r.shape

    def w(self, r, h) -> np.ndarray:
        """:math:`W(r, h)`."""
        rr, hh, shape = self._args(r, h)
        return _eval_w(self.shape, self.norm, self.ndim, rr, hh, False).reshape(shape)

    def dw_dr(self, r, h) -> np.ndarray:
        """:math:`\\partial W/\\partial r = C_d f'(q)/h^{d+1}` (the gradient is this times :math:`\\hat r`)."""
        rr, hh, shape = self._args(r, h)
        return _eval_dw(self.shape, self.norm, self.ndim, rr, hh).reshape(shape)

    def dw_dh(self, r, h) -> np.ndarray:
        """:math:`\\partial W/\\partial h = -C_d [d f + q f']/h^{d+1}` (grad-h terms)."""
        rr, hh, shape = self._args(r, h)
        return _eval_dwdh(self.shape, self.norm, self.ndim, rr, hh).reshape(shape)

    def drag(self, r, h) -> np.ndarray:
        """Double-hump drag kernel :math:`D(r, h) = C^D_d q^2 f(q)/h^d` (Laibe & Price 2012a)."""
        rr, hh, shape = self._args(r, h)
        return _eval_w(self.shape, self.norm_drag, self.ndim, rr, hh, True).reshape(shape)

    def neighbours(self, hfact: float | None = None) -> float:
        """Mean neighbour number :math:`V_d (R h_{\\rm fact})^d` inside the support."""
        hf = self.default_hfact if hfact is None else hfact
        x = self.radius * hf
        return {1: 2.0 * x, 2: math.pi * x * x, 3: 4.0 / 3.0 * math.pi * x**3}[self.ndim]


def get_kernel(name: str, ndim: int) -> KernelSpec:
    """The kernel ``name`` (one of :data:`KERNEL_NAMES`) in ``ndim`` dimensions."""
    if name not in _TABLE:
        raise ValueError(f"unknown kernel {name!r}; choose one of {', '.join(KERNEL_NAMES)}")
    if ndim not in (1, 2, 3):
        raise ValueError(f"ndim must be 1, 2 or 3, not {ndim!r}")
    shape, shape1d, radius, hfact, norms, dnorms = _TABLE[name]
    return KernelSpec(name, ndim, shape1d if ndim == 1 else shape, radius, norms[ndim], dnorms[ndim], hfact)
