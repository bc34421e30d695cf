"""Parameter files and the command line: round trips, and one-line errors for bad input.

The command line runs in-process through ``main(argv)`` (what the installed script calls)."""

import numpy as np
import pandas as pd
import pytest
import yaml

from leuven_friction.app.cli import main
from leuven_friction.identify.paramfile import load_params, save_params
from leuven_friction.model import FrictionParams, ParameterError, default_params, simulate_displacement, simulate_force


def cli(capsys, *args):
    """Run the command line in-process: (exit status, stdout, stderr)."""
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def test_yaml_round_trip_preserves_model(tmp_path, kuka):
    path = tmp_path / "p.yaml"
    save_params(kuka, path)
    back = load_params(path)
    assert back == kuka
    assert back.to_dict() == kuka.to_dict()
    t = np.arange(0, 2, 1e-4)
    np.testing.assert_array_equal(simulate_force(back, t, 20 * t).position, simulate_force(kuka, t, 20 * t).position)


BAD = [
    ({"transition_curve": {"kind": "piecewise_linear", "z": [0, 1e-5, 5e-6], "F": [0, 10, 20]}}, "transition_curve.z.2"),
    ({"transition_curve": {"kind": "piecewise_linear", "z": [0, 1e-5, 2e-5], "F": [0, 10, 9]}}, "transition_curve.F.2"),
    ({"n": 0}, "n: must be >= 1"),
    ({"n": -2}, "n: must be >= 1"),
    ({"n": 0.63}, "n: must be >= 1"),  # (simulates to NaN: eq. (5)'s step at a reversal)
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
def test_cli_bad_parameter_file_is_one_line_no_traceback(tmp_path, capsys, change, field):
    d = default_params().to_dict()
    d.update(change)
    pfile = tmp_path / "bad.yaml"
    pfile.write_text(yaml.safe_dump(d))
    out = tmp_path / "out.csv"
    rc, _, err = cli(capsys, "simulate", "--experiment", "abcd_ramp", "--params", pfile, "--out", out)
    assert rc == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and field in lines[0] and str(pfile) in lines[0]
    assert not out.exists()


def test_cli_list_and_experiment_csv(tmp_path, capsys):
    rc, stdout, _ = cli(capsys, "simulate", "--list")
    assert rc == 0
    for name in ("abcd_ramp", "stick_slip", "tracking", "frictional_lag", "breakaway"):
        assert name in stdout
    out = tmp_path / "abcd.csv"
    rc, stdout, err = cli(capsys, "simulate", "--experiment", "abcd_ramp", "--model", "lugre", "--out", out)
    assert rc == 0, err
    # the columns keep their bare names; their units (the built-in set's, the paper's joint) are said
    assert "time s, position and z rad, velocity rad/s, forces N*m" in stdout, stdout
    df = pd.read_csv(out)
    assert list(df.columns) == ["time", "position", "velocity", "applied_force", "friction_force", "hysteresis_force", "z"]
    assert df["applied_force"].max() == pytest.approx(30.0, abs=1e-3)


def _steady_friction(side, v):
    """Eq. (6) with eq. (7), Table I, written out here: S(v) + σ2·v at constant velocity."""
    Fs, Fc, vs, delta, sigma2 = {"positive": (36.0, 27.0, 0.007, 0.5, 7.7),
                                 "negative": (-63.0, -52.0, -0.004, 0.9, 8.0)}[side]
    return Fc + (Fs - Fc) * np.exp(-abs(v / vs) ** delta) + sigma2 * v


def test_cli_simulate_input_uses_recorded_position(tmp_path, capsys):
    # a recorded motion at +v then -v, written in mrad: the prediction must convert it to rad
    # and settle at the paper's steady sliding friction in each direction
    v, dt = 0.02, 1e-3
    t = np.arange(0, 3, dt)
    x = np.where(t < 1.5, v * t, v * 1.5 - v * (t - 1.5))
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"Time (s)": t, "Angle [mrad]": x * 1e3}).to_csv(rec, index=False)
    out = tmp_path / "pred.csv"
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--out", out)
    assert rc == 0, err
    pred = pd.read_csv(out)
    np.testing.assert_allclose(pred["position"], x, atol=1e-12)  # mrad converted to rad
    F = pred["friction_force"].to_numpy()
    i_up = np.searchsorted(t, 1.45)  # 1.45 s of sliding at +v, far past the approach (~0.01 s)
    assert F[i_up] == pytest.approx(_steady_friction("positive", v), abs=1e-3)
    assert F[-1] == pytest.approx(_steady_friction("negative", -v), abs=1e-3)


