"""Units as a user's files give them: inch-pound headers, headers with no unit at all, empty
cells, and parameter files that are not in SI."""

import numpy as np
import pytest

from leuven_friction.identify.data import DataError, load_recording
from leuven_friction.identify.errors import IdentificationError
from leuven_friction.identify.segment import check_force_or_friction
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


def test_a_load_without_a_unit_is_said_as_read_in_newtons_on_either_kind_of_machine():
    # the note had named no column ("no unit in the header of : assumed SI") for a load logged
    # in lbf without its unit, which was read 4.45 times too small without a word
    t, x, f = _signals()
    for header, kind in ((["time [s]", "position [in]", "friction [lbf]", "normal_load"], "linear"),
                         (["time [s]", "angle [deg]", "torque [N*m]", "normal_load"], "rotary")):
        rec = load_recording(_csv(header, [t, x, f, 250.0 + 0 * t]), name="rig.csv")
        assert rec.units["normal_load"] == "N"
        np.testing.assert_array_equal(rec.normal_load, 250.0)
        said = [n for n in rec.notes if "assumed SI" in n]
        assert said == [f"no unit in the header of normal_load in N: assumed SI, a {kind} machine's (as the units of "
                        f"its other columns say)"], rec.notes


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


def test_a_last_line_cut_short_is_left_out_and_said_and_an_empty_cell_before_it_still_refused():
    # a log whose writing stopped inside its last line ('31343.9982,-381'): that line is no
    # sample (its last cell may be cut too); before, "row 155892: is empty or NaN" was all
    t, x, f = _signals(50)
    text = _csv(["time [s]", "position [m]", "force [N]"], [t, x, f])
    cut = text[: text.rstrip("\n").rindex(",")]  # the last line without its last cell
    rec = load_recording(cut, name="cut.csv")
    assert len(rec.time) == 49 and rec.time[-1] == t[-2]
    assert any("last row (line 51)" in n and "'force [N]'" in n and "cut short" in n for n in rec.notes), rec.notes
    # the same cell empty one line earlier is a hole in the log, not its end: a dropout, its row
    # left out (1 of 50 rows is over the share dropouts may take: refused, naming it)
    lines = text.splitlines()
    lines[-2] = lines[-2][: lines[-2].rindex(",") + 1]
    with pytest.raises(DataError) as e:
        load_recording("\n".join(lines) + "\n", name="hole.csv")
    assert "row 50" in str(e.value) and "empty" in str(e.value)


def test_a_file_cut_inside_its_last_cell_loses_that_row_and_says_so(tmp_path):
    # a logger stopped mid-write: '0.098000,0.0013,29.70' where it writes '%.6f' — the last cell
    # lost its digits, and no line end follows. Read as written it was a sample 0.006 N off; now
    # the row is left out and the notes say why, from a file and from an upload's text alike.
    # The same file written whole with no line end at its close keeps every row.
    t, x, f = _signals(50)
    whole = "time [s],position [m],force [N]\n" + "\n".join(f"{a:.6f},{b:.6f},{c:.6f}" for a, b, c in zip(t, x, f))
    cut = whole[:-4]
    assert whole.endswith(f"{f[-1]:.6f}") and not cut.endswith(f"{f[-1]:.6f}")
    path = tmp_path / "cut.csv"
    path.write_text(cut)
    for rec in (load_recording(path), load_recording(cut, name="cut.csv")):
        assert len(rec.time) == 49 and rec.time[-1] == pytest.approx(t[-2], abs=1e-9)
        assert any("last row (line 51)" in n and "'force [N]' cell" in n and "cut short" in n for n in rec.notes), \
            rec.notes
    (tmp_path / "whole.csv").write_text(whole)
    for rec in (load_recording(tmp_path / "whole.csv"), load_recording(whole, name="whole.csv")):
        assert len(rec.time) == 50 and rec.force[-1] == pytest.approx(f[-1], abs=1e-6)
        assert not any("cut short" in n for n in rec.notes), rec.notes


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


