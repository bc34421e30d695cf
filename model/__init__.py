"""Friction models and their simulation: the Leuven integrated friction model (Swevers,
Al-Bender, Ganseman, Prajogo), LuGre and the static Coulomb + viscous + Stribeck model.

Pure computation: no file I/O, no user interface, no imports from ``identify`` or ``app``.

The names below are imported on first use (PEP 562): ``from leuven_friction.model.errors
import ...`` or ``.layout`` must not pay for numba, so that the command line starts at once.
"""

from __future__ import annotations

import importlib

_WHERE = {
    "FrictionError": "errors", "ParameterError": "errors", "SignalError": "errors",
    "FrictionParams": "params", "Stribeck": "params", "StribeckSide": "params", "TransitionCurve": "params",
    "as_model": "params", "default_params": "params",
    "COLUMNS": "simulate", "SimResult": "simulate", "initial_state": "simulate",
    "simulate_closed_loop": "simulate", "simulate_displacement": "simulate", "simulate_force": "simulate",
    "stribeck_curve": "simulate", "transition_curve_values": "simulate",
}

__all__ = sorted(_WHERE)


def __getattr__(name: str):
    mod = _WHERE.get(name)
    if mod is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{mod}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
