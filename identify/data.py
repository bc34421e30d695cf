"""Recorded data: CSV/TSV in, validated SI arrays out.

Users name their columns in many ways and often write units in the header
(``Position [mm]``, ``Friction (uN)``, ``Time (s)``). ``load_recording`` recognises the common
names, accepts an explicit mapping (``{"time": "t", "position": "q", "force": "tau"}``),
converts units to SI and says what it assumed. Every problem is a ``DataError`` whose one-line
message names the file, the column and the row (rows are numbered as lines of the file,
the header being line 1).
"""

from __future__ import annotations

import io
import math
import re
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from .columns import ALIASES, COF_NAMES, UNITS_ACCEPTED
from .errors import DataError, IdentificationError

SIGNALS = ("time", "position", "force", "velocity", "friction", "normal_load", "temperature")


# factor to SI, and the SI unit it lands in
UNITS = {
    "s": (1.0, "s"), "sec": (1.0, "s"), "ms": (1e-3, "s"), "us": (1e-6, "s"), "µs": (1e-6, "s"), "min": (60.0, "s"),
    "m": (1.0, "m"), "mm": (1e-3, "m"), "um": (1e-6, "m"), "µm": (1e-6, "m"), "micron": (1e-6, "m"), "nm": (1e-9, "m"),
    "rad": (1.0, "rad"), "mrad": (1e-3, "rad"), "urad": (1e-6, "rad"), "µrad": (1e-6, "rad"),
    "deg": (np.pi / 180, "rad"), "°": (np.pi / 180, "rad"), "degree": (np.pi / 180, "rad"),
    "degrees": (np.pi / 180, "rad"),
    # a telescope's or an optical stage's angle: minutes and seconds of arc (′ and ″, the primes,
    # not the quotes a CSV writes its fields in)
    "arcmin": (np.pi / 10800, "rad"), "arcminute": (np.pi / 10800, "rad"), "arcminutes": (np.pi / 10800, "rad"),
    "′": (np.pi / 10800, "rad"), "arcsec": (np.pi / 648000, "rad"), "arcsecond": (np.pi / 648000, "rad"),
    "arcseconds": (np.pi / 648000, "rad"), "″": (np.pi / 648000, "rad"),
    # a turn of a spindle or a disc; its speed in turns a minute (rev/min, 1/min: a quotient)
    "rev": (2 * np.pi, "rad"), "revs": (2 * np.pi, "rad"), "turn": (2 * np.pi, "rad"), "turns": (2 * np.pi, "rad"),
    "rpm": (2 * np.pi / 60, "rad/s"), "u/min": (2 * np.pi / 60, "rad/s"), "1/min": (2 * np.pi / 60, "rad/s"),
    "n": (1.0, "N"), "mn": (1e-3, "N"), "un": (1e-6, "N"), "µn": (1e-6, "N"), "kn": (1e3, "N"), "megan": (1e6, "N"),
    "nm_torque": (1.0, "N*m"), "n*m": (1.0, "N*m"), "n.m": (1.0, "N*m"), "n m": (1.0, "N*m"), "mnm": (1e-3, "N*m"),
    "m/s": (1.0, "m/s"), "mm/s": (1e-3, "m/s"), "um/s": (1e-6, "m/s"), "rad/s": (1.0, "rad/s"),
    "deg/s": (np.pi / 180, "rad/s"), "c": (1.0, "degC"), "degc": (1.0, "degC"), "°c": (1.0, "degC"), "k": (1.0, "K"),
    # inch-pound (exact by definition: 1 in = 25.4 mm, 1 lbf = 0.45359237 kg × 9.80665 m/s²); a
    # "lb" in a force or friction column is a pound-force
    "in": (0.0254, "m"), "inch": (0.0254, "m"), "mil": (2.54e-5, "m"), "ft": (0.3048, "m"),
    "lbf": (4.4482216152605, "N"), "lb": (4.4482216152605, "N"), "ozf": (4.4482216152605 / 16, "N"),
}

_KNOWN_NAMES = frozenset(a for names in ALIASES.values() for a in names)

# Words of a header name (``tau_motor``, ``F_friction``, ``x_mm``) that say its signal, tried
# where no name above matches the whole of it, in this order (a friction word wins over a force
# word: ``F_friction`` is measured friction). Only for the signals a fit or a diagnosis cannot do
# without and for measured friction: a velocity, load or temperature changes what is compared
# (``motor_speed``, ``load_cell``), so those are taken by their full names alone.
WORDS = {
    "friction": ("friction", "fric", "reibkraft", "reibmoment", "reibung"),
    "time": ("time", "t", "timestamp", "zeit"),
    "position": ("position", "pos", "x", "q", "angle", "theta", "displacement", "disp", "encoder", "enc", "weg",
                 "winkel"),
    "force": ("force", "torque", "tau", "trq", "moment", "kraft", "drehmoment", "effort", "f"),
}
# a reference, an estimate or a model of a signal is not the signal ...
_NOT_MEASURED = frozenset(("ref", "des", "desired", "target", "err", "error", "model", "est", "estimate", "estimated",
                           "comp", "compensation", "ff", "feedforward", "sim", "simulated", "pred", "predicted",
                           "nominal", "offset", "limit", "max", "min"))
# ... nor a command of a motion (a commanded torque is the applied one)
_COMMANDED = frozenset(("cmd", "command", "commanded", "setpoint", "sp", "demand"))

# the SI units each signal may land in (a header's unit of another kind is refused), and their names
# (a normal load may be a moment: a slewing ring's or a pitch bearing's tilting moment presses its
# raceways as a force does, and the load law reads only N/N0)
SI_OF = {"time": ("s",), "position": ("m", "rad"), "force": ("N", "N*m"), "friction": ("N", "N*m"),
         "velocity": ("m/s", "rad/s"), "normal_load": ("N", "N*m"), "temperature": ("degC", "K")}
_KIND = {"s": "time", "m": "length", "rad": "angle", "N": "force", "N*m": "torque", "m/s": "speed",
         "rad/s": "angular speed", "degC": "temperature", "K": "temperature"}


# a product's factors may be written with any of these between them (N·m, N*m, N.m, N m, N×m, N-m)
_PRODUCT = re.compile(r"\s*[*·⋅.×-]\s*|\s+")
# the single units a product or a quotient is made of, by kind (the lower-case keys of UNITS)
_FORCE = ("n", "mn", "un", "µn", "kn", "megan", "lbf", "lb", "ozf")
_LENGTH = ("m", "mm", "um", "µm", "nm", "in", "ft")


def _single(word: str) -> tuple[float, str] | None:
    """A unit written as one word: UNITS, or a force and a length run together (Nmm, mNm, kNm)."""
    if word in UNITS:
        return UNITS[word]
    for f in _FORCE:
        if word.startswith(f) and word[len(f):] in _LENGTH and word[len(f):] != "nm":
            return UNITS[f][0] * UNITS[word[len(f):]][0], "N*m"
    return None


def _compound(key: str) -> tuple[float, str] | None:
    """A product of a force and a length (a torque) or a quotient of a length or an angle by a
    time (a speed), each part a ``_single`` unit; None for anything else."""
    num, slash, den = key.partition("/")
    parts = [_single(w) for w in _PRODUCT.split(num.strip()) if w]
    if not parts or any(p is None for p in parts):
        return None
    factor = float(np.prod([p[0] for p in parts]))
    dims = sorted(p[1] for p in parts)
    if slash:
        d = _single(den.strip())
        if len(parts) != 1 or d is None or d[1] != "s" or dims[0] not in ("m", "rad"):
            return None
        return factor / d[0], f"{dims[0]}/s"
    if dims == ["N", "m"]:
        return factor, "N*m"
    return (factor, dims[0]) if len(dims) == 1 else None


