"""`fit` on a vertical ball-screw axis simulated apart from the project
(``synth/vertical_axis.py``: a 40 kg carriage and a motor rotor reflected through a 10 mm lead,
gravity, a LuGre contact, a current loop; a 4096-count encoder logged as the motor's angle in
degrees, its current in A with an offset, time in ms at 2 kHz with rows dropped). On A a gas
spring counterbalances the weight, 3 kN/m over the stroke; on C the weight is held by the motor
alone. Neither is friction, and the model has no term for either: `fit` must say them, not
fit them as S(v). Every expectation is the simulator's own constant, not a number the tool
printed."""

import re

import pytest
import yaml

from leuven_friction.app.cli import main
from synth import vertical_axis as Z

# the lead turns degrees into mm (10 mm a turn), the torque constant amperes into newtons
UNITS = "position=0.02777777778 mm,force=502.6548 N"


def _fit(tmp_path, case, capsys):
    csv, out = tmp_path / f"{case}.csv", tmp_path / f"{case}.yaml"
    Z.write(case, str(csv))
    capsys.readouterr()
    assert main(["fit", str(csv), "--columns", "force=motor_current", "--units", UNITS, "--out", str(out)]) == 0
    said = capsys.readouterr()
    return yaml.safe_load(out.read_text()), said.out + said.err


@pytest.mark.slow
def test_a_gas_spring_in_the_motors_force_is_said_with_its_rate(tmp_path, capsys):
    _, said = _fit(tmp_path, "A", capsys)
    m = re.search(r"the applied force rises by (\S+) ± (\S+) N/m along the travel whichever way", said)
    assert m, said
    rate, sd = float(m.group(1)), float(m.group(2))
    assert abs(rate - Z.k_gs) < 3 * sd + 0.01 * Z.k_gs, (rate, sd)
    assert "write the column less it" in said


@pytest.mark.slow
def test_a_weight_held_by_the_motor_is_said_as_a_constant_force_not_a_presliding_spring(tmp_path, capsys):
    # every stroke down reads a force against its velocity (the weight beyond friction), over
    # most of the travel: the note says a constant force, and no spring is said (there is none)
    _, said = _fit(tmp_path, "C", capsys)
    assert "which no presliding spring gives back over: the force holds a constant force beyond friction" in said, said
    assert "rises by" not in said