def test_cli_simulate_says_an_inertia_the_fit_held_and_what_depends_on_it(tmp_path, capsys, kuka):
    # a fit of measured friction keeps the built-in inertia (provenance.held): simulated along a
    # motion, the applied force is friction + I·ẍ (eq. (8)) from that held I, the friction not
    t = np.arange(0, 2, 1e-3)
    x = 0.05 * np.sin(2 * np.pi * t)
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"time": t, "position": x}).to_csv(rec, index=False)
    runs = {}
    for inertia, held in ((5.0, True), (0.5, False)):
        prov = {"held": {"inertia": "not needed: kept from the built-in default"}} if held else {}
        pfile = tmp_path / f"p{inertia}.yaml"
        save_params(kuka.replace(inertia=inertia, provenance=prov), pfile)
        out = tmp_path / f"o{inertia}.csv"
        rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--params", pfile, "--out", out)
        assert rc == 0, err
        assert (f"inertia {inertia:g} was held by the fit, not estimated" in err) == held, err
        runs[inertia] = pd.read_csv(out)
    a, b = runs[5.0], runs[0.5]
    np.testing.assert_allclose(a["friction_force"], b["friction_force"])
    acc = -0.05 * (2 * np.pi) ** 2 * np.sin(2 * np.pi * t)
    inner = slice(10, -10)  # the ends' finite differences
    # ΔI·ẍ, of amplitude 8.9 N·m; ẍ by finite differences, one sample (0.056 N·m of ΔI·jerk·dt) off
    np.testing.assert_allclose((a["applied_force"] - b["applied_force"])[inner], 4.5 * acc[inner], atol=0.1)


def test_cli_simulate_says_a_built_in_inertia_the_file_left_out(tmp_path, capsys, kuka):
    # a file in the paper's units may leave the inertia out: it is then the built-in 5, another
    # machine's, and a simulation driven by force says so; the same file with `inertia: 5` does not
    t = np.arange(0, 1, 1e-3)
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"time": t, "force": 20.0 * np.sin(2 * np.pi * t)}).to_csv(rec, index=False)
    d = kuka.to_dict()
    for name, text in (("given", yaml.safe_dump(d)), ("left", yaml.safe_dump({k: v for k, v in d.items() if k != "inertia"}))):
        (tmp_path / f"{name}.yaml").write_text(text)
        rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "force", "--params", tmp_path / f"{name}.yaml",
                         "--out", tmp_path / f"{name}.csv")
        assert rc == 0, err
        assert ("no inertia in the file: the built-in default 5 is used, not this machine's" in err) == (name == "left"), err
    np.testing.assert_array_equal(pd.read_csv(tmp_path / "given.csv")["position"], pd.read_csv(tmp_path / "left.csv")["position"])


