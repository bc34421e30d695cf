"""The explorer's view of the parameter schema (``model.params.schema``): one record per control.

Values are read and written by dotted path (``stribeck.positive.vs``,
``transition_curve.z.2``), the names the YAML file and the fit report use.
"""

from __future__ import annotations

from dataclasses import dataclass

from ...model import FrictionParams
from ...model.errors import ParameterError
from ...model.params import SIDE_MARK, ParamSpec, get_value as _get, sanity_warnings, schema, with_value  # noqa: F401

MODELS = {"n": ("leuven",), "sigma1": ("leuven", "lugre"), "sigma0": ("lugre",)}


@dataclass(frozen=True)
class Field:
    """A schema entry with the model kinds that use it."""

    spec: ParamSpec
    models: tuple

    path = property(lambda self: self.spec.path)
    label = property(lambda self: self.spec.label)
    unit = property(lambda self: self.spec.unit)
    scale = property(lambda self: self.spec.scale)
    sign = property(lambda self: self.spec.sign)

    @property
    def hint(self) -> str:
        return self.spec.hint


def fields_of(p: FrictionParams) -> list[Field]:
    """Every parameter the explorer shows, in the schema's order (all model kinds)."""
    out = []
    for s in schema(p.replace(model="leuven") if p.transition_curve.kind != "piecewise_linear" else p, all_models=True):
        if not s.control:
            continue
        models = MODELS.get(s.path, ("leuven",) if s.group == "transition_curve" else ("leuven", "lugre", "static"))
        out.append(Field(s, models))
    return out


def get_value(p: FrictionParams, path: str) -> float | None:
    try:
        v = _get(p, path)
    except ParameterError:
        return None
    return None if v is None else float(v)


def with_values(p: FrictionParams, values: dict) -> FrictionParams:
    """A new, validated parameter set with ``values`` (dotted path -> float) written in.

    The uncertainty of an edited value no longer applies and is dropped. Every problem is
    a ParameterError naming the field."""
    for path, v in values.items():
        p = with_value(p, path, v)
    unc = {k: s for k, s in p.uncertainty.items() if k not in values}
    return p.replace(uncertainty=unc).validate()


def check_field(f: Field, value: float) -> str | None:
    """Why ``value`` cannot be the value of ``f`` (sign rule, bounds), or None."""
    try:
        f.spec.check(value)
    except ParameterError as e:
        return str(e)
    return None
