"""The bad-input cases of the README's table that this part of the package answers: each is
exit status 2, one line naming the option, file or field, and nothing written. The command line
runs in-process through ``main(argv)``. (The loader and fit cases are in
tests/unit/test_fit_recordings.py.)"""

import os

import numpy as np
import socket

import pytest
import yaml

from leuven_friction.app import cli as cli_module
from leuven_friction.app.cli import main
from leuven_friction.identify.paramfile import load_params
from leuven_friction.model import default_params

SAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "sample_data", "constant_velocity.csv")


def run(capsys, *args):
    rc = main([str(a) for a in args])
    out = capsys.readouterr()
    return rc, out.out, out.err


def one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    return lines[0]


def param_file(tmp_path, change=None, remove=(), text=None):
    path = tmp_path / "p.yaml"
    if text is None:
        d = default_params().to_dict()
        d.update(change or {})
        for k in remove:
            d.pop(k)
        text = yaml.safe_dump(d)
    path.write_text(text)
    return path


# -- output paths: refused before the work, nothing left behind ---------------------------------
@pytest.mark.parametrize("command", [
    ["fit", SAMPLE, "--out", "{nodir}/p.yaml"],
    ["diagnose", SAMPLE, "--json", "{tmp}/ok.json", "--html", "{nodir}/r.html"],
    ["diagnose", SAMPLE, "--out", "{nodir}/p.yaml"],
    ["bench", "--quick", "--json", "{nodir}/b.json"],
    ["simulate", "--experiment", "abcd_ramp", "--out", "{nodir}/x.csv"],
])
def test_output_in_a_missing_directory_is_refused_before_the_work(tmp_path, capsys, command):
    argv = [a.format(tmp=tmp_path, nodir=tmp_path / "nodir") for a in command]
    rc, _, err = run(capsys, *argv)
    assert rc == 2
    assert one_line(err).endswith(f"directory {tmp_path / 'nodir'} does not exist")
    assert os.listdir(tmp_path) == []  # in particular no ok.json beside the refused report


def test_softening_thresholds_below_one_is_refused_before_the_work(tmp_path, capsys):
    rc, _, err = run(capsys, "diagnose", SAMPLE, "--softening-thresholds", "0", "--json", tmp_path / "r.json")
    assert rc == 2 and one_line(err).startswith("error: --softening-thresholds 0: must be at least 1")
    assert os.listdir(tmp_path) == []


def test_a_recording_given_twice_to_fit_is_refused_whatever_it_is_called(tmp_path, capsys):
    # counted twice its samples would halve every variance: the σ written would be √2 too small
    for second in (SAMPLE, os.path.realpath(SAMPLE)):  # the same file spelt otherwise
        rc, _, err = run(capsys, "fit", SAMPLE, second, "-o", tmp_path / "p.yaml")
        assert rc == 2 and "given twice" in one_line(err) and "each recording counts once" in err
    assert os.listdir(tmp_path) == []


def test_a_unit_whose_bracket_is_not_closed_is_refused_not_read_as_si(tmp_path, capsys):
    # 'torque [mN*m' had been read as a header without a unit: SI, a spindle's torque a thousand
    # times too large, said only in a note
    src = open(SAMPLE).read().splitlines()
    assert src[0] == "time,position,torque"
    bad = tmp_path / "unclosed.csv"
    bad.write_text("\n".join(["time [s],position [rad],torque [mN*m"] + src[1:]) + "\n")
    rc, _, err = run(capsys, "fit", bad, "-o", tmp_path / "p.yaml")
    assert rc == 2 and one_line(err) == (f"error: {bad}: column 'torque [mN*m': the bracket around its unit is not "
                                         f"closed: write 'torque [mN*m]' (or give the unit with --units force=<unit>)")
    assert not (tmp_path / "p.yaml").exists()


def test_output_that_is_read_only_or_a_directory(tmp_path, capsys):
    ro = tmp_path / "ro.yaml"
    ro.write_text("keep me")
    ro.chmod(0o444)
    rc, _, err = run(capsys, "fit", SAMPLE, "--out", ro)
    assert rc == 2 and one_line(err) == f"error: --out {ro}: the file is read-only"
    assert ro.read_text() == "keep me"
    rc, _, err = run(capsys, "fit", SAMPLE, "--out", tmp_path)
    assert rc == 2 and "is a directory" in one_line(err)


# -- parameter files ------------------------------------------------------------------------------
def test_huge_integer_in_a_parameter_file(tmp_path, capsys):
    p = param_file(tmp_path, text=yaml.safe_dump(default_params().to_dict()).replace("n: 7.0", "n: " + "9" * 401))
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and one_line(err) == f"error: {p}: n: number too large (401 digits)"
    assert not (tmp_path / "o.csv").exists()


