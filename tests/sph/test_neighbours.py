"""Neighbour search against brute force: periodic and open, same and different particle sets."""

import numpy as np
import pytest

from dustygas.errors import SimulationError
from dustygas.sph.neighbours import Box, NeighbourFinder


def _brute(qpos, qh, spos, sh, box, radius, same):
    d = qpos[:, None, :] - spos[None, :, :]
    length = box.length
    for ax in range(box.ndim):
        if box.periodic[ax]:
            d[..., ax] -= length[ax] * np.rint(d[..., ax] / length[ax])
    r = np.sqrt((d**2).sum(-1))
    hmax = np.maximum(qh[:, None], sh[None, :])
    hit = r < radius * hmax
    if same:
        np.fill_diagonal(hit, False)
    return [set(np.flatnonzero(row)) for row in hit]


def _random_set(rng, n, ndim, lo, hi):
    pos = np.zeros((n, 3))
    pos[:, :ndim] = lo + (hi - lo) * rng.random((n, ndim))
    return pos


@pytest.mark.parametrize("method", ["cells", "tree"])
@pytest.mark.parametrize("ndim", [1, 2, 3])
@pytest.mark.parametrize("periodic", [True, False])
def test_matches_brute_force(ndim, periodic, method):
    """Every pair with r < R max(h_a, h_b) is found, and no other, with variable h (0 mismatches),
    by the cell list and by the k-d tree."""
    rng = np.random.default_rng(10 * ndim + periodic)
    n = 600
    lo, hi = -0.3, 0.7
    pos = _random_set(rng, n, ndim, lo, hi)
    scale = (hi - lo) * n ** (-1.0 / ndim)
    h = scale * rng.uniform(0.6, 1.8, n)
    box = Box.periodic_box(ndim, (lo,) * ndim, (hi,) * ndim) if periodic else Box.open_box(ndim)
    nl = NeighbourFinder(box, 2.0, method=method).find(pos, h)
    ref = _brute(pos, h, pos, h, box, 2.0, True)
    assert sum(set(nl.neighbours_of(a).tolist()) != ref[a] for a in range(n)) == 0
    assert nl.total == sum(len(s) for s in ref)


@pytest.mark.parametrize("ndim", [2, 3])
def test_thin_periodic_box_uses_minimum_image(ndim):
    """A box only a few kernel radii across (single cell along y, z) still finds every pair."""
    rng = np.random.default_rng(3)
    n = 400
    hi = (1.0,) + (0.2,) * (ndim - 1)
    pos = np.zeros((n, 3))
    pos[:, :ndim] = rng.random((n, ndim)) * np.array(hi)
    h = np.full(n, 0.04)
    box = Box.periodic_box(ndim, (0.0,) * ndim, hi)
    nl = NeighbourFinder(box, 2.0).find(pos, h)
    ref = _brute(pos, h, pos, h, box, 2.0, True)
    assert sum(set(nl.neighbours_of(a).tolist()) != ref[a] for a in range(n)) == 0


@pytest.mark.parametrize("method", ["cells", "tree"])
def test_queries_against_another_set(method):
    """Dust querying gas: neighbours of each query among the sources, with both sets of h."""
    rng = np.random.default_rng(7)
    gas = _random_set(rng, 500, 3, 0.0, 1.0)
    dust = _random_set(rng, 80, 3, 0.0, 1.0)
    h_gas = rng.uniform(0.05, 0.1, 500)
    h_dust = np.zeros(80)  # dust: interactions set by the gas smoothing length only
    box = Box.periodic_box(3, (0.0,) * 3, (1.0,) * 3)
    nl = NeighbourFinder(box, 2.0, method=method).find(gas, h_gas, query_pos=dust, query_h=h_dust)
    ref = _brute(dust, h_dust, gas, h_gas, box, 2.0, False)
    assert sum(set(nl.neighbours_of(a).tolist()) != ref[a] for a in range(80)) == 0


def test_coincident_particles_are_reported():
    """Two particles at the same position raise SimulationError naming both, with their state."""
    pos = _random_set(np.random.default_rng(1), 50, 2, 0.0, 1.0)
    pos[17] = pos[4]
    with pytest.raises(SimulationError, match=r"first: 4 and 17") as err:
        NeighbourFinder(Box.periodic_box(2, (0.0, 0.0), (1.0, 1.0)), 2.0).find(pos, np.full(50, 0.1))
    assert sorted(err.value.state["overlapping"].tolist()) == [4, 17]


def test_kernel_larger_than_half_box_is_refused():
    pos = _random_set(np.random.default_rng(2), 20, 1, 0.0, 1.0)
    with pytest.raises(SimulationError, match="exceeds half the periodic box"):
        NeighbourFinder(Box.periodic_box(1, (0.0,), (1.0,)), 2.0).find(pos, np.full(20, 0.3))


def test_clustered_particles_use_the_tree_and_find_every_pair():
    """A centrally concentrated open distribution (h spread 30x): ``auto`` picks the tree, whose
    table matches brute force."""
    rng = np.random.default_rng(11)
    n = 800
    r = rng.random(n) ** 3
    direction = rng.normal(size=(n, 3))
    pos = r[:, None] * direction / np.linalg.norm(direction, axis=1)[:, None]
    h = 0.02 + 0.3 * r
    finder = NeighbourFinder(Box.open_box(3), 2.0)
    assert finder.choose(h) == "tree"
    nl = finder.find(pos, h)
    ref = _brute(pos, h, pos, h, Box.open_box(3), 2.0, True)
    assert sum(set(nl.neighbours_of(a).tolist()) != ref[a] for a in range(n)) == 0
