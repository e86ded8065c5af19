"""The figure gallery: ``DIR/index.html`` with every figure, its caption, its numbers and checks.

:func:`make_figures` runs registered figures into ``DIR``, evaluates each figure's declared
checks and writes a manifest per figure, ``DIR/gallery/<name>.json`` (files, checks, wall time,
version, errors); :func:`write_index` then writes ``DIR/index.html`` from every manifest in
``DIR/gallery`` -- figures made by earlier ``dustygas reproduce`` calls into the same folder
stay in the gallery. The page is self-contained (inline CSS, no network): each figure sits
beside its caption (the thesis's, :mod:`dustygas.reproduce.captions`, or the one the figure
declares), with a table of its checks (value, expected, tolerance, PASS/FAIL), links to the
data files and a preview of each CSV. A small inline script records how many images loaded in
``<body data-images-ok="N" data-images="M">`` (what the browser test reads).
"""

from __future__ import annotations

import html
import inspect
import json
import sys
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable

from .._version import __version__
from ..io.atomic import atomic_write_text
from . import FigureSpec, _key, get_figure
from .checks import Check, verdict

__all__ = ["FigureRecord", "make_figures", "write_index", "read_manifests"]

MANIFEST_DIR = "gallery"


@dataclass
class FigureRecord:
    """What one figure run produced (the manifest ``DIR/gallery/<name>.json``)."""

    name: str
    summary: str
    caption: str
    thesis_number: str | None
    files: list[str]
    checks: list[dict[str, Any]] = field(default_factory=list)
    wall: float = 0.0
    quick: bool = True
    error: str = ""
    version: str = __version__
    date: str = ""

    @property
    def passed(self) -> bool:
        return not self.error and all(verdict(c) != "FAIL" for c in self.checks)

    def to_dict(self) -> dict[str, Any]:
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def _run_one(spec: FigureSpec, output: Path, quick: bool, extra: dict[str, Any]) -> FigureRecord:
    t0 = time.perf_counter()
    accepted = inspect.signature(spec.function).parameters
    kwargs = {k: v for k, v in extra.items() if k in accepted}
    files: list[Path] = []
    checks: list[Check] = []
    error = ""
    try:
        files = list(spec.function(output, quick=quick, **kwargs))
        if spec.all_checks is not None:
            checks = list(spec.all_checks(output))
    except Exception as exc:  # a broken figure is shown as broken; the others still get made
        error = f"{type(exc).__name__}: {exc}"
        traceback.print_exc(file=sys.stderr)
    rel = []
    for p in files:
        p = Path(p)
        try:
            rel.append(str(p.resolve().relative_to(output.resolve())))
        except ValueError:
            rel.append(str(p))
    return FigureRecord(spec.name, spec.summary, spec.full_caption, spec.thesis_number, rel,
                        [c.to_dict() for c in checks], time.perf_counter() - t0, quick, error,
                        date=time.strftime("%Y-%m-%d %H:%M:%S"))


def make_figures(names: Iterable[str], output: str | Path, quick: bool = True, log=None,
                 **extra: Any) -> list[FigureRecord]:
    """Make the figures ``names`` into ``output``, with checks and manifests; then the index.

    ``extra`` keyword arguments go to the figure functions that take them (``run=RUN``: the
    figures drawn from a simulation use that run directory, ``dustygas reproduce --from RUN``)."""
    output = Path(output)
    specs = [get_figure(n) for n in names]
    (output / MANIFEST_DIR).mkdir(parents=True, exist_ok=True)
    records = []
    for spec in specs:
        record = _run_one(spec, output, quick, extra)
        atomic_write_text(output / MANIFEST_DIR / f"{spec.name}.json", json.dumps(record.to_dict(), indent=1) + "\n")
        records.append(record)
        if log is not None:
            log(record)
    write_index(output)
    return records


def read_manifests(output: str | Path) -> list[FigureRecord]:
    """Every figure manifest in ``output/gallery``, in thesis order."""
    folder = Path(output) / MANIFEST_DIR
    records = []
    for path in folder.glob("*.json") if folder.is_dir() else []:
        data = json.loads(path.read_text(encoding="utf-8"))
        records.append(FigureRecord(**{k: data[k] for k in FigureRecord.__dataclass_fields__ if k in data}))
    return sorted(records, key=lambda r: _key(r.name))


# ------------------------------------------------------------------------------------------ HTML

_CSS = """
body{font-family:Georgia,serif;max-width:1180px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}
h1{font-size:1.6em;margin-bottom:.2em} h2{font-size:1.25em;margin:0 0 .4em}
.summary{color:#555;margin-bottom:1.5em}
section{border-top:1px solid #ccc;padding:1.2em 0;display:grid;grid-template-columns:minmax(0,3fr) minmax(0,2fr);gap:1.4em}
section img{max-width:100%;height:auto;border:1px solid #eee}
figcaption{font-size:.92em;color:#333;margin-top:.4em}
table{border-collapse:collapse;font-size:.85em;width:100%;margin:.4em 0}
td,th{border:1px solid #ddd;padding:.2em .4em;text-align:left;vertical-align:top}
.pass{color:#116611;font-weight:bold} .fail{color:#aa1111;font-weight:bold}
.error{background:#fee;border:1px solid #c66;padding:.5em;white-space:pre-wrap}
details{font-size:.8em;margin:.3em 0} pre{overflow-x:auto;background:#f7f7f7;padding:.4em;max-height:18em}
.meta{font-size:.8em;color:#666}
nav a{margin-right:.6em;font-size:.9em}
"""

