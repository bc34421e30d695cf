"""The parameter schema: one entry per scalar parameter, units rendered for the data's units,
validation from the metadata, immutable records, and the YAML rules."""

import dataclasses

import pytest

from leuven_friction.model import FrictionParams, ParameterError, TransitionCurve, default_params
from leuven_friction.model import params as P


def test_schema_lists_every_scalar_field_once(kuka):
    paths = [s.path for s in P.schema(kuka)]
    assert len(paths) == len(set(paths))
    # S(v) per side (Table I's ten), the four free knots of Table II (z and F each), n, σ1, I, reversal tol.
    for side in ("positive", "negative"):
        for name in ("Fs", "Fc", "vs", "delta", "sigma2"):
            assert f"stribeck.{side}.{name}" in paths
    for i in range(1, 5):
        assert f"transition_curve.z.{i}" in paths and f"transition_curve.F.{i}" in paths
    assert {"n", "sigma1", "inertia", "reversal_tol"} <= set(paths)
    assert "sigma0" not in paths  # the Leuven model has no σ0
    # the schema is built from the dataclass fields: a field with metadata is in it
    meta_fields = [f.name for f in dataclasses.fields(FrictionParams) if "kind" in f.metadata]
    assert set(meta_fields) - {"sigma0"} <= set(paths)
    for s in P.schema(kuka):
        assert s.description and s.scale in ("lin", "log") and s.label
        assert P.get_value(kuka, s.path) == pytest.approx(P.values(kuka)[s.path])


def test_units_render_for_the_data_units():
    rot = {s.path: s.unit for s in P.schema(default_params("lugre"))}
    assert rot["stribeck.positive.Fs"] == "N·m"
    assert rot["stribeck.positive.vs"] == "rad/s"
    assert rot["sigma1"] == "N·m·s/rad"  # the paper's unit for σ1 and σ2
    assert rot["sigma0"] == "N·m/rad"
    lin = default_params().replace(units={"position": "m", "force": "N", "time": "s"})
    u = {s.path: s.unit for s in P.schema(lin)}
    assert u["stribeck.negative.sigma2"] == "N·s/m"
    assert u["transition_curve.z.1"] == "m" and u["transition_curve.F.1"] == "N"
    assert u["inertia"] == "N·s²/m"  # = kg
    assert u["n"] == "" and "[" not in P.spec_of(lin, "n").hint


def test_sign_rule_and_bounds_come_from_the_metadata(kuka):
    neg = P.spec_of(kuka, "stribeck.negative.Fc")
    assert neg.sign == -1 and neg.bounds[1] == 0.0
    lo, hi = neg.slider_range(-52.0)
    assert lo < -52.0 < hi <= 0.0
    with pytest.raises(ParameterError, match=r"stribeck\.negative\.Fc: must be negative"):
        P.with_value(kuka, "stribeck.negative.Fc", 5.0)
    with pytest.raises(ParameterError, match=r"sigma1: must be >= 0"):
        P.with_value(kuka, "sigma1", -1.0)
    with pytest.raises(ParameterError, match=r"transition_curve\.F\.2: F_d must be strictly increasing"):
        P.with_value(kuka, "transition_curve.F.2", 10.0)
    q = P.with_value(kuka, "transition_curve.z.4", 6e-4)
    assert q.transition_curve.z[4] == 6e-4 and kuka.transition_curve.z[4] == 5.21e-4
    lo, hi = P.spec_of(kuka, "transition_curve.z.1").slider_range(1.8e-6)
    assert lo > 0 and hi / lo == pytest.approx(1e4)  # log sliders span a factor 100 either way


def test_records_are_immutable(kuka):
    with pytest.raises(dataclasses.FrozenInstanceError):
        kuka.n = 3.0
    with pytest.raises(dataclasses.FrozenInstanceError):
        kuka.stribeck.positive.Fs = 1.0
    assert isinstance(kuka.transition_curve.z, tuple)
    p = kuka.replace(uncertainty={"n": 0.5}, provenance={"data": ["a.csv"]})
    with pytest.raises(TypeError):
        p.uncertainty["n"] = 1.0
    assert p.provenance["data"] == ("a.csv",)
    hash(p)  # usable as a cache key


def test_tanh_curve_round_trips_and_has_its_schema(kuka):
    p = kuka.replace(transition_curve=TransitionCurve(kind="tanh_linear", shape={"A": 20, "z0": 2e-5, "k": 2e4})).validate()
    assert [s.path for s in P.knot_specs(p.transition_curve)] == [
        "transition_curve.shape.A", "transition_curve.shape.z0", "transition_curve.shape.k"]
    assert FrictionParams.from_dict(p.to_dict()) == p
    with pytest.raises(ParameterError, match=r"transition_curve\.shape\.k: missing"):
        TransitionCurve(kind="tanh_linear", shape={"A": 20, "z0": 2e-5})


