"""`fit` on the rotary joint simulated apart from the project (``synth/joint_maxwell_slip_logged.py``)
with its stiff contact (friction ×3, stiffness ×5): presliding over within a few steps of its
19-bit encoder, so the sensor, not the contact, sets how many segments the transition curve
can have — and the report says so."""

import math

import numpy as np

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.fit import RESOLVED, fit_recordings
from synth import joint_maxwell_slip_logged as J


def _fit(monkeypatch, tmp_path, count_deg):
    monkeypatch.setattr(J, "CNT", count_deg)
    t, angle, torque, _, _ = J.simulate(77, "control2", stiff_scale=5, fric_scale=3, T=40.0)
    J.write(tmp_path / "joint.csv", t, angle, torque, decimals=9)  # 9 places hold the 27-bit count
    return fit_recordings([load_recording(tmp_path / "joint.csv")], refine=False)


def test_a_curve_cut_short_by_the_encoder_says_the_sensor_set_its_knots(monkeypatch, tmp_path):
    step = J.CNT * math.pi / 180.0  # one count of the 19-bit encoder, in rad
    res = _fit(monkeypatch, tmp_path, J.CNT)
    z = np.array(res.params.transition_curve.z)
    note = [n for n in res.notes if "the sensor does not tell them apart" in n]
    assert len(z) - 1 < 6 and len(note) == 1, (z, res.notes)
    assert f"({step:.3g})" in note[0], note
    assert np.all(np.diff(z) >= RESOLVED * step * (1 - 1e-9)), z


def test_the_same_contact_through_a_fine_encoder_has_every_knot_and_no_such_note(monkeypatch, tmp_path):
    res = _fit(monkeypatch, tmp_path, J.CNT / 256)  # a 27-bit encoder
    assert len(res.params.transition_curve.z) == 7, res.params.transition_curve.z
    assert not any("the sensor does not tell them apart" in n for n in res.notes), res.notes