_SCRIPT = """
window.addEventListener('load', function () {
  var images = document.querySelectorAll('img.figure');
  var ok = 0;
  images.forEach(function (img) { if (img.complete && img.naturalWidth > 0) { ok += 1; } });
  document.body.setAttribute('data-images', String(images.length));
  document.body.setAttribute('data-images-ok', String(ok));
});
"""


def _esc(text: Any) -> str:
    return html.escape(str(text), quote=True)


def _csv_preview(path: Path, rows: int = 12) -> str:
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return ""
    comments = [ln for ln in lines if ln.startswith("#")]
    data = [ln for ln in lines if ln and not ln.startswith("#")]
    shown = comments + data[: rows + 1] + ([f"... ({len(data) - rows - 1} more rows)"] if len(data) > rows + 1 else [])
    return "<pre>" + _esc("\n".join(shown)) + "</pre>"


def _h5_preview(path: Path) -> str:
    try:
        import h5py

        lines = []
        with h5py.File(path, "r") as f:
            f.visititems(lambda name, obj: lines.append(f"{name}  {obj.shape} {obj.dtype}")
                         if isinstance(obj, h5py.Dataset) else None)
        return "<pre>" + _esc("\n".join(lines)) + "</pre>"
    except Exception:
        return ""


def _checks_table(checks: list[dict[str, Any]]) -> str:
    if not checks:
        return "<p class='meta'>No quantitative checks declared for this figure.</p>"
    rows = ["<table><tr><th>check</th><th>value</th><th>expected</th><th>tolerance</th><th></th></tr>"]
    for c in checks:
        value = c["value"]
        value = f"{value:.6g}" if isinstance(value, (int, float)) else value
        exp = c["expected"]
        exp = f"{exp:.6g}" if isinstance(exp, (int, float)) else exp
        ref = f"<br><span class='meta'>{_esc(c.get('reference', ''))}</span>" if c.get("reference") else ""
        mark = {"PASS": "<span class='pass'>PASS</span>", "FAIL": "<span class='fail'>FAIL</span>",
                "NOT JUDGED": "<span class='meta'>NOT JUDGED</span>"}[verdict(c)]
        rows.append(f"<tr><td>{_esc(c['name'])}{ref}</td><td>{_esc(value)}</td><td>{_esc(exp)}</td>"
                    f"<td>{_esc(c['tolerance'])}</td><td>{mark}</td></tr>")
    rows.append("</table>")
    return "\n".join(rows)


def _section(r: FigureRecord, output: Path) -> str:
    title = f"Figure {r.thesis_number}" if r.thesis_number else r.name
    pngs = [f for f in r.files if f.endswith(".png")]
    data = [f for f in r.files if not f.endswith(".png")]
    images = "".join(f"<img class='figure' src='{_esc(p)}' alt='{_esc(r.name)}: {_esc(r.summary)}'>" for p in pngs)
    parts = [f"<section id='{_esc(r.name)}'><div><h2>{_esc(title)} <span class='meta'>({_esc(r.name)})</span></h2>",
             f"<figure>{images}<figcaption>{_esc(r.caption)}</figcaption></figure></div><div>",
             f"<p><b>{_esc(r.summary)}</b></p>"]
    if r.error:
        parts.append(f"<div class='error'>figure failed: {_esc(r.error)}</div>")
    parts.append("<h3>Checks</h3>" + _checks_table(r.checks))
    if data:
        parts.append("<h3>Numbers behind the figure</h3>")
        for f in data:
            path = output / f
            preview = _csv_preview(path) if f.endswith(".csv") else (_h5_preview(path) if f.endswith(".h5") else "")
            link = f"<a href='{_esc(f)}'>{_esc(f)}</a>"
            parts.append(f"<details><summary>{link}</summary>{preview}</details>" if preview else f"<p>{link}</p>")
    scale = "quick (laptop) scale" if r.quick else "thesis scale"
    parts.append(f"<p class='meta'>{scale}, {r.wall:.1f} s, dustygas {_esc(r.version)}, {_esc(r.date)}</p>")
    parts.append("</div></section>")
    return "\n".join(parts)


def write_index(output: str | Path) -> Path:
    """Write ``output/index.html`` from the manifests in ``output/gallery``."""
    output = Path(output)
    records = read_manifests(output)
    n_checks = sum(len(r.checks) for r in records)
    n_failed = sum(1 for r in records for c in r.checks if verdict(c) == "FAIL")
    n_open = sum(1 for r in records for c in r.checks if verdict(c) == "NOT JUDGED")
    n_errors = sum(1 for r in records if r.error)
    nav = " ".join(f"<a href='#{_esc(r.name)}'>{_esc(r.name)}</a>" for r in records)
    body = "\n".join(_section(r, output) for r in records)
    page = f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>dustygas figure gallery</title>
<link rel="icon" href="data:,">
<style>{_CSS}</style></head>
<body>
<h1>dustygas: the thesis's computational figures</h1>
<p class="summary">{len(records)} figures, {n_checks - n_failed - n_open} of {n_checks} checks passed{f", {n_failed} failed" if n_failed else ""}{f", {n_open} not judged" if n_open else ""}{f", {n_errors} figures failed to build" if n_errors else ""}.
Regenerate with <code>dustygas reproduce --all -o {_esc(output.name)}</code>.</p>
<nav>{nav}</nav>
{body}
<script>{_SCRIPT}</script>
</body></html>
"""
    path = output / "index.html"
    atomic_write_text(path, page)
    return path
