"""The gallery: each figure beside its caption, its numbers and its checks (acceptance 3)."""

import json
import os
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

import dustygas.reproduce as registry
from dustygas.plot import Column, new_figure, save_figure
from dustygas.reproduce import FigureSpec, figure_names, get_figure
from dustygas.reproduce.captions import THESIS_CAPTIONS
from dustygas.reproduce.checks import compare, not_judged
from dustygas.reproduce.gallery import make_figures, read_manifests


def line_figure(slope: float, stem: str):
    """A figure function that draws ``y = slope x`` into ``stem.png``, with its CSV."""
    def line(output: Path, quick: bool = True):
        fig, ax = new_figure()
        x = np.linspace(0, 1, 11)
        ax.plot(x, slope * x)
        return save_figure(fig, output / f"{stem}.png", [Column("x", x, "1"), Column("y", slope * x, "1")])

    return line


@pytest.fixture
def failing_figure():
    """A registered figure whose check fails (a straight line whose slope is not the claimed 2)."""
    def checks(output: Path):
        from dustygas.plot import read_table

        d = read_table(output / "test_line.csv")
        return [compare("slope", np.polyfit(d["x"], d["y"], 1)[0], 2.0, rtol=1e-6, reference="a claim")]

    registry.figure("test-line", "a line with slope 3", caption="A test figure <b>caption</b> & more.",
                    checks=checks)(line_figure(3.0, "test_line"))
    yield "test-line"
    registry._FIGURES.pop("test-line")


def test_every_thesis_figure_name_gets_its_caption():
    for name in figure_names():
        spec = get_figure(name)
        if spec.thesis_number:
            assert spec.full_caption == THESIS_CAPTIONS[spec.thesis_number]
    assert get_figure("fig3.5").full_caption.startswith("Velocity of the radial drift of dust particles")
    assert FigureSpec("fig4.3-settling", "s", lambda o, quick=True: [], "1 s").full_caption == "s"


def test_index_shows_figures_captions_checks_and_numbers(tmp_path, failing_figure, capsys):
    """fig3.5 (checks pass) and a figure whose check fails: the page holds both images, the thesis
    caption (escaped), each check with value and verdict, and a preview of the data; the command's
    exit status is 1 because one check failed."""
    from dustygas.cli import main

    status = main(["reproduce", "fig3.5", failing_figure, "-o", str(tmp_path)])
    assert status == 1
    err = capsys.readouterr().err
    assert "FAIL slope: 3 vs 2" in err and "PASS peak of -v_r/v_K" in err
    page = (tmp_path / "index.html").read_text()
    assert page.count("<img class='figure'") == 2 and "src='fig3_5.png'" in page and "src='test_line.png'" in page
    assert THESIS_CAPTIONS["3.5"].replace("'", "&#x27;") in page
    assert "A test figure &lt;b&gt;caption&lt;/b&gt; &amp; more." in page
    assert re.search(r"slope.*?<td>3</td><td>2</td><td>rtol 1e-06</td><td><span class='fail'>FAIL", page, re.S)
    assert re.search(r"peak of -v_r/v_K.*?<span class='pass'>PASS", page, re.S)
    assert "fig3_5.csv" in page and "tau_s,minus_vr_over_vK" in page
    assert "2 of 3 checks passed, 1 failed" in page
    records = {r.name: r for r in read_manifests(tmp_path)}
    assert records["fig3.5"].passed and not records[failing_figure].passed
    assert json.loads((tmp_path / "gallery" / "fig3.5.json").read_text())["checks"][0]["passed"] is True


def test_a_check_not_judged_is_neither_passed_nor_failed(tmp_path, capsys):
    """A figure with one passing check and one the data cannot decide: the command exits 0, prints
    NOT JUDGED with the reason, and the page counts it apart ("1 of 2 checks passed, 1 not judged")."""
    from dustygas.cli import main

    def checks(output: Path):
        return [compare("slope", 2.0, 2.0, rtol=1e-6), not_judged("steady", 1.5, "too short a run")]

    registry.figure("test-open", "a line", checks=checks)(line_figure(2.0, "test_line2"))
    try:
        status = main(["reproduce", "test-open", "-o", str(tmp_path)])
    finally:
        registry._FIGURES.pop("test-open")
    assert status == 0
    assert "NOT JUDGED steady: 1.5 (too short a run)" in capsys.readouterr().err
    page = (tmp_path / "index.html").read_text()
    assert "1 of 2 checks passed, 1 not judged" in page and "NOT JUDGED" in page
    (record,) = read_manifests(tmp_path)
    assert record.passed and record.checks[1]["judged"] is False and record.checks[1]["passed"] is False


