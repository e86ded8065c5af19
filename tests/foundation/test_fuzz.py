"""Fuzzing ``dustygas run`` with bad input (hypothesis and tables): 241 commands per run (counted;
hypothesis does not repeat a draw it has tried, so a few budgets are not used up).

Wrong types, out-of-range values, NaN and infinities for every parameter of every registered
problem; unknown keys and malformed ``--set``; malformed and mis-shaped TOML files; impossible
output paths and bad options; run directories with damaged checkpoints (truncated, overwritten
values, empty, a directory, another file) or an edited ``config.toml``. Every case must be
refused with exit status 2, exactly one line on stderr (``dustygas: error: ...``), no
traceback, and the files on disk exactly as they were. The command runs in-process, so a case
costs milliseconds; ``derandomize`` makes every CI run try the same cases. Fixed lists
(options, paths, TOML shapes, kinds of damage) are parametrized so that each entry runs; the
values inside them are drawn.
"""

import contextlib
import io
import math
import os
import shutil
import tempfile
from pathlib import Path

import h5py
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import _toyproblem  # noqa: F401  (registers toy-oscillator)
from dustygas import api
from dustygas.cli import main
from dustygas.config import dump_toml
from dustygas.io.rundir import RunDirectory
from dustygas.problems import all_problems


def fuzz(n):
    return settings(max_examples=n, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much,
                                           HealthCheck.function_scoped_fixture])


def _listing(root: Path) -> list:
    out = []
    for p in sorted(root.rglob("*")):
        if p.is_file() and p.name != ".lock":
            out.append((str(p.relative_to(root)), p.read_bytes()))
        else:
            out.append((str(p.relative_to(root)), None))
    return out


def assert_refused(argv, cwd: Path) -> str:
    """Run the CLI in ``cwd``: exit 2, one line, no traceback, no file changed."""
    before = _listing(cwd)
    err = io.StringIO()
    old = os.getcwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            rc = main(list(argv))
    finally:
        os.chdir(old)
    text = err.getvalue()
    lines = [ln for ln in text.splitlines() if ln.strip()]
    assert rc == 2, (argv, text)
    assert len(lines) == 1 and lines[0].startswith("dustygas: error: "), (argv, text)
    assert "Traceback" not in text
    assert _listing(cwd) == before, argv
    return lines[0]


@pytest.fixture(scope="module")
def sandbox(tmp_path_factory):
    """A working directory with a file ``afile`` (for paths through a file) and a finished run."""
    root = tmp_path_factory.mktemp("fuzz")
    (root / "afile").write_text("not a directory\n")
    (root / "binary.toml").write_bytes(b"\xff\xfe\x00garbage\x80")
    (root / "adir").mkdir()
    api.run("toy-oscillator", output=root / "done", set=["run.tlim=0.05"])
    return root


# ----------------------------------------------------------------------------- parameter values

PARAMS = [(name, section, key, p) for name, prob in all_problems().items() for section, table in prob.schema.items()
          for key, p in table.items() if not (p.type == "str" and p.choices is None)]
WORD = st.from_regex(r"[a-z][a-z_]{0,8}", fullmatch=True).filter(lambda w: w not in ("inf", "nan", "true", "false"))
FINITE = dict(allow_nan=False, allow_infinity=False, width=64)


def _toml(x) -> str:
    return dump_toml({"s": {"v": x}}).splitlines()[1].split(" = ", 1)[1]


def bad_values(p):
    """TOML texts of values that ``p`` must refuse."""
    numeric = p.type in ("float", "int", "float_list", "int_list")
    options = [st.just("[[1], 2]"), st.just("{ a = 1 }")]
    if p.type in ("str", "str_list"):
        options.append(WORD.filter(lambda w: w not in p.choices).map(lambda w: f'"{w}"'))
        options.append(st.floats(**FINITE).map(_toml))
    if p.type == "bool":
        options += [st.integers().map(str), WORD.map(lambda w: f'"{w}"'), st.just("[true]")]
    if numeric:
        options += [WORD.map(lambda w: f'"{w}"'), st.just("nan"), st.just("true"), st.just('"12"')]
        if not p.allow_inf:
            options += [st.just("inf"), st.just("-inf")]
        if p.choices is not None:
            options.append(st.integers(-1000, 1000).filter(lambda v: v not in p.choices).map(str))
        if p.type.startswith("int"):
            options.append(st.floats(min_value=-1e12, max_value=1e12, **FINITE).filter(lambda x: not x.is_integer())
                           .map(_toml))
            options.append(st.integers(min_value=2**63, max_value=2**300).map(lambda n: str(n * -1 if n % 2 else n)))
        # a bound computed from the rest of the configuration (config.Limit) has no one value to
        # step over here; its refusals are tested in tests/problems/test_registry.py
        if isinstance(p.min, (int, float)):
            if p.type.startswith("int"):
                below = st.integers(max_value=int(math.ceil(p.min)) - (0 if p.min_open and p.min == int(p.min) else 1),
                                    min_value=-(2**62)).filter(lambda v: v < p.min or (p.min_open and v == p.min))
            else:
                below = st.floats(max_value=p.min, exclude_max=not p.min_open, min_value=-1e300, **FINITE)
            options.append(below.map(_toml))
        if isinstance(p.max, (int, float)):
            if p.type.startswith("int"):
                above = st.integers(min_value=int(math.floor(p.max)) + 1, max_value=2**62)
            else:
                above = st.floats(min_value=p.max, exclude_min=not p.max_open, max_value=1e300, **FINITE)
            options.append(above.map(_toml))
        if p.type.endswith("_list"):
            options.append(st.just("[]"))
            if p.length is not None:
                good = _toml(p.default[0] if isinstance(p.default, list) else p.default)
                options.append(st.just("[" + ", ".join([good] * (p.length + 1)) + "]"))
    return st.one_of(options)