def test_mega_and_milli_newton_are_told_apart_by_case_alone():
    # units are read without case, but M is mega and m milli: a bearing's torque in MN·m had
    # been read in mN·m, 10⁹ times small
    from leuven_friction.identify.data import unit_of

    for spelt in ("MN", "MN*m", "MNm", "MN·m", "MN m"):
        factor, si = unit_of(spelt, "force")
        assert factor == 1e6 and si == ("N" if spelt == "MN" else "N*m"), spelt
    assert unit_of("mN", "force") == (1e-3, "N") and unit_of("mNm", "force") == (1e-3, "N*m")
    assert unit_of("kN*m", "force") == (1e3, "N*m")


def _turning_axis(n=6000, dt=1e-3):
    """A rotary axis running three and a half turns forward at 2π rad/s with a 0.3 rad wobble,
    then back: its continuous angle (rad), and the torque it logs."""
    t = np.arange(n) * dt
    angle = 0.4 + 2 * np.pi * 3.5 * np.sin(np.pi * t / t[-1]) + 0.3 * np.sin(40 * t)
    return t, angle, 0.2 * np.cos(3 * t)


@pytest.mark.parametrize("unit,turn", [("deg", 360.0), ("rad", 2 * np.pi)])
def test_an_angle_logged_modulo_one_turn_is_read_as_the_continuous_angle(tmp_path, unit, turn):
    t, angle, torque = _turning_axis()
    scale = turn / (2 * np.pi)
    logged = np.mod(angle * scale, turn)  # a single-turn encoder's reading, [0, 1 turn)
    p = tmp_path / "spindle.csv"
    p.write_text(_csv(["time [s]", f"angle [{unit}]", "torque [N*m]"], [t, logged, torque]))
    rec = load_recording(p)
    # the continuous angle, up to a whole number of turns where it starts
    shift = rec.position[0] - angle[0]
    assert abs(shift / (2 * np.pi) - round(shift / (2 * np.pi))) < 1e-9
    assert np.max(np.abs(rec.position - shift - angle)) < 1e-9
    wraps = int(np.sum(np.abs(np.diff(logged)) > turn / 2))
    assert wraps >= 6 and any(f"wraps at one turn ({wraps} time(s)" in note for note in rec.notes), rec.notes


def test_a_jump_that_is_no_whole_turn_or_a_length_is_left_as_logged(tmp_path):
    t, angle, torque = _turning_axis()
    jumped = angle.copy()
    jumped[3000:] += 4.0  # a jump of 4 rad between two samples: no wrap, left for the user to see
    for header, pos in ((["time [s]", "angle [rad]", "torque [N*m]"], jumped),
                        (["time [s]", "position [m]", "force [N]"], np.mod(angle, 2 * np.pi))):
        p = tmp_path / "axis.csv"
        p.write_text(_csv(header, [t, pos, torque]))
        rec = load_recording(p)
        assert np.array_equal(rec.position, pos) and not any("wraps" in note for note in rec.notes)


def test_a_motor_current_is_refused_saying_to_write_the_torque_constant_as_its_unit(tmp_path):
    t, x, f = _signals()
    p = tmp_path / "joint.csv"
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [A]"], [t, x, f]))
    with pytest.raises(IdentificationError) as unnamed:  # the fit's check that a force is there
        check_force_or_friction(load_recording(p))
    with pytest.raises(DataError) as named:
        load_recording(p, columns={"force": "motor_current [A]"})
    for said in (str(unnamed.value), str(named.value)):
        assert "\n" not in said and "'motor_current [A]'" in said and "torque constant" in said, said
        assert "motor_current [0.12 N*m]" in said, said
    # the constant written as its unit: the torque is the constant times the current
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [0.12 N*m]"], [t, x, f]))
    rec = load_recording(p, columns={"force": "motor_current [0.12 N*m]"})
    assert rec.units["force"] == "N*m" and np.allclose(rec.force, 0.12 * f)
    # in mA the constant to write is per mA: the example a thousandth of the N·m/A (a header of
    # '[0.05 N*m]' over mA, as the example for amperes read, wrote a thousand times the torque)
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [mA]"], [t, x, 1e3 * f]))
    with pytest.raises(DataError) as named:
        load_recording(p, columns={"force": "motor_current"})
    assert "per mA" in str(named.value) and "motor_current [0.12 mN*m]' for 0.12 N·m/A" in str(named.value), named.value
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [0.12 mN*m]"], [t, x, 1e3 * f]))
    rec = load_recording(p, columns={"force": "motor_current"})
    assert rec.units["force"] == "N*m" and np.allclose(rec.force, 0.12 * f)
    # the constant given with --units and no column named: the unit names the column to name
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [A]"], [t, x, f]))
    with pytest.raises(DataError, match=r"a unit is given for the force \('0.12 N\*m'\), but no column is read as the "
                                        r"force: name the column it is for, --columns force='motor_current \[A\]'$"):
        load_recording(p, units={"force": "0.12 N*m"})
    rec = load_recording(p, columns={"force": "motor_current [A]"}, units={"force": "0.12 N*m"})
    assert rec.units["force"] == "N*m" and np.allclose(rec.force, 0.12 * f)
    # a command that reads no force (a simulation driven by the position) is not stopped by it
    rec = load_recording(p, units={"force": "0.12 N*m"}, require=("time", "position"), only=("time", "position"))
    assert np.array_equal(rec.position, x)


