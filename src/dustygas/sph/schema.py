"""The ``[sph]`` section shared by every SPH problem, and its translation into :class:`SPHOptions`.

Problems copy :data:`SPH_SCHEMA` with their own defaults
(``with_defaults(SPH_SCHEMA, kernel="quintic")``) and build the engine options with
:func:`options_from_config`.
"""

from __future__ import annotations

from typing import Mapping

from ..config import Param
from .engine import SPHOptions
from .kernels import KERNEL_NAMES

__all__ = ["SPH_SCHEMA", "INVISCID", "options_from_config"]

SPH_SCHEMA: dict[str, Param] = {
    "kernel": Param("cubic", "smoothing kernel", choices=KERNEL_NAMES),
    "hfact": Param(0.0, "h_fact of rho h^d = m h_fact^d (0: the kernel's usual value)", min=0.0),
    "force": Param("price2012", "pressure force: Price (2012) grad-h form or GASOLINE2 (thesis eqs. 3.2-3.3)",
                   choices=("price2012", "gasoline2")),
    "gasoline2_f": Param("gradh", "f_a of the GASOLINE2 force: 1/Omega_a or Wadsley et al. (2017)",
                         choices=("gradh", "wadsley")),
    "alpha": Param(1.0, "initial (or, without switch, constant) artificial viscosity alpha", min=0.0),
    "alpha_min": Param(0.1, "lower bound of the switched alpha", min=0.0),
    "alpha_max": Param(1.0, "upper bound of the switched alpha", min=0.0),
    "beta": Param(2.0, "quadratic (signal-velocity) viscosity coefficient", min=0.0),
    "switch": Param("morris-monaghan", "viscosity switch", choices=("none", "morris-monaghan", "cullen-dehnen")),
    "switch_decay": Param(0.1, "sigma of the switch's decay time h/(sigma c_s)", min=0.0, min_open=True),
    "alpha_u": Param(1.0, "artificial conductivity coefficient (adiabatic gas)", min=0.0),
    "c_cour": Param(0.3, "Courant factor (thesis eq. 2.13)", min=0.0, max=1.0, min_open=True),
    "c_force": Param(0.25, "acceleration time-step factor (thesis eq. 2.14)", min=0.0, max=1.0, min_open=True),
    "h_tolerance": Param(1e-4, "relative tolerance of the smoothing-length iteration", min=0.0, max=0.1,
                         min_open=True),
    "h_max_iterations": Param(30, "iteration limit of the smoothing-length iteration", min=1),
    "neighbour_buffer": Param(0.02, "relative margin on h of the neighbour tables", min=0.0, max=1.0),
    "neighbour_search": Param("auto", "neighbour search: cell list, k-d tree, or chosen by the spread of h",
                              choices=("auto", "cells", "tree")),
    "reorder_every": Param(20, "steps between spatial re-orderings of the particle arrays (0: never)", min=0),
    "fixed_dt": Param(0.0, "fixed time step (0: adaptive)", "code time", min=0.0),
}


#: ``[sph]`` defaults of the smooth linear tests (sound waves, dusty boxes and waves, diffusion): no
#: artificial viscosity or conductivity and no switch, ``with_defaults(SPH_SCHEMA, **INVISCID)``
INVISCID: dict[str, float | str] = {"alpha": 0.0, "alpha_min": 0.0, "switch": "none", "alpha_u": 0.0}


def options_from_config(section: Mapping) -> SPHOptions:
    """:class:`SPHOptions` from a validated ``[sph]`` configuration section."""
    return SPHOptions(**{key: section[key] for key in SPH_SCHEMA})
