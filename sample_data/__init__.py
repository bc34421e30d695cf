"""Sample recordings shipped with the package (see README.md beside them).

``leuven-friction samples --list`` names them, ``leuven-friction samples --out DIR`` copies them
out, and every command that reads a recording accepts ``sample:NAME`` (e.g.
``leuven-friction fit sample:constant_velocity``) for the shipped file.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

PREFIX = "sample:"

DESCRIPTIONS = {
    "constant_velocity": "constant velocities ±(0.001 … 1) rad/s: S(v) of both signs (Table I form)",
    "presliding_proximity": "applied-torque ramps with internal loops, position by a precise proximity sensor",
    "presliding_encoder": "applied-torque ramps, position quantised by the motor encoder (columns t, q, tau)",
    "session_mixed": "the proximity ramps then the constant-velocity runs, headers with units",
    "effect_position_periodic": "a recording with friction that varies periodically with position",
}


def names() -> tuple[str, ...]:
    """The shipped recordings, without the .csv suffix."""
    return tuple(sorted(p.name[:-4] for p in resources.files(__name__).iterdir() if p.name.endswith(".csv")))


def path(name: str) -> Path:
    """The file of a shipped recording (``constant_velocity`` or ``constant_velocity.csv``)."""
    stem = name[len(PREFIX):] if name.startswith(PREFIX) else name
    stem = stem[:-4] if stem.endswith(".csv") else stem
    if stem not in names():
        from ..identify.errors import DataError

        raise DataError(f"{name}: no such sample; the samples are {', '.join(names())}")
    return Path(str(resources.files(__name__).joinpath(stem + ".csv")))


def resolve(source: str) -> str:
    """A recording argument: ``sample:NAME`` becomes the shipped file, anything else is kept."""
    if isinstance(source, str) and source.startswith(PREFIX):
        return str(path(source))
    return source
