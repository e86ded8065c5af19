"""Acceptance 3 (clump finder): planted Plummer spheres in a noisy shearing-box background."""

import numpy as np
import pytest

from dustygas.analysis.clumps import ClumpCatalogue, find_clumps, hop_cells
from dustygas.analysis.synthetic import planted_clumps
from dustygas.errors import UserError
from dustygas.physics.gravity import hill_density, hill_radius

G = 0.1 / (4 * np.pi)  # G~ = 0.1: Hill density 90
BOX, CELLS, SHEAR = (1.0, 1.0, 0.5), (32, 32, 16), 0.3137  # s = 10.04 cells
MASSES = np.array([0.08, 0.12, 0.2, 0.3, 0.45, 0.7])  # Hill radii 1.9 .. 3.9 cells
# the first two straddle the radial faces (r_H = 0.060 and 0.068 from them), the fourth the y face
CENTRES = np.array([[0.47, 0.1, 0.02], [-0.48, -0.3, -0.03], [0.0, 0.0, 0.0], [-0.2, 0.47, 0.05],
                    [0.25, -0.3, -0.02], [0.2, 0.3, 0.0]])


@pytest.fixture(scope="module")
def planted():
    # background: 2 particles per cell at 0.3 % of the Hill density, velocity noise 0.01
    return planted_clumps(CENTRES, MASSES, box=BOX, G=G, shear_offset=SHEAR, particles_per_clump=2000,
                          background_density=0.003 * float(hill_density(G)), background_particles=2 * 32 * 32 * 16,
                          hill_fraction=1 / 30, seed=0)


def _match(cat, planted):
    """Planted clump of each found clump (the one most of its members come from)."""
    out = []
    for c in range(len(cat)):
        tags = planted.clump[cat.members(c)]
        out.append(int(np.bincount(tags[tags >= 0], minlength=len(MASSES)).argmax()) if (tags >= 0).any() else -1)
    return out


def test_every_planted_clump_is_found_with_99_percent_of_its_mass(planted):
    cat = find_clumps(planted.pos, planted.vel, planted.mass, box=BOX, cells=CELLS, G=G, shear_offset=SHEAR)
    match = _match(cat, planted)
    assert len(cat) == len(MASSES) and sorted(match) == list(range(len(MASSES))), match  # none missed, none spurious
    for c, k in enumerate(match):
        members = cat.members(c)
        mine = planted.clump[members] == k
        recovered = planted.mass[members][mine].sum() / planted.mass[planted.clump == k].sum()
        foreign = planted.mass[members][~mine].sum() / MASSES[k]
        # measured 99.35 .. 99.65 % recovered, 0.08 .. 0.12 % background
        assert recovered >= 0.99, f"clump {k}: {100 * recovered:.2f} % of its mass"
        assert foreign < 0.002, f"clump {k}: {100 * foreign:.3f} % of its mass is background"
        assert cat.particle_count[c] == members.size
        assert abs(cat.mass[c] / MASSES[k] - 1) < 0.01
        assert np.isclose(cat.hill_radius[c], hill_radius(cat.mass[c], G))
        # the centre of mass: within 2 % of r_H of the planted centre (through the sheared images)
        d = cat.position[c] - CENTRES[k]
        n = np.round(d[0] / BOX[0])
        d[0] -= n * BOX[0]
        d[1] += n * SHEAR
        d[1] -= BOX[1] * np.round(d[1] / BOX[1])
        assert np.linalg.norm(d) < 0.02 * cat.hill_radius[c], (k, d)
        # the clump moves with the shear at its centre: v_y = -q Omega x_c
        assert abs(cat.velocity[c, 1] + 1.5 * cat.position[c, 0]) < 0.01


def test_background_alone_has_no_clumps(planted):
    bg = planted.clump < 0
    cat = find_clumps(planted.pos[:, bg], planted.vel[:, bg], planted.mass[bg], box=BOX, cells=CELLS, G=G,
                      shear_offset=SHEAR)
    assert len(cat) == 0 and cat.member_offsets.tolist() == [0]


