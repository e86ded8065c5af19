"""Long checks (``-m slow``): large LAPACK comparisons, full-scale maps, a 4D sweep."""

import math
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import pytest

from dustygas.linear import growth_rate, operator_matrix
from dustygas.linear.maps import growth_map
from dustygas.linear.shearing_wave import sweep

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
    gm = growth_map(mu, taus, method="kx", kz=1000.0, kx_range=(0.1, 1e6), Pi=0.0)
    T, M = np.meshgrid(taus, mu, indexing="ij")
    direct = growth_rate(T, M, gm.kx, gm.kz, Pi=0.0)
    assert np.max(np.abs(direct - gm.growth)) <= 1e-12
    assert not gm.at_edge.any()
    coarse = growth_rate(T[..., None], M[..., None], np.logspace(-1, 6, 12)[None, None, :], 1000.0, Pi=0.0)
    assert np.all(gm.growth >= coarse.max(axis=-1) * (1 - 1e-10) - 1e-14)  # round-off in the k values


@pytest.mark.slow
def test_4d_sweep_process_pool_and_preferred_angle():
    """A 2×2×6×4 sweep over one orbit: pool == serial, and the preferred angle is the argmax."""
    args = dict(mu=[0.5, 2.0], taus=[0.1, 0.3], kx=np.linspace(-60, 60, 6), ky=[1.0, 3.0, 10.0, 30.0],
                kz=30.0, t_end=2 * math.pi)
    serial = sweep(**args)
    with ProcessPoolExecutor(2) as ex:
        pooled = sweep(**args, executor=ex, chunksize=4)
    assert np.array_equal(serial.amplification, pooled.amplification)
    ang, kx, ky = serial.preferred_angle()
    for i in range(2):
        for j in range(2):
            a = serial.amplification[i, j]
            ii, jj = np.unravel_index(np.nanargmax(a), a.shape)
            assert ang[i, j] == pytest.approx(math.degrees(math.atan2(args["ky"][jj], args["kx"][ii])))
