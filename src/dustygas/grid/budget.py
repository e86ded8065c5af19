"""The grid engine's running budgets, kept per row of cells so that no sum depends on the blocks.

A budget is a time integral of a sum over cells or boundary faces (the mass through the radial
boundary, the y-momentum of the shearing-box sources, the mass out through the z faces). Summed
over the whole box at every stage it would depend on how the box is cut into blocks
(:mod:`dustygas.parallel`): a block sums its own cells, and the blocks' sums added together are
the serial sum only to round-off. So each budget is a running total per *unit* -- a set of
cells that one block always holds whole, whose per-stage increment is summed in a fixed order
-- and the history value is the correctly rounded sum of the units' totals
(:func:`math.fsum`: it does not depend on their order either). One flat array holds them:

==================  ===============  ================================================================
section             units            increment per stage
==================  ===============  ================================================================
``radial``          ``nz`` z planes  the plane's radial mass flux after the flux correction
                                     (:func:`~dustygas.grid.boundaries.correct_radial_fluxes`)
``y_source``        ``nz ny`` rows   the y-momentum source summed along the stage's first sweep's
                    ``(k, j)``       pencil (x; in a box without x, the y pencil of plane ``k``
                                     goes to row ``(k, 0)``), in cell order
``z_lower``,        ``ny nx`` face   the mass flux out through that face cell
``z_upper``         cells ``(j, i)``
==================  ===============  ================================================================

A shear-periodic box is split along z only, so every unit lies in one block; the z faces' cells
do too for any layout. The one case left to round-off: a box with a y-momentum source (a
rotating frame) whose first swept axis is split (x, or y in a box without x), where a pencil's
sum is made of its blocks' parts.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..errors import UserError

__all__ = ["budget_offsets", "budget_sections", "budget_totals", "budget_rows_from"]


@njit(cache=True)
def budget_offsets(nx: int, ny: int, nz: int) -> tuple[int, int, int, int]:
    """``(size, y0, zl0, zu0)``: the length of the flat budget array of an ``nx ny nz`` block and
    the first entries of its ``y_source``, ``z_lower`` and ``z_upper`` sections (``radial`` is first).

    >>> budget_offsets(4, 3, 2)
    (32, 2, 8, 20)
    """
    y0 = nz
    zl0 = y0 + nz * ny
    zu0 = zl0 + ny * nx
    return zu0 + ny * nx, y0, zl0, zu0


def budget_sections(rows: np.ndarray, shape: tuple[int, int, int]) -> dict[str, np.ndarray]:
    """Views of the sections of the flat budget ``rows`` of a block of ``shape`` ``(nx, ny, nz)``:
    ``radial`` ``(nz,)``, ``y_source`` ``(nz, ny)``, ``z_lower`` and ``z_upper`` ``(ny, nx)``."""
    nx, ny, nz = shape
    size, y0, zl0, zu0 = budget_offsets(nx, ny, nz)
    if rows.shape != (size,):
        raise ValueError(f"budget rows of shape {rows.shape}, a {nx} x {ny} x {nz} block has ({size},)")
    return {"radial": rows[:y0], "y_source": rows[y0:zl0].reshape(nz, ny), "z_lower": rows[zl0:zu0].reshape(ny, nx),
            "z_upper": rows[zu0:].reshape(ny, nx)}


def budget_totals(rows: np.ndarray, shape: tuple[int, int, int]) -> np.ndarray:
    """``[radial mass, y-momentum source, mass out through the lower z face, ... the upper]``: each
    section's correctly rounded sum (:func:`math.fsum`) over its non-zero entries: the same value
    (zeros add nothing to the exact sum, and an all-zero section sums to +0.0 either way), but the
    sections a box does not use -- the z faces of a 2D x-y box, 2 x 65 536 cells at 256^2 -- cost a
    comparison instead of 1.8 ms of :func:`math.fsum` each per history row (2026-12-05).

    >>> rows = np.zeros(budget_offsets(2, 1, 3)[0]); rows[3:6] = [0.1, 0.2, 0.3]
    >>> budget_totals(rows, (2, 1, 3)).tolist()
    [0.0, 0.6, 0.0, 0.0]
    """
    return np.array([math.fsum(a[a != 0.0]) for a in budget_sections(rows, shape).values()])


def budget_rows_from(arrays: dict, shape: tuple[int, int, int]) -> np.ndarray:
    """The whole box's flat budget of a checkpoint: its ``budget_rows``, or, in a checkpoint
    written before them, its totals ``budget`` (2 or 4 entries) as the first unit of each section
    (whose block then goes on adding to it: a restart on any rank count gives the same numbers).

    >>> budget_rows_from({"budget": np.array([1.0, 2.0])}, (2, 1, 3))[:4].tolist()
    [1.0, 0.0, 0.0, 2.0]
    """
    size = budget_offsets(*shape)[0]
    if "budget_rows" in arrays:
        rows = np.array(arrays["budget_rows"], dtype=np.float64)
        if rows.shape != (size,):
            raise UserError(f"checkpoint holds budget rows of shape {rows.shape}, the configuration needs ({size},)")
        return rows
    rows = np.zeros(size)
    totals = np.asarray(arrays["budget"], dtype=np.float64)
    for value, part in zip(totals, budget_sections(rows, shape).values()):
        part.reshape(-1)[0] = value
    return rows