def test_a_position_of_whole_numbers_without_a_unit_is_said_to_look_like_encoder_counts(tmp_path):
    # a gantry's motor encoder (4096 counts per 60 mm) logged without a unit: read as metres, as the
    # header says nothing, but the note says what whole numbers over thousands of counts look like;
    # the same travel in metres says nothing of counts
    t, x, f = _signals()
    counts = np.round((x - x.min()) / np.ptp(x) * 27000)
    p = tmp_path / "gantry.csv"
    p.write_text(_csv(["time", "position", "force"], [t, counts, f]))
    note = load_recording(p).units_assumed
    assert "whole numbers over 27000" in note and "encoder counts" in note and "'position [0.01 mm]'" in note, note
    p.write_text(_csv(["time", "position", "force"], [t, counts * 60e-3 / 4096, f]))
    assert "encoder counts" not in load_recording(p).units_assumed


def test_a_payload_in_kg_named_as_the_normal_load_is_refused_saying_the_load_is_a_force(tmp_path):
    # a gantry's payload logged in kg: the load on its rail is the whole moving mass times g, which
    # the file does not give (the carriage's own weight presses it too); refused in one line
    t, x, f = _signals()
    p = tmp_path / "gantry.csv"
    p.write_text(_csv(["time [s]", "position [m]", "F_drive [N]", "payload [kg]"], [t, x, f, np.full(len(t), 5.0)]))
    with pytest.raises(DataError) as said:
        load_recording(p, columns={"normal_load": "payload [kg]"})
    msg = str(said.value)
    assert "\n" not in msg and "'payload [kg]'" in msg and "is a mass, not a force" in msg and "in N" in msg, msg
    assert "carriage and payload" in msg and "times g" in msg, msg
    # the same column in N is read as the load
    p.write_text(_csv(["time [s]", "position [m]", "F_drive [N]", "payload [N]"], [t, x, f, np.full(len(t), 49.0)]))
    assert np.allclose(load_recording(p, columns={"normal_load": "payload [N]"}).normal_load, 49.0)


@pytest.mark.parametrize("start,fmt", [("2026-11-29 23:59:59.5", "%Y-%m-%d %H:%M:%S.%f"),
                                       ("2026-11-29T23:59:59.5", "%Y-%m-%dT%H:%M:%S.%f"),
                                       ("2026-11-29 23:59:59.5", "%H:%M:%S.%f")])
def test_a_time_column_of_clock_readings_is_read_as_seconds_from_its_first_row(tmp_path, start, fmt):
    # a logger that writes its clock, across midnight: 200 rows at 2 ms from 23:59:59.5
    t, x, f = _signals(400)
    import pandas as pd

    stamps = (pd.Timestamp(start) + pd.to_timedelta(t, unit="s")).strftime(fmt)
    p = tmp_path / "clock.csv"
    p.write_text("timestamp,position [mm],force [N]\n" + "".join(f"{s},{float(a)!r},{float(b)!r}\n" for s, a, b in zip(stamps, x, f)))
    rec = load_recording(p)
    assert np.max(np.abs(rec.time - t)) < 1e-6
    assert any("clock readings" in note for note in rec.notes), rec.notes


def test_a_time_column_with_a_word_in_it_is_still_refused_naming_the_row(tmp_path):
    p = tmp_path / "clock.csv"
    p.write_text("time,position [mm],force [N]\n10:00:00.000,0,1\n10:00:00.002,0,1\nstop,0,1\n" +
                 "".join(f"10:00:00.{k:03d},0,1\n" for k in range(4, 40, 2)))
    with pytest.raises(DataError) as e:
        load_recording(p)
    assert "row 4" in str(e.value) and "'stop'" in str(e.value), str(e.value)