def test_cli_simulate_says_when_it_drives_along_encoder_steps(tmp_path, capsys, kuka):
    # along a position logged in encoder steps the velocity jumps between 0 and a step per sample,
    # and σ1·dz/dt with it, and a step coarse for the presliding range makes F_d jump: said where
    # either is a tenth (of F_s, of the range) or more (the paper's 1.6e-5 rad encoder at 500 Hz:
    # σ1 × a step per sample 1500 × 8e-3 = 12 N·m, 0.19 × 63), with the option that smooths the
    # path; not for a finer encoder (2e-7 rad: 0.15 N·m), nor with it
    t = np.arange(0, 4, 2e-3)
    x = 0.02 * np.sin(2 * np.pi * t / 4)
    said, friction = {}, {}
    for step in (1.6e-5, 2e-7):
        rec = tmp_path / f"steps{step:g}.csv"
        pd.DataFrame({"time": t, "position": np.round(x / step) * step}).to_csv(rec, index=False)
        for extra in ((), ("--smooth-path",)):
            out = tmp_path / f"o{step:g}{len(extra)}.csv"
            rc, stdout, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", *extra, "--out", out)
            assert rc == 0, err
            said[(step, bool(extra))] = "(an encoder's)" in stdout
            friction[(step, bool(extra))] = pd.read_csv(out)["friction_force"].to_numpy()
            if step == 1.6e-5 and not extra:
                assert "steps of 1.6e-05 rad" in stdout and "by up to 12 N*m (0.19 × F_s)" in stdout, stdout
    assert said == {(1.6e-5, False): True, (1.6e-5, True): False, (2e-7, False): False, (2e-7, True): False}
    # what it says is there: along the coarse steps the friction departs from the one along the
    # motion itself, unquantised, by a fifth of F_s (63 N·m) and more (18 N·m), along the finer
    # encoder's by under a tenth (3.5 N·m, at a reversal)
    exact = simulate_displacement(kuka, t, x).friction_force
    fs = -kuka.stribeck.negative.Fs
    assert np.max(np.abs(friction[1.6e-5, False] - exact)) > 0.2 * fs
    assert np.max(np.abs(friction[2e-7, False] - exact)) < 0.1 * fs


def test_cli_simulate_reads_only_the_columns_its_drive_uses(tmp_path, capsys):
    # a logged friction with a gap does not stop a simulation driven by the position; a dropout
    # in the position leaves its row out, said; a position that is mostly gaps stops it, in one
    # line naming the column and the row
    t = np.arange(0, 1, 1e-3)
    friction = np.ones(len(t))
    friction[100] = np.nan
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"time [s]": t, "position [rad]": 0.02 * t, "friction [N*m]": friction}).to_csv(rec, index=False)
    out = tmp_path / "pred.csv"
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--out", out)
    assert rc == 0, err
    assert len(pd.read_csv(out)) == len(t)
    position = 0.02 * t
    position[7] = np.nan
    pd.DataFrame({"time [s]": t, "position [rad]": position}).to_csv(rec, index=False)
    out.unlink()
    rc, said, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--out", out)
    assert rc == 0, err
    assert len(pd.read_csv(out)) == len(t) - 1 and "('position [rad]' in 1, the first at row 9)" in said + err
    position[::10] = np.nan
    pd.DataFrame({"time [s]": t, "position [rad]": position}).to_csv(rec, index=False)
    out.unlink()
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--out", out)
    assert rc != 0 and "'position [rad]' row 2" in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


def test_cli_simulate_smooth_path_takes_encoder_steps_for_measurement(tmp_path, capsys):
    # the same motion logged by an encoder of 5 µrad steps: along the logged steps the model's
    # presliding state jumps at every step (the velocity is zero, then one step per sample);
    # along the smoothed path it stays near the steady friction of the exact motion
    v, dt, q = 0.0013, 1e-3, 5e-6
    t = np.arange(0, 3, dt)
    x = np.where(t < 1.5, v * t, v * 1.5 - v * (t - 1.5))
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"time": t, "position": np.round(x / q) * q}).to_csv(rec, index=False)
    exact = _steady_friction("positive", v)
    i = (t > 0.5) & (t < 1.45)
    sd = {}
    for flag in ([], ["--smooth-path"]):
        out = tmp_path / f"pred{len(flag)}.csv"
        rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", *flag, "--out", out)
        assert rc == 0, err
        sd[bool(flag)] = float(np.sqrt(np.mean((pd.read_csv(out)["friction_force"].to_numpy()[i] - exact) ** 2)))
    assert sd[True] < 0.02 * exact and sd[True] < 0.35 * sd[False], sd
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "force", "--smooth-path", "--out", tmp_path / "f.csv")
    assert rc == 2 and "--smooth-path" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "f.csv").exists()


def test_cli_missing_column_is_one_line(tmp_path, capsys):
    rec = tmp_path / "rec.csv"
    pd.DataFrame({"t": np.arange(20.0), "temperature": np.ones(20)}).to_csv(rec, index=False)
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--out", tmp_path / "o.csv")
    assert rc == 2
    assert "no column for position" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "o.csv").exists()


