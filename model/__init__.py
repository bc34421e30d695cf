"""Friction models and their simulation: the Leuven integrated friction model (Swevers,
Al-Bender, Ganseman, Prajogo), LuGre and the static Coulomb + viscous + Stribeck model.

Pure computation: no file I/O, no user interface, no imports from ``identify`` or ``app``.

The names below are imported on first use (PEP 562): ``from leuven_friction.model.errors
import ...`` or ``.layout`` must not pay for numba, so that the command line starts at once.
"""

from __future__ import annotations

from .lazy import lazy_exports

_WHERE = {
    "FrictionError": "errors", "ParameterError": "errors", "SignalError": "errors",
    "FrictionParams": "params", "Stribeck": "params", "StribeckSide": "params", "TransitionCurve": "params",
    "as_model": "params", "default_params": "params",
    "COLUMNS": "simulate", "SimResult": "simulate", "SteadyAlong": "simulate", "initial_state": "simulate",
    "simulate_closed_loop": "simulate", "simulate_displacement": "simulate", "simulate_force": "simulate",
    "friction_along": "simulate",
    "steady_along": "simulate", "stribeck_curve": "simulate", "transition_curve_values": "simulate",
}

__all__ = sorted(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
