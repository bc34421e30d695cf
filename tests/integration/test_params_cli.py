"""Parameter files and the command line: round trips, and one-line errors for bad input."""

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest
import yaml

from leuven_friction.identify.paramfile import load_params, save_params
from leuven_friction.model import FrictionParams, ParameterError, default_params, simulate_force


def cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "leuven_friction.app.cli", *args], capture_output=True, text=True, cwd=cwd)


def test_yaml_round_trip_preserves_model(tmp_path, kuka):
    path = tmp_path / "p.yaml"
    save_params(kuka, path)
    back = load_params(path)
    assert back.to_dict() == kuka.to_dict()
    t = np.arange(0, 2, 1e-4)
    np.testing.assert_array_equal(simulate_force(back, t, 20 * t).position, simulate_force(kuka, t, 20 * t).position)


BAD = [
    ({"transition_curve": {"kind": "piecewise_linear", "z": [0, 1e-5, 5e-6], "F": [0, 10, 20]}}, "transition_curve.z.2"),
    ({"transition_curve": {"kind": "piecewise_linear", "z": [0, 1e-5, 2e-5], "F": [0, 10, 9]}}, "transition_curve.F.2"),
    ({"n": 0}, "n: must be > 0"),
    ({"n": -2}, "n: must be > 0"),
    ({"stribeck": {"positive": {"Fs": 36, "Fc": 27, "vs": 0.007, "delta": 0.5, "sigma2": 7.7},
                   "negative": {"Fs": 63, "Fc": -52, "vs": -0.004, "delta": 0.9, "sigma2": 8}}}, "stribeck.negative.Fs"),
    ({"sigma1": float("nan")}, "sigma1: must be finite"),
    ({"inertia": "heavy"}, "inertia: expected a number"),
    ({"effects": [{"name": "gremlins", "params": {}}]}, "effects.0.name"),
    ({"transition_curve": {"kind": "cubic", "z": [0, 1]}}, "transition_curve.kind"),
]


@pytest.mark.parametrize("change,field", BAD)
def test_bad_parameters_name_the_field(change, field):
    d = default_params().to_dict()
    d.update(change)
    with pytest.raises(ParameterError, match=field.replace(".", r"\.")):
        FrictionParams.from_dict(d)


@pytest.mark.parametrize("change,field", BAD[:5])
def test_cli_bad_parameter_file_is_one_line_no_traceback(tmp_path, change, field):
    d = default_params().to_dict()
    d.update(change)
    pfile = tmp_path / "bad.yaml"
    pfile.write_text(yaml.safe_dump(d))
    out = tmp_path / "out.csv"
    r = cli("simulate", "--experiment", "abcd_ramp", "--params", str(pfile), "--out", str(out))
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and "Traceback" not in r.stderr
    assert not out.exists()


def test_cli_list_and_experiment_csv(tmp_path):
    r = cli("simulate", "--list")
    assert r.returncode == 0
    for name in ("abcd_ramp", "stick_slip", "tracking", "frictional_lag", "breakaway"):
        assert name in r.stdout
    out = tmp_path / "abcd.csv"
    r = cli("simulate", "--experiment", "abcd_ramp", "--model", "lugre", "--out", str(out))
    assert r.returncode == 0, r.stderr
    df = pd.read_csv(out)
    assert list(df.columns) == ["time", "position", "velocity", "applied_force", "friction_force", "hysteresis_force", "z"]
    assert df["applied_force"].max() == pytest.approx(30.0, abs=1e-3)


def test_cli_simulate_input_uses_recorded_position(tmp_path, kuka):
    t = np.arange(0, 3, 1e-3)
    x = 1e-4 * np.sin(2 * np.pi * t)
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"Time (s)": t, "Angle [mrad]": x * 1e3}).to_csv(rec, index=False)
    out = tmp_path / "pred.csv"
    r = cli("simulate", "--input", str(rec), "--drive", "displacement", "--out", str(out))
    assert r.returncode == 0, r.stderr
    pred = pd.read_csv(out)
    np.testing.assert_allclose(pred["position"], x, atol=1e-12)  # mrad converted to rad
    from leuven_friction.model import simulate_displacement

    np.testing.assert_allclose(pred["friction_force"], simulate_displacement(kuka, t, x).friction_force, rtol=1e-8, atol=1e-8)


def test_cli_missing_column_is_one_line(tmp_path):
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"t": np.arange(20.0), "temperature": np.ones(20)}).to_csv(rec, index=False)
    r = cli("simulate", "--input", str(rec), "--out", str(tmp_path / "o.csv"))
    assert r.returncode == 2
    assert "no column for position" in r.stderr and len(r.stderr.strip().splitlines()) == 1
