"""The discrepancy workflow on recordings it has never seen (``synth/hidden.py``: effects
imposed inside an independent Maxwell-slip simulator, in shapes and with parameters that are
not the candidates'): the real-data shape of a
tribometer whose load ramps while the contact sticks; the CLI and its report. The confusion
matrix over the whole hidden-effect suite (72 cases, 8 minutes) is a benchmark (``python -m
bench.diagnosis --suite``, numbers in the README); a sample of it on fresh seeds is a test here.

The base model is the generator's own friction without the effect, seen through the Leuven
model (``synth.hidden.oracle_params``): a model as good as a fit can be, of another form."""

import json
import re

import numpy as np
import pytest

from leuven_friction.app.cli import main
from leuven_friction.identify.diagnose import diagnose, gap_by_regime
from leuven_friction.model.effects import EFFECTS
from synth.hidden import make_case, oracle_params, to_recording


def test_tribometer_load_ramped_while_sticking_names_normal_load():
    df, truth, case = make_case("tribometer", 4242, (), load_ramps=True)
    d = diagnose(to_recording(df, "tribometer.csv"), oracle_params(truth))
    assert "normal_load" in d.effects, d.text()
    alpha = d.steps[d.effects.index("normal_load") + 2]["params"]["alpha"]
    assert 0.5 < alpha < 1.5, d.text()  # friction ∝ load in the generator


def test_clean_recording_names_nothing_and_keeps_the_model(tmp_path):
    df, truth, case = make_case("tribometer", 4243, ())
    base = oracle_params(truth)
    rec = to_recording(df, "clean.csv")
    d = diagnose(rec, base)
    assert d.effects == [] and d.params_after is base, d.text()
    # the gap stated after is the file's that is written — the one given — not the alternative's
    assert d.rms_after == d.steps[0]["rms"] and np.array_equal(d.model_after, d.model_before)
    # what `fit` reports of a model's friction gap is the gap the diagnosis starts from
    said = gap_by_regime(rec, base)
    assert said.startswith(f"RMS {d.rms_before:.3g} ") and f"× the noise floor {d.noise:.3g}" in said, (said, d.text())
    pre = d.regimes["presliding"]["rms_before"]
    assert f"presliding {pre:.3g} ({pre / d.noise:.1f} ×)," in said, said


def test_the_work_reported_counts_every_simulation_and_its_time(monkeypatch):
    # every simulation of the record goes through model.friction_along (friction compared):
    # a spy on it counts them and times them on its own, and the diagnosis's account of its
    # work must agree, its simulations a part of its wall time and its JSON carrying the same
    import dataclasses
    import time

    import leuven_friction.identify.diagnose as D

    calls, spent = [], [0.0]
    real = D.friction_along

    def spy(*args, **kw):
        t0 = time.perf_counter()
        out = real(*args, **kw)
        spent[0] += time.perf_counter() - t0
        calls.append(1)
        return out

    monkeypatch.setattr(D, "friction_along", spy)
    df, truth, case = make_case("tribometer", 4247, ("time_drift",))
    t0 = time.perf_counter()
    d = diagnose(to_recording(df, "drift.csv"), oracle_params(truth))
    wall = time.perf_counter() - t0
    w = d.work
    assert w.simulations == len(calls) > 0
    # the engine's clock brackets the spy's (each call to the spy lies inside the engine's interval)
    assert 0.0 < spent[0] <= w.simulation_seconds < w.seconds <= wall
    assert json.loads(json.dumps(d.summary()))["work"] == dataclasses.asdict(w)


def test_a_base_off_by_half_is_returned_as_given_and_said_to_be_off():
    # S(v) levels 1.5 × the machine's: the level the alternative refits takes that up, no effect
    # is named, the file written is the one given, and the report says the base is what is off
    import dataclasses

    from leuven_friction.model import Stribeck

    df, truth, case = make_case("tribometer", 4243, ())
    base = oracle_params(truth)
    off = base.replace(stribeck=Stribeck(*(dataclasses.replace(sd, Fs=1.5 * sd.Fs, Fc=1.5 * sd.Fc)
                                           for sd in (base.stribeck.positive, base.stribeck.negative))))
    d = diagnose(to_recording(df, "clean.csv"), off)
    assert d.effects == [] and d.params_after is off, d.text()
    assert d.rms_after == d.steps[0]["rms"] > 10 * d.steps[1]["rms"], d.text()
    assert any("the base, not a missing effect, is what is off" in n for n in d.notes), d.text()
    # and the alternative's step says which way: all of the friction scaled down, towards 1/1.5
    # (the free steady curve beside it takes a part: measured ×0.58), said as a scale of all the
    # model's friction beneath the curve, not as "level ×0.58", which read as a change of S(v)
    label = d.steps[1]["label"]
    g = float(re.search(r"the model's friction ×([0-9.]+) beneath the curve, presliding stiffness ×", label).group(1))
    assert 0.4 < g < 0.8, label


