"""The diagnosis, run as a new user runs it (``leuven-friction diagnose FILE``: a fit first, no
parameter file), on a crank-driven tribometer simulated on its own terms (``synth/crank.py``:
a sinusoidal prescribed motion with no constant-velocity run, Dahl's presliding plus viscous
friction, position in µm, 80,000 samples): the fit takes S(v) from the steady sliding, and the
diagnosis names what was imposed and nothing on the control."""

import pytest

from synth import crank
from synth.crank import crank_recording
from tests.cli_runs import diagnose_file


def _diagnose(tmp_path, effect, seed=1):
    df, truth = crank_recording(seed, effect)
    return diagnose_file(tmp_path, df, f"crank_{effect}.csv", "%.9g"), truth


@pytest.mark.slow
def test_a_crank_control_names_nothing_and_its_fit_leaves_the_noise(tmp_path):
    rep, _ = _diagnose(tmp_path, None)
    assert rep["effects"] == []
    assert rep["travel_spring"] is None, rep["travel_spring"]
    assert rep["units"] == {"position": "m", "force": "N", "time": "s"}  # the µm file read into SI, said so
    # the base as fitted (no parameter file) within a few noise floors: before S(v) came from
    # the sliding and σ1 from the data's scale, 0.67 N against a floor of 0.028
    assert rep["steps"][0]["rms"] < 3 * rep["noise"], (rep["steps"][0], rep["noise"])


@pytest.mark.slow
@pytest.mark.parametrize("effect, seed", [("time_drift", 1), ("time_drift", 2), ("normal_load", 1), ("normal_load", 2)])
def test_a_drift_or_a_load_on_a_crank_is_named_and_closes_most_of_the_gap(tmp_path, effect, seed):
    rep, truth = _diagnose(tmp_path, effect, seed)
    assert rep["effects"] == [effect], rep["effects"]
    # no force in proportion to the travel said: on a crank ẍ = −ω²x, so the half sample the
    # model's σ2·v lags the log's (σ2·Δt/2·ẍ) rises along every stroke whichever way, as a spring
    # of σ2·Δt·ω²/2 = 5.9 N/m would; read with the acceleration beside it, it is not one
    assert rep["travel_spring"] is None, rep["travel_spring"]
    step = rep["steps"][2]
    assert step["rms"] < 0.5 * rep["steps"][1]["rms"]  # the gap more than halves
    # the simulator scales the dry friction only (F_c and σ0), the model's friction effect the
    # whole F of eq. (3), σ2·v with it: the effect's size comes out near the dry share of the
    # sliding friction, F_c / (F_c + σ2·mean|v|) = 4 / (4 + 150 · 0.016) = 0.62 of the imposed one
    dry = crank.FC / (crank.FC + crank.SIGMA2 * crank.AMPLITUDE * 4 * crank.FREQ)
    if effect == "normal_load":
        ratio = step["params"]["alpha"] / truth["alpha"]  # friction ∝ (N/N0)^α in both
    else:
        ratio = step["params"]["b"] / truth["b"]  # the drift's end value 1 + b, its sign with it
    assert 0.75 * dry < ratio < 1.25 * dry, (step["params"], truth, dry)
    if effect == "time_drift":
        assert abs(step["params"]["tau"] / truth["tau"] - 1) < 0.15, (step["params"], truth)