def test_gallery_accumulates_and_a_broken_figure_is_shown(tmp_path):
    def broken(output, quick=True):
        raise RuntimeError("no data")

    registry.figure("test-broken", "a figure that fails")(broken)
    try:
        make_figures(["fig3.5"], tmp_path)
        records = make_figures(["test-broken"], tmp_path)
    finally:
        registry._FIGURES.pop("test-broken")
    assert records[0].error == "RuntimeError: no data" and not records[0].passed
    page = (tmp_path / "index.html").read_text()
    assert "fig3_5.png" in page and "figure failed: RuntimeError: no data" in page  # both made into DIR


CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update",
         "--disable-sync", "--no-first-run", "--enable-logging=stderr", "--v=0"]


def _chromium(page: Path, *args: str) -> subprocess.CompletedProcess:
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *args, page.resolve().as_uri()],
                              capture_output=True, text=True, timeout=180)


def browser_check(folder: Path, expected: int) -> None:
    """Open ``folder/index.html`` in headless Chromium: no console errors, ``expected`` images all
    loaded (the page's own count after its load event), and a screenshot with the figures in it."""
    assert CHROMIUM, "the gallery test needs Debian's chromium (installed by .ci/run)"
    page = folder / "index.html"
    dom = _chromium(page, "--virtual-time-budget=10000", "--dump-dom")
    assert dom.returncode == 0, dom.stderr[-2000:]
    assert f'data-images="{expected}"' in dom.stdout and f'data-images-ok="{expected}"' in dom.stdout
    console = [ln for ln in dom.stderr.splitlines() if "CONSOLE" in ln or "Uncaught" in ln]
    assert not console, console
    shot = folder / "screenshot.png"
    grab = _chromium(page, "--window-size=1280,2400", "--hide-scrollbars", f"--screenshot={shot}")
    assert grab.returncode == 0 and shot.exists(), grab.stderr[-2000:]
    from PIL import Image

    with Image.open(shot) as im:
        pixels = np.asarray(im.convert("RGB")).reshape(-1, 3)
    colours = len(np.unique(pixels[::7], axis=0))
    assert colours > 200, f"the screenshot has {colours} colours: no figures drawn"


@pytest.mark.slow
def test_full_gallery_opens_in_headless_chromium(tmp_path):
    """``dustygas reproduce --all -o DIR``: every registered figure is in DIR/index.html, every
    check passes but one that the quick runs cannot decide (the steady layer of Fig 1.13 needs a
    run of 20 orbits, the quick one has 10), and the page opens in headless Chromium without
    console errors with every image loaded."""
    from dustygas.cli import main
    from dustygas.reproduce.checks import verdict

    names = figure_names()
    status = main(["reproduce", "--all", "-o", str(tmp_path)])
    records = read_manifests(tmp_path)
    assert [r.name for r in records] == names
    failed = [(r.name, r.error, [c for c in r.checks if verdict(c) == "FAIL"]) for r in records if not r.passed]
    assert status == 0 and not failed, failed
    open_checks = [(r.name, c["name"]) for r in records for c in r.checks if verdict(c) == "NOT JUDGED"]
    assert open_checks == [("fig1.13", "Hp_0: mean scale height, second half of the window / first half")]
    expected = sum(1 for r in records for f in r.files if f.endswith(".png"))
    browser_check(tmp_path, expected)


def test_small_gallery_opens_in_headless_chromium(tmp_path):
    """Two figures (seconds): the browser sees both images load and no console errors."""
    make_figures(["fig3.5", "fig3.1"], tmp_path)
    browser_check(tmp_path, 2)
    os.remove(tmp_path / "screenshot.png")
