"""Reading and comparing run directories in tests (restart tests of every engine).

``run_outputs(path)`` returns ``{snapshot file name or "history": (arrays, attrs)}``;
``assert_runs_identical(a, b)`` requires the same files, the same arrays bit for bit and the same
attributes -- what "a killed and restarted run finishes identical to an uninterrupted one" means.
The ``config`` attribute (the configuration in force when the file was written) must agree in
every section but ``[run]``: a restart may change run control (``run.tlim``, ``run.max_cycles``).
"""

import tomllib

import numpy as np

from dustygas.io import read_h5
from dustygas.io.rundir import RunDirectory


def run_outputs(path) -> dict:
    rd = RunDirectory(path)
    out = {f.name: read_h5(f) for f in rd.snapshots()}
    out["history"] = read_h5(rd.history_file)
    return out


def assert_runs_identical(a: dict, b: dict) -> None:
    assert a.keys() == b.keys()
    for key in a:
        (arrays_a, attrs_a), (arrays_b, attrs_b) = a[key], b[key]
        assert arrays_a.keys() == arrays_b.keys(), key
        for name in arrays_a:
            np.testing.assert_array_equal(arrays_a[name], arrays_b[name], err_msg=f"{key}:{name}")
        assert attrs_a.keys() == attrs_b.keys(), key
        for name in attrs_a:
            if name == "config":
                physics_a, physics_b = tomllib.loads(attrs_a[name]), tomllib.loads(attrs_b[name])
                physics_a.pop("run"), physics_b.pop("run")
                assert physics_a == physics_b, (key, name)
                continue
            assert np.array_equal(attrs_a[name], attrs_b[name]), (key, name)
