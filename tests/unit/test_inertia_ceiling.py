"""The inertia of eq. (8) where nothing reads it: the ceiling the applied force sets.

The recordings come from ``tests/unit/plants.py`` (a mass under two sines of force, a bristle
contact with a Gaussian Stribeck limit, explicit Euler, a 1 µm encoder): it never slides
steadily, so the force regressed on the acceleration reads nothing. The expectation is
Newton's, not the code's: a force of span ΔF cannot give a mass I more than ΔF/I of acceleration,
so the ceiling read from the accelerations the record reaches lies at or above the true mass."""

import numpy as np
import pytest

from leuven_friction.identify import diagnose
from leuven_friction.identify.data import load_recording
from leuven_friction.identify.diagnose import inertia_ceiling
from leuven_friction.identify.fit import fit_recordings
from leuven_friction.model import default_params
from tests.unit.plants import forced_bristle_mass


def _csv(t, x, f, position_scale=1.0, force_scale=1.0, units=("m", "N")) -> str:
    head = f"time [s],position [{units[0]}],force [{units[1]}]\n"
    return head + "".join(f"{a:.17g},{b * position_scale:.17g},{c * force_scale:.17g}\n" for a, b, c in zip(t, x, f))


@pytest.fixture(scope="module")
def records():
    return {m: forced_bristle_mass(m) for m in (0.02, 0.2, 2.0)}


def test_the_ceiling_lies_above_the_true_mass_and_within_a_few_times_it(records):
    for mass, (t, x, f) in records.items():
        c = inertia_ceiling(load_recording(_csv(t, x, f), name="m.csv"))
        assert c is not None
        assert mass <= c <= 20 * mass, (mass, c)
    # a heavier mass under the same force: a tighter bound, the inertial part a larger share of the force
    ratios = [inertia_ceiling(load_recording(_csv(*records[m]), name="m.csv")) / m for m in sorted(records)]
    assert ratios[0] > ratios[1] > ratios[2]


def test_the_ceiling_is_the_same_physics_in_mm_and_mn(records):
    t, x, f = records[0.2]
    si = inertia_ceiling(load_recording(_csv(t, x, f), name="si.csv"))
    mm = inertia_ceiling(load_recording(_csv(t, x, f, 1e3, 1e3, ("mm", "mN")), name="mm.csv"))
    assert mm == pytest.approx(si, rel=1e-6)


def test_a_force_that_never_moves_the_mass_sets_no_ceiling():
    # the position at rest on its encoder: no acceleration above its noise, nothing to bound
    t = np.arange(4000) * 1e-3
    rng = np.random.default_rng(1)
    x = np.round(rng.normal(0, 2e-7, len(t)) / 1e-6) * 1e-6
    f = 0.3 * np.sin(2 * np.pi * 0.4 * t)
    assert inertia_ceiling(load_recording(_csv(t, x, f), name="rest.csv")) is None


def test_fit_holds_an_unread_inertia_at_the_ceiling_not_at_another_machines_default(records, monkeypatch):
    # the model-beside reading is taken out, so that nothing reads the inertia (as on a haptic
    # joint made apart, whose closed loop left too little steady sliding for either reading)
    monkeypatch.setattr(diagnose, "inertia_beside_model", lambda rec, params: None)
    t, x, f = records[0.2]
    rec = load_recording(_csv(t, x, f), name="m.csv")
    res = fit_recordings([rec], refine=False)
    ceiling = inertia_ceiling(rec)
    assert default_params().inertia > ceiling  # (the rule has something to do)
    assert res.params.inertia == pytest.approx(ceiling)
    assert res.params.inertia >= 0.2
    assert "inertia" not in res.params.uncertainty  # held, not estimated
    assert "upper bound" in res.held["inertia"] and "held at that ceiling" in res.held["inertia"]


def test_an_inertia_refitted_beside_the_model_is_read_only_where_its_term_stands_over_the_noise():
    # I·ẍ at 2·10⁴ kg·m² × 10⁻³ rad/s² spans 20 N·m under a 536 N·m noise floor: the refitted
    # "−7070" is what the misfit asks, said so, with no advice to give the inertia; the same
    # reading where I·ẍ spans 50 against a floor of 1 is a column with no inertial term
    from leuven_friction.identify.diagnose import inertia_beside_notes

    quiet = inertia_beside_notes(2e4, -2.707e4, 1e-3, 536.0)
    assert len(quiet) == 1 and "as if I were -7070" in quiet[0]
    assert "spans 20 (its sd here), under the noise floor 536: the record does not read the inertia" in quiet[0]
    loud = inertia_beside_notes(5.0, -6.0, 10.0, 1.0)
    assert len(loud) == 2 and "does not read" not in loud[0]
    assert loud[1].startswith("that is no positive inertia at all") and "give this machine's inertia" in loud[1]
    assert len(inertia_beside_notes(5.0, -1.0, 10.0, 1.0)) == 1  # 4 of 5: an inertia, read
