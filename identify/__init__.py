"""Identification: recorded data in, model parameters with uncertainties out.

The names below are imported on first use (PEP 562), so that importing one submodule (e.g.
``identify.errors`` in the command line) does not load YAML, pandas or the fitting code.
"""

from __future__ import annotations

from ..model.lazy import lazy_exports

_WHERE = {"load_params": "paramfile", "params_to_yaml": "paramfile", "save_params": "paramfile",
          "write_atomic": "paramfile"}

__all__ = sorted(_WHERE)


__getattr__, __dir__ = lazy_exports(__name__, _WHERE)
