"""Helpers: build a registered dust problem and advance it without the run loop."""

from dustygas.problems import get_problem


def build(name, *overrides):
    prob = get_problem(name)
    cfg = prob.config(overrides=list(overrides))
    return prob, cfg, prob.build(cfg)


def advance_to(engine, tend, every=None):
    """Advance ``engine`` to ``tend`` with its own time steps, landing exactly; call ``every(engine)``
    after each step if given."""
    while engine.t < tend * (1 - 1e-14):
        engine.advance(min(engine.timestep(), tend - engine.t))
        if every is not None:
            every(engine)
    return engine
