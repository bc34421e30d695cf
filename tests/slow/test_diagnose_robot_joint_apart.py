"""`fit` then `diagnose` on a robot joint simulated apart from the project
(``synth/robot_joint_apart.py``: a five-element Maxwell-slip bank under a stretched-exponential
Stribeck limit with a |v|^1.5 viscous term, symplectic Euler at 10 kHz, a P-position/PI-velocity
cascade at 1 kHz, a 2¹⁷-count encoder logged at 500 Hz, the applied torque with white and AR(1)
noise; 74,000 samples, friction not logged) — the shape of session the diagnosis issue was
reported on, each effect imposed inside the simulation its own way. Every expectation is the
simulator's own constant, not a number the tool printed."""

import json
import math

import numpy as np
import pytest

from leuven_friction.app.cli import main
from synth import robot_joint_apart as R


def _run(tmp_path, effect, seed):
    csv = tmp_path / f"{effect}.csv"
    t, pos, tq, N, *_ = R.simulate(effect, seed)
    R.write_csv(csv, effect, t, pos, tq, N)
    base, out = tmp_path / f"{effect}.yaml", tmp_path / f"{effect}.json"
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out)]) == 0
    rep = json.loads(out.read_text())
    return rep, (rep["steps"][2] if rep["effects"] else None)


@pytest.mark.slow
def test_its_control_names_nothing(tmp_path):
    rep, _ = _run(tmp_path, "none", 11)
    assert rep["effects"] == [] and not rep["confounded"], rep


@pytest.mark.slow
def test_a_ripple_along_the_angle_is_named_with_its_wavelength_and_amplitude(tmp_path):
    rep, step = _run(tmp_path, "ripple", 12)
    assert rep["effects"] == ["position_ripple"], rep["effects"]
    p, sd = step["params"], step["sd"]
    assert abs(p["wavelength"] - R.RIP_LAM) < 3 * sd["wavelength"] + 1e-3 * R.RIP_LAM, (p, sd)
    assert abs(p["a"] - R.RIP_A) < 3 * sd["a"], (p, sd)
    # the phase's σ is the folds' and the model's move; measured 0.67 ± 0.02 for 0.6, so a
    # looser band than 3 σ, on the angle the encoder reads (the simulator's own frame), at x0
    assert abs(math.remainder(p["phase"] - (R.RIP_PHI + 2 * math.pi * p["x0"] / R.RIP_LAM), 2 * math.pi)) < 0.2, p


@pytest.mark.slow
def test_a_load_stepping_up_and_down_is_named_with_its_exponent(tmp_path):
    rep, step = _run(tmp_path, "load", 14)
    assert rep["effects"] == ["normal_load"], rep["effects"]
    p, sd = step["params"], step["sd"]
    assert abs(p["alpha"] - R.LOAD_ALPHA) < 3 * sd["alpha"], (p, sd)


@pytest.mark.slow
def test_a_warm_up_still_under_way_at_the_first_sliding_is_named_and_its_rise_read(tmp_path):
    rep, step = _run(tmp_path, "drift", 13)
    assert rep["effects"] == ["time_drift"], rep["effects"]
    p = step["params"]
    law = lambda t: 1.0 + R.DR_B * (1.0 - np.exp(-t / R.DR_TAU))  # noqa: E731
    # the friction's rise from the first sample compared (t0) to the session's end, as simulated
    truth = law(R.T_END) / law(p["t0"]) - 1.0
    reached = p["b"] * (1.0 - np.exp(-(R.T_END - p["t0"]) / p["tau"]))
    assert 0.7 * truth < reached < 1.5 * truth, (p, truth, reached)
