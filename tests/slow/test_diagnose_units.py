"""The diagnosis is the same physics in any unit of force: a tribometer of the hidden-effect suite
(``synth/hidden.py``, measured friction along a prescribed motion) and the same tribometer with
every force a millionth of it (its friction column and the parameter set's forces, σ1 and σ2;
along a prescribed motion the Leuven model's friction scales with them exactly). A galvanometer
axis made apart, friction 2·10⁻⁵ N·m, had its least squares stop at their start (scipy's
gradient test is absolute) and a softening written with σ = 0; the least squares now run on
residuals in noise floors (``Engine.unit``)."""

import numpy as np
import pytest

from leuven_friction.identify.diagnose import diagnose
from leuven_friction.model import Stribeck, StribeckSide, TransitionCurve
from synth.hidden import make_case, oracle_params, to_recording

SCALE = 1e-6


def _forces_scaled(p, c: float):
    side = lambda s: StribeckSide(Fs=c * s.Fs, Fc=c * s.Fc, vs=s.vs, delta=s.delta, sigma2=c * s.sigma2)  # noqa: E731
    tc = p.transition_curve
    return p.replace(stribeck=Stribeck(side(p.stribeck.positive), side(p.stribeck.negative)),
                     transition_curve=TransitionCurve(kind="piecewise_linear", z=tc.z, F=tuple(c * f for f in tc.F)),
                     sigma1=c * p.sigma1, inertia=c * p.inertia)


@pytest.mark.slow
def test_a_tribometer_with_every_force_a_millionth_is_diagnosed_alike():
    df, truth, case = make_case("tribometer", 1002, ("time_drift",))
    base = oracle_params(truth)
    friction = next(c for c in df.columns if c.lower().startswith("friction"))
    small = df.copy()
    small[friction] = SCALE * df[friction]
    d1 = diagnose(to_recording(df, "tribometer.csv"), base)
    d2 = diagnose(to_recording(small, "tribometer.csv"), _forces_scaled(base, SCALE))
    assert d1.effects == d2.effects == ["time_drift"], (d1.text(), d2.text())
    assert d2.noise == pytest.approx(SCALE * d1.noise, rel=1e-6)
    # the model as given and the alternative: the same gaps, scaled
    for s1, s2 in zip(d1.steps[:2], d2.steps[:2]):
        assert s2["rms"] == pytest.approx(SCALE * s1["rms"], rel=1e-3), (s1, s2)
    gains = [{c["name"]: c["heldout_gain"] for c in d.candidates} for d in (d1, d2)]
    assert gains[1].keys() == gains[0].keys()
    for name, g in gains[0].items():
        assert gains[1][name] == pytest.approx(g, abs=1e-3), (name, gains)
    # the drift as the decision fitted it, whose values do not scale with the forces: the same
    # within a quarter of its σ
    for k in ("b", "tau"):
        sd1 = d1.steps[2]["sd"][k]
        assert abs(d2.steps[2]["params_decided"][k] - d1.steps[2]["params_decided"][k]) < 0.25 * sd1, (k, d1.steps, d2.steps)
    # the model written (n, σ1, S(v) and the drift refitted together) ends its least squares at
    # another point of a valley where b and τ trade off, by rounding: measured on an AMD EPYC,
    # b −0.203 and −0.184, τ 80 and 62 s, gaps 0.0467 and 0.0415 N (scaled back), where another
    # day's machine had them within 0.0004 and 1 s. Asserted: the same within 1.5 of the larger
    # σ, and gaps within 15 % — both below the alternative's
    s1, s2 = d1.steps[2], d2.steps[2]
    for k in ("b", "tau"):
        sd = max(s1["sd"][k], s2["sd"][k])
        assert np.isfinite(sd) and abs(s2["params"][k] - s1["params"][k]) < 1.5 * sd, (k, s1, s2)
    assert s2["rms"] == pytest.approx(SCALE * s1["rms"], rel=0.15), (s1, s2)
    assert s1["rms"] < d1.steps[1]["rms"] and s2["rms"] < d2.steps[1]["rms"]
