"""leuven-friction: the Leuven integrated friction model (Swevers, Al-Bender, Ganseman, Prajogo):
simulate, identify, explore and diagnose friction in machines.

In the repository the three parts sit at the root (``model/``, ``identify/``, ``app/``); setuptools
``package-dir`` installs them under this one import name, so that a generic name such as ``model``
never collides with another distribution or with a user's own folder.
"""

__version__ = "0.2.0"