def unit_of(unit: str, sig: str) -> tuple[float, str] | None:
    """(factor to SI, SI unit) of a header's unit for ``sig``; None when unknown. 'Nm' in a force
    or friction column is newton-metre, not nanometre; a torque may be written as a product in
    any of the usual ways (N·m, N*m, N.m, mN·m, N·mm, Nmm), a speed as a quotient (mm/s)."""
    raw = unit.strip()
    # read without case but for 'MN': M is mega where m is milli (a bearing's MN·m; 'MN' lowered
    # had been read as mN, 10⁹ times small)
    key = ("megan" + raw[2:] if raw.startswith("MN") else raw).lower()
    # the Greek small mu (U+03BC, what many keyboards and loggers write) as the micro sign (U+00B5)
    key = key.replace("\u03bc", "\u00b5")
    if key.replace(" ", "") == "nm" and sig in ("force", "friction", "normal_load"):
        return UNITS["nm_torque"]
    if key.replace(" ", "") in UNITS:
        return UNITS[key.replace(" ", "")]
    # a size written with a decimal comma ('5,9 N' in a European header) is the same size
    scaled = _SCALED.match(re.sub(r"^(\d+),(\d+)", r"\1.\2", key))
    if scaled:
        # a unit with a size in front ('50 nm', '0.001 deg'): what one count of an encoder is
        size, base = float(scaled[1]), unit_of(scaled[2], sig)
        return (size * base[0], base[1]) if base is not None and size > 0 else None
    return _compound(key)


_SCALED = re.compile(r"^(\d*\.?\d+(?:e[-+]?\d+)?)\s*(?:[*·]\s*)?(\D.*)$")
# units that count steps and say nothing of their size (``unit_of`` takes '50 nm' for one)
COUNTS = ("count", "counts", "cts", "ct", "inc", "incs", "increments", "pulses", "ticks", "lsb", "steps")


CURRENTS = ("a", "ma", "amp", "amps", "ampere", "amperes")  # a motor current, which is no force until scaled
# the words of a motor current's name: with a force's or a torque's unit (its constant per A) it is the applied force
CURRENT_NAMES = ("current", "curr", "strom", "motorstrom", "iq", "amps")
MASSES = ("kg", "g", "lb", "lbm", "t")  # a mass, which is no force until weighed (a payload logged as such)


def header_unit(column: str) -> str | None:
    """The unit a column's header gives in brackets ("temperature [°C]" → "°C"), or None."""
    return _split_header(column)[1]


def is_current_unit(unit: str | None) -> bool:
    return unit is not None and unit.strip().lower() in CURRENTS


def current_word(column: str) -> str | None:
    """The current unit a header name without brackets writes as its last word, as spelled
    (``current_A`` → "A", ``iq_mA`` → "mA"), or None: a motor current logged so is still no
    force (a haptic joint made apart, ``current_A`` named as its force, was read in N·m)."""
    key, unit = _split_header(column)
    words = [w for w in key.split("_") if w]
    if unit is not None or len(words) < 2 or words[-1] not in CURRENTS:
        return None
    return _as_spelled(column, words[-1])


def is_mass_unit(unit: str | None) -> bool:
    return unit is not None and unit.strip().lower() in MASSES


def _current_fix(column: str, unit: str) -> str:
    """What to write for a column logged as a motor current in ``unit`` (one of
    CURRENTS): the torque (or force) constant per that unit as its unit. (In mA the constant
    per mA is a thousandth of the N·m/A a data sheet gives: '[0.05 N*m]' over a current in mA
    reads a thousand times the torque, which nothing downstream can tell.)"""
    m = _UNIT_RE.match(str(column).strip())
    name = (m.group(1) if m else str(column)).strip()  # as the file spells it, without its unit
    milli = unit.strip().lower() == "ma"
    rotary, linear = ("0.12 mN*m", "35 mN") if milli else ("0.12 N*m", "35 N")
    return (f"a motor current is no force: the torque is the motor's torque constant times it; write that constant "
            f"per {'mA' if milli else 'A'} as its unit, e.g. '{name} [{rotary}]' for 0.12 N·m/A (a linear motor: "
            f"'{name} [{linear}]' for 35 N/A), or give it as {columns_option('force', column)} --units \"force={rotary}\"")


def _counts_fix(name: str) -> str:
    """What to write for a column ``name`` logged in counts: the size of one step as its unit."""
    return f"write the size of one step as its unit, e.g. '{name} [50 nm]' or '{name} [0.001 deg]'"


def _fits(unit: str | None, sig: str) -> bool:
    u = unit_of(unit, sig) if unit is not None else None
    return u is not None and u[1] in SI_OF[sig]


def may_be_load(column: str) -> bool:
    """Whether a column no signal was taken from may hold a normal load by its header's unit: none
    given, one of a force or a moment, a mass (a payload, once weighed: ``is_mass``), or one not
    known here (a clamp's pressure in bar presses a contact too); not a unit of another kind (a
    winding's °C, a time, a length) nor a current (a motor's, which drives, not presses)."""
    unit = _split_header(column)[1]
    if is_current_unit(unit):
        return False
    u = unit_of(unit, "normal_load") if unit is not None else None
    return u is None or u[1] in SI_OF["normal_load"]


def is_mass(column: str) -> bool:
    """Whether a column's header gives it a mass's unit (a payload in kg): no load until weighed
    ("lb", read as pound-force in a load's column, is not one)."""
    unit = _split_header(column)[1]
    return is_mass_unit(unit) and unit_of(unit, "normal_load") is None


def _reads_as_not_measured(key: str, sig: str) -> str:
    """What a header name's words say a column of signal ``sig`` is if not a measurement ("a
    reference (ref)", "a command (cmd)" of a motion; a commanded force is the one applied), or "":
    such a column is not recognised by its words (``recognise``), and one named as asked is said."""
    for w in (w for w in key.split("_") if w):
        if w in _COMMANDED and sig in ("time", "position", "velocity"):
            return f"a command ({w})"
        if w in _NOT_MEASURED:
            return f"a reference, model or estimate ({w})"
    return ""


def split_unit_word(key: str) -> tuple[list, str | None]:
    """A header name without brackets as its words and the unit written as its last word
    (``x_mm`` → (["x"], "mm")), or all its words and None."""
    words = [w for w in key.split("_") if w]
    return (words[:-1], words[-1]) if len(words) > 1 and words[-1] in UNITS else (words, None)


def unit_word_of(key: str, sig: str) -> str | None:
    """The unit a header name without brackets writes as its last word, if a unit of signal
    ``sig`` (``force_kn`` → "kn" for a force; ``x_mm`` → "mm" for a position), else None."""
    word = split_unit_word(key)[1]
    return word if _fits(word, sig) else None


def _as_spelled(col: str, unit_word: str) -> str:
    """A unit word read from a header name, as the header spells it ('friction_mN' → 'mN'), for the notes."""
    tail = str(col).strip()[-len(unit_word):]
    return tail if tail.lower() == unit_word else unit_word


