"""Names of a package imported on first use (PEP 562), so that importing one light submodule
(``model.errors``, ``identify.errors``) from the command line does not load numba, pandas or
YAML: ``leuven-friction --help`` starts at once."""

from __future__ import annotations

import importlib


def lazy_exports(package: str, where: dict[str, str]):
    """Module ``__getattr__`` and ``__dir__`` for ``package`` that import ``name`` from the
    submodule ``where[name]`` the first time it is asked for, then keep it."""
    module_globals = importlib.import_module(package).__dict__

    def __getattr__(name: str):
        mod = where.get(name)
        if mod is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(f".{mod}", package), name)
        module_globals[name] = value
        return value

    def __dir__():
        return sorted(set(module_globals) | set(where))

    return __getattr__, __dir__
