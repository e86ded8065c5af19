"""Long checks (``-m slow``): large LAPACK comparisons, full-scale maps."""

import numpy as np
import pytest

from dustygas.linear import growth_rate, operator_matrix
from dustygas.linear.maps import growth_map

from .test_eigensolver import _check, random_operators


@pytest.mark.slow
@pytest.mark.parametrize("species, n, seed", [(1, 20000, 11), (2, 3000, 12), (3, 1000, 13)])
def test_against_lapack_many_operators(species, n, seed):
    """Every eigenvalue within 1e-10 |λ| + 1e4 ε‖A‖_F of LAPACK (see test_eigensolver)."""
    _check([operator_matrix(p) for p in random_operators(n, seed=seed, species=species)])


@pytest.mark.slow
def test_full_scale_yg05_map_is_self_consistent():
    """200×200 map (fig4.1 --full set-up): every optimum reproduces growth_rate at its (Kx, Kz),
    no optimum sits on the Kx-range edge, and the golden-section optimum beats the coarse grid."""
    mu = np.logspace(-2, 2, 200)
    taus = np.logspace(-3, 1, 200)
    gm = growth_map(mu=mu, taus=taus, method="kx", kz=1000.0, kx_range=(0.1, 1e6), Pi=0.0)
    T, M = np.meshgrid(taus, mu, indexing="ij")
    direct = growth_rate(taus=T, mu=M, kx=gm.kx, kz=gm.kz, Pi=0.0)
    assert np.max(np.abs(direct - gm.growth)) <= 1e-12
    assert not gm.at_edge.any()
    coarse = growth_rate(taus=T[..., None], mu=M[..., None], kx=np.logspace(-1, 6, 12)[None, None, :], kz=1000.0, Pi=0.0)
    assert np.all(gm.growth >= coarse.max(axis=-1) * (1 - 1e-10) - 1e-14)  # round-off in the k values