def test_parameter_file_without_stribeck(tmp_path, capsys):
    p = param_file(tmp_path, remove=("stribeck",))
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and one_line(err).startswith(f"error: {p}: stribeck: missing")


@pytest.mark.parametrize("text", ["", "\n\n", "# only a comment\n"])
def test_empty_parameter_file(tmp_path, capsys, text):
    p = param_file(tmp_path, text=text)
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and one_line(err).startswith(f"error: {p}: the file is empty")


def test_ten_thousand_knots_are_refused(tmp_path, capsys):
    knots = {"kind": "piecewise_linear", "z": [i * 1e-6 for i in range(10_000)], "F": [float(i) for i in range(10_000)]}
    p = param_file(tmp_path, change={"transition_curve": knots})
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and one_line(err) == f"error: {p}: transition_curve.z: 10000 knots, at most 64 are accepted"


def test_parameter_file_in_other_units_needs_its_dimensioned_fields(tmp_path, capsys):
    # the paper's σ1 = 1500 N·m·s/rad must not slip silently into a file in m and N
    p = param_file(tmp_path, change={"units": {"position": "m", "force": "N", "time": "s"}}, remove=("sigma1",))
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and "sigma1: missing" in one_line(err)


# -- server start-up ------------------------------------------------------------------------------
@pytest.fixture
def no_server(monkeypatch):
    """Record the call instead of serving forever (the checks under test all run before it)."""
    calls = []
    import leuven_friction.app.server as server

    monkeypatch.setattr(server, "serve", lambda *a, **kw: calls.append(kw))
    return calls


def test_port_out_of_range(capsys, no_server):
    rc, _, err = run(capsys, "serve", "--port", "99999")
    assert rc == 2 and one_line(err) == "error: --port 99999: must be between 0 and 65535 (0 picks a free port)"
    assert no_server == []


def test_host_that_does_not_resolve(capsys, no_server):
    rc, _, err = run(capsys, "serve", "--host", "example.invalid")
    assert rc == 2 and one_line(err).startswith("error: --host example.invalid: ")
    assert no_server == []


def test_taken_port_is_named(capsys, no_server):
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        rc, _, err = run(capsys, "serve", "--port", port)
    assert rc == 2 and one_line(err).startswith(f"error: --port {port}: already in use on 127.0.0.1")
    assert no_server == []


def test_host_reachable_from_the_network_is_warned_about(capsys, no_server):
    rc, _, err = run(capsys, "serve", "--host", "0.0.0.0", "--port", "0")
    assert rc == 0 and no_server and no_server[0]["host"] == "0.0.0.0"
    assert "reachable from the network" in one_line(err) and "without authentication" in err
    rc, _, err = run(capsys, "serve", "--port", "0")
    assert rc == 0 and err == ""


def test_cli_turns_only_user_errors_into_one_line(monkeypatch):
    # a bug stays a bug: anything but a FrictionError propagates with its traceback
    monkeypatch.setattr(cli_module, "cmd_bench", lambda args: 1 / 0)
    with pytest.raises(ZeroDivisionError):
        main(["bench", "--quick"])


def test_fit_writes_the_units_of_the_data(tmp_path, capsys):
    # the shipped constant-velocity sample re-labelled as a linear stage logged in mm and µN:
    # the loader converts to m and N, and the parameter file must say m and N (not rad, N·m)
    import pandas as pd

    df = pd.read_csv(SAMPLE)
    lin = pd.DataFrame({"Time (s)": df["time"], "Position [mm]": df["position"] * 1e3, "Force (uN)": df["torque"] * 1e6})
    lin.to_csv(tmp_path / "stage.csv", index=False)
    rc, _, err = run(capsys, "fit", tmp_path / "stage.csv", "--out", tmp_path / "p.yaml")
    assert rc == 0, err
    p = yaml.safe_load((tmp_path / "p.yaml").read_text())
    assert p["units"] == {"position": "m", "force": "N", "time": "s"}
    assert abs(p["stribeck"]["positive"]["Fc"] - 27.0) < 1.0  # N, the same numbers as the sample's N·m
    # the thresholds it derived are recorded as numbers, not as the report's text: the sample rate
    # is the one of the file's time column
    th = p["provenance"]["thresholds"][str(tmp_path / "stage.csv")]
    assert isinstance(th["rate"], float) and th["rate"] == pytest.approx(1.0 / df["time"].diff().median(), rel=1e-6)
    assert isinstance(th["window"], int) and isinstance(th["velocity_source"], str)


