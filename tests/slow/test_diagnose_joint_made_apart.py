"""`fit` then `diagnose` on a rotary joint simulated apart from the project
(``synth/joint_maxwell_slip_logged.py``: five Maxwell-slip elements driven along the angle a
60 Hz drive reaches, friction torque measured with the reaction sign in N·mm, the angle in
degrees through a 19-bit encoder; 120,000 samples at 1 kHz). Its speed levels are reached
through a 150 °/s² ramp, so a fast stroke's friction climbs the viscous line for tens of
milliradians after presliding is over. Every expectation is the simulator's own constant."""

import json
import math

import numpy as np
import pytest
import yaml

from leuven_friction.app.cli import main
from synth import joint_maxwell_slip_logged as J

DEG = math.pi / 180.0


def _record(tmp_path, seed, effect):
    t, angle, torque, truth, _ = J.simulate(seed, effect)
    csv = tmp_path / "joint.csv"
    J.write(csv, t, angle, torque)
    base = tmp_path / "joint.yaml"
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    out = tmp_path / "joint.json"
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out)]) == 0
    return truth, yaml.safe_load(base.read_text()), json.loads(out.read_text())


def _reach(p, swing):
    """Where F_d, extended past its last knot with its last slope, reaches ``swing``."""
    z, F = np.array(p["transition_curve"]["z"]), np.array(p["transition_curve"]["F"])
    if F[-1] >= swing:
        return float(np.interp(swing, F, z))
    slope = (F[-1] - F[-2]) / (z[-1] - z[-2])
    return math.inf if slope <= 0 else float(z[-1] + (swing - F[-1]) / slope)


@pytest.mark.slow
def test_the_control_fits_a_curve_that_reaches_a_reversal_and_names_nothing(tmp_path):
    truth, p, rep = _record(tmp_path, 11, None)
    st = truth["stribeck"]
    # a reversal from sliding one way to sliding the other swings the torque by F_c⁺ + |F_c⁻| at
    # least, and every element has slipped once the angle has moved twice the largest slip
    # limit (at the breakaway level F_s⁺) from the reversal
    swing = 0.9 * (st["Fc_p"] - st["Fc_n"]) / 1000.0  # N·m
    travel = 2.0 * max(truth["zmax_at_S1000_deg"]) * st["Fs_p"] / 1000.0 * DEG  # rad
    assert _reach(p, swing) < travel, (p["transition_curve"], swing, travel)
    assert rep["effects"] == [], rep["effects"]


@pytest.mark.slow
def test_a_ripple_along_the_angle_is_named_with_the_simulators_wavelength(tmp_path):
    truth, _, rep = _record(tmp_path, 13, "ripple")
    assert rep["effects"] == ["position_ripple"], rep["effects"]
    rip = next(e for e in rep["written_effects"] if e["name"] == "position_ripple")
    # the simulator's friction × (1 + 0.08·sin(2π·θ/12°))
    assert abs(rip["params"]["wavelength"] - 12.0 * DEG) < 3 * rip["sd"]["wavelength"] + 0.01 * 12.0 * DEG, rip
    assert abs(rip["params"]["a"] - 0.08) < 3 * rip["sd"]["a"] + 0.01, rip
