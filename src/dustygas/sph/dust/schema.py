"""The ``[dust]`` section shared by the dust problems, and the module it builds.

Problems copy :data:`DUST_SCHEMA` with their own defaults
(``with_defaults(DUST_SCHEMA, method="one-fluid", K=1000.0)``) and turn the validated section into
an engine module with :func:`one_fluid_from_config` / :func:`two_fluid_from_config`.
"""

from __future__ import annotations

import math
from typing import Mapping

from ...config import Param
from .drag_law import DRAG_LAWS, DragLaw
from .grain_size import GrainGrowth
from .one_fluid import EXCHANGES, ONE_FLUID_MODELS, VARIABLES, OneFluidDust, OneFluidOptions
from .two_fluid import DRAG_FORMS, DRAG_INTEGRATIONS, RECONSTRUCTIONS, TwoFluidDust, TwoFluidOptions

__all__ = ["DUST_SCHEMA", "GROWTH_SCHEMA", "drag_law_from_config", "growth_from_config", "one_fluid_from_config",
           "two_fluid_from_config"]

DUST_SCHEMA: dict[str, Param] = {
    "method": Param("two-fluid", "dust as a dust fraction on mixture particles, or as dust particles",
                    choices=("one-fluid", "two-fluid")),
    "drag": Param("constant-K", "drag law: constant K, constant stopping time, or Epstein from the grain size",
                  choices=DRAG_LAWS),
    "K": Param(1.0, "drag coefficient K (drag = constant-K)", "code density/time", min=0.0, min_open=True),
    "ts": Param(0.1, "mixture stopping time (drag = constant-ts)", "code time", min=0.0, min_open=True),
    "grain_size": Param(1.0, "grain radius (drag = epstein)", "code length", min=0.0, min_open=True),
    "grain_density": Param(1.0, "grain material density (drag = epstein)", "code density", min=0.0, min_open=True),
    "model": Param("terminal-velocity", "one-fluid: terminal-velocity approximation or full equations with "
                   "the relative velocity (thesis eqs. 2.10-2.11 / 2.9)", choices=ONE_FLUID_MODELS),
    "exchange": Param("upwind", "one-fluid dust exchange between neighbours: upwind (eq. 3.17) or arithmetic "
                      "(eq. 3.4)", choices=EXCHANGES),
    "variable": Param("dust-fraction", "one-fluid evolved variable: eps or sqrt(rho eps) (Ballabio et al. 2018)",
                      choices=VARIABLES),
    "c_eps": Param(0.3, "one-fluid dust-fraction time-step factor (0: no criterion, as in the thesis)", min=0.0),
    "clamp": Param(False, "one-fluid: clamp eps to [eps_floor, eps_ceiling] after each step, counting every "
                   "event and the dust mass it creates or destroys (thesis §3.2.4)"),
    "eps_floor": Param(0.0, "lower clamp bound", min=0.0, max=1.0),
    "eps_ceiling": Param(1.0, "upper clamp bound", min=0.0, max=1.0),
    "form": Param("projected", "two-fluid drag: projected along the pair (eq. 3.19) or not (eq. 3.18)",
                  choices=DRAG_FORMS),
    "reconstruction": Param("mc", "two-fluid: velocity reconstruction at the pair midpoint (Price & Laibe 2020) "
                            "with the MC limiter, without limiter, the gas velocity extrapolated to the dust particle with the gas's "
                            "gradient (gas), or none", choices=RECONSTRUCTIONS),
    "integration": Param("explicit", "two-fluid drag in time: explicit (dt <= c_drag t_s, eq. 2.15) or pairwise "
                         "exponential (implicit)", choices=DRAG_INTEGRATIONS),
    "c_drag": Param(0.9, "explicit-drag time-step factor: dt <= c_drag t_s", min=0.0, min_open=True),
    "heating": Param(True, "drag heating of the gas (adiabatic gas)"),
}

GROWTH_SCHEMA: dict[str, Param] = {
    "enabled": Param(False, "grow and fragment grains locally (thesis eqs. 3.6-3.7; Epstein drag)"),
    "alpha": Param(1e-2, "turbulence alpha of V_rel (eq. 3.7)", min=0.0, min_open=True),
    "rossby": Param(3.0, "Rossby number of alpha_tilde = sqrt(2) Ro alpha", min=0.0, min_open=True),
    "omega": Param(1.0, "orbital frequency Omega of tau_s = t_s Omega", "1/code time", min=0.0, min_open=True),
    "v_frag": Param(math.inf, "fragmentation threshold V_frag (inf: pure growth, 0: pure fragmentation)",
                    "code velocity", min=0.0),
    "min_size": Param(1e-6, "smallest grain radius", "code length", min=0.0, min_open=True),
    "c_size": Param(0.02, "time-step factor dt <= c s/|ds/dt|", min=0.0, min_open=True),
}


def drag_law_from_config(dust: Mapping, gamma: float = 1.0) -> DragLaw:
    """:class:`DragLaw` of a validated ``[dust]`` section."""
    return DragLaw(dust["drag"], K=dust["K"], ts=dust["ts"], grain_size=dust["grain_size"],
                   grain_density=dust["grain_density"], gamma=gamma)


def growth_from_config(growth: Mapping | None, dust: Mapping) -> GrainGrowth | None:
    """:class:`GrainGrowth` of a validated ``[growth]`` section (``None`` if absent or disabled)."""
    if not growth or not growth["enabled"]:
        return None
    return GrainGrowth(alpha=growth["alpha"], rossby=growth["rossby"], omega=growth["omega"],
                       v_frag=growth["v_frag"], grain_density=dust["grain_density"], min_size=growth["min_size"],
                       c_size=growth["c_size"])


def one_fluid_from_config(dust: Mapping, dust_fraction, gamma: float = 1.0, delta_v=None, grain_size=None,
                          growth: Mapping | None = None, hold_gas: bool = False) -> OneFluidDust:
    """The one-fluid module for a validated ``[dust]`` (and optional ``[growth]``) section."""
    opts = OneFluidOptions(model=dust["model"], exchange=dust["exchange"], variable=dust["variable"],
                           drag=drag_law_from_config(dust, gamma), c_eps=dust["c_eps"], c_drag=dust["c_drag"],
                           clamp=dust["clamp"], eps_floor=dust["eps_floor"], eps_ceiling=dust["eps_ceiling"],
                           hold_gas=hold_gas, growth=growth_from_config(growth, dust))
    return OneFluidDust(opts, dust_fraction, delta_v=delta_v, grain_size=grain_size)


def two_fluid_from_config(dust: Mapping, gamma: float = 1.0, grain_size=None) -> TwoFluidDust:
    """The two-fluid module for a validated ``[dust]`` section."""
    opts = TwoFluidOptions(drag=drag_law_from_config(dust, gamma), form=dust["form"],
                           reconstruction=dust["reconstruction"], integration=dust["integration"],
                           c_drag=dust["c_drag"], heating=dust["heating"])
    return TwoFluidDust(opts, grain_size=grain_size)
