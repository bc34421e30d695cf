"""`fit` then `diagnose` on a haptic device's capstan joint simulated apart from the project
(``synth/haptic_apart.py``: 2·10⁻⁴ kg·m², a four-element Maxwell-slip contact, PD control at
1 kHz, semi-implicit Euler at 20 kHz, a 4096-count encoder coarser than most of its presliding,
the motor current logged in A as `current_A`). Every expectation is the simulator's own
constant or Newton's, not a number the tool printed."""

import json

import pytest
import yaml

from leuven_friction.app.cli import main
from synth import haptic_apart as H

UNITS = ["--columns", "force=current_A", "--units", "force=0.025 N*m"]


def _fit_and_diagnose(tmp_path, seed, soften):
    text, truth = H.recording(seed, soften)
    tsv = tmp_path / f"joint_{seed}.tsv"
    tsv.write_text(text)
    base, out = tmp_path / f"joint_{seed}.yaml", tmp_path / f"joint_{seed}.json"
    assert main(["fit", str(tsv), *UNITS, "--out", str(base)]) == 0
    assert main(["diagnose", str(tsv), *UNITS, "--params", str(base), "--json", str(out)]) == 0
    return yaml.safe_load(base.read_text()), json.loads(out.read_text()), truth


@pytest.mark.slow
def test_the_current_without_its_torque_constant_is_refused_not_read_as_a_torque(tmp_path):
    text, _ = H.recording(1)
    tsv = tmp_path / "joint.tsv"
    tsv.write_text(text)
    out = tmp_path / "joint.yaml"
    assert main(["fit", str(tsv), "--columns", "force=current_A", "--out", str(out)]) == 2
    assert not out.exists()


@pytest.mark.slow
def test_its_control_holds_the_inertia_above_the_true_one_and_names_nothing(tmp_path):
    params, rep, truth = _fit_and_diagnose(tmp_path, 1, False)
    # nothing reads the inertia here (too little steady sliding); the ceiling the torque sets
    # lies above the true 2·10⁻⁴ (a torque of that span cannot accelerate more), and far below the
    # paper's robot joint's 5 it had been held at
    assert truth["inertia"] <= params["inertia"] <= 20 * truth["inertia"], params["inertia"]
    assert "inertia" not in (params.get("uncertainty") or {})
    # Coulomb friction within 10 % of the contact's 0.012 N·m (the torque constant applied)
    assert abs(abs(params["stribeck"]["positive"]["Fc"]) - truth["Fc"]) < 0.1 * truth["Fc"], params["stribeck"]
    # the model fitted leaves about the noise floor: no effect is named on what is left (a ripple
    # of a few encoder steps had been, at 0.56 → 0.48 noise floors)
    assert rep["effects"] == [] and not rep["confounded"], rep["effects"]


@pytest.mark.slow
def test_a_softening_under_the_encoder_resolution_is_not_taken_for_a_ripple(tmp_path):
    # the softened spring acts within 0.2–3 mrad, at or under one encoder step: it cannot be
    # told here, and no effect the joint does not have may be named for it
    _, rep, _ = _fit_and_diagnose(tmp_path, 2, True)
    assert not set(rep["effects"]) - {"cyclic_softening"}, rep["effects"]
