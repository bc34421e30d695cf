"""`fit` then `diagnose` on a reciprocating tribometer's export simulated apart from the project
(``synth/tribometer_export.py``: a Maxwell-slip bank under sine strokes and triangles, a force
sensor whose offset drifts, low-passed and noisy, an LVDT, a jittered clock with dropouts; the
file opens with the instrument's notes above its header, in semicolons, decimal commas and
Windows-1252), as a new user runs them: no option. Every expectation is the simulator's own,
not a number the tool printed."""

import json

import pytest

from synth import tribometer_export as T
from tests.cli_runs import simulated_fit_then_diagnose


def _fit_and_diagnose(tmp_path, name):  # as a user runs them: the default settings
    doc, rep = simulated_fit_then_diagnose(tmp_path, T.simulate_to, name)
    return doc, rep, json.loads((tmp_path / f"{name}_truth.json").read_text())


@pytest.mark.slow
def test_a_tribometer_export_reads_past_its_notes_and_its_steady_curve_is_the_simulators(tmp_path):
    doc, rep, truth = _fit_and_diagnose(tmp_path, "steady")
    st = doc["stribeck"]
    # the sensor's offset adds to both sides alike: half the difference of the two sides is the
    # contact's own (μ·N), their mean the offset, within the range it drifted over. (A trial
    # had lost every triangle leg of 3–20 mm/s, each shorter than the window the velocity is
    # smoothed over, and held F_s at F_c: ``segment.runs_under_window`` takes them)
    for k in ("Fs", "Fc"):
        assert (st["positive"][k] - st["negative"][k]) / 2 == pytest.approx(truth[k], rel=0.01), st
    off = (st["positive"]["Fc"] + st["negative"]["Fc"]) / 2
    assert truth["sensor"]["offset_start"] - 0.005 < off < truth["sensor"]["offset_end"] + 0.005, (off, truth["sensor"])
    for side, sign in (("positive", 1), ("negative", -1)):
        assert st[side]["vs"] == pytest.approx(sign * truth["v_s"], rel=0.03), st[side]
        assert st[side]["delta"] == pytest.approx(truth["delta"], rel=0.1), st[side]
        assert st[side]["sigma2"] == pytest.approx(truth["sigma2"], rel=0.1), st[side]
    # the drifting offset and the sensor's lag are no effect of the contact: nothing named
    assert rep["effects"] == [], (rep["effects"], rep["candidates"])


@pytest.mark.slow
def test_a_tribometer_running_in_has_a_rising_drift_named(tmp_path):
    # the bank's friction rises by 25 % over the session, τ a third of it: a drift in time,
    # friction rising
    doc, rep, truth = _fit_and_diagnose(tmp_path, "runin")
    assert rep["effects"] == ["time_drift"], (rep["effects"], rep["candidates"])
    (drift,) = rep["written_effects"]
    assert drift["params"]["b"] > 0, drift
    steps = rep["steps"]
    assert steps[-1]["rms"] < steps[1]["rms"] < steps[0]["rms"], steps
