"""``dustygas plot``: images of known fields read back pixel by pixel, every engine, movies (acceptance 4).

A rendered figure is drawn with Agg; the colour of the screen pixel at a data point is mapped back
to a value through the colour map (the nearest of its 256 entries in bytes), so each probe is exact to half a
colour step, (vmax - vmin)/512, plus what the field itself differs from the expected value.
"""

import json
import shutil
import subprocess

import matplotlib
import numpy as np
import pytest
from PIL import Image
from scipy.integrate import quad
from scipy.special import j0

from dustygas.plot.maps import CMAP, image_figure, snapshot_figure
from dustygas.plot.run import history_figure, write_movie
from dustygas.sph.kernels import get_kernel
from foundation._cli import cli

#: the colour map's 256 entries as matplotlib turns them into bytes (truncating, like ``to_rgba(bytes=True)``)
LUT = (matplotlib.colormaps[CMAP](np.linspace(0, 1, 256))[:, :3] * 255).astype(np.uint8).astype(float)


def _probe(fig, points, vmin, vmax):
    """Values shown at data points ``points`` of the first axes of ``fig``."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    rgba = np.asarray(canvas.buffer_rgba())[..., :3].astype(float)
    height = rgba.shape[0]
    ax = fig.axes[0]
    out = []
    for x, y in points:
        px, py = ax.transData.transform((x, y))
        colour = rgba[int(height - py), int(px)]
        idx = int(np.argmin(np.sum((LUT - colour) ** 2, axis=1)))
        out.append(vmin + (idx + 0.5) / 256 * (vmax - vmin))
    return np.array(out)


def _grid(f, nx=32, ny=24, nz=1, lx=2.0, ly=1.5, lz=1.0):
    x = -lx / 2 + (np.arange(nx) + 0.5) * lx / nx
    y = -ly / 2 + (np.arange(ny) + 0.5) * ly / ny
    z = -lz / 2 + (np.arange(nz) + 0.5) * lz / nz if nz > 1 else np.array([0.5])
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    rho = f(X, Y, Z)
    zeros = np.zeros_like(rho)
    arrays = {"rho": rho, "vx": zeros, "vy": zeros, "vz": zeros, "x": x, "y": y, "z": z}
    return arrays, {"time": 1.5, "lx": lx, "ly": ly, "lz": lz}


def test_grid_slice_pixels_show_the_field(tmp_path):
    """rho = 1 + 0.5 sin(pi x) cos(4 pi y / 3) on 32 x 24 cells: at five probes (cell centres) the
    picture shows the cell's value to half a colour step (1/512 of the range)."""
    def f(x, y, z):
        return 1 + 0.5 * np.sin(np.pi * x) * np.cos(4 * np.pi * y / 3)
    arrays, attrs = _grid(f)
    fig = snapshot_figure(arrays, attrs, "rho", vmin=0.5, vmax=1.5)
    points = [(-0.53125, 0.28125), (0.78125, -0.59375), (0.03125, 0.03125), (-0.96875, -0.71875), (0.40625, 0.65625)]
    shown = _probe(fig, points, 0.5, 1.5)
    expected = [f(x, y, 0) for x, y in points]
    np.testing.assert_allclose(shown, expected, rtol=0, atol=1.0 / 512 + 1e-12)
    labels = fig.axes[0].get_xlabel(), fig.axes[0].get_ylabel(), fig.axes[1].get_ylabel()
    assert "code\\ length" in labels[0] and labels[1].startswith("y") and "code\\ mass" in labels[2]


def test_grid_projection_integrates_along_the_axis():
    """3D rho = g(x, y)(1 + cos(2 pi z/Lz)): the projection along z is Lz g(x, y) exactly (the
    cosine sums to zero over the cell centres); probed to half a colour step."""
    def g(x, y):
        return 2 + np.cos(np.pi * x) * np.sin(2 * np.pi * y / 1.5)
    arrays, attrs = _grid(lambda x, y, z: g(x, y) * (1 + np.cos(2 * np.pi * z / 0.8)), nz=8, lz=0.8)
    fig = snapshot_figure(arrays, attrs, "rho", kind="projection", axis="z", vmin=0.8, vmax=2.4)
    points = [(-0.40625, 0.21875), (0.65625, -0.34375), (0.15625, 0.59375)]
    np.testing.assert_allclose(_probe(fig, points, 0.8, 2.4), [0.8 * g(x, y) for x, y in points], atol=1.6 / 512 + 1e-12)
    assert fig.axes[1].get_ylabel() == r"rho [$\mathrm{code\ mass}/\mathrm{code\ length}^{2}$]"
    assert "integrated along z" in fig.axes[0].get_title(loc="left")


