"""Rendered maps: SPH interpolation onto pixels conserves the mass it spreads."""

import numpy as np
import pytest

from dustygas.sph.render import render_plane

from ._run import build


def test_rendered_density_integrates_to_the_mass():
    """The density map of the 2D Kepler ring, integrated over the pixels, equals the ring mass to
    1e-4 (each particle's kernel integrates to m_b; pixels 1/10 of h)."""
    prob, cfg, eng = build("sph-kepler-ring")
    eng.update_derivatives()
    p = eng.particles
    extent = (-1.3, 1.3, -1.3, 1.3)
    npix = 1040
    img = render_plane(p.pos, p.mass, eng.rho, p.h, eng.rho, "cubic", 2, extent, npix)
    area = (2.6 / npix) ** 2
    assert img.sum() * area == pytest.approx(p.mass.sum(), rel=1e-4)
    # at a particle the map is the SPH density estimate there (self-consistent rho, 2 %)
    i = int(np.argmin(np.abs(np.hypot(p.pos[:, 0], p.pos[:, 1]) - 1.0)))
    col = int((p.pos[i, 0] + 1.3) / 2.6 * npix)
    row = int((p.pos[i, 1] + 1.3) / 2.6 * npix)
    assert img[row, col] == pytest.approx(eng.rho[i], rel=0.02)
