"""Logs with samples lost: a logger that drops single rows at random (irregular sampling) and
one that loses bursts of rows (time gaps). What is asserted is what losing rows must not
change: the slope of a line, a Stribeck rise the levels show, and how the comparison treats
the stretches it cannot see."""

import numpy as np
import pytest

from leuven_friction.identify.markov import Levels, fit_side_honest
from leuven_friction.identify.segment import across_gaps, local_slope, piecewise_slope, time_gaps


def _irregular_times(n, dt, lost, seed):
    rng = np.random.default_rng(seed)
    t = np.arange(n) * dt
    return t[rng.random(n) > lost]


def _windowed_line_slope(t, x, w):
    """The least-squares line's slope over each full window of w samples, summed directly
    about each window's own first sample (no running sums)."""
    from numpy.lib.stride_tricks import sliding_window_view

    T, X = sliding_window_view(t, w), sliding_window_view(x, w)
    tc, xc = T - T[:, :1], X - X[:, :1]
    tm, xm = tc.mean(axis=1, keepdims=True), xc.mean(axis=1, keepdims=True)
    return np.sum((tc - tm) * (xc - xm), axis=1) / np.sum((tc - tm) ** 2, axis=1)


@pytest.mark.parametrize("w", [5, 31, 301])
def test_slope_over_a_long_log_sampled_irregularly_is_the_windows_least_squares_line(w):
    # 200,000 samples at 1 kHz with 3 % lost at random, along a parabola: each slope is the
    # least-squares line's through its window (for a parabola, its slope at the window's mean
    # time plus the skew of the window's times, which lost rows make). Running sums over the
    # whole log lost 1 % of Σ(t − t̄)² to rounding with 5-sample windows
    t = _irregular_times(200_000, 1e-3, 0.03, seed=4)
    x = 0.3 + 0.0123 * t - 6e-5 * t**2
    h = w // 2
    v = local_slope(t, x, w, uniform=False)[h:len(t) - h]
    ref = _windowed_line_slope(t, x, w)
    assert np.max(np.abs(v - ref)) < 1e-7 * np.max(np.abs(ref))


def test_gaps_split_the_slope_and_mark_the_windows_across_them():
    dt = 1e-3
    t = np.arange(10_000) * dt
    keep = np.ones(len(t), bool)
    keep[3000:3200] = False  # 0.2 s lost
    keep[7000:7150] = False
    t = t[keep]
    # a stage at 0.01 m/s that reverses to −0.02 m/s inside the first gap: no slope is taken
    # across it, so none mixes the two speeds
    x = np.where(t < 3.1, 0.01 * t, 0.031 - 0.02 * (t - 3.1))
    gaps = time_gaps(t)
    assert list(t[gaps]) == [3.2, 7.15]
    v = piecewise_slope(t, x, 51, gap=0.01)
    assert np.allclose(v[t < 3.0], 0.01) and np.allclose(v[t > 3.2], -0.02)
    near = across_gaps(len(t), gaps, 25)
    assert near.sum() == 2 * 50 and np.all(near[gaps - 1]) and np.all(near[gaps]) and not near[gaps[0] - 26]


def test_a_stribeck_rise_the_levels_show_is_kept_where_the_free_fit_slides_into_a_corner():
    # the negative side of a rotary joint made apart (synth/joint_maxwell_slip_logged.py, a
    # ripple along its travel, 3 % of its samples lost): 11 levels whose friction rises from
    # 0.82 N·m at 0.09 rad/s to 0.98 N·m at 0.9 mrad/s, each to within 0.5 % of its value.
    # With δ free the fit slides to δ 0.26, v_s 3.9 rad/s (past every level), F_c at 0
    v = -np.array([0.52359, 0.29271, 0.16363, 0.09148, 0.05114, 0.02859, 0.01598, 0.00894, 0.00499, 0.00279, 0.00087])
    F = -np.array([1.1532, 0.9455, 0.8491, 0.8209, 0.8475, 0.8725, 0.8962, 0.8738, 0.9146, 0.9442, 0.9771])
    sd = np.array([0.02067, 0.01833, 0.01816, 0.01227, 0.00418, 0.01495, 0.01155, 0.00708, 0.00436, 0.00255, 0.00032])
    d = fit_side_honest(Levels(v, F, sd**2, np.full(len(v), 1400.0)), -1)
    assert d.model.startswith("Stribeck + viscous")
    Fs, Fc = -d.fit.values["Fs"], -d.fit.values["Fc"]
    # the rise: F_s near the slowest level, F_c near the bottom of the dip, beyond their σ
    assert abs(Fs - 0.9771) < 0.03 and 0.75 < Fc < 0.85
    assert Fs - Fc > 3 * np.hypot(d.fit.stderr["Fs"], d.fit.stderr["Fc"])
    # and the curve passes through the levels: under 10 per degree of freedom, where a
    # Coulomb level with a viscous slope misses the slowest level alone by 0.1 N·m (300 σ)
    assert d.fit.chi2 / max(d.fit.dof, 1) < 10
