"""Parameter records of the friction models, with validation that names the offending field.

Everything here is pure data: conversion to and from plain dicts (the YAML shape of
DESIGN.md), validation, and packing into the flat arrays the compiled kernels take.
Reading and writing files lives in ``identify.paramfile``; ``model`` does no I/O.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, replace

import numpy as np

from .errors import ParameterError

MODEL_KINDS = ("leuven", "lugre", "static")
TRANSITION_KINDS = ("piecewise_linear", "tanh_linear")


def _finite(path: str, value) -> float:
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{path}: expected a number, got {value!r}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{path}: must be finite, got {value!r}")
    return x


@dataclass(frozen=True)
class StribeckSide:
    """Eq. (7) for one velocity sign: S(v) = Fc + (Fs - Fc)·exp(-|v/vs|^delta), plus sigma2·v.

    On the negative side Fs, Fc and vs are negative numbers (Table I convention).
    """

    Fs: float
    Fc: float
    vs: float
    delta: float
    sigma2: float

    def validate(self, path: str, sign: int) -> None:
        for name in ("Fs", "Fc", "vs", "delta", "sigma2"):
            _finite(f"{path}.{name}", getattr(self, name))
        word = "positive" if sign > 0 else "negative"
        for name in ("Fs", "Fc", "vs"):
            if getattr(self, name) * sign <= 0:
                raise ParameterError(
                    f"{path}.{name}: must be {word} on the {word}-velocity side "
                    f"(Table I convention), got {getattr(self, name)}"
                )
        if self.delta <= 0:
            raise ParameterError(f"{path}.delta: must be > 0, got {self.delta}")
        if self.sigma2 < 0:
            raise ParameterError(f"{path}.sigma2: must be >= 0, got {self.sigma2}")

    def as_array(self) -> np.ndarray:
        return np.array([self.Fs, self.Fc, self.vs, self.delta, self.sigma2], dtype=np.float64)


@dataclass(frozen=True)
class Stribeck:
    positive: StribeckSide
    negative: StribeckSide

    def validate(self, path: str = "stribeck") -> None:
        self.positive.validate(f"{path}.positive", +1)
        self.negative.validate(f"{path}.negative", -1)

    def as_array(self) -> np.ndarray:
        """[Fs+, Fc+, vs+, delta+, sigma2+, Fs-, Fc-, vs-, delta-, sigma2-] for the kernels."""
        return np.concatenate([self.positive.as_array(), self.negative.as_array()])


@dataclass(frozen=True)
class TransitionCurve:
    """The positive half of the point-symmetric, strictly increasing transition curve F_d(z).

    ``piecewise_linear``: knots ``z`` (rad or m) and ``F`` (N·m or N) starting at (0, 0), as
    Table II; beyond the last knot the last segment is extended (F_d must be invertible over
    every force difference the hysteresis memory can ask for).
    ``tanh_linear``: F_d(z) = A·tanh(z/z0) + k·z, a smooth three-parameter family
    (``shape = {A, z0, k}``): initial stiffness A/z0 + k, far-field stiffness k.
    """

    kind: str = "piecewise_linear"
    z: tuple[float, ...] = ()
    F: tuple[float, ...] = ()
    shape: dict = field(default_factory=dict)

    def validate(self, path: str = "transition_curve") -> None:
        if self.kind not in TRANSITION_KINDS:
            raise ParameterError(f"{path}.kind: must be one of {', '.join(TRANSITION_KINDS)}, got {self.kind!r}")
        if self.kind == "piecewise_linear":
            if len(self.z) != len(self.F):
                raise ParameterError(f"{path}: z has {len(self.z)} knots but F has {len(self.F)}")
            if len(self.z) < 2:
                raise ParameterError(f"{path}: needs at least 2 knots (0,0) and one more, got {len(self.z)}")
            z = [_finite(f"{path}.z.{i}", v) for i, v in enumerate(self.z)]
            F = [_finite(f"{path}.F.{i}", v) for i, v in enumerate(self.F)]
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
            for name in ("A", "z0", "k"):
                if name not in self.shape:
                    raise ParameterError(f"{path}.shape.{name}: missing (tanh_linear needs A, z0, k)")
                if _finite(f"{path}.shape.{name}", self.shape[name]) <= 0:
                    raise ParameterError(f"{path}.shape.{name}: must be > 0, got {self.shape[name]}")

    def kernel_arrays(self) -> tuple[int, np.ndarray, np.ndarray]:
        """(kind code, abscissas, ordinates-or-shape) for ``model.kernels``."""
        if self.kind == "piecewise_linear":
            return 0, np.asarray(self.z, dtype=np.float64), np.asarray(self.F, dtype=np.float64)
        s = self.shape
        return 1, np.zeros(1), np.array([s["A"], s["z0"], s["k"]], dtype=np.float64)


@dataclass(frozen=True)
class FrictionParams:
    """A complete friction model: the kind, S(v) per sign, the transition curve and the rest.

    ``n`` and ``transition_curve`` belong to the Leuven model, ``sigma0`` to LuGre; ``sigma1``
    is the micro-viscous coefficient of both. ``inertia`` is the I of eq. (8): the paper gives
    none, so the default (5 kg·m²) is our choice. ``reversal_tol`` is the smallest hysteresis
    force excursion (force units) that counts as a velocity reversal; a sign change of v within
    it wipes the previous reversal out again (see ``model.kernels.velocity_reversal``).
    """

    model: str = "leuven"
    stribeck: Stribeck = None  # type: ignore[assignment]
    transition_curve: TransitionCurve = None  # type: ignore[assignment]
    n: float = 7.0
    sigma1: float = 1500.0
    sigma0: float | None = None
    inertia: float = 5.0
    reversal_tol: float = 1e-7
    units: dict = field(default_factory=lambda: {"position": "rad", "force": "N*m", "time": "s"})
    effects: tuple = ()
    uncertainty: dict = field(default_factory=dict)
    provenance: dict = field(default_factory=dict)

    def validate(self) -> "FrictionParams":
        if self.model not in MODEL_KINDS:
            raise ParameterError(f"model: must be one of {', '.join(MODEL_KINDS)}, got {self.model!r}")
        if self.stribeck is None:
            raise ParameterError("stribeck: missing")
        self.stribeck.validate()
        if self.transition_curve is None:
            raise ParameterError("transition_curve: missing")
        self.transition_curve.validate()
        if _finite("n", self.n) <= 0:
            raise ParameterError(f"n: must be > 0, got {self.n}")
        if _finite("sigma1", self.sigma1) < 0:
            raise ParameterError(f"sigma1: must be >= 0, got {self.sigma1}")
        if _finite("inertia", self.inertia) <= 0:
            raise ParameterError(f"inertia: must be > 0, got {self.inertia}")
        if _finite("reversal_tol", self.reversal_tol) < 0:
            raise ParameterError(f"reversal_tol: must be >= 0, got {self.reversal_tol}")
        if self.model == "lugre":
            if self.sigma0 is None:
                raise ParameterError("sigma0: LuGre needs the bristle stiffness sigma0")
            if _finite("sigma0", self.sigma0) <= 0:
                raise ParameterError(f"sigma0: must be > 0, got {self.sigma0}")
        return self

    def replace(self, **changes) -> "FrictionParams":
        return replace(self, **changes)

    # -- plain dicts (the YAML shape) -------------------------------------------------------
    def to_dict(self) -> dict:
        tc = self.transition_curve
        tc_d: dict = {"kind": tc.kind}
        if tc.kind == "piecewise_linear":
            tc_d["z"] = [float(v) for v in tc.z]
            tc_d["F"] = [float(v) for v in tc.F]
        else:
            tc_d["shape"] = {k: float(v) for k, v in tc.shape.items()}
        side = lambda s: {k: float(getattr(s, k)) for k in ("Fs", "Fc", "vs", "delta", "sigma2")}  # noqa: E731
        out = {
            "model": self.model,
            "units": dict(self.units),
            "stribeck": {"positive": side(self.stribeck.positive), "negative": side(self.stribeck.negative)},
            "transition_curve": tc_d,
            "n": float(self.n),
            "sigma1": float(self.sigma1),
        }
        if self.sigma0 is not None:
            out["sigma0"] = float(self.sigma0)
        out["inertia"] = float(self.inertia)
        out["reversal_tol"] = float(self.reversal_tol)
        out["effects"] = copy.deepcopy(list(self.effects))
        if self.uncertainty:
            out["uncertainty"] = {k: float(v) for k, v in self.uncertainty.items()}
        if self.provenance:
            out["provenance"] = copy.deepcopy(self.provenance)
        return out

    @classmethod
    def from_dict(cls, d) -> "FrictionParams":
        """Build and validate; every problem is a ParameterError naming the dotted field."""
        if not isinstance(d, dict):
            raise ParameterError(f"parameter file: expected a mapping at the top level, got {type(d).__name__}")
        known = {
            "model", "units", "stribeck", "transition_curve", "n", "sigma1", "sigma0", "inertia",
            "reversal_tol", "effects", "uncertainty", "provenance",
        }
        unknown = sorted(set(d) - known)
        if unknown:
            raise ParameterError(f"{unknown[0]}: unknown field (known: {', '.join(sorted(known))})")
        base = default_params()
        st = d.get("stribeck")
        if st is None:
            stribeck = base.stribeck
        else:
            if not isinstance(st, dict):
                raise ParameterError("stribeck: expected a mapping with 'positive' and 'negative'")
            sides = {}
            for sname in ("positive", "negative"):
                sd = st.get(sname)
                if not isinstance(sd, dict):
                    raise ParameterError(f"stribeck.{sname}: missing or not a mapping of Fs, Fc, vs, delta, sigma2")
                vals = {}
                for k in ("Fs", "Fc", "vs", "delta", "sigma2"):
                    if k not in sd:
                        raise ParameterError(f"stribeck.{sname}.{k}: missing")
                    vals[k] = _finite(f"stribeck.{sname}.{k}", sd[k])
                extra = sorted(set(sd) - set(vals))
                if extra:
                    raise ParameterError(f"stribeck.{sname}.{extra[0]}: unknown field")
                sides[sname] = StribeckSide(**vals)
            stribeck = Stribeck(**sides)
        tcd = d.get("transition_curve")
        if tcd is None:
            tc = base.transition_curve
        else:
            if not isinstance(tcd, dict):
                raise ParameterError("transition_curve: expected a mapping")
            kind = tcd.get("kind", "piecewise_linear")
            if kind not in TRANSITION_KINDS:
                raise ParameterError(f"transition_curve.kind: must be one of {', '.join(TRANSITION_KINDS)}, got {kind!r}")
            if kind == "piecewise_linear":
                for k in ("z", "F"):
                    if not isinstance(tcd.get(k), (list, tuple)):
                        raise ParameterError(f"transition_curve.{k}: expected a list of knot values")
                tc = TransitionCurve(
                    kind=kind,
                    z=tuple(_finite(f"transition_curve.z.{i}", v) for i, v in enumerate(tcd["z"])),
                    F=tuple(_finite(f"transition_curve.F.{i}", v) for i, v in enumerate(tcd["F"])),
                )
            else:
                shape = tcd.get("shape")
                if not isinstance(shape, dict):
                    raise ParameterError("transition_curve.shape: expected a mapping of A, z0, k")
                tc = TransitionCurve(kind=kind, shape={k: shape[k] for k in shape})
        effects = d.get("effects") or []
        if not isinstance(effects, list):
            raise ParameterError("effects: expected a list")
        from .effects import EFFECTS

        for i, eff in enumerate(effects):
            if not isinstance(eff, dict) or eff.get("name") not in EFFECTS:
                raise ParameterError(f"effects.{i}.name: must be one of {', '.join(EFFECTS)}")
            if not isinstance(eff.get("params"), dict):
                raise ParameterError(f"effects.{i}.params: expected a mapping of parameter values")
            for k, v in eff["params"].items():
                _finite(f"effects.{i}.params.{k}", v)
        unc = d.get("uncertainty") or {}
        if not isinstance(unc, dict):
            raise ParameterError("uncertainty: expected a mapping of dotted paths to 1-sigma values")
        prov = d.get("provenance") or {}
        if not isinstance(prov, dict):
            raise ParameterError("provenance: expected a mapping")
        units = d.get("units") or dict(base.units)
        if not isinstance(units, dict):
            raise ParameterError("units: expected a mapping like {position: rad, force: N*m, time: s}")
        sigma0 = d.get("sigma0")
        p = cls(
            model=str(d.get("model", "leuven")),
            stribeck=stribeck,
            transition_curve=tc,
            n=_finite("n", d.get("n", base.n)),
            sigma1=_finite("sigma1", d.get("sigma1", base.sigma1)),
            sigma0=None if sigma0 is None else _finite("sigma0", sigma0),
            inertia=_finite("inertia", d.get("inertia", base.inertia)),
            reversal_tol=_finite("reversal_tol", d.get("reversal_tol", base.reversal_tol)),
            units=dict(units),
            effects=tuple(effects),
            uncertainty={str(k): _finite(f"uncertainty.{k}", v) for k, v in unc.items()},
            provenance=dict(prov),
        )
        if p.model == "lugre" and p.sigma0 is None:
            from .lugre import lugre_sigma0_from_transition_curve

            p = p.replace(sigma0=lugre_sigma0_from_transition_curve(p))
        return p.validate()


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
