"""Sphinx extension: pages generated from the code, and executed tutorials.

At ``builder-inited`` it writes ``docs/generated/``:

* ``problems/<name>.rst`` -- one page per registered problem: its summary, the docstring of its
  module and a table per schema section with every parameter (default, units, allowed values,
  description), each with a target ``param-<problem>-<section>-<key>``;
* ``config.rst`` -- the configuration reference: every ``section.key`` of every problem, with the
  problems that have it and their defaults;
* ``schema.rst`` -- the output schema tables of :mod:`dustygas.io.schema`;
* ``figures.rst`` -- every registered figure with its caption and whether it declares checks;
* ``equations.rst`` -- every thesis equation number cited in a docstring, with the objects citing it.

The ``tutorial`` directive runs a script (``.. tutorial:: tutorials/x.py``) in a fresh folder with
``DUSTYGAS_TUTORIAL_OUT`` set, and shows its code, its output and the PNG files it wrote there.
A script that fails fails the build.
"""

from __future__ import annotations

import contextlib
import importlib
import inspect
import io
import os
import pkgutil
import re
import runpy
import shutil
import tempfile
from collections import defaultdict
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive, directives

HERE = Path(__file__).resolve().parent.parent


def _rst_escape(text: str) -> str:
    return str(text).replace("\\", "\\\\").replace("*", "\\*").replace("`", "\\`").replace("|", "\\|").replace("_", "\\_")


def _literal(text: str) -> str:
    text = str(text)
    return f"``{text}``" if text else ""


def _table(header: list[str], rows: list[list[str]]) -> list[str]:
    out = [".. list-table::", "   :header-rows: 1", "   :widths: auto", ""]
    for row in [header] + rows:
        out.append("   * - " + (row[0] or " "))
        out += [f"     - {cell or ' '}" for cell in row[1:]]
    out.append("")
    return out


def _write(path: Path, lines: list[str]) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    text = "\n".join(lines) + "\n"
    if not path.exists() or path.read_text(encoding="utf-8") != text:
        path.write_text(text, encoding="utf-8")


def _doc_of(obj) -> str:
    return inspect.cleandoc(obj.__doc__ or "")


def problem_pages(out: Path) -> None:
    """One page per problem and the configuration reference."""
    from dustygas.config import _toml_value
    from dustygas.problems import all_problems

    problems = all_problems()
    index = ["Problems", "========", "",
             "Every registered problem, generated from its schema (``dustygas problems NAME`` prints the same).", "",
             ".. toctree::", "   :maxdepth: 1", ""]
    index += [f"   {name}" for name in problems]
    _write(out / "problems" / "index.rst", index)
    params = defaultdict(list)
    for name, prob in problems.items():
        lines = [f".. _problem-{name}:", "", name, "=" * len(name), "", _rst_escape(prob.summary), ""]
        module = inspect.getmodule(type(prob))
        lines += [f"Defined in :mod:`{module.__name__}`." if module else "", ""]
        for section, table in prob.schema.items():
            lines += [section, "-" * len(section), ""]
            rows = []
            for key, p in table.items():
                params[(section, key)].append((name, _toml_value(p.default)))
                target = f"param-{name}-{section}-{key}"
                allowed = p.allowed() if (p.choices is not None or p.min is not None or p.max is not None
                                          or p.length is not None) else ""
                rows.append([f":ref:`{section}.{key} <{target}>`", _literal(_toml_value(p.default)), _rst_escape(p.units),
                             _rst_escape(allowed), _rst_escape(p.doc)])
            lines += _table(["parameter", "default", "units", "allowed", "description"], rows)
            for key in table:  # targets (rendered as anchors) for every parameter
                lines += [f".. _param-{name}-{section}-{key}:", "", f"``{section}.{key}``", "", ""]
        _write(out / "problems" / f"{name}.rst", lines)
    cfg = ["Configuration reference", "=======================", "",
           "Every parameter of every problem, generated from the schemas. Parameters are set in TOML",
           "files (``-c FILE``) or with ``--set section.key=value``; each problem's page has the full",
           "description, units and allowed values.", ""]
    rows = []
    for (section, key), users in sorted(params.items()):
        defaults = sorted({d for _, d in users})
        who = ", ".join(f":ref:`{n} <param-{n}-{section}-{key}>`" for n, _ in users)
        rows.append([f"``{section}.{key}``", ", ".join(_literal(d) for d in defaults[:4])
                     + (" ..." if len(defaults) > 4 else ""), who])
    cfg += _table(["parameter", "defaults", "problems"], rows)
    _write(out / "config.rst", cfg)


def schema_page(out: Path) -> None:
    from dustygas.io import schema

    lines = []
    rows = [[f"``{k}``", f"``{q.units}``", _rst_escape(q.description)] for k, q in schema.SNAPSHOT_FIELDS.items()]
    lines += ["Snapshot datasets", "^^^^^^^^^^^^^^^^^", ""] + _table(["dataset", "units", "meaning"], rows)
    rows = [[f"``{k}``", f"``{q.units}``", _rst_escape(q.description)] for k, q in schema.HISTORY_COLUMNS.items()]
    rows += [[f"``{p}`` (pattern)", f"``{q.units}``", _rst_escape(q.description)] for p, q in schema.HISTORY_PATTERNS]
    lines += ["History columns", "^^^^^^^^^^^^^^^", ""] + _table(["column", "units", "meaning"], rows)
    _write(out / "schema.rst", lines)