def test_diagnose_cli_writes_json_html_yaml_that_simulate_reproduces(tmp_path):
    df, truth, case = make_case("tribometer", 4244, ("time_drift",))
    data = tmp_path / "rec.csv"
    df.to_csv(data, index=False)
    from leuven_friction.identify.paramfile import load_params, save_params

    base = tmp_path / "base.yaml"
    save_params(oracle_params(truth), base)
    out_json, out_html, out_yaml = tmp_path / "r.json", tmp_path / "r.html", tmp_path / "p.yaml"
    assert main(["diagnose", str(data), "--params", str(base), "--columns", "normal_load=Normal [uN]", "--json",
                 str(out_json), "--html", str(out_html), "--out", str(out_yaml)]) == 0
    res = json.loads(out_json.read_text())
    assert "time_drift" in res["effects"]
    # the JSON carries the first named effect's fitted parameters, under that effect's names
    assert set(res["effect_params"]) == set(EFFECTS[res["effects"][0]].param_names), res["effect_params"]
    assert res["steps"][-1]["rms"] <= 0.7 * res["steps"][1]["rms"]
    html = out_html.read_text()
    assert "Plotly.newPlot" in html and "<script src=\"http" not in html  # plotly.js embedded
    p = load_params(out_yaml)
    assert [e["name"] for e in p.effects] == res["effects"]
    # the drift's estimated parameters carry their 1-σ (the jackknife over the cross-validation's
    # folds and the model's move from the value decided on), in the file and in the report, and
    # its start t0, fixed at the first sample compared, none. The generator's drift, a viscosity
    # law exp(−β·ΔT(t)) of a first-order temperature, is best matched from t0 to the end by the
    # candidate's law (``truth_comparable``): both within 3 σ
    from bench.diagnosis import truth_comparable

    i = [e["name"] for e in p.effects].index("time_drift")
    drift, unc = p.effects[i]["params"], p.uncertainty
    assert {k for k in unc if k.startswith("effects.")} == {f"effects.{i}.params.b", f"effects.{i}.params.tau"}, unc
    best = truth_comparable("time_drift", case.params["time_drift"], float(df.iloc[-1, 0] - df.iloc[0, 0]),
                            drift["t0"] - float(df.iloc[0, 0]))
    assert abs(drift["tau"] - best["tau"]) < 3 * unc[f"effects.{i}.params.tau"], (drift, unc, best)
    assert abs(drift["b"] - best["b"]) < 3 * unc[f"effects.{i}.params.b"], (drift, unc, best)
    assert set(res["steps"][2]["sd"]) == {"b", "tau"} and "± 1 σ" in html
    # the extended model, driven by the recorded motion through `simulate --input` along the
    # path the diagnosis compares (the logged position smoothed: its steps are the sensor's),
    # closes the gap the report states (the file logs friction as a reaction: compared with its
    # negative)
    pred = tmp_path / "pred.csv"
    assert main(["simulate", "--input", str(data), "--drive", "displacement", "--smooth-path", "--params",
                 str(out_yaml), "--columns", "normal_load=Normal [uN]", "--out", str(pred)]) == 0
    import pandas as pd

    meas = -df["Friction [uN]"].to_numpy() * 1e-6
    rms = float(np.sqrt(np.mean((pd.read_csv(pred)["friction_force"].to_numpy() - meas) ** 2)))
    assert rms == pytest.approx(res["rms_after"], rel=0.2)
    assert rms < 0.7 * res["steps"][0]["rms"]


def test_the_file_a_diagnosis_writes_starts_the_next_one_from_its_last_gap(tmp_path):
    # name, add, look again: a robot joint whose presliding spring softens with the reversals
    # (friction taken from the applied torque by eq. (8)). The file the first diagnosis writes
    # carries the softening; diagnosed again from that file, the model as given already shows
    # the first one's last gap (the same things left free beside it: the memory's constant
    # and eq. (8)'s inertia, which neither writes), nothing more is named, and the file's own
    # softening is not flagged as unsettled. Both count reversals from the same back-travel: by
    # default each derives it from its file's presliding range, and the written file's, 2.5 times
    # the first's, moves the first significant reversal past the first gross sliding, so the
    # second would compare from 16.8 s, not 3.9 s (a gap 9 % smaller, of another span)
    from leuven_friction.identify.paramfile import save_params
    from synth.hidden import SUITE_RATE

    df, truth, _ = make_case("robot_joint", 4251, ("cyclic_softening",), rate=SUITE_RATE["robot_joint"])
    data, base, written = tmp_path / "joint.csv", tmp_path / "base.yaml", tmp_path / "written.yaml"
    df.to_csv(data, index=False)
    save_params(oracle_params(truth), base)
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    assert main(["diagnose", str(data), "--params", str(base), "--out", str(written), "--json", str(first)]) == 0
    r1 = json.loads(first.read_text())
    assert r1["effects"] == ["cyclic_softening"], r1["effects"]
    back_travel = r1["reading"]["min_excursion"]
    assert main(["diagnose", str(data), "--params", str(written), "--json", str(second),
                 "--threshold", f"min_excursion={back_travel!r}"]) == 0
    r2 = json.loads(second.read_text())
    assert r2["effects"] == [] and not r2.get("unsettled"), r2
    assert r2["reading"]["min_excursion"] == back_travel
    assert r2["steps"][0]["rms"] == pytest.approx(r1["steps"][-1]["rms"], rel=0.02)
    # … where the file the first one started from was 4 times as far off
    assert r1["steps"][0]["rms"] > 3 * r2["steps"][0]["rms"]


