"""`fit` then `diagnose` on a ball-screw axis simulated apart from the project
(``synth/ballscrew.py``: a four-element Maxwell-slip contact with damped stuck elements under a
Gaussian Stribeck limit, semi-implicit Euler at 10 kHz logged at 500 Hz, a 2·10⁻⁵ in scale,
the motor force in lbf with 0.3 lbf of noise, force ramps then a PI velocity loop over eight
speeds in shuffled order), read from its inch-pound files as a user has them."""

import json

import numpy as np
import pytest

from leuven_friction.app.cli import main
from synth import ballscrew as B


def _files(tmp_path, name, drift, seed):
    t, x, f, _ = B.simulate(drift, seed)
    B.write(tmp_path / f"{name}.csv", t, x, f, "in")
    B.write(tmp_path / f"{name}_mm.csv", t, x, f, "mm")
    return tmp_path / f"{name}.csv", tmp_path / f"{name}_mm.csv"


def _diagnose(tmp_path, path):
    out = tmp_path / (path.stem + ".json")
    assert main(["diagnose", str(path), "--json", str(out)]) == 0
    return json.loads(out.read_text())


@pytest.mark.slow
def test_the_inch_pound_file_fits_the_simulators_steady_friction_in_si(tmp_path):
    inch, mm = _files(tmp_path, "A", 0.0, 11)
    for path in (inch, mm):
        assert main(["fit", str(path), "--out", str(tmp_path / (path.stem + ".yaml"))]) == 0
    import yaml

    a, b = (yaml.safe_load((tmp_path / f"{s}.yaml").read_text()) for s in ("A", "A_mm"))
    assert a["units"] == {"position": "m", "force": "N", "time": "s"}
    for side, sign in (("positive", 1), ("negative", -1)):
        got, other = a["stribeck"][side], b["stribeck"][side]
        # the simulator's S(v) + σ2·v in SI, read from inches and pound-force
        assert got["Fs"] == pytest.approx(sign * B.FS, rel=0.01)
        assert got["Fc"] == pytest.approx(sign * B.FC, rel=0.01)
        assert got["vs"] == pytest.approx(sign * B.VS, rel=0.05)
        assert got["sigma2"] == pytest.approx(B.SIG2, rel=0.02)
        # and the same numbers as from the file in mm and N (ten digits of each file apart)
        for k in ("Fs", "Fc", "vs", "sigma2"):
            assert got[k] == pytest.approx(other[k], rel=1e-4), (side, k)


@pytest.mark.slow
def test_a_control_names_nothing_and_a_drift_is_named(tmp_path):
    control, _ = _files(tmp_path, "A", 0.0, 11)
    drifting, _ = _files(tmp_path, "B", 0.15, 12)
    rep = _diagnose(tmp_path, control)
    assert rep["effects"] == [], rep["effects"]
    rep = _diagnose(tmp_path, drifting)
    assert rep["effects"] == ["time_drift"], rep["effects"]
    alternative, written = rep["steps"][1]["rms"], rep["steps"][2]["rms"]
    assert written < 0.7 * alternative, (alternative, written)
    # the friction grew by 15 % over the session, linearly: from the first sample compared (t0)
    # to the session's end, (1 + 0.15·t_end/T)/(1 + 0.15·t0/T); the drift's first-order law
    # 1 + b·(1 − e^(−(t − t0)/τ)) reaches that within a fifth of the change
    p = rep["steps"][2]["params"]
    t_end = float(np.loadtxt(drifting, delimiter=",", skiprows=1, usecols=0)[-1])
    truth = (1 + 0.15) / (1 + 0.15 * p["t0"] / t_end) - 1
    reached = p["b"] * (1.0 - np.exp(-(t_end - p["t0"]) / p["tau"]))
    assert abs(reached - truth) < 0.2 * truth, (p, t_end, reached, truth)
