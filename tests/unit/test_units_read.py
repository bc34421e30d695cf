"""Units as a user's files give them: inch-pound headers, headers with no unit at all, empty
cells, and parameter files that are not in SI."""

import numpy as np
import pytest

from leuven_friction.identify.data import DataError, load_recording
from leuven_friction.model import FrictionParams, ParameterError, default_params

INCH, LBF = 0.0254, 0.45359237 * 9.80665  # exact by definition (m, N)


def _csv(header, cols) -> str:
    return "\n".join([",".join(header)] + [",".join(repr(float(c)) for c in row) for row in zip(*cols)]) + "\n"


def _signals(n=200):
    t = np.arange(n) * 2e-3
    return t, 0.01 * np.sin(7 * t), 30.0 * np.cos(5 * t)


@pytest.mark.parametrize("header,pos_factor,force_factor,force_si", [
    (["time [s]", "position [in]", "force [lbf]"], INCH, LBF, "N"),
    (["time [s]", "position [inch]", "force [lb]"], INCH, LBF, "N"),
    (["time [s]", "position [deg]", "torque [lbf·in]"], np.pi / 180, LBF * INCH, "N*m"),
    (["time [s]", "position [deg]", "torque [in-lb]"], np.pi / 180, LBF * INCH, "N*m"),
    (["time [s]", "position [deg]", "torque [lbf*ft]"], np.pi / 180, LBF * 12 * INCH, "N*m"),
    (["time [s]", "position [mm]", "torque [N-m]"], 1e-3, 1.0, "N*m"),
])
def test_inch_pound_units_are_converted_to_si(header, pos_factor, force_factor, force_si):
    t, x, f = _signals()
    rec = load_recording(_csv(header, [t, x, f]), name="ip.csv", require=("time", "position", "force"))
    np.testing.assert_allclose(rec.position, x * pos_factor, rtol=1e-12)
    np.testing.assert_allclose(rec.force, f * force_factor, rtol=1e-12)
    assert rec.units["force"] == force_si


@pytest.mark.parametrize("header,units", [
    (["time", "position", "force"], {"position": "m", "force": "N"}),
    (["t", "x", "u"], {"position": "m", "force": "N"}),
    (["time", "position", "torque"], {"position": "rad", "force": "N*m"}),
    (["t", "q", "tau"], {"position": "rad", "force": "N*m"}),
    # a unit given for one column sets the kind of the others
    (["time [s]", "position [mm]", "effort"], {"position": "m", "force": "N"}),
    (["time [s]", "angle", "force [N*m]"], {"position": "rad", "force": "N*m"}),
])
def test_a_header_without_units_is_read_as_si_of_the_machine_its_names_say(header, units):
    t, x, f = _signals()
    rec = load_recording(_csv(header, [t, x, f]), name="plain.csv", require=("time", "position", "force"))
    assert {k: rec.units[k] for k in units} == units
    np.testing.assert_array_equal(rec.force, f)  # SI assumed where no unit is written: nothing rescaled
    assert any("assumed SI" in n for n in rec.notes)


def test_an_empty_cell_is_named_by_column_and_row():
    t, x, f = _signals(50)
    text = _csv(["time [s]", "position [m]", "force [N]"], [t, x, f]).splitlines()
    cells = text[8].split(",")
    text[8] = ",".join([cells[0], "", cells[2]])  # the 8th data row: file line 9
    with pytest.raises(DataError) as e:
        load_recording("\n".join(text) + "\n", name="gap.csv")
    msg = str(e.value)
    assert "gap.csv" in msg and "'position [m]'" in msg and "row 9" in msg and "empty" in msg
    assert "\n" not in msg


@pytest.mark.parametrize("units,field", [
    ({"position": "mm", "force": "N", "time": "s"}, "units.position"),
    ({"position": "in", "force": "lbf", "time": "s"}, "units.position"),
    ({"position": "m", "force": "banana", "time": "s"}, "units.force"),
    ({"position": "rad", "force": "N*m", "time": "ms"}, "units.time"),
])
def test_a_parameter_file_not_in_si_is_refused_naming_the_field(units, field):
    d = default_params().to_dict()
    d["units"] = units
    with pytest.raises(ParameterError) as e:
        FrictionParams.from_dict(d)
    assert str(e.value).startswith(field) and "SI" in str(e.value)


def test_a_torque_unit_spelt_another_way_is_the_same_unit():
    d = default_params().to_dict()
    d["units"] = {"position": "rad", "force": "N m", "time": "s"}
    assert FrictionParams.from_dict(d).units.force == "N*m"
