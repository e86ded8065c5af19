"""The command line: one-line errors with exit status 2 that leave nothing on disk."""

import re

import pytest

from ._cli import cli


def _assert_one_line_error(proc, fragment):
    assert proc.returncode == 2, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1, proc.stderr
    assert lines[0].startswith("dustygas: error:")
    assert fragment in lines[0]
    assert "Traceback" not in proc.stderr


@pytest.mark.parametrize(
    "toml, args, fragment",
    [
        ("[problem]\nn = = 3\n", [], "invalid TOML"),
        ("[problem]\nnn = 3\n", [], "did you mean 'problem.n'?"),
        (None, ["--set", "problem.n=three"], "problem.n = 'three': expected an integer"),
        (None, ["--set", "problem.cfl=2"], "problem.cfl = 2.0 is out of range: allowed 0 < value <= 1"),
        (None, ["--set", "problem.scheme=rk4"], "choose one of leapfrog"),
    ],
)
def test_bad_input_one_line_exit2_nothing_written(tmp_path, toml, args, fragment):
    cmd = ["run", "toy-oscillator", "-o", "out"]
    if toml is not None:
        (tmp_path / "p.toml").write_text(toml)
        cmd += ["-c", "p.toml"]
    proc = cli(*cmd, *args, cwd=tmp_path)
    _assert_one_line_error(proc, fragment)
    assert not (tmp_path / "out").exists()
    assert not (tmp_path / "runs").exists()


def test_unknown_problem_and_command(tmp_path):
    _assert_one_line_error(cli("run", "toy-oscilator", cwd=tmp_path), "did you mean 'toy-oscillator'?")
    _assert_one_line_error(cli("frobnicate", cwd=tmp_path), "invalid choice")


def test_run_writes_run_directory(tmp_path):
    proc = cli("run", "toy-oscillator", "-o", "out", "--set", "run.tlim=1.0", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    out = tmp_path / "out"
    for name in ("config.toml", "log.txt", "history.h5", "snapshots/snap_00000.h5", "snapshots/snap_00002.h5"):
        assert (out / name).exists(), name
    assert "throughput=" in proc.stderr and "particle-updates/s" in proc.stderr
    # the first step's time is a part of the loop's (both printed to four and three digits)
    wall = float(re.search(r"wall=([0-9.e+-]+)s", proc.stderr).group(1))
    first = float(re.search(r"first_step=([0-9.e+-]+)s", proc.stderr).group(1))
    assert 0 < first <= wall * 1.001
    assert "version" in (out / "config.toml").read_text()
    # a second run into the same directory is refused without touching it
    before = sorted(p.name for p in out.rglob("*"))
    again = cli("run", "toy-oscillator", "-o", "out", cwd=tmp_path)
    _assert_one_line_error(again, "already holds a run")
    assert sorted(p.name for p in out.rglob("*")) == before


def test_problems_lists_and_describes(tmp_path):
    proc = cli("problems", "toy-oscillator", cwd=tmp_path)
    assert proc.returncode == 0
    assert "cfl    = 0.01" in proc.stdout and "omega * dt  (0 < value <= 1)" in proc.stdout


def test_reproduce_list_names_every_figure_in_thesis_order(tmp_path):
    from dustygas.reproduce import figure_names

    proc = cli("reproduce", "--list", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    listed = [line.split()[0] for line in proc.stdout.splitlines()]
    assert listed == figure_names() and len(listed) >= 9
    # chapter, then figure number, then a suffixed variant after its parent figure
    assert listed.index("fig3.5") < listed.index("fig4.1") < listed.index("fig4.3") < listed.index("fig4.3-settling")
    assert listed.index("fig4.3-settling") < listed.index("fig4.6")


def test_progress_lines_on_a_pipe_and_none_when_quiet(tmp_path):
    loud = cli("run", "toy-oscillator", "-o", "loud", "--set", "run.tlim=1.0", "--set", "run.log_every=10", cwd=tmp_path)
    quiet = cli("run", "toy-oscillator", "-o", "quiet", "--set", "run.tlim=1.0", "-q", cwd=tmp_path)
    assert loud.returncode == 0 and quiet.returncode == 0, (loud.stderr, quiet.stderr)
    n_steps = int(loud.stderr.split("cycles=")[1].split()[0])
    assert loud.stderr.count("cycle=") == n_steps // 10 and n_steps >= 10
    assert "cycle=" not in quiet.stderr and "finished:" in quiet.stderr
    # -q is an output choice, not a parameter: the two runs record the same configuration
    def config(run):
        return [line for line in (tmp_path / run / "config.toml").read_text().splitlines() if "log_every" not in line]

    assert config("loud") == config("quiet") and "tlim = 1.0" in config("quiet")
