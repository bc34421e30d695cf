"""Number entry in the explorer: what a person types is read exactly, or refused with a reason."""

import pytest

from leuven_friction.app.explorer.numbers import parse_number
from leuven_friction.model.errors import ParameterError


@pytest.mark.parametrize("text, expected", [
    ("1e-3", 0.001), ("2.5E5", 250000.0), ("1e9", 1e9), ("0,005", 0.005), ("-0,5", -0.5), ("\u22123", -3.0),
    (" 7.7 ", 7.7), ("1,5e3", 1500.0), (".5", 0.5), ("36", 36.0), ("5e+2", 500.0),
])
def test_reads_what_people_type(text, expected):
    assert parse_number(text) == pytest.approx(expected, rel=1e-15)


@pytest.mark.parametrize("text, reason", [
    ("abc", "not a number"), ("", "empty"), ("1e-", "not a number"), ("nan", "not a number"),
    ("1e400", "too large"), ("1,000", "ambiguous"), ("1.000,5", "mixes separators"), ("1,2,3", "mixes separators"),
])
def test_refuses_with_a_reason_naming_the_field(text, reason):
    with pytest.raises(ParameterError, match=reason) as e:
        parse_number(text, "vs⁺")
    assert str(e.value).startswith("vs⁺:")
