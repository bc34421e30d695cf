"""Parameter records of the friction models and their schema.

Every scalar parameter is a dataclass field whose metadata (``_param``) says what it is: the
kind of unit, the bounds, the sign rule, a one-line description in the paper's words and the
slider scale. That metadata is the single source for validation, for the YAML shape
(``to_dict``/``from_dict``), for the explorer's controls and hints and for parameter tables
(``schema``, ``parameter_rows``). Adding a parameter is one edit: a field with its metadata.

The records are immutable: frozen dataclasses, tuples instead of lists, and read-only
mappings (``FrozenDict``) for the free-form parts (uncertainty, provenance, effects).

Pure data: reading and writing files lives in ``identify.paramfile``; ``model`` does no I/O.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import MISSING, dataclass, field, fields, replace

import numpy as np

from .errors import ParameterError
from .layout import CURVE_NAMES, MODEL_NAMES, CurveKind

MODEL_KINDS = MODEL_NAMES  # ("leuven", "lugre", "static"): model.layout.ModelKind
TRANSITION_KINDS = CURVE_NAMES  # ("piecewise_linear", "tanh_linear"): model.layout.CurveKind

# A transition curve is a handful of turning points (Table II has five, the fit uses five);
# more than this is a mistake, and refusing it keeps a file from stalling a simulation or the
# explorer (which draws one control per knot).
MAX_KNOTS = 64


# -- read-only records --------------------------------------------------------------------------
class FrozenDict(dict):
    """A dict that cannot change after construction (hashable when its values are)."""

    def _immutable(self, *_, **__):
        raise TypeError("parameter records are immutable; use FrictionParams.replace(...)")

    __setitem__ = __delitem__ = clear = pop = popitem = setdefault = update = __ior__ = _immutable  # type: ignore[assignment]

    def __hash__(self):  # type: ignore[override]
        return hash(tuple(sorted((str(k), v) for k, v in self.items())))

    def __reduce__(self):
        return (FrozenDict, (dict(self),))

    def __copy__(self):
        return self

    def __deepcopy__(self, memo):
        return self

    def __repr__(self) -> str:
        return f"FrozenDict({dict.__repr__(self)})"


def freeze(obj):
    """Deep read-only copy: mappings -> FrozenDict, lists -> tuples."""
    if isinstance(obj, FrozenDict):
        return obj
    if isinstance(obj, Mapping):
        return FrozenDict({k: freeze(v) for k, v in obj.items()})
    if isinstance(obj, (list, tuple)):
        return tuple(freeze(v) for v in obj)
    return obj


def thaw(obj):
    """Plain dicts and lists again (for YAML and JSON)."""
    if isinstance(obj, Mapping):
        return {k: thaw(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [thaw(v) for v in obj]
    if isinstance(obj, np.generic):
        return obj.item()
    return obj


class _RecordMapping(Mapping):
    """Read access by name (``rec["z0"]``, ``dict(rec)``) for small frozen records."""

    def __getitem__(self, key):
        if key not in self._names():
            raise KeyError(key)
        return getattr(self, key)

    def __iter__(self):
        return iter(self._names())

    def __len__(self) -> int:
        return len(self._names())

    @classmethod
    def _names(cls) -> tuple:
        return tuple(f.name for f in fields(cls))


# -- units ----------------------------------------------------------------------------------------
# How each unit kind is written from the units of a parameter set (position, force, time).
UNIT_KINDS = {
    "force": "{force}",
    "position": "{position}",
    "velocity": "{position}/{time}",
    "stiffness": "{force}/{position}",
    "damping": "{force}·{time}/{position}",  # force per velocity
    "inertia": "{force}·{time}²/{position}",  # force per acceleration: kg·m² for rad/N·m, kg for m/N
    "dimensionless": "",
}


# the SI units a parameter set may be in, and the spellings taken for each (a torque as N·m, N*m, Nm)
SI_UNITS = {"position": ("m", "rad"), "force": ("N", "N*m"), "time": ("s",)}
_SI_SPELLINGS = {"position": {"m": "m", "rad": "rad"},
                 "force": {"n": "N", "n*m": "N*m", "n·m": "N*m", "n.m": "N*m", "nm": "N*m", "n⋅m": "N*m", "n-m": "N*m",
                           "n×m": "N*m"},
                 "time": {"s": "s"}}


@dataclass(frozen=True)
class Units(_RecordMapping):
    """The units every number of a parameter set is in: those of the data it came from
    (the loader converts recordings to SI, so rotary data give rad/N·m, linear data m/N)."""

    position: str = "rad"
    force: str = "N*m"
    time: str = "s"

    def __post_init__(self):
        for f in fields(self):
            v = getattr(self, f.name)
            if not isinstance(v, str) or not v.strip() or "\n" in v:
                raise ParameterError(f"units.{f.name}: expected a unit name such as "
                                     f"{f.default!r}, got {v!r}")
            # recordings are converted to SI when read, so a parameter set in any other unit
            # would be applied to them unconverted: refused, not rescaled
            si = _SI_SPELLINGS[f.name].get(v.strip().replace(" ", "").lower())
            if si is None:
                raise ParameterError(f"units.{f.name}: {v!r} is not an SI unit; parameter sets are in SI "
                                     f"({' or '.join(SI_UNITS[f.name])}), as recordings are once read: "
                                     f"convert the numbers and write the SI unit")
            object.__setattr__(self, f.name, si)

    @classmethod
    def coerce(cls, value) -> "Units":
        if isinstance(value, Units):
            return value
        if value is None:
            return cls()
        if not isinstance(value, Mapping):
            raise ParameterError("units: expected a mapping like {position: rad, force: N*m, time: s}")
        unknown = sorted(str(k) for k in value if k not in cls._names())
        if unknown:
            raise ParameterError(f"units.{unknown[0]}: unknown (known: {', '.join(cls._names())})")
        missing = [n for n in cls._names() if n not in value]
        if value and missing:  # half a unit record would pair the file's position unit with our force unit
            raise ParameterError(f"units.{missing[0]}: missing (give position, force and time)")
        return cls(**{str(k): v for k, v in value.items()})

    @classmethod
    def of_signals(cls, signal_units: Mapping) -> "Units":
        """From a recording's signal -> unit record (``identify.data.Recording.units``)."""
        u = signal_units or {}
        pos = u.get("position") or str(u.get("velocity", "")).split("/")[0] or cls.position
        force = u.get("force") or u.get("friction") or cls.force
        return cls(position=pos, force=force, time=u.get("time") or cls.time)

    def render(self, kind: str) -> str:
        """The unit of a parameter of this kind, e.g. ``render('damping')`` -> 'N·m·s/rad'."""
        return UNIT_KINDS[kind].format(position=self.position, force=self.force, time=self.time).replace("*", "·")