def _kernel_transform(k: float, h: float) -> float:
    """2D Fourier transform of the cubic kernel at wavenumber k: 2 pi int W(r) J0(k r) r dr."""
    kern = get_kernel("cubic", 2)
    return quad(lambda r: 2 * np.pi * float(kern.w(r, h)) * j0(k * r) * r, 0, 2 * h, limit=200)[0]


def test_sph_render_pixels_show_the_kernel_smoothed_field():
    """Particles on a 48 x 48 periodic lattice (unit density, h = 1.2 dx) carry A = 1 + 0.5 sin(8 pi x):
    the rendering is the field smoothed with the cubic kernel, 1 + 0.5 W^(k) sin(8 pi x) with W^ its
    Fourier transform (Hankel integral, scipy), probed away from the box edge to half a colour step
    plus 4e-3 (the lattice sum differs from the integral by up to 3.6e-3 on this lattice)."""
    n, h_fact = 48, 1.2
    dx = 1.0 / n
    c = -0.5 + (np.arange(n) + 0.5) * dx
    X, Y = np.meshgrid(c, c, indexing="ij")
    pos = np.zeros((n * n, 3))
    pos[:, 0], pos[:, 1] = X.ravel(), Y.ravel()
    shift = [(sx, sy) for sx in (-1, 0, 1) for sy in (-1, 0, 1)]  # periodic images so the edge is complete
    pos = np.concatenate([pos + [sx, sy, 0] for sx, sy in shift])
    N = len(pos)
    field = 1 + 0.5 * np.sin(8 * np.pi * pos[:, 0])
    arrays = {"pos": pos, "vel": np.zeros((N, 3)), "mass": np.full(N, dx * dx), "h": np.full(N, h_fact * dx),
              "rho": np.ones(N), "u": field, "ptype": np.zeros(N, dtype=np.int8)}
    attrs = {"time": 0.0, "ndim": 2, "kernel": "cubic", "box_lo": [-0.5, -0.5], "box_hi": [0.5, 0.5]}
    fig = snapshot_figure(arrays, attrs, "u", vmin=0.4, vmax=1.6, npix=64)
    w_hat = _kernel_transform(8 * np.pi, h_fact * dx)
    pix = 1.0 / 64
    points = [(-0.5 + (i + 0.5) * pix, -0.5 + (j + 0.5) * pix) for i, j in ((2, 20), (13, 30), (37, 5), (57, 60))]
    expected = [1 + 0.5 * w_hat * np.sin(8 * np.pi * x) for x, _ in points]
    np.testing.assert_allclose(_probe(fig, points, 0.4, 1.6), expected, atol=1.2 / 512 + 4e-3)
    assert 0.9 < w_hat < 0.97  # the smoothing (3-10 % of the amplitude) is far above the tolerance


def test_sph_projection_of_unit_density_column():
    """3D lattice of unit-density particles, 16 layers in z of thickness 1: the column-integrated
    density is 1 (per unit area) away from the edges, to half a colour step plus 1 %."""
    n = 16
    dx = 1.0 / n
    c = -0.5 + (np.arange(n) + 0.5) * dx
    X, Y, Z = np.meshgrid(c, c, c, indexing="ij")
    pos = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    pos = np.concatenate([pos + [sx, sy, 0] for sx in (-1, 0, 1) for sy in (-1, 0, 1)])
    N = len(pos)
    arrays = {"pos": pos, "vel": np.zeros((N, 3)), "mass": np.full(N, dx**3), "h": np.full(N, 1.2 * dx),
              "rho": np.ones(N), "ptype": np.zeros(N, dtype=np.int8)}
    attrs = {"time": 0.0, "ndim": 3, "kernel": "cubic", "box_lo": [-0.5] * 3, "box_hi": [0.5] * 3}
    fig = snapshot_figure(arrays, attrs, "rho", kind="projection", axis="z", vmin=0.5, vmax=1.5, npix=32)
    points = [(-0.2, 0.1), (0.3, -0.3), (0.0, 0.0)]
    np.testing.assert_allclose(_probe(fig, points, 0.5, 1.5), 1.0, atol=1.0 / 512 + 0.01)


