"""Reading a number typed by a person: ``1e-3``, ``2.5E5``, ``0,005``, ``−3`` — or a reason.

The browser's numeric input drops characters it does not expect (``1e-3`` arrives as ``-13``),
so the explorer takes text and parses it here, on the server. Nothing is clamped: a value
is read exactly or refused with a message saying why.
"""

from __future__ import annotations

import math
import re

from ...model.errors import ParameterError

_NUMBER = re.compile(r"^[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?$")


def parse_number(text: str, label: str = "value") -> float:
    """The float a person meant by ``text``; ``ParameterError`` naming ``label`` otherwise.

    Accepts scientific notation (``1e-3``, ``2.5E5``), a decimal comma (``0,005``), the
    Unicode minus sign, spaces and the thin spaces some locales put between digit groups.
    Refuses ``1,000`` (thousands separator or decimal comma?) rather than guess.
    """
    s = str(text).strip().replace("\u2212", "-").replace("\u2009", "").replace("\u202f", "").replace(" ", "")
    if not s:
        raise ParameterError(f"{label}: empty; type a number such as 0.005 or 5e-3")
    if "," in s:
        if "." in s or s.count(",") > 1:
            raise ParameterError(f"{label}: {text!r} mixes separators; write e.g. 1234.5 or 1,5e3")
        head, tail = s.split(",")
        digits = re.match(r"^\d*", tail).group(0)
        if len(digits) == 3 and head.lstrip("+-").isdigit() and head.lstrip("+-") != "0" and digits == tail:
            raise ParameterError(f"{label}: {text!r} is ambiguous (thousands or decimals?); write {head}{tail} or {head}.{tail}")
        s = f"{head}.{tail}"
    if not _NUMBER.match(s):
        raise ParameterError(f"{label}: {text!r} is not a number; type e.g. 0.005, 5e-3 or 0,005")
    x = float(s)
    if not math.isfinite(x):
        raise ParameterError(f"{label}: {text!r} is too large to be a finite number")
    return x


def format_number(x: float) -> str:
    """Short, exact enough to type back: 6 significant digits, scientific outside 1e-3..1e6."""
    if x == 0:
        return "0"
    return f"{x:.6g}"
