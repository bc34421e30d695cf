"""Friction models and their simulation: the Leuven integrated friction model (Swevers,
Al-Bender, Ganseman, Prajogo), LuGre and the static Coulomb + viscous + Stribeck model.

Pure computation: no file I/O, no user interface, no imports from ``identify`` or ``app``.
"""

from .errors import FrictionError, ParameterError, SignalError
from .params import (
    FrictionParams,
    Stribeck,
    StribeckSide,
    TransitionCurve,
    as_model,
    default_params,
)
from .simulate import (
    COLUMNS,
    SimResult,
    initial_state,
    simulate_closed_loop,
    simulate_displacement,
    simulate_force,
    stribeck_curve,
    transition_curve_values,
)

__all__ = [
    "COLUMNS", "FrictionError", "FrictionParams", "ParameterError", "SignalError", "SimResult", "Stribeck", "StribeckSide", "TransitionCurve",
    "as_model", "default_params", "initial_state", "simulate_closed_loop", "simulate_displacement",
    "simulate_force", "stribeck_curve", "transition_curve_values",
]