def test_history_figure_labels_units(grid_run):
    fig = history_figure(grid_run, ["mass", "kinetic_energy"])
    ylabels = [ax.get_ylabel() for ax in fig.axes if ax.get_visible()]
    assert ylabels[0].startswith("mass") and "code\\ mass" in ylabels[0]
    assert "code\\ time" in fig.axes[0].get_xlabel() or "code\\ time" in fig.axes[-1].get_xlabel()


@pytest.mark.parametrize("which,field,history", [("grid_run", "rho", True), ("particle_run", "rho_p", True),
                                                 ("particle_run", "particles", False),
                                                 ("sph_run", "dust_fraction", True), ("sph2d_run", "rho", True)],
                         ids=["grid_run-rho", "particle_run-rho_p", "particle_run-particles", "sph_run-dust_fraction",
                              "sph2d_run-rho"])
def test_plot_command_on_every_engine(which, field, history, request, tmp_path, capsys):
    """``dustygas plot`` (in-process) writes the history and the snapshot image for runs of the grid,
    particle-grid and SPH (1D and 2D) engines. The particle run's history (36 panels: 9 CPU-s of
    matplotlib, 2026-12-03) is drawn once, with ``rho_p``; its ``particles`` image comes alone
    (``--no-history``)."""
    from dustygas.cli import main

    run = request.getfixturevalue(which)
    assert main(["plot", str(run), "--field", field, "-o", str(tmp_path)] + ([] if history else ["--no-history"])) == 0
    written = capsys.readouterr().out.split()
    names = [p.rsplit("/", 1)[-1] for p in written]
    if history:
        assert names[0] == "history.png"
    else:
        assert names == [f"snap_00001_{field}.png"]
    for path in written:
        with Image.open(path) as im:
            assert im.format == "PNG" and im.size[0] > 300 and im.size[1] > 200
            pixels = np.asarray(im.convert("RGB")).reshape(-1, 3)
            assert len(np.unique(pixels, axis=0)) > 20  # something drawn, not blank


def test_plot_command_errors_are_one_line(grid_run, tmp_path):
    bad = cli("plot", str(grid_run), "--field", "temperature", cwd=tmp_path)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "choose one of" in bad.stderr
    bad = cli("plot", str(tmp_path), cwd=tmp_path)
    assert bad.returncode == 2 and "not a run directory" in bad.stderr


def test_movie_gif_has_one_frame_per_snapshot(grid_run, tmp_path):
    out = write_movie(grid_run, tmp_path / "rho.gif", "rho", fps=4)
    with Image.open(out) as im:
        assert im.n_frames == 3 and im.size[0] > 200


def test_movie_mp4_plays(grid_run, tmp_path, capsys):
    """ffmpeg (installed by .ci/run) writes the mp4; ffprobe decodes every frame of its h264 stream."""
    assert shutil.which("ffprobe"), "ffmpeg is a system dependency of the movie writer (apt-get install ffmpeg)"
    from dustygas.cli import main

    assert main(["plot", str(grid_run), "--no-history", "--movie", "rho.mp4", "-o", str(tmp_path)]) == 0
    probe = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                            "stream=codec_name,nb_read_frames,width,height", "-of", "json", str(tmp_path / "rho.mp4")],
                           capture_output=True, text=True, timeout=60)
    stream = json.loads(probe.stdout)["streams"][0]
    assert stream["codec_name"] == "h264" and int(stream["nb_read_frames"]) == 3 and stream["width"] > 200