def test_units_in_the_row_under_the_header_are_read_and_rows_named_as_in_the_file(tmp_path):
    # a DAQ export: names, then units, then data
    t, x, f = _signals()
    body = "".join(f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(t * 1e3, x * 1e3, f))
    p = tmp_path / "daq.csv"
    p.write_text("time,position,force\nms,mm,kN\n" + body)
    rec = load_recording(p)
    assert np.allclose(rec.time, t) and np.allclose(rec.position, x) and np.allclose(rec.force, 1e3 * f)
    assert rec.units == {"time": "s", "position": "m", "force": "N"}
    assert any("units read from the row under the header" in note for note in rec.notes), rec.notes
    # a bad cell is named by the file's line: header 1, units 2, the first data row 3
    lines = ("time,position,force\nms,mm,kN\n" + body).splitlines()
    lines[9] = lines[9].split(",")[0] + ",oops," + lines[9].split(",")[2]
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError) as e:
        load_recording(p)
    assert "row 10" in str(e.value) and "'oops'" in str(e.value), str(e.value)


def test_rows_with_every_cell_empty_are_skipped_and_later_rows_keep_their_lines(tmp_path):
    t, x, f = _signals()
    lines = _csv(["time [s]", "position [m]", "force [N]"], [t, x, f]).splitlines()
    lines.insert(50, ",,")  # a spreadsheet's empty row mid-file, and two at its end
    p = tmp_path / "sheet.csv"
    p.write_text("\n".join(lines + [",,", ",,"]) + "\n")
    rec = load_recording(p)
    assert np.array_equal(rec.time, t) and any("3 row(s) with every cell empty" in n for n in rec.notes), rec.notes
    # one empty cell is a dropout, its row left out and named by its line in the file (the empty
    # row counted)
    lines[120] = "," + lines[120].split(",", 1)[1]
    p.write_text("\n".join(lines) + "\n")
    rec = load_recording(p)
    assert len(rec.time) == len(t) - 1
    assert any("('time [s]' in 1, the first at row 121)" in n for n in rec.notes), rec.notes


def _tribometer_log(n=500, dt=0.01):
    """A disc's speed in rpm ramping 0 → 60 → 20, its friction coefficient, its normal load."""
    t = np.arange(n) * dt
    rpm = np.interp(t, [0.0, 1.0, 3.0, t[-1]], [0.0, 60.0, 20.0, 20.0])
    mu = 0.4 + 0.1 * np.exp(-t)
    fn = 10.0 + 2.0 * np.sin(t)
    return t, rpm, mu, fn


def test_a_tribometer_log_of_speed_in_rpm_and_friction_coefficient_reads_as_position_and_friction(tmp_path):
    t, rpm, mu, fn = _tribometer_log()
    p = tmp_path / "pod.csv"
    p.write_text(_csv(["Time [s]", "Speed [rpm]", "COF", "Fn [N]"], [t, rpm, mu, fn]))
    rec = load_recording(p, require=("time", "position"))
    omega = rpm * 2 * np.pi / 60
    assert rec.units["velocity"] == "rad/s" and np.allclose(rec.velocity, omega)
    # the position: the speed integrated (trapezoids, exact on this piecewise-linear speed)
    exact = np.concatenate([[0.0], np.cumsum(0.5 * (omega[1:] + omega[:-1]) * np.diff(t))])
    assert rec.units["position"] == "rad" and np.allclose(rec.position, exact)
    assert abs(rec.position[-1] - 2 * np.pi / 60 * (0.5 * 60 + 2 * 40 + 0.99 * 20 + 20 * (t[-1] - 3.0 - 0.99))) < 1e-9
    # the friction: μ times the normal load, in N
    assert rec.units["friction"] == "N" and np.allclose(rec.friction, mu * fn)
    said = " ".join(rec.notes)
    assert "integrated over time" in said and "friction coefficient" in said, said