def recognise(key: str, unit: str | None = None) -> list:
    """The signals a header name (lower case, its bracketed ``unit`` apart) may name by its words,
    most likely first, each with a unit written as the name's last word (or None):
    ``tau_motor`` → force, ``f_friction`` → friction, ``x_mm`` → position in mm, ``t_oil_c`` →
    the alias ``t_oil`` in °C. A signal the bracketed unit is not a unit of is passed over
    (``tau_load [N*m]`` is no normal load), and so is a reference or an estimate (``q_ref``,
    ``friction_model``). [] when no word says."""
    words, word_unit = split_unit_word(key) if unit is None else ([w for w in key.split("_") if w], None)
    base = "_".join(words)
    for sig, names in ALIASES.items():
        if word_unit is not None and base in names:  # a known name followed by its unit
            return [(sig, word_unit if _fits(word_unit, sig) else None)]
    out = []
    for sig, names in WORDS.items():
        if not any(w in names for w in words) or _reads_as_not_measured(base, sig):
            continue
        if unit is not None and not _fits(unit, sig):
            continue
        # a last word that is no unit of this signal ("tau_m") is part of the name
        out.append((sig, word_unit if _fits(word_unit, sig) else None))
    if not out and unit is not None and any(w in CURRENT_NAMES for w in words) and _fits(unit, "force") \
            and not _reads_as_not_measured(base, "force"):
        # a motor's current whose bracket gives its torque constant per A as the unit, as the
        # README asks (``motor_current [0.11 N*m]``), is the applied torque: its unit says so
        # (a wrist joint made apart, logged so as told, still had to be named with --columns)
        out.append(("force", None))
    return out


MIN_SAMPLES = 10
# rows with an empty cell in a signal read (a logger's dropped sample) are left out, with a
# note, up to this share of the rows; more is no dropout but a column that does not hold that
# signal, and is refused
EMPTY_ROWS_DROPPED = 0.01


@dataclass
class Recording:
    """One recording in SI units. ``force`` is the applied force (or motor torque)."""

    time: np.ndarray
    position: np.ndarray | None = None
    force: np.ndarray | None = None
    velocity: np.ndarray | None = None
    friction: np.ndarray | None = None
    normal_load: np.ndarray | None = None
    temperature: np.ndarray | None = None
    source: str = "<memory>"
    columns: dict = field(default_factory=dict)  # signal -> column name in the file
    units: dict = field(default_factory=dict)  # signal -> SI unit
    notes: list = field(default_factory=list)  # what was assumed or converted
    units_assumed: str = ""  # the note of ``_assume_si`` where a header gave no unit (also in ``notes``)
    ignored: list = field(default_factory=list)  # the file's columns no signal was taken from
    ambiguous: dict = field(default_factory=dict)  # signal -> columns whose names could each be it
    turned: set = field(default_factory=set)  # signals taken with their sign turned (``--columns force=-F``)

    def sign_mend(self, sig: str) -> str:
        """The ``--columns`` option that turns signal ``sig``'s sign from the way it was read: the
        column negated, or, where it was taken negated as asked, taken as it is (a pneumatic
        slide's force turned by the user was told to turn it again, the same option)."""
        return columns_option(sig, self.columns.get(sig, "<column>"), sig not in self.turned)

    def unrecognised(self, *signals: str) -> str:
        """Why none of the file's columns was taken as one of ``signals``, for a message."""
        could = [f"{', '.join(self.ambiguous[s])} could each be {s}" for s in signals if s in self.ambiguous]
        if could:
            return "; ".join(could)
        currents = [(c, key, unit) for c in self.ignored for key, unit in [_split_header(c)]
                    if is_current_unit(unit or current_word(c))]
        if currents and {"force", "friction"} & set(signals):
            col, key, unit = currents[0]
            unit = unit or current_word(col)
            return f"column {col!r} is a current ({unit}): {_current_fix(col, unit)}"
        if not self.ignored:
            return ""
        near = misspelt_column(self.ignored, signals)
        guess = (f" ({near[0]!r} reads like {near[2]!r} misspelt: {columns_option(near[1], near[0])})"
                 if near else "")
        return f"none of {_listing(self.ignored)} was recognised as one{guess}"

    def __len__(self) -> int:
        return len(self.time)

    def has(self, signal: str) -> bool:
        return getattr(self, signal) is not None


_UNIT_RE = re.compile(r"^(.*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*$")


def _listing(cols, most: int = 8) -> str:
    """Column names for a one-line message: the first ``most`` of a wide file, and how many more."""
    cols = list(cols)
    return ", ".join(cols[:most]) + (f" and {len(cols) - most} more" if len(cols) > most else "")


# words of a column's name that say whether the machine is rotary or linear, for a header with no
# unit (``_assume_si``): a column named 'force' is in N, one named 'torque' in N·m
_ROTARY_WORDS = frozenset(("torque", "tau", "trq", "moment", "drehmoment", "angle", "theta", "q", "winkel", "omega",
                           "qd"))
_LINEAR_WORDS = frozenset(("force", "kraft", "f", "x", "displacement", "disp", "weg"))
_SI_BY_KIND = {"rotary": {"position": "rad", "velocity": "rad/s", "force": "N*m", "friction": "N*m"},
               "linear": {"position": "m", "velocity": "m/s", "force": "N", "friction": "N"}}


def _assume_si(rec: "Recording", unitless: list) -> str:
    """SI units for the signals ``unitless`` whose header gave none: those of a linear machine
    (m, N) or a rotary one (rad, N·m), as the recording's other units or its column names say
    (a unit given elsewhere wins over a name); rotary where nothing says. The note for the user."""
    kinds = {k for sig, u in rec.units.items() for k, table in _SI_BY_KIND.items() if table.get(sig) == u}
    why = "the units of its other columns"
    if not kinds:
        words = {w for sig in unitless for w in _split_header(rec.columns[sig])[0].split("_")}
        kinds = {k for k, ws in (("rotary", _ROTARY_WORDS), ("linear", _LINEAR_WORDS)) if words & ws}
        why = "the column names"
    kind = kinds.pop() if len(kinds) == 1 else None
    table = _SI_BY_KIND[kind or "rotary"]
    # the normal load is a force on either kind of machine (it tells neither kind apart, so it is not in the table)
    table = {**table, "normal_load": "N"}
    for sig in unitless:
        if sig in table:
            rec.units[sig] = table[sig]
    given = ", ".join(f"{rec.columns[s]} in {table[s]}" for s in unitless if s in table)
    time = ["time in s"] if "time" in unitless else []
    said = ", ".join(time + ([given] if given else []))
    counts = (_counts_hint(rec) or _speed_hint(rec, kind)) if "position" in unitless else ""
    if kind:
        return f"no unit in the header of {said}: assumed SI, a {kind} machine's (as {why} say){counts}"
    return (f"no unit in the header of {said}: assumed SI, a rotary machine's (nothing says linear or rotary: "
            f"write the units in the header, e.g. 'position [m]', 'force [N]'){counts}")


COUNTS_SPAN = 1000  # a unitless position of whole numbers over more than this many of them reads as encoder counts


def _counts_hint(rec: "Recording") -> str:
    """For a position read without a unit: where it holds only whole numbers spread over more than
    COUNTS_SPAN of them (an encoder's counts, not metres or radians), what to write instead. A
    gantry made apart, its counts read as metres, had v_s written as 414 m/s without a word."""
    x = np.asarray(rec.position, dtype=np.float64)
    finite = x[np.isfinite(x)]
    if not len(finite) or np.ptp(finite) <= COUNTS_SPAN or np.any(finite != np.round(finite)):
        return ""
    return (f"; its position holds only whole numbers over {np.ptp(finite):.0f} of them: if those are encoder "
            f"counts, write the size of one as its unit, e.g. '{rec.columns['position']} [0.01 mm]'")


