"""Helpers for SPH tests: build a registered problem's engine and advance it without the run loop."""

from dustygas.problems import get_problem


def build(name, *overrides):
    prob = get_problem(name)
    cfg = prob.config(overrides=list(overrides))
    return prob, cfg, prob.build(cfg)


def advance_to(engine, tend, dt=None):
    """Advance ``engine`` to ``tend`` with its own time steps (or a fixed ``dt``), landing exactly."""
    while engine.t < tend * (1 - 1e-14):
        step = engine.timestep() if dt is None else dt
        engine.advance(min(step, tend - engine.t))
    return engine