def test_a_friction_coefficient_without_a_normal_load_is_refused_saying_what_it_needs(tmp_path):
    t, rpm, mu, _ = _tribometer_log()
    p = tmp_path / "pod.csv"
    p.write_text(_csv(["Time [s]", "Speed [rev/min]", "mu"], [t, rpm, mu]))
    with pytest.raises(DataError) as e:
        load_recording(p, require=("time", "position"))
    said = str(e.value)
    assert "\n" not in said and "'mu' is a friction coefficient" in said and "normal load" in said, said


def test_turns_and_rpm_are_units_of_angle_and_angular_speed():
    from leuven_friction.identify.data import unit_of

    assert unit_of("rev", "position") == pytest.approx((2 * np.pi, "rad"))
    for u in ("rpm", "RPM", "rev/min", "1/min"):
        f, si = unit_of(u, "velocity")
        assert si == "rad/s" and f == pytest.approx(2 * np.pi / 60), u


def test_a_telescope_axis_in_arc_seconds_reads_as_radians(tmp_path):
    from leuven_friction.identify.data import unit_of

    # a second of arc is 1/3600 of a degree: 4.84813681109536e-6 rad (π/648000), a minute 60 of them
    arcsec = 4.84813681109536e-6
    for u in ("arcsec", "arcseconds", "″"):
        assert unit_of(u, "position") == pytest.approx((arcsec, "rad"), rel=1e-14), u
    assert unit_of("arcmin", "position") == pytest.approx((60 * arcsec, "rad"), rel=1e-14)
    assert unit_of("arcsec/s", "velocity") == pytest.approx((arcsec, "rad/s"), rel=1e-14)
    p = tmp_path / "mount.csv"
    t = np.arange(20) * 4.0
    p.write_text(_csv(["time [ms]", "position [arcsec]", "torque [mN*m]"], [t, 15.0 * t / 1000, np.full(20, 3100.0)]))
    rec = load_recording(p)
    assert rec.units["position"] == "rad"
    np.testing.assert_allclose(rec.position[-1], 15.0 * 0.076 * arcsec, rtol=1e-12)  # sidereal rate for 76 ms
    np.testing.assert_allclose(rec.force, 3.1, rtol=1e-12)


def test_a_pitch_bearings_bending_moment_is_its_normal_load_in_newton_metres(tmp_path):
    # a slewing ring's load is its tilting moment: 'bending moment [kN*m]' beside the drive's
    # 'drive torque [kN*m]' is the load, not a second candidate for the force
    p = tmp_path / "pitch.csv"
    t = np.arange(20) * 0.01
    p.write_text(_csv(["t [s]", "pitch angle [deg]", "drive torque [kN*m]", "bending moment [kN*m]"],
                      [t, 40.0 + 0.05 * t, np.full(20, 31.5), np.full(20, 3986.8)]))
    rec = load_recording(p)
    assert rec.columns["force"] == "drive torque [kN*m]" and rec.columns["normal_load"] == "bending moment [kN*m]"
    assert rec.units["normal_load"] == "N*m"
    np.testing.assert_allclose(rec.normal_load, 3.9868e6, rtol=1e-12)
    np.testing.assert_allclose(rec.force, 3.15e4, rtol=1e-12)
    # a friction coefficient times a moment is no friction force: refused in one line
    q = tmp_path / "cof.csv"
    q.write_text(_csv(["time [s]", "position [deg]", "mu", "bending moment [kN*m]"],
                      [t, 40.0 + 0.05 * t, np.full(20, 0.1), np.full(20, 3986.8)]))
    with pytest.raises(DataError, match=r"cof.csv: column 'mu' is a friction coefficient.*'bending moment \[kN\*m\]' is a moment") as e:
        load_recording(q)
    assert "\n" not in str(e.value)

def test_a_row_written_twice_is_dropped_and_a_repeated_time_with_other_values_refused(tmp_path):
    t, x, f = _signals()
    lines = _csv(["time [s]", "position [m]", "force [N]"], [t, x, f]).splitlines()
    for at in (150, 90, 30):  # a logger that wrote three samples twice
        lines.insert(at + 1, lines[at])
    p = tmp_path / "twice.csv"
    p.write_text("\n".join(lines) + "\n")
    rec = load_recording(p)
    assert np.array_equal(rec.time, t) and np.array_equal(rec.position, x) and np.array_equal(rec.force, f)
    assert any("3 row(s) repeating the row before in every value (first at row 32)" in n for n in rec.notes), rec.notes
    # the same time with another reading is no repetition: refused, named by the file's line
    time, _, force = lines[61].split(",")
    lines.insert(62, f"{time},0.5,{force}")
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(DataError, match=r"row 63: time .* does not increase"):
        load_recording(p)