def test_yaml_dict_writes_the_units_of_the_data(kuka):
    lin = kuka.replace(units={"position": "m", "force": "N", "time": "s"})
    d = lin.to_dict()
    assert d["units"] == {"position": "m", "force": "N", "time": "s"}
    assert FrictionParams.from_dict(d).units == lin.units
    assert P.Units.of_signals({"time": "s", "position": "m", "force": "N"}) == lin.units


@pytest.mark.parametrize("mutate,match", [
    (lambda d: d.pop("stribeck"), r"^stribeck: missing"),
    (lambda d: d.pop("transition_curve"), r"^transition_curve: missing"),
    (lambda d: d.update(n=10 ** 400), r"^n: number too large \(401 digits\)"),
    (lambda d: d.update(transition_curve={"z": list(range(10_000)), "F": list(range(10_000))}),
     rf"transition_curve\.z: 10000 knots, at most {P.MAX_KNOTS}"),
    (lambda d: d.update(units={"position": "m", "force": "N", "time": "s"}) or d.pop("sigma1"),
     r"^sigma1: missing; its default .* is in the paper's units"),
    (lambda d: d.update(units={"angle": "rad"}), r"^units\.angle: unknown"),
    (lambda d: d.update(units={"position": "m"}), r"^units\.force: missing"),
    (lambda d: d.update({1: 2}), r"^1: unknown field"),
])
def test_parameter_dict_errors_name_the_field(kuka, mutate, match):
    d = kuka.to_dict()
    mutate(d)
    with pytest.raises(ParameterError, match=match):
        FrictionParams.from_dict(d)


def test_missing_optional_fields_take_documented_defaults_in_the_paper_units(kuka):
    d = kuka.to_dict()
    for k in ("n", "sigma1", "inertia", "reversal_tol", "units", "effects", "model"):
        d.pop(k)
    p = FrictionParams.from_dict(d)
    assert p.n == 7.0 and p.sigma1 == 1500.0 and p.units == P.PAPER_UNITS
    assert p.inertia == 5.0  # the README's choice where the paper gives none (kg·m², the KUKA axis)


def test_parameter_rows_mark_held_parameters(kuka):
    p = kuka.replace(uncertainty={"stribeck.positive.Fc": 0.3})
    rows = {r.spec.path: r for r in P.parameter_rows(p)}
    assert rows["stribeck.positive.Fc"].status == "estimated" and rows["stribeck.positive.Fc"].stderr == 0.3
    assert rows["n"].status == "held" and rows["n"].value == 7.0


def test_an_uncertainty_key_must_name_a_parameter_of_the_file(kuka):
    d = kuka.to_dict()
    d["uncertainty"] = {"stribeck.positive.Fs": 0.5, "transition_curve.F.4": 1.0, "sigma1": 10.0}
    assert FrictionParams.from_dict(d).uncertainty["stribeck.positive.Fs"] == 0.5
    # an effect's parameter is keyed by its place in the list
    d["effects"] = [{"name": "time_drift", "params": {"t0": 0.0, "b": 0.1, "tau": 30.0}}]
    d["uncertainty"]["effects.0.params.tau"] = 3.0
    assert FrictionParams.from_dict(d).uncertainty["effects.0.params.tau"] == 3.0
    for bad in ("stribeck.positive.Fss", "transition_curve.Fd.1", "effects.1.params.tau", "effects.0.params.T"):
        d2 = dict(d, uncertainty={**d["uncertainty"], bad: 0.1})
        with pytest.raises(ParameterError, match=rf"^uncertainty\.{bad}: no such parameter"):
            FrictionParams.from_dict(d2)
    # the σ of a knot the curve no longer has (removed in the explorer, or a file saved so) is
    # dropped: by ``replace`` when the curve changes, and on reading
    p = FrictionParams.from_dict(d)
    cut = p.replace(transition_curve=TransitionCurve(z=kuka.transition_curve.z[:-1], F=kuka.transition_curve.F[:-1]))
    assert "transition_curve.F.4" not in cut.uncertainty and cut.uncertainty["sigma1"] == 10.0
    d3 = dict(cut.to_dict(), uncertainty={**d["uncertainty"]})
    assert set(FrictionParams.from_dict(d3).uncertainty) == {"stribeck.positive.Fs", "sigma1", "effects.0.params.tau"}
