"""`fit` then `diagnose` on a rotary table simulated apart from the project
(``synth/rotary_table.py``: four Maxwell-slip elements with damped stuck elements under an
asymmetric Stribeck limit, semi-implicit Euler at 10 kHz, a PID loop at 5 kHz, logged at 1 kHz
from a 2²⁰-count encoder in degrees, the motor torque in mN·m with white and AR(1) noise; torque
ramps for 31 s, then nine speeds in shuffled order). Its first gross sliding comes at 31 s of
92, and the diagnosis compares from there: a warm-up drift whose law started at the log's
first sample read b = 3.1 for 0.21 there, with S(v) divided by four in the model written, which
then ran 5 rad along the ramps where the table moved 0.9 mrad."""

import json
import re

import numpy as np
import pandas as pd
import pytest

from leuven_friction.app.cli import main
from synth import rotary_table as R


def _run(tmp_path, case):
    path = str(tmp_path / f"{case}.csv")
    R.simulate(out=path, **R.CASES[case])
    out, written = tmp_path / f"{case}.json", tmp_path / f"{case}.yaml"
    assert main(["diagnose", path, "--json", str(out), "--out", str(written)]) == 0
    return path, json.loads(out.read_text()), written


@pytest.mark.slow
def test_a_drift_compared_from_a_late_first_sliding_is_read_from_there(tmp_path):
    path, rep, written = _run(tmp_path, "drift")
    assert rep["effects"] == ["time_drift"], rep["effects"]
    p = rep["steps"][2]["params"]
    b_true, tau_true = R.CASES["drift"]["drift"]
    T = float(pd.read_csv(path)["t [ms]"].iloc[-1]) / 1e3
    # the friction's rise from the first sample compared (t0) to the end, as the simulator made it
    law = lambda t: 1.0 + b_true * (1.0 - np.exp(-t / tau_true))  # noqa: E731
    truth = law(T) / law(p["t0"]) - 1.0
    reached = p["b"] * (1.0 - np.exp(-(T - p["t0"]) / p["tau"]))
    assert 0.5 * truth < reached < 2.0 * truth, (p, truth, reached)
    # the model written, driven by the logged torque over the ramps before t0, stays stuck
    # within presliding as the table did (its S(v) is the friction's level at t0, not a quarter)
    rec = pd.read_csv(path)
    ramps = rec[rec["t [ms]"] < 1e3 * p["t0"] - 500.0]
    ramps_csv = tmp_path / "ramps.csv"
    ramps.to_csv(ramps_csv, index=False)
    sim = tmp_path / "sim.csv"
    assert main(["simulate", "--input", str(ramps_csv), "--drive", "force", "--params", str(written),
                 "--out", str(sim)]) == 0
    travel = float(np.ptp(pd.read_csv(sim)["position"]))
    logged = float(np.ptp(np.radians(ramps["angle [deg]"])))
    assert travel < 10 * logged, (travel, logged)


def _averaged_torque_noise(L: int) -> float:
    """The sd of the simulator's torque noise averaged over L samples: white, plus AR(1) whose
    mean over L samples has variance γ0/L·(1 + 2Σ_{k<L}(1 − k/L)ρ^k)."""
    rho = R.TORQUE_AR
    g0 = R.TORQUE_AR_E**2 / (1.0 - rho**2)
    k = np.arange(1, L)
    ar = g0 / L * (1.0 + 2.0 * np.sum((1.0 - k / L) * rho**k))
    return float(np.sqrt(R.TORQUE_WHITE**2 / L + ar))


@pytest.mark.slow
def test_its_control_names_nothing_against_a_noise_floor_that_counts_the_coloured_noise(tmp_path):
    _, rep, _ = _run(tmp_path, "control_a")
    assert rep["effects"] == [], rep["effects"]
    # the torque's AR(1) part survives the average of eq. (8): a floor taken as white noise
    # (sample-to-sample differences over √L) read 3·10⁻⁴ N·m here, a sixth of the truth
    L = int(next(re.search(r"averaged over (\d+) samples", n).group(1) for n in rep["notes"] if "eq. (8) averaged" in n))
    expected = _averaged_torque_noise(L)
    assert 0.8 * expected < rep["noise"] < 1.4 * expected, (rep["noise"], expected, L)
    # its nine speeds are each held once per direction (``synth/rotary_table.py``): with nothing
    # named the report still says that a slow drift would hide level by level in S(v) there, and
    # which experiment tells
    again = [n for n in rep["notes"] if "visited again later in the session" in n]
    assert again and "taken as the shape of S(v)" in again[0] and "visit a speed level again" in again[0], rep["notes"]


@pytest.mark.slow
def test_a_load_beside_a_ripple_is_written_as_the_report_lists_it_within_its_sigma(tmp_path, capsys):
    # both effects named; each step's line has its effect as refitted at that step, and the
    # report lists them as written to the file, refitted together: the file is what it lists,
    # and each value there is within 3 σ of the simulator's (σ: the folds' and the model's move)
    from leuven_friction.identify.paramfile import load_params

    _, rep, written = _run(tmp_path, "load_ripple")
    assert set(rep["effects"]) == {"normal_load", "position_ripple"}, rep["effects"]
    assert "Effects as written to the file" in capsys.readouterr().out
    listed = {e["name"]: e for e in rep["written_effects"]}
    p = load_params(written)
    for i, e in enumerate(p.effects):
        assert e["params"] == pytest.approx(listed[e["name"]]["params"])
        for k, sd in listed[e["name"]]["sd"].items():
            assert p.uncertainty[f"effects.{i}.params.{k}"] == pytest.approx(sd)
    case = R.CASES["load_ripple"]
    a_true, wavelength, _ = case["ripple"]  # (amplitude, wavelength in rad, phase)
    truth = {("normal_load", "alpha"): case["alpha"], ("position_ripple", "a"): a_true,
             ("position_ripple", "wavelength"): wavelength}
    for (name, k), v in truth.items():
        e = listed[name]
        assert abs(e["params"][k] - v) < 3 * e["sd"][k], (name, k, e, v)
    # the simulator's ripple is one sine: the second harmonic is not there, so its phase is
    # not an estimate — no σ in the file, named as not determined, and said so in the report
    i = next(i for i, e in enumerate(p.effects) if e["name"] == "position_ripple")
    assert f"effects.{i}.params.phase2" not in p.uncertainty
    assert "not determined" in p.provenance["held"][f"effects.{i}.params.phase2"]
    assert f"effects.{i}.params.phase" in p.uncertainty  # the fundamental's is
    assert "phase2" in listed["position_ripple"]["params"] and "phase2" not in listed["position_ripple"]["sd"]
    # and the JSON says why beside the values, as the file's provenance.held does
    assert listed["position_ripple"]["held"]["phase2"] == p.provenance["held"][f"effects.{i}.params.phase2"]
