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
def test_a_logged_temperature_that_turns_back_is_said_with_its_course_and_no_other_effect_named(tmp_path, base):
    # the friction rises 20 % over the first half and falls back towards +5 %, a temperature
    # column following it: no candidate reads a temperature, so the report says it was logged and
    # how it went over the span compared — the simulator's own column, read here apart from the tool
    data, rep = _diagnose(tmp_path, "warm_then_cool", base)
    said = [n for n in rep["notes"] if n.startswith("a temperature is logged (temperature [°C])")]
    assert said and "No candidate reads a temperature" in said[0], rep["notes"]
    rows = np.loadtxt(data, delimiter=",", skiprows=1)
    course = said[0].split("over the span compared it ")[1]
    start, end = (float(course.split(w)[1].split()[0]) for w in (" from ", " to "))
    t_end = rows[-1, 0]
    # the span compared ends with the log: its last temperature, and its first within the range the log spans
    assert abs(end - rows[rows[:, 0] > t_end - 1.0, 3].mean()) < 0.3, (course, rows[-1])
    assert rows[:, 3].min() - 0.5 < start < rows[:, 3].max() + 0.5, course
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