@pytest.mark.parametrize("given", ["-F_coil [mN]", "-F_coil", "- F_coil"])
def test_a_column_named_with_a_leading_minus_is_taken_with_its_sign_turned(tmp_path, given):
    # a sensor mounted the other way: `--columns force=-F_coil` turns the column's sign, with the
    # header's unit still read; named as it is, the column keeps its sign
    from leuven_friction.identify.data import parse_column_mapping

    t, x, f = _signals()
    path = tmp_path / "stage.csv"
    path.write_text(_csv(["t [ms]", "x_interf [nm]", "F_coil [mN]"], (1e3 * t, 1e9 * x, 1e3 * f)))
    turned = load_recording(str(path), columns=parse_column_mapping(f"force={given}"))
    np.testing.assert_allclose(turned.force, -f, rtol=1e-12)
    assert any("sign turned" in n and "F_coil [mN]" in n for n in turned.notes), turned.notes
    kept = load_recording(str(path), columns=parse_column_mapping("force=F_coil"))
    np.testing.assert_allclose(kept.force, f, rtol=1e-12)
    assert not any("sign turned" in n for n in kept.notes)


def test_a_column_whose_unit_is_of_another_kind_is_not_offered_as_a_normal_load():
    from leuven_friction.identify.data import may_be_load

    # a load presses the contact: a force or a moment, or a unit read nowhere here (a clamp's bar,
    # a strain gauge's V, a payload's kg, which the hint then tells how to give in N)
    for column in ("axial load [kN]", "Fn", "tilting moment [kN*m]", "bending moment [Nm]", "clamp [bar]",
                   "strain [V]", "payload [kg]"):
        assert may_be_load(column), column
    # a temperature, a time or a length is no load
    for column in ("winding_temp[degC]", "t_oil [°C]", "housing [K]", "t [ms]", "pos [mm]", "angle [deg]"):
        assert not may_be_load(column), column
    # nor is a motor's current, which drives the axis (a joint's note had offered `motor_current [A]`)
    for column in ("motor_current [A]", "i_q [mA]"):
        assert not may_be_load(column), column


def test_a_mass_is_told_from_a_force_for_the_advice_to_weigh_it():
    from leuven_friction.identify.data import is_mass

    assert is_mass("payload [kg]") and is_mass("m [g]")
    # pound in a load's column is read as pound-force; a force, a moment or no unit is no mass
    for column in ("load [lb]", "Fn [N]", "moment [N*m]", "payload"):
        assert not is_mass(column), column


def test_a_load_at_zero_is_said_to_make_the_load_law_vanish():
    from leuven_friction.identify.diagnose import load_not_pressing

    # a payload's weight alone: 0 N while unloaded, on a third of the samples compared
    load = np.repeat([0.0, 24.5, 49.0], 1000)
    said = load_not_pressing(load, np.ones(3000, bool), "payload_force [N]", "N")
    assert said is not None and "33.3% of the samples compared (down to 0 N)" in said and "never 0" in said, said
    # the whole load (the carriage's weight beside it) presses everywhere: nothing said; nor where
    # the zeros lie outside what is compared
    assert load_not_pressing(load + 49.0, None, "load [N]", "N") is None
    assert load_not_pressing(load, load > 0, "payload_force [N]", "N") is None


