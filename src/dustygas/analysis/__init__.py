"""Analysis of run directories (files in, numbers out).

Modules
-------
growth
    Growth rate and frequency of the linear mode recorded in a run's history (thesis §4.4):
    :func:`~dustygas.analysis.growth.measure_growth`, ``dustygas analyze growth RUN``.
"""

from .growth import GrowthFit, measure_growth

__all__ = ["GrowthFit", "measure_growth"]
