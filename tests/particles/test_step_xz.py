"""The coupled step of a periodic x-z box as one compiled call (:mod:`dustygas.particles.step_xz`)
against the same step through the Python sequence of kernel calls: bit for bit the same state.

Both paths call the same compiled kernels with the same arguments in the same order, so the
law checked is exact equality of every array the step writes, after steps in which particles
change cells (velocities scrambled), on one thread and on two (in this process: the kernels'
results do not depend on the thread count, which ``test_kernels`` checks on its own).
"""

from __future__ import annotations

import numba
import numpy as np
import pytest

from dustygas.particles.coupling import ParticleGridEngine
from dustygas.problems import get_problem


def build(problem: str, sets: list[str], **options):
    prob = get_problem(problem)
    eng = prob.build(prob.config(overrides=sets))
    if options:
        eng = ParticleGridEngine(eng.gas, eng.particles, **{**eng.options, **options})
    rng = np.random.default_rng(3)
    eng.particles.vel[...] += 0.02 * rng.standard_normal(eng.particles.vel.shape)
    return eng


def state(eng) -> dict:
    p = eng.particles
    return {"gas": eng.gas.states, "pos": p.pos, "vel": p.vel, "pid": p.pid, "species": p.species,
            "mass": p.mass, "lost": eng.lost, "terms_rows": eng.terms_rows, "budget": eng.gas.budget_rows,
            "source": eng._source, "t": np.array(eng.gas.t), "cycle": np.array(eng.gas.cycle),
            "vmax": np.array(eng._vmax), "rows": np.array(eng.field_rows), "dt": np.array(eng.timestep())}


#: every registered problem whose engine takes the compiled step, on a 16² mesh where it has a bigger one
SMALL = ["grid.nx=16", "grid.nz=16"]
CASES = {
    **{name: (name, SMALL, {}) for name in ("si-linA", "si-linB", "si-linC", "si-linear", "si-AB", "si-BA",
                                            "si-multispecies", "si-nonlinear")},
    "nsh": ("nsh", [], {}),
    "dustybox-grid": ("dustybox-grid", [], {}),
    "si-linA without back-reaction": ("si-linA", SMALL, {"feedback": False}),
    "si-linA, Epstein drag": ("si-linA", SMALL, {"drag_law": "epstein"}),
}


@pytest.mark.parametrize("case", list(CASES))
def test_compiled_step_is_bit_identical_to_the_python_sequence(case):
    problem, sets, options = CASES[case]
    one_call, python = build(problem, sets, **options), build(problem, sets, **options)
    assert one_call.compiled_step, "the case the compiled step is for"
    python.compiled_step = False
    before = numba.get_num_threads()
    try:
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(threads)
            for _ in range(8):
                one_call.advance(one_call.timestep())
                python.advance(python.timestep())
    finally:
        numba.set_num_threads(before)
    a, b = state(one_call), state(python)
    assert one_call.gas.cycle == 16 and one_call.sorts == python.sorts == 16
    assert not np.array_equal(a["pos"], state(build(problem, sets, **options))["pos"])  # the particles moved
    for key in a:
        assert np.array_equal(a[key], b[key]), key


def test_the_engine_runs_the_python_sequence_where_the_compiled_step_does_not_apply():
    """A 3D box, gas terms (si-settling's vertical gravity on the gas), the CTU integrator: the
    Python sequence."""
    cases = [("si3d", ["grid.nx=8", "grid.ny=8", "grid.nz=12", "problem.Hp=0.03"]),
             ("si-settling", ["grid.nx=16", "grid.nz=16"]),
             ("si-linA", ["grid.nx=16", "grid.nz=16", "scheme.integrator=ctu", "scheme.cfl=0.8"])]
    for problem, sets in cases:
        prob = get_problem(problem)
        assert not prob.build(prob.config(overrides=sets)).compiled_step, problem


def test_the_compiled_step_calls_the_kernels_the_python_sequence_compiled():
    """The kernels the compiled step calls get no specialization of their own: a constant passed to
    a kernel inside compiled code is typed as a literal and compiles that kernel again for it
    (before the flags and stage numbers arrived as run-time values, the two gas stages and the
    deposit compiled anew: 95 s on a first run)."""
    from numba.core import types
    from numba.core.registry import CPUDispatcher

    import dustygas.particles.step_xz as step_xz

    eng = build("si-linA", SMALL)
    eng.compiled_step = False  # a first step through the Python sequence: each kernel's own signatures
    eng.advance(eng.timestep())
    eng.compiled_step = True
    for _ in range(2):
        eng.advance(eng.timestep())
    # every compiled function the step module imports: a kernel added to the step is checked too
    kernels = [f for name, f in vars(step_xz).items() if isinstance(f, CPUDispatcher) and name != "coupled_step_xz"]
    assert len(kernels) >= 13, [k.py_func.__name__ for k in kernels]
    for kernel in kernels:
        assert kernel.signatures, kernel.py_func.__name__
        for signature in kernel.signatures:
            literal = [str(t) for t in signature if isinstance(t, types.Literal)]
            assert not literal, (kernel.py_func.__name__, literal)
