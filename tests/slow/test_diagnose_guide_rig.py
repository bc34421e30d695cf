"""`fit` then `diagnose` on a linear rolling-element guide simulated apart from the project
(``synth/guide_rig.py``: a Maxwell-slip bank on a steady curve of its own under a PID loop, the
friction from a load cell logged with the reaction's sign in mN, the position in µm, time in ms,
the normal load in kN), as a new user runs them: no option. Every expectation is the
simulator's own, not a number the tool printed."""

import pytest

from synth import guide_rig as G
from tests.cli_runs import simulated_fit_then_diagnose, written


def _fit_and_diagnose(tmp_path, name):  # as a user runs them: the default settings
    return simulated_fit_then_diagnose(tmp_path, G.simulate_to, name)


@pytest.mark.slow
def test_a_guide_rig_control_names_nothing_and_its_steady_curve_is_the_simulators(tmp_path):
    doc, rep = _fit_and_diagnose(tmp_path, "control")
    assert doc["units"] == {"position": "m", "force": "N", "time": "s"}  # from µm, mN and ms
    for side, sign in (("positive", 1), ("negative", -1)):
        truth, st = G.SIDE[sign], doc["stribeck"][side]
        # the load cell's reaction turned to the action's sign; within 1 % of the simulator's
        for k, t in (("Fs", truth["Fs"]), ("Fc", truth["Fc"]), ("vs", truth["vs"])):
            assert st[k] == pytest.approx(sign * t, rel=0.01), (side, k, st)
        assert st["sigma2"] == pytest.approx(truth["s2"], rel=0.02), (side, st)
    assert rep["effects"] == [], (rep["effects"], rep["candidates"])


@pytest.mark.slow
def test_a_guide_rigs_load_beside_a_softening_are_both_named(tmp_path):
    # friction ∝ (N / 2 kN)^0.7 on a load stepped and ramped over 1.0–3.5 kN, and the presliding
    # springs softening by 30 % with the reversals: both effects of the pair
    doc, rep = _fit_and_diagnose(tmp_path, "load_soft")
    assert set(rep["effects"]) == {"normal_load", "cyclic_softening"}, (rep["effects"], rep["candidates"])
    load = written(rep, "normal_load")
    assert abs(load["params"]["alpha"] - G.ALPHA) < max(3 * load["sd"]["alpha"], 0.05), load
    assert written(rep, "cyclic_softening")["params"]["h"] < 0, rep["written_effects"]  # softening, not hardening
    steps = rep["steps"]
    assert steps[-1]["rms"] < 0.7 * steps[1]["rms"], steps
