"""An engine's ``load_kernels()``: numba loads (or compiles) the compiled step before the run
loop's clock starts (:mod:`dustygas.runner`), instead of at the first step.

Two laws, each exact: the call leaves every array of the state bit for bit as it was, and the
argument types it has numba compile for are those with which every step of the run then calls
the kernel (a difference -- an ``int`` time where the steps pass a ``float`` -- would make the
first step load or compile a second overload, the cost ``load_kernels`` exists to move).
"""

from __future__ import annotations

import numpy as np
import pytest

from dustygas import api
from dustygas.grid import engine as grid_engine
from dustygas.particles import step_xz
from dustygas.problems import get_problem


class Recorder:
    """A compiled function's stand-in that records the signatures compiled and called."""

    def __init__(self, dispatcher):
        self.dispatcher = dispatcher
        self.compiled: list[tuple] = []
        self.called: list[tuple] = []

    def typeof_pyval(self, value):
        return self.dispatcher.typeof_pyval(value)

    def compile(self, sig):
        self.compiled.append(tuple(sig))
        return self.dispatcher.compile(sig)

    def __call__(self, *args):
        self.called.append(tuple(self.dispatcher.typeof_pyval(a) for a in args))
        return self.dispatcher(*args)


#: (problem, settings, module holding the step's kernel, its name there)
CASES = {
    "si-linA (coupled_step_xz)": ("si-linA", ["grid.nx=16", "grid.nz=16"], step_xz, "coupled_step_xz"),
    "shearing-wave (advance_gas)": ("shearing-wave", ["grid.nx=16", "grid.ny=16"], grid_engine, "advance_gas"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_run_loads_the_signature_its_steps_call(case, monkeypatch, tmp_path):
    problem, sets, module, name = CASES[case]
    recorder = Recorder(getattr(module, name))
    monkeypatch.setattr(module, name, recorder)
    res = api.run(problem, output=tmp_path / "run", set=sets + ["run.max_cycles=4"])
    assert res.cycles == 4
    assert len(recorder.compiled) == 1, "one load, before the loop"
    assert len(recorder.called) == 4 and set(recorder.called) == {recorder.compiled[0]}


@pytest.mark.parametrize("case", list(CASES))
def test_load_kernels_leaves_the_state_as_it_was(case):
    problem, sets, _, _ = CASES[case]
    prob = get_problem(problem)
    eng = prob.build(prob.config(overrides=sets))
    before, attrs = eng.checkpoint()
    before = {k: np.array(v, copy=True) for k, v in before.items()}
    eng.load_kernels()
    after, attrs_after = eng.checkpoint()
    assert attrs_after == attrs
    assert sorted(after) == sorted(before)
    for key, value in before.items():
        assert np.array_equal(after[key], value, equal_nan=True), key
