"""Tables in and out: the compiled CSV formatter against Python's own formatting, Parquet and
MATLAB files through the recording loader, and simulate --input/--out in each format."""

import numpy as np
import pytest

from leuven_friction.identify.csvformat import rows_bytes
from leuven_friction.identify.data import load_recording, parse_column_mapping, velocity_of
from leuven_friction.identify.errors import DataError
from leuven_friction.identify.io import read_table_file, sniff, write_table


def _tricky_values(rng):
    p = 10.0 ** np.arange(-13, 10)
    ints = rng.integers(10**9, 10**10, size=5000).astype(float)
    return np.concatenate([
        rng.normal(size=50_000) * 10.0 ** rng.uniform(-15, 12, size=50_000),  # incl. Python's fallback range
        p, -p, np.nextafter(p, 0), np.nextafter(p, np.inf),
        9.9999999995 * p, 9.99999999949 * p, 9.99999999951 * p,  # rounding across a power of ten
        ints + 0.5, (ints + 0.5) / 1e3, (ints + 0.5) * 1e-12,  # exact ties at the tenth digit
        [0.0, -0.0, 1.0, -1.0, 0.1, 0.5, 1e-4, 1e-5, 123456789.5, 1234567890.5, np.inf, -np.inf, np.nan],
        rng.integers(-10**6, 10**6, size=2000).astype(float),
    ])