def test_port_zero_picks_a_free_port_and_prints_it(tmp_path):
    # the real server, in a child process: it must listen on the port it prints
    import re
    import subprocess
    import sys
    import threading

    proc = subprocess.Popen([sys.executable, "-m", "leuven_friction.app.cli", "serve", "--port", "0"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, cwd=tmp_path)
    lines = []
    reader = threading.Thread(target=lambda: lines.extend(iter(proc.stdout.readline, "")), daemon=True)
    reader.start()
    try:
        url = None
        for _ in range(600):  # a safety net against a hang, not a speed requirement
            m = next((re.search(r"explorer at http://127\.0\.0\.1:(\d+)", ln) for ln in list(lines)
                      if "explorer at" in ln), None)
            if m or proc.poll() is not None:
                url = m
                break
            reader.join(0.5)
        assert url, "".join(lines)
        port = int(url.group(1))
        assert port != 0
        with socket.create_connection(("127.0.0.1", port), timeout=10):
            pass
    finally:
        proc.terminate()
        proc.wait(timeout=30)


def test_fit_never_reports_plus_minus_zero(tmp_path, capsys):
    # this sample's levels cannot determine several S(v) parameters: they must be held and
    # named as held, never written as estimates with a zero (or huge) uncertainty
    import re

    sample = os.path.join(os.path.dirname(SAMPLE), "effect_position_periodic.csv")
    rc, report, err = run(capsys, "fit", sample, "--out", tmp_path / "p.yaml")
    assert rc == 0, err
    assert not re.search(r"±\s*0(\.0*)?(\s|$)", report), report
    assert "(held)" in report
    p = yaml.safe_load((tmp_path / "p.yaml").read_text())
    assert all(v > 0 for v in p.get("uncertainty", {}).values())
    held = [ln.split(":")[0].strip() for ln in report.split("[[Held parameters")[1].splitlines()[1:] if ":" in ln]
    assert held and not set(held) & set(p.get("uncertainty", {}))


@pytest.mark.parametrize("setting, says", [
    ("window=nan", "must be finite"),
    ("min_run=inf", "must be finite"),
    ("window=4", "odd whole number"),
    ("v_floor=-1", "must be > 0"),
    ("rate=10", "measured from the recording"),
    ("speed=3", "not a threshold"),
])
def test_bad_threshold_settings_are_one_line_and_write_nothing(tmp_path, capsys, setting, says):
    out = tmp_path / "p.yaml"
    rc, _, err = run(capsys, "fit", SAMPLE, "--threshold", setting, "--out", out)
    assert rc == 2 and says in one_line(err) and setting.split("=")[0] in err
    assert not out.exists()


def test_a_threshold_set_by_the_user_is_the_one_used(tmp_path, capsys):
    # the velocity window: a longer Savitzky–Golay window than the derived one must show in the
    # report, and the fit must still find the sample's 22 levels (11 speeds per side)
    out = tmp_path / "p.yaml"
    rc, text, _ = run(capsys, "fit", SAMPLE, "--threshold", "window=41", "--no-refine", "--out", out)
    assert rc == 0
    assert "window          = 41" in text and "window set to 41 by the user" in text
    assert "22 constant-velocity level(s) (11 positive, 11 negative)" in text
    # and the levels still give Table I's Coulomb friction (27 and −52 N·m) within 3σ
    p = load_params(out)
    for side, Fc in (("positive", 27.0), ("negative", -52.0)):
        assert abs(getattr(p.stribeck, side).Fc - Fc) < 3 * p.uncertainty[f"stribeck.{side}.Fc"]


def test_simulate_refuses_a_mat_output_before_the_work(tmp_path, capsys):
    out = tmp_path / "o.mat"
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--out", out)
    assert rc == 2 and "o.mat: MATLAB files are read, not written" in one_line(err)
    assert list(tmp_path.iterdir()) == []  # nothing staged, nothing written


def test_a_misspelt_field_inside_s_of_v_is_named_not_reported_missing(tmp_path, capsys):
    d = default_params().to_dict()
    d["stribeck"]["positive"]["Fss"] = d["stribeck"]["positive"].pop("Fs")
    p = param_file(tmp_path, text=yaml.safe_dump(d))
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 2 and one_line(err) == (f"error: {p}: stribeck.positive.Fss: unknown field "
                                         f"(known: Fs, Fc, vs, delta, sigma2)")
    assert not (tmp_path / "o.csv").exists()


def test_a_valid_but_odd_parameter_file_is_warned_about_on_the_command_line(tmp_path, capsys):
    # |Fc| > |Fs|: friction rising with speed, no Stribeck dip — valid, run, and said on stderr
    d = default_params().to_dict()
    d["stribeck"]["positive"]["Fc"] = 2.0 * d["stribeck"]["positive"]["Fs"]
    p = param_file(tmp_path, text=yaml.safe_dump(d))
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", p, "--out", tmp_path / "o.csv")
    assert rc == 0 and (tmp_path / "o.csv").exists()
    warned = [ln for ln in err.splitlines() if ln.startswith(f"warning: {p}: ")]
    assert len(warned) == 1 and "|Fc⁺| = 72 > |Fs⁺| = 36" in warned[0], err
    # the paper's own parameters draw no warning
    rc, _, err = run(capsys, "simulate", "--experiment", "abcd_ramp", "--params", param_file(tmp_path),
                     "--out", tmp_path / "o2.csv")
    assert rc == 0 and "warning" not in err


def test_nothing_to_fit_names_the_file(tmp_path, capsys):
    # a joint that never moves: an encoder at rest, a torque of noise — no level, no reversal
    import numpy as np
    import pandas as pd

    rng = np.random.default_rng(0)
    t = np.arange(2000) * 1e-3
    pd.DataFrame({"time": t, "position": rng.normal(0.0, 1e-6, t.size), "torque": rng.normal(0.0, 0.05, t.size)}
                 ).to_csv(tmp_path / "short.csv", index=False)
    rc, _, err = run(capsys, "fit", tmp_path / "short.csv", "--out", tmp_path / "p.yaml")
    errors = [ln for ln in err.splitlines() if ln.startswith("error:")]  # besides the progress lines
    assert rc == 2 and len(errors) == 1 and f"{tmp_path / 'short.csv'}: nothing to fit" in errors[0], err
    assert "Traceback" not in err
    assert not (tmp_path / "p.yaml").exists()


@pytest.mark.parametrize("setting, says", [
    ("window=4", "--threshold window=4: must be an odd whole number of samples, at least 5"),
    ("window=6", "--threshold window=6: must be an odd whole number of samples, at least 5"),
    ("v_rest=-0.1", "--threshold v_rest=-0.1: must be > 0"),
    ("min_excursion=nan", "--threshold min_excursion=nan: must be finite"),
    ("v_floor=1", "--threshold v_floor: not a threshold of the diagnosis's reading (settable: window, v_rest, "
                  "min_excursion)"),
    ("window", "--threshold 'window': expected name=number"),
])
def test_a_bad_reading_threshold_is_refused_before_the_work(tmp_path, capsys, setting, says):
    rc, _, err = run(capsys, "diagnose", SAMPLE, "--threshold", setting, "--json", tmp_path / "r.json")
    assert rc == 2 and one_line(err) == f"error: {says}"
    assert os.listdir(tmp_path) == []


def test_a_reading_threshold_set_reaches_the_report_marked(tmp_path, capsys):
    import json

    out = tmp_path / "r.json"
    rc, text, _ = run(capsys, "diagnose", SAMPLE, "--threshold", "v_rest=0.002", "--threshold", "min_excursion=1e-3",
                      "--json", out)
    assert rc == 0
    res = json.loads(out.read_text())
    assert res["settings"]["reading"] == {"v_rest": 0.002, "min_excursion": 0.001}
    assert "|v| < 0.002 rad/s (set) counts as presliding" in res["notes"][0]
    assert "0.001 rad (set) of back-travel" in res["notes"][0] and "samples (set)" not in res["notes"][0]
    assert "|v| < 0.002 rad/s (set)" in text


def test_a_load_effect_without_a_load_column_names_the_file_and_the_option(tmp_path, capsys):
    # a diagnosed file with a normal-load effect, driven by a recording whose load column is
    # not named as one (a rig's 'Fz'): said with the file and --columns, nothing written
    d = default_params().to_dict()
    d["effects"] = [{"name": "normal_load", "params": {"alpha": 0.8, "N0": 35.0}}]
    p = param_file(tmp_path, text=yaml.safe_dump(d))
    rec = tmp_path / "rig.csv"
    t = np.arange(200) * 1e-3
    rec.write_text("time [s],position [rad],Fz [N]\n" + "".join(f"{a},{1e-4 * np.sin(9 * a)},35\n" for a in t))
    rc, _, err = run(capsys, "simulate", "--input", rec, "--params", p, "--out", tmp_path / "o.csv")
    # (the reading's notes come first: the column left unread among them)
    assert rc == 2 and err.strip().splitlines()[-1] == (f"error: {rec}: the parameter file's effect normal_load needs the normal load, "
                                         f"and no column of this file is read as it: name it with --columns "
                                         f"normal_load=<column>"), err
    assert not (tmp_path / "o.csv").exists()
    rc, _, err = run(capsys, "simulate", "--input", rec, "--columns", "normal_load=Fz", "--params", p,
                     "--out", tmp_path / "o.csv")
    assert rc == 0 and (tmp_path / "o.csv").exists(), err