# Faster than machines of a kind move, read in that kind's SI unit: linear-motor axes reach a few
# m/s, spindles ~2000 rad/s (19,000 rpm). Not a threshold of any method: only what a note says of
# a position whose header gave no unit (a stage's µm read as metres moved at 10⁴ m/s).
IMPLAUSIBLE_SPEED = {"linear": 20.0, "rotary": 2000.0}
_SMALLER_UNITS = {"linear": ("mm", "um"), "rotary": ("deg", "mrad")}
SPEED_SPAN = 10  # samples the speed is taken over: a position updated less often than logged, or a jittery clock, is not read as fast


def _speed_hint(rec: "Recording", kind: str | None) -> str:
    """For a position read without a unit as SI (``kind`` None: a rotary machine's, nothing said
    which): where its speed (99th percentile over SPEED_SPAN samples) is beyond
    IMPLAUSIBLE_SPEED for the kind of machine, what to write instead."""
    x = np.asarray(rec.position, dtype=np.float64)
    t = np.asarray(rec.time, dtype=np.float64)
    k = min(SPEED_SPAN, len(x) - 1)
    if k < 1:
        return ""
    dx, dt = x[k:] - x[:-k], t[k:] - t[:-k]
    ok = np.isfinite(dx) & np.isfinite(dt) & (dt > 0)
    if not ok.any():
        return ""
    speed = float(np.quantile(np.abs(dx[ok] / dt[ok]), 0.99))
    read_as = kind or "rotary"  # what _assume_si took where nothing says
    if speed <= IMPLAUSIBLE_SPEED[read_as]:
        return ""
    u = _SI_BY_KIND[read_as]["position"]
    col = rec.columns["position"]
    units = _SMALLER_UNITS[kind] if kind else _SMALLER_UNITS["linear"] + _SMALLER_UNITS["rotary"]
    return (f"; read as {u}, its position moves at {speed:.3g} {u}/s (99th percentile), faster than "
            f"{f'a {kind} machine moves' if kind else 'machines move'}: if it is in a smaller unit, write it in the header, "
            f"e.g. " + " or ".join(f"'{col} [{w}]'" for w in units))


_UNCLOSED_RE = re.compile(r"^(.*?\S)\s*([\[(])\s*([^\])]+?)\s*$")


def _unit_unclosed(name: str) -> str | None:
    """The header ``name`` with its unit's bracket closed, where it opens one and never closes
    it ('torque [mN*m' -> 'torque [mN*m]'); None otherwise."""
    m = _UNCLOSED_RE.match(str(name).strip())
    if m is None or _UNIT_RE.match(str(name).strip()):
        return None
    return str(name).strip() + ("]" if m.group(2) == "[" else ")")


def _split_header(name: str) -> tuple[str, str | None]:
    """'Position [mm]' -> ('position', 'mm'); 'Time (s)' -> ('time', 's')."""
    m = _UNIT_RE.match(str(name).strip())
    base, unit = (m.group(1), m.group(2)) if m else (str(name).strip(), None)
    key = re.sub(r"[^0-9a-zA-Z_]+", "_", base.strip().lower()).strip("_")
    return key, unit


NO_COLUMN = "-"  # ``--columns velocity=-``: take no column for this signal, not even a recognised one
NEGATED = "-"  # ``--columns force=-F_coil``: that column with its sign turned (a sensor mounted the other way)


def _empty(cell) -> bool:
    """A table cell that holds nothing (NaN as read, or blank text)."""
    return cell is None or (isinstance(cell, float) and math.isnan(cell)) or not str(cell).strip()


def misspelt_column(columns, signals) -> tuple[str, str, str] | None:
    """The first of ``columns`` one of whose words is a misspelling of a word that names one of
    ``signals`` (``tua_motor`` → tau, a force), as (column, signal, word), or None: the same
    letters in another order, or at most a letter longer or shorter and 75 % alike (difflib's
    ratio). Words of three letters or more only, and only where the column's unit may be the
    signal's: a short word ("f", "u") is close to too much ("status" holds "tau"), and a speed in
    deg/s is no torque however it is spelt."""
    import difflib

    for col in columns:
        key, unit = _split_header(col)
        words = [w for w in split_unit_word(key)[0] if len(w) >= 3]
        for sig in signals:
            if unit is not None and not _fits(unit, sig):
                continue
            names = [n for n in WORDS.get(sig, ()) + ALIASES.get(sig, ()) if len(n) >= 3]
            for w in words:
                for n in names:
                    if w == n or abs(len(w) - len(n)) > 1:
                        continue
                    if sorted(w) == sorted(n) or difflib.SequenceMatcher(None, w, n).ratio() >= 0.75:
                        return col, sig, n
    return None


def columns_option(sig: str, col: str, negated: bool = False) -> str:
    """The ``--columns`` option that takes column ``col`` as signal ``sig`` (with its sign
    turned if ``negated``), quoted for a shell where the name has a space or a bracket."""
    pair = f"{sig}={NEGATED if negated else ''}{col}"
    return f'--columns "{pair}"' if re.search(r"[\s\[\]()*;&|<>$'\\]", pair) else f"--columns {pair}"


def _signal_pairs(spec: str, option: str, what: str) -> list[tuple[str, str]]:
    """The 'signal=value' pairs of an option's comma-separated ``spec``, each signal known."""
    out = []
    # a comma separates pairs only where a 'name=' follows it: a decimal comma stays in its
    # value ("force=5,9 N", a European torque constant; "force=Motorstrom [5,9 N]"), and a
    # signal misnamed ("load=Fz") is refused as one, not read into the column before it
    for part in re.split(r",(?=\s*[A-Za-z_]\w*\s*=)", spec):
        if "=" not in part or part.rstrip().endswith(","):
            raise DataError(f"{option}: expected signal={what} pairs separated by commas, got {part!r}")
        k, v = (s.strip() for s in part.split("=", 1))
        if k not in SIGNALS:
            raise DataError(f"{option}: unknown signal {k!r}; known: {', '.join(SIGNALS)}")
        out.append((k, v))
    return out


def parse_unit_mapping(spec: str | None) -> dict:
    """'force=0.025 N*m,time=ms' -> {'force': '0.025 N*m', 'time': 'ms'}: each signal's unit,
    as a header's brackets would give it (over the header's own), for a file that cannot be
    edited (a motor current in A, its torque constant the unit)."""
    out = {}
    for k, v in _signal_pairs(spec, "--units", "unit") if spec else ():
        if not v:
            raise DataError(f"--units: no unit given for {k}")
        out[k] = v
    return out


def parse_column_mapping(spec: str | None) -> dict:
    """'time=t,position=q,force=tau' -> {'time': 't', 'position': 'q', 'force': 'tau'};
    ``velocity=-`` -> {'velocity': None}: that signal is taken from no column."""
    return {k: None if v == NO_COLUMN else v for k, v in _signal_pairs(spec, "--columns", "column")} if spec else {}


def units_row(df: pd.DataFrame) -> dict | None:
    """{column: unit} where a table's first row under its header holds units rather than
    numbers (a DAQ export: names, then units, then data): none of its cells a number, each
    empty or a unit of some signal (or counts, or amperes, refused later with their fix), and
    at least one a unit. None otherwise."""
    if len(df) < 2:
        return None
    out = {}
    for col, cell in df.iloc[0].items():
        text = "" if cell is None or (isinstance(cell, float) and np.isnan(cell)) else str(cell).strip()
        text = text.strip("[]() ")
        if not text:
            continue
        try:
            float(text.replace(",", "."))
            return None
        except ValueError:
            pass
        low = text.lower()
        if low in COUNTS or low in CURRENTS or any(unit_of(text, sig) is not None for sig in SI_OF):
            out[str(col)] = text
        else:
            return None
    return out or None


