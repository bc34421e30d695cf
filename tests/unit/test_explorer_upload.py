"""What the explorer keeps when an upload is no recording: a table of numbers whose columns were
not recognised is shown for the user to choose them; a picture or a page of prose is refused and
the recording that was there stays (a PNG and a text uploaded by mistake had replaced it)."""

from leuven_friction.app.explorer.data_tab import has_numbers


def test_a_table_of_numbers_has_columns_to_choose_from():
    assert has_numbers(b"t,q,tau\n0,1,2\n0.001,1.1,2.2\n")
    assert has_numbers(b"Zeit [s];Weg [mm]\n0,1;2,5\n0,2;2,6\n")  # decimal commas
    assert has_numbers("time [ms]\tposition [arcsec]\n0.0\t12.35\n4.0\t12.40\n".encode())


def test_prose_a_picture_and_a_table_of_words_have_none():
    prose = (b"It was a bright cold day in April, and the clocks were striking thirteen.\n"
             b"Winston Smith, his chin nuzzled into his breast, slipped quickly through the doors.\n")
    assert not has_numbers(prose)
    assert not has_numbers(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\x01\0")
    assert not has_numbers(b"a,b,c\nx,y,z\nu,v,w\n")
    assert not has_numbers(b"")


def test_a_loaders_note_keeps_its_asterisks_and_underscores_in_the_data_tab():
    # Markdown read 'mN*m … N*m' as italics between the asterisks and dropped them
    from leuven_friction.app.explorer.data_tab import as_markdown_text

    assert as_markdown_text("torque [mN*m]: converted from mN*m to N*m") == \
        "torque [mN\\*m]: converted from mN\\*m to N\\*m"
    assert as_markdown_text("tau_motor_a: taken as force") == "tau\\_motor\\_a: taken as force"


def test_the_diagnose_tab_writes_a_torque_as_the_rest_of_the_page_and_keeps_the_candidates_marks():
    # the report is the command line's (files' N*m, option hints); the tab showed N*m beside the
    # Sets tab's N·m
    from leuven_friction.app.explorer.diagnose_tab import report_on_page

    report = ("  model as given                               0.912 (9.12 × noise)\n"
              "      alpha = 0.597 ± 0.057, N0 = 1.2e+04 N*m\n"
              "* normal_load     held out −21.3 %, folds 5/5\n"
              "  nothing named; refit the base with --refit-base")
    shown = report_on_page(report).splitlines()
    assert shown[1] == "      alpha = 0.597 ± 0.057, N0 = 1.2e+04 N·m"
    assert shown[2].startswith("* normal_load")
    assert "--" not in shown[3] and shown[3].startswith("  nothing named")
