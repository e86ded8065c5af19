"""Uniform Cartesian mesh: one local block of cells with ghost zones.

The engine always stores 3D arrays indexed ``[k, j, i]`` (z, y, x; x varies fastest). A
dimension with one cell is *inactive*: it has no ghost zones and no fluxes, its cell size is
taken as 1 (so that masses and momenta are per unit length in the missing directions) and its
velocity component is still carried. 1D runs use ``nx`` only; 2D runs in the radial-azimuthal
plane use ``(nx, ny)``, in the radial-vertical plane ``(nx, nz)`` with ``ny = 1``.

The box is centred on the origin, ``x in [-Lx/2, Lx/2]`` etc.: in a shearing box the tidal
force and the background shear ``-q Omega x`` vanish at the centre of the box.

:class:`Layout` (integers) and :class:`Spacing` (floats) are the two small records the numba
kernels receive; :class:`Mesh` is the Python object that builds them and answers geometry
questions (cell centres, the index of a position).

The kernels a step calls from Python take these records, and the other named tuples of the
engines (:class:`~dustygas.grid.boundaries.Boundaries`, the source terms, the particles'
boundaries, species and force tables), as *plain* tuples of the same fields and rebuild the
named tuple in their first lines (``lay = Layout(*layout)``, free once compiled; a named tuple
passed in works too), one statement each: rebuilt in one tuple assignment, a record used in a
parallel loop made numba's parfor lowering fail (it looks for the class that built the record
and finds the unpacking). numba's dispatcher types a plain tuple in C at every call but a named
one in Python, about 0.6 µs each: the 32 named tuples of a linA step (16 kernel calls) took
41 µs of its dispatch, plain 23 µs -- serial time, which two threads cannot halve
(2026-12-05, benchmarks/RESULTS.md). The engines keep both forms (:class:`KernelTuple`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ..errors import SetupError

__all__ = ["Mesh", "Layout", "Spacing", "Offsets", "KernelTuple", "NGHOST", "cell_average_factor"]

#: Ghost cells per side in every active dimension: PPM reconstruction in the corrector needs
#: three (the interface value at the first face uses four cells on each side of the parabola).
NGHOST = 3


class Layout(NamedTuple):
    """Integer shape of a block: domain cells and ghost cells per side in x, y, z."""

    nx: int
    ny: int
    nz: int
    gx: int
    gy: int
    gz: int


class Spacing(NamedTuple):
    """Cell sizes, the coordinate of the lower domain corner and the box lengths."""

    dx: float
    dy: float
    dz: float
    x0: float
    y0: float
    z0: float
    lx: float
    ly: float
    lz: float


class Offsets(NamedTuple):
    """Where a block sits in the global mesh: its first domain cell ``(i0, j0, k0)`` and the
    global cell counts ``(NX, NY, NZ)``. A single-block run has offsets 0 and the block's own
    counts. Kernels that need global indices (the particle assignment weights, which must not
    depend on how the box is split) form ``global = local + offset`` and positions relative to
    the global origin ``Spacing.x0 - i0 dx``."""

    i0: int
    j0: int
    k0: int
    NX: int
    NY: int
    NZ: int


class KernelTuple:
    """An engine attribute holding a named tuple that kernels take (module docstring): setting
    ``engine.name`` also sets ``engine.name_t``, the plain tuple of its fields, which the step
    passes to the kernels; a replaced record (a decomposed run's boundaries) renews both.

    >>> class Engine:
    ...     layout = KernelTuple()
    >>> e = Engine()
    >>> e.layout = Layout(4, 1, 4, 3, 0, 3)
    >>> e.layout.nx, e.layout_t
    (4, (4, 1, 4, 3, 0, 3))
    """

    def __set_name__(self, owner: type, name: str) -> None:
        self.name, self.plain = name, name + "_t"

    def __get__(self, obj, objtype=None):
        return self if obj is None else obj.__dict__[self.name]

    def __set__(self, obj, value: tuple) -> None:
        obj.__dict__[self.name] = value
        obj.__dict__[self.plain] = tuple(value)


def cell_average_factor(k, dx) -> float:
    """Cell average of ``e^{i k.x}`` over a cell centred at ``x_c``, divided by ``e^{i k.x_c}``.

    .. math:: \\frac{1}{\\Delta V}\\int_{cell} e^{i k\\cdot x}\\,dV = e^{i k\\cdot x_c}
              \\prod_d \\operatorname{sinc}\\left(\\frac{k_d \\Delta x_d}{2}\\right)

    (``sinc(u) = sin(u)/u``): a finite-volume mesh holds cell averages, so a Fourier mode of
    point values ``A`` appears with amplitude ``A`` times this factor.

    >>> round(cell_average_factor((3.141592653589793, 0.0, 0.0), (0.5, 1.0, 1.0)), 12)
    0.900316316157
    """
    return float(np.prod([np.sinc(kd * d / (2 * np.pi)) for kd, d in zip(k, dx)]))


@dataclass(frozen=True)
class Mesh:
    """A uniform mesh of ``shape = (nx, ny, nz)`` cells filling the box ``size = (Lx, Ly, Lz)``.

    Parameters
    ----------
    shape
        Cells per dimension; 1 marks an inactive dimension.
    size
        Box lengths; an inactive dimension's length is ignored and taken as 1.
    nghost
        Ghost cells per side in active dimensions.

    Examples
    --------
    >>> m = Mesh((64, 1, 32), (2.0, 1.0, 1.0))
    >>> m.ndim, m.active, m.array_shape
    (2, (True, False, True), (38, 1, 70))
    >>> float(m.centers(0)[0]), float(m.dx[0])
    (-0.984375, 0.03125)
    """

    shape: tuple[int, int, int]
    size: tuple[float, float, float]
    nghost: int = NGHOST

    def __post_init__(self) -> None:
        shape = tuple(int(n) for n in self.shape)
        if len(shape) != 3 or min(shape) < 1:
            raise SetupError(f"mesh shape {self.shape}: expected three cell counts >= 1")
        if max(shape) == 1:
            raise SetupError("mesh has no active dimension: at least one of nx, ny, nz must exceed 1")
        size = tuple(float(s) if n > 1 else 1.0 for s, n in zip(self.size, shape))
        if min(size) <= 0 or not all(np.isfinite(size)):
            raise SetupError(f"box size {self.size}: lengths must be positive and finite")
        object.__setattr__(self, "shape", shape)
        object.__setattr__(self, "size", size)

    # ------------------------------------------------------------------ shape
    @property
    def active(self) -> tuple[bool, bool, bool]:
        """Which of x, y, z have more than one cell."""
        return tuple(n > 1 for n in self.shape)  # type: ignore[return-value]

    @property
    def ndim(self) -> int:
        return sum(self.active)

    @property
    def ghosts(self) -> tuple[int, int, int]:
        """Ghost cells per side in x, y, z (0 in inactive dimensions)."""
        return tuple(self.nghost if a else 0 for a in self.active)  # type: ignore[return-value]

    @property
    def array_shape(self) -> tuple[int, int, int]:
        """Shape ``(NZ, NY, NX)`` of one variable's array including ghost zones."""
        (nx, ny, nz), (gx, gy, gz) = self.shape, self.ghosts
        return (nz + 2 * gz, ny + 2 * gy, nx + 2 * gx)

    @property
    def ncells(self) -> int:
        """Number of domain cells (the run loop's work units per step)."""
        return int(np.prod(self.shape))

    @property
    def dx(self) -> tuple[float, float, float]:
        """Cell sizes (1 in inactive dimensions)."""
        return tuple(s / n if n > 1 else 1.0 for s, n in zip(self.size, self.shape))  # type: ignore[return-value]

    @property
    def lower(self) -> tuple[float, float, float]:
        """Coordinates of the lower corner of the domain (``-L/2``; 0 in inactive dimensions)."""
        return tuple(-0.5 * s if n > 1 else 0.0 for s, n in zip(self.size, self.shape))  # type: ignore[return-value]

    @property
    def origin(self) -> tuple[float, float, float]:
        """Lower corner of the whole mesh (of a single block: :attr:`lower`); kernels that need
        global coordinates form ``origin + (offset + i + 1/2) dx`` (:attr:`offsets`)."""
        return self.lower

    @property
    def cell_volume(self) -> float:
        dx, dy, dz = self.dx
        return dx * dy * dz

    # ------------------------------------------------------------------ kernels' view
    @property
    def layout(self) -> Layout:
        return Layout(*self.shape, *self.ghosts)

    @property
    def spacing(self) -> Spacing:
        return Spacing(*self.dx, *self.lower, *self.size)

    @property
    def offsets(self) -> Offsets:
        """A single block: offsets 0, global counts = its own."""
        return Offsets(0, 0, 0, *self.shape)

    # ------------------------------------------------------------------ coordinates
    def centers(self, axis: int, ghosts: bool = False) -> np.ndarray:
        """Cell-centre coordinates along ``axis`` (0, 1, 2), optionally including ghost cells."""
        n, g = self.shape[axis], self.ghosts[axis]
        d, lo = self.dx[axis], self.lower[axis]
        idx = np.arange(-g, n + g) if ghosts else np.arange(n)
        return lo + (idx + 0.5) * d

    def meshgrid(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Cell-centre coordinates ``(x, y, z)`` broadcastable to the domain shape ``(nz, ny, nx)``."""
        x = self.centers(0)[None, None, :]
        y = self.centers(1)[None, :, None]
        z = self.centers(2)[:, None, None]
        return x, y, z

    def interior(self) -> tuple[slice, slice, slice]:
        """Index of the domain inside a ghost-padded ``(NZ, NY, NX)`` array."""
        (nx, ny, nz), (gx, gy, gz) = self.shape, self.ghosts
        return (slice(gz, gz + nz), slice(gy, gy + ny), slice(gx, gx + nx))