def test_the_model_written_from_a_fitted_file_holds_only_what_stayed_held(tmp_path, capsys):
    # a fitted file holds F_s at F_c (its negative side: no level shows the drop) and n at 7; the
    # diagnosis refits both (the S(v) levels, n, σ1 by output error) when it names an effect: the
    # file it writes no longer says they are held, says where they moved, and still holds what
    # stayed undetermined (the negative side's v_s and δ; σ2 is determined by the diagnosis's
    # own steady sliding). --refit-base, which chooses what is written where nothing is named,
    # says it was not used
    import yaml

    fitted, written = tmp_path / "fit.yaml", tmp_path / "diag.yaml"
    assert main(["fit", "sample:effect_position_periodic", "--out", str(fitted)]) == 0
    held_before = yaml.safe_load(fitted.read_text())["provenance"]["held"]
    assert any(k.endswith(".Fs") for k in held_before) and "n" in held_before, held_before
    capsys.readouterr()
    assert main(["diagnose", "sample:effect_position_periodic", "--params", str(fitted), "--out", str(written),
                 "--refit-base"]) == 0
    assert "--refit-base: not used: position_ripple named" in capsys.readouterr().err
    prov = yaml.safe_load(written.read_text())["provenance"]
    assert "position_ripple" in prov["diagnosis"] and "the S(v) levels" in prov["diagnosis"]
    moved = [k for k in held_before if k not in prov["held"]]
    assert "n" in moved and any(k.endswith(".Fs") for k in moved), prov
    assert all(f"{k} " in prov["diagnosis"].split("moved from held:")[1].split(";")[0] for k in moved), prov["diagnosis"]
    # the σ the refit made stale are gone from the file, and the file says so
    unc = yaml.safe_load(written.read_text())["uncertainty"]
    assert not [k for k in unc if k.startswith(("stribeck.", "transition_curve")) or k in ("n", "sigma1")], unc
    assert any(k.startswith("effects.") for k in unc) and "no σ is written for S(v)" in prov["diagnosis"]
    # what the file still holds of S(v) is the fit's value, or one the diagnosis's own steady
    # sliding held anew and says so (its S(v) is identified anew: a δ or a σ2 the fit held may
    # be determined there, and is then among the moved)
    def at(doc, k):
        side, name = k.split(".")[1:]
        return doc["stribeck"][side][name]

    fit_doc, written_doc = yaml.safe_load(fitted.read_text()), yaml.safe_load(written.read_text())
    still = [k for k in held_before if k.startswith("stribeck.") and k in prov["held"]]
    assert still, prov["held"]  # (the negative side's v_s and δ, on this version)
    for k in still:
        assert at(written_doc, k) == at(fit_doc, k) or "the diagnosis's" in prov["held"][k], (k, prov["held"][k])


