"""The FFT Poisson solver of :mod:`dustygas.grid.gravity` (see the package docstring for the method).

:class:`PoissonSolver` holds the wavenumber tables of one block; :meth:`~PoissonSolver.potential`
and :meth:`~PoissonSolver.acceleration` are functions of a density array and the shear offset.
:func:`potential` and :func:`acceleration` build a solver and call it once.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ...errors import SetupError
from .isolated import isolated_green_transform
from .kernels import apply_periodic_green, apply_sheet_green, gradient, multiply_phase, vacuum_columns

__all__ = ["GRAVITY_BOUNDARIES", "PoissonSolver", "potential", "acceleration"]

#: boundary conditions of the potential along an axis
GRAVITY_BOUNDARIES = ("periodic", "shear-periodic", "vacuum")


def _reduced(theta: np.ndarray) -> np.ndarray:
    """Phase advance per cell reduced to ``(-π, π)``; NaN where it is ``±π`` (a Nyquist mode, whose
    wavenumber has no sign and which is dropped so that the set of modes is symmetric)."""
    red = theta - 2.0 * np.pi * np.round(theta / (2.0 * np.pi))
    return np.where(np.abs(red) >= np.pi * (1.0 - 1e-12), np.nan, red)


class PoissonSolver:
    """``∇²Φ = 4πG ρ`` on one block by FFT, and ``-∇Φ`` by centred differences.

    Parameters
    ----------
    shape
        Cells ``(nx, ny, nz)``; 1 marks an inactive axis (along which the field is uniform,
        except that an inactive z with vacuum boundaries is a razor-thin sheet: the density
        array is then the surface density ``Σ`` and the potential is the one in its plane).
    box
        Box lengths ``(Lx, Ly, Lz)`` (inactive axes: ignored).
    four_pi_G
        ``4πG`` in the units of ``rho`` and ``box`` (in shearing-box code units, ``G̃``).
    boundaries
        Per axis, one of :data:`GRAVITY_BOUNDARIES`: x periodic or shear-periodic, y periodic,
        z periodic or vacuum; or vacuum along all three (an isolated system, 3D only).
    order
        Order of the centred differences of :meth:`acceleration`, 2 or 4.
    workers
        Threads of the FFTs (default: numba's thread count at the call). The result does not
        depend on it: every one-dimensional transform is computed by one thread.

    Examples
    --------
    A density wave ``cos(kx)`` has the potential ``-4πG cos(kx) / k²``:

    >>> solver = PoissonSolver((32, 1, 1), (2 * np.pi, 1.0, 1.0), four_pi_G=1.0)
    >>> x = (np.arange(32) + 0.5) * 2 * np.pi / 32
    >>> phi = solver.potential(np.cos(3 * x)[None, None, :])
    >>> bool(np.allclose(phi[0, 0], -np.cos(3 * x) / 9, rtol=0, atol=1e-15))
    True
    """

    def __init__(self, shape: tuple[int, int, int], box: tuple[float, float, float], four_pi_G: float,
                 boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic"), order: int = 2,
                 workers: int | None = None):
        shape = tuple(int(n) for n in shape)
        if len(shape) != 3 or min(shape) < 1 or max(shape) == 1:
            raise SetupError(f"gravity: mesh shape {shape} needs three cell counts >= 1, one of them > 1")
        if not (math.isfinite(four_pi_G) and four_pi_G > 0):
            raise SetupError(f"gravity: 4 pi G = {four_pi_G}: must be positive and finite (G~ = 4 pi G rho_g0 / Omega^2 > 0)")
        if order not in (2, 4):
            raise SetupError(f"gravity: difference order {order}: choose 2 or 4")
        boundaries = tuple(boundaries)
        if len(boundaries) != 3 or any(b not in GRAVITY_BOUNDARIES for b in boundaries):
            raise SetupError(f"gravity: boundaries {boundaries}: each of x, y, z must be one of "
                             f"{', '.join(GRAVITY_BOUNDARIES)}")
        if "shear-periodic" in boundaries[1:]:
            raise SetupError("gravity: only the radial (x) axis can be shear-periodic")
        nx, ny, nz = shape
        self.isolated = boundaries == ("vacuum",) * 3
        if self.isolated and min(shape) == 1:
            raise SetupError("gravity: an isolated (all-vacuum) system needs three active axes")
        if not self.isolated and "vacuum" in boundaries[:2]:
            raise SetupError(f"gravity: boundaries {boundaries}: vacuum is supported along z, or along all "
                             "three axes (an isolated system); x and y must otherwise be (shear-)periodic")
        size = tuple(float(s) if n > 1 else 1.0 for s, n in zip(box, shape))
        if not all(math.isfinite(s) and s > 0 for s in size):
            raise SetupError(f"gravity: box {box}: lengths must be positive and finite")
        self.shape, self.box, self.boundaries = shape, size, boundaries
        self.four_pi_G = float(four_pi_G)
        self.order = int(order)
        self.workers = workers
        self.dx = tuple(s / n for s, n in zip(size, shape))
        self.ghosts = tuple(order // 2 if n > 1 else 0 for n in shape)
        self.shear = boundaries[0] == "shear-periodic" and nx > 1 and ny > 1
        self.vacuum_z = boundaries[2] == "vacuum" and not self.isolated
        self.thin = self.vacuum_z and nz == 1
        self._tables()

    # ------------------------------------------------------------------ set-up
    def _tables(self) -> None:
        (nx, ny, nz), ly, (dx, _, dz) = self.shape, self.box[1], self.dx
        gx, gy, gz = self.ghosts
        if self.isolated:
            self._doubled = tuple(2 * (n + g) for n, g in zip((nz, ny, nx), (gz, gy, gx)))
            self._green = isolated_green_transform(self._doubled, self.dx, self.four_pi_G / (4.0 * np.pi))
            self._no_columns = (np.zeros((1, 1, 0)), np.zeros((1, 1, 0)))
            return
        if ny > 1:
            self._my = (ny + 1) // 2  # the Nyquist mode of an even ny is dropped
            self._ky = 2.0 * np.pi * np.arange(self._my) / ly
            # phase advance per cell of the x transform's modes (before the shear)
            self._theta_x = 2.0 * np.pi * np.fft.fftfreq(nx) if nx > 1 else np.zeros(1)
        else:
            self._my = 1
            self._ky = np.zeros(1)
            self._theta_x = 2.0 * np.pi * np.arange((nx + 1) // 2) / nx if nx > 1 else np.zeros(1)
        self._kx0 = np.ascontiguousarray(_reduced(np.broadcast_to(self._theta_x, (self._my, self._theta_x.size))) / dx)
        if nz > 1 and not self.vacuum_z:
            kz = 2.0 * np.pi * np.fft.fftfreq(nz)
            self._kz = _reduced(kz) / dz
        else:
            self._kz = np.zeros(1)
        self._unit_phase = np.ones((self._my, nx), dtype=np.complex128)
        self._no_columns = (np.zeros((1, 1, 0)), np.zeros((1, 1, 0)))

    def _kx(self, shift: float) -> np.ndarray:
        """Radial wavenumbers ``(my, mx)`` of the sheared-frame modes at shear offset ``shift``."""
        if not self.shear or shift == 0.0:
            return self._kx0
        theta = self._theta_x[None, :] + (self._ky * shift * self.dx[0] / self.box[0])[:, None]
        return np.ascontiguousarray(_reduced(theta) / self.dx[0])

    def _workers(self) -> int:
        return self.workers if self.workers is not None else numba.get_num_threads()

    # ------------------------------------------------------------------ solve
    def _check(self, rho: np.ndarray) -> np.ndarray:
        nx, ny, nz = self.shape
        rho = np.asarray(rho, dtype=np.float64)
        if rho.shape != (nz, ny, nx):
            raise ValueError(f"density has shape {rho.shape}, the solver's mesh {(nz, ny, nx)}")
        return rho

    def _solve(self, rho: np.ndarray, shear_offset: float, layers: tuple[int, int] | None = None) -> tuple:
        """``(phi, x_lo, x_hi, offsets, periodic)`` as :func:`~.kernels.gradient` reads them.

        ``phi`` ``(L, ny, nx)``: the potential at the cell centres, under vacuum z with ``gz``
        exterior layers below and above (the potential of the box's mass there; ``L = nz +
        2gz``); ``x_lo``, ``x_hi`` ``(L, ny, gx)``: the columns beyond the inner and outer radial
        faces, the sheared images ``Φ(x ± L_x, y) = Φ(x, y ± s)`` (exact: a shift of the same
        Fourier modes). Under vacuum z, ``layers = (k0, k1)`` restricts the work to the layers
        ``k0 .. k1-1``, which must hold all the mass: ``phi`` then covers ``k0 - gz .. k1 + gz - 1``.
        """
        from scipy import fft  # imported here: scipy.fft costs every process 0.3 s at start-up

        rho = self._check(rho)
        (nx, ny, nz), (gx, gy, gz) = self.shape, self.ghosts
        if layers is not None:
            rho = rho[layers[0]:layers[1]]
            nz = rho.shape[0]
        if self.isolated:
            return self._isolated(rho), *self._no_columns, (gx, gy, gz), (False, False, False)
        w = self._workers()
        shift = float(shear_offset) if self.shear else 0.0
        kx = self._kx(shift)
        my = self._my
        periodic_z = nz > 1 and not self.vacuum_z
        phase = self._phase(shift)
        # ---- forward: y (real), sheared-frame phase, then x (and a periodic z) in one call
        if ny > 1:
            a = np.empty((nz, my, nx), dtype=np.complex128)
            multiply_phase(fft.rfft(rho, axis=1, workers=w), phase, a)
            axes = tuple(ax for ax, on in ((0, periodic_z), (2, nx > 1)) if on)
            if axes:
                a = fft.fftn(a, axes=axes, workers=w, overwrite_x=True)
        elif nx > 1:
            a = fft.rfftn(rho, axes=(0, 2) if periodic_z else (2,), workers=w)[:, :, :kx.shape[1]]
            a = np.ascontiguousarray(a)
        else:
            a = fft.fft(rho, axis=0, workers=w) if periodic_z else rho.astype(np.complex128)
        # ---- the Green's function (and the vertical solve under vacuum)
        if periodic_z:
            apply_periodic_green(a, kx, self._ky, self._kz, self.four_pi_G)
        elif nz == 1:
            apply_sheet_green(a, kx, self._ky, self.four_pi_G, self.thin)
        else:
            out = np.empty((nz + 2 * gz,) + a.shape[1:], dtype=np.complex128)
            vacuum_columns(a, kx, self._ky, self.dx[2], self.four_pi_G, gz, out)
            a = out
        # ---- inverse: x (and z), phase, y
        layers = a.shape[0]
        if ny > 1:
            axes = tuple(ax for ax, on in ((0, periodic_z), (2, nx > 1)) if on)
            if axes:
                a = fft.ifftn(a, axes=axes, workers=w, overwrite_x=True)
            full = np.empty((layers, ny // 2 + 1, nx), dtype=np.complex128)
            multiply_phase(a, np.conj(phase), full)
            phi = fft.irfft(full, n=ny, axis=1, workers=w)
        elif nx > 1:
            if periodic_z:
                a = fft.ifft(a, axis=0, workers=w, overwrite_x=True)
            full = np.zeros((layers, 1, nx // 2 + 1), dtype=np.complex128)
            full[:, :, :a.shape[2]] = a
            phi = fft.irfft(full, n=nx, axis=2, workers=w)
        else:
            phi = np.ascontiguousarray((fft.ifft(a, axis=0, workers=w) if periodic_z else a).real)
        # ---- the sheared radial images of the first and last columns
        if nx > 1 and gx:
            x_lo, x_hi = phi[:, :, nx - gx:], phi[:, :, :gx]
            if shift != 0.0:
                x_lo, x_hi = (self._shift_y(c, sign * shift, w) for c, sign in ((x_lo, -1.0), (x_hi, 1.0)))
            else:
                x_lo, x_hi = np.ascontiguousarray(x_lo), np.ascontiguousarray(x_hi)
        else:
            x_lo, x_hi = self._no_columns
        return phi, x_lo, x_hi, (0, 0, gz if self.vacuum_z and nz > 1 else 0), (True, True, periodic_z)

    def _phase(self, shift: float) -> np.ndarray:
        """``exp(-i k_y s i Δx / L_x)`` ``(my, nx)``: the sheared-frame phase of mode ``j``, column ``i``."""
        nx = self.shape[0]
        if shift == 0.0:
            return self._unit_phase
        theta = self._ky * shift * self.dx[0] / self.box[0]
        return np.exp(-1j * theta[:, None] * np.arange(nx)[None, :])

    def _shift_y(self, columns: np.ndarray, shift: float, workers: int) -> np.ndarray:
        """``columns(y + shift)`` by the Fourier shift theorem (they hold no Nyquist mode)."""
        from scipy import fft  # imported here: scipy.fft costs every process 0.3 s at start-up

        ny = self.shape[1]
        c = fft.rfft(columns, axis=1, workers=workers)
        c[:, :self._my] *= np.exp(1j * self._ky * shift)[None, :, None]
        c[:, self._my:] = 0.0
        return fft.irfft(c, n=ny, axis=1, workers=workers)

    def _isolated(self, rho: np.ndarray) -> np.ndarray:
        from scipy import fft  # imported here: scipy.fft costs every process 0.3 s at start-up

        (nx, ny, nz), (gx, gy, gz) = self.shape, self.ghosts
        w = self._workers()
        pad = np.zeros(self._doubled)
        pad[:nz, :ny, :nx] = rho
        phi = fft.irfftn(fft.rfftn(pad, workers=w) * self._green, s=self._doubled, workers=w)
        phi = np.roll(phi, (gz, gy, gx), axis=(0, 1, 2))
        return np.ascontiguousarray(phi[:nz + 2 * gz, :ny + 2 * gy, :nx + 2 * gx])

    def potential(self, rho: np.ndarray, shear_offset: float = 0.0) -> np.ndarray:
        """Potential ``(nz, ny, nx)`` of the density ``rho`` ``(nz, ny, nx)`` at shear offset
        ``shear_offset`` (:meth:`~dustygas.grid.GridGeometry.shear_offset`: the outer radial
        image at ``(x + Lx, y)`` holds the box's content at ``(x, y + s)``)."""
        (nx, ny, nz) = self.shape
        phi, _, _, (ox, oy, oz), _ = self._solve(rho, shear_offset)
        return phi[oz:oz + nz, oy:oy + ny, ox:ox + nx].copy()

    def acceleration(self, rho: np.ndarray, shear_offset: float = 0.0, out: np.ndarray | None = None,
                     occupied_only: bool = False, layers: tuple[int, int] | None = None) -> np.ndarray:
        """Gravitational acceleration ``-∇Φ`` ``(3, nz, ny, nx)`` at the cell centres (0 along
        inactive axes), by centred differences of :attr:`order` of the potential.

        ``occupied_only`` (vacuum z): compute it only in the layers between the lowest and the
        highest that hold mass -- all a particle's assignment stencil reaches when ``rho`` is
        the particles' own deposit -- and set the other layers to NaN. A settled dust layer
        fills a fraction of the box's height, and the solve costs that fraction. ``layers =
        (k0, k1)`` (vacuum z) names those layers instead; they must hold all the mass.
        """
        nx, ny, nz = self.shape
        if out is None:
            out = np.empty((3, nz, ny, nx))
        active = tuple(n > 1 for n in self.shape)
        k0, k1 = 0, nz
        if (occupied_only or layers is not None) and self.vacuum_z and nz > 1:
            rho = self._check(rho)
            if layers is not None:
                k0, k1 = max(int(layers[0]), 0), min(int(layers[1]), nz)
            else:
                filled = np.flatnonzero(np.any(rho != 0.0, axis=(1, 2)))
                k0, k1 = (int(filled[0]), int(filled[-1]) + 1) if filled.size else (0, 0)
            out[:, :k0] = np.nan
            out[:, k1:] = np.nan
            if k1 == k0:
                return out
        phi, x_lo, x_hi, offsets, periodic = self._solve(rho, shear_offset, (k0, k1) if (k0, k1) != (0, nz) else None)
        gradient(phi, x_lo, x_hi, offsets, periodic, active, self.dx, self.order, out[:, k0:k1])
        return out


def potential(rho: np.ndarray, *, box: tuple[float, float, float], four_pi_G: float,
              boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic"),
              shear_offset: float = 0.0) -> np.ndarray:
    """The potential of ``rho`` ``(nz, ny, nx)``: :meth:`PoissonSolver.potential` of a new solver."""
    nz, ny, nx = np.shape(rho)
    return PoissonSolver((nx, ny, nz), box, four_pi_G, boundaries).potential(rho, shear_offset)


def acceleration(rho: np.ndarray, *, box: tuple[float, float, float], four_pi_G: float,
                 boundaries: tuple[str, str, str] = ("periodic", "periodic", "periodic"),
                 shear_offset: float = 0.0, order: int = 2) -> np.ndarray:
    """``-∇Φ`` ``(3, nz, ny, nx)`` of ``rho``: :meth:`PoissonSolver.acceleration` of a new solver."""
    nz, ny, nx = np.shape(rho)
    return PoissonSolver((nx, ny, nz), box, four_pi_G, boundaries, order).acceleration(rho, shear_offset)
