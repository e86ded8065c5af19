"""Particle-mesh assignment: NGP, CIC and TSC weights, one stencil for gathering and depositing.

A particle at position ``x`` exchanges momentum with the cells of a small stencil around it
(thesis §4.2; Hockney & Eastwood 1981, §5-3). Along one active axis with cell size ``Δx`` and
the particle at ``s = (x - x_0)/Δx - 1/2`` cell widths from the centre of cell 0, the
one-dimensional assignment functions are

=====  ===========================================================  =====================
NGP    ``W = 1`` in the nearest cell ``i = round(s)``                 1 cell
CIC    ``W = 1 - f, f`` in cells ``i, i + 1`` (``i = floor(s)``,      2 cells
       ``f = s - i``)
TSC    ``W = (1/2 - d)^2/2, 3/4 - d^2, (1/2 + d)^2/2`` in cells       3 cells
       ``i - 1, i, i + 1`` (``i = round(s)``, ``d = s - i``)
TSC-C  TSC convolved with the filter ``1 - δ²/8`` (``δ²u_j = u_{j+1} - 2u_j + u_{j-1}``):  5 cells
       weights ``-W_{-1}/8, W_{-1} - (W_0 - 2W_{-1})/8, ...``
=====  ===========================================================  =====================

and the weight of a cell in 2D and 3D is the product over the active axes. Every assignment
function sums to one over the cells for any position (a partition of unity), so a particle
deposits exactly its own mass and momentum, and a uniform lattice of particles deposits a
uniform density whatever its offset (for TSC and CIC; NGP needs the lattice on the cell
centres).

The engine stores, for each particle and axis, the weights of the cells ``c - R .. c + R``
around the cell ``c`` that *contains* the particle (:func:`cell_weights`; ``R`` is the
kernel's reach, :data:`KERNEL_REACH`: 1 for NGP, CIC and TSC, whose cells all lie within one
cell of ``c``, 2 for TSC-C). The **same weights** serve to gather the gas at the particle
(thesis eq. 4.22, :math:`\\bar u(x_d) = \\sum_a W(x_d - x_a) u_a`) and to deposit its
back-reaction (eq. 4.24), so the drag impulse the gas receives is exactly minus the one the
particles receive (eq. 4.25) and no particle accelerates itself (Youdin & Johansen 2007).

Positions are measured from the global origin of the mesh and cells are numbered globally
(:class:`~dustygas.grid.mesh.Offsets`), so the weights of a particle do not depend on how the
box is split into blocks.
"""

from __future__ import annotations

from numba import njit

__all__ = ["NGP", "CIC", "TSC", "TSC_C", "KERNELS", "KERNEL_WIDTH", "KERNEL_REACH", "axis_weights", "cell_weights",
           "axis_cell", "stencil_into"]

