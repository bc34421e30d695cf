"""The explorer's saved session and its pure figure/field helpers (no server, no browser)."""

import json

import numpy as np
import pytest

from leuven_friction.app import plots
from leuven_friction.app.explorer.fields import fields_of, sanity_warnings, with_values
from leuven_friction.app.explorer.session import Session, SessionStore
from leuven_friction.model import default_params
from leuven_friction.model.errors import ParameterError


def test_session_round_trip(tmp_path):
    store = SessionStore(tmp_path)
    p0 = default_params()
    p1 = with_values(p0, {"stribeck.positive.Fc": 20.0})
    s = Session(params=p1, recording_name="run.tsv", recording_bytes=b"t\tx\n0\t1\n", mapping={"position": "x"},
                flip_friction=True, model_view={"overlay": "lugre"})
    s.add("start", p0)
    s.add("your edits", p1)
    assert store.save(s) is None
    back, why = SessionStore(tmp_path).load()
    assert why is None
    assert back.params.stribeck.positive.Fc == 20.0
    assert [e.label for e in back.history] == ["start", "your edits"]
    assert back.history[0].params.stribeck.positive.Fc == 27.0  # Table I
    assert back.recording_bytes == b"t\tx\n0\t1\n" and back.mapping == {"position": "x"} and back.flip_friction is True


def test_unreadable_session_is_said_not_hidden(tmp_path):
    (tmp_path / "session.json").write_text(json.dumps({"params": {"model": "leuven", "n": "many"}}))
    s, why = SessionStore(tmp_path).load()
    assert s is None and "session.json" in why and "cannot be read" in why
    assert SessionStore(tmp_path / "nothing").load() == (None, None)


def test_edit_drops_the_uncertainty_of_the_edited_value_only():
    p = default_params().replace(uncertainty={"stribeck.positive.Fc": 0.5, "stribeck.positive.Fs": 0.7})
    q = with_values(p, {"stribeck.positive.Fc": 25.0})
    assert dict(q.uncertainty) == {"stribeck.positive.Fs": 0.7}
    with pytest.raises(ParameterError, match="stribeck.positive.Fs"):
        with_values(p, {"stribeck.positive.Fs": -1.0})  # sign rule of Table I


def test_fields_carry_units_and_log_scales():
    f = {x.path: x for x in fields_of(default_params())}
    assert f["stribeck.positive.vs"].unit == "rad/s" and f["stribeck.positive.vs"].scale == "log"
    assert f["transition_curve.z.1"].scale == "log"
    lin = default_params().replace(units={"position": "m", "force": "N", "time": "s"})
    assert {x.path: x for x in fields_of(lin)}["stribeck.positive.sigma2"].unit == "N·s/m"


def test_sanity_warning_when_coulomb_exceeds_static():
    p = with_values(default_params(), {"stribeck.positive.Fc": 40.0})  # > Fs⁺ = 36
    assert any("Fc⁺" in w and "> |Fs⁺|" in w for w in sanity_warnings(p))
    assert not any("Fc" in w for w in sanity_warnings(default_params()))


