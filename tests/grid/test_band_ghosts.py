"""The ghosts of a radial-vertical (x-z) box filled band by band, as the integrator's threads do.

:func:`fill_band_ghosts` must give every ghost cell, bit for bit, the value of the serial
:func:`fill_ghosts` (z first over the whole rows, then x over every plane), and each band must
read domain cells only: the bands run at the same time in the integrator, so a band that read
a ghost another band writes would depend on their order. Both are checked here by starting
from ghosts full of NaN and running the bands in either order.
"""

import numpy as np
import pytest

from dustygas.grid import Mesh
from dustygas.grid.boundaries import fill_band_ghosts, fill_ghosts, make_boundaries

X_KINDS = ("shear-periodic", "periodic", "outflow", "reflecting")
Z_KINDS = ("periodic", "outflow", "reflecting", "hydrostatic")


@pytest.mark.parametrize("x_kind", X_KINDS)
@pytest.mark.parametrize("z_kind", Z_KINDS)
def test_bands_fill_every_ghost_as_the_serial_fill(x_kind, z_kind):
    nx, nz = 10, 9
    mesh = Mesh((nx, 1, nz), (1.0, 1.0, 0.6))
    lay, sp = mesh.layout, mesh.spacing
    bc = make_boundaries((x_kind, "periodic", z_kind), (True, False, True), q_omega_lx=1.5, vy_jump=1.5,
                         scale_height=0.25 if z_kind == "hydrostatic" else 0.0)
    gx, gz = lay.gx, lay.gz
    rng = np.random.default_rng(7)
    u = np.full((4, nz + 2 * gz, 1, nx + 2 * gx), np.nan)
    u[:, gz:gz + nz, :, gx:gx + nx] = 1.0 + rng.random((4, nz, 1, nx))
    reference = u.copy()
    fill_ghosts(reference, 0.3, lay, sp, bc)
    assert not np.isnan(reference).any()
    for nband in (1, 2, 3, nz):
        for order in (1, -1):
            banded = u.copy()
            for c in range(nband)[::order]:
                fill_band_ghosts(banded, 0.3, lay, sp, bc, c * nz // nband, (c + 1) * nz // nband)
            assert np.array_equal(banded, reference), (nband, order)
