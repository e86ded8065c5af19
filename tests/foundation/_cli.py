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
