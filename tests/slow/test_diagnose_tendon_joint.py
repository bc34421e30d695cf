"""`fit` then `diagnose` on a tendon-driven rotary joint simulated apart from the project
(``synth/tendon_joint.py``: 2·10⁻⁵ kg·m² under a PID loop at 2 kHz, four Maxwell-slip elements
under a Lorentzian Stribeck limit of 8–11 mN·m, a 0.01° encoder, the motor current in mA with
the torque constant per mA as its unit, the cable's pretension logged beside it), as a new user
runs them. Every expectation is the simulator's own constant, not a number the tool printed."""

import json

import numpy as np
import pytest

from leuven_friction.app.cli import main
from leuven_friction.identify.paramfile import load_params
from synth import tendon_joint as S

COLUMNS = ["--columns", "force=motor_current,normal_load=pretension"]


def _recording(tmp_path, kind):
    path = tmp_path / f"{kind}.csv"
    S.write_csv(path, S.simulate(kind, seed=S.SEEDS[kind]))
    return path


@pytest.mark.slow
def test_a_load_with_steps_on_a_rising_schedule_is_named_not_called_confounded_with_a_drift(tmp_path):
    # pretension 10 N, a step to 18 N, ramps to 30 N, a step to 36 N, a ramp to 40 N; friction ∝
    # (T/20 N)^0.7. A drift in time follows the rise (their corrections correlate 0.97) but not the
    # steps: fitted beside the drift the load still gains held out, the drift beside the load
    # does not, and the load is named — where before the two were reported confounded
    control, load = _recording(tmp_path, "control"), _recording(tmp_path, "load")
    base, out, rep_path = (tmp_path / n for n in ("fit.yaml", "diagnosed.yaml", "d.json"))
    assert main(["fit", str(control), "--columns", "force=motor_current", "--out", str(base)]) == 0
    # the fit's S(v), both sides against the simulator's S(v) + σ2·v between its slowest and
    # fastest steady levels: the negative side has one level fewer than the Stribeck form asks
    # for (a slow sine's tops made two more positive ones) and takes δ from the positive side
    st = load_params(base).stribeck
    v = np.geomspace(0.03, 0.5, 12)
    true = S.s_of_v(v) + S.SIG2 * v
    for side, sign in ((st.positive, 1.0), (st.negative, -1.0)):
        got = sign * (side.Fc + (side.Fs - side.Fc) * np.exp(-np.abs(v / side.vs) ** side.delta) + side.sigma2 * sign * v)
        assert np.max(np.abs(got / true - 1.0)) < 0.05, (sign, got, true)
    assert main(["diagnose", str(load), "--params", str(base), *COLUMNS, "--json", str(rep_path),
                 "--out", str(out)]) == 0
    rep = json.loads(rep_path.read_text())
    assert rep["effects"] == ["normal_load"] and not rep["confounded"], (rep["effects"], rep["confounded"])
    said = [n for n in rep["notes"] if n.startswith("normal_load and time_drift explain much the same part")]
    assert len(said) == 1 and "normal_load shows a part of its own" in said[0], rep["notes"]
    # the load rises over the session: that it follows time is said, with the experiment that tells
    assert any(n.startswith("the normal load follows time") for n in rep["notes"]), rep["notes"]
    load_fx = next(e for e in rep["written_effects"] if e["name"] == "normal_load")
    assert abs(load_fx["params"]["alpha"] - 0.7) < 3 * load_fx["sd"]["alpha"], load_fx