def clock_seconds(raw: pd.Series) -> np.ndarray | None:
    """A time column written as clock readings — dates and times ('2026-11-29 10:15:03.125',
    ISO 8601) or times of day ('10:15:03.125') — as seconds from its first row, NaN in a cell
    that is no clock reading; None where most cells are none (the column is numbers or words).
    A time of day that falls back by over twelve hours has passed midnight."""
    if pd.api.types.is_numeric_dtype(raw.dtype):
        return None
    text = raw.astype(str).str.strip()
    if text.str.contains(":").mean() < 0.5:
        return None
    dated = text.str.contains(r"\d[-/.]\d+[-/.]\d", regex=True).mean() >= 0.5
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            parsed = (pd.to_datetime(text, format="mixed", errors="coerce") if dated
                      else pd.to_timedelta(text, errors="coerce"))
        except (ValueError, TypeError, OverflowError):
            return None
    ok = parsed.notna().to_numpy()
    if ok.mean() < 0.5:
        return None
    sec = (parsed - parsed[ok].iloc[0]).dt.total_seconds().to_numpy(dtype=np.float64, copy=True)
    if not dated:
        # past midnight: a time of day falling back by over twelve hours between readings (a
        # date says the day itself, and a clock of dates going back is refused below)
        sec[ok] += 86400.0 * np.concatenate([[0], np.cumsum(np.diff(sec[ok]) < -43200.0)])
    return sec


def numbers_of(raw: pd.Series, decimal: str = ".") -> np.ndarray:
    """A column's values as floats, NaN where a cell is no number. In a table with the decimal
    comma, a column that holds a word somewhere is read as text with its numbers' commas in
    place: they are read as decimal marks here, so the message names the word, not the first
    number (which "0,5" would otherwise be)."""
    if decimal != "." and not pd.api.types.is_numeric_dtype(raw.dtype):
        raw = raw.map(lambda c: c.replace(decimal, ".") if isinstance(c, str) else c)
    return pd.to_numeric(raw, errors="coerce").to_numpy(dtype=np.float64)


def _read_table(path: Path, text: str) -> pd.DataFrame:
    """Guess the separator from the header (the first line that is not a ``#`` comment):
    tab, semicolon (European CSV: then a comma is the decimal mark), comma, or whitespace."""
    from .io import TAIL_BYTES, csv_options, last_cell_cut, preamble_lines, sniff  # shared with the reader of files

    lines = text.splitlines()
    skip = preamble_lines(lines[:1000])
    sep, decimal = sniff(lines[skip:])
    try:
        df = pd.read_csv(io.StringIO(text), **csv_options(sep, decimal, skip))
        df.attrs["decimal"] = decimal
        df.attrs["preamble"] = skip
        df.attrs["last_cell_cut"] = last_cell_cut(text[-TAIL_BYTES:], sep, decimal)
        return df
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        raise DataError(f"{path}: not a readable CSV/TSV table ({msg})") from None


