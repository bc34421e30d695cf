"""The guideway simulated apart from the project (synth/guideway.py) against the physics it
claims: at a held speed the motor force equals LuGre's steady friction g(v) + σ2·v, written out
here, in both directions, and the effects it hides act where they say."""

import numpy as np

from synth import guideway as G


def _holds(cols, window=200):
    """(speed, mean force, its standard error) over the steady part of every held speed: the
    velocity over ``window`` samples within 1 % of one of the levels, 0.5 s after it got there."""
    t = cols["time [s]"]
    x = cols["position [mm]"] * 1e-3
    f = cols["force [N]"]
    v = np.full(len(x), np.nan)
    h = window // 2
    v[h:-h] = (x[window:] - x[:-window]) / (t[window:] - t[:-window])
    out = []
    for lv in G.LEVELS:
        for sg in (1, -1):
            m = np.abs(v - sg * lv) < 0.01 * lv
            m[1:] &= m[:-1]  # drop the first sample of each stretch
            # and 0.5 s more: a sample counts once the 500 up to it all do
            run = np.concatenate([[0], np.cumsum(m)])
            steady = np.zeros(len(m), bool)
            steady[499:] = run[500:] - run[:-500] == 500
            if steady.sum() > 200:
                out.append((sg * lv, float(np.mean(f[steady])), float(np.std(f[steady]) / np.sqrt(steady.sum() / 50))))
    return out


def lugre_steady(v):
    """LuGre's steady friction with the guideway's parameters: g(v) + σ2·v, g Gaussian (δ = 2)."""
    return np.sign(v) * (G.FC + (G.FS - G.FC) * np.exp(-(v / G.VS) ** 2)) + G.S2 * v


def test_held_speeds_show_lugre_steady_friction():
    cols, _ = G.simulate(seed=101)
    holds = _holds(cols)
    assert len(holds) >= 16  # most of the 12 speeds, both directions
    for v, F, se in holds:
        # the force sensor's offset wanders 0.05 N over the session; its white noise averages out
        assert abs(F - lugre_steady(v)) < 0.1 + 4 * se, (v, F, lugre_steady(v))


def test_hidden_drift_raises_the_steady_friction_as_it_says():
    # with the warm-up drift 1 + 0.25(1 − e^(−t/30 s)) the late holds carry its factor
    base, _ = G.simulate(seed=101)
    warm, _ = G.simulate(seed=101, drift=True)
    t = base["time [s]"]
    late = {round(v, 6): F for v, F, _ in _holds({k: a[t > 120.0] for k, a in warm.items()})}
    late0 = {round(v, 6): F for v, F, _ in _holds({k: a[t > 120.0] for k, a in base.items()})}
    common = set(late) & set(late0)
    assert len(common) >= 2
    for v in common:
        # after 120 s the factor is 1.2454–1.25
        assert abs(late[v] / late0[v] - 1.248) < 0.01, (v, late[v], late0[v])
