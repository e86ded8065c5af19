"""Run the CLI in a subprocess with the test-only toy problem registered."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

TESTS = Path(__file__).resolve().parents[1]
SRC = TESTS.parent / "src"
PRELUDE = "import sys, _toyproblem; from dustygas.cli import main; sys.exit(main(sys.argv[1:]))"


def env() -> dict:
    e = dict(os.environ)
    e["PYTHONPATH"] = os.pathsep.join([str(TESTS), str(SRC), e.get("PYTHONPATH", "")])
    return e


def cli(*args: str, cwd: Path, **kw) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", PRELUDE, *args], cwd=cwd, env=env(),
                          capture_output=True, text=True, timeout=120, **kw)


def cli_popen(*args: str, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", PRELUDE, *args], cwd=cwd, env=env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def cli_in_process(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    """``dustygas ARGS`` through :func:`dustygas.cli.main` in this process, in ``cwd``, with its
    stdout, stderr and exit status as :func:`cli` returns them. For refusals of bad input (exit 2,
    one line, nothing written), which do not depend on the process: an interpreter start-up costs
    1.5-2 CPU-s on the loaded two cores (2026-12-03). :func:`cli` stays the test of the real
    command (``tests/foundation/test_cli.py``)."""
    import contextlib
    import io

    from dustygas.cli import main

    out, err = io.StringIO(), io.StringIO()
    old = os.getcwd()
    os.chdir(cwd)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                rc = main(list(args))
            except SystemExit as exc:  # argparse's own errors
                rc = exc.code if isinstance(exc.code, int) else 1
    finally:
        os.chdir(old)
    return subprocess.CompletedProcess(["dustygas", *args], rc, out.getvalue(), err.getvalue())
