"""`fit` then `diagnose` on a telescope mount's axis simulated apart from the project
(``synth/telescope_mount.py``: 40 kg·m² behind a worm gear, a five-element Maxwell-slip contact
under a Lorentzian Stribeck limit, a 0.05″ encoder logged in arc-seconds, the torque in mN·m,
time in ms; 60 s of torque ramps, then ten speeds from sidereal rate to a slew in a shuffled
order). Every expectation is the simulator's own constant, not a number the tool printed."""

import json
import math

import numpy as np
import pytest

from leuven_friction.app.cli import main
from leuven_friction.identify.paramfile import load_params
from leuven_friction.model.simulate import stribeck_curve
from synth import telescope_mount as S
from tests.cli_runs import written


def _fitted(tmp_path, case):
    df, truth = S.recording(case)
    csv, base = tmp_path / f"{case}.csv", tmp_path / f"{case}.yaml"
    df.to_csv(csv, index=False)
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    return csv, base, truth


def _diagnosed(tmp_path, csv, base, *extra):
    out = tmp_path / f"{csv.stem}.json"
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out), *extra]) == 0
    return json.loads(out.read_text())


@pytest.mark.slow
def test_the_control_read_in_arc_seconds_fits_its_steady_friction_and_names_nothing(tmp_path):
    csv, base, truth = _fitted(tmp_path, "a_control")
    p = load_params(base)
    assert p.units.position == "rad"  # the log's arc-seconds read as radians
    arcsec = math.pi / 648000
    for sign, side in ((1, truth["pos"]), (-1, truth["neg"])):
        # the sweep's ten speeds, sidereal to slew: the Lorentzian limit plus viscous friction
        v = np.geomspace(15.0, 3000.0, 10) * arcsec
        true = side["Fc"] + (side["Fs"] - side["Fc"]) / (1.0 + (v / (side["vs_arcsec"] * arcsec)) ** 2) \
            + truth["sigma2"] * v
        fitted = sign * stribeck_curve(p, sign * v)
        np.testing.assert_allclose(fitted, true, rtol=0.06)
    rep = _diagnosed(tmp_path, csv, base)
    assert rep["effects"] == [], rep["effects"]


@pytest.mark.slow
def test_a_load_is_named_and_a_change_over_within_the_torque_ramps_is_not_called_a_softening(tmp_path):
    # the load steps 500 → 800 → 400 → 700 N after the ramps, friction ∝ (N/500 N)^0.6. The
    # 60 s of ramps make 6 reversals of the softening's back-travel before the first gross
    # sliding; a softening of n_c 3.5 found there (82 % of it within the ramps) had been named
    # beside the load, where the contact has none: a step between the ramps and the rest looks
    # the same, and it is seen, not named
    csv, base, truth = _fitted(tmp_path, "c_load")
    rep = _diagnosed(tmp_path, csv, base)
    assert rep["effects"] == ["normal_load"], rep["effects"]
    load = written(rep, "normal_load")
    assert abs(load["params"]["alpha"] - truth["load_alpha"]) < 3 * load["sd"]["alpha"] + 0.03, load
    assert all(c["name"] != "cyclic_softening" or "before the first gross sliding" in c["unsettled"]
               for c in rep["candidates"] if c.get("unsettled")), rep["candidates"]


@pytest.mark.slow
def test_a_softening_counted_from_the_back_travel_the_user_sets_is_counted_from_it(tmp_path):
    # the simulator counts a reversal from 3″ of back-travel; set so (in rad, SI), the
    # diagnosis counts from exactly that, the softening's count too, and writes it
    csv, base, truth = _fitted(tmp_path, "b_softening")
    back = truth["rev_back_arcsec"] * math.pi / 648000
    rep = _diagnosed(tmp_path, csv, base, "--threshold", f"min_excursion={back!r}")
    assert rep["reading"]["min_excursion"] == pytest.approx(back, rel=1e-12)
    assert "cyclic_softening" in rep["effects"], (rep["effects"], rep["unsettled"])
    soft = written(rep, "cyclic_softening")
    assert soft["params"]["min_excursion"] == pytest.approx(back, rel=1e-12), soft
    assert abs(soft["params"]["h"] - truth["soft_h"]) < 3 * soft["sd"]["h"], soft
