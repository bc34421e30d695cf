"""The independent recording generator (synth/recordings.py) against physics it must obey:
steady sliding friction equals S(v) + σ2·v, presliding follows the elements and Masing's rule,
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


def test_presliding_of_the_loop_follows_its_elements_and_masing():
    # the generator's contact (linear stage 3's elements) driven slowly along an imposed path from
    # rest: forward, every element loads until it slips at α_i·F_s⁺, so F = Σ min(k_i x, α_i F_s⁺);
    # back from far beyond the presliding range, the force falls by Σ min(k_i z, α_i (F_s⁺ − F_s⁻))
    # — the reversal curve the generator documents (``Truth.transition_curve``, Masing: the span
    # of the limits, not twice the virgin curve unless F_s⁻ = −F_s⁺)
    from synth.recordings import _run

    _, truth = make_recording("linear_stage", 3)
    k, a = truth.element_stiffness, truth.element_weight
    sp, sn = (np.array([truth.stribeck[sd][q] for q in ("Fs", "Fc", "vs", "delta", "sigma2")])
              for sd in ("positive", "negative"))
    sp[4] = sn[4] = 0.0  # no viscous term: the elements alone
    Fs_p, Fs_n = sp[0], sn[0]
    L = 3.0 * truth.presliding_range
    n, dt = 4000, 1e-2
    up = np.linspace(0.0, L, n)
    down = L - np.linspace(0.0, 2.0 * L, 2 * n)[1:]
    x_ref = np.concatenate([up, down])
    m = len(x_ref)
    state = np.zeros(5 + len(k))
    X, V, F, U = (np.zeros(m) for _ in range(4))
    ones = np.ones(m)
    _run(2, m, 1, dt, np.zeros(m), np.zeros(m), x_ref, 0.0, 0.0, np.zeros(m), ones, ones,
         k, a, sp, sn, 0.0, truth.inertia, state, X, V, F, U)
    # the slip limits at the path's speed (|v| = L/(n·dt), far below v_s): eq. (7) written out
    v = L / (n * dt)
    lim_p = sp[1] + (sp[0] - sp[1]) * np.exp(-abs(v / sp[2]) ** sp[3])
    lim_n = sn[1] + (sn[0] - sn[1]) * np.exp(-abs(v / sn[2]) ** sn[3])
    virgin = np.sum(np.minimum(np.multiply.outer(up, k), a * lim_p), axis=1)
    np.testing.assert_allclose(F[:n], virgin, rtol=1e-6, atol=1e-9 * Fs_p)
    z = L - down
    back = np.sum(a) * lim_p - np.sum(np.minimum(np.multiply.outer(z, k), a * (lim_p - lim_n)), axis=1)
    np.testing.assert_allclose(F[n:], back, rtol=1e-6, atol=1e-6 * (Fs_p - Fs_n))
    # the generator's documented reversal curve (at the static limits) is that fall, to within
    # how far the limits at this speed are from F_s
    slack = abs(lim_p - Fs_p) + abs(lim_n - Fs_n)
    assert slack < 1e-3 * (Fs_p - Fs_n)
    assert np.max(np.abs(F[n - 1] - F[n:] - truth.transition_curve(z))) <= 2 * slack + 1e-9 * (Fs_p - Fs_n)


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