PAPER_UNITS = Units()


# -- field metadata -------------------------------------------------------------------------------
def _param(default=MISSING, *, kind: str, description: str, symbol: str, lower: float = -math.inf,
           upper: float = math.inf, lower_open: bool = False, signed: bool = False, scale: str = "lin",
           typical: tuple | None = None, models: tuple = MODEL_KINDS, control: bool = True, group: str = ""):
    """A scalar parameter: ``kind`` of unit (UNIT_KINDS), bounds on the value (on its magnitude
    when ``signed``: the value then carries the sign of its velocity side, Table I convention),
    a one-line ``description``, the slider ``scale`` (lin/log), a ``typical`` range for
    dimensionless parameters, the model kinds that use it, and whether the explorer shows it."""
    assert kind in UNIT_KINDS and scale in ("lin", "log")
    meta = dict(kind=kind, description=description, symbol=symbol, lower=lower, upper=upper,
                lower_open=lower_open, signed=signed, scale=scale, typical=typical, models=models,
                control=control, group=group)
    return field(default=default, metadata=meta)


def _number(path: str, value) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating, str)):
        raise ParameterError(f"{path}: expected a number, got {value!r}"[:200])
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{path}: expected a number, got {value!r}"[:200]) from None
    except OverflowError:  # an integer beyond the float range (YAML reads `n: 1000…0` as int)
        raise ParameterError(f"{path}: number too large{_digits(value)}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{path}: must be finite, got {value!r}")
    return x


def _digits(value) -> str:
    """ (N digits) of a huge integer, for the message."""
    if not isinstance(value, int):
        return ""
    try:
        return f" ({len(str(abs(value)))} digits)"
    except ValueError:  # beyond the interpreter's limit for int -> str
        return f" (about {int(abs(value).bit_length() * math.log10(2)) + 1} digits)"


_finite = _number  # older name, kept for callers


@dataclass(frozen=True)
class ParamSpec:
    """One scalar parameter of a parameter set, as the schema describes it."""

    path: str  # dotted path, e.g. 'stribeck.positive.Fs', 'transition_curve.F.3'
    name: str  # field name, e.g. 'Fs'
    label: str  # short symbol for a control or a table, e.g. 'Fs⁺'
    kind: str  # unit kind (UNIT_KINDS)
    unit: str  # rendered for the units of the parameter set, e.g. 'N·m·s/rad'
    description: str
    lower: float  # bounds of the value itself (for a negative-side parameter: -inf .. 0)
    upper: float
    lower_open: bool
    upper_open: bool
    sign: int  # +1/-1: the value carries this sign (Table I); 0: no sign rule
    scale: str  # 'lin' or 'log' (for sliders)
    typical: tuple | None
    group: str  # 'stribeck', 'transition_curve' or 'model'
    control: bool  # shown as a control in the explorer

    @property
    def bounds(self) -> tuple[float, float]:
        return (self.lower, self.upper)

    @property
    def hint(self) -> str:
        unit = f" [{self.unit}]" if self.unit else ""
        return f"{self.label}{unit}: {self.description}"

    def check(self, value) -> float:
        """The value as a float, or a ParameterError naming the path and the rule."""
        x = _number(self.path, value)
        if self.sign:
            word = "positive" if self.sign > 0 else "negative"
            if x * self.sign <= 0:
                raise ParameterError(f"{self.path}: must be {word} on the {word}-velocity side "
                                     f"(Table I convention), got {x:g}")
            return x
        if self.lower_open and not x > self.lower:
            raise ParameterError(f"{self.path}: must be > {self.lower:g}, got {x:g}")
        if x < self.lower:
            raise ParameterError(f"{self.path}: must be >= {self.lower:g}, got {x:g}")
        if self.upper_open and not x < self.upper:
            raise ParameterError(f"{self.path}: must be < {self.upper:g}, got {x:g}")
        if x > self.upper:
            raise ParameterError(f"{self.path}: must be <= {self.upper:g}, got {x:g}")
        return x

    def slider_range(self, value: float) -> tuple[float, float]:
        """A control's range around the current value: the typical range for dimensionless
        parameters, else a factor 100 either way (log) or 0 .. 3× the value (lin). Dimensioned
        ranges scale with the value, so the same rule serves rad/N·m and m/N sets alike."""
        if self.typical is not None:
            lo, hi = self.typical
            return (min(lo, value), max(hi, value))
        mag = abs(value) or 1.0
        if self.scale == "log":
            lo, hi = mag / 100.0, mag * 100.0
        else:
            lo, hi = (max(self.lower, 0.0) if self.sign == 0 else 0.0), 3.0 * mag
        return (-hi, -lo) if self.sign < 0 else (lo, hi)


