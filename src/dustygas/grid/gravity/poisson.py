"""The FFT Poisson solver of :mod:`dustygas.grid.gravity` (see the package docstring for the method).

:class:`PoissonSolver` holds the wavenumber tables of one block; :meth:`~PoissonSolver.potential`
and :meth:`~PoissonSolver.acceleration` are functions of a density array and the shear offset.
:func:`potential` and :func:`acceleration` build a solver and call it once.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from scipy import fft

from ...errors import SetupError
from .isolated import isolated_green_transform
from .kernels import apply_periodic_green, apply_sheet_green, gradient, vacuum_columns

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
        (nx, ny, nz), (lx, ly, lz), (dx, _, dz) = self.shape, self.box, self.dx
        gx, gy, gz = self.ghosts
        if self.isolated:
            self._doubled = tuple(2 * (n + g) for n, g in zip((nz, ny, nx), (gz, gy, gx)))
            self._green = isolated_green_transform(self._doubled, self.dx, self.four_pi_G / (4.0 * np.pi))
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
        # columns i = -gx .. nx + gx - 1 of the inverse transform (x ghosts)
        self._cells = np.arange(-gx, nx + gx, dtype=np.float64)

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

    def potential_with_ghosts(self, rho: np.ndarray, shear_offset: float = 0.0) -> np.ndarray:
        """Potential ``(nz + 2gz, ny + 2gy, nx + 2gx)`` with :attr:`ghosts` layers per active side.

        Ghost layers hold the potential one (two) cells outside the box: periodic images, the
        sheared radial images (``Φ(x ± Lx, y) = Φ(x, y ± s)``, exact: from the same Fourier
        modes), or under vacuum the potential of the box's mass outside it.
        """
        rho = self._check(rho)
        if self.isolated:
            return self._isolated(rho)
        (nx, ny, nz), (gx, gy, gz) = self.shape, self.ghosts
        w = self._workers()
        shift = float(shear_offset) if self.shear else 0.0
        kx = self._kx(shift)
        my = self._my
        # ---- forward: y (real), sheared-frame phase, x
        if ny > 1:
            a = fft.rfft(rho, axis=1, workers=w)[:, :my, :]
            if shift != 0.0:
                theta = self._ky * shift * self.dx[0] / self.box[0]
                a = a * np.exp(-1j * theta[:, None] * self._cells[None, gx:gx + nx])[None]
            if nx > 1:
                a = fft.fft(a, axis=2, workers=w, overwrite_x=True)
            else:
                a = np.ascontiguousarray(a)
        elif nx > 1:
            a = np.ascontiguousarray(fft.rfft(rho, axis=2, workers=w)[:, :, :kx.shape[1]])
        else:
            a = rho.astype(np.complex128)
        # ---- vertical and the Green's function
        if nz > 1 and not self.vacuum_z:
            a = fft.fft(a, axis=0, workers=w, overwrite_x=True)
            apply_periodic_green(a, kx, self._ky, self._kz, self.four_pi_G)
            a = fft.ifft(a, axis=0, workers=w, overwrite_x=True)
        elif nz == 1:
            apply_sheet_green(a, kx, self._ky, self.four_pi_G, self.thin)
        else:
            out = np.empty((nz + 2 * gz,) + a.shape[1:], dtype=np.complex128)
            vacuum_columns(a, kx, self._ky, self.dx[2], self.four_pi_G, gz, out)
            a = out
        # ---- inverse: x (with its ghost columns), phase, y
        layers = a.shape[0]
        if ny > 1:
            if nx > 1:
                a = fft.ifft(a, axis=2, workers=w, overwrite_x=True)
                if gx:
                    a = np.concatenate((a[:, :, nx - gx:], a, a[:, :, :gx]), axis=2)
                if shift != 0.0:
                    a *= np.exp(1j * theta[:, None] * self._cells[None, :])[None]
            full = np.zeros((layers, ny // 2 + 1, a.shape[2]), dtype=np.complex128)
            full[:, :my] = a
            phi = fft.irfft(full, n=ny, axis=1, workers=w)
        elif nx > 1:
            full = np.zeros((layers, 1, nx // 2 + 1), dtype=np.complex128)
            full[:, :, :a.shape[2]] = a
            phi = fft.irfft(full, n=nx, axis=2, workers=w)
            if gx:
                phi = np.concatenate((phi[:, :, nx - gx:], phi, phi[:, :, :gx]), axis=2)
        else:
            phi = a.real
        # ---- periodic ghost layers in y and (unless vacuum) z
        ext = np.empty((nz + 2 * gz, ny + 2 * gy, nx + 2 * gx))
        z0 = 0 if layers == nz + 2 * gz else gz
        ext[z0:z0 + layers, gy:gy + ny] = phi
        if gy:
            ext[:, :gy] = ext[:, ny:ny + gy]
            ext[:, ny + gy:] = ext[:, gy:2 * gy]
        if gz and z0:
            ext[:gz] = ext[nz:nz + gz]
            ext[nz + gz:] = ext[gz:2 * gz]
        return ext

    def _isolated(self, rho: np.ndarray) -> np.ndarray:
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
        (gx, gy, gz), (nx, ny, nz) = self.ghosts, self.shape
        return self.potential_with_ghosts(rho, shear_offset)[gz:gz + nz, gy:gy + ny, gx:gx + nx].copy()

    def acceleration(self, rho: np.ndarray, shear_offset: float = 0.0, out: np.ndarray | None = None) -> np.ndarray:
        """Gravitational acceleration ``-∇Φ`` ``(3, nz, ny, nx)`` at the cell centres (0 along
        inactive axes), by centred differences of :attr:`order` of the potential."""
        nx, ny, nz = self.shape
        phi = self.potential_with_ghosts(rho, shear_offset)
        if out is None:
            out = np.empty((3, nz, ny, nx))
        gradient(phi, *self.ghosts, *self.dx, self.order, out)
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