def load_recording(source, *, columns: dict | None = None, units: dict | None = None,
                   require: tuple = ("time",), name: str | None = None, only: tuple | None = None) -> Recording:
    """Read a recording from a path, or from bytes/str content (``name`` labels messages).

    ``columns`` maps signals to column names, or to None for a signal to take from no column
    (a recognised name is then left alone); ``units`` maps signals to unit names and
    overrides what the header says. Columns not recognised are ignored (listed in ``notes``).
    ``only``: the signals the caller uses (with ``require``); a column recognised as another
    one is not read, so a gap in a column the command does not use is no error.
    """
    refused = {sig for sig, col in (columns or {}).items() if col is None}
    columns = {sig: col for sig, col in (columns or {}).items() if col is not None}
    encoding = "utf-8-sig"
    if isinstance(source, (bytes, bytearray)):
        from .io import decode_text

        label = name or "<upload>"
        text, encoding = decode_text(bytes(source), label)
        path = Path(label)
    elif isinstance(source, str) and ("\n" in source) and name:
        text, path = source, Path(name)
    else:
        path = Path(source)
        text = None  # read straight from the file by identify.io: CSV/TSV, Parquet or MATLAB .mat
    if text is not None and not text.strip():
        raise DataError(f"{path}: the file is empty")
    if text is None:
        from .io import read_table_file

        # only the columns a signal can come from: the other columns of a wide file cost nothing
        explicit = set((columns or {}).values())
        keys = _KNOWN_NAMES | COF_NAMES | {_split_header(c)[0] for c in explicit}  # "Zeit" reads "Zeit [ms]" too
        df = read_table_file(path, usecols=lambda c: (str(c) in explicit or _split_header(c)[0] in keys
                                                      or bool(recognise(*_split_header(c)))))
    else:
        df = _read_table(path, text)
    encoding = df.attrs.get("encoding", encoding)
    # rows that are no samples: a DAQ's export with its units in the row under the names (read
    # there), and rows with every cell empty (a spreadsheet's trailing ",,,"); the others keep
    # the file's numbering in messages
    row_units = units_row(df)
    rows = np.flatnonzero(~df.isna().all(axis=1).to_numpy())
    blank = len(df) - len(rows)
    if row_units is not None:
        rows = rows[rows > 0]
    if len(rows) < len(df):
        df = _rows_kept(df, rows)

    def row_of(index: int) -> int:
        """The row a message names: the file's line (comments and blank lines counted, as an
        editor or a spreadsheet numbers them), or in a Parquet or .mat table the header's row + 1."""
        from .io import file_line_of_row, line_of_row, table_format

        index = int(rows[index])
        line = None
        if text is not None:
            line = line_of_row(text.splitlines(), index, df.attrs.get("preamble", 0))
        elif table_format(path) not in ("parquet", "mat"):
            line = file_line_of_row(path, index, df.attrs.get("preamble", 0))
        return line if line is not None else index + 2

    in_file = [str(c) for c in df.attrs.get("columns_in_file", df.columns)]
    if not in_file or (df.shape[1] > 0 and len(df) == 0):
        raise DataError(f"{path}: no data rows under the header")

    mapping = dict(columns or {})
    headers = {str(c): _split_header(c) for c in df.columns}
    if row_units:
        for c, unit in row_units.items():
            if headers[str(c)][1] is None:
                headers[str(c)] = (headers[str(c)][0], unit)
    def named(col: str) -> str | None:
        """The file's column ``col`` names: itself, or the one whose header is that name with a
        unit ("Zeit" for "Zeit [ms]"); None if none or several."""
        if col in headers:
            return col
        same = [c for c, (key, _) in headers.items() if _split_header(col)[0] == key and _split_header(col)[1] is None]
        return same[0] if len(same) == 1 else None

    negated = set()
    for sig, col in list(mapping.items()):
        found = col if col in headers else None  # (a column whose own name starts with '-' is itself)
        if found is None and col.startswith(NEGATED) and (found := named(col[len(NEGATED):].strip())) is not None:
            negated.add(sig)
        found = found or named(col)
        if found is None:
            raise DataError(f"{path}: column {col!r} given for {sig} is not in the file (columns: {', '.join(in_file)})"
                            + ("; a leading '-' takes a column with its sign turned, e.g. force=-F" if "-" not in col
                               and sig in ("force", "friction", "position", "velocity") else ""))
        mapping[sig] = found
        key, unit = headers[found]
        if unit is None and (word := unit_word_of(key, sig)) is not None:
            # a column named as asked reads its unit from its name as one recognised by its
            # words does ('force_kN' as force in kN, '-position/mm' turned and in mm): read as
            # SI, a guideway's force in kN came out a thousand times too small
            headers[found] = (key, _as_spelled(found, word))
        elif unit is None and sig in ("force", "friction") and (word := current_word(found)) is not None:
            headers[found] = (key, word)  # refused below as a current, with the constant to write
    taken = set(mapping.values())
    for sig in SIGNALS:
        if sig in mapping or sig in refused:
            continue
        for col, (key, _) in headers.items():
            if col not in taken and key in ALIASES[sig]:
                mapping[sig] = col
                taken.add(col)
                break
    # then by the words of the names left (``recognise``): each column for the first signal it
    # may be that no column has yet; one column a signal, none where two could be it
    by_words = {}
    for col, (key, unit) in headers.items():
        if col in taken:
            continue
        for sig, unit_word in recognise(key, unit):
            if sig not in mapping and sig not in refused:
                by_words.setdefault(sig, []).append(col)
                if unit is None and unit_word is not None:
                    headers[col] = (key, _as_spelled(col, unit_word))
                break
    notes = []
    if skip := df.attrs.get("preamble", 0):
        notes.append(f"line(s) 1–{skip} before the header (line {skip + 1}) read as the file's own notes (an "
                     f"instrument's export opens so), not as the table: skipped")
    if blank:
        notes.append(f"{blank} row(s) with every cell empty: skipped")
    if row_units:
        notes.append(f"units read from the row under the header ({', '.join(f'{c}: {u}' for c, u in row_units.items())})")
    ambiguous = {}
    for sig, cols in by_words.items():
        if len(cols) == 1:
            mapping[sig] = cols[0]
            notes.append(f"{cols[0]}: taken as {sig} by its name")
        else:
            ambiguous[sig] = cols
            notes.append(f"{', '.join(cols)} could each be {sig}: none taken (name one with --columns {sig}=<column>)")
    # a tribometer that logs its friction coefficient and no force: the friction is μ·N (below)
    cof = None
    if not {"friction", "force"} & (set(mapping) | refused):
        cof = next((c for c, (key, _) in headers.items() if c not in mapping.values() and key in COF_NAMES), None)
        if cof is not None:
            mapping["friction"] = cof
    given = [sig for sig in ("force", "friction") if sig in (units or {})]
    uses_force = only is None or bool({"force", "friction"} & (set(only) | set(require)))
    if given and uses_force and not {"friction", "force"} & set(mapping):
        # a unit given for a force no column is read as (``--units "force=5.9 N"`` beside a
        # 'motor_current [A]' column): the unit names no column, and the file's own message
        # would repeat the advice to give it
        sig = given[0]
        currents = [c for c in in_file for _, unit in [_split_header(c)] if c not in mapping.values()
                    and (is_current_unit(unit) or current_word(c) is not None)]
        raise DataError(f"{path}: a unit is given for the {sig} ({units[sig]!r}), but no column is read as the {sig}: "
                        + (f"name the column it is for, --columns {sig}={currents[0]!r}" if len(currents) == 1 else
                           f"name the column it is for with --columns {sig}=<column> (columns: {_listing(in_file)})"))
    # a tribometer or a spindle that logs its speed and not its position: the position is the
    # speed integrated (below)
    missing = [s for s in require if s not in mapping and not (s == "position" and "velocity" in mapping)]
    if missing:
        could = "".join(f"; {', '.join(ambiguous[m])} could each be {m}" for m in missing if m in ambiguous)
        # a column whose name says a missing signal, passed over for a unit in counts (no unit of
        # any signal): say what that unit lacks before naming columns
        counted = [(c, key) for c in in_file for key, unit in [_split_header(c)]
                   if (unit or "").strip().lower() in COUNTS and any(sig in missing for sig, _ in recognise(key.lower()))]
        if counted:
            (col, name), = counted[:1]
            raise DataError(f"{path}: no column for {', '.join(missing)}: column {col!r} counts steps without saying "
                            f"their size: {_counts_fix(name)}")
        # a column whose name says a missing signal, passed over for a unit not known here (a
        # valve's 'stem_angle [degrees]' was told "no column for position", and only once named
        # with --columns that its unit was unknown): said beside the usual advice, where it is
        # the only such column and none could each be the signal (a current, a mass or a count
        # has its own message once the column is named)
        unknown = [(c, unit, sig) for c in in_file for key, unit in [_split_header(c)]
                   if unit is not None and unit_of(unit, "position") is None and unit_of(unit, "force") is None
                   and not is_current_unit(unit) and not is_mass_unit(unit)
                   for sig, _ in recognise(key.lower())[:1] if sig in missing]
        # a motor current in A or mA where a force is wanted: the fix is its constant as its unit
        # (said by ``Recording.unrecognised`` to a command that reads the file first; the same here)
        currents = [(c, unit) for c in in_file for unit in [header_unit(c) or current_word(c)] if is_current_unit(unit)]
        if currents and "force" in missing and not could:
            (col, unit), = currents[:1]
            raise DataError(f"{path}: no column for {', '.join(missing)}: column {col!r} is a current ({unit}): "
                            f"{_current_fix(col, unit)}")
        if len(unknown) == 1 and not could:
            (col, unit, sig), = unknown
            raise DataError(f"{path}: no column for {', '.join(missing)}: column {col!r} reads as {sig} by its name, "
                            f"but its unit {unit!r} is not known (known: {UNITS_ACCEPTED}); correct the header, or name "
                            f"the {sig} with --columns {sig}=<column>")
        raise DataError(
            f"{path}: no column for {', '.join(missing)} (columns: {_listing(in_file)}{could}; "
            f"name them with --columns {missing[0]}=<column>)"
        )

    read_cols = [c for sig, c in mapping.items() if only is None or sig in only or sig in require]
    if len(df) > 2 and read_cols:
        last, before = df[read_cols].iloc[-1], df[read_cols].iloc[-2]
        cut = [c for c in read_cols if _empty(last[c]) and not _empty(before[c])]
        if cut:
            # a last line short of cells where the line before has them: a log cut short while
            # it was written (the logger stopped, a copy interrupted). That line is no sample; its
            # last cell may be cut as well, so the whole line goes
            notes.append(f"the last row (line {row_of(len(df) - 1)}) has no {', '.join(map(repr, cut))}, as a file cut "
                         f"short while it was written ends: left out")
            df = _rows_kept(df, np.arange(len(df) - 1))
        elif df.attrs.get("last_cell_cut") and (last_col := df.attrs.get("columns_in_file", list(df.columns))[-1]) in read_cols:
            # the file ends inside its last cell, no line end after it and that cell shorter than
            # on every line before: a log cut short while it was written, whose last number lost
            # its last digits (``io.last_cell_cut``): that number is not the one logged
            notes.append(f"the last row (line {row_of(len(df) - 1)}) ends inside its {last_col!r} cell, shorter than "
                         f"on the lines before and with no line end, as a file cut short while it was written ends: "
                         f"left out")
            df = _rows_kept(df, np.arange(len(df) - 1))
    rec = Recording(time=np.empty(0), source=str(path))
    unitless = []  # signals whose header gives no unit: SI assumed (``_assume_si``)
    emptied = {}  # column: its rows whose cell is empty (``EMPTY_ROWS_DROPPED``)
    for sig, col in mapping.items():
        if only is not None and sig not in only and sig not in require:
            # its values are not read (a gap there is no error), its unit is still the file's
            unit = (units or {}).get(sig) or headers[col][1]
            known = unit_of(unit, sig) if unit is not None and sig != "temperature" else None
            if known is not None and known[1] in SI_OF[sig]:
                rec.units[sig] = known[1]
            notes.append(f"{col}: taken as {sig}" + (" with its sign turned, as asked" if sig in negated else "")
                         + "; this command does not use it, so its values are not read")
            continue
        raw = df[col]
        values = numbers_of(raw, df.attrs.get("decimal", "."))
        clock = clock_seconds(raw) if sig == "time" and not np.all(np.isfinite(values)) else None
        if clock is not None:
            values = clock
            notes.append(f"{col}: clock readings, taken as seconds from the first row ({raw.iloc[0]})")
        bad = np.flatnonzero(~np.isfinite(values))
        if len(bad) and sig == "temperature" and all(_empty(c) for c in raw.iloc[bad]):
            # a temperature is only reported (``diagnose.temperature_course`` reads its finite
            # samples): empty cells are a slower logger's rows between readings, not an error
            # (a stage's 1 Hz thermocouple in a 1 kHz log stopped the whole file)
            if len(bad) == len(values):
                notes.append(f"{col}: every cell empty: not read")
                continue
            notes.append(f"{col}: {len(bad)} of {len(values)} rows empty (a slower logger): only its readings are used")
        elif len(bad) and all(_empty(c) for c in raw.iloc[bad]):
            emptied[col] = bad  # dropped with the other columns' below, or refused there
        elif len(bad):
            r = int(bad[0])
            cell = raw.iloc[r]
            what = ("is empty or NaN" if _empty(cell)
                    else f"{str(cell)!r} is not a clock reading" if clock is not None
                    else f"{str(cell)!r} is not a finite number")
            raise DataError(
                f"{path}: column {col!r} row {row_of(r)}: {what}"
                + (f" ({len(bad)} such rows)" if len(bad) > 1 else "")
            )
        if sig in negated:
            values = -values
            rec.turned.add(sig)
            notes.append(f"{col}: taken as {sig} with its sign turned, as asked ({columns_option(sig, col, True)})")
        asked = (units or {}).get(sig)
        unit = asked or headers[col][1]
        # where the unit was written, where a mistake in it is mended
        where = f"--units {sig}={asked}" if asked else f"column {col!r}"
        if asked and headers[col][1] and (unit_of(asked, sig) or asked.strip()) != (
                unit_of(headers[col][1], sig) or headers[col][1].strip()):
            # as asked, and said: a header's ms read as s made a 29-hour session of a 106 s one, unsaid
            notes.append(f"{col}: read in {asked} as --units asks, not in the header's {headers[col][1]}")
        if unit is None and (closed := _unit_unclosed(col)) is not None:
            # a unit whose bracket is not closed is no unit to the header's reader: read as SI, a
            # spindle's torque written '[mN*m' came out a thousand times too large, said in a note
            raise DataError(f"{path}: column {col!r}: the bracket around its unit is not closed: write {closed!r} "
                            f"(or give the unit with --units {sig}=<unit>)")
        if col == cof:
            # a friction coefficient: dimensionless (a header may say "-" or "1"), N times it is the friction
            if unit is not None and unit.strip() not in ("-", "1", "—", ""):
                raise DataError(f"{path}: column {col!r} reads as a friction coefficient, which has no unit, but its "
                                f"header says {unit!r}: name the friction with --columns friction=<column>")
            setattr(rec, sig, values)
            rec.columns[sig] = col
            continue
        if unit is not None and sig != "temperature":
            if unit_of(unit, sig) is None:
                if unit.strip().lower() in COUNTS:
                    raise DataError(f"{path}: {where}: unit {unit!r} counts steps without saying their size: "
                                    f"{_counts_fix(headers[col][0])}")
                if is_current_unit(unit) and sig in ("force", "friction"):
                    raise DataError(f"{path}: {where}: unit {unit!r}: {_current_fix(col, unit)}")
                if is_current_unit(unit) and sig == "normal_load":
                    # (a valve's motor current named as its load was told "unknown unit 'A'")
                    raise DataError(f"{path}: {where}: unit {unit!r} is a current, not a load: a motor's current "
                                    f"drives the motion, the normal load is the force pressing the contact (N, or a "
                                    f"moment in N·m): name the load's own column with --columns normal_load=<column>")
                if is_mass_unit(unit) and sig in ("force", "friction", "normal_load"):
                    # a payload's mass is not the load on the contact: the carriage's own weight presses it too
                    what = ("the normal load is the force pressing the contact: the whole moving mass on it (carriage "
                            "and payload) times g, in N" if sig == "normal_load" else f"{sig} is a force, in N")
                    raise DataError(f"{path}: {where}: unit {unit!r} is a mass, not a force: {what}; write "
                                    f"that column in N")
                raise DataError(f"{path}: {where}: unknown unit {unit!r} (known: {UNITS_ACCEPTED})")
            factor, si = unit_of(unit, sig)
            if si not in SI_OF[sig]:
                kind = _KIND[si]
                fix = (f"correct --units {sig}=…" if asked else
                       f"correct the header's unit, or name another column with --columns {sig}=<column>")
                raise DataError(f"{path}: column {col!r} was taken as {sig}, but its unit {unit!r}"
                                + (" (from --units)" if asked else "")
                                + f" is {'an' if kind[0] in 'aeiou' else 'a'} {kind} unit; {sig} needs "
                                f"{' or '.join(SI_OF[sig])} or a multiple: {fix}")
            if factor != 1.0:
                values = values * factor
                notes.append(f"{col}: converted from {unit} to {si}")
            rec.units[sig] = si
        elif sig != "temperature":
            unitless.append(sig)
        setattr(rec, sig, values)
        rec.columns[sig] = col
    if unitless:
        rec.units_assumed = _assume_si(rec, unitless)
        notes.append(rec.units_assumed)
    for sig, col in (columns or {}).items():
        if col is not None and sig in ("position", "force", "friction", "velocity") and (
                said := _reads_as_not_measured(headers[mapping[sig]][0], sig)):
            # taken as asked; said, as a reference or a command moves as it was told to, not as
            # the machine did (a feed axis's reference position read as the position: no noise at
            # all, a transition curve to 10⁻⁴ N, and its refinement running off)
            notes.append(f"{mapping[sig]}: taken as {sig} as asked, though its name reads as {said}, not a "
                         f"measurement; friction is read from what the machine did")
    if cof is not None and rec.friction is not None:  # (a command that reads no friction leaves it)
        if rec.normal_load is None:
            raise DataError(f"{path}: column {cof!r} is a friction coefficient, and the friction μ·N needs the normal "
                            f"load: add its column (e.g. 'Fn [N]'), or name the friction with --columns friction=<column>")
        if rec.units.get("normal_load") == "N*m":
            raise DataError(f"{path}: column {cof!r} is a friction coefficient, and the friction μ·N needs the normal "
                            f"load as a force, but {rec.columns['normal_load']!r} is a moment: log the friction itself, "
                            f"or name it with --columns friction=<column>")
        rec.friction = rec.friction * rec.normal_load
        rec.units["friction"] = "N"
        notes.append(f"{cof}: a friction coefficient; the friction is it times the normal load "
                     f"{rec.columns['normal_load']} (N)")
    ignored = [c for c in in_file if c not in mapping.values()]
    rec.ignored = ignored
    rec.ambiguous = ambiguous
    if ignored:
        notes.append(f"ignored columns: {', '.join(ignored)}")
    if encoding != "utf-8-sig":
        notes.append("not UTF-8: read as Windows-1252")
    rec.notes = notes

    if emptied:
        gap = np.zeros(len(rec.time), bool)
        for idx in emptied.values():
            gap[idx] = True
        col, idx = next(iter(emptied.items()))
        if gap.sum() > EMPTY_ROWS_DROPPED * len(gap):
            raise DataError(f"{path}: column {col!r} row {row_of(int(idx[0]))}: is empty or NaN"
                            + (f" ({len(idx)} such rows)" if len(idx) > 1 else "")
                            + f": {int(gap.sum())} of {len(gap)} rows have an empty cell in a signal read, over the "
                            f"{EMPTY_ROWS_DROPPED:.0%} left out as a logger's dropouts: is that the column of this "
                            f"signal? (--columns names another)")
        keep = ~gap
        said = "; ".join(f"{c!r} in {len(i)}, the first at row {row_of(int(i[0]))}" for c, i in emptied.items())
        for sig in SIGNALS:
            if getattr(rec, sig) is not None:
                setattr(rec, sig, getattr(rec, sig)[keep])
        rows, df = rows[keep], _rows_kept(df, np.flatnonzero(keep))
        notes.append(f"{int(gap.sum())} row(s) with an empty cell left out ({said}): a logger's dropouts, under "
                     f"{EMPTY_ROWS_DROPPED:.0%} of the rows; the time they leave is a gap in the record")

    # a row that repeats the one before it in every value read (a logger that wrote a sample
    # twice) is no second sample: dropped, and counted; a repeated time with other values is
    # refused below
    read = [sig for sig in SIGNALS if getattr(rec, sig) is not None]
    again = np.ones(max(len(rec.time) - 1, 0), bool)
    for sig in read:
        a = getattr(rec, sig)
        again &= a[1:] == a[:-1]
    if again.any():
        keep = np.concatenate([[True], ~again])
        first = row_of(int(np.flatnonzero(again)[0]) + 1)
        for sig in read:
            setattr(rec, sig, getattr(rec, sig)[keep])
        rows, df = rows[keep], _rows_kept(df, np.flatnonzero(keep))
        notes.append(f"{int(again.sum())} row(s) repeating the row before in every value (first at row {first}): "
                     f"dropped")
    n = len(rec.time)
    if n < MIN_SAMPLES:
        raise DataError(f"{path}: only {n} sample(s); need at least {MIN_SAMPLES}")
    dt = np.diff(rec.time)
    bad = np.flatnonzero(dt <= 0)
    if len(bad):
        r = int(bad[0]) + 1
        raw = df[rec.columns["time"]]  # the file's own numbers, in the file's unit
        # a clock that goes back is most often a second log appended (a logger restarted), not
        # rows out of order
        why = ("the same time as the row before, with other values (a row repeated in every value is "
               "dropped): remove one of the two, or write the time with more digits" if dt[r - 1] == 0 else
               "the clock goes back: two logs in one file? split it there (fit takes several files), or sort "
               "the rows if they are out of order")
        raise DataError(f"{path}: column {rec.columns['time']!r} row {row_of(r)}: time {raw.iloc[r]} does not "
                        f"increase (previous {raw.iloc[r - 1]}): {why}")
    if rec.position is None and rec.velocity is not None and "position" not in refused:
        rec.position = integrated_speed(rec.time, rec.velocity)
        rec.units["position"] = {"m/s": "m", "rad/s": "rad"}.get(rec.units.get("velocity"), "m")
        rec.columns["position"] = rec.columns["velocity"]
        notes.append(f"no position column: the position is {rec.columns['velocity']} integrated over time (its noise "
                     f"and any offset integrate into a drift of the position, so presliding is not resolved; name a "
                     f"position column with --columns position=<column> if the file has one)")
    if rec.position is not None and rec.units.get("position") == "rad":
        wraps = turn_wraps(rec.position)
        if len(wraps):
            rec.position = np.unwrap(rec.position, period=2.0 * np.pi)
            notes.append(f"{rec.columns['position']}: the angle wraps at one turn ({len(wraps)} time(s), first at row "
                         f"{row_of(int(wraps[0]) + 1)}): unwrapped to a continuous angle")
    return rec