def _spec(f, path: str, units: Units, sign: int = 0, suffix: str = "", index: int | None = None) -> ParamSpec:
    m = f.metadata
    sym = m["symbol"] if index is None else m["symbol"].format(i=index)
    sign = sign if m["signed"] else 0
    lower, upper, lower_open, upper_open = m["lower"], m["upper"], m["lower_open"], False
    if sign < 0:  # the metadata bounds the magnitude; the negative side mirrors them
        lower, upper, lower_open, upper_open = -upper, -lower, False, lower_open
    return ParamSpec(path=path, name=f.name, label=sym + suffix, kind=m["kind"], unit=units.render(m["kind"]),
                     description=m["description"], lower=lower, upper=upper, lower_open=lower_open,
                     upper_open=upper_open, sign=sign, scale=m["scale"], typical=m["typical"], group=m["group"],
                     control=m["control"])


def _scalar_fields(cls):
    return [f for f in fields(cls) if "kind" in f.metadata]


# -- records --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StribeckSide:
    """Eq. (7) for one velocity sign: S(v) = Fc + (Fs - Fc)·exp(-|v/vs|^delta), plus sigma2·v.

    On the negative side Fs, Fc and vs are negative numbers (Table I convention).
    """

    Fs: float = _param(kind="force", symbol="Fs", signed=True, lower=0.0, lower_open=True, scale="log",
                       group="stribeck", description="static friction: S(v) at zero velocity, eq. (7)")
    Fc: float = _param(kind="force", symbol="Fc", signed=True, lower=0.0, lower_open=True, scale="log",
                       group="stribeck", description="Coulomb friction: the level S(v) settles to past the "
                                                     "Stribeck velocity, eq. (7)")
    vs: float = _param(kind="velocity", symbol="vs", signed=True, lower=0.0, lower_open=True, scale="log",
                       group="stribeck", description="Stribeck velocity: how fast S(v) falls from Fs to Fc, eq. (7)")
    delta: float = _param(kind="dimensionless", symbol="δ", lower=0.0, lower_open=True, typical=(0.1, 3.0),
                          group="stribeck", description="an arbitrary exponent shaping the Stribeck effect, eq. (7)")
    sigma2: float = _param(kind="damping", symbol="σ2", lower=0.0, scale="lin", group="stribeck",
                           description="viscous damping coefficient: the σ2·v term of eqs. (3) and (6)")

    def validate(self, path: str, sign: int) -> None:
        for f in _scalar_fields(StribeckSide):
            _spec(f, f"{path}.{f.name}", PAPER_UNITS, sign).check(getattr(self, f.name))

    def as_array(self) -> np.ndarray:
        return np.array([getattr(self, f.name) for f in _scalar_fields(StribeckSide)], dtype=np.float64)


STRIBECK_SIDES = (("positive", +1, "⁺"), ("negative", -1, "⁻"))


@dataclass(frozen=True)
class Stribeck:
    positive: StribeckSide
    negative: StribeckSide

    def validate(self, path: str = "stribeck") -> None:
        for side, sign, _ in STRIBECK_SIDES:
            getattr(self, side).validate(f"{path}.{side}", sign)

    def as_array(self) -> np.ndarray:
        """[Fs+, Fc+, vs+, delta+, sigma2+, Fs-, Fc-, vs-, delta-, sigma2-] for the kernels."""
        return np.concatenate([self.positive.as_array(), self.negative.as_array()])


@dataclass(frozen=True)
class TanhShape(_RecordMapping):
    """F_d(z) = A·tanh(z/z0) + k·z: a smooth three-parameter transition curve (the paper's
    remark 2 cites such single continuous functions); initial stiffness A/z0 + k."""

    A: float = _param(kind="force", symbol="A", lower=0.0, lower_open=True, scale="log", group="transition_curve",
                      description="saturating part of the transition curve F_d")
    z0: float = _param(kind="position", symbol="z0", lower=0.0, lower_open=True, scale="log",
                       group="transition_curve", description="displacement over which the saturating part builds up")
    k: float = _param(kind="stiffness", symbol="k", lower=0.0, lower_open=True, scale="log",
                      group="transition_curve", description="far-field stiffness of the transition curve F_d")

    def validate(self, path: str) -> None:
        for f in _scalar_fields(TanhShape):
            _spec(f, f"{path}.{f.name}", PAPER_UNITS).check(getattr(self, f.name))


REACH_WITHIN = 20.0  # a curve's extension must reach the outer loop's span by this many times its last knot


