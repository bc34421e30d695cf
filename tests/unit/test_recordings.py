"""The independent recording generator (synth/recordings.py) against physics it must obey:
steady sliding friction equals S(v) + σ2·v, presliding follows Masing's doubled virgin curve,
and the hidden-effect hooks act inside the loop (the plant feels them)."""

import numpy as np

from synth.recordings import make_recording


def _steady_means(df, truth, t_range):
    """Mean friction over the middle of each constant-velocity hold (tribometer strokes)."""
    c = truth.columns
    t = df[c["time"]].to_numpy()
    x = df[c["position"]].to_numpy() * truth.factors["position"]
    F = -df[c["friction"]].to_numpy() * truth.factors["friction"]  # reaction sign → action
    v = np.gradient(x, t)
    out = []
    for lv in truth.levels:
        for sg in (1, -1):
            m = (np.abs(v - sg * lv) < 0.02 * lv) & (t > t_range[0]) & (t < t_range[1])
            if m.sum() > 20:
                out.append((sg * lv, float(np.mean(F[m])), float(np.std(F[m]) / np.sqrt(m.sum()))))
    return out


def test_steady_sliding_friction_is_S_of_v():
    df, truth = make_recording("tribometer", 1)
    means = _steady_means(df, truth, truth.segments["strokes"])
    assert len(means) >= 8
    for v, F, se in means:
        expected = truth.S(np.array([v]))[0]
        assert abs(F - expected) < 0.02 * abs(expected) + 4 * se, (v, F, expected)


def test_reversal_curve_is_twice_the_virgin_curve_scaled():
    # presliding from rest follows Σ min(k_i x, α_i Fs): the truth's reversal curve (span
    # Fs⁺ − Fs⁻) evaluated at twice the displacement, halved (Masing)
    _, truth = make_recording("linear_stage", 3)
    z = np.linspace(0, truth.presliding_range, 50)
    span = truth.stribeck["positive"]["Fs"] - truth.stribeck["negative"]["Fs"]
    virgin = np.sum(np.minimum(np.multiply.outer(z, truth.element_stiffness), truth.element_weight * span / 2), axis=1)
    assert np.allclose(truth.transition_curve(2 * z) / 2, virgin)


def test_friction_modifier_acts_inside_the_loop():
    """Doubling friction after a time doubles the measured steady friction after it (motion
    imposed), and the hook sees the running count of reversals."""
    seen = []

    def double_late(ctx):
        seen.append(ctx.reversals)
        return np.where(ctx.t > 30.0, 2.0, 1.0)

    df0, truth = make_recording("tribometer", 1)
    df1, _ = make_recording("tribometer", 1, friction_modifier=double_late)
    a = _steady_means(df0, truth, (30.0, np.inf))
    b = _steady_means(df1, truth, (30.0, np.inf))
    assert len(a) >= 3 and len(a) == len(b)
    for (_, F0, se0), (_, F1, se1) in zip(a, b):
        assert abs(F1 - 2 * F0) < 0.01 * abs(F0) + 4 * (se1 + 2 * se0)
    assert max(seen) >= 10 and seen == sorted(seen)  # reversals counted as the strokes go


def test_stiffness_modifier_changes_presliding_in_a_force_driven_plant():
    df0, truth = make_recording("robot_joint", 2)
    df1, _ = make_recording("robot_joint", 2, stiffness_modifier=lambda ctx: 0.5)
    end = int(truth.segments["presliding_ramps"][1] * truth.rate * 0.3)  # the first ramp
    x0 = df0["position [rad]"].to_numpy()[:end]
    x1 = df1["position [rad]"].to_numpy()[:end]
    # half the element stiffness: about twice the presliding excursion under the same torque
    ratio = np.ptp(x1) / np.ptp(x0)
    assert 1.6 < ratio < 2.4, ratio
