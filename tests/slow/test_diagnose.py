"""The discrepancy workflow on data with a hidden effect: it must name the effect and shrink
the RMS gap by at least 30 %; on data without one it must name nothing.

The data come from ``synth/effects.py`` (an unrelated parameter set, the effect
imposed by its own rule, noise); the base model is fitted to the data without knowing the
effect, and the workflow never sees the truth."""

import io
import json
import subprocess
import sys

import pytest

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.diagnose import diagnose
from leuven_friction.identify.fit import fit_recordings
from synth.effects import EFFECT_NAMES, make_recording

SEED = 21


def _recording(effect):
    df, truth = make_recording(effect, seed=SEED)
    buf = io.StringIO()
    df.to_csv(buf, index=False)
    return load_recording(buf.getvalue().encode(), name=f"{effect}.csv"), truth


@pytest.mark.parametrize("effect", EFFECT_NAMES)
def test_names_the_hidden_effect_and_shrinks_the_gap(effect):
    rec, _ = _recording(effect)
    base = fit_recordings([rec]).params  # the base model, fitted without knowing the effect
    d = diagnose(rec, base)
    assert d.effect == effect, d.text()
    assert d.rms_after <= 0.7 * d.rms_before, d.text()
    assert d.params_after.effects[-1]["name"] == effect
    # the extended model loads back (YAML shape) with the effect recorded
    from leuven_friction.model import FrictionParams

    back = FrictionParams.from_dict(d.params_after.to_dict())
    assert back.effects[-1]["name"] == effect


def test_control_without_effect_names_nothing():
    rec, _ = _recording(None)
    base = fit_recordings([rec]).params
    d = diagnose(rec, base)
    assert d.effect is None, d.text()
    assert d.params_after is base
    assert not any(c["significant"] for c in d.candidates)


def test_diagnose_cli_json_and_self_contained_html(tmp_path):
    df, _ = make_recording("position_periodic", seed=SEED)
    data = tmp_path / "rec.csv"
    df.to_csv(data, index=False)
    out_json, out_html, out_yaml = tmp_path / "r.json", tmp_path / "r.html", tmp_path / "p.yaml"
    r = subprocess.run([sys.executable, "-m", "leuven_friction.app.cli", "diagnose", str(data), "--json", str(out_json),
                        "--html", str(out_html), "--out", str(out_yaml)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    res = json.loads(out_json.read_text())
    for key in ("effect", "rms_before", "rms_after", "regimes", "candidates"):
        assert key in res
    assert res["effect"] == "position_periodic" and res["rms_after"] < res["rms_before"]
    assert {"presliding", "sliding, v > 0", "sliding, v < 0"} <= set(res["regimes"])
    assert all({"name", "delta_bic", "reduction"} <= set(c) for c in res["candidates"])
    html = out_html.read_text()
    assert "Plotly.newPlot" in html and "<script src=\"http" not in html  # plotly.js embedded
    from leuven_friction.identify.paramfile import load_params

    assert load_params(out_yaml).effects[-1]["name"] == "position_periodic"
    # the extended model, driven by the recorded motion, reproduces the gap the report states
    pred = tmp_path / "pred.csv"
    r = subprocess.run([sys.executable, "-m", "leuven_friction.app.cli", "simulate", "--input", str(data), "--drive", "displacement",
                        "--params", str(out_yaml), "--out", str(pred)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    import numpy as np
    import pandas as pd

    rms = float(np.sqrt(np.mean((pd.read_csv(pred)["friction_force"].to_numpy() - df["friction"].to_numpy()) ** 2)))
    assert rms == pytest.approx(res["rms_after"], rel=0.02)


def test_diagnose_cli_bad_input_is_one_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("time,temperature\n" + "".join(f"{i},{20 + i}\n" for i in range(30)))
    r = subprocess.run([sys.executable, "-m", "leuven_friction.app.cli", "diagnose", str(bad)], capture_output=True, text=True)
    assert r.returncode == 2 and "no column for position" in r.stderr and "Traceback" not in r.stderr