def test_catalogue_round_trips_through_hdf5(planted, tmp_path):
    cat = find_clumps(planted.pos, planted.vel, planted.mass, box=BOX, cells=CELLS, G=G, shear_offset=SHEAR,
                      ids=np.arange(planted.mass.size) + 1000)
    back = ClumpCatalogue.read(cat.write(tmp_path / "clumps.h5"))
    for key in ClumpCatalogue._COLUMNS:
        np.testing.assert_array_equal(getattr(back, key), getattr(cat, key))
    assert back.attrs["threshold"] == pytest.approx(90.0) and back.attrs["clumps"] == len(cat)
    assert back.members(0).min() >= 1000


def test_hop_joins_cells_to_their_peak_across_the_sheared_face():
    # two peaks: one at the outer radial face, its shoulder in the inner column shifted by the
    # shear (3 cells); the shoulder must hop to it, not form a group of its own
    rho = np.zeros((1, 16, 8))
    rho[0, 5, 7] = 10.0  # peak at the last column, row 5
    rho[0, 8, 0] = 5.0  # first column, row 5 + 3: the peak's image neighbour
    rho[0, 12, 3] = 7.0  # an unrelated peak
    root = hop_cells(rho, 1.0, 3, True, False).reshape(rho.shape)
    assert root[0, 8, 0] == root[0, 5, 7] == 5 * 8 + 7
    assert root[0, 12, 3] == 12 * 8 + 3
    assert (root[rho <= 1.0] == -1).all()
    # without the shear the two are not neighbours
    assert hop_cells(rho, 1.0, 3, False, False)[8 * 8] == 8 * 8


def test_bad_input_is_one_line():
    with pytest.raises(UserError, match="must be positive"):
        find_clumps(np.zeros((3, 2)), np.zeros((3, 2)), np.ones(2), box=BOX, cells=CELLS, G=0.0)


# ---------------------------------------------------------------------------- the command line
def test_analyze_clumps_on_a_synthetic_run(planted, tmp_path, capsys):
    import json

    from dustygas.analysis.synthetic import write_snapshot_run
    from dustygas.cli import main

    run = write_snapshot_run(tmp_path / "run", planted, cells=CELLS, G=G, time=12.5)
    assert main(["analyze", "clumps", str(run), "--json", "--bootstrap", "20"]) == 0
    out = json.loads(capsys.readouterr().out)
    (row,) = out["snapshots"]
    assert row["clumps"] == len(MASSES) and row["time"] == 12.5
    assert abs(row["mass_in_clumps"] / MASSES.sum() - 1) < 0.01
    cat = ClumpCatalogue.read(run / "clumps" / "clumps_00000.h5")
    assert np.allclose(np.sort(cat.mass), np.sort(row["masses"]))
    assert out["mass_function"]["preferred"] in ("power-law", "truncated-power-law")
    assert out["mass_function"]["power-law"]["n"] == len(MASSES)


def test_analyze_clumps_bad_input_is_one_line(planted, tmp_path, capsys):
    from dustygas.analysis.synthetic import write_snapshot_run
    from dustygas.cli import main
    from dustygas.io.rundir import RunDirectory

    run = write_snapshot_run(tmp_path / "run", planted, cells=CELLS, G=G)
    assert main(["analyze", "clumps", str(run), "--g-tilde", "0"]) == 2
    err = capsys.readouterr().err
    assert "--g-tilde 0.0: must be positive" in err and err.count("\n") == 1
    gas_only = RunDirectory(tmp_path / "gas")
    gas_only.create()
    gas_only.write_snapshot(0, {"rho": np.ones((1, 1, 4))}, {"lx": 1.0, "ly": 1.0, "lz": 1.0, "omega": 1.0})
    assert main(["analyze", "clumps", str(gas_only.path)]) == 2
    err = capsys.readouterr().err
    assert "needs a particle snapshot" in err and err.count("\n") == 1
    assert not (gas_only.path / "clumps").exists()


def test_a_mesh_with_an_inactive_axis_needs_an_explicit_threshold():
    with pytest.raises(UserError, match="give the threshold explicitly"):
        find_clumps(np.zeros((3, 2)), np.zeros((3, 2)), np.ones(2), box=(1.0, 1.0, 1.0), cells=(8, 8, 1), G=1.0)