def test_diagnose_cli_bad_input_is_one_line(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("time,temperature\n" + "".join(f"{i},{20 + i}\n" for i in range(30)))
    assert main(["diagnose", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "position" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_load_rising_with_time_is_reported_as_confounded_with_drift():
    # a tribometer (friction ∝ load by construction) whose load creeps up as a first-order
    # approach over the whole session: a load effect and a drift in time explain the same
    # residual; the diagnosis must say so, name neither, and say which experiment separates them
    from synth.recordings import make_recording

    def load(t):
        return 2.0 + 2.5 * (1.0 - np.exp(-np.asarray(t) / 30.0))

    df, truth = make_recording("tribometer", 4245, normal_load=load)
    d = diagnose(to_recording(df, "creep.csv"), oracle_params(truth))
    pairs = [set(c["effects"]) for c in d.confounded]
    assert {"normal_load", "time_drift"} in pairs, d.text()
    assert "normal_load" not in d.effects and "time_drift" not in d.effects, d.text()
    c = d.confounded[pairs.index({"normal_load", "time_drift"})]
    assert "load" in c["experiment"] and "temperature" in c["experiment"]


def test_final_model_predicts_through_the_model_path():
    # the extended parameter set, driven along the compared path by model.effects.predict,
    # gives exactly the prediction the diagnosis scored
    from leuven_friction.model.effects import Signals, predict

    df, truth, case = make_case("tribometer", 4246, ("position_ripple",))
    d = diagnose(to_recording(df, "ripple.csv"), oracle_params(truth))
    assert d.effects, d.text()
    path = d.explaining["position"][1]
    load = d.explaining["load"][1] if "load" in d.explaining else None
    got = predict(d.params_after, "displacement", Signals(time=d.time, position=path, load=load)).friction_force
    assert np.allclose(got, d.model_after, rtol=1e-6, atol=1e-9 * np.max(np.abs(got)))


def test_model_written_closes_the_gap_on_a_robot_joint():
    # the parameter file written after a named effect, driven along the compared path by the
    # model itself, must shrink the gap by the 30 % against the alternative written
    # without the effect, and beat the model as given. On a robot joint the generator's
    # micro-damping fades as its elements break, the Leuven σ1 acts until the transition
    # ends: σ1 must be refitted for the file to close the gap (it is, and the file says so).
    from leuven_friction.model.effects import Signals, predict

    df, truth, case = make_case("robot_joint", 4250, ("position_ripple",))
    d = diagnose(to_recording(df, "ripple.csv"), oracle_params(truth))
    assert "position_ripple" in d.effects, d.text()
    sig = Signals(time=d.time, position=d.explaining["position"][1])
    # after the presliding ramps: the memory's constant of the start is zero there
    late = d.compared & (d.time > d.time[0] + 0.4 * (d.time[-1] - d.time[0]))

    def gap(model):
        return float(np.sqrt(np.mean((d.measured - model)[late] ** 2)))

    after = gap(predict(d.params_after, "displacement", sig).friction_force)
    given = gap(predict(d.params_before, "displacement", sig).friction_force)
    assert after <= 0.7 * gap(d.step_predictions[1]), d.text()
    assert after <= 0.5 * given, d.text()
    assert d.params_after.sigma1 != d.params_before.sigma1 and "σ1" in d.params_after.provenance["diagnosis"]


def test_hidden_effect_suite_sample_on_fresh_seeds_finds_the_effects_and_names_no_false_one():
    # a sample of the hidden-effect suite on seeds the suite does not use, chosen before the
    # run: each hidden effect once per kind of recording, and two controls per kind. Targets of
    # the whole suite: the right effect found in ≥ 90 % of the cases, a false effect named on
    # ≤ 5 % of the controls. On a sample of 12 and 6 cases: at most two misses (at a 10 % miss
    # rate three or more happen with probability 0.11, at 30 % with 0.75) and at most one false
    # effect (at a 5 % rate two or more happen with probability 0.03). A softening whose n_c
    # ends at its bound is found but not named (seen, not named: it does not settle within the
    # session, the default policy, README), so it counts as found here, not as named; the
    # friction factors, which have no such scale, must be named
    from bench.diagnosis import _diagnose_case

    effects = ("time_drift", "normal_load", "position_ripple")
    kinds = ("robot_joint", "linear_stage", "tribometer")
    rows = []
    seed = 7000
    for eff in effects:
        for kind in kinds:
            rows.append(_diagnose_case(kind, seed, (eff,)))
            seed += 1
    controls = []
    for kind in kinds * 2:
        controls.append(_diagnose_case(kind, seed, ()))
        seed += 1
    for kind in kinds:
        rows.append(_diagnose_case(kind, seed, ("cyclic_softening",)))
        seed += 1
    found = [r["expected"][0] in r["named"] + r["unsettled"] for r in rows]
    assert sum(found) >= len(rows) - 2, [(r["kind"], r["hidden"], r["named"], r["unsettled"]) for r in rows]
    named = [r["expected"][0] in r["named"] for r in rows if r["expected"][0] != "cyclic_softening"]
    assert sum(named) >= len(named) - 2, [(r["kind"], r["hidden"], r["named"]) for r in rows]
    assert sum(bool(r["named"]) for r in controls) <= 1, [(r["kind"], r["named"]) for r in controls]
    # (the gap's shrink is not asserted: the ≥ 30 % target is missed for weak drifts and for
    # softenings in the suite, README)


def test_a_stiffness_that_follows_the_speed_is_not_credited_to_softening():
    # a contact whose presliding spring stiffens with the sliding speed (the generator's state
    # velocity, saturating — not the alternative's log-quadratic form), on a robot joint whose
    # sweep raises its speed with every pair of reversals: the stiffness then also rises with
    # the reversal count, yet no softening or hardening with the reversals may be named
    from synth import recordings as R
    from synth.hidden import SUITE_RATE

    kind, seed = "robot_joint", 3001
    vs = abs(R._random_machine(kind, np.random.default_rng(seed))["stribeck"]["positive"]["vs"])
    df, truth = R.make_recording(kind, seed, rate=SUITE_RATE[kind],
                                 stiffness_modifier=lambda c: 1.0 + (1.0 - np.exp(-np.abs(c.v) / (2 * vs))))
    d = diagnose(to_recording(df), oracle_params(truth))
    assert "cyclic_softening" not in d.effects, d.text()


def test_an_effect_the_model_written_does_not_use_is_not_named(monkeypatch):
    # the rule: an effect named last whose own gain in the model written (``own_gain``: its gap
    # against the same fit with the effect's amplitudes at no effect) is under PRESCREEN·min_gain
    # is not named, its step goes, and the report says why. On a tribometer with a drift hidden
    # (base fitted by `fit`) the drift is named and does a good part of the written gap itself;
    # reported as doing nothing (``own_gain`` replaced), the same decision must drop it. (The
    # rule fired by itself on robot joint 3064 until the fit integrated eq. (5) exactly; on this
    # version no suite case passes held out and then does nothing written.)
    import leuven_friction.identify.diagnose as D
    from leuven_friction.identify.diagnose import PRESCREEN, Settings
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE

    df, _, case = make_case("tribometer", 1002, ("time_drift",), rate=SUITE_RATE["tribometer"])
    rec = to_recording(df, f"{case.label}.csv")
    params = fit_recordings([rec]).params
    s = Settings()
    real = D.own_gain
    seen = []
    monkeypatch.setattr(D, "own_gain", lambda engine, fit: seen.append(real(engine, fit)) or seen[-1])
    d = diagnose(rec, params, settings=s)
    assert d.effects == ["time_drift"] and not d.unused, d.text()
    assert seen and seen[-1] > 10 * PRESCREEN * s.min_gain  # the drift does its share itself
    # the named step's line carries the evidence it was named on (its held-out gain and folds)
    step = d.steps[2]
    line = next(ln for ln in d.text().splitlines() if ln.startswith("  + time_drift"))
    assert f"held out −{100 * step['heldout_gain']:.1f} % (folds {step['folds']})" in line, line
    assert step["heldout_gain"] >= s.min_gain
    monkeypatch.setattr(D, "own_gain", lambda engine, fit: 0.0)
    d = diagnose(rec, params, settings=s)
    assert d.effects == [] and [c["name"] for c in d.unused] == ["time_drift"], d.text()
    assert "Passed, not named: time_drift" in d.text()
    # one step per effect named beside the model as given and the alternative: none for the drift
    assert len(d.steps) == 2


def _stiffness_falling_in_time(kind, seed):
    """A recording whose presliding spring loses 40 % of its stiffness in proportion to the time
    run (wear through the whole session, never settling), and the generator's own base."""
    from synth import recordings as R
    from synth.hidden import SUITE_RATE

    probe, _ = R.make_recording(kind, seed, rate=SUITE_RATE[kind])
    T = float(probe["Time [s]"].iloc[-1])
    df, truth = R.make_recording(kind, seed, rate=SUITE_RATE[kind],
                                 stiffness_modifier=lambda c: 1.0 - 0.4 * np.clip(c.t / T, 0.0, 1.0))
    return to_recording(df), oracle_params(truth)


def test_a_stiffness_trend_that_never_settles_is_seen_and_not_named():
    # a presliding spring that loses stiffness in proportion to the time run on a linear stage
    # whose sweep orders its speeds in time: a softening with the reversals fitted to it runs
    # its n_c to the bound. With must_settle (the default) it is not named, and the report says it
    # was seen and why; without (diagnose --no-require-settling) it is named with that caveat.
    # Counted at the smallest back-travel alone (softening_thresholds=1), where it passes held
    # out; with the threshold fitted (6 tried, the default) it does not even pass here (2.3 %)
    from leuven_friction.identify.diagnose import Settings

    rec, base = _stiffness_falling_in_time("linear_stage", 3002)
    d = diagnose(rec, base, settings=Settings(must_settle=False, softening_thresholds=1))
    assert "cyclic_softening" in d.effects and "its n_c is at its bound" in d.text(), d.text()
    assert "cyclic_softening is named because settling is not required here" in d.text(), d.text()
    assert "cyclic_softening" not in diagnose(rec, base, settings=Settings(softening_thresholds=6)).effects
    strict = diagnose(rec, base, settings=Settings(softening_thresholds=1))
    assert "cyclic_softening" not in strict.effects, strict.text()
    assert [c["name"] for c in strict.unsettled] == ["cyclic_softening"], strict.text()
    assert "Seen, not named: cyclic_softening" in strict.text()
    assert strict.summary()["unsettled"] == ["cyclic_softening"]
    # the explorer's line under its Diagnose button (its "Require settling" box ticked, as it
    # starts) says so rather than "no missing effect"; with the box cleared it names the softening
    from leuven_friction.app.explorer.diagnose_tab import status_line

    assert status_line(strict).startswith("Nothing named: cyclic_softening seen, not named"), status_line(strict)
    assert status_line(d).startswith("Found **") and "cyclic_softening" in status_line(d).split(":")[0]


def test_a_stiffness_falling_in_time_on_cycled_strokes_is_not_named_a_softening():
    # the same wear in time on a tribometer, whose passes cycle through their speeds (the
    # strokes' speeds do not follow the reversals, ρ 0.48): a softening with the reversals fitted
    # to it runs its n_c to the bound again. A stiffness following the speed makes at most a
    # part of that trend here, and one changing with time all of it: seen, not named, and the
    # reason says so.
    # (Naming such a softening where the strokes are not in order of speed was tried: it named
    # this one.)
    d = diagnose(*_stiffness_falling_in_time("tribometer", 3002))
    assert "cyclic_softening" not in d.effects, d.text()
    seen = [c for c in d.unsettled if c["name"] == "cyclic_softening"]
    assert seen and "do not follow the reversals" in seen[0]["unsettled"], d.text()
    assert "a stiffness following the speed makes at most a part of it" in seen[0]["unsettled"]
    assert "changing with time would look the same" in d.text()


def test_a_softening_that_slows_down_on_cycled_strokes_is_named_with_its_size():
    # the generator's softening is hyperbolic in its own reversal count, 1 − h·(1 − 1/(1 + n/n_h)),
    # h = 0.49, n_h = 3.15: by the tribometer's 23rd reversal 88 % of it has happened and it runs
    # at a sixty-sixth of its first rate, yet an exponential fitted to it ends at an n_c well above
    # n_h. Its strokes cycle through their speeds in three passes (ρ 0.48), so no stiffness
    # following the speed makes that trend, and a change seen slowing down within the session
    # (n_c below the reversal count, ``softening_nc_max``) is named. Its size: the hyperbola
    # has dropped by h·23/(23 + n_h) = 0.43 by the session's end, an exponential with n_c inside
    # the session by 63–99 % of its h. (Tribometer 1032, a case of the same shape, served here
    # on earlier numerical platforms; on numpy 2.4 / scipy 1.17 its n_c ends at the bound, 23:
    # seen, not named.)
    from synth.hidden import SUITE_RATE

    df, truth, _ = make_case("tribometer", 3032, ("cyclic_softening",), rate=SUITE_RATE["tribometer"])
    d = diagnose(to_recording(df), oracle_params(truth))
    assert "cyclic_softening" in d.effects and not d.unsettled, d.text()
    soft = next(e for e in d.params_after.effects if e["name"] == "cyclic_softening")["params"]
    end = soft["h"] * -np.expm1(-23.0 / soft["n_c"])  # the exponential's change by the 23rd reversal
    assert 3.0 < soft["n_c"] < 23.0, soft
    assert -0.6 < end < -0.25, soft


def test_fit_then_diagnose_on_fresh_controls_reaches_the_generators_own_base():
    # the user's path on recordings nobody here made: `fit` on the recording, then `diagnose`
    # with what it wrote (a transition curve the fit identified from a few presliding branches,
    # or held at the paper's where it found none). On controls of every kind, on seeds chosen
    # before the run, the alternative every effect must beat (the base refitted, its transition
    # curve reshaped segment by segment where that pays) comes as close to the data as the
    # generator's own friction seen through the Leuven model (``oracle_params``), refitted the
    # same way (measured: 0.90, 0.84, 1.03 and 1.12 of it); and at most one of the four names a
    # false effect (at the target's 5 % rate two or more happen with probability 0.014; measured:
    # one, `cyclic_softening` on the linear stage 7105, which the oracle base names as well)
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE

    false = []
    for kind, seed in (("robot_joint", 7104), ("linear_stage", 7105), ("tribometer", 7106), ("robot_joint", 7107)):
        df, truth, case = make_case(kind, seed, (), rate=SUITE_RATE[kind])
        rec = to_recording(df, f"{case.label}.csv")
        fitted = diagnose(rec, fit_recordings([rec]).params)
        oracle = diagnose(rec, oracle_params(truth))
        false += [(case.label, e) for e in fitted.effects]
        assert fitted.steps[1]["rms_free"] <= 1.25 * oracle.steps[1]["rms_free"], (fitted.text(), oracle.text())
        # the robot joint's and linear stage's velocity sweeps visit their levels slowest first
        # (``_schedule_velocity_sweep``), the tribometer's strokes cycle through theirs: only the
        # sweeps confound a drift with S(v), and the report says so
        ordered = ["speeds in order of time" in n for n in oracle.notes]
        assert any(ordered) == (kind != "tribometer"), oracle.text()
        # the robot joint's strokes also run faster with every reversal (its slow presliding
        # ramps, then the sweep: ρ 0.98 and 0.85): there a softening with the reversals and a
        # stiffness varying with speed follow one trend; not on the tribometer (ρ 0.48). This
        # linear stage's ρ is 0.77, too near the note's 0.8 to assert either way
        strokes = ["speeds in order of the reversals" in n for n in oracle.notes]
        if kind != "linear_stage":
            assert any(strokes) == (kind == "robot_joint"), oracle.text()
    assert len(false) <= 1, false


def test_a_drift_a_rising_sweep_hides_is_named_once_the_speeds_are_shuffled():
    # robot joints 1006 and 3000 of the suite: a warming (1006: friction rising by 20 % over
    # the session) or thinning (3000: falling) lubricant, the generator's exp(−β·ΔT(t)), on a
    # sweep that visits its speed levels slowest first. The fitted S(v) takes the drift in:
    # the diagnosis names nothing, and says that a drift and S(v) are confounded here and
    # which experiment tells them apart. That experiment — the same machines and drifts, the
    # levels visited in a shuffled order (``synth.hidden.shuffled_levels``) — lifts the
    # confound, and gets a drift named with the generator's sign. Each joint is at the bar on
    # its own (1006 named with b = +0.09 ± 0.09 when σ1 was held at the paper's 1500, and
    # seen at 3.1 % held out, 1.9 % in steady sliding, with σ1 at the stuck plant's damping
    # ratio; 3000 the other way round, b = −0.21 ± 0.14), so the test asks it of one of the
    # two. Over the suite's joints and stages the same change of schedule names 18 of 21
    # drifts (19 with σ1 at 1500) against 16 (docs/diagnosis-history.md, "A drift on a sweep in
    # rising speeds", and "σ1 held at a damping ratio of the stuck plant")
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE, shuffled_levels

    def run(seed, levels):
        df, truth, case = make_case("robot_joint", seed, ("time_drift",), rate=SUITE_RATE["robot_joint"], levels=levels)
        rec = to_recording(df, f"{case.label}.csv")
        return diagnose(rec, fit_recordings([rec]).params), case.params["time_drift"]

    named = []
    for seed in (1006, 3000):
        rising, truth = run(seed, None)
        assert "time_drift" not in rising.effects, rising.text()
        note = [n for n in rising.notes if "speeds in order of time" in n]
        assert note and "visit the speed levels in a shuffled order" in note[0], rising.text()
        shuffled, _ = run(seed, shuffled_levels("robot_joint", seed))
        assert not any("speeds in order of time" in n for n in shuffled.notes), shuffled.text()
        if "time_drift" in shuffled.effects:
            drift = next(e for e in shuffled.params_after.effects if e["name"] == "time_drift")["params"]
            # the generator's factor exp(−β·ΔT) rises for β·ΔT < 0: the candidate's b has its sign
            assert np.sign(drift["b"]) == -np.sign(truth["beta_dT"]), (seed, drift, truth)
            named.append(seed)
    assert named, "neither joint's drift named once its speeds were shuffled"


def test_a_ripple_shorter_than_a_held_transition_curve_is_named_from_the_range_the_recording_shows():
    # tribometer 2022 of the suite: a stiff contact (the generator's presliding over 3·10⁻⁷ m,
    # three encoder steps) whose friction crosses within a few samples of each turn, so `fit`
    # finds no presliding branches and holds a transition curve. That was its starting file's —
    # the paper's, in rad, a range of 3·10⁻⁴ "m" here — and a ripple of 3.2·10⁻⁵ m wavelength
    # was then shorter than the shortest the diagnosis tried (two presliding ranges, an eighth
    # of the stroke each): nothing was named, 26 noise floors left. Now either way the range is
    # this machine's: the fit holds the paper's shape within the travel of the crossings' first
    # samples (the curve unresolved), or, given a curve over an eighth of the stroke, the
    # diagnosis takes the range the recording shows after its turns. The ripple is named with
    # the generator's wavelength
    from leuven_friction.identify.fit import fit_recordings
    from leuven_friction.model import default_params
    from synth.hidden import SUITE_RATE

    df, truth, case = make_case("tribometer", 2022, ("position_ripple",), rate=SUITE_RATE["tribometer"])
    rec = to_recording(df, f"{case.label}.csv")
    fitted = fit_recordings([rec])
    assert "transition_curve" in fitted.held and fitted.params.transition_curve.z[-1] < 1e-5, fitted.held
    d = diagnose(rec, fitted.params)
    assert list(d.effects) == ["position_ripple"], d.text()
    lam = d.steps[2]["params"]["wavelength"]
    assert abs(lam / case.params["position_ripple"]["wavelength"] - 1) < 0.05, d.text()
    assert d.steps[2]["rms"] < 0.7 * d.steps[1]["rms"], d.text()  # the gap shrinks by over 30 %
    # the same fit holding the paper's curve in rad (as it did): the range the recording shows
    paper = fitted.params.replace(transition_curve=default_params().transition_curve)
    d = diagnose(rec, paper)
    assert [n for n in d.notes if "not identified: the friction covers 90 %" in n], d.text()
    assert list(d.effects) == ["position_ripple"], d.text()
    lam = d.steps[2]["params"]["wavelength"]
    assert abs(lam / case.params["position_ripple"]["wavelength"] - 1) < 0.05, d.text()
    assert d.steps[2]["rms"] < 0.7 * d.steps[1]["rms"], d.text()  # the gap shrinks by over 30 %


def test_a_softening_that_explains_a_drift_as_well_is_not_named_by_accident():
    # a linear stage whose friction drifts in time, on a sweep in rising speeds (suite case 2001,
    # base fitted by `fit`): a softening and the drift had passed together, 4.5 % better held out
    # each, their corrections unlike (one in the transitions, one in the sliding), and beside the
    # softening the drift no longer gained. The softening had been named: a tie settled by
    # rounding. Whichever of the two comes first, the other is then subsumed by it, so the pair
    # is reported confounded — or the drift, the effect imposed, is named, or (with the base
    # `fit` now gives, its slow runs that trend taken as points of S(v)) neither passes; never
    # the softening alone.
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE

    df, _, _ = make_case("linear_stage", 2001, ("time_drift",), rate=SUITE_RATE["linear_stage"])
    rec = to_recording(df, "stage.csv")
    d = diagnose(rec, fit_recordings([rec]).params)
    assert "cyclic_softening" not in d.effects, d.text()
    _assert_subsumed_pairs_are_said(d)


def _assert_subsumed_pairs_are_said(d):
    from leuven_friction.identify.diagnose import Settings

    for c in d.confounded:
        if c["beside_gain"] is not None:  # subsumed: under the bar beside the first
            assert c["beside_gain"] < Settings().min_gain and min(c["gains"]) >= Settings().min_gain, c
            assert f"beside {c['effects'][0]}" in d.text()


def test_two_effects_that_explain_the_same_part_are_reported_confounded_with_their_evidence():
    # a linear stage with a drift on a sweep in rising speeds (suite case 1007, base fitted by
    # `fit`): a softening passes first, the drift (with a presliding range following it) passes
    # in the same round, not clearly beaten, and gains under the bar once the softening is in the
    # model. Neither is named by accident: the two are reported confounded, each with its own gain
    # over the bar and the second's gain beside the first under it. (A robot joint's load and
    # softening, case 2067, had been; with the load judged beside a range as well, both are named.)
    # Which of the three a machine gives turns on its rounding (below).
    from leuven_friction.identify.diagnose import Settings
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE

    df, _, _ = make_case("linear_stage", 1007, ("time_drift",), rate=SUITE_RATE["linear_stage"])
    rec = to_recording(df, "stage.csv")
    d = diagnose(rec, fit_recordings([rec]).params)
    pair = [c for c in d.confounded if set(c["effects"]) == {"time_drift", "cyclic_softening"}]
    if pair:
        assert not ({"time_drift", "cyclic_softening"} & set(d.effects)), d.text()
        assert all(c["beside_gain"] is not None for c in pair)
    elif "time_drift" in d.effects:
        # a borderline case (README, how firm the counts are): on an Intel Xeon whose OpenBLAS
        # takes AVX-512 kernels, this version and the one before it name both — the drift, and a
        # softening beside it — on the same file; the drift is then not lost either
        pass
    else:
        # on an AMD EPYC without AVX-512 the softening is named first and the drift, in that
        # round not passing beside it, gains under the bar in the next (1.5 % held out): a miss
        # the README counts. What the report must still show: the drift's evidence where a drift
        # must show (the steady sliding, over the bar in most folds) and the schedule that
        # confounds a slow change in time with S(v), with the experiment that tells them apart
        drift = next(c for c in d.candidates if c["name"] == "time_drift")
        assert drift["gain_where"] is not None and drift["gain_where"] >= Settings().min_gain, drift
        assert "a slow change in time and the shape of S(v) are confounded" in d.text()
        assert "visit the speed levels in a shuffled order" in d.text()
    _assert_subsumed_pairs_are_said(d)


@pytest.mark.parametrize("kind, seed, effect", [("linear_stage", 1021, "position_ripple"), ("tribometer", 1002, "time_drift")])
def test_the_same_machine_at_another_scale_gets_the_same_diagnosis(kind, seed, effect):
    # the user's path (`fit`, then `diagnose` with what it wrote) on a recording and on the same
    # recording written as another machine: a thousand times the travel, a thousandth of the
    # force, ten times slower (the header's units kept: no conversion the reader undoes). The
    # same effect is named, with its parameters in that machine's scale, and each gap is the
    # same in its force unit. Written a thousand times larger in travel and force, the linear
    # stage once named a drift beside its ripple: the free steady curve's ridge, a 10⁻⁹ of the
    # largest square of its columns, followed the acceleration's units onto the hats, and the
    # alternative every effect must beat ended a quarter worse.
    from leuven_friction.identify.fit import fit_recordings
    from synth.hidden import SUITE_RATE

    df, _, _ = make_case(kind, seed, (effect,), rate=SUITE_RATE[kind])
    kx, kf, kt = 1e3, 1e-3, 10.0
    other = df.copy()
    for c in other.columns:
        name = c.lower()
        other[c] = other[c] * (kt if name.startswith("time") else kx if name.startswith(("position", "angle")) else
                               kf if name.startswith(("torque", "force", "friction", "applied")) else 1.0)
    a, b = (diagnose(r, fit_recordings([r]).params) for r in (to_recording(df, "a.csv"), to_recording(other, "b.csv")))
    assert a.effects == b.effects == [effect], (a.text(), b.text())
    for sa, sb in zip(a.steps, b.steps, strict=True):
        assert sb["rms"] / kf == pytest.approx(sa["rms"], rel=0.03), (a.text(), b.text())
    pa, pb = (next(e["params"] for e in d.params_after.effects if e["name"] == effect) for d in (a, b))
    if effect == "position_ripple":
        assert pb["wavelength"] / kx == pytest.approx(pa["wavelength"], rel=1e-3)
        assert pb["a"] == pytest.approx(pa["a"], rel=0.01)
    else:
        assert pb["tau"] / kt == pytest.approx(pa["tau"], rel=0.05) and pb["b"] == pytest.approx(pa["b"], rel=0.02)


@pytest.mark.parametrize("how", ["added", "scaled", "none"])
def test_a_force_along_the_travel_is_told_from_a_friction_ripple_by_its_sign(how):
    # a tribometer's logged friction with 7.3 periods over its 0.5 mm stroke, 3 % of its
    # friction: added to the force (a cogging: it keeps its sign whichever way the pin moves) or
    # scaling the friction (a ripple: its sign follows the motion's, as friction's does). Only
    # the first is a force along the travel, and it is said with its period and size
    df, truth, case = make_case("tribometer", 4243, ())
    x = df["Position [mm]"].to_numpy()
    lam, amp = 0.5 / 7.3, 0.03 * 2.0e6  # mm, µN (the contact's friction is about 2 N)
    wave = np.sin(2 * np.pi * x / lam + 0.4)
    f = df["Friction [uN]"].to_numpy()
    df["Friction [uN]"] = f + amp * wave if how == "added" else f * (1 + 0.03 * wave) if how == "scaled" else f
    rec = to_recording(df, f"{how}.csv")
    before = np.array(rec.friction, copy=True)
    rec.friction.setflags(write=False)  # as a column read from a file is
    d = diagnose(rec, oracle_params(truth))
    # taken out of the friction compared, the force is not taken out of the recording's column
    np.testing.assert_array_equal(rec.friction, before)
    tf = d.travel_force
    if how == "added":
        assert tf is not None and "position_ripple" not in d.effects, (d.effects, d.text())
        assert abs(tf.wavelength - lam * 1e-3) < 0.005 * lam * 1e-3, tf  # written in m
        assert abs(tf.amplitude - amp * 1e-6) < 3 * tf.sd + 0.05 * amp * 1e-6, tf  # in N
        assert "Seen, not a friction effect: a force along the travel" in d.text()
        # the evidence to look at: the residual folded over the period lies on itself moving up and
        # moving down, and the report's figures show it
        up, down = (np.array([np.nan if m is None else m for m in p]) for p in (tf.up, tf.down))
        ok = np.isfinite(up) & np.isfinite(down)
        assert np.corrcoef(up[ok], down[ok])[0, 1] > 0.8, (tf.up, tf.down)
        from leuven_friction.app import plots

        titles = [f.layout.title.text for f in plots.diagnosis_report_figures(d)]
        assert any(t.startswith("A force along the travel") for t in titles), titles
    else:
        assert tf is None, tf
        assert d.effects == (["position_ripple"] if how == "scaled" else []), d.effects