def test_a_torque_constant_with_a_decimal_comma_reads_as_with_a_point(tmp_path):
    # a European logger's header and option: '5,9 N' per A is 5.9 N per A, in the header, in
    # --units (whose pairs are separated by commas too) and in a column named with --columns
    from leuven_friction.identify.data import parse_column_mapping, parse_unit_mapping, unit_of

    t, x, f = _signals()
    assert parse_unit_mapping("force=5,9 N, time=ms") == {"force": "5,9 N", "time": "ms"}
    assert parse_unit_mapping("position=mm,force=N") == {"position": "mm", "force": "N"}
    with pytest.raises(DataError, match="got 'force=N,'"):  # a trailing comma is no unit's
        parse_unit_mapping("force=N,")
    # a misnamed signal after a comma is refused as one, not read into the column before it
    with pytest.raises(DataError, match="unknown signal 'load'"):
        parse_column_mapping("friction=Fx,load=Fz")
    # the Greek small mu as the micro sign
    assert unit_of("\u03bcm", "position") == unit_of("\u00b5m", "position") == (1e-6, "m")
    assert parse_column_mapping("force=Motorstrom [5,9 N],time=Zeit") == {"force": "Motorstrom [5,9 N]", "time": "Zeit"}
    p = tmp_path / "stage.csv"  # as such a logger writes it: semicolons, decimal commas
    rows = (";".join(repr(float(c)).replace(".", ",") for c in row) for row in zip(t, x, f))
    p.write_text("\n".join(["time [s];position [m];Motorstrom [5,9 N]", *rows]) + "\n")
    rec = load_recording(p, columns={"force": "Motorstrom [5,9 N]"})
    assert rec.units["force"] == "N" and np.allclose(rec.force, 5.9 * f)
    p.write_text(_csv(["time [s]", "position [m]", "Motorstrom [A]"], [t, x, f]))
    rec = load_recording(p, columns={"force": "Motorstrom [A]"}, units={"force": "5,9 N"})
    assert np.allclose(rec.force, 5.9 * f)


def test_a_motor_current_with_its_torque_constant_as_its_unit_is_read_as_the_applied_torque(tmp_path):
    # logged as the README asks (the constant per A as the unit: 0.11 N·m/A × a gear of 100),
    # the column is the applied torque by its unit, with no --columns; a current in A is still
    # refused as a force with the fix, and a current's reference is no measurement
    t, x, i = _signals()
    p = tmp_path / "wrist.csv"
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [11 N*m]"], [t, x, i]))
    rec = load_recording(p, require=("time", "position", "force"))
    assert rec.columns["force"] == "motor_current [11 N*m]" and rec.units["force"] == "N*m"
    assert np.allclose(rec.force, 11.0 * i)
    rows = (";".join(repr(float(c)).replace(".", ",") for c in row) for row in zip(t, x, i))
    p.write_text("\n".join(["Zeit [s];Winkel [rad];Motorstrom [5,9 N*m]", *rows]) + "\n")  # a European logger's
    assert np.allclose(load_recording(p, require=("time", "position", "force")).force, 5.9 * i)
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current [A]"], [t, x, i]))
    with pytest.raises(DataError, match=r"'motor_current \[A\]' is a current \(A\)"):
        load_recording(p, require=("time", "position", "force"))
    p.write_text(_csv(["time [s]", "angle [rad]", "motor_current_ref [11 N*m]"], [t, x, i]))
    with pytest.raises(DataError, match="no column for force"):
        load_recording(p, require=("time", "position", "force"))


def test_a_position_without_a_unit_moving_faster_than_machines_do_is_said_to_need_its_unit(tmp_path):
    # a stage's position logged in µm (0.1 µm steps, a sine of 20 mm and 2 s: 63 mm/s at most)
    # without a unit: read as metres, as the header says nothing, it moves at 6·10⁴ m/s, and the
    # note says which unit to write; the same motion in metres says nothing of it
    t = np.arange(4000) * 1e-3
    x_m = 0.02 * np.sin(np.pi * t)
    x_um = np.round(x_m * 1e7) / 10
    f = np.sign(np.gradient(x_m)) * 3.0
    p = tmp_path / "stage.csv"
    p.write_text(_csv(["time", "position", "force"], [t, x_um, f]))
    note = load_recording(p, units={"force": "N"}).units_assumed
    import re

    speed = float(re.search(r"moves at ([0-9.e+]+) m/s", note).group(1))
    assert 0.95 * np.pi * 0.02e6 <= speed <= np.pi * 0.02e6 * 1.001 and "'position [um]'" in note, note
    p.write_text(_csv(["time", "position", "force"], [t, x_m, f]))
    assert "moves at" not in load_recording(p, units={"force": "N"}).units_assumed
    # nothing saying linear or rotary (read as rad): the units of both kinds are offered
    p.write_text(_csv(["time", "position", "friction"], [t, x_um, f]))
    note = load_recording(p).units_assumed
    assert "rad/s (99th percentile), faster than machines move" in note, note
    assert "'position [um]'" in note and "'position [mrad]'" in note, note