def test_compiled_csv_rows_are_byte_identical_to_python_formatting():
    rng = np.random.default_rng(7)
    v = _tricky_values(rng)
    v = v[: len(v) // 3 * 3].reshape(-1, 3)
    expected = "".join("%.10g,%.10g,%.10g\n" % tuple(r) for r in v).encode()
    assert rows_bytes(v) == expected
    finite = v[np.all(np.isfinite(v) & ((np.abs(v) >= 1e-13) & (np.abs(v) < 1e10) | (v == 0)), axis=1)]
    assert len(finite) > 10_000  # most of it went through the compiled path
    assert rows_bytes(finite) == "".join("%.10g,%.10g,%.10g\n" % tuple(r) for r in finite).encode()


def test_csv_writer_matches_pandas_float_format(tmp_path):
    pd = pytest.importorskip("pandas")
    rng = np.random.default_rng(3)
    cols = {"time": np.arange(1000) * 1e-4, "x": rng.normal(size=1000) * 1e-5, "F": rng.normal(size=1000) * 30}
    write_table(cols, tmp_path / "a.csv")
    pd.DataFrame(cols).to_csv(tmp_path / "b.csv", index=False, float_format="%.10g")
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()
    labelled = {"run": np.array(["a"] * 500 + ["b"] * 500, dtype=object), **cols}
    write_table(labelled, tmp_path / "c.csv")
    pd.DataFrame(labelled).to_csv(tmp_path / "d.csv", index=False, float_format="%.10g")
    assert (tmp_path / "c.csv").read_bytes() == (tmp_path / "d.csv").read_bytes()


def test_sniff_reads_the_header_not_the_comments():
    assert sniff(["# made by rig 4; units SI", "t;q;tau", "0,1;2,5;3"]) == (";", ",")
    assert sniff(["time\tposition", "0\t1"]) == ("\t", ".")
    assert sniff(["time position", "0 1"]) == (r"\s+", ".")


def test_parquet_recording_loads_like_its_csv(tmp_path):
    pytest.importorskip("pyarrow")
    rng = np.random.default_rng(4)
    n = 5000
    cols = {"Time (ms)": np.arange(n) * 0.5, "Angle [mrad]": np.cumsum(rng.normal(size=n)) * 1e-3,
            "Torque [Nm]": rng.normal(size=n)}
    write_table(cols, tmp_path / "r.parquet")
    rec = load_recording(tmp_path / "r.parquet")
    # units from the headers, as for a CSV: ms -> s, mrad -> rad
    np.testing.assert_array_equal(rec.time, cols["Time (ms)"] * 1e-3)
    np.testing.assert_array_equal(rec.position, cols["Angle [mrad]"] * 1e-3)
    np.testing.assert_array_equal(rec.force, cols["Torque [Nm]"])
    assert list(read_table_file(tmp_path / "r.parquet", usecols=lambda c: c.startswith("T")).columns) == [
        "Time (ms)", "Torque [Nm]"]


def test_matlab_file_loads_vectors_structs_and_matrices(tmp_path):
    from scipy.io import savemat

    n = 400
    t = np.arange(n) * 1e-3
    q = np.sin(t)
    tau = np.cos(t)
    savemat(tmp_path / "a.mat", {"t": t, "q": q.reshape(-1, 1), "tau": tau, "note": "rig 3"})
    rec = load_recording(tmp_path / "a.mat")
    np.testing.assert_array_equal(rec.time, t)
    np.testing.assert_array_equal(rec.position, q)
    np.testing.assert_array_equal(rec.force, tau)
    # a struct of signals and an N×2 matrix
    savemat(tmp_path / "b.mat", {"log": {"time": t, "angle": q}, "u": np.column_stack([tau, 2 * tau])})
    df = read_table_file(tmp_path / "b.mat")
    assert set(df.columns) == {"log.time", "log.angle", "u_1", "u_2"}
    np.testing.assert_array_equal(df["u_2"], 2 * tau)
    rec = load_recording(tmp_path / "b.mat", columns={"time": "log.time", "position": "log.angle", "force": "u_1"})
    np.testing.assert_array_equal(rec.force, tau)


def test_unreadable_files_are_data_errors(tmp_path):
    (tmp_path / "bad.mat").write_bytes(b"not a mat file at all" * 10)
    with pytest.raises(DataError, match="bad.mat: not a readable MATLAB"):
        load_recording(tmp_path / "bad.mat")
    for name, content in (("empty.mat", b""), ("short.mat", b"hello\n")):  # scipy: "truncated"
        (tmp_path / name).write_bytes(content)
        with pytest.raises(DataError, match=f"{name}: not a readable MATLAB"):
            load_recording(tmp_path / name)
    (tmp_path / "empty.csv").write_bytes(b"")
    with pytest.raises(DataError, match="empty.csv: the file is empty"):
        load_recording(tmp_path / "empty.csv")
    with pytest.raises(DataError, match="nothere.csv: cannot read"):
        load_recording(tmp_path / "nothere.csv")
    (tmp_path / "bin.csv").write_bytes(b"\x00\x01\x02" * 50)
    with pytest.raises(DataError, match="bin.csv: not a text file"):
        load_recording(tmp_path / "bin.csv")
    # as an upload's bytes too: a picture whose bytes Windows-1252 decodes had been read as a
    # table of one column named '‰PNG'
    with pytest.raises(DataError, match="picture.png: not a text file"):
        load_recording(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\x01\0" + b"x" * 64, name="picture.png")
    # a spreadsheet workbook, by file and as an upload's bytes: said what it is and what to do
    # (before, a workbook's bytes were read as a table with one column named 'PK…')
    import zipfile

    with zipfile.ZipFile(tmp_path / "session.xlsx", "w") as z:
        z.writestr("xl/workbook.xml", "<workbook/>")
    for source, kw in ((tmp_path / "session.xlsx", {}), ((tmp_path / "session.xlsx").read_bytes(), {"name": "up.xlsx"})):
        with pytest.raises(DataError, match=r"xlsx: a zip archive \(an Excel .xlsx.*save the sheet as CSV"):
            load_recording(source, **kw)


@pytest.mark.parametrize("fmt", ["csv", "parquet"])
def test_simulate_input_output_formats(tmp_path, fmt, kuka):
    if fmt == "parquet":
        pytest.importorskip("pyarrow")
    from leuven_friction.app.cli import main
    from leuven_friction.model import simulate_displacement

    n = 3000
    t = np.arange(n) * 1e-3
    x = 1e-4 * np.sin(2 * np.pi * t)
    write_table({"time": t, "position": x}, tmp_path / f"in.{fmt}")
    assert main(["simulate", "--input", str(tmp_path / f"in.{fmt}"), "--out", str(tmp_path / f"out.{fmt}")]) == 0
    out = read_table_file(tmp_path / f"out.{fmt}")
    assert list(out.columns) == ["time", "position", "velocity", "applied_force", "friction_force",
                                 "hysteresis_force", "z"]
    rec = load_recording(tmp_path / f"in.{fmt}")  # a CSV input holds x to ten digits
    F = simulate_displacement(kuka, rec.time, rec.position).friction_force
    # CSV keeps ten significant digits; Parquet keeps the doubles
    np.testing.assert_allclose(out["friction_force"], F, rtol=1e-9 if fmt == "csv" else 0, atol=1e-12)
    assert not list(tmp_path.glob(".*.part"))  # nothing left staged


def test_a_wide_file_reads_only_the_signal_columns(tmp_path):
    rng = np.random.default_rng(5)
    n = 2000
    cols = {"time": np.arange(n) * 1e-3, "position": rng.normal(size=n), "torque": rng.normal(size=n)}
    cols.update({f"channel {i}": rng.normal(size=n) for i in range(30)})
    formats = ["csv"]
    try:
        import pyarrow  # noqa: F401

        formats.append("parquet")
    except ImportError:
        pass
    for fmt in formats:
        write_table(cols, tmp_path / f"wide.{fmt}")
        df = read_table_file(tmp_path / f"wide.{fmt}", usecols=lambda c: not c.startswith("channel"))
        assert list(df.columns) == ["time", "position", "torque"]
        assert len(df.attrs["columns_in_file"]) == 33
        rec = load_recording(tmp_path / f"wide.{fmt}")
        np.testing.assert_allclose(rec.force, cols["torque"], rtol=1e-9)  # CSV: ten digits
        # what was left out is still named, as before
        assert any(note.startswith("ignored columns: channel 0, channel 1") for note in rec.notes)
        narrow = {k: v for k, v in cols.items() if k not in ("position", "torque")}
        write_table(narrow, tmp_path / f"nopos.{fmt}")
        with pytest.raises(DataError, match=r"no column for position \(columns: time, channel 0"):
            load_recording(tmp_path / f"nopos.{fmt}", require=("time", "position"))


def _lab_rows(n=40):
    t = np.arange(n) * 1.0  # ms
    x = 10.0 * np.sin(t / 7.0)  # µm
    f = 300.0 * np.cos(t / 7.0)  # mN
    return t, x, f


def test_european_lab_exports_read_the_same_numbers(tmp_path):
    # the same table as a tab-separated file with decimal commas, in Windows-1252 (µ as one byte),
    # with German headers named by --columns without their units, and as plain UTF-8 CSV
    t, x, f = _lab_rows()
    plain = tmp_path / "plain.csv"
    plain.write_text("Time [ms],Position [µm],Force [mN]\n"
                     + "".join(f"{a:.6g},{b:.6g},{c:.6g}\n" for a, b, c in zip(t, x, f)), encoding="utf-8")
    euro = tmp_path / "euro.tsv"
    euro.write_bytes(("Zeit [ms]\tWeg [µm]\tKraft [mN]\n"
                      + "".join(f"{a:.6g}\t{b:.6g}\t{c:.6g}\n".replace(".", ",") for a, b, c in zip(t, x, f))
                      ).encode("cp1252"))
    ref = load_recording(plain)
    for rec in (load_recording(euro), load_recording(euro, columns={"time": "Zeit", "position": "Weg", "force": "Kraft"})):
        assert np.allclose(rec.time, ref.time) and np.allclose(rec.position, ref.position)
        assert np.allclose(rec.force, ref.force)
        assert np.allclose(rec.position.max(), 1e-5, rtol=1e-3)  # µm read as such: SI metres
        assert any("Windows-1252" in n for n in rec.notes), rec.notes
    with pytest.raises(DataError, match="column 'Zeitstempel' given for time is not in the file"):
        load_recording(euro, columns={"time": "Zeitstempel"})


def test_a_line_with_an_extra_field_and_time_going_back_are_refused_in_the_files_terms(tmp_path):
    t, x, f = _lab_rows()
    rows = [f"{a:g},{b:.6g},{c:.6g}" for a, b, c in zip(t, x, f)]
    ragged = tmp_path / "ragged.csv"
    ragged.write_text("Time [ms],Position [µm],Force [mN]\n" + "\n".join(rows[:9] + [rows[9] + ",5"] + rows[10:]) + "\n")
    with pytest.raises(DataError, match=r"ragged.csv: line 11 has 4 fields, the header 3"):
        load_recording(ragged)
    back = tmp_path / "back.csv"
    rows[20], rows[21] = rows[21], rows[20]
    back.write_text("Time [ms],Position [µm],Force [mN]\n" + "\n".join(rows) + "\n")
    # the message quotes the file's own numbers (ms), not the converted seconds
    with pytest.raises(DataError, match=r"row 23: time 20 does not increase \(previous 21\)"):
        load_recording(back)


def test_ragged_line_only_refuses_a_line_with_more_fields_than_the_header(tmp_path):
    from leuven_friction.identify.io import ragged_line

    def check(name, text, sep=","):
        f = tmp_path / name
        f.write_bytes(text if isinstance(text, bytes) else text.encode())
        return ragged_line(f, sep)

    assert check("ok.csv", "a,b,c\n1,2,3\n4,5,6") is None  # no newline at the end
    assert check("bom.csv", b"\xef\xbb\xbf# note\na,b,c\n1,2,3\n") is None  # a mark, then a comment
    assert check("blank.csv", "a,b,c\r\n1,2,3\r\n   \r\n\r\n4,5,6\r\n") is None  # blank lines, CRLF
    assert check("lead.csv", "   \n\t\na,b,c\n1,2,3\n") is None  # blank lines before the header
    assert check("tail.csv", "a,b,c\n1,2,3 # x,y\n") is None  # a comment after values: not checked
    assert check("short.csv", "a,b,c\n1,2,3\n4,5\n") is None  # fewer fields: the column reader's business
    assert check("quoted.csv", 'a,"b, c",d\n1,2,3\n') is None  # a quote may hold the separator: not checked
    assert check("more.csv", "# c\na,b,c\n1,2,3\n\n4,5,6,7\n") == (5, 4, 3)
    assert check("more.tsv", "a\tb\n1\t2\n3\t4\t5\n", "\t") == (3, 3, 2)
    # the same over block boundaries: the line number counts across blocks
    import leuven_friction.identify.io as io_mod

    body = "a,b,c\n" + "1,2,3\n" * 5000 + "1,2,3,4\n"
    old = io_mod.RAGGED_BLOCK
    io_mod.RAGGED_BLOCK = 1000
    try:
        assert check("long.csv", body) == (5002, 4, 3)
    finally:
        io_mod.RAGGED_BLOCK = old


def test_decimal_mark_of_tab_files_and_thousands(tmp_path):
    assert sniff(["a\tb", "1\t2", "3\t4,5"]) == ("\t", ",")
    assert sniff(["a\tb", "1,234\t2", "5,678\t4"]) == ("\t", ".")  # three digits after each comma: ambiguous
    assert sniff(["a\tb", "1,5\t2.5"]) == ("\t", ".")  # a point somewhere: the comma is no decimal mark


def test_windows_1252_after_the_sniffed_head(tmp_path):
    # UTF-8 as far as the first 64 KiB go, then a byte of Windows-1252 in a column not used
    rows = "".join(f"{i},{0.001 * i:.6g},{np.sin(i):.6g},ok\n" for i in range(6000))
    f = tmp_path / "late.csv"
    f.write_bytes(("Time [ms],Position [mm],Force [N],Bemerkung\n" + rows).encode() + "5999,1,2,Ma\xdf\n".encode("cp1252"))
    with pytest.raises(DataError, match="row 6002: time 5999 does not increase"):
        load_recording(f)  # read through to the last line (which repeats a time stamp)


@pytest.mark.parametrize("header, signals", [
    # a motor torque and a measured friction named as loggers name them, with the unit as a last word
    ("t [s],q [rad],tau_motor [N*m]", {"time": 1.0, "position": 1.0, "force": 1.0}),
    # a known name followed by its unit as a word: normal_kN is the normal load in kN
    ("t_ms,x_mm,F_friction [mN],normal_kN", {"time": 1e-3, "position": 1e-3, "friction": 1e-3, "normal_load": 1e3}),
    # a force word beside a position word: taken as the force once the position has a column
    ("t,q,F_x [N]", {"time": 1.0, "position": 1.0, "force": 1.0}),
    ("time,joint_position [deg],torque_cmd [N*m]", {"time": 1.0, "position": np.pi / 180, "force": 1.0}),
])
def test_columns_are_recognised_by_the_words_of_their_names(tmp_path, header, signals):
    # column 0 (time) holds i, column k the numbers (i + 1)·(k + 1)
    path = tmp_path / "words.csv"
    width = len(header.split(","))
    path.write_text(header + "\n" + "".join(f"{i}," + ",".join(f"{(i + 1) * (k + 1)}" for k in range(1, width)) + "\n"
                                            for i in range(40)))
    rec = load_recording(path)
    assert set(rec.columns) == set(signals)
    i = np.arange(40.0)
    for k, (sig, factor) in enumerate(signals.items()):
        # in SI by the unit its header writes, in brackets or as the last word of its name
        expected = (i if k == 0 else (i + 1) * (k + 1)) * factor
        np.testing.assert_allclose(getattr(rec, sig), expected, rtol=1e-12)


def test_two_columns_that_could_each_be_a_signal_are_not_guessed_between(tmp_path):
    path = tmp_path / "two.csv"
    path.write_text("t [s],q [rad],tau_motor [N*m],tau_load [N*m]\n" + "".join(f"{i},{i},{i},{i}\n" for i in range(20)))
    rec = load_recording(path)
    assert rec.force is None
    assert any("tau_motor [N*m], tau_load [N*m] could each be force: none taken" in n for n in rec.notes), rec.notes
    # a reference is not the measured position
    ref = tmp_path / "ref.csv"
    ref.write_text("t [s],q_ref [rad],tau [N*m]\n" + "".join(f"{i},{i},{i}\n" for i in range(20)))
    with pytest.raises(DataError, match=r"no column for position \(columns: t \[s\], q_ref \[rad\], tau \[N\*m\]"):
        load_recording(ref, require=("time", "position"))


def test_a_unit_of_another_kind_is_refused_naming_the_column(tmp_path):
    path = tmp_path / "kind.csv"
    path.write_text("time [s],position [s],force [N]\n" + "".join(f"{i},{i},{i}\n" for i in range(20)))
    with pytest.raises(DataError, match=r"column 'position \[s\]' was taken as position, but its unit 's' is a "
                                        r"time unit; position needs m or rad"):
        load_recording(path)


@pytest.mark.parametrize("unit, factor", [("N·m", 1.0), ("N*m", 1.0), ("N.m", 1.0), ("N m", 1.0), ("Nm", 1.0),
                                          ("N·mm", 1e-3), ("N*mm", 1e-3), ("Nmm", 1e-3), ("mN·m", 1e-3),
                                          ("mN*m", 1e-3), ("mNm", 1e-3), ("kN·m", 1e3)])
def test_a_torque_reads_in_the_ways_it_is_written(tmp_path, unit, factor):
    # a torque is a force times a length however the product is spelt: 250 in the file is
    # 250·(force unit)·(length unit) in N·m
    path = tmp_path / "torque.csv"
    path.write_text(f"time [ms],angle [deg],torque [{unit}]\n" + "".join(f"{i},{0.1 * i},250\n" for i in range(20)))
    rec = load_recording(path)
    assert rec.units["force"] == "N*m"
    np.testing.assert_allclose(rec.force, 250.0 * factor, rtol=1e-12)
    np.testing.assert_allclose(rec.position[1], 0.1 * np.pi / 180, rtol=1e-12)
    np.testing.assert_allclose(rec.time[1], 1e-3, rtol=1e-12)


def test_an_unknown_unit_is_refused_with_the_known_ones(tmp_path):
    path = tmp_path / "odd.csv"
    path.write_text("time [s],position [furlong],force [N]\n" + "".join(f"{i},{i},{i}\n" for i in range(20)))
    with pytest.raises(DataError, match=r"column 'position \[furlong\]': unknown unit 'furlong' \(known: s, ms.*N·mm"):
        load_recording(path)


def test_a_unit_given_by_option_is_named_as_the_options_and_overriding_a_header_is_said(tmp_path):
    # a mistake in --units is fixed in the option, not in the header the message used to name;
    # an option read over a header's unit is taken as asked and said (a header's ms read as s
    # had made a 106 s session 29 hours long without a word)
    path = tmp_path / "joint.csv"
    path.write_text("time [ms],angle [deg],torque [mN*m]\n" + "".join(f"{i},{0.1 * i},{i}\n" for i in range(20)))
    with pytest.raises(DataError, match=r"--units force=mN\*n: unknown unit 'mN\*n'"):
        load_recording(path, units={"force": "mN*n"})
    with pytest.raises(DataError, match=r"unit 'deg/s' \(from --units\) is an angular speed unit; .*correct --units "
                                        r"position=…$"):
        load_recording(path, units={"position": "deg/s"})
    with pytest.raises(DataError, match=r"its unit 'mN\*m' is a torque unit; .*correct the header's unit"):
        load_recording(path, columns={"position": "torque [mN*m]", "force": "angle [deg]"})
    rec = load_recording(path, units={"time": "s"})
    np.testing.assert_allclose(rec.time[1], 1.0)  # as asked
    assert "time [ms]: read in s as --units asks, not in the header's ms" in rec.notes, rec.notes
    assert not any("--units asks" in n for n in load_recording(path, units={"time": "ms"}).notes)


def test_an_encoder_logged_in_counts_reads_with_the_size_of_a_count_as_its_unit(tmp_path):
    # 1234 counts of 50 nm are 61.7 µm; of 0.001° they are 1.234° (the radian by hand)
    rows = "".join(f"{i},{1234 + i},{i}\n" for i in range(20))
    for unit, count in (("50 nm", 50e-9), ("5e-8 m", 5e-8), ("0.001 deg", 0.001 * np.pi / 180)):
        path = tmp_path / "enc.csv"
        path.write_text(f"time [ms],encoder [{unit}],force [mN]\n" + rows)
        rec = load_recording(path)
        np.testing.assert_allclose(rec.position[:2], [1234 * count, 1235 * count], rtol=1e-12)
    # a count without its size is refused, saying what to write, whether or not the column is named
    path.write_text("time [ms],encoder [counts],force [mN]\n" + rows)
    with pytest.raises(DataError, match=r"column 'encoder \[counts\]' counts steps without saying their size: write "
                                        r"the size of one step as its unit, e.g. 'encoder \[50 nm\]'"):
        load_recording(path, require=("time", "position"))
    with pytest.raises(DataError, match=r"unit 'counts' counts steps without saying their size"):
        load_recording(path, columns={"position": "encoder [counts]"})


def test_columns_a_logger_adds_are_not_taken_by_their_words(tmp_path):
    # a file that loaded before the names' words were read loads the same: a controller's friction
    # model, a reference, a current, a load cell, a motor temperature with blanks and a sample
    # index are none of the signals
    head = ("time,position,torque,friction_model,friction_comp,x_ref,q_cmd,force_ref,motor_current,motor_speed,"
            "load_cell,temperature_motor,status,index,sample")
    rows = "".join(f"{i},{i},{i}," + ",".join("" if k == 9 and i % 3 else str(i) for k in range(12)) + "\n"
                   for i in range(30))
    path = tmp_path / "logger.csv"
    path.write_text(head + "\n" + rows)
    rec = load_recording(path)
    assert rec.columns == {"time": "time", "position": "position", "force": "torque"}
    assert rec.friction is None and rec.velocity is None and rec.normal_load is None and rec.temperature is None


def test_a_signal_can_be_taken_from_no_column(tmp_path):
    # a tachometer column the user does not trust: velocity=- leaves it out, though its name is
    # recognised, and the velocity is then differentiated from the position
    path = tmp_path / "tacho.csv"
    path.write_text("time [s],position [rad],velocity [rad/s],torque [N*m],normal [N]\n"
                    + "".join(f"{0.01 * i},{np.sin(0.01 * i)},{7.0},{i},{5}\n" for i in range(50)))
    assert parse_column_mapping("velocity=-,force=torque [N*m]") == {"velocity": None, "force": "torque [N*m]"}
    rec = load_recording(path, columns=parse_column_mapping("velocity=-"))
    assert rec.velocity is None and "velocity" not in rec.columns
    assert rec.ignored == ["velocity [rad/s]"]
    assert rec.columns == {"time": "time [s]", "position": "position [rad]", "force": "torque [N*m]",
                           "normal_load": "normal [N]"}
    np.testing.assert_allclose(velocity_of(rec)[5:-5], np.cos(0.01 * np.arange(50))[5:-5], atol=0.006)  # not 7
    # a word-recognised name is left alone too, and a required signal taken from no column is refused
    words = tmp_path / "words.csv"
    words.write_text("t [s],q [rad],tau_motor [N*m]\n" + "".join(f"{i},{i},{i}\n" for i in range(20)))
    assert load_recording(words, columns={"force": None}).force is None
    with pytest.raises(DataError, match=r"words.csv: no column for time"):
        load_recording(words, columns={"time": None})


def test_a_unit_taken_from_a_name_is_said_as_the_header_spells_it(tmp_path):
    path = tmp_path / "u.csv"
    path.write_text("time_ms,x_mm,friction_mN\n" + "".join(f"{i},{i * 2},{i * 3}\n" for i in range(40)))
    rec = load_recording(path)
    assert "friction_mN: converted from mN to N" in rec.notes and "x_mm: converted from mm to m" in rec.notes
    np.testing.assert_allclose(rec.friction, 3e-3 * np.arange(40.0), rtol=1e-12)


def _loaded(tmp_path, name: str, text: str, as_upload: bool):
    """``text`` loaded as an upload's bytes, or from a file written with it."""
    if as_upload:
        return load_recording(text.encode(), name=name)
    f = tmp_path / name
    f.write_text(text)
    return load_recording(f)


@pytest.mark.parametrize("as_upload", [False, True])
def test_a_bad_cell_is_named_by_the_line_an_editor_shows(tmp_path, as_upload):
    # a European logger's export: two # lines above the header, semicolons, decimal commas
    head = "# Messschrieb Schlitten X\n# Datum: 12.03.2024; 1 kHz\nZeit [ms];Position [mm];Kraft [kN]\n"
    rows = [f"{i},5;{0.01 * i:.3f};0,{300 + i:04d}".replace(".", ",") for i in range(200)]

    def load(name, body):
        return _loaded(tmp_path, name, head + "\n".join(body) + "\n", as_upload)

    rec = load("ok.csv", rows)
    assert rec.force[3] == pytest.approx(30.3) and rec.time[1] == pytest.approx(1.5e-3)  # kN, ms
    # a word in a column of decimal commas: the word and its line (3 lines above the first row),
    # not the column's first number, which the reader left as text
    word = rows[:50] + [rows[50].rsplit(";", 1)[0] + ";ERR"] + rows[51:]
    with pytest.raises(DataError, match=r"column 'Kraft \[kN\]' row 54: 'ERR' is not a finite number$"):
        load("word.csv", word)
    # a blank line inside the data is skipped by the reader but counted as a line: the row
    # after the misplaced one (line 105) is on line 106
    back = rows[:100] + [""] + [rows[120]] + rows[101:]
    with pytest.raises(DataError, match=r"row 106: time 101.5 does not increase \(previous 120.5\)"):
        load("back.csv", back)


@pytest.mark.parametrize("as_upload", [False, True])
def test_an_instruments_notes_above_the_header_are_skipped_and_lines_still_named_as_an_editor_shows(tmp_path,
                                                                                                 as_upload):
    # a tribometer's export: notes of its own above the names of its columns, not # comments (a
    # comma in the first, none in the others), a blank line, then the table in semicolons and
    # decimal commas. It was refused: "line 2 has 4 fields, the header 2"
    head = ("Instrument: UMT TriboLab, reciprocating module (S/N 41-0273)\nOperator: K. Vermeulen\nLoad: 10 N\n"
            "Sample rate: 1000 Hz\n\nTime [s];Stroke position [mm];Ff [N];Fn [N]\n")
    rows = [f"{1e-3 * i:.3f};{0.5 * np.sin(0.05 * i):.5f};{0.12 * np.cos(0.05 * i):.4f};10,0".replace(".", ",")
            for i in range(300)]

    def load(name, body, lead=head):
        return _loaded(tmp_path, name, lead + "\n".join(body) + "\n", as_upload)

    rec = load("export.csv", rows)
    plain = load("plain.csv", rows, lead="Time [s];Stroke position [mm];Ff [N];Fn [N]\n")
    assert np.array_equal(rec.time, plain.time) and np.array_equal(rec.friction, plain.friction)
    assert len(rec.time) == 300 and rec.position[10] == pytest.approx(0.5e-3 * np.sin(0.5), abs=1e-8)  # mm
    assert any("line(s) 1–5 before the header (line 6)" in n for n in rec.notes), rec.notes
    assert not any("before the header" in n for n in plain.notes), plain.notes
    # a word in the 41st row: line 47, the notes and the blank line counted as an editor counts them
    word = rows[:40] + [rows[40].rsplit(";", 1)[0] + ";ERR"] + rows[41:]
    with pytest.raises(DataError, match=r"column 'Fn \[N\]' row 47: 'ERR' is not a finite number$"):
        load("word.csv", word)
    # a line with a field more than the header, named by its line (a file's reader counts them,
    # an upload's is pandas' own words)
    extra = rows[:60] + [rows[60] + ";7"] + rows[61:]
    with pytest.raises(DataError, match=r"line 67 has 5 fields, the header 4|Expected 4 fields in line 67, saw 5"):
        load("extra.csv", extra)


def _axis_file(tmp_path):
    # a feed axis as its logger writes it: the reference position beside the measured one
    rng = np.random.default_rng(3)
    t = np.arange(4000) * 1e-3
    # mm: strokes at 7.31 mm/s, one a second, with 50 ms ramps of constant acceleration
    v = 7.31 * np.sign(np.sin(np.pi * (t + 0.5e-3))) * np.minimum(1.0, np.minimum(t % 1.0, 1.0 - t % 1.0) / 0.05)
    ref = np.cumsum(v) * 1e-3
    pos = np.round((ref + 0.003 * rng.standard_normal(t.size)) / 2e-4) * 2e-4
    force = 45.0 * np.tanh(np.gradient(ref, t) / 2.0) + 0.3 * rng.standard_normal(t.size)
    p = tmp_path / "axis.csv"
    p.write_text("time [ms],pos_ref [mm],pos [mm],force_cmd [N]\n"
                 + "".join(f"{a * 1e3:.1f},{b:.6f},{c:.4f},{d:.4f}\n" for a, b, c, d in zip(t, ref, pos, force)))
    return p


def test_a_reference_named_as_the_position_is_taken_and_said_a_commanded_force_is_not(tmp_path):
    p = _axis_file(tmp_path)
    rec = load_recording(p, columns={"position": "pos_ref"})
    assert rec.columns["position"] == "pos_ref [mm]"
    assert any("pos_ref [mm]: taken as position as asked, though its name reads as a reference" in n for n in rec.notes)
    rec = load_recording(p, columns={"force": "force_cmd"})  # a commanded force is the one applied
    assert not any("as asked" in n for n in rec.notes)


def test_a_position_without_noise_is_said_to_be_no_measurement_naming_the_columns_not_read(tmp_path):
    from leuven_friction.identify.segment import prepare

    p = _axis_file(tmp_path)
    said = [n for n in prepare(load_recording(p, columns={"position": "pos_ref"})).notes if "no measurement noise" in n]
    assert len(said) == 1 and "not read: pos [mm]" in said[0]
    assert not [n for n in prepare(load_recording(p)).notes if "no measurement noise" in n]


def test_help_of_a_command_that_reads_a_recording_says_how_columns_and_units_are_read(capsys):
    from leuven_friction.app.cli import main

    with pytest.raises(SystemExit):
        main(["fit", "--help"])
    out = capsys.readouterr().out
    assert "friction_torque" in out and "'pos [mm]'" in out and "lbf" in out and "q_ref" in out
    # the sign-turning form of the mapping, which the sign hints of `fit` point to
    assert "force=-F takes column F with its sign turned" in " ".join(out.split())


def test_a_grid_finer_than_the_noise_is_the_files_digits_not_an_encoder(tmp_path):
    # a capacitive sensor's 20 nm of noise, written to 10⁻³ µm: every reading lies on a 10⁻⁹ m
    # grid, which had been taken for an encoder (at 10⁻¹⁰ m, x_noise 2.9·10⁻¹¹, and the transition curve
    # moved by 5 σ against the same file written with more digits); an encoder's readings,
    # whose steps the noise does not span, stay quantised
    from leuven_friction.identify.segment import Gaussian, Quantized, detect_noise, noise_sd

    rng = np.random.default_rng(8)
    t = np.arange(40000) * 5e-4
    x_um = 1500.0 * np.clip(2.0 * np.sin(2 * np.pi * 0.2 * t), -1.0, 1.0)  # strokes with dwells
    for name, x, noisy in (("capacitive", x_um + 0.02 * rng.standard_normal(t.size), True),
                           ("encoder", np.round(x_um / 0.1) * 0.1, False)):
        p = tmp_path / f"{name}.tsv"
        p.write_text("t [s]\tx [um]\tFt [N]\n" + "".join(f"{a:.4f}\t{b:.3f}\t1.0\n" for a, b in zip(t, x)))
        noise = detect_noise(load_recording(p, columns={"friction": "Ft [N]"}).position)
        if noisy:
            assert isinstance(noise, Gaussian) and noise_sd(noise) == pytest.approx(2e-8, rel=0.1), noise
        else:
            assert isinstance(noise, Quantized) and noise.step == pytest.approx(1e-7, rel=1e-6), noise


def test_an_encoder_written_in_degrees_to_nine_decimals_is_an_encoder(tmp_path):
    # a 26-bit encoder (5.364·10⁻⁶ deg a count) logged in degrees to 9 decimals, slewing at up
    # to 2 deg/s at 500 Hz (750 counts a sample): the smallest step carries the file's rounding
    # (8·10⁻⁵ of it), which the fast steps multiplied off the grid, and the position was read as
    # one without noise (x_noise 10⁻¹¹ rad). The grid is told on steps of up to 50 counts
    from leuven_friction.identify.segment import Quantized, detect_noise

    count = 360.0 / 2**26
    t = np.arange(60000) * 2e-3
    deg = 120.0 + np.cumsum(np.where(t < 60.0, 0.004 * np.sin(t) ** 2, 1e-5 * np.sin(0.5 * t)))
    p = tmp_path / "az.csv"
    p.write_text("t [ms],az_angle [deg],torque [N*m]\n"
                 + "".join(f"{a * 1e3:.1f},{b:.9f},1.0\n" for a, b in zip(t, np.floor(deg / count) * count)))
    noise = detect_noise(load_recording(p).position)
    assert isinstance(noise, Quantized) and noise.step == pytest.approx(count * np.pi / 180, rel=1e-4), noise


@pytest.mark.parametrize("times, says", [
    ([0.0, 0.1, 0.2, 0.3, 0.0, 0.1, 0.2] + [0.3 + 0.1 * i for i in range(1, 10)],
     r"row 6: time 0.0 does not increase \(previous 0.3\): the clock goes back: two logs in one file\? split it there"),
    ([0.0, 0.1, 0.2, 0.2] + [0.3 + 0.1 * i for i in range(12)],
     r"row 5: time 0.2 does not increase \(previous 0.2\): the same time as the row before, with other values"),
])
def test_time_going_back_is_said_as_two_logs_repeated_time_as_a_repeated_row(tmp_path, times, says):
    # a logger restarted and appended: "sort the file" was the wrong fix for it
    p = tmp_path / "two.csv"
    p.write_text("time,position,force\n" + "".join(f"{t:g},{i},{i}\n" for i, t in enumerate(times)))
    with pytest.raises(DataError, match=says):
        load_recording(p)


def test_a_word_deep_in_a_long_column_gives_the_one_line_error_alone(tmp_path, recwarn):
    # pandas reads a long file chunk by chunk; a word in a late chunk made it warn of mixed types
    # on the console before the error that names the cell
    p = tmp_path / "long.tsv"
    rows = [f"{i * 1e-3:.3f}\t{i * 1e-6:.6f}\t{0.5 + 1e-4 * (i % 7):.4f}" for i in range(300000)]
    rows[250000] = rows[250000].rsplit("\t", 1)[0] + "\tovfl"
    p.write_text("t [s]\tx [mm]\tFt [N]\n" + "\n".join(rows) + "\n")
    with pytest.raises(DataError, match=r"column 'Ft \[N\]' row 250002: 'ovfl' is not a finite number"):
        load_recording(p)
    assert not [w for w in recwarn if "mixed types" in str(w.message)]


def test_a_tribometers_tangential_force_beside_its_normal_force_is_its_friction(tmp_path):
    p = tmp_path / "tribo.tsv"
    p.write_text("t [s]\tx [um]\tFt [N]\tFn [N]\n" + "".join(f"{i * 1e-3}\t{i}\t0.5\t10\n" for i in range(20)))
    rec = load_recording(p)
    assert rec.columns == {"time": "t [s]", "position": "x [um]", "friction": "Ft [N]", "normal_load": "Fn [N]"}


def test_a_temperature_logged_slower_leaves_its_rows_between_readings_empty(tmp_path):
    # a 1 Hz thermocouple in a 100 Hz log: its cell is empty between readings, which is no
    # error; its readings are kept where they are, and a cell that is text still is one
    rows = "".join(f"{0.01 * i},{1e-3 * i},{2.0},{'' if i % 100 else 20 + i / 100}\n" for i in range(400))
    path = tmp_path / "slow_temp.csv"
    path.write_text("time [s],position [m],force [N],temperature [degC]\n" + rows)
    rec = load_recording(path)
    assert np.isfinite(rec.temperature).sum() == 4
    np.testing.assert_allclose(rec.temperature[::100], [20.0, 21.0, 22.0, 23.0])
    assert "temperature [degC]: 396 of 400 rows empty (a slower logger): only its readings are used" in rec.notes
    # the position is not let off the same way: a row without one is no sample, left out with
    # every other signal's cell in it (a logger's dropout), and said
    path.write_text("time [s],position [m],force [N],temperature [degC]\n" + rows.replace(",0.002,", ",,", 1))
    rec = load_recording(path)
    assert len(rec.time) == 399 and 0.02 not in rec.time and np.all(np.diff(rec.time) > 0)
    np.testing.assert_allclose(rec.position, rec.time / 10.0)  # every row's own position, none shifted
    assert any("1 row(s) with an empty cell left out ('position [m]' in 1, the first at row 4)" in n
               for n in rec.notes), rec.notes
    path.write_text("time [s],position [m],force [N],temperature [degC]\n" + rows.replace(",20.0\n", ",warm\n", 1))
    with pytest.raises(DataError, match=r"column 'temperature \[degC\]' row 2: 'warm' is not a finite number"):
        load_recording(path)
    # a temperature column with no reading at all is left out, and said
    path.write_text("time [s],position [m],force [N],temperature [degC]\n"
                    + "".join(f"{0.01 * i},{1e-3 * i},{2.0},\n" for i in range(50)))
    rec = load_recording(path)
    assert rec.temperature is None and "temperature [degC]: every cell empty: not read" in rec.notes


@pytest.mark.parametrize("header, asked", [
    ("t_s,position_mm,force_kN", "force=-force_kN"),
    ("t_s,position_mm,force_kN", "position=-position_mm"),
    ("t/s,position/mm,force/kN", "force=-force/kN"),
    ("t_s,position_mm,force_kN", "force=force_kN"),
])
def test_a_column_named_as_asked_reads_its_unit_from_its_name(tmp_path, header, asked):
    # a guideway's force in kN turned with --columns, as the refusal of its sign advises, was
    # read as N: a thousand times too small, with only a note; named as asked, a column's unit
    # written as its name's last word is read as when it is recognised by its words
    path = tmp_path / "units_in_names.csv"
    path.write_text(header + "\n" + "".join(f"{0.001 * i},{0.5 * i},{0.2}\n" for i in range(30)))
    rec = load_recording(path, columns=parse_column_mapping(asked))
    sign = {"force": -1.0 if "force=-" in asked else 1.0, "position": -1.0 if "position=-" in asked else 1.0}
    np.testing.assert_allclose(rec.force, sign["force"] * 200.0)  # 0.2 kN
    np.testing.assert_allclose(rec.position[:3], sign["position"] * np.array([0.0, 0.5e-3, 1e-3]))  # mm
    assert not rec.units_assumed and rec.units["force"] == "N" and rec.units["position"] == "m"


def test_the_sign_mend_turns_a_column_back_where_it_was_taken_turned(tmp_path):
    # a force taken with its sign turned (--columns force=-F) and found the wrong way round is
    # mended by taking the column as it is, not by turning it again
    path = tmp_path / "r.csv"
    path.write_text("t [s],x [m],F [N]\n" + "".join(f"{i * 0.01},{i * 1e-4},{(-1) ** i}\n" for i in range(20)))
    as_is = load_recording(path)
    assert as_is.sign_mend("force") == '--columns "force=-F [N]"'
    turned = load_recording(path, columns={"force": "-F"})
    assert turned.force[0] == -1.0 and turned.sign_mend("force") == '--columns "force=F [N]"'


def test_an_angle_in_degrees_spelled_out_is_read_and_an_unknown_unit_is_named_at_once(tmp_path):
    # a valve's 'stem_angle [degrees]' was told "no column for position", and only once named with
    # --columns that its unit was unknown; 'degree(s)' is now a spelling of deg
    rows = "".join(f"{i * 0.01},{i * 0.5},{(-1) ** i}\n" for i in range(20))
    ok = tmp_path / "deg.tsv"
    ok.write_text("time [s],stem_angle [degrees],stem_torque [N*m]\n" + rows)
    rec = load_recording(ok)
    assert rec.units["position"] == "rad" and rec.position[1] == pytest.approx(0.5 * np.pi / 180)
    bad = tmp_path / "furlong.tsv"
    bad.write_text("time [s],stem_angle [furlong],stem_torque [N*m]\n" + rows)
    with pytest.raises(DataError) as e:
        load_recording(bad, require=("time", "position"))
    assert "column 'stem_angle [furlong]' reads as position by its name, but its unit 'furlong' is not known" in str(e.value), str(e.value)
    # where two columns could each be the position, that is what is said (not the third's unit)
    two = tmp_path / "two.csv"
    two.write_text("time [s],pos_a [mm],pos_b [mm],q_flow [l/min],F [N]\n"
                   + "".join(f"{i * 0.01},{i},{i},1,{(-1) ** i}\n" for i in range(20)))
    with pytest.raises(DataError) as e:
        load_recording(two, require=("time", "position"))
    assert "could each be position" in str(e.value) and "is not known" not in str(e.value), str(e.value)


def test_a_current_named_as_the_load_is_told_it_is_no_load(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text("time [s],x [m],F [N],motor_current [A]\n" + "".join(f"{i * 0.01},{i * 1e-4},1,2\n" for i in range(20)))
    with pytest.raises(DataError) as e:
        load_recording(path, columns={"normal_load": "motor_current [A]"})
    msg = str(e.value)
    assert "is a current, not a load" in msg and "--columns normal_load=" in msg and "\n" not in msg, msg


def test_a_current_whose_unit_is_the_last_word_of_its_name_is_no_force(tmp_path):
    # a haptic joint made apart logged `current_A`: named as the force, it was read in N·m
    path = tmp_path / "c.tsv"
    path.write_text("t_s\tangle_rad\tcurrent_A\n" + "".join(f"{i * 0.01}\t{i * 1e-4}\t{0.4 * (-1) ** i}\n"
                                                           for i in range(20)))
    for columns in ({"force": "current_A"}, {"friction": "current_A"}):
        with pytest.raises(DataError) as e:
            load_recording(path, columns=columns)
        msg = str(e.value)
        assert "column 'current_A'" in msg and "a motor current is no force" in msg, msg
        assert "'current_A [0.12 N*m]'" in msg and '--units "force=0.12 N*m"' in msg and "\n" not in msg, msg
    # not named: the reason none was taken as the force (`fit`'s message) says it too
    why = load_recording(path).unrecognised("force", "friction")
    assert "column 'current_A' is a current (A)" in why and "per A as its unit" in why, why


def test_units_given_apart_from_the_file_read_it_as_its_headers_would(tmp_path):
    rows = [(i * 0.001, i * 2e-3, 0.4 * np.sin(i)) for i in range(50)]
    plain = tmp_path / "p.tsv"
    plain.write_text("t_ms\tangle\tcurrent_A\n" + "".join(f"{t * 1e3}\t{x}\t{c}\n" for t, x, c in rows))
    from leuven_friction.identify.data import parse_unit_mapping

    units = parse_unit_mapping("force=0.025 N*m, position=mrad")
    rec = load_recording(plain, columns={"force": "current_A"}, units=units)
    assert np.allclose(rec.force, [0.025 * c for *_, c in rows], rtol=1e-12)  # the torque constant × the current
    assert np.allclose(rec.position, [1e-3 * x for _, x, _ in rows], rtol=1e-12)
    assert np.allclose(rec.time, [t for t, *_ in rows], rtol=1e-9)  # its own `_ms` word still read
    for bad, said in (("force", "expected signal=unit"), ("speed=mm/s", "unknown signal 'speed'"),
                      ("force=", "no unit given for force")):
        with pytest.raises(DataError, match=said):
            parse_unit_mapping(bad)


def test_a_carriage_column_is_the_position():
    # a pick-and-place axis made apart logged `carriage [mm]`; it had to be named on every call
    text = "time [ms],carriage [mm],motor_force [N]\n" + "".join(f"{i},{i * 0.01},1.5\n" for i in range(20))
    rec = load_recording(text, name="axis.csv")
    assert rec.columns["position"] == "carriage [mm]"
    assert np.allclose(rec.position, [i * 1e-5 for i in range(20)], rtol=1e-12)


def test_a_few_empty_cells_are_dropouts_left_out_and_many_are_a_column_refused(tmp_path):
    # 1 kHz of a force ramp: 5 rows (0.5 %) with an empty force cell are a logger's dropouts, the
    # rows left out, the others kept as written; 40 (4 %) are no dropouts: refused, naming the
    # column, its first empty row (the file's line) and what to check, and nothing is read
    t = np.arange(1000) * 1e-3
    lines = [f"{ti:.3f},{1e-4 * ti:.8f},{10.0 * ti:.4f}" for ti in t]
    few = [ln if i not in (100, 101, 102, 500, 900) else ln.rsplit(",", 1)[0] + "," for i, ln in enumerate(lines)]
    path = tmp_path / "dropouts.csv"
    path.write_text("time [s],position [m],force [N]\n" + "\n".join(few) + "\n")
    rec = load_recording(path)
    assert len(rec.time) == 995
    np.testing.assert_allclose(rec.force, 10.0 * rec.time, atol=1e-4)
    assert any("5 row(s) with an empty cell left out ('force [N]' in 5, the first at row 102)" in n for n in rec.notes)
    # a clock going back after a dropout is quoted from its own line's cells
    back = list(few)
    back[700] = "0.650," + back[700].split(",", 1)[1]
    path.write_text("time [s],position [m],force [N]\n" + "\n".join(back) + "\n")
    with pytest.raises(DataError, match=r"row 702: time 0.65 does not increase \(previous 0.699\)"):
        load_recording(path)
    many = [ln if i % 25 else ln.rsplit(",", 1)[0] + "," for i, ln in enumerate(lines)]
    path.write_text("time [s],position [m],force [N]\n" + "\n".join(many) + "\n")
    with pytest.raises(DataError, match=r"dropouts.csv: column 'force \[N\]' row 2: is empty or NaN \(40 such rows\): "
                                        r"40 of 1000 rows .* over the 1% left out"):
        load_recording(path)
