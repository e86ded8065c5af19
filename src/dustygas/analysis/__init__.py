"""Analysis of run directories (files in, numbers out).

Modules
-------
growth
    Growth rate and frequency of the linear mode recorded in a run's history (thesis §4.4):
    :func:`~dustygas.analysis.growth.measure_growth`, ``dustygas analyze growth RUN``.
clumps, clump_search, planetesimals, mass_function, synthetic
    Bound clumps of particles in a snapshot (:func:`~dustygas.analysis.clumps.find_clumps`),
    per-snapshot catalogues of a run (``dustygas analyze clumps RUN``), the mass function's
    maximum-likelihood fits, and synthetic snapshots with planted clumps to validate them.
"""

from .growth import GrowthFit, measure_growth

__all__ = ["GrowthFit", "measure_growth"]
