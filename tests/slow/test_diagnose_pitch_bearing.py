"""`fit` then `diagnose` on a wind turbine's pitch bearing simulated apart from the project
(``synth/pitch_bearing.py``: 8000 kg·m², friction of tens of kN·m from a four-element
Maxwell-slip contact under a rational Stribeck limit, a 0.005° encoder, the drive torque in
kN·m, and the blade's bending moment in kN·m as the bearing's load). Every expectation is the
simulator's own constant, not a number the tool printed."""

import json
import math

import pytest

from leuven_friction.app.cli import main
from synth import pitch_bearing as S
from tests.cli_runs import written


def _run(tmp_path, effect, seed):
    csv, base, out = tmp_path / "pitch.csv", tmp_path / "pitch.yaml", tmp_path / "pitch.json"
    truth = S.simulate(effect, seed, str(csv))
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out)]) == 0
    return truth, json.loads(out.read_text())


@pytest.mark.slow
def test_the_control_names_nothing(tmp_path):
    _, rep = _run(tmp_path, "none", 48271)
    assert rep["effects"] == [], rep["effects"]


@pytest.mark.slow
def test_the_blades_bending_moment_is_read_as_the_load_and_named(tmp_path):
    # the log as the pitch system writes it: 'bending moment [kN*m]' beside 'drive torque
    # [kN*m]', no --columns; friction ∝ (M/4000 kN·m)^0.5
    truth, rep = _run(tmp_path, "load", 69621)
    assert rep["units"]["normal_load"] == "N*m"
    assert "normal_load" in rep["effects"], rep["effects"]
    load = written(rep, "normal_load")
    # (the base `fit` writes averages S(v) over the loads, and α reads low beside it: 0.41 ± 0.03)
    assert abs(load["params"]["alpha"] - truth["load_alpha"]) < 3 * load["sd"]["alpha"] + 0.03, load
    assert 2.0e6 < load["params"]["N0"] < 6.0e6, load  # a reference within the moments logged, in N·m


@pytest.mark.slow
def test_a_load_and_a_warm_up_are_both_named_with_the_simulators_values(tmp_path):
    truth, rep = _run(tmp_path, "load+warmup", 39373)
    assert set(rep["effects"]) == {"normal_load", "time_drift"}, rep["effects"]
    load, drift = written(rep, "normal_load"), written(rep, "time_drift")
    assert abs(load["params"]["alpha"] - truth["load_alpha"]) < 3 * load["sd"]["alpha"], load
    # the simulator's factor 1 − 0.3·(1 − e^(−t/τ)) relative to its value at the drift's t0 is
    # 1 + b'·(1 − e^(−(t−t0)/τ)) with b' = −0.3·e^(−t0/τ) / (1 − 0.3·(1 − e^(−t0/τ)))
    t0, tau = drift["params"]["t0"], truth["warm_tau"]
    left = math.exp(-t0 / tau)
    b_true = truth["warm_b"] * left / (1.0 + truth["warm_b"] * (1.0 - left))
    assert abs(drift["params"]["b"] - b_true) < 3 * drift["sd"]["b"], (drift, b_true)


@pytest.mark.slow
def test_the_pinions_ripple_is_named_with_its_wavelength_and_size(tmp_path):
    truth, rep = _run(tmp_path, "ripple", 22695)
    assert rep["effects"] == ["position_ripple"], rep["effects"]
    rip = written(rep, "position_ripple")
    assert abs(rip["params"]["wavelength"] - truth["ripple_lambda"]) < 3 * rip["sd"]["wavelength"], rip
    assert abs(rip["params"]["a"] - truth["ripple_a"]) < 3 * rip["sd"]["a"], rip
