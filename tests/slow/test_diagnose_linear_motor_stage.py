"""`fit` then `diagnose` on a linear-motor stage simulated apart from the project
(``synth/linear_motor_stage.py``: an 11.3 kg carriage, a LuGre contact with an asymmetric
exponential Stribeck curve and viscous friction, semi-implicit Euler at 20 kHz, a PID at 5 kHz
with feedforward, a 0.1 µm scale and the motor force with noise and a wandering offset logged at
1 kHz; 147,060 samples, friction not logged). Motor cogging is a force along the travel, not
friction: it must be said as such and not named a friction effect, where a friction ripple is
named a ripple. Every expectation is the simulator's own constant, not a number the tool printed."""

import json
import math

import numpy as np
import pytest

from leuven_friction.app.cli import main
from synth import linear_motor_stage as S


def _run(tmp_path, seed, **effects):
    csv = tmp_path / "stage.csv"
    t, x, f = S.simulate(seed, **effects)
    np.savetxt(csv, np.column_stack([t, x * 1e3, f]), delimiter=",", header="time [s],pos [mm],motor_force [N]",
               comments="", fmt=("%.4f", "%.4f", "%.4f"))
    base, out = tmp_path / "stage.yaml", tmp_path / "stage.json"
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out)]) == 0
    return json.loads(out.read_text())


@pytest.mark.slow
def test_cogging_is_said_as_a_force_along_the_travel_and_not_named_friction(tmp_path):
    rep = _run(tmp_path, 202, cog=True)
    assert rep["effects"] == [], rep["effects"]
    tf = rep["travel_force"]
    assert tf is not None, rep["notes"]
    # the magnet pitch, written in m (the file's mm converted), and the fundamental's size
    assert abs(tf["wavelength"] - S.COG_P) < 0.005 * S.COG_P, tf
    assert abs(tf["amplitude"] - S.COG_C1) < 3 * tf["sd"] + 0.1 * S.COG_C1, tf


@pytest.mark.slow
def test_a_friction_ripple_is_named_and_not_said_a_force_along_the_travel(tmp_path):
    rep = _run(tmp_path, 303, ripple=True)
    assert rep["effects"] == ["position_ripple"], rep["effects"]
    assert rep["travel_force"] is None, rep["travel_force"]
    p = rep["effect_params"]
    assert abs(p["wavelength"] - S.RIP_P) < 0.01 * S.RIP_P, p
    assert abs(p["a"] - S.RIP_A) < 0.2 * S.RIP_A, p
    # the phase is written at x0 (the middle of the travel): the simulator's, carried there
    assert abs(math.remainder(p["phase"] - (S.RIP_PHI + 2 * math.pi * p["x0"] / S.RIP_P), 2 * math.pi)) < 0.5, p
