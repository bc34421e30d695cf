"""The hidden-effect suite's case list, filtered to kinds of recording (`bench.diagnosis --kinds`)."""

import pytest

from bench.diagnosis import main, suite_cases


def test_one_kind_keeps_its_share_of_the_suite():
    # kinds take turns within each block: of 10 seeds per effect the third kind gets 3, of 20
    # controls 6, of 4 seeds per pair 1 — 4·3 + 6 + 3·1 = 21 tribometer cases
    cases = suite_cases(start=2000, kinds=["tribometer"])
    assert len(cases) == 21
    assert {k for k, _, _ in cases} == {"tribometer"}
    assert sum(not e for _, _, e in cases) == 6 and sum(len(e) == 2 for _, _, e in cases) == 3
    both = suite_cases(start=2000, kinds=["tribometer", "robot_joint"])
    assert len(both) == 21 + len(suite_cases(start=2000, kinds=["robot_joint"]))


def test_an_unknown_kind_is_named():
    with pytest.raises(ValueError, match="unknown kind 'robot'.*robot_joint"):
        suite_cases(kinds=["robot"])


@pytest.mark.parametrize("argv, said", [
    (["--start"], "--start: expected one argument"),
    (["--suite", "--start", "ten"], "--start: invalid int value: 'ten'"),
    (["--suite", "--kinds", "robot"], "unknown kind 'robot'"),
    # a suite's option without --suite would otherwise run the two-recording benchmark instead
    (["--kinds", "tribometer"], "--kinds is an option of the suite: add --suite"),
    (["--bogus"], "unrecognized arguments: --bogus"),
])
def test_a_mistyped_command_line_is_one_line_of_usage_error_and_runs_nothing(argv, said, capsys):
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert said in err and "Traceback" not in err