def _rows_kept(df, index: np.ndarray):
    """The table's rows at ``index``, renumbered as the recording's samples are (a message
    quoting the file's own cell of a sample reads it there), its attributes (the file's
    dialect, its columns) kept."""
    attrs = dict(df.attrs)
    out = df.iloc[index].reset_index(drop=True)
    out.attrs.update(attrs)
    return out


def integrated_speed(t: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The position a logged speed gives, by the trapezoidal rule from 0 at the first sample."""
    return np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])


def turn_wraps(angle: np.ndarray) -> np.ndarray:
    """Indices i where an angle (rad) logged modulo one turn wraps between samples i and i + 1:
    a step over half a turn that is a whole number of turns to within a tenth of one, on an
    axis whose median step is under a hundredth of a turn (a log that samples the motion turns
    far less than half a turn between two samples, and a position with noise that large is no
    angle logged modulo a turn).
    Empty where there is no such wrap, or where a step over half a turn is not one."""
    d = np.diff(angle)
    big = np.flatnonzero(np.abs(d) > np.pi)
    if not len(big) or np.median(np.abs(d)) > 2e-2 * np.pi:
        return np.zeros(0, dtype=int)
    off = d[big] - 2.0 * np.pi * np.round(d[big] / (2.0 * np.pi))
    return big if np.all(np.abs(off) < 0.2 * np.pi) else np.zeros(0, dtype=int)


def units_of_recordings(recordings) -> dict:
    """The units a parameter set fitted to ``recordings`` is in: theirs as read (SI of their kind,
    whatever their headers said; the force's, else the friction's), one kind of machine at a time."""
    units = None
    for r in recordings:
        u = {"position": r.units.get("position", "rad"), "force": r.units.get("force", r.units.get("friction", "N*m")),
             "time": "s"}
        if units is None:
            units = u
        elif u["position"] != units["position"]:
            raise IdentificationError(f"{r.source}: position in {u['position']} but another file has {units['position']}: "
                                      f"fit one kind of machine at a time")
    return units or {"position": "rad", "force": "N*m", "time": "s"}


def other_kind_of_machine(param_units, rec_units) -> bool:
    """Whether a parameter set's units and a recording's are of different kinds of machine (one
    in rad, the other in m): its numbers would be applied to the recording as they are."""
    pu, ru = param_units.get("position"), rec_units.get("position")
    return bool(pu and ru and pu != ru)


OTHER_MACHINE_SCALE = 30.0  # static friction this many times over or under a recording's forces: another machine's


def other_size_of_machine(params, rec: Recording) -> str | None:
    """Why a parameter set in the recording's units is still another machine's, or None: its
    static friction over OTHER_MACHINE_SCALE times the recording's forces (their 95th
    percentile), or under a 1/OTHER_MACHINE_SCALE of them (a telescope mount's 3 N·m set kept
    its 33 kg·m² on a pitch bearing of 40 kN·m, both in rad and N·m)."""
    signal = rec.friction if rec.friction is not None else rec.force
    st = params.stribeck
    level = max(abs(st.positive.Fs), abs(st.negative.Fs), abs(st.positive.Fc), abs(st.negative.Fc))
    if signal is None or not level > 0:
        return None
    scale = float(np.nanquantile(np.abs(np.asarray(signal, dtype=np.float64)), 0.95))
    if scale > 0 and not 1.0 / OTHER_MACHINE_SCALE <= level / scale <= OTHER_MACHINE_SCALE:
        return (f"its static friction {level:.3g} is {level / scale:.3g} × the recording's forces ({scale:.3g}, "
                f"95th percentile): another machine's")
    return None


def velocity_of(rec: Recording) -> np.ndarray:
    """The recorded velocity, or the backward difference of the position (first sample 0)."""
    if rec.velocity is not None:
        return rec.velocity
    if rec.position is None:
        raise DataError(f"{rec.source}: neither a velocity nor a position column")
    v = np.zeros(len(rec.time))
    v[1:] = np.diff(rec.position) / np.diff(rec.time)
    return v
