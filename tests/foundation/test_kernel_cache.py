"""numba's on-disk cache never runs stale code (dustygas._numba_cache).

In a copy of the source tree: two processes compile the SPH render kernel at once on a cold
cache, a third loads it from the cache, and after an edit of the kernel *shape* in another file
(``sph/kernels.py``, inlined into ``sph/render.py``'s kernel) a fourth sees the new shape.
The rendered value is the cubic M4 shape at q = 1.5, f = (2 - q)^3 / 4 = 1/32 (Monaghan &
Lattanzio 1985), exactly; the edit doubles the coefficient, so the value becomes 1/16.
For the kernels of grid, particles, sph and linear, a second test edits (in a copy) a file
each one inlines from and checks that the kernel's source stamp changes (no compilation). A
damaged cache file is compiled afresh, with a warning.
"""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "dustygas"

PROBE = """
import json, numpy as np
from dustygas.sph.kernels import CUBIC
from dustygas.sph.render import _render
img = np.zeros((1, 1))
# one particle at the origin, h = 1; one pixel centred at (1.5, 0): q = 1.5
_render(np.zeros((1, 2)), np.ones(1), np.ones(1), CUBIC, 1.0, 2.0, 2, 1.0, 2.0, -0.5, 0.5, 0.0, 1, 1, 0, 1, 2, img)
s = _render.stats
print(json.dumps({"value": img[0, 0], "hits": sum(s.cache_hits.values()), "misses": sum(s.cache_misses.values())}))
"""


def _env(root: Path) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_CACHE_DIR"}
    env["PYTHONPATH"] = str(root)
    env["NUMBA_NUM_THREADS"] = "1"
    return env


def _start(root: Path) -> subprocess.Popen:
    return subprocess.Popen([sys.executable, "-c", PROBE], cwd=root, env=_env(root), stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)


def _result(proc: subprocess.Popen) -> dict:
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    return json.loads(out.strip().splitlines()[-1])


def test_cross_file_edit_recompiles_and_concurrent_processes_share_the_cache(tmp_path):
    shutil.copytree(SRC, tmp_path / "dustygas", ignore=shutil.ignore_patterns("__pycache__"))
    first = [_start(tmp_path), _start(tmp_path)]  # cold cache, compiled by both at once
    for result in map(_result, first):
        assert result["value"] == 1.0 / 32.0 and result["misses"] == 1
    cached = _result(_start(tmp_path))
    assert cached["value"] == 1.0 / 32.0 and cached["hits"] == 1 and cached["misses"] == 0

    kernels = tmp_path / "dustygas" / "sph" / "kernels.py"
    text = kernels.read_text()
    old = "return 0.25 * t2 * t2 * t2 - t1 * t1 * t1,"
    assert text.count(old) == 1
    kernels.write_text(text.replace(old, "return 0.5 * t2 * t2 * t2 - t1 * t1 * t1,"))
    edited = _result(_start(tmp_path))
    assert edited["value"] == 1.0 / 16.0 and edited["misses"] == 1 and edited["hits"] == 0


def test_a_damaged_cache_file_is_compiled_afresh(tmp_path):
    """Every data file of the render kernel cut to half its length (as a copy taken mid-write would
    leave it): the next process warns, compiles afresh and renders 1/32; the one after loads the
    rewritten file from the cache."""
    shutil.copytree(SRC, tmp_path / "dustygas", ignore=shutil.ignore_patterns("__pycache__"))
    assert _result(_start(tmp_path))["misses"] == 1
    data = sorted((tmp_path / "dustygas" / "sph" / "__pycache__").glob("render._render-*.nbc"))
    assert data
    for file in data:
        file.write_bytes(file.read_bytes()[: file.stat().st_size // 2])
    proc = _start(tmp_path)
    out, err = proc.communicate(timeout=300)
    assert proc.returncode == 0, err
    damaged = json.loads(out.strip().splitlines()[-1])
    assert damaged["value"] == 1.0 / 32.0 and damaged["misses"] == 1 and damaged["hits"] == 0
    assert "could not be read" in err and "compiling it afresh" in err
    again = _result(_start(tmp_path))
    assert again["value"] == 1.0 / 32.0 and again["hits"] == 1 and again["misses"] == 0


def _stamp_module(root: Path):
    """The copy's ``dustygas._numba_cache``, loaded on its own (its root is the copy)."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("_copied_numba_cache", root / "_numba_cache.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# (file defining a cached kernel, a file it inlines from, directly or through another module)
CROSS_FILE = [
    ("grid/integrator.py", "grid/riemann.py"),  # through grid/sweep.py
    ("particles/push.py", "particles/drag.py"),
    ("particles/push.py", "physics/drag.py"),
    ("sph/density.py", "sph/kernels.py"),
    ("linear/modes.py", "linear/operator.py"),
    ("linear/maps.py", "linear/eigensolver.py"),
]


def test_every_engine_kernel_stamp_covers_the_files_it_inlines(tmp_path):
    """For grid, particles, sph and linear: an edit of an inlined file (a comment appended, in a
    copy of the source) changes the stamp of the kernel's file, so its cache entry is not used."""
    shutil.copytree(SRC, tmp_path / "dustygas", ignore=shutil.ignore_patterns("__pycache__"))
    root = tmp_path / "dustygas"
    before = _stamp_module(root)
    stamps = {kernel: before.source_stamp(root / kernel) for kernel, _ in CROSS_FILE}
    for kernel, inlined in CROSS_FILE:
        with open(root / inlined, "a") as fh:
            fh.write(f"\n# edited for the test of {kernel}\n")
        after = _stamp_module(root)  # a fresh process would read the files afresh
        assert after.source_stamp(root / kernel) != stamps[kernel], (kernel, inlined)
        stamps = {k: after.source_stamp(root / k) for k, _ in CROSS_FILE}


UNCACHEABLE = '''
import ctypes
from numba import njit

_abs = ctypes.CDLL(None).abs
_abs.restype, _abs.argtypes = ctypes.c_int, [ctypes.c_int]


@njit(cache=True)
def absolute(x):
    return _abs(x)
'''


def test_a_kernel_numba_cannot_cache_warns_and_runs(tmp_path):
    """A kernel numba cannot cache (it holds a ctypes pointer, a dynamic global) inside the package
    gets numba's own warning, not an AttributeError from the dustygas locator; and |-5| = 5."""
    shutil.copytree(SRC, tmp_path / "dustygas", ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "dustygas" / "_uncacheable_probe.py").write_text(UNCACHEABLE)
    probe = ("import warnings, dustygas\nfrom dustygas._uncacheable_probe import absolute\n"
             "with warnings.catch_warnings(record=True) as w:\n    warnings.simplefilter('always')\n"
             "    print(absolute(-5), any('Cannot cache' in str(x.message) for x in w))\n")
    proc = subprocess.run([sys.executable, "-c", probe], cwd=tmp_path, env=_env(tmp_path), capture_output=True,
                          text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["5", "True"]