def reaching_knots(z, F, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """The knots of a piecewise-linear F_d as the kernels evaluate it: the knots given, and,
    where the last segment's slope carried on would reach ``reach`` (the outer loop's span
    F_s⁺ − F_s⁻) only beyond ``REACH_WITHIN`` (20) times the last knot, one more knot at
    (20·z_last, reach).

    Why: eq. (5) settles in sliding where F_d(z) = S(v) − F_b, which after a reset is up to
    that span. A curve topping below it with a nearly flat last segment (a fit whose branches
    end where the contact starts to slide: a guideway made apart, F_d flat at 47.5 N for a span
    of 58.3 N) puts that point metres away; z then runs on, and σ1·dz/dt reaches hundreds of
    newtons in every fast stroke. Continued this way, every force difference the memory can
    ask for is reached within presliding's own scale; a curve that gets there already (Table
    II's 100 N·m for Table I's 36 + 63), or whose last slope gets there within 20 of its last
    knot, is evaluated as given: a fitted curve's knots end where its branches end, and a stage
    whose curve stopped at 1.5 µm, with a last slope reaching the span at 10 times that (the
    generator's own curve reaches it at 7), was bent into sliding when twice was the bound."""
    z, F = np.asarray(z, dtype=np.float64), np.asarray(F, dtype=np.float64)
    if len(z) < 2 or not reach > F[-1] or not z[-1] > z[-2]:
        return z, F
    slope = (F[-1] - F[-2]) / (z[-1] - z[-2])
    if F[-1] + slope * (REACH_WITHIN - 1.0) * z[-1] >= reach:
        return z, F
    return np.append(z, REACH_WITHIN * z[-1]), np.append(F, reach)


@dataclass(frozen=True)
class TransitionCurve:
    """The positive half of the point-symmetric, strictly increasing transition curve F_d(z).

    ``piecewise_linear``: knots ``z`` (rad or m) and ``F`` (N·m or N) starting at (0, 0), as
    Table II; beyond the last knot the last segment is extended (F_d must be invertible over
    every force difference the hysteresis memory can ask for). At most ``MAX_KNOTS`` knots.
    ``tanh_linear``: ``shape`` (``TanhShape``: A, z0, k).
    """

    kind: str = "piecewise_linear"
    z: tuple[float, ...] = _param((), kind="position", symbol="z{i}", lower=0.0, lower_open=True, scale="log",
                                  group="transition_curve", description="abscissa of a turning point of the "
                                                                        "piecewise linear transition curve F_d (Table II)")
    F: tuple[float, ...] = _param((), kind="force", symbol="F_d(z{i})", lower=0.0, lower_open=True, scale="lin",
                                  group="transition_curve", description="ordinate of a turning point of the "
                                                                        "transition curve F_d, estimated by maximum likelihood")
    shape: TanhShape | None = None

    def __post_init__(self):
        object.__setattr__(self, "z", tuple(self.z))
        object.__setattr__(self, "F", tuple(self.F))
        if self.shape is not None and not isinstance(self.shape, TanhShape):
            if not isinstance(self.shape, Mapping):
                raise ParameterError("transition_curve.shape: expected a mapping of A, z0, k")
            if not self.shape and self.kind != "tanh_linear":
                object.__setattr__(self, "shape", None)
                return
            missing = [n for n in TanhShape._names() if n not in self.shape]
            if missing:
                raise ParameterError(f"transition_curve.shape.{missing[0]}: missing (tanh_linear needs A, z0, k)")
            extra = sorted(str(k) for k in self.shape if k not in TanhShape._names())
            if extra:
                raise ParameterError(f"transition_curve.shape.{extra[0]}: unknown field (known: A, z0, k)")
            object.__setattr__(self, "shape", TanhShape(**{n: _number(f"transition_curve.shape.{n}", self.shape[n])
                                                           for n in TanhShape._names()}))

    def validate(self, path: str = "transition_curve") -> None:
        if self.kind not in TRANSITION_KINDS:
            raise ParameterError(f"{path}.kind: must be one of {', '.join(TRANSITION_KINDS)}, got {self.kind!r}")
        if self.kind == "piecewise_linear":
            if len(self.z) != len(self.F):
                raise ParameterError(f"{path}: z has {len(self.z)} knots but F has {len(self.F)}")
            if len(self.z) < 2:
                raise ParameterError(f"{path}: needs at least 2 knots (0,0) and one more, got {len(self.z)}")
            if len(self.z) > MAX_KNOTS:
                raise ParameterError(f"{path}: {len(self.z)} knots, at most {MAX_KNOTS} are accepted")
            z = [_number(f"{path}.z.{i}", v) for i, v in enumerate(self.z)]
            F = [_number(f"{path}.F.{i}", v) for i, v in enumerate(self.F)]
            if z[0] != 0.0 or F[0] != 0.0:
                raise ParameterError(f"{path}: the first knot must be (0, 0) (point symmetry), got ({z[0]}, {F[0]})")
            for i in range(1, len(z)):
                if z[i] <= z[i - 1]:
                    raise ParameterError(f"{path}.z.{i}: knots must be strictly increasing, got {z[i - 1]} then {z[i]}")
                if F[i] <= F[i - 1]:
                    raise ParameterError(
                        f"{path}.F.{i}: F_d must be strictly increasing, got {F[i - 1]} then {F[i]}"
                    )
        else:
            if self.shape is None:
                raise ParameterError(f"{path}.shape: missing (tanh_linear needs A, z0, k)")
            self.shape.validate(f"{path}.shape")

    def initial_stiffness(self) -> float:
        """dF_d/dz at z = 0: the stiffness of the stuck contact (the first segment's slope of a
        piecewise-linear curve; A/z0 + k of the tanh curve)."""
        if self.kind == "piecewise_linear":
            return float(self.F[1] / self.z[1])
        return float(self.shape.A / self.shape.z0 + self.shape.k)

    def kernel_arrays(self, reach: float = 0.0) -> tuple[int, np.ndarray, np.ndarray]:
        """(kind code, abscissas, ordinates-or-shape) for ``model.kernels``; ``reach``: the
        largest force difference the memory asks of F_d (``FrictionParams.outer_loop_span``),
        which a piecewise-linear curve is made to reach by 20 times its last knot
        (``reaching_knots``)."""
        if self.kind == "piecewise_linear":
            z, F = reaching_knots(self.z, self.F, reach)
            return int(CurveKind.PIECEWISE_LINEAR), z, F
        s = self.shape
        return int(CurveKind.TANH_LINEAR), np.zeros(1), np.array([s.A, s.z0, s.k], dtype=np.float64)

    def to_dict(self) -> dict:
        if self.kind == "piecewise_linear":
            return {"kind": self.kind, "z": [float(v) for v in self.z], "F": [float(v) for v in self.F]}
        return {"kind": self.kind, "shape": {k: float(v) for k, v in self.shape.items()}}


@dataclass(frozen=True)
class FrictionParams:
    """A complete friction model: the kind, S(v) per sign, the transition curve and the rest.

    ``n`` and ``transition_curve`` belong to the Leuven model, ``sigma0`` to LuGre; ``sigma1``
    is the micro-viscous coefficient of both. ``inertia`` is the I of eq. (8): the paper gives
    none, so the default (5 kg·m²) is our choice. ``reversal_tol`` is the smallest hysteresis
    force excursion (force units) that counts as a velocity reversal; a sign change of v within
    it wipes the previous reversal out again (see ``model.kernels.velocity_reversal``).
    ``units`` are those of the data the numbers came from (the YAML writes them).
    """

    model: str = "leuven"
    stribeck: Stribeck = None  # type: ignore[assignment]
    transition_curve: TransitionCurve = None  # type: ignore[assignment]
    # n ≥ 1: below it eq. (5) has an infinite slope in F_d at every reversal, which the implicit
    # step of the kernels cannot take (|r|^(n−1) at r = 0 is infinite: the simulation is NaN)
    n: float = _param(7.0, kind="dimensionless", symbol="n", lower=1.0, typical=(1.0, 20.0),
                      models=("leuven",), group="model",
                      description="exponent of the state equation (5), similar to the exponent of the general "
                                  "Dahl model; the paper chose 7 (at least 1)")
    sigma1: float = _param(1500.0, kind="damping", symbol="σ1", lower=0.0, scale="lin", models=("leuven", "lugre"),
                           group="model", description="micro-viscous damping coefficient: the σ1·dz/dt term of eq. (3)")
    sigma0: float | None = _param(None, kind="stiffness", symbol="σ0", lower=0.0, lower_open=True, scale="log",
                                  models=("lugre",), group="model",
                                  description="LuGre: equivalent stiffness for the position-force relationship at "
                                              "velocity reversal, eq. (2)")
    inertia: float = _param(5.0, kind="inertia", symbol="I", lower=0.0, lower_open=True, scale="log", group="model",
                            description="mass or mass moment of inertia of the moving part, eq. (8); the paper gives none")
    reversal_tol: float = _param(1e-7, kind="force", symbol="reversal tol.", lower=0.0, scale="log", group="model",
                                 control=False, description="smallest hysteresis force excursion that counts as a "
                                                            "velocity reversal (our choice; the paper has none)")
    units: Units = field(default_factory=Units)
    effects: tuple = ()
    uncertainty: FrozenDict = field(default_factory=FrozenDict)
    provenance: FrozenDict = field(default_factory=FrozenDict)

    def __post_init__(self):
        # immutable all the way down: callers may hand in dicts and lists
        object.__setattr__(self, "units", Units.coerce(self.units))
        object.__setattr__(self, "effects", freeze(tuple(self.effects or ())))
        object.__setattr__(self, "uncertainty", freeze(self.uncertainty or {}))
        object.__setattr__(self, "provenance", freeze(self.provenance or {}))

    @property
    def defaulted(self) -> tuple:
        """The dimensioned scalars (σ1, the inertia) this set holds at their built-in defaults
        because its file, in the paper's units, left them out (``from_dict``): the paper's robot
        joint's σ1 and a made-up 5 kg·m², not this machine's. Kept in ``provenance.defaulted``,
        so that a set written back out still says so while the value is the default. A value
        changed since (``replace``, the explorer's controls) is the user's, not a default: the
        mark holds only while the value is still the field's default, as ``from_dict`` reads it."""
        defaults = {f.name: f.default for f in _scalar_fields(type(self))}
        return tuple(k for k in (self.provenance or {}).get(DEFAULTED) or ()
                     if k in defaults and getattr(self, k) == defaults[k])

    @property
    def outer_loop_span(self) -> float:
        """The largest S(v) − F_b the memory asks of F_d: from one side's largest |S(v)| (F_s,
        or F_c where friction rises with speed) to the other's."""
        pos, neg = self.stribeck.positive, self.stribeck.negative
        return max(abs(pos.Fs), abs(pos.Fc)) + max(abs(neg.Fs), abs(neg.Fc))

    def curve_arrays(self) -> tuple[int, np.ndarray, np.ndarray]:
        """The transition curve's arrays for ``model.kernels``, reaching ``outer_loop_span``."""
        return self.transition_curve.kernel_arrays(self.outer_loop_span)

    def validate(self) -> "FrictionParams":
        if self.model not in MODEL_KINDS:
            raise ParameterError(f"model: must be one of {', '.join(MODEL_KINDS)}, got {self.model!r}")
        if self.stribeck is None:
            raise ParameterError("stribeck: missing")
        self.stribeck.validate()
        if self.transition_curve is None:
            raise ParameterError("transition_curve: missing")
        self.transition_curve.validate()
        for f in _scalar_fields(FrictionParams):
            value = getattr(self, f.name)
            if value is None and f.name == "sigma0":
                if self.model == "lugre":
                    raise ParameterError("sigma0: LuGre needs the bristle stiffness sigma0")
                continue
            _spec(f, f.name, self.units).check(value)
        _validate_effects(self.effects)
        return self

    def replace(self, **changes) -> "FrictionParams":
        """A copy with ``changes``; a new transition curve drops the σ of knots it no longer has
        (an explorer's removed knot, a tanh curve made piecewise)."""
        if "transition_curve" in changes and "uncertainty" not in changes:
            tc = changes["transition_curve"]
            kept = {sp.path for sp in knot_specs(tc)} if tc is not None else set()
            changes["uncertainty"] = {k: v for k, v in self.uncertainty.items()
                                      if not k.startswith("transition_curve.") or k in kept}
        return replace(self, **changes)

    # -- plain dicts (the YAML shape) -------------------------------------------------------
    def to_dict(self) -> dict:
        side = lambda s: {f.name: float(getattr(s, f.name)) for f in _scalar_fields(StribeckSide)}  # noqa: E731
        out = {
            "model": self.model,
            "units": dict(self.units),
            "stribeck": {name: side(getattr(self.stribeck, name)) for name, _, _ in STRIBECK_SIDES},
            "transition_curve": self.transition_curve.to_dict(),
        }
        for f in _scalar_fields(FrictionParams):
            value = getattr(self, f.name)
            if value is not None:
                out[f.name] = float(value)
        out["effects"] = thaw(self.effects)
        if self.uncertainty:
            out["uncertainty"] = {k: float(v) for k, v in self.uncertainty.items()}
        if self.provenance:
            out["provenance"] = thaw(self.provenance)
        return out

    @classmethod
    def from_dict(cls, d) -> "FrictionParams":
        """Build and validate; every problem is a ParameterError naming the dotted field.

        ``stribeck`` and ``transition_curve`` are required. The scalar fields may be left out
        where their default means the same in every unit system (n, reversal_tol) or the file is
        in the paper's units (rad, N*m, s); otherwise a missing one is an error, so that no
        value in the wrong units slips in.
        """
        if d is None:
            raise ParameterError("parameter file is empty (expected stribeck:, transition_curve: and the rest)")
        if not isinstance(d, Mapping):
            raise ParameterError(f"parameter file: expected a mapping at the top level, got {type(d).__name__}")
        known = [f.name for f in fields(cls)]
        unknown = sorted(str(k) for k in d if k not in known)
        if unknown:
            raise ParameterError(f"{unknown[0]}: unknown field (known: {', '.join(known)})"[:300])
        units = Units.coerce(d.get("units"))
        model = d.get("model", "leuven")
        if model not in MODEL_KINDS:
            raise ParameterError(f"model: must be one of {', '.join(MODEL_KINDS)}, got {model!r}"[:200])
        stribeck = _stribeck_from(d.get("stribeck"))
        tc = _transition_curve_from(d.get("transition_curve"))
        scalars = {}
        for f in _scalar_fields(cls):
            if f.name in d and d[f.name] is not None:
                scalars[f.name] = _number(f.name, d[f.name])
            elif f.name == "sigma0":
                scalars[f.name] = None
            elif units != PAPER_UNITS and f.metadata["kind"] not in ("dimensionless", "force") and f.name != "sigma0":
                raise ParameterError(f"{f.name}: missing; its default ({f.default:g} "
                                     f"{PAPER_UNITS.render(f.metadata['kind'])}) is in the paper's units, and this "
                                     f"file's are {units.position}, {units.force}, {units.time}")
        effects = d.get("effects") or []
        if not isinstance(effects, (list, tuple)):
            raise ParameterError("effects: expected a list")
        effects = _validate_effects(effects)
        unc = d.get("uncertainty") or {}
        if not isinstance(unc, Mapping):
            raise ParameterError("uncertainty: expected a mapping of dotted paths to 1-sigma values")
        prov = d.get("provenance") or {}
        if not isinstance(prov, Mapping):
            raise ParameterError("provenance: expected a mapping")
        # the dimensioned scalars the file leaves to the built-in defaults (a spindle's file without
        # `inertia:` had 5 kg·m² simulated and kept by a fit against its log's 0.004, unsaid); a
        # file written from such a set keeps the mark while its value is still the default
        marked = prov.get(DEFAULTED)
        marked = set(marked) if isinstance(marked, (list, tuple)) else set()
        left = [f.name for f in _scalar_fields(cls) if f.name in DEFAULTABLE
                and (f.name not in scalars or (f.name in marked and scalars[f.name] == f.default))]
        prov = {**{k: v for k, v in prov.items() if k != DEFAULTED}, **({DEFAULTED: left} if left else {})}
        p = cls(model=model, stribeck=stribeck, transition_curve=tc, units=units, effects=tuple(effects),
                uncertainty={str(k): _number(f"uncertainty.{k}", v) for k, v in unc.items()},
                provenance=prov, **scalars)
        p = _check_uncertainty_paths(p)
        if p.model == "lugre" and p.sigma0 is None:
            p.transition_curve.validate()
            p.stribeck.validate()
            from .lugre import lugre_sigma0_from_transition_curve

            p = p.replace(sigma0=lugre_sigma0_from_transition_curve(p))
        return p.validate()


DEFAULTED = "defaulted"  # provenance: the scalars a file left to their built-in defaults (``FrictionParams.defaulted``)
DEFAULTABLE = ("sigma1", "inertia")  # the dimensioned scalars a file in the paper's units may leave out


def _stribeck_from(st) -> Stribeck:
    if st is None:
        raise ParameterError("stribeck: missing (S(v) of eq. (7) for both velocity signs: "
                             "positive and negative, each with Fs, Fc, vs, delta, sigma2)")
    if not isinstance(st, Mapping):
        raise ParameterError("stribeck: expected a mapping with 'positive' and 'negative'")
    extra = sorted(str(k) for k in st if k not in ("positive", "negative"))
    if extra:
        raise ParameterError(f"stribeck.{extra[0]}: unknown field (known: positive, negative)")
    names = [f.name for f in _scalar_fields(StribeckSide)]
    sides = {}
    for sname, _, _ in STRIBECK_SIDES:
        sd = st.get(sname)
        if not isinstance(sd, Mapping):
            raise ParameterError(f"stribeck.{sname}: missing or not a mapping of {', '.join(names)}")
        # an unknown field first: a misspelt one ('Fss') is also the one then missing
        extra = sorted(str(k) for k in sd if k not in names)
        if extra:
            raise ParameterError(f"stribeck.{sname}.{extra[0]}: unknown field (known: {', '.join(names)})")
        for k in names:
            if k not in sd:
                raise ParameterError(f"stribeck.{sname}.{k}: missing")
        sides[sname] = StribeckSide(**{k: _number(f"stribeck.{sname}.{k}", sd[k]) for k in names})
    return Stribeck(**sides)


def _transition_curve_from(tcd) -> TransitionCurve:
    if tcd is None:
        raise ParameterError("transition_curve: missing (kind piecewise_linear with knots z and F, "
                             "or tanh_linear with shape A, z0, k)")
    if not isinstance(tcd, Mapping):
        raise ParameterError("transition_curve: expected a mapping")
    kind = tcd.get("kind", "piecewise_linear")
    if not isinstance(kind, str) or kind not in TRANSITION_KINDS:
        raise ParameterError(f"transition_curve.kind: must be one of {', '.join(TRANSITION_KINDS)}, got {kind!r}"[:200])
    allowed = ("kind", "z", "F") if kind == "piecewise_linear" else ("kind", "shape")
    extra = sorted(str(k) for k in tcd if k not in allowed)
    if extra:
        raise ParameterError(f"transition_curve.{extra[0]}: unknown field for {kind} (known: {', '.join(allowed)})")
    if kind == "piecewise_linear":
        for k in ("z", "F"):
            if not isinstance(tcd.get(k), (list, tuple)):
                raise ParameterError(f"transition_curve.{k}: expected a list of knot values")
            if len(tcd[k]) > MAX_KNOTS:  # refuse before converting anything
                raise ParameterError(f"transition_curve.{k}: {len(tcd[k])} knots, at most {MAX_KNOTS} are accepted")
        return TransitionCurve(kind=kind, z=tuple(_number(f"transition_curve.z.{i}", v) for i, v in enumerate(tcd["z"])),
                               F=tuple(_number(f"transition_curve.F.{i}", v) for i, v in enumerate(tcd["F"])))
    shape = tcd.get("shape")
    if not isinstance(shape, Mapping):
        raise ParameterError("transition_curve.shape: expected a mapping of A, z0, k")
    return TransitionCurve(kind=kind, shape=shape)


_CURVE_SIGMA = re.compile(r"^transition_curve\.((z|F)\.\d+|shape\.(A|z0|k))$")


def _check_uncertainty_paths(p: "FrictionParams") -> "FrictionParams":
    """Every key of ``uncertainty`` names a parameter of the file (a schema path, or an effect's
    parameter): a misspelt one ('stribeck.positive.Fss') would otherwise be read and shown
    nowhere, as if that σ had been given. The σ of a knot the curve no longer has (a file saved
    after a knot was removed, before ``replace`` dropped such σ) is dropped, not refused."""
    known = {s.path for s in schema(p, all_models=True)}
    for i, eff in enumerate(p.effects):
        params = eff.get("params") if isinstance(eff, Mapping) else None
        known.update(f"effects.{i}.params.{k}" for k in (params or {}))
    stale = [k for k in p.uncertainty if k not in known and _CURVE_SIGMA.match(k)]
    if stale:
        p = replace(p, uncertainty={k: v for k, v in p.uncertainty.items() if k not in stale})
    unknown = sorted(k for k in p.uncertainty if k not in known)
    if unknown:
        raise ParameterError(f"uncertainty.{unknown[0]}: no such parameter in this file (a σ is keyed by the "
                             f"parameter's dotted path, e.g. stribeck.positive.Fs, transition_curve.F.1, sigma1)")
    return p


def _validate_effects(effects) -> tuple:
    """Each entry checked by ``model.effects.validate_effect_entry`` (the effect's own parameter
    rules); returns the cleaned entries."""
    from . import effects as fx

    check = getattr(fx, "validate_effect_entry", None)
    if check is not None:
        return tuple(check(eff, f"effects.{i}") for i, eff in enumerate(effects))
    for i, eff in enumerate(effects):
        if not isinstance(eff, Mapping) or eff.get("name") not in fx.EFFECTS:
            raise ParameterError(f"effects.{i}.name: must be one of {', '.join(fx.EFFECTS)}")
        if not isinstance(eff.get("params"), Mapping):
            raise ParameterError(f"effects.{i}.params: expected a mapping of parameter values")
        for k, v in eff["params"].items():
            _number(f"effects.{i}.params.{k}", v)
    return tuple(effects)


# -- the schema: one entry per scalar parameter ---------------------------------------------------
def schema(params: "FrictionParams | None" = None, *, all_models: bool = False) -> tuple[ParamSpec, ...]:
    """Every scalar parameter of ``params`` (default: the paper's set) in display order:
    S(v) per side, the transition curve's knots (or tanh shape), then n, σ1, σ0, I, reversal tol.
    Units are rendered in the parameter set's units. Parameters the model kind does not use are
    left out unless ``all_models``."""
    p = params if params is not None else default_params()
    u = p.units
    out = []
    for side, sign, suffix in STRIBECK_SIDES:
        for f in _scalar_fields(StribeckSide):
            out.append(_spec(f, f"stribeck.{side}.{f.name}", u, sign, suffix))
    if all_models or p.model == "leuven":
        out.extend(knot_specs(p.transition_curve, u))
    for f in _scalar_fields(FrictionParams):
        if all_models or p.model in f.metadata["models"]:
            if f.name == "sigma0" and p.sigma0 is None and not all_models:
                continue
            out.append(_spec(f, f.name, u))
    return tuple(out)


def knot_specs(tc: TransitionCurve, units: Units = PAPER_UNITS) -> tuple[ParamSpec, ...]:
    """The free coordinates of the transition curve: z_i and F_d(z_i) for i >= 1 (the first knot
    is (0, 0) by point symmetry), or the tanh shape's A, z0, k."""
    if tc.kind == "tanh_linear":
        return tuple(_spec(f, f"transition_curve.shape.{f.name}", units) for f in _scalar_fields(TanhShape))
    fz, fF = (next(f for f in fields(TransitionCurve) if f.name == n) for n in ("z", "F"))
    out = []
    for i in range(1, len(tc.z)):
        out.append(_spec(fz, f"transition_curve.z.{i}", units, index=i))
        out.append(_spec(fF, f"transition_curve.F.{i}", units, index=i))
    return tuple(out)


def spec_of(params: FrictionParams, path: str) -> ParamSpec:
    for s in schema(params, all_models=True):
        if s.path == path:
            return s
    raise ParameterError(f"{path}: no such parameter")


def get_value(params: FrictionParams, path: str) -> float:
    """The value at a dotted path, e.g. 'stribeck.negative.Fc', 'transition_curve.F.2'."""
    obj = params
    try:
        for part in path.split("."):
            obj = obj[int(part)] if part.isdigit() else (obj[part] if isinstance(obj, Mapping) else getattr(obj, part))
    except (AttributeError, IndexError, KeyError, TypeError):
        raise ParameterError(f"{path}: no such parameter") from None
    return obj


def with_value(params: FrictionParams, path: str, value: float) -> FrictionParams:
    """A new parameter set with one value changed (checked against the schema; the whole set is
    validated, so e.g. a knot that breaks monotonicity is refused with its path)."""
    x = spec_of(params, path).check(value)

    def put(obj, parts):
        head, rest = parts[0], parts[1:]
        if isinstance(obj, tuple):
            i = int(head)
            return obj[:i] + (put(obj[i], rest) if rest else x,) + obj[i + 1:]
        new = put(getattr(obj, head), rest) if rest else x
        return replace(obj, **{head: new})

    return put(params, path.split(".")).validate()


def values(params: FrictionParams) -> dict:
    """{dotted path: value} for every scalar parameter of the schema."""
    return {s.path: float(get_value(params, s.path)) for s in schema(params)}


@dataclass(frozen=True)
class ParamRow:
    """One line of a parameter table: the schema entry, the value and its 1-sigma uncertainty
    (None when the parameter was held, not estimated)."""

    spec: ParamSpec
    value: float
    stderr: float | None

    @property
    def status(self) -> str:
        return "held" if self.stderr is None else "estimated"


def parameter_rows(params: FrictionParams) -> tuple[ParamRow, ...]:
    unc = params.uncertainty
    return tuple(ParamRow(s, float(get_value(params, s.path)), unc.get(s.path)) for s in schema(params))


# -- the paper's values ---------------------------------------------------------------------------
def kuka_stribeck() -> Stribeck:
    """Table I: KUKA IR 361, axis 1."""
    return Stribeck(
        positive=StribeckSide(Fs=36.0, Fc=27.0, vs=0.007, delta=0.5, sigma2=7.7),
        negative=StribeckSide(Fs=-63.0, Fc=-52.0, vs=-0.004, delta=0.9, sigma2=8.0),
    )


def kuka_transition_curve() -> TransitionCurve:
    """Table II: the four-segment piecewise-linear positive transition curve."""
    return TransitionCurve(
        kind="piecewise_linear",
        z=(0.0, 1.80e-6, 1.41e-4, 2.66e-4, 5.21e-4),
        F=(0.0, 16.4, 75.1, 87.5, 100.0),
    )


def default_params(model: str = "leuven") -> FrictionParams:
    """The paper's KUKA IR 361 axis-1 model: Tables I and II, n = 7, sigma1 = 1500 N·m·s/rad.

    For ``model='lugre'`` sigma0 is derived by fitting the LuGre transition curve to the Leuven
    one (Fig. 4), see ``model.lugre.lugre_sigma0_from_transition_curve``.
    """
    p = FrictionParams(model="leuven", stribeck=kuka_stribeck(), transition_curve=kuka_transition_curve())
    if model == "leuven":
        return p
    if model == "lugre":
        from .lugre import lugre_sigma0_from_transition_curve

        return p.replace(model="lugre", sigma0=lugre_sigma0_from_transition_curve(p))
    if model == "static":
        return p.replace(model="static")
    raise ParameterError(f"model: must be one of {', '.join(MODEL_KINDS)}, got {model!r}")


def as_model(p: FrictionParams, model: str) -> FrictionParams:
    """The same physical parameters seen by another model kind (LuGre gets a fitted sigma0)."""
    if model == p.model:
        return p
    if model == "lugre" and p.sigma0 is None:
        from .lugre import lugre_sigma0_from_transition_curve

        return p.replace(model="lugre", sigma0=lugre_sigma0_from_transition_curve(p)).validate()
    return p.replace(model=model).validate()


SIDE_MARK = {"positive": "⁺", "negative": "⁻"}


def sanity_warnings(p: FrictionParams) -> list[str]:
    """Physically odd but valid parameter sets: said, not refused."""
    out = []
    for side in ("positive", "negative"):
        s = getattr(p.stribeck, side)
        if abs(s.Fc) > abs(s.Fs):
            out.append(f"|Fc{SIDE_MARK[side]}| = {abs(s.Fc):.4g} > |Fs{SIDE_MARK[side]}| = {abs(s.Fs):.4g}: "
                       "friction would rise with speed (no Stribeck dip)")
        if s.delta > 5 or s.delta < 0.2:
            out.append(f"δ{SIDE_MARK[side]} = {s.delta:.3g} is far outside the usual 0.5–2")
    tc = p.transition_curve
    if tc.kind == "piecewise_linear":
        Fs = max(abs(p.stribeck.positive.Fs), abs(p.stribeck.negative.Fs))
        if tc.F[-1] < 0.5 * Fs:
            out.append(f"the transition curve ends at {tc.F[-1]:.4g}, well below |Fs| = {Fs:.4g}: "
                       "presliding beyond the last knot follows its extended last segment")
    elif tc.kind == "tanh_linear" and tc.shape is not None:
        # a tanh curve is evaluated as written (``reaching_knots`` is for knots): where it reaches
        # the outer loop's span only far past its bend, eq. (5) settles in sliding only there
        A, z0, k = tc.shape["A"], tc.shape["z0"], tc.shape["k"]
        span = p.outer_loop_span
        if span > A and (k <= 0 or (span - A) / k > 20.0 * z0):
            out.append(f"the tanh transition curve (A = {A:.4g}, k = {k:.3g}) reaches the outer loop's span {span:.4g} "
                       f"only past z = {(span - A) / k if k > 0 else float('inf'):.3g}, {((span - A) / k / z0) if k > 0 else float('inf'):.3g} × z0: "
                       "sliding settles only there, and σ1·dz/dt acts until then")
    return out