def test_cli_warns_when_the_parameters_are_of_another_kind_of_machine(tmp_path, capsys):
    # the paper's joint (rad, N·m) simulated along a linear stage's logged motion (mm): it runs,
    # and says so on one line naming both files
    t = np.arange(0, 1, 1e-3)
    rec = tmp_path / "stage.csv"
    pd.DataFrame({"time [s]": t, "position [mm]": 2.0 * np.sin(3 * t)}).to_csv(rec, index=False)
    par = tmp_path / "joint.yaml"
    save_params(default_params(), par)
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "displacement", "--params", par,
                     "--out", tmp_path / "o.csv")
    assert rc == 0, err
    line = [ln for ln in err.splitlines() if ln.startswith("warning:") and "another kind of machine" in ln]
    assert len(line) == 1 and "joint.yaml" in line[0] and "stage.csv" in line[0] and "rad" in line[0]


def test_cli_warns_when_the_parameters_are_of_a_machine_of_another_size(tmp_path, capsys):
    # the paper's joint (static friction 63 N·m) along a pitch bearing's log of 40 kN·m, both in
    # rad and N·m, the plant driven by the logged torque: it runs, and says the set's friction is
    # of another machine
    t = np.arange(0, 1, 1e-3)
    rec = tmp_path / "pitch.csv"
    pd.DataFrame({"t [s]": t, "pitch angle [rad]": 0.01 * np.sin(3 * t),
                  "drive torque [N*m]": 4e4 * np.cos(3 * t)}).to_csv(rec, index=False)
    par = tmp_path / "joint.yaml"
    save_params(default_params(), par)
    rc, _, err = cli(capsys, "simulate", "--input", rec, "--drive", "force", "--params", par,
                     "--out", tmp_path / "o.csv")
    assert rc == 0, err
    line = [ln for ln in err.splitlines() if ln.startswith("warning: ") and "another machine's" in ln]
    assert len(line) == 1 and "joint.yaml" in line[0] and "static friction 63" in line[0], err


def test_cli_fit_names_a_missing_position_column_before_any_work(tmp_path, capsys):
    t = np.arange(0, 1, 1e-3)
    rec = tmp_path / "f.csv"
    pd.DataFrame({"time [s]": t, "positon [mm]": t, "force [N]": np.cos(t)}).to_csv(rec, index=False)
    rc, out, err = cli(capsys, "fit", rec, "--out", tmp_path / "f.yaml")
    assert rc != 0 and not (tmp_path / "f.yaml").exists()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert "f.csv" in lines[0] and "position" in lines[0] and "--columns position=" in lines[0]


def test_diagnose_says_the_effects_it_writes_without_naming_them():
    from leuven_friction.app.cli import held_effects_said

    written = [{"name": "presliding_range", "params": {"e": -0.42180995950209077}},
               {"name": "time_drift", "params": {"t0": 3730.028, "b": -0.2578, "tau": 28.37}}]
    said = held_effects_said(written, ["time_drift"])
    assert said == "; also written, held beside them and not named: presliding_range (e = -0.422)"
    assert held_effects_said(written[1:], ["time_drift"]) == ""


def test_a_simulation_that_reads_no_force_says_so_beside_the_default_parameters(tmp_path, capsys):
    # a position-only recording in mm simulated with the paper's joint (rad, N·m): the warning
    # names the recording's units as read, and says no force was read, not a "?"
    rec = tmp_path / "pos.csv"
    t = np.arange(2000) * 1e-3
    pd.DataFrame({"time [s]": t, "position [mm]": np.sin(t)}).to_csv(rec, index=False)
    rc, out, err = cli(capsys, "simulate", "--input", rec, "--out", tmp_path / "s.csv")
    assert rc == 0
    assert "its parameters are in rad and N*m, the recording in m (no force read)" in err
    assert "?" not in err
    # the memory the model starts with is said, where the model has one; a static model has none
    assert "starts at the first row with an empty memory (F_h = 0" in out and "until the first gross sliding" in out
    rc, out, err = cli(capsys, "simulate", "--input", rec, "--model", "static", "--out", tmp_path / "s.csv")
    assert rc == 0 and "history before the log" not in out
