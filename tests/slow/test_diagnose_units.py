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
    for s1, s2 in zip(d1.steps, d2.steps):
        assert s2["rms"] == pytest.approx(SCALE * s1["rms"], rel=1e-3), (s1, s2)
    gains = [{c["name"]: c["heldout_gain"] for c in d.candidates} for d in (d1, d2)]
    assert gains[1].keys() == gains[0].keys()
    for name, g in gains[0].items():
        assert gains[1][name] == pytest.approx(g, abs=1e-3), (name, gains)
    # the drift's own values and σ, which do not scale with the forces: the same within a quarter
    # of that σ (the least squares' paths differ by rounding: 1,441 and 1,387 simulations), and
    # the σ within 20 %
    for k in ("b", "tau"):
        sd1, sd2 = d1.steps[2]["sd"][k], d2.steps[2]["sd"][k]
        assert np.isfinite(sd2) and sd2 == pytest.approx(sd1, rel=0.2), (k, sd1, sd2)
        for values in ("params", "params_decided"):
            assert abs(d2.steps[2][values][k] - d1.steps[2][values][k]) < 0.25 * sd1, (k, values, d1.steps, d2.steps)