@fuzz(110)
@given(st.data())
def test_bad_parameter_values(sandbox, data):
    name, section, key, p = data.draw(st.sampled_from(PARAMS), label="parameter")
    value = data.draw(bad_values(p), label="value")
    if data.draw(st.booleans(), label="from a TOML file"):
        work = Path(tempfile.mkdtemp(dir=sandbox))
        (work / "p.toml").write_text(f"[{section}]\n{key} = {value}\n")
        line = assert_refused(["run", name, "-o", "out", "-c", "p.toml"], work)
        shutil.rmtree(work)
    else:
        line = assert_refused(["run", name, "-o", "out", "--set", f"{section}.{key}={value}"], sandbox)
    assert f"{section}.{key}" in line or "invalid TOML" in line or "not valid TOML" in line


# ----------------------------------------------------------------------------- keys and --set shapes

SCHEMA = all_problems()["si-linA"].schema
IDENT = st.from_regex(r"[a-z][a-z0-9_]{0,10}", fullmatch=True)


@fuzz(25)
@given(st.data())
def test_unknown_keys_and_malformed_overrides(sandbox, data):
    kind = data.draw(st.sampled_from(["key", "section", "shape"]))
    if kind == "key":
        section = data.draw(st.sampled_from(sorted(SCHEMA)))
        key = data.draw(IDENT.filter(lambda k: k not in SCHEMA[section]))
        text = f"{section}.{key}=1"
    elif kind == "section":
        text = data.draw(IDENT.filter(lambda s: s not in SCHEMA and s != "dustygas")) + ".nx=1"
    else:
        text = data.draw(st.sampled_from(["grid.nx", "=5", ".nx=1", "grid.=1", "grid..nx=1", "a.b.c=1",
                                          "grid.nx=[1,", "grid.nx={", 'grid.nx="x', "grid.nx=1\nrun.tlim=2"]))
    assert_refused(["run", "si-linA", "-o", "out", "--set", text], sandbox)


# ----------------------------------------------------------------------------- TOML shapes

TOML_SHAPES = [
    "[{s}\n{k} = 1\n", "[{s}]\n{k} = = 1\n", "[{s}]\n{k} = [1, 2\n", "[{s}]\n{k} = 'abc\n", "[[{s}]]\n{k} = 1\n",
    "{s} = 5\n", "[{s}]\n{k} = {{ a = 1 }}\n", "[{s}.{k}]\nx = 1\n", "[{s}]\n{k} = 1\n{k} = 2\n",
    "[{s}]\n{k} = 1{z}\n", "[{s}]\n{k} = " + "[" * 600 + "]" * 600 + "\n", "{k}\n", "[{s}]\n{k} = 1979-05-27\n",
    "[{s}]\n{k} = \0\n", "[{s}]\n[{s}]\n",
]


@pytest.mark.parametrize("shape", TOML_SHAPES)
@fuzz(2)
@given(where=st.sampled_from([(s, k) for s in SCHEMA for k in SCHEMA[s]]),
       zeros=st.integers(min_value=400, max_value=6000))  # 1e400 and more: no float, no int64
def test_malformed_and_misshaped_toml_files(sandbox, shape, where, zeros):
    work = Path(tempfile.mkdtemp(dir=sandbox))
    (work / "p.toml").write_text(shape.format(s=where[0], k=where[1], z="0" * zeros))
    assert_refused(["run", "si-linA", "-o", "out", "-c", "p.toml"], work)
    shutil.rmtree(work)


# ----------------------------------------------------------------------------- paths and options

BAD_ARGS = [
    ["-o", ""], ["-o", "   "], ["-o", "afile"], ["-o", "afile/sub"], ["-o", "afile/a/b"], ["-o", "/proc/dustygas/run"],
    ["-o", "x" * 300], ["-o", "a\0b"], ["-o", "done"], ["-c", "missing.toml"], ["-c", "adir"], ["-c", "binary.toml"],
    ["-c", "a\0b.toml"], ["--threads", "0"], ["--threads", "-3"], ["--threads", "two"], ["--threads", "1.5"],
    ["--walltime", "nan"], ["--walltime", "-1"], ["--walltime", "inf"], ["--walltime", "abc"], ["--frobnicate"],
    ["--restart", "done"], ["--overwrite", "--restart", "done"],
]


