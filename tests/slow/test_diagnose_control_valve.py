"""`fit` then `diagnose` on a pneumatic control valve simulated apart from the project
(``synth/control_valve.py``: a sliding stem on a spring-diaphragm actuator, packing friction as a
five-element Maxwell-slip bank under a Lorentzian Stribeck limit, semi-implicit Euler at 20 kHz,
an I/P lag and a PI positioner, an LVDT quantised to 5 µm in mm, logged at 1 kHz with jitter).
The force a user writes is P·A less the spring, taken at the datasheet's rate: 4 % off the
valve's own on A, 15 % off on D, so the force holds (k − k_datasheet)·x, which keeps its sign
whichever way the stem moves and is no friction effect. Every expectation is the simulator's
own constant, not a number the tool printed."""

import json

import pytest

from leuven_friction.app.cli import main
from synth import control_valve as V


@pytest.mark.slow
@pytest.mark.parametrize("case, off", [("A", 0.04), ("D", 0.15)])
def test_a_spring_rate_taken_off_wrongly_is_said_as_a_force_in_proportion_to_the_travel(tmp_path, case, off):
    csv, base, out = tmp_path / f"valve_{case}.csv", tmp_path / f"{case}.yaml", tmp_path / f"{case}.json"
    V.write(case, str(csv))
    assert main(["fit", str(csv), "--out", str(base)]) == 0
    assert main(["diagnose", str(csv), "--params", str(base), "--json", str(out)]) == 0
    rep = json.loads(out.read_text())
    assert rep["effects"] == [], rep["effects"]  # no friction effect is imposed
    ts = rep["travel_spring"]
    assert ts is not None, rep["notes"]
    rate = off * V.K_TRUE  # N/m, the spring left in the force (the file's mm read as m)
    assert abs(ts["rate"] - rate) < 3 * ts["sd"] + 0.05 * rate, (ts["rate"], ts["sd"], rate)
    assert abs(ts["following"]) < 0.5 * abs(ts["rate"]), ts
    assert any(n.startswith("a force in proportion to the travel") for n in rep["notes"]), rep["notes"]
