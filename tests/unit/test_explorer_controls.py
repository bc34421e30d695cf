"""A parameter's slider, as the browser receives it: its range and tick labels follow a value
typed outside the range (viser sends a slider's marks only through its prop ``_marks``)."""

import math
import socket

import pytest
import viser

from leuven_friction.app.explorer.controls import ParamControl, value_for
from leuven_friction.app.explorer.fields import fields_of
from leuven_friction.model import default_params


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def server():
    s = viser.ViserServer(host="127.0.0.1", port=_free_port())
    yield s
    s.stop()


def _labels(slider) -> list:
    return [(m.value, m.label) for m in slider._impl.props._marks]  # what the browser is sent


def test_tick_labels_follow_the_range_of_a_log_slider(server):
    p = default_params()
    f = next(f for f in fields_of(p) if f.scale == "log")
    applied = []
    c = ParamControl(server.gui, f, value_for(p, f), lambda fld, val, why: applied.append(val))
    lo, hi = c.slider.min, c.slider.max
    far = 10.0 ** (hi + 3)  # three decades above the slider's end
    c.text.value = f"{far:g}"
    assert applied and applied[-1] == pytest.approx(far)
    assert c.slider.max >= math.log10(far) > hi
    exps = [v for v, _ in _labels(c.slider)]
    assert max(exps) > hi and all(c.slider.min <= e <= c.slider.max for e in exps)
    assert all(label == f"1e{int(e)}" for e, label in _labels(c.slider))


def test_tick_labels_are_the_new_range_ends_of_a_linear_slider_after_another_set(server):
    p = default_params()
    f = next(f for f in fields_of(p) if f.scale != "log")
    c = ParamControl(server.gui, f, value_for(p, f), lambda fld, val, why: None)
    c.show(250.0)
    (a, la), (b, lb) = _labels(c.slider)
    assert (a, b) == (pytest.approx(c.slider.min), pytest.approx(c.slider.max)) and a <= 250.0 <= b
    assert la == f"{c.slider.min:.3g}" and lb == f"{c.slider.max:.3g}"