def test_overview_static_note_and_overlay_on_its_own_axes():
    from leuven_friction.model import as_model
    from leuven_friction.model.experiments import abcd_ramp

    p = default_params()
    r = abcd_ramp(p, rate=20.0).runs[0]
    lu = abcd_ramp(as_model(p, "lugre"), rate=20.0).runs[0]
    fig = plots.overview_figure(units=dict(p.units), hyst=[("static", "main", None), ("lugre", "overlay", lu)],
                                strib=[], slip=[], bottom={})
    texts = " ".join(a["text"] for a in fig.layout.annotations)
    assert "no presliding" in texts
    # no main loop to protect: the overlay is drawn on the main axes
    assert [t.xaxis for t in fig.data if t.name == "lugre"] == ["x"]
    fig1 = plots.overview_figure(units=dict(p.units), hyst=[("leuven", "main", r), ("lugre", "overlay", lu)],
                                 strib=[], slip=[], bottom={})
    over = [t for t in fig1.data if t.name == "lugre"]
    assert over and over[0].xaxis == "x5" and fig1.layout.xaxis5.overlaying == "x"  # its own scale
    fig2 = plots.overview_figure(units=dict(p.units), hyst=[("leuven", "main", r)], strib=[], slip=[], bottom={})
    marks = next(t for t in fig2.data if t.name == "A–D")
    # B is the top of the first ramp (20 N·m), C the bottom of the unloading (5 N·m), D the end (30 N·m)
    assert np.allclose(marks.y[1:], [20.0, 5.0, 30.0], atol=0.5)
    csv_text = plots.figure_csv(fig2)
    assert csv_text.splitlines()[0] == "trace,x_axis,x,y,sigma" and "A–D" in csv_text
    # the page's first figure, before anything is simulated, does not claim the static model
    first = plots.overview_figure(units=dict(p.units), hyst=[], strib=[], slip=[], bottom={})
    texts = " ".join(a["text"] for a in first.layout.annotations)
    assert "no presliding" not in texts and "simulating" in texts


def test_web_messages_name_the_file_and_no_command_line_options():
    from leuven_friction.app.explorer.data_tab import without_cli_hints, web_message
    from leuven_friction.identify.errors import DataError

    msg = web_message(DataError("no column for position (columns: a, b; name them with --columns position=<column>)"),
                      "run7.tsv")
    assert msg.startswith("run7.tsv: ") and "--" not in msg and "Columns in the Data tab" in msg
    # a motor current: the header's unit is the web user's way to give its constant, not --units
    from leuven_friction.identify.data import load_recording

    with pytest.raises(DataError) as e:
        load_recording("t_s,angle_rad,current_A\n" + "".join(f"{i * 0.01},{i * 1e-4},0.4\n" for i in range(20)),
                       name="joint.csv", columns={"force": "current_A"})
    msg = web_message(e.value, "joint.csv")
    assert "--" not in msg and msg.endswith("for 35 N/A)") and "'current_A [0.12 N*m]'" in msg, msg
    assert without_cli_hints("fixed at 7 (the paper's choice; --fit-n estimates it)") == "fixed at 7 (the paper's choice)"
    # the clause that names the option goes whole, not the option alone
    assert (without_cli_hints("held at 5 (another machine's; give --params with this machine's)")
            == "held at 5 (another machine's)")
    assert without_cli_hints("kept from the paper's axis (give --params with this machine's values)") == "kept from the paper's axis"
    assert without_cli_hints("a; see --threshold x; b") == "a; b"
    # with the clause's own bracket (a diagnosis's note on the base refitted alone)
    assert (without_cli_hints("moves (see above); `diagnose --refit-base --out` writes it (it leaves 1.5); the rest")
            == "moves (see above); the rest")


def test_the_candidates_figure_draws_an_in_sample_gain_apart_from_held_out_ones():
    # a candidate the prescreen did not cross-validate has its in-sample gain as its number (an
    # upper bound): drawn hatched, in a trace that says so, not on the held-out one
    from types import SimpleNamespace

    cands = [dict(name="normal_load", heldout_gain=0.38, significant=True, passes=True, cross_validated=True,
                  folds_improved=5, folds_informative=5),
             dict(name="position_ripple", heldout_gain=0.004, significant=False, passes=False, cross_validated=False,
                  folds_improved=0, folds_informative=0)]
    fig = plots.diagnosis_cv_figure(SimpleNamespace(candidates=cands, settings=SimpleNamespace(min_gain=0.03)))
    bars = {t.name: t for t in fig.data if t.type == "bar"}
    assert list(bars["held-out RMS gain (%)"].y) == ["normal_load"]
    assert list(bars["held-out RMS gain (%)"].x) == pytest.approx([38.0])
    inside = bars["in-sample RMS gain, not cross-validated (%)"]
    assert list(inside.y) == ["position_ripple"] and inside.marker.pattern.shape == "/"
    assert list(fig.layout.yaxis.categoryarray) == ["normal_load", "position_ripple"]  # the candidates' order
