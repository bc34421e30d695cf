"""`fit` then `diagnose` on a crossed-roller stage simulated apart from the project
(``synth/crossed_roller_stage.py``: 4.5 kg on a linear motor, four Maxwell-slip elements under a
stretched-exponential Stribeck limit, a 0.05 µm scale, the force with noise and an offset), as a
new user runs them. Every expectation is the simulator's own, not a number the tool printed."""

import json

import numpy as np
import pytest

from leuven_friction.app.cli import main
from synth import crossed_roller_stage as S


def _recording(tmp_path, kind):
    path = tmp_path / f"{kind}.csv"
    S.write_csv(path, S.simulate(*S.KINDS[kind]))
    return path


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("stage")
    out = tmp / "fit.yaml"
    assert main(["fit", str(_recording(tmp, "control")), "--out", str(out)]) == 0
    return out


def _diagnose(tmp_path, kind, base):
    data = _recording(tmp_path, kind)
    rep_path = tmp_path / f"{kind}.json"
    assert main(["diagnose", str(data), "--params", str(base), "--json", str(rep_path),
                 "--out", str(tmp_path / f"{kind}.yaml")]) == 0
    return data, json.loads(rep_path.read_text())


@pytest.mark.slow
def test_a_logged_temperature_is_said_with_its_course_over_the_span_compared(tmp_path, base):
    # the friction rises 20 % over the first half and falls back towards +5 %, a temperature
    # column following it: no candidate reads a temperature, so the report says it was logged and
    # how it went over the span compared. That span starts at the first gross sliding (24.9 s),
    # after the peak's rise had mostly run: from there the temperature goes one way, down — read
    # here in the simulator's own column, apart from the tool
    data, rep = _diagnose(tmp_path, "warm_then_cool", base)
    said = [n for n in rep["notes"] if n.startswith("a temperature is logged (temperature [°C])")]
    assert said and "No candidate reads a temperature" in said[0], rep["notes"]
    course = said[0].split("over the span compared it ")[1]
    assert course.startswith("goes from ") and "turns back" not in said[0], course
    start, end = (float(course.split(w)[1].split()[0]) for w in ("goes from ", " to "))
    rows = np.loadtxt(data, delimiter=",", skiprows=1)
    t, temp = rows[:, 0], rows[:, 3]
    assert abs(end - temp[t > t[-1] - 1.0].mean()) < 0.3, (course, temp[-1])
    # the drift named counts from the first sample compared: there the column reads the start said
    drift = [e for e in rep["written_effects"] if e["name"] == "time_drift"]
    if drift:
        t0 = drift[0]["params"]["t0"]
        assert abs(start - temp[(t >= t0) & (t < t0 + 1.0)].mean()) < 0.5, (course, t0)
    assert start > end + 2.0, course  # it cools over that span
    # a friction that changes in time is the only thing there: nothing else is named
    assert set(rep["effects"]) <= {"time_drift"}, rep["effects"]


@pytest.mark.slow
def test_a_cam_load_is_named_with_its_exponent(tmp_path, base):
    # the normal load swings 300–900 N over a 7 s cam, friction ∝ (N/600)^0.7, logged in N
    _, rep = _diagnose(tmp_path, "cam_load", base)
    assert rep["effects"] == ["normal_load"], (rep["effects"], rep["notes"])
    fit = next(e for e in rep["written_effects"] if e["name"] == "normal_load")
    alpha, sd = fit["params"]["alpha"], fit["sd"]["alpha"]
    assert abs(alpha - S.LOAD["alpha"]) < 3 * sd + 0.05, (alpha, sd)
