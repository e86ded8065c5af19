"""Kernels: normalisation integrals, gradients equal derivatives, compact support, drag kernels."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from dustygas.sph.kernels import KERNEL_NAMES, get_kernel

SURFACE = {1: 2.0, 2: 2.0 * math.pi, 3: 4.0 * math.pi}  # d-sphere surface at unit radius
ALL = [(name, d) for name in KERNEL_NAMES for d in (1, 2, 3)]


def _radial_integral(fn, kernel, h):
    d = kernel.ndim
    breaks = [h * q for q in (1.0, 2.0) if q < kernel.radius]
    val, _ = quad(lambda r: fn(r) * SURFACE[d] * r ** (d - 1), 0.0, kernel.radius * h, points=breaks,
                  epsabs=0, epsrel=1e-13, limit=200)
    return val


@pytest.mark.parametrize("name,ndim", ALL)
def test_kernel_normalised_to_one(name, ndim):
    """int W dV = 1 to 1e-10 (h = 0.7, an arbitrary smoothing length)."""
    k = get_kernel(name, ndim)
    assert _radial_integral(lambda r: float(k.w(r, 0.7)), k, 0.7) == pytest.approx(1.0, abs=1e-10)


@pytest.mark.parametrize("name,ndim", ALL)
def test_double_hump_drag_kernel_normalised(name, ndim):
    """Laibe & Price (2012a): int D dV = 1 (to 1e-10)."""
    k = get_kernel(name, ndim)
    h = 1.3
    assert _radial_integral(lambda r: float(k.drag(r, h)), k, h) == pytest.approx(1.0, abs=1e-10)
    # D vanishes at the centre and at the edge, positive between: a double hump in 1D
    q = np.linspace(0.05, k.radius - 0.05, 50)
    assert float(k.drag(0.0, h)) == 0.0 and np.all(k.drag(q * h, h) > 0)


@pytest.mark.parametrize("name", KERNEL_NAMES)
def test_projected_drag_kernel_gives_identity_2d(name):
    """nu int (x/r)^2 D dV = 1 and nu int (x y/r^2) D dV = 0 in 2D (the factor nu = d of thesis eq. 3.19),
    by midpoint quadrature on a Cartesian grid (independent of the radial formula), to 1e-6."""
    k = get_kernel(name, 2)
    h = 1.0
    n = 1200
    x = (np.arange(n) + 0.5) / n * 2 * k.radius - k.radius
    X, Y = np.meshgrid(x, x, indexing="ij")
    R = np.hypot(X, Y)
    D = k.drag(R, h) * (2 * k.radius / n) ** 2
    assert 2 * np.sum(D * X**2 / R**2) == pytest.approx(1.0, abs=1e-6)
    assert abs(2 * np.sum(D * X * Y / R**2)) < 1e-12


@pytest.mark.parametrize("name,ndim", ALL)
def test_gradient_is_the_radial_derivative(name, ndim):
    """dW/dr and dW/dh agree with centred finite differences to 1e-7 (relative to max |dW|)."""
    k = get_kernel(name, ndim)
    h = 0.9
    r = np.linspace(0.01, k.radius * h - 0.01, 97)
    eps = 1e-6
    fd_r = (k.w(r + eps, h) - k.w(r - eps, h)) / (2 * eps)
    assert np.max(np.abs(k.dw_dr(r, h) - fd_r)) < 1e-7 * np.max(np.abs(fd_r))
    fd_h = (k.w(r, h + eps) - k.w(r, h - eps)) / (2 * eps)
    assert np.max(np.abs(k.dw_dh(r, h) - fd_h)) < 1e-7 * np.max(np.abs(fd_h))


@pytest.mark.parametrize("name,ndim", ALL)
def test_compact_support(name, ndim):
    """W, dW/dr and dW/dh vanish exactly for q >= R; W > 0 and dW/dr < 0 inside."""
    k = get_kernel(name, ndim)
    h = 1.0
    outside = np.array([k.radius, k.radius + 1e-12, k.radius + 0.5, 10.0])
    for fn in (k.w, k.dw_dr, k.dw_dh):
        assert np.all(fn(outside, h) == 0.0)
    inside = np.linspace(0.01, k.radius - 1e-3, 200)
    assert np.all(k.w(inside, h) > 0) and np.all(k.dw_dr(inside, h) < 0)


def test_published_normalisations():
    """C_d against Price (2012) Table 1 / Dehnen & Aly (2012) and Phantom's drag constants."""
    pi = math.pi
    expect = {("cubic", 1): 2 / 3, ("cubic", 2): 10 / (7 * pi), ("cubic", 3): 1 / pi,
              ("quintic", 1): 1 / 120, ("quintic", 2): 7 / (478 * pi), ("quintic", 3): 1 / (120 * pi),
              ("wendland-c2", 3): 21 / (16 * pi), ("wendland-c4", 3): 495 / (256 * pi)}
    for (name, d), c in expect.items():
        assert get_kernel(name, d).norm == pytest.approx(c, rel=1e-15)
    assert get_kernel("cubic", 3).norm_drag == pytest.approx(10 / (9 * pi), rel=1e-15)
    assert get_kernel("quintic", 3).norm_drag == pytest.approx(1 / (168 * pi), rel=1e-15)
    assert get_kernel("cubic", 3).neighbours() == pytest.approx(57.9, abs=0.05)