NGP, CIC, TSC, TSC_C = 0, 1, 2, 3
#: name -> code of the assignment functions
KERNELS = {"ngp": NGP, "cic": CIC, "tsc": TSC, "tsc-c": TSC_C}
#: cells per axis of each assignment function, by code
KERNEL_WIDTH = (1, 2, 3, 5)
#: cells the stencil reaches on either side of the cell that contains the particle, by code
KERNEL_REACH = (1, 1, 1, 2)


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def axis_weights(s: float, order: int):
    """First cell ``i`` and the weights ``(w0, ..., w4)`` of cells ``i, ..., i+4`` along one axis.

    ``s`` is the particle position in cell widths from the centre of cell 0; unused weights
    are 0 (NGP uses one cell, CIC two, TSC three, compensated TSC five).
    """
    # floor(v) as int(v + 2) - 2: exact for v > -2 (particles lie within a cell of the block) and
    # much cheaper than a call to floor
    if order == CIC:
        i = int(s + 2.0) - 2
        f = s - i
        return i, 1.0 - f, f, 0.0, 0.0, 0.0
    if order == NGP:
        return int(s + 2.5) - 2, 1.0, 0.0, 0.0, 0.0, 0.0
    i = int(s + 2.5) - 2
    d = s - i
    a = 0.5 - d
    b = 0.5 + d
    wm, w0, wp = 0.5 * a * a, 0.75 - d * d, 0.5 * b * b
    if order == TSC:
        return i - 1, wm, w0, wp, 0.0, 0.0
    # TSC convolved with the filter 1 - δ²/8 (δ² u_j = u_{j+1} - 2 u_j + u_{j-1})
    e = 0.125
    return (i - 2, -e * wm, wm - e * (w0 - 2.0 * wm), w0 - e * (wp - 2.0 * w0 + wm), wp - e * (w0 - 2.0 * wp),
            -e * wp)


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def cell_weights(s: float, order: int, reach: int, out) -> int:
    """Global index ``c`` of the cell containing the particle (``floor(s + 1/2)``) and, in
    ``out[0 .. 2 reach]``, the weights of cells ``c - reach .. c + reach`` (zeros where the
    kernel is narrower)."""
    c = int(s + 2.5) - 2  # the containing cell: floor(s + 1/2)
    first, w0, w1, w2, w3, w4 = axis_weights(s, order)
    for m in range(2 * reach + 1):
        out[m] = 0.0
    off = first - c + reach
    out[off] = w0
    if order >= CIC:
        out[off + 1] = w1
    if order >= TSC:
        out[off + 2] = w2
    if order == TSC_C:
        out[off + 3] = w3
        out[off + 4] = w4
    return c


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def axis_cell(x: float, x0: float, inv_dx: float, offset: int, n: int) -> int:
    """Local index of the cell containing ``x`` along an axis of this block: ``floor((x - x0)/Δx)``
    from the global origin ``x0``, minus the block's first cell ``offset``, clipped into
    ``0 .. n-1`` (0 on an inactive axis). The same arithmetic as :func:`stencil_into`."""
    if n == 1:
        return 0
    c = int((x - x0) * inv_dx - 0.5 + 2.5) - 2 - offset
    return min(max(c, 0), n - 1)


@njit(cache=True, error_model="numpy", inline="always")  # hot: a call costs more than its body
def stencil_into(x: float, x0: float, inv_dx: float, offset: int, n: int, order: int, reach: int, wts, p: int,
                 axis: int) -> int:
    """:func:`axis_cell` and the weights of the cells around it (:func:`cell_weights`), written
    into ``wts[p, axis, 0 .. 2 reach]`` (indices, not a view per particle and axis: a view
    costs a reference count, more than the weights).

    On an inactive axis: cell 0 and the weight 1 in the middle slot. A position that rounds
    onto the upper face of the block is given the weights of the last cell (the physical
    weights are the same there), so that the cell always matches :func:`axis_cell`.
    """
    if n == 1:
        for m in range(2 * reach + 1):
            wts[p, axis, m] = 0.0
        wts[p, axis, reach] = 1.0
        return 0
    s = (x - x0) * inv_dx - 0.5
    c = int(s + 2.5) - 2 - offset  # the containing cell, as cell_weights
    while c > n - 1:
        s = s - 1e-12 * max(1.0, abs(s))
        c = int(s + 2.5) - 2 - offset
    while c < 0:
        s = s + 1e-12 * max(1.0, abs(s))
        c = int(s + 2.5) - 2 - offset
    first, w0, w1, w2, w3, w4 = axis_weights(s, order)
    for m in range(2 * reach + 1):
        wts[p, axis, m] = 0.0
    o = first - (c + offset) + reach
    wts[p, axis, o] = w0
    if order >= CIC:
        wts[p, axis, o + 1] = w1
    if order >= TSC:
        wts[p, axis, o + 2] = w2
    if order == TSC_C:
        wts[p, axis, o + 3] = w3
        wts[p, axis, o + 4] = w4
    return c
