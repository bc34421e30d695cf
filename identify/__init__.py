"""Identification: recorded data in, model parameters with uncertainties out.

The names below are imported on first use (PEP 562), so that importing one submodule (e.g.
``identify.errors`` in the command line) does not load YAML, pandas or the fitting code.
"""

from __future__ import annotations

import importlib

_WHERE = {"load_params": "paramfile", "params_to_yaml": "paramfile", "save_params": "paramfile",
          "write_atomic": "paramfile"}

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
