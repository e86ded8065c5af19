"""Particle splitting: more resolution where it is needed (thesis §3.3.3; Kitsionas & Whitworth 2002).

The thesis's scheme splits a particle into a *pair*: a particle of mass :math:`m` and smoothing
length :math:`h` at :math:`\\mathbf x` becomes two of mass :math:`m/2` at :math:`\\mathbf x \\pm (h/2)\\hat{\\mathbf n}`,
both with the parent's velocity (and every other field), and smoothing length :math:`h/2^{1/3}` so that
:math:`\\rho h^3 = m h_{\\rm fact}^3` still holds. Mass and linear momentum are conserved exactly
(:math:`m/2` is exact in binary), the centre of mass and the angular momentum
:math:`\\tfrac m2[(\\mathbf x+\\mathbf d)+(\\mathbf x-\\mathbf d)]\\times\\mathbf v` to round-off. Three
generations, along three mutually perpendicular directions of a frame drawn at random for each
original particle, turn it into eight at the corners of a box of edges
:math:`h, h/2^{1/3}, h/2^{2/3}`: the spacing :math:`l = (m/\\rho)^{1/3}` halves where the density is
unchanged.

:func:`split_band` applies this in a radial band :math:`R_1 \\le R \\le R_2` of a disk with *buffer
zones* on both sides, where particles are split fewer times (4x, then 2x: spacing ratios
:math:`l_u/l_s = 4^{1/3} \\approx 1.6` and :math:`2^{1/3} \\approx 1.26`), so that the resolution changes
in steps (the thesis's Fig. 3.12). It works on any particles, gas and dust alike.

Examples
--------
>>> p = ParticleSet.create(np.array([[1.0, 0.0, 0.0]]), np.array([[0.0, 1.0, 0.0]]), mass=1.0, h=0.1)
>>> q = split_pairs(p, np.array([True]), np.array([[0.0, 0.0, 1.0]]))
>>> q.mass.tolist(), q.pos[:, 2].tolist(), round(float(q.h[0] ** 3 * 2 / 0.1**3), 12)
([0.5, 0.5], [0.05, -0.05], 1.0)
"""

from __future__ import annotations

import numpy as np

from ..errors import SetupError
from .particles import ParticleSet

__all__ = ["split_pairs", "split_generations", "split_band", "random_frames"]


def random_frames(n: int, seed: int) -> np.ndarray:
    """``n`` random orthonormal frames ``(n, 3, 3)`` (rows are the axes), uniform over rotations."""
    rng = np.random.default_rng(seed)
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    w, x, y, z = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)], 1),
        np.stack([2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)], 1),
        np.stack([2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)], 1),
    ], 1)


def split_pairs(particles: ParticleSet, select: np.ndarray, direction: np.ndarray) -> ParticleSet:
    """Split the particles ``select`` (boolean mask) into pairs along ``direction`` (unit vectors, one
    per selected particle), module docstring. The first child keeps the parent's place in the arrays
    and its id; second children are appended with new ids."""
    p = particles
    idx = np.flatnonzero(select)
    if direction.shape != (idx.size, 3):
        raise ValueError("split_pairs: need one direction per selected particle")
    d = 0.5 * p.h[idx, None] * direction
    out = p.take(np.arange(len(p)))
    out.mass[idx] = 0.5 * p.mass[idx]
    out.h[idx] = p.h[idx] * 2.0 ** (-1.0 / 3.0)
    out.pos[idx] = p.pos[idx] + d
    twins = out.take(idx)
    twins.pos[:] = p.pos[idx] - d
    twins.pid[:] = int(p.pid.max(initial=-1)) + 1 + np.arange(idx.size)
    fields = [f for f in ("pos", "vel", "mass", "h", "u", "alpha", "ptype", "pid")]
    merged = {f: np.concatenate([getattr(out, f), getattr(twins, f)]) for f in fields}
    extra = {k: np.concatenate([v, twins.extra[k]]) for k, v in out.extra.items()}
    return ParticleSet(**merged, extra=extra)


def split_generations(particles: ParticleSet, generations: np.ndarray, seed: int = 1) -> ParticleSet:
    """Split particle ``a`` ``generations[a]`` times (0-3) into :math:`2^g` (module docstring)."""
    g = np.asarray(generations, dtype=np.int64)
    if g.shape != (len(particles),) or g.min(initial=0) < 0 or g.max(initial=0) > 3:
        raise SetupError("splitting: between 0 and 3 generations per particle")
    frames = random_frames(len(particles), seed)
    p, left, frame = particles, g.copy(), frames
    for k in range(int(g.max(initial=0))):
        sel = left > 0
        p = split_pairs(p, sel, frame[sel, k])
        left = np.concatenate([left - sel, (left - 1)[sel]])
        frame = np.concatenate([frame, frame[sel]])
    return p


def split_band(particles: ParticleSet, r1: float, r2: float, buffers: tuple[float, ...] = (10.0, 10.0),
               seed: int = 1) -> ParticleSet:
    """Eight-fold splitting of the particles with cylindrical radius in ``[r1, r2]``, four-fold within
    ``buffers[0]`` of the band and two-fold within a further ``buffers[1]`` (module docstring)."""
    if not (0 <= r1 < r2) or len(buffers) != 2 or min(buffers) < 0:
        raise SetupError(f"splitting: need 0 <= r1 < r2 and two non-negative buffer widths (r1={r1:g}, r2={r2:g})")
    R = np.hypot(particles.pos[:, 0], particles.pos[:, 1])
    dist = np.maximum(r1 - R, R - r2)  # <= 0 inside the band
    w4, w2 = buffers
    gen = np.where(dist <= 0, 3, np.where(dist <= w4, 2, np.where(dist <= w4 + w2, 1, 0)))
    return split_generations(particles, gen, seed)