def figures_page(out: Path) -> None:
    from dustygas.reproduce import figure_names, get_figure

    lines = []
    for name in figure_names():
        spec = get_figure(name)
        title = f"{name}: {spec.summary}"
        lines += [_rst_escape(title), "^" * len(_rst_escape(title)), "",
                  f"*Caption.* {_rst_escape(spec.full_caption)}", "",
                  f"Cost at quick scale: {_rst_escape(spec.cost)}. Checks: "
                  + ("declared (shown in the gallery)." if spec.all_checks else "none declared."), ""]
    _write(out / "figures.rst", lines)


_EQ = re.compile(r"\beq(?:uation)?s?\.?\s+((?:\d+\.\d+[a-z]?)(?:\s*(?:-|–|,|and)\s*\d+\.\d+[a-z]?)*)", re.IGNORECASE)


def equations_page(out: Path) -> None:
    """Index of thesis equation numbers cited in docstrings of modules, classes and functions."""
    import dustygas

    cited = defaultdict(set)
    for info in pkgutil.walk_packages(dustygas.__path__, "dustygas."):
        if info.name.endswith("__main__") or ".cli" in info.name:
            continue
        module = importlib.import_module(info.name)
        objects = [(info.name, module, ":mod:")]
        for attr, obj in vars(module).items():
            if (inspect.isfunction(obj) or inspect.isclass(obj)) and getattr(obj, "__module__", "") == info.name \
                    and not attr.startswith("_"):
                objects.append((f"{info.name}.{attr}", obj, ":class:" if inspect.isclass(obj) else ":func:"))
        for qualname, obj, role in objects:
            for m in _EQ.finditer(_doc_of(obj)):
                for number in re.findall(r"\d+\.\d+", m.group(1)):
                    cited[number].add(f"{role}`{qualname}`")
    key = lambda n: tuple(int(p) for p in n.split("."))  # noqa: E731
    rows = [[f"{n}", ", ".join(sorted(cited[n]))] for n in sorted(cited, key=key)]
    lines = ["Thesis equation index", "=====================", "",
             "Every thesis equation number cited in a docstring of dustygas, with the modules, classes",
             "and functions citing it (generated from the code: the formula lives where the first",
             "function or the module listed implements it).", ""]
    lines += _table(["thesis eq.", "cited by"], rows)
    _write(out / "equations.rst", lines)


def generate(app) -> None:
    out = Path(app.srcdir) / "generated"
    problem_pages(out)
    schema_page(out)
    figures_page(out)
    equations_page(out)


class TutorialDirective(Directive):
    """``.. tutorial:: tutorials/script.py`` with ``:title:``: code, output and figures of a run."""

    required_arguments = 1
    option_spec = {"title": directives.unchanged}

    def run(self):
        env = self.state.document.settings.env
        src = Path(env.srcdir) / self.arguments[0]
        env.note_dependency(str(src))
        figdir = Path(env.srcdir) / "generated" / "tutorials" / src.stem
        shutil.rmtree(figdir, ignore_errors=True)
        figdir.mkdir(parents=True)
        stdout = io.StringIO()
        cwd = os.getcwd()
        old = os.environ.get("DUSTYGAS_TUTORIAL_OUT")
        with tempfile.TemporaryDirectory() as tmp:
            os.environ["DUSTYGAS_TUTORIAL_OUT"] = str(figdir)
            os.chdir(tmp)
            try:
                with contextlib.redirect_stdout(stdout):
                    runpy.run_path(str(src), run_name="__main__")
            finally:
                os.chdir(cwd)
                if old is None:
                    os.environ.pop("DUSTYGAS_TUTORIAL_OUT", None)
                else:
                    os.environ["DUSTYGAS_TUTORIAL_OUT"] = old
        title = self.options.get("title", src.stem)
        section = nodes.section(ids=[nodes.make_id(src.stem)])
        section += nodes.title(text=title)
        code = src.read_text(encoding="utf-8")
        block = nodes.literal_block(code, code, language="python")
        section += nodes.paragraph(text=f"docs/{self.arguments[0]}:")
        section += block
        if stdout.getvalue().strip():
            section += nodes.paragraph(text="Output:")
            section += nodes.literal_block(stdout.getvalue(), stdout.getvalue())
        for png in sorted(figdir.glob("*.png")):
            section += nodes.image(uri="/" + str(png.relative_to(env.srcdir)), alt=png.stem, width="80%")
        return [section]


def setup(app):
    app.connect("builder-inited", generate)
    app.add_directive("tutorial", TutorialDirective)
    return {"version": "1", "parallel_read_safe": False}