BAD_COMMANDS = [["run", "toy-oscillator", *a] for a in BAD_ARGS] + [
    ["run"], ["run", "--restart", ""], ["run", "--restart", "nowhere"], ["run", "--restart", "afile"],
    ["run", "--restart", "adir"], ["run", "--restart", "a\0b"],
]


@pytest.mark.parametrize("argv", BAD_COMMANDS, ids=lambda a: " ".join(a[1:]).replace("\0", "NUL")[:40])
def test_bad_paths_and_options(sandbox, argv):
    assert_refused(argv, sandbox)


@fuzz(10)
@given(WORD.filter(lambda w: w not in all_problems()))
def test_unknown_problem_names(sandbox, name):
    assert "unknown problem" in assert_refused(["run", name, "-o", "out"], sandbox)


# ----------------------------------------------------------------------------- damaged run directories

def _damage_checkpoint(run: Path, how: str, data) -> None:
    (chk,) = RunDirectory(run).checkpoints()
    raw = chk.read_bytes()
    if how == "truncate":
        chk.write_bytes(raw[: data.draw(st.integers(min_value=0, max_value=len(raw) - 1), label="length")])
    elif how == "values":
        with h5py.File(chk, "r") as f:
            name = data.draw(st.sampled_from(sorted(k for k in ("engine/x", "engine/v", "history/time", "history/x0")
                                                    if k in f)), label="dataset")
            offset, size = f[name].id.get_offset(), f[name].id.get_storage_size()
        start = data.draw(st.integers(min_value=offset, max_value=offset + size - 1), label="offset")
        masks = data.draw(st.lists(st.integers(1, 255), min_size=1, max_size=8), label="xor")
        b = bytearray(raw)
        for i, m in enumerate(masks):
            if start + i < offset + size:
                b[start + i] ^= m
        chk.write_bytes(bytes(b))
    elif how == "garbage":
        chk.write_bytes(data.draw(st.binary(min_size=0, max_size=4096), label="bytes"))
    elif how == "directory":
        chk.unlink()
        chk.mkdir()
    elif how == "snapshot":
        shutil.copy(RunDirectory(run).snapshots()[-1], chk)
    elif how == "none":
        chk.unlink()


def _damage_config(run: Path, how: str, data) -> list:
    config = run / "config.toml"
    text = config.read_text()
    if how == "physics":
        config.write_text(text.replace("omega = 1.0", f"omega = {data.draw(st.floats(2.0, 9.0), label='omega')!r}"))
    elif how == "deleted":
        key = data.draw(st.sampled_from(["n = 16", "omega = 1.0", "cfl = 0.01", 'scheme = "leapfrog"']))
        config.write_text(text.replace(key + "\n", ""))
    elif how == "unknown":
        config.write_text(text.replace("[problem]\n", "[problem]\nomgea = 2.0\n"))
    elif how == "garbage":
        config.write_text(text[: data.draw(st.integers(0, len(text) - 2), label="cut")] + "[[\n")
    elif how == "problem":
        other = data.draw(st.sampled_from(["si-linA", "not-a-problem", ""]), label="problem")
        config.write_text(text.replace('problem = "toy-oscillator"', f'problem = "{other}"'))
    elif how == "missing":
        config.unlink()
    elif how == "set":
        key = data.draw(st.sampled_from(["problem.n=17", "problem.omega=2", "problem.scheme=leapfrog2", "grid.nx=4"]))
        return ["--set", key]
    return []


CHECKPOINT_DAMAGE = ["truncate", "values", "garbage", "directory", "snapshot", "none"]
CONFIG_DAMAGE = ["physics", "deleted", "unknown", "garbage", "problem", "missing", "set"]


@pytest.mark.parametrize("how", [f"checkpoint:{h}" for h in CHECKPOINT_DAMAGE] + [f"config:{h}" for h in CONFIG_DAMAGE])
@fuzz(4)
@given(data=st.data())
def test_damaged_checkpoints_and_edited_configurations(sandbox, how, data):
    work = Path(tempfile.mkdtemp(dir=sandbox))
    run = work / "run"
    shutil.copytree(sandbox / "done", run)
    what, how = how.split(":")
    extra = _damage_checkpoint(run, how, data) if what == "checkpoint" else _damage_config(run, how, data)
    line = assert_refused(["run", "--restart", "run", "--set", "run.tlim=0.1", *(extra or [])], work)
    assert "checkpoint" in line or "config.toml" in line or "--set" in line or "problem" in line, line
    shutil.rmtree(work)
