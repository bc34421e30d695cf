"""leuven-friction: the Leuven integrated friction model (Swevers, Al-Bender, Ganseman, Prajogo):
simulate, identify, explore and diagnose friction in machines.

In the repository the three parts sit at the root (``model/``, ``identify/``, ``app/``); setuptools
``package-dir`` installs them under this one import name, so that a generic name such as ``model``
never collides with another distribution or with a user's own folder.
"""

__version__ = "0.2.0"

# Run from a checkout without an editable install (``python -c`` or ``python -m`` in the
# repository root, that folder first on sys.path), this folder holds no parts: they sit beside
# it, and are found there, as ``package-dir`` maps them. An installed copy has them inside.
import os as _os

_root = _os.path.dirname(_os.path.dirname(__file__))
if not _os.path.isdir(_os.path.join(_os.path.dirname(__file__), "model")) and _os.path.isfile(
        _os.path.join(_root, "model", "__init__.py")):
    __path__.append(_root)
del _os, _root
