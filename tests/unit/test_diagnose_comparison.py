"""The diagnosis's comparison, checked against expectations written out here: friction taken
from an applied force by eq. (8) in integral form (an analytic motion whose acceleration is
known), the alternative's free steady curve (what it may absorb and what it must leave), and
the regimes a candidate must help in."""

import math

import re

import numpy as np
import pytest
from leuven_friction.identify.diagnose import (
    Comparison,
    FreeSteadyCurve,
    SpeedOrder,
    Term,
    averaging_length,
    averaging_limit,
    unresolved_rest,
    friction_from_force,
    gross_sliding,
    load_changing,
    mean_acceleration,
    model_nuisance,
    noise_colour,
    with_model_shift,
    speed_order,
    stroke_order,
    steady_sliding,
)
from scipy.ndimage import uniform_filter1d
from scipy.stats import spearmanr


def test_friction_from_force_removes_the_inertial_term_of_a_known_motion():
    # x = A sin(ωt): I·ẍ = −I·A·ω²·sin(ωt) is far larger than the friction, an arbitrary slow
    # signal with steps; the applied force is f = I·ẍ + F at the sampling instants
    dt, I, A, w = 1e-3, 2.5, 0.3, 2 * np.pi * 1.7
    t = np.arange(0, 6, dt)
    v = A * w * np.cos(w * t)
    F = 4.0 + 1.5 * np.sin(0.9 * t) + 0.5 * np.sign(np.sin(0.3 * t))
    f = -I * A * w * w * np.sin(w * t) + F
    L = 21
    got = friction_from_force(f, v, I, t, L)
    want = uniform_filter1d(F, L, mode="nearest")  # the friction seen through the same average
    inner = slice(L, len(t) - L)
    assert I * A * w * w > 80.0  # the inertial force dwarfs the friction
    # what is left is the difference between a window's mean acceleration and the central
    # difference of the velocity: relative (ω·T)²/24 with T = L·dt, under 0.2 %
    assert np.max(np.abs(got - want)[inner]) < 2e-3 * I * A * w * w
    # averaging the force alone would leave most of the inertial term
    assert np.max(np.abs(uniform_filter1d(f, L) - want)[inner]) > 0.9 * I * A * w * w


def test_averaging_length_makes_the_inertial_term_no_noisier_than_the_averaged_force():
    # √2·I·σv/T ≤ σf/√L with T = L·dt: L ≥ (√2·I·σv/(dt·σf))² = (√2·1·1e-3/(1e-3·0.1))² = 200
    assert averaging_length(1.0, 0.1, 1e-3, 1e-3, 5, 100_000) == 201
    # a quiet velocity: the path's smoothing window sets it
    assert averaging_length(1.0, 0.1, 1e-5, 1e-3, 9, 100_000) == 9
    # never more than 1 % of the record
    assert averaging_length(1.0, 0.1, 1e-3, 1e-3, 5, 5_000) == 51
    # nor than the motion resolves: here the 200 asked for, against a limit of 60 samples
    assert averaging_length(1.0, 0.1, 1e-3, 1e-3, 5, 100_000, longest=60) == 61


def test_the_averaging_limit_is_a_tenth_of_the_time_between_significant_reversals():
    # a triangle wave reversing every 0.8 s at 500 Hz (400 samples), with an encoder's steps and
    # wiggles below the significant excursion: a tenth of 400 samples
    t = np.arange(40_000) / 500.0
    x = 1e-3 * (2.0 * np.abs((t / 1.6) % 1.0 - 0.5) - 0.5)
    x = np.round((x + 2e-6 * np.sin(2 * np.pi * 37 * t)) / 2.4e-5) * 2.4e-5
    assert averaging_limit(t, x, 1e-4) in (39, 40, 41)
    # the same motion logged at 2 kHz: the same time, four times the samples
    t4 = np.arange(160_000) / 2000.0
    x4 = np.round(1e-3 * (2.0 * np.abs((t4 / 1.6) % 1.0 - 0.5) - 0.5) / 2.4e-5) * 2.4e-5
    assert averaging_limit(t4, x4, 1e-4) in range(158, 163)
    # too few reversals to tell: no limit beyond the record
    assert averaging_limit(t[:500], x[:500], 1e-4) == 500


def _holds(speeds, n_per=400):
    """A velocity schedule: constant-velocity holds, a short rest between them."""
    v = []
    for s in speeds:
        v += [s] * n_per + [0.0] * 50
    return np.array(v, dtype=float)


def test_free_steady_curve_absorbs_any_function_of_velocity():
    v = _holds([0.01, -0.01, 0.03, -0.05, 0.1, -0.2, 0.4, -0.4, 1.0, -1.0])
    curve = FreeSteadyCurve(v, v_rest=1e-3)
    r = np.where(v > 0, 0.7 * np.log(np.abs(v) + 1e-9), np.where(v < 0, -0.2 * np.abs(v) ** 0.5, 0.0)) + 0.3 * (v == 0)
    fitted = curve.fit(r, np.ones(len(v), bool))
    # hat functions a factor 2 apart interpolate a smooth curve of log|v|; the constants at
    # rest and the log-law are captured to well within 2 % of the signal
    assert np.sqrt(np.mean((r - fitted) ** 2)) < 0.02 * np.sqrt(np.mean(r**2))


def test_free_steady_curve_leaves_a_change_between_two_visits_of_one_speed():
    # the same speeds visited twice, minutes apart: a drift in time changes the friction
    # between the visits, which no function of velocity can hold
    speeds = [0.02, -0.02, 0.2, -0.2, 2.0, -2.0]
    v = _holds(speeds + speeds)
    n = len(v)
    drift = np.linspace(0.0, 1.0, n)
    curve = FreeSteadyCurve(v, v_rest=1e-3)
    left = drift - curve.fit(drift, np.ones(n, bool))
    # the best a function of v can do is the mean of the two visits: half the step between
    # them (0.5 here) remains, ±0.25 on every sample, plus the within-hold slopes
    assert np.sqrt(np.mean(left**2)) > 0.2
    # fitted on one half of the samples it predicts the other half no better
    half = np.arange(n) < n // 2
    pred = curve.fit(drift, half)
    assert np.sqrt(np.mean((drift - pred)[~half] ** 2)) > 0.3


def test_speed_order_tells_a_sweep_in_order_from_one_that_returns():
    # a robot joint's sweep: each level forward then back, slowest first. Spearman's ρ over the
    # holds (each counted once) is 1 up to the ties of ± one level; the same levels visited
    # forward and then backward (a V in time) have ρ ≈ 0; three holds are too few to judge
    levels = [0.01, 0.03, 0.1, 0.3, 1.0, 3.0]
    sweep = _holds([s * lv for lv in levels for s in (1, -1)])
    t = np.arange(len(sweep)) * 1e-3
    up = speed_order(t, sweep, sweep != 0)
    assert up.count == 12 and up.rho > 0.95
    vee = _holds([s * lv for lv in levels + levels[::-1] for s in (1, -1)])
    back = speed_order(np.arange(len(vee)) * 1e-3, vee, vee != 0)
    assert back.count == 24 and abs(back.rho) < 0.2
    # a hold shorter than min_samples is not a stretch of steady sliding at one speed
    few = _holds([0.1, -0.3, 1.0])
    assert math.isnan(speed_order(np.arange(len(few)) * 1e-3, few, few != 0).rho)
    assert speed_order(t, sweep, sweep != 0, min_samples=401).count == 0


def test_a_level_visited_again_late_is_told_from_levels_visited_once():
    # shuffled levels, each forward and back once: no level is visited again, whatever the
    # order; the slowest one repeated at the session's end makes two holds (its first visit and
    # the last) per direction that have a twin far away in time; a level's forward and backward
    # holds, adjacent in time, are not a revisit (other directions)
    from leuven_friction.identify.diagnose import levels_revisited, steady_holds

    levels = [0.3, 0.01, 1.0, 0.1, 3.0, 0.03]
    once = _holds([s * lv for lv in levels for s in (1, -1)])
    t = np.arange(len(once)) * 1e-3
    h = steady_holds(t, once, once != 0)
    assert len(h) == 12 and levels_revisited(h, t[-1] - t[0]) == 0
    again = _holds([s * lv for lv in levels + [0.3] for s in (1, -1)])
    t2 = np.arange(len(again)) * 1e-3
    h2 = steady_holds(t2, again, again != 0)
    assert len(h2) == 14 and levels_revisited(h2, t2[-1] - t2[0]) == 4
    # the same repeat right after the first visit is no revisit late in the session
    near = _holds([s * lv for lv in [0.3] + levels for s in (1, -1)])
    t3 = np.arange(len(near)) * 1e-3
    h3 = steady_holds(t3, near, near != 0)
    assert levels_revisited(h3, t3[-1] - t3[0]) == 0


def test_stroke_order_follows_the_reversals_not_the_transitions_or_dwells():
    # strokes between reversals, each from rest through a transition (a ramp up to the stroke's
    # speed) and back to a dwell: speeds doubling with every second reversal (the generator's
    # linear-stage sweep) give ρ = 1 up to the ties of a pair; the same speeds cycled three
    # times over the session (a tribometer's passes) give the ρ of the levels alone (scipy's),
    # under the threshold of a note: the ramps and dwells do not enter
    def session(levels):
        v = [np.r_[np.linspace(0.0, lv, 40), np.full(300, lv), np.linspace(lv, 0.0, 40), np.zeros(60)]
             * (1 if k % 2 else -1) for k, lv in enumerate(levels)]
        return np.concatenate([np.full(len(a), k) for k, a in enumerate(v)]), np.concatenate(v)

    rising = [1e-4 * 2.0 ** (k // 2) for k in range(16)]
    up = stroke_order(*session(rising), v_rest=1e-6)
    assert up.count == 16 and up.rho > 0.95
    cycled = [1e-4 * 2.0 ** (k % 6) for k in range(18)]
    expected = abs(spearmanr(np.arange(18), cycled).statistic)
    assert stroke_order(*session(cycled), v_rest=1e-6).rho == pytest.approx(expected, abs=1e-9) and expected < 0.8
    # three strokes are too few to judge; below the rest threshold nothing moves
    assert math.isnan(stroke_order(*session(rising[:3]), v_rest=1e-6).rho)
    assert stroke_order(*session(rising), v_rest=1.0).count == 0


def test_a_saturation_scale_at_either_bound_is_not_seen_settling():
    # n_c free between 3 and 10 reversals (log): at 10 the change still runs at the session's
    # end (a trend), at 3 it is over within the first reversals (a step); between, it is seen
    term = Term("cyclic_softening", {}, (("h", "lin", -0.9, 5.0), ("n_c", "log", math.log(3.0), math.log(10.0))),
                settles="n_c")
    assert "at its bound 10" in term.unsettled(np.array([-0.3, math.log(10.0)]))
    assert "at its bound 10" in term.unsettled(np.array([-0.3, math.log(9.9)]))  # within 2 %
    assert "at its lower bound 3" in term.unsettled(np.array([-0.3, math.log(3.0)]))
    assert term.unsettled(np.array([-0.3, math.log(5.0)])) is None
    assert term.unsettled(np.array([-0.3, math.log(3.2)])) is None  # 7 % above the bound
    # the spring losing 90 % once settled (h at its lower bound), or stiffening six times (at its
    # upper): the range holds the change, not the data, wherever n_c ends
    assert "h is at a bound" in term.unsettled(np.array([-0.9, math.log(5.0)]))
    assert "h is at a bound" in term.unsettled(np.array([5.0, math.log(5.0)]))
    assert term.unsettled(np.array([-0.85, math.log(5.0)])) is None  # h inside its range
    assert term.pinned(np.array([-0.9, math.log(5.0)])) is None  # said by ``unsettled``, not twice
    assert Term("time_drift", {}, (("b", "lin", -0.9, 5.0),)).unsettled(np.array([5.0])) is None  # no scale to settle
    # where the strokes' speeds do not follow the reversals over the session, a trend at the
    # upper bound is at most in part a stiffness following the speed (within passes of rising
    # speeds), and may be one changing with time: a reason all the same
    assert term.bound(np.array([-0.3, math.log(9.9)])) == "upper"
    assert term.bound(np.array([-0.3, math.log(5.0)])) is None
    cycled, swept = SpeedOrder(24, 0.48), SpeedOrder(18, 0.99)
    why = term.unsettled(np.array([-0.3, math.log(10.0)]), cycled)
    assert "do not follow the reversals" in why and "changing with time" in why and "at most a part" in why
    assert "speed levels in order" in term.unsettled(np.array([-0.3, math.log(10.0)]), swept)
    assert "at its lower bound 3" in term.unsettled(np.array([-0.3, math.log(3.0)]), cycled)


def test_a_drift_at_a_bound_of_its_time_constant_or_of_its_size_is_not_seen_settling():
    # τ between T/10 and 20·T of a 100 s session, b between −0.9 and 5: at τ = 10 s the change is
    # over early (a step at the start looks the same); at 2000 s, or with b at −0.9 (friction
    # falling by 90 % once settled), it is a straight trend whose bend is not seen
    term = Term("time_drift", {"t0": 0.0}, (("b", "lin", -0.9, 5.0), ("tau", "log", math.log(0.1), math.log(20.0))),
                settles="tau", refs={"tau": 100.0})
    assert "lower bound 10 s" in term.unsettled(np.array([0.2, math.log(0.1)]))
    assert "first tenth" in term.unsettled(np.array([0.2, math.log(0.101)]))  # within 2 %
    assert "upper bound 2e+03 s" in term.unsettled(np.array([0.2, math.log(20.0)]))
    assert "straight trend" in term.unsettled(np.array([-0.9, math.log(3.0)]))
    assert "straight trend" in term.unsettled(np.array([5.0, math.log(3.0)]))
    assert term.unsettled(np.array([0.2, math.log(0.3)])) is None
    assert term.unsettled(np.array([-0.85, math.log(3.0)])) is None  # b inside its range


def test_the_level_at_rest_is_a_free_scale_of_the_model_there():
    v = _holds([0.05, -0.05, 0.1, -0.1])
    rest = v == 0
    model = np.where(rest, np.linspace(-3, 3, len(v)), 1.0)
    r = np.where(rest, 0.25 * model, 0.0)  # the model at rest is 25 % off in level
    curve = FreeSteadyCurve(v, v_rest=1e-3)
    assert np.max(np.abs(r - curve.fit(r, np.ones(len(v), bool), model))) < 1e-9
    # without the model column only a constant at rest is free: most of it stays
    assert np.sqrt(np.mean((r - curve.fit(r, np.ones(len(v), bool)))[rest] ** 2)) > 0.5 * np.sqrt(np.mean(r[rest] ** 2))


def _cmp(t, x, v, z_pres, v_rest=1e-3, window=5):
    return Comparison("friction", t, np.zeros_like(t), x, v, None, None, 0.1, 1e-6, window, 1e-5, v_rest,
                      z_presliding=z_pres)


def test_gross_and_steady_sliding_follow_the_travel_since_the_last_reversal():
    dt = 1e-3
    t = np.arange(0, 4, dt)
    # forth at 0.1 for 2 s, then back at 0.1: a reversal at t = 2
    v = np.where(t < 2, 0.1, -0.1)
    x = np.cumsum(v) * dt
    c = _cmp(t, x, v, z_pres=0.01)
    gross = gross_sliding(c)
    # more than 2·z_pres = 0.02 travelled since the reversal: 0.2 s after it at 0.1/s
    after = (t > 2.0) & (t < 2.19)
    assert not gross[after].any()
    assert gross[(t > 2.21) & (t < 3.9)].all()
    assert gross[(t > 0.21) & (t < 1.9)].all()
    steady = steady_sliding(c)
    assert steady[(t > 2.5) & (t < 3.9)].all() and not steady[np.abs(t - 2.0) < 0.003].any()
    # a change of speed within a few samples (a controller stepping to the next level) is not
    # steady around it; either side of it is
    v2 = np.clip(0.1 + (t - 2.0) * 20.0, 0.1, 0.3)  # 0.1 → 0.3 in 10 ms
    c2 = _cmp(t, np.cumsum(v2) * dt, v2, z_pres=0.01)
    s2 = steady_sliding(c2)
    assert s2[(t > 0.5) & (t < 1.99)].all() and s2[(t > 2.02) & (t < 3.99)].all()
    assert not s2[(t > 2.0) & (t < 2.009)].any()
    # no reversal: gross sliding once 2·z_pres is travelled from the start
    assert math.isclose(gross_sliding(c2).mean(), (t > 0.2).mean(), abs_tol=0.002)


def test_inertia_from_force_recovers_the_mass_of_a_controlled_plant():
    # a mass I under a noisy velocity PI loop holding speed levels, friction S(v) = a smooth
    # Coulomb-plus-viscous law; integrated here with 20 substeps a sample (not the product's
    # simulator); S(v) is not given to the estimator (its free steady curve takes it up)
    from leuven_friction.identify.diagnose import inertia_from_force
    from tests.unit.plants import velocity_loop

    I, dt = 0.8, 2e-3
    t, _, v, f = velocity_loop(I, lambda v: 2.0 * np.tanh(v / 1e-3) + 5.0 * v, [0.05, -0.05, 0.2, -0.2, 0.6, -0.6] * 2,
                               1500, dt=dt, kp=40.0)
    got = inertia_from_force(f, v, t, 5, 1e-3)
    assert got is not None
    I_hat, se = got.value, got.stderr
    # the force is logged once a sample, at the end of it, while the proportional term moves
    # with the velocity within it: the logged force lags the sample's mean force by
    # kp·a·dt/2, so the inertia read from the log is I − kp·dt/2
    expected = I - 40.0 * dt / 2
    assert abs(I_hat - expected) < 3 * se + 0.01 * I and se < 0.05 * I


def test_inertia_reads_the_velocity_twice_and_its_sigma_holds_the_move():
    # the same plant; the "wider" velocity is the logged one scaled by 1/2, so its mean
    # acceleration is the regressor halved: least squares on a column scaled by c reads the
    # slope divided by c (the free steady curve's columns, built from the first velocity, stay),
    # so the second reading is exactly 2·I, a rise, and σ is the jackknife's and that rise in
    # quadrature
    from leuven_friction.identify.diagnose import inertia_read
    from tests.unit.plants import velocity_loop

    t, _, v, f = velocity_loop(0.8, lambda v: 2.0 * np.tanh(v / 1e-3) + 5.0 * v,
                               [0.05, -0.05, 0.2, -0.2, 0.6, -0.6] * 2, 1500, kp=40.0)
    once = inertia_read(f, v, t, 5, 1e-3).estimate
    twice = inertia_read(f, v, t, 5, 1e-3, v_wide=0.5 * v).estimate
    assert once.wider is None and twice.value == once.value
    assert math.isclose(twice.wider, 2.0 * once.value, rel_tol=1e-9)
    assert math.isclose(twice.stderr, math.hypot(once.stderr, once.value), rel_tol=1e-9)
    # read again on the same velocity nothing moves, and on one scaled by 2 it falls to I/2 (a
    # smoothing of the wider slope's own, not the pull of noise towards 0): σ is the jackknife's
    for v_wide in (v, 2.0 * v):
        again = inertia_read(f, v, t, 5, 1e-3, v_wide=v_wide).estimate
        assert again.wider is None and math.isclose(again.stderr, once.stderr, rel_tol=1e-9)


def test_ripple_wavelength_is_read_off_the_spectrum_against_position():
    # strokes back and forth over 0.3 (position units) at varying speed; the relative residual
    # is a ripple of wavelength 0.0237 with a second harmonic: the strongest peak of its
    # spectrum against position is the fundamental, found to within a fraction of a bin
    from leuven_friction.identify.diagnose import _ripple_wavelengths

    dt = 1e-3
    t = np.arange(0, 60, dt)
    x = 0.15 * (1 - np.cos(2 * np.pi * t / 7.0)) + 0.002 * np.sin(2 * np.pi * t / 1.3)
    v = np.gradient(x, dt)
    base = 10.0 * np.sign(v)
    lam = 0.0237
    resid = base * (0.1 * np.sin(2 * np.pi * x / lam) + 0.03 * np.sin(4 * np.pi * x / lam + 1.0))
    c = _cmp(t, x, v, z_pres=1e-4)
    got = _ripple_wavelengths(c, resid, base, lam_min=1e-3)
    assert got and abs(got[0] - lam) < 0.02 * lam
    assert all(g > 0 and np.isfinite(g) for g in got)


def test_free_steady_curve_holds_an_inertia_error_when_given_the_acceleration():
    # friction taken from an applied force with the wrong inertia carries ΔI·ā; beside the
    # acceleration column that residual is taken up entirely, without it barely at all
    rng = np.random.default_rng(5)
    v = _holds([0.05, -0.05, 0.2, -0.2]) + 0.002 * rng.standard_normal(4 * 450)
    acc = np.gradient(v, 1e-3)
    r = 0.3 * acc
    with_acc = FreeSteadyCurve(v, v_rest=1e-3, acceleration=acc)
    assert np.max(np.abs(r - with_acc.fit(r, np.ones(len(v), bool)))) < 1e-6 * np.max(np.abs(r))
    without = FreeSteadyCurve(v, v_rest=1e-3)
    assert np.sqrt(np.mean((r - without.fit(r, np.ones(len(v), bool))) ** 2)) > 0.9 * np.sqrt(np.mean(r**2))


def test_the_model_written_leaves_the_inertia_and_the_memory_constant_free():
    # a plant of I = 2.7 driven along x = A sin(ωt), its friction taken from the applied force by
    # eq. (8) with I = 2: beside the model's (exact) friction the residual is 0.7·ā, plus the
    # memory's constant 0.4 over the start. Both come back, and ΔI with the sign that names the
    # recording's inertia (2 + ΔI = 2.7)
    dt, A, w = 1e-3, 0.3, 2 * np.pi * 1.7
    t = np.arange(0, 6, dt)
    v = A * w * np.cos(w * t)
    F = 4.0 + 1.5 * np.sin(0.9 * t)
    f = -2.7 * A * w * w * np.sin(w * t) + F
    L = 21
    acc = mean_acceleration(v, t, L)
    offset = (t < 1.5).astype(float)
    model = uniform_filter1d(F, L, mode="nearest")  # the model's friction averaged like the measurement
    r = friction_from_force(f, v, 2.0, t, L) - model + 0.4 * offset
    inner = np.zeros(len(t), bool)
    inner[L:-L] = True  # the clipped windows at the ends are no test of the algebra
    got = model_nuisance(r, inner, offset, acc)
    assert got.d_inertia == pytest.approx(0.7, rel=1e-3)
    assert np.max(np.abs((r - got.correction)[inner])) < 1e-3 * np.max(np.abs(r))
    # without the acceleration (friction measured, not taken from a force) the constant only
    only = model_nuisance(r, inner, offset, None)
    assert only.d_inertia == 0.0 and np.all(only.correction[offset == 0] == 0.0)


def _maxwell_slip(x, k, alpha, Fs):
    """Friction of a Maxwell-slip contact along the path ``x`` (elements of stiffness k_i
    slipping at ±α_i·Fs), from a virgin contact: every element unloaded at the start."""
    Fe = np.zeros(len(k))
    out = np.zeros(len(x))
    for i in range(1, len(x)):
        Fe = np.clip(Fe + k * (x[i] - x[i - 1]), -alpha * Fs, alpha * Fs)
        out[i] = Fe.sum()
    return out


def test_initial_memory_leaves_the_first_curve_out_and_a_constant_free_until_the_first_gross_sliding():
    # A virgin Maxwell-slip contact against the Leuven model with its exact reversal curve
    # F_d(z) = Σ min(k_i·z, 2·α_i·Fs): after any reversal the two agree (Masing's rule), but the
    # model starts as if from a reversal at F_h = 0, the contact from its virgin curve
    # Σ min(k_i·z, α_i·Fs). So until the first gross sliding they differ by the constant the
    # first curve left (every later curve starts from a reversal point that inherits it), and
    # after it they agree again.
    from leuven_friction.identify.diagnose import initial_memory, model_nuisance
    from leuven_friction.model import Stribeck, StribeckSide, TransitionCurve, default_params, simulate_displacement

    k = np.array([1e6, 1e5, 3e4])
    alpha = np.array([0.2, 0.3, 0.5])
    Fs = 2.0
    zb = np.sort(2 * alpha * Fs / k)
    z_knots = np.concatenate([[0.0], zb, [2 * zb[-1]]])  # from (0, 0), as Table II
    F_knots = np.array([np.sum(np.minimum(k * z, 2 * alpha * Fs)) for z in z_knots])
    F_knots[-1] += 1e-6 * Fs  # strictly increasing past the last break point
    side = StribeckSide(Fs=Fs, Fc=Fs, vs=1e-3, delta=2.0, sigma2=0.0)
    neg = StribeckSide(Fs=-Fs, Fc=-Fs, vs=-1e-3, delta=2.0, sigma2=0.0)
    p = default_params().replace(stribeck=Stribeck(side, neg), sigma1=0.0, n=40.0,
                                 transition_curve=TransitionCurve(kind="piecewise_linear", z=tuple(z_knots),
                                                                  F=tuple(F_knots)))
    z_pres = zb[-1]
    # nested presliding loops (0 → 0.075 → −0.05 → 0.06 → −0.04 presliding ranges: past the
    # stiff element's break-away, short of sliding), gross sliding to +4, then loops again;
    # 1 ms samples, a smooth path at 1e-4 per second
    turns = np.array([0.0, 0.075, -0.05, 0.06, -0.04, 4.0, 3.4, 3.8, 3.5]) * z_pres
    dt = 1e-3
    legs = [np.linspace(a, b, int(abs(b - a) / (1e-4 * dt)) + 2)[:-1] for a, b in zip(turns[:-1], turns[1:])]
    x = np.concatenate(legs)
    at_turn = np.cumsum([0] + [len(leg) for leg in legs])  # sample index of each turn
    t = np.arange(len(x)) * dt
    v = np.gradient(x, dt)
    measured = _maxwell_slip(x, k, alpha, Fs)
    model = simulate_displacement(p, t, x).friction_force
    c = Comparison("friction", t, measured, x, v, None, None, 1e-3, 0.0, 5, 0.05 * z_pres, 1e-9, z_presliding=z_pres)
    mem = initial_memory(c)
    i_first_turn, i_last_turn = at_turn[1], at_turn[4]  # at 0.075, and at −0.04 where the stroke that slides starts
    i_slide = int(np.argmax(x > turns[4] + 2 * z_pres))  # twice the presliding range from the last turn
    # the first curve is left out, the loops after it are compared, the stroke into the first
    # gross sliding is left out, all after it is compared
    assert not mem.scored[: i_first_turn - 1].any() and mem.scored[i_first_turn + 2: i_last_turn - 1].all()
    assert not mem.scored[i_last_turn + 2: i_slide - 1].any() and mem.scored[i_slide + 2:].all()
    assert mem.offset is not None
    assert np.all(mem.offset[i_first_turn + 2: i_last_turn - 1] == 1) and not mem.offset[i_last_turn + 2:].any()
    r = measured - model
    loops = mem.offset > 0
    left = r - model_nuisance(r, mem.scored, mem.offset, None).correction
    # the first curve leaves a clear difference (the virgin curve is softer past the stiff
    # element's break-away), which the constant takes up through the loops that follow (not
    # exactly: the model keeps its start F_h = 0 as a minimum of its memory, which the first
    # curve down closes, and continues from the outer branch there) …
    assert abs(np.mean(r[loops])) > 0.15 * Fs
    assert np.sqrt(np.mean(left[loops] ** 2)) < 0.1 * np.sqrt(np.mean(r[loops] ** 2))
    # … and after the first gross sliding nothing is left
    after = mem.scored & ~loops
    assert after.sum() > len(x) // 3 and np.max(np.abs(left[after])) < 0.01 * Fs


def test_position_noise_is_that_of_the_noisy_part_of_a_record_logged_partly_exactly():
    # a proximity sensor's noise (σ = 5e-8) over the first 60 % of a slow motion, then a
    # prescribed motion logged exactly: the thresholds must be built on 5e-8, not on a median
    # that the exact part pulls down
    from leuven_friction.identify.diagnose import position_noise

    rng = np.random.default_rng(5)
    n = 40_000
    x = 1e-4 * np.sin(np.linspace(0, 20, n))
    x[: int(0.6 * n)] += rng.normal(0.0, 5e-8, int(0.6 * n))
    sd, q = position_noise(x)
    assert q == 0.0
    assert abs(sd - 5e-8) < 0.1 * 5e-8


def test_savgol_noise_gain_matches_the_filter_on_white_noise():
    from leuven_friction.identify.diagnose import savgol_noise_gain
    from scipy.signal import savgol_filter

    e = np.random.default_rng(6).normal(0.0, 1.0, 400_000)
    for w in (5, 9, 21):
        got = np.std(savgol_filter(e, w, 2)[w:-w])
        assert abs(got - savgol_noise_gain(w)) < 0.01, (w, got, savgol_noise_gain(w))


def test_noise_floor_is_taken_regime_by_regime():
    # a friction log twice as noisy in its second half: each half's floor is its own
    rng = np.random.default_rng(7)
    n = 20_000
    t = np.arange(n) * 1e-3
    meas = np.sin(t) + np.where(t < t[n // 2], rng.normal(0, 0.01, n), rng.normal(0, 0.02, n))
    c = Comparison("friction", t, meas, t.copy(), np.ones(n), None, None, 0.01, 0.0, 5, 1e-5, 1e-3, raw=meas)
    first = t < t[n // 2]
    assert abs(c.noise_on(first) - 0.01) < 0.001 and abs(c.noise_on(~first) - 0.02) < 0.002
    # the noise the position carries through the model adds to a regime's floor
    c.input_noise = np.where(first, 0.03, 0.0)
    assert abs(c.noise_on(first) - math.hypot(0.01, 0.03)) < 0.002


def test_median_stroke_counts_strokes_not_a_velocity_flickering_in_dwells():
    from leuven_friction.identify.diagnose import median_stroke

    # strokes of 0.2 back and forth with dwells in which the position wiggles by 1e-6 about
    # its rest (a noisy sensor, well under min_excursion = 1e-5)
    rng = np.random.default_rng(8)
    legs = []
    pos = 0.0
    for k in range(12):
        end = 0.2 if k % 2 == 0 else 0.0
        legs.append(np.linspace(pos, end, 400))
        legs.append(end + rng.uniform(-1e-6, 1e-6, 300))
        pos = end
    x = np.concatenate(legs)
    t = np.arange(len(x)) * 1e-3
    v = np.gradient(x, t)
    c = _cmp(t, x, v, z_pres=0.01)
    assert abs(median_stroke(c) - 0.2) < 0.01


def test_friction_from_force_reads_a_record_whose_sampling_rate_changes():
    # the same analytic motion as above, logged at 200 Hz for 3 s and then at 500 Hz: the mean
    # acceleration must come from the actual times (a median interval would misread the
    # second part by a factor 2.5)
    I, A, w = 2.5, 0.3, 2 * np.pi * 1.7
    t = np.concatenate([np.arange(0, 3, 5e-3), np.arange(3, 6, 2e-3)])
    v = A * w * np.cos(w * t)
    F = 4.0 + 1.5 * np.sin(0.9 * t)
    f = -I * A * w * w * np.sin(w * t) + F
    L = 5
    got = friction_from_force(f, v, I, t, L)
    want = uniform_filter1d(F, L, mode="nearest")
    err = np.abs(got - want)[L:-L]
    seam = np.abs(t[L:-L] - 3.0) < 3 * 5e-3
    # the centred difference of the velocity over the window against the window's mean
    # acceleration: relative (ω·T)²/24 with T ≤ 4·5 ms, under 0.2 % of the inertial force;
    # at the seam the window's samples are unevenly spread in time (its force mean is not
    # its time mean): under 2 % there
    assert np.max(err[~seam]) < 2e-3 * I * A * w * w
    assert np.max(err[seam]) < 2e-2 * I * A * w * w
    # read with the median interval, the 500 Hz part would be off by most of the inertial force
    wrong = uniform_filter1d(f, L, mode="nearest") - I * (np.roll(v, -2) - np.roll(v, 2)) / (4 * 5e-3)
    assert np.max(np.abs(wrong - want)[L:-L][t[L:-L] > 3.1]) > 0.5 * I * A * w * w


def test_moved_from_held_tells_a_refit_from_the_common_level():
    from leuven_friction.identify.diagnose import bake, moved_from_held
    from leuven_friction.model import Stribeck, StribeckSide, default_params

    p = default_params()
    pos = p.stribeck.positive
    coulomb = p.replace(stribeck=Stribeck(StribeckSide(Fs=pos.Fc, Fc=pos.Fc, vs=pos.vs, delta=pos.delta,
                                                       sigma2=pos.sigma2), p.stribeck.negative))
    held = {"stribeck.positive.Fs": "held at Fc", "stribeck.positive.vs": "held", "n": "fixed at 7",
            "inertia": "not estimated", "transition_curve": "kept"}
    # every force scaled by the level g (and z by κ0): nothing held has moved
    assert moved_from_held(held, coulomb, bake(coulomb, 1.3, 0.8), 1.3, False) == {}
    # F_s refitted apart from F_c, n refitted, the curve reshaped: those three moved
    q = coulomb.replace(n=3.5, stribeck=Stribeck(StribeckSide(Fs=1.1 * pos.Fc, Fc=pos.Fc, vs=pos.vs, delta=pos.delta,
                                                              sigma2=pos.sigma2), p.stribeck.negative))
    moved = moved_from_held(held, coulomb, bake(q, 1.3, 0.8), 1.3, True)
    assert set(moved) == {"stribeck.positive.Fs", "n", "transition_curve"}
    assert moved["n"] == (f"{coulomb.n:.4g}", "3.5")


def test_a_curve_compressed_below_the_sensors_resolution_is_written_as_a_bound():
    # a 0.01° encoder (1.75·10⁻⁴ rad) and `fit`'s knots 0.52–2.76 mrad apart: the curve as
    # fitted is resolved; with the presliding stiffness ×18 a refit reached, its knots are 29 µrad
    # apart, under two encoder steps: said as a bound, with the spacing and the step
    from leuven_friction.identify.diagnose import ComparedPath, bake, unresolved_curve
    from leuven_friction.model import TransitionCurve, default_params

    p = default_params().replace(transition_curve=TransitionCurve(
        kind="piecewise_linear", z=(0.0, 5.2e-4, 1.35e-3, 1.93e-3, 2.76e-3), F=(0.0, 9.6e-3, 13.2e-3, 16.5e-3, 17.9e-3)))
    enc = ComparedPath(np.zeros(3), 5e-5, np.deg2rad(0.01), 5, 3.5e-4)
    assert unresolved_curve(bake(p, 1.0, 1.0), enc, 1.0, "rad") is None
    said = unresolved_curve(bake(p, 0.25, 18.2), enc, 18.2, "rad")
    assert said is not None and "0.000175 rad, an encoder step" in said and "not an estimate" in said, said
    # a Gaussian sensor: its noise sd is the resolution
    gauss = ComparedPath(np.zeros(3), 4e-4, 0.0, 5, 8e-4)
    assert "its noise sd" in unresolved_curve(bake(p, 1.0, 1.0), gauss, 1.0)


def test_a_load_rising_over_the_session_steps_or_not_is_told_to_follow_time():
    # a tendon's pretension: 10 N, a step to 18 N, ramps to 30 N, a step to 36 N, a ramp to 40 N,
    # with 0.15 N of noise: it follows time; the same load cycled up and down three times does not
    from types import SimpleNamespace

    from leuven_friction.identify.diagnose import SPEED_ORDER_RHO, load_order

    rng = np.random.default_rng(2)
    t = np.linspace(0.0, 116.0, 50000)
    rising = np.interp(t, [0, 17.4, 17.401, 46.4, 69.6, 69.601, 116], [10, 10, 18, 26, 30, 36, 40])
    cycled = 25.0 + 15.0 * np.sin(2 * np.pi * 3 * t / 116.0)
    everywhere = np.ones(len(t), bool)
    for load, follows in ((rising, True), (cycled, False)):
        cmp_ = SimpleNamespace(time=t, load=load + rng.normal(0, 0.15, len(t)))
        assert (load_order(cmp_, everywhere).rho >= SPEED_ORDER_RHO) == follows
    assert math.isnan(load_order(SimpleNamespace(time=t, load=np.full(len(t), 20.0)), everywhere).rho)


def test_jackknife_over_folds_is_the_standard_error_from_the_group_means():
    # the mean of k equal groups, each refit leaving one group out: the delete-a-group
    # jackknife's σ is the standard error of the mean estimated from the k group means,
    # sd(group means)/√k (an identity, whatever the data)
    from leuven_friction.identify.diagnose import jackknife_sd

    rng = np.random.default_rng(5)
    x = rng.normal(3.0, 2.0, 500)
    groups = x.reshape(5, 100)
    leave_out = [np.delete(groups, i, axis=0).mean() for i in range(5)]
    expected = groups.mean(axis=1).std(ddof=1) / math.sqrt(5)
    assert jackknife_sd(x.mean(), leave_out) == pytest.approx(expected, rel=1e-12)
    # and across a large sample of such sessions its spread matches that of the estimate itself
    est, sds = [], []
    for _ in range(2000):
        g = rng.normal(3.0, 2.0, (5, 40))
        est.append(g.mean())
        sds.append(jackknife_sd(g.mean(), [np.delete(g, i, axis=0).mean() for i in range(5)]))
    assert np.sqrt(np.mean(np.square(sds))) == pytest.approx(2.0 / math.sqrt(200), rel=0.05)
    assert np.std(est) == pytest.approx(2.0 / math.sqrt(200), rel=0.05)


def test_jackknife_of_a_phase_does_not_count_a_turn_as_spread():
    from leuven_friction.identify.diagnose import jackknife_sd

    folds = [math.pi - 0.01, -math.pi + 0.01, math.pi - 0.03, -math.pi + 0.02, math.pi]
    # their deviations from π, a turn taken off: −0.01, 0.01, −0.03, 0.02, 0
    d = np.array([-0.01, 0.01, -0.03, 0.02, 0.0])
    expected = math.sqrt(4 / 5 * np.sum((d - d.mean()) ** 2))
    assert jackknife_sd(math.pi, folds, angle=True) == pytest.approx(expected, rel=1e-9)
    assert jackknife_sd(math.pi, folds) > 1.0  # taken as plain numbers, the turn would be spread


def test_effect_sds_leave_fixed_parameters_and_unnamed_terms_without_one():
    from leuven_friction.identify.diagnose import effect_sds

    drift = Term("time_drift", {"t0": 0.0}, (("b", "lin", -0.9, 5.0), ("tau", "log", 0.0, 9.0)))
    rate = Term("rate_stiffness", {"v_ref": 0.1, "v_floor": 1e-4}, (("c1", "lin", -2, 2), ("c2", "lin", -1, 1)))
    full = [{"name": "rate_stiffness", "params": {"v_ref": 0.1, "v_floor": 1e-4, "c1": 0.2, "c2": 0.0}},
            {"name": "time_drift", "params": {"t0": 0.0, "b": -0.2, "tau": 50.0}}]
    folds = [[{"name": "rate_stiffness", "params": {"v_ref": 0.1, "v_floor": 1e-4, "c1": 0.2 + d, "c2": 0.0}},
              {"name": "time_drift", "params": {"t0": 0.0, "b": -0.2 + d, "tau": 50.0 + 100 * d}}]
             for d in (-0.02, -0.01, 0.0, 0.01, 0.02)]
    sds = effect_sds([rate, drift], full, folds, ["time_drift"])
    assert set(sds) == {"time_drift"} and set(sds["time_drift"]) == {"b", "tau"}
    assert sds["time_drift"]["b"] == pytest.approx(math.sqrt(4 / 5 * 0.001))
    assert sds["time_drift"]["tau"] == pytest.approx(100 * math.sqrt(4 / 5 * 0.001))


def test_a_parameter_held_at_its_bound_gets_no_sigma():
    # named without settling (``--no-require-settling``): n_c at the top of its range in every
    # fold, where the bound and not the data holds it; h, free inside its range, keeps its σ
    from leuven_friction.identify.diagnose import effect_sds

    soft = Term("cyclic_softening", {"min_excursion": 1e-6}, (("h", "lin", -0.9, 5.0),
                                                               ("n_c", "log", math.log(3.0), math.log(11.5))),
                settles="n_c")
    full = [{"name": "cyclic_softening", "params": {"min_excursion": 1e-6, "h": -0.3, "n_c": 11.5}}]
    folds = [[{"name": "cyclic_softening", "params": {"min_excursion": 1e-6, "h": -0.3 + d, "n_c": 11.5}}]
             for d in (-0.02, -0.01, 0.0, 0.01, 0.02)]
    assert effect_sds([soft], full, folds, {"cyclic_softening"}) == {"cyclic_softening": {"h": pytest.approx(
        math.sqrt(4 / 5 * 0.001))}}
    inside = [{"name": "cyclic_softening", "params": {"min_excursion": 1e-6, "h": -0.3, "n_c": 6.0}}]
    assert set(effect_sds([soft], inside, folds, {"cyclic_softening"})["cyclic_softening"]) == {"h", "n_c"}
    # a drift whose end value b sits at its floor −0.9 in every fold (a linear parameter): no σ
    # for b (the jackknife would give ~1e-8), τ inside its range keeps one
    drift = Term("time_drift", {"t0": 0.0}, (("b", "lin", -0.9, 5.0), ("tau", "log", math.log(10.0), math.log(2000.0))))
    full = [{"name": "time_drift", "params": {"t0": 0.0, "b": -0.9, "tau": 300.0}}]
    folds = [[{"name": "time_drift", "params": {"t0": 0.0, "b": -0.9 + 1e-8 * d, "tau": 300.0 + 10 * d}}]
             for d in (-2, -1, 0, 1, 2)]
    assert effect_sds([drift], full, folds, {"time_drift"}) == {"time_drift": {"tau": pytest.approx(
        math.sqrt(4 / 5 * 1000.0))}}


def test_steady_stribeck_identifies_s_of_v_anew_under_a_load_the_file_averaged_over():
    # the file's S(v) is what a fit gives when its Markov levels average over a varying load:
    # Coulomb (F_s held at F_c), σ2 held at 0. The recording: a Stribeck curve + viscous law of
    # another machine (its own F_s, F_c, v_s, δ, σ2 per side), times a load factor that changes
    # from hold to hold, plus noise. With the load's factor divided out, the Markov estimator on
    # the steady levels recovers that law; the file's S(v), even at its best level per side,
    # cannot follow it. A file with the true law is left as it is (no clear gain).
    from leuven_friction.identify.diagnose import steady_stribeck
    from leuven_friction.model import Stribeck, StribeckSide, default_params
    from tests.paper import two_sided

    def law(st, v):  # eqs. (6)-(7) written out (tests/paper.py), on a Stribeck's two sides
        return two_sided(*[tuple(getattr(getattr(st, sd), k) for k in ("Fs", "Fc", "vs", "delta", "sigma2"))
                           for sd in ("positive", "negative")], v)

    rng = np.random.default_rng(3)
    true = Stribeck(StribeckSide(Fs=9.0, Fc=5.0, vs=0.02, delta=1.4, sigma2=3.0),
                    StribeckSide(Fs=-7.0, Fc=-4.0, vs=-0.03, delta=0.8, sigma2=2.5))
    base = default_params()
    truth = base.replace(stribeck=true)
    speeds = np.geomspace(0.002, 1.0, 14)
    v = _holds([s * sg for s in speeds for sg in (1, -1)], n_per=300)
    load = np.repeat(rng.uniform(0.6, 1.6, len(v) // 350 + 1), 350)[: len(v)]
    meas = law(true, v) * load + rng.normal(0.0, 0.05, len(v))
    t = np.arange(len(v)) * 1e-3
    c = Comparison("friction", t, meas, np.cumsum(v) * 1e-3, v, None, None, 0.05, 1e-6, 5, 1e-5, 1e-4)
    steady = np.abs(v) > 0
    coulomb = base.replace(stribeck=Stribeck(StribeckSide(Fs=6.0, Fc=6.0, vs=0.001, delta=1.0, sigma2=0.0),
                                             StribeckSide(Fs=-5.0, Fc=-5.0, vs=-0.001, delta=1.0, sigma2=0.0)))
    reid = steady_stribeck(coulomb, c, load, steady)
    assert reid is not None and reid.sides == ("positive", "negative") and reid.levels == 28
    assert reid.used and reid.gap_new < 0.5 * reid.gap_file
    # the noise's 0.05 over 300 samples a level, counted in stretches of 5 (a level's sd 0.0065)
    assert reid.noise == pytest.approx(0.05 / math.sqrt(60), rel=0.15) and reid.gap_new < 2 * reid.noise
    assert np.allclose(law(reid.stribeck, v), law(true, v), rtol=0.02, atol=0.02)
    for side in ("positive", "negative"):
        assert getattr(reid.stribeck, side).sigma2 == pytest.approx(getattr(true, side).sigma2, rel=0.05)
    # the load left in: the levels scatter with it, and S(v) no longer follows the law
    unfactored = steady_stribeck(coulomb, c, np.ones(len(v)), steady)
    assert unfactored.gap_new > 10 * reid.gap_new
    # the file already holds the law: it fits within the levels' noise, and is kept
    same = steady_stribeck(truth, c, load, steady)
    assert same.gap_file < 2 * same.noise and not same.used


def _rests_and_strokes(spring: float, q: float):
    """A joint held still, pushed back and forth by ±6 within its static band (friction at rest
    is what is applied), then slid at ±0.05 with friction ±10; the position is the motion the
    contact's ``spring`` allows under that push, quantised to steps of ``q``."""
    t = np.arange(20_000) * 2e-3
    push = 6.0 * np.sin(2 * np.pi * t / 4.0)
    rest = t < 20.0
    x_true = np.where(rest, push / spring, 0.0)
    slide = ~rest
    v_true = np.where(slide, 0.05 * np.sign(np.sin(2 * np.pi * (t - 20.0) / 8.0)), 0.0)
    x_true = x_true + np.cumsum(v_true) * 2e-3
    friction = np.where(rest, push, 10.0 * np.sign(v_true))
    x = np.round(x_true / q) * q
    v = np.gradient(x_true, t)
    c = Comparison("friction", t, friction, x, v, None, None, 0.05, q / math.sqrt(12), 5, 4 * q, 3e-3, average=5,
                   z_presliding=1e-4)
    return c


def test_rests_are_unresolved_where_the_friction_swings_while_the_position_stands():
    # a spring of 6e4 moves 1e-4 under the push: an encoder of 1e-6 sees it, so its rests (one
    # step each) hold the friction within a step's worth of force, 6e4·1e-6 = 0.06, of the level 10
    seen = unresolved_rest(_rests_and_strokes(6e4, 1e-6))
    assert seen.runs > 50 and not seen.unresolved and seen.ratio < 0.05
    # an encoder step of 4e-4 is longer than all of it: the friction swings over ±6 (12 of 10)
    # while the position stands
    hidden = unresolved_rest(_rests_and_strokes(6e4, 4e-4))
    assert hidden.unresolved and hidden.ratio == pytest.approx(1.2, rel=0.1)
    # the joint stood for the first 20 s (10,000 samples): nearly all of them are the rests left
    # out, and next to nothing of the 20 s of sliding after them
    assert hidden.mask[:10_000].mean() > 0.95 and hidden.mask[10_000:].mean() < 0.02


def test_the_compared_path_removes_wiggles_without_lagging_the_motion():
    # a triangle of travel ±1 with Gaussian noise of sd 1e-3 and dwells: the play of half-width
    # h = 4 sd holds the dwells flat but runs h behind while moving (after each reversal the
    # model would run 2h behind on its transition curve); the centred play follows the motion
    from leuven_friction.identify.diagnose import centred_play, play

    rng = np.random.default_rng(3)
    legs, pos = [], 0.0
    for end in (1.0, -1.0, 1.0, 0.0):
        legs.append(np.linspace(pos, end, 2000))
        legs.append(np.full(500, end))
        pos = end
    x_true = np.concatenate(legs)
    sd, h = 1e-3, 4e-3
    x = x_true + rng.normal(0.0, sd, len(x_true))
    v = np.gradient(x_true)
    moving = np.abs(v) > 0
    for path, lag in ((play(x, h), h), (centred_play(x, h), 0.0)):
        err = (path - x_true)[moving] * np.sign(v[moving])
        assert abs(np.mean(err) + lag) < 0.3 * h, (np.mean(err), lag)
    c = centred_play(x, h)
    # the path turns three times, where the motion does: no wiggle of the dwells reaches the model
    # (after its first samples: the play starts at the first reading, a noise draw h from it moves it)
    steps = np.sign(np.diff(c[50:]))
    steps = steps[steps != 0]
    assert int(np.sum(steps[1:] != steps[:-1])) == 3
    # the turns are where the motion turned (within the noise), not h short of them
    assert abs(c.max() - 1.0) < 4 * sd and abs(c.min() + 1.0) < 4 * sd
    # the path the diagnosis compares along is the centred one for such a sensor (Gaussian noise)
    from leuven_friction.identify.diagnose import compared_path

    cp = compared_path(x, 1e-3)
    assert cp.step == 0.0
    assert abs(np.mean((cp.path - x_true)[moving] * np.sign(v[moving]))) < 0.3 * cp.h


def test_median_stroke_is_the_stroke_that_carries_the_travel_not_a_controllers_dither():
    from leuven_friction.identify.diagnose import median_stroke

    # six strokes of 0.2 with dwells in which a controller holding the position reverses forty
    # times by 3e-5 (over min_excursion = 1e-5): 240 dither strokes against 6 real ones, but
    # they carry 1 % of the travel
    legs, pos = [], 0.0
    for k in range(6):
        end = 0.2 if k % 2 == 0 else 0.0
        legs.append(np.linspace(pos, end, 400))
        legs.append(end + 3e-5 * (np.arange(40 * 8) // 8 % 2))
        pos = end
    x = np.concatenate(legs)
    t = np.arange(len(x)) * 1e-3
    c = _cmp(t, x, np.gradient(x, t), z_pres=0.01)
    assert abs(median_stroke(c) - 0.2) < 0.01


def test_softening_thresholds_double_while_six_reversals_remain_and_skip_equal_counts():
    # five small cycles (back-travel 0.15) then four large ones (1.0): 17 turning points, all
    # counted at 0.1; at 0.2 only the 7 of the large strokes — at 0.4 and 0.8 the very same
    # reversals, left out — and at 1.6 none, where the doubling stops
    from types import SimpleNamespace

    from leuven_friction.identify.diagnose import softening_thresholds
    from leuven_friction.model.effects import significant_reversals

    turns = [0.0, 0.15] * 5 + [0.0, 1.0] * 4 + [0.0]
    x = np.concatenate([np.linspace(a, b, 40, endpoint=False) for a, b in zip(turns[:-1], turns[1:])])
    assert [significant_reversals(x, th)[-1] for th in (0.1, 0.2, 0.4, 0.8, 1.6)] == [17, 7, 7, 7, 0]
    c = SimpleNamespace(min_excursion=0.1, path=x)
    assert softening_thresholds(c, 1) == [0.1]
    assert softening_thresholds(c, 6) == [0.1, 0.2]
    assert softening_thresholds(SimpleNamespace(min_excursion=2.0, path=x), 6) == [2.0]  # none counts: the base kept
    # a back-travel the user set is what counts as a reversal, the softening's too: it alone
    set_ = SimpleNamespace(min_excursion=0.1, path=x, reading=SimpleNamespace(set_by_user=("min_excursion",)))
    assert softening_thresholds(set_, 6) == [0.1]


def test_a_softening_over_within_the_reversals_before_the_first_gross_sliding_is_not_seen_to_settle():
    # 6 reversals before the first gross sliding at 60 s: an n_c of 3.5 has 1 − e^(−6/3.5) = 82 %
    # of its change there, within the session's first experiment (a step between it and the
    # rest looks the same); an n_c of 7 has 58 % (its n_c past those 6), and is judged as before
    import math

    from leuven_friction.identify.diagnose import Term

    free = (("h", "lin", -0.9, 5.0), ("n_c", "log", math.log(3.0), math.log(40.0)))
    term = Term("cyclic_softening", {"min_excursion": 1e-5}, free, settles="n_c", before_sliding=(6.0, 60.1))
    why = term.unsettled(np.array([-0.3, math.log(3.5)]))
    assert why is not None and "within the 6 reversals before the first gross sliding (at 60.1 s)" in why, why
    assert "82%" in why, why
    assert term.unsettled(np.array([-0.3, math.log(7.0)])) is None
    # with none there (a record that slides before it reverses) only the bounds count
    none_before = Term("cyclic_softening", {"min_excursion": 1e-5}, free, settles="n_c", before_sliding=(0.0, 1.0))
    assert none_before.unsettled(np.array([-0.3, math.log(3.5)])) is None
    assert "lower bound" in none_before.unsettled(np.array([-0.3, math.log(3.0)]))

def test_a_factor_of_the_alternative_at_a_bound_of_its_range_is_said_to_be_there():
    # κ0 within ×1/20 … ×20: at ×20 the record pushed it to the end of its range, at ×0.83 it settled
    from leuven_friction.identify.diagnose import _factor_said

    assert _factor_said(0.83, 20.0) == "×0.830"
    assert _factor_said(20.0, 20.0) == "×20.000 (at the end of its range ×1/20–×20)"
    assert _factor_said(1 / 20.0, 20.0).endswith("(at the end of its range ×1/20–×20)")
    assert _factor_said(4.9, 5.0) == "×4.900"  # 2 % inside a bound is not at it

def test_observed_presliding_range_reads_the_crossing_after_each_turn_of_a_maxwell_slip_contact():
    # Strokes of ±10 presliding ranges of a Maxwell-slip contact (its friction computed here
    # element by element): after each turn the friction follows the reversal curve
    # Σ min(k_i·dx, 2·α_i·Fs) (Masing), so it has covered 90 % of its 2·Fs swing where that sum
    # reaches 1.8·Fs — a travel solved here on a fine grid, not by the function under test.
    # The range read must be that travel (to a sample), and follow the position's unit.
    from leuven_friction.identify.diagnose import observed_presliding_range

    k = np.array([1e6, 1e5, 3e4])
    alpha = np.array([0.2, 0.3, 0.5])
    Fs = 2.0
    zg = np.linspace(0.0, 1e-4, 200001)
    rev = np.sum(np.minimum(np.outer(zg, k), 2 * alpha * Fs), axis=1)
    expect = float(zg[np.argmax(rev > 1.8 * Fs)])
    z_pres = float(np.max(2 * alpha * Fs / k))
    amp, step = 10 * z_pres, z_pres / 200  # samples 1/200 of the range apart
    turns = np.array([0.0, amp, -amp, amp, -amp, amp, -amp])
    x = np.concatenate([np.arange(a, b, step * np.sign(b - a)) for a, b in zip(turns[:-1], turns[1:])])
    t = np.arange(len(x)) * 1e-3
    rng = np.random.default_rng(3)
    noise = 0.005 * Fs
    measured = _maxwell_slip(x, k, alpha, Fs) + rng.normal(0.0, noise, len(x))
    for unit in (1.0, 1e3):  # in m, and the same motion in mm
        xs = x * unit
        c = Comparison("friction", t, measured, xs, np.gradient(xs, t), None, None, noise, 0.0, 5,
                       0.05 * z_pres * unit, 1e-9, z_presliding=1e3 * z_pres * unit)
        seen = observed_presliding_range(c)
        assert seen is not None and abs(seen - expect * unit) <= 3 * step * unit
    # two strokes say nothing
    c = Comparison("friction", t[: 2 * int(2 * amp / step)], measured[: 2 * int(2 * amp / step)],
                   x[: 2 * int(2 * amp / step)], np.gradient(x, t)[: 2 * int(2 * amp / step)], None, None, noise, 0.0,
                   5, 0.05 * z_pres, 1e-9)
    assert observed_presliding_range(c) is None


def _coarse_encoder_sweep(tmp_path):
    """A joint swept at ±0.002, ±0.02 and ±0.3 rad/s (4 s each, rests between) logged at
    500 Hz through an encoder of 4.8·10⁻⁵ rad, written as a real CSV: the slowest level moves
    one step every 12 samples, under the rest speed of the shortest window."""
    from leuven_friction.identify.data import load_recording

    dt, q = 2e-3, 4.8e-5
    v = np.concatenate([np.r_[np.zeros(500), np.full(2000, s * lv)] for lv in (0.002, 0.02, 0.3) for s in (1, -1)]
                       + [np.zeros(500)])
    t = np.arange(len(v)) * dt
    x = np.concatenate([[0.0], np.cumsum(v[1:] * dt)])  # exact: the speed is constant between samples
    rows = ["time [s],position [rad],friction [N*m]"] + [
        f"{ti:.4f},{q * np.floor(xi / q + 0.5):.7g},{2.0 * np.tanh(vi / 1e-3):.5g}" for ti, xi, vi in zip(t, x, v)]
    path = tmp_path / "coarse.csv"
    path.write_text("\n".join(rows) + "\n")
    return load_recording(str(path)), t, v, dt, q


def _note_with_window_set(rec):
    from leuven_friction.identify.diagnose import motion_reading

    return motion_reading(rec, {"window": 301}).note()


def test_a_longer_window_set_by_the_user_reads_slow_sliding_a_short_one_takes_for_rest(tmp_path):
    from leuven_friction.identify.diagnose import motion_reading

    rec, t, v, dt, q = _coarse_encoder_sweep(tmp_path)
    slow = np.abs(np.abs(v) - 0.002) < 1e-12
    derived = motion_reading(rec)
    assert derived.set_by_user == ()
    # the derived window is short (the fast levels set it): the slowest level counts as rest
    assert derived.v_rest > 3 * 0.002
    assert np.mean(np.abs(derived.velocity[slow]) > derived.v_rest) < 0.2
    # and the note says the encoder's step sets that rest speed (one step per window, above the
    # slowest level's 0.002 rad/s), and what lowers it
    import re

    said = re.search(r"one encoder step per (\d+) samples is ([0-9.e+-]+)", derived.note())
    assert said and int(said.group(1)) == derived.compared.window, derived.note()
    assert float(said.group(2)) == pytest.approx(q / (derived.compared.window * dt), rel=0.01) and float(said.group(2)) > 0.002
    assert "a longer window lowers it" in derived.note() and "lowers it" not in _note_with_window_set(rec)
    W = 301
    m = motion_reading(rec, {"window": W})
    # the rest speed follows the window set: three times one encoder step per window (the
    # step's noise over the window, q/(W^1.5·dt), is far smaller)
    assert m.compared.window == W and m.v_rest == pytest.approx(3 * q / (W * dt), rel=0.02)
    # away from the level's ends by a window, the slow sliding is read, at its speed
    inner = slow & (np.convolve(slow, np.ones(2 * W + 1), "same") >= 2 * W + 1)
    assert inner.sum() > 2000
    assert np.all(np.abs(m.velocity[inner]) > m.v_rest)
    assert np.allclose(np.abs(m.velocity[inner]), 0.002, rtol=0.05)
    # and the note says which thresholds were set, beside those still derived
    note = m.note()
    assert f"smoothed over {W} samples (set)" in note and "counts as presliding;" in note
    both = motion_reading(rec, {"window": W, "v_rest": 1e-3, "min_excursion": 2e-4})
    assert both.v_rest == 1e-3 and both.min_excursion == 2e-4
    assert "|v| < 0.001 (set)" in both.note() and "0.0002 (set) of back-travel" in both.note()


def test_the_back_travel_a_reversal_needs_is_the_one_the_note_says_and_a_users_setting_holds(tmp_path):
    # a quarter of the model's presliding range raises the reading's own threshold (the
    # position's noise), and the reading's note says the value used, not the one raised from;
    # a value the user set holds, below that quarter too
    from types import SimpleNamespace

    from leuven_friction.identify.diagnose import motion_reading, reversal_threshold

    rec, *_ = _coarse_encoder_sweep(tmp_path)

    def threshold(overrides, z_presliding):
        m = motion_reading(rec, overrides)
        c = SimpleNamespace(reading=m, z_presliding=z_presliding, min_excursion=m.min_excursion,
                            position_unit="rad", notes=[m.note("rad"), "another note"])
        reversal_threshold(c)
        return m, c

    m, c = threshold(None, 4e-3)  # a quarter: 1e-3, over the encoder's 4 steps (1.9e-4)
    assert m.min_excursion < 1e-3 and c.min_excursion == pytest.approx(1e-3)
    assert "a reversal counts from 0.001 rad (a quarter of the model's presliding range" in c.notes[0]
    assert c.notes[1] == "another note"
    m, c = threshold(None, 1e-4)  # a quarter under the position's noise: the reading's own holds
    assert c.min_excursion == m.min_excursion and c.notes[0] == m.note("rad")
    m, c = threshold({"min_excursion": 2e-4}, 4e-3)
    assert c.min_excursion == 2e-4
    assert "0.0002 rad (set) (under a quarter of the model's presliding range, 0.001" in c.notes[0]


def _ar1_mean_sd(sd_e: float, rho: float, L: int) -> float:
    """sd of the mean of L consecutive samples of AR(1) noise x_k = ρ·x_{k−1} + e_k."""
    k = np.arange(1, L)
    g0 = sd_e**2 / (1.0 - rho**2)
    return math.sqrt(g0 / L * (1.0 + 2.0 * np.sum((1.0 - k / L) * rho**k)))


def _ar1(n: int, rho: float, sd_e: float, rng) -> np.ndarray:
    ar = np.zeros(n)
    e = rng.normal(0.0, sd_e, n)
    for i in range(1, n):
        ar[i] = rho * ar[i - 1] + e[i]
    return ar


def test_noise_colour_is_the_averaged_noise_of_correlated_noise_over_that_of_white():
    rng = np.random.default_rng(4)
    n, L, rho, sd_e, sd_w = 60_000, 100, 0.96, 1.0, 2.0
    ar = _ar1(n, rho, sd_e, rng)
    t = np.arange(n) * 1e-3
    # a stuck contact under torque ramps: the force a triangle wave in time, the machine at rest
    ramp = 50.0 * np.abs(((t / 7.0) % 2.0) - 1.0)
    rest = np.ones(n, bool)
    rest[20_000:20_500] = False  # a stroke between the rests
    white_noise = ramp + rng.normal(0.0, sd_w, n)
    coloured = white_noise + ar
    assert noise_colour(white_noise, rest, L).factor == 1.0
    # a force that swings at rest within a few averaging lengths (presliding cycles) is not noise
    swing = 30.0 * np.sin(2 * np.pi * t / 0.35) * (1.0 + 0.5 * np.sin(2 * np.pi * t / 1.3))
    assert noise_colour(swing + rng.normal(0.0, sd_w, n), rest, L).factor == 1.0
    c = noise_colour(coloured, rest, L)
    # white noise of the same sample-to-sample sd: var(Δ)/2 = sd_w² + γ0(1 − ρ)
    white_equivalent = math.sqrt(sd_w**2 + sd_e**2 / (1.0 - rho**2) * (1.0 - rho)) / math.sqrt(L)
    expected = math.sqrt(sd_w**2 / L + _ar1_mean_sd(sd_e, rho, L) ** 2) / white_equivalent
    # sized over the whole averaging; neighbouring means of this noise are correlated, and their
    # third differences read it low (0.75–0.94 of the truth over twelve seeds), never high
    assert c.sized_over == L and 0.7 * expected < c.factor < 1.02 * expected, (c, expected)
    # the same noise beside that swing: seen over the shortest blocks, sized only as far as the
    # swing lets it be told apart — a lower bound, which the note says, never the swing itself
    both = noise_colour(coloured + swing, rest, L)
    assert both.factor > 1.0 and both.sized_over < L and both.factor < 1.02 * expected, (both, expected)
    assert "at least" in both.note()
    # nothing at rest long enough for four blocks: nothing is claimed
    assert noise_colour(coloured, np.zeros(n, bool), L).factor == 1.0


def test_noise_colour_is_seen_at_a_short_averaging_too():
    # eq. (8) averaged over 13 samples: read over blocks of 13, not 13/8
    rng = np.random.default_rng(7)
    n, L, rho = 60_000, 13, 0.96
    t = np.arange(n) * 1e-3
    ramp = 50.0 * np.abs(((t / 7.0) % 2.0) - 1.0)
    rest = np.ones(n, bool)
    x = ramp + rng.normal(0.0, 2.0, n) + _ar1(n, rho, 1.0, rng)
    white_equivalent = math.sqrt(4.0 + 1.0 / (1.0 - rho**2) * (1.0 - rho)) / math.sqrt(L)
    expected = math.sqrt(4.0 / L + _ar1_mean_sd(1.0, rho, L) ** 2) / white_equivalent
    c = noise_colour(x, rest, L)
    # seen and counted; correlated over longer than the averaging (25 samples against 13), its
    # neighbouring means read it well low (measured 2.5 for 5.7): a lower bound, never above
    assert c.shortest == 13 and 2.0 < c.factor < expected, (c, expected)
    assert noise_colour(ramp + rng.normal(0.0, 2.0, n), rest, L).factor == 1.0


def test_a_written_value_moved_from_the_decided_one_widens_its_sigma_by_the_move():
    sd = {"a": 0.0037, "phase": 0.007, "wavelength": float("nan")}
    decided = {"a": 0.087, "phase": 3.10, "wavelength": 0.1274}
    written = {"a": 0.104, "phase": -3.10, "wavelength": 0.1275}
    out = with_model_shift(sd, decided, written)
    assert out["a"] == pytest.approx(math.sqrt(0.0037**2 + 0.017**2))
    # 3.10 → −3.10 is a step of 2π − 6.20 ≈ 0.083 across ±π, not 6.2
    assert out["phase"] == pytest.approx(math.sqrt(0.007**2 + (2 * math.pi - 6.20) ** 2))
    assert math.isnan(out["wavelength"])  # no σ to widen: none is made up
    # nothing moved: the folds' σ stands
    assert with_model_shift(sd, decided, decided)["a"] == pytest.approx(0.0037)


def test_a_candidate_that_gains_held_out_but_not_where_it_must_show_is_seen_elsewhere_not_evident():
    from leuven_friction.identify.diagnose import Evidence, Settings

    s = Settings()
    better = np.array([0.80, 0.85, 0.90, 1.10, 0.80])  # held-out SSE against the alternative's 1: 4 of 5 folds
    null, inf = np.ones(5), np.ones(5, bool)

    def ev(sse, failed):
        return Evidence("time_drift", {}, 1.0, sse, null, inf, 0.0, not_where_it_shows=failed, where="steady sliding",
                        gain_where=0.02, folds_where="3/5")

    # 1 − √(mean SSE ratio) = 1 − √0.89 ≈ 5.7 % pooled, over the 3 % bar
    there, elsewhere = ev(better, None), ev(better, "steady sliding")
    assert there.evident(s) and not there.elsewhere(s)
    assert elsewhere.elsewhere(s) and not elsewhere.evident(s) and not elsewhere.passes(s)
    d = elsewhere.as_dict(s)
    assert d["elsewhere"] and not d["evident"] and d["not_where_it_shows"] == "steady sliding"
    # no held-out gain at all: neither named nor said to be seen
    assert not ev(np.full(5, 1.05), "steady sliding").elsewhere(s)


def test_a_stiffness_following_the_friction_effects_held_at_a_fit_is_exact_there_and_simulates_less(kuka):
    # A presliding range that follows a load's factor, held at the factor of one set of entries:
    # the prediction there is the one that follows the current factor, to rounding; away from
    # it the stiffness stays where it was held (the presliding response differs, the sliding
    # level follows the new load law), and moving the load's exponent, a friction effect only,
    # asks for no new simulation of the record.
    from leuven_friction.identify.data import Recording
    from leuven_friction.identify.diagnose import Engine, comparison_of

    t = np.arange(0.0, 8.0, 1e-3)
    x = 2e-3 * np.sin(2 * np.pi * 0.5 * t) * (1 + 0.5 * np.sin(2 * np.pi * 0.13 * t))
    load = 100.0 * (1.0 + 0.4 * np.sin(2 * np.pi * 0.21 * t))
    rec = Recording(time=t, position=x, friction=np.zeros_like(t), normal_load=load)
    eng = Engine(kuka, comparison_of(rec, kuka))
    at = [{"name": "normal_load", "params": {"N0": 100.0, "alpha": 0.8}},
          {"name": "presliding_range", "params": {"e": 0.7}}]
    moved = [{"name": "normal_load", "params": {"N0": 100.0, "alpha": 1.1}}, at[1]]
    exact_at, exact_moved = eng.predict(1.0, 1.0, at), eng.predict(1.0, 1.0, moved)
    eng.following_held(at)
    held_at = eng.predict(1.0, 1.0, at)
    before = eng.sims
    held_moved = eng.predict(1.0, 1.0, moved)
    assert eng.sims == before
    scale = np.max(np.abs(exact_at))
    assert np.max(np.abs(held_at - exact_at)) < 1e-12 * scale
    # the held stiffness is a different model away from the anchor: not the exact one in
    # presliding, but in gross sliding (the fastest tenth of the motion, far past any turn) the
    # load law acts in full, as the stiffness no longer matters there
    assert np.max(np.abs(held_moved - exact_moved)) > 1e-6 * scale
    v = np.gradient(x, t)
    fast = np.abs(v) > 0.9 * np.max(np.abs(v))
    assert np.max(np.abs(held_moved - exact_moved)[fast]) < 1e-3 * scale
    # released, it follows the current factor again
    eng.following_held(None)
    assert np.max(np.abs(eng.predict(1.0, 1.0, moved) - exact_moved)) == 0.0


def _softening_record(kuka, rng):
    """A load and a softening over 40 reversals, the friction the engine predicts at known
    entries plus white noise: (engine, terms, u at the truth, noise sd)."""
    from leuven_friction.identify.data import Recording
    from leuven_friction.identify.diagnose import Engine, _entry_to_u, _terms_for, _unpack, comparison_of

    t = np.arange(0.0, 20.0, 1e-3)
    x = 2e-3 * np.sin(2 * np.pi * 1.0 * t) * (1 + 0.3 * np.sin(2 * np.pi * 0.07 * t))
    load = 100.0 * (1.0 + 0.4 * np.sin(2 * np.pi * 0.11 * t))
    rec = Recording(time=t, position=x, friction=np.zeros_like(t), normal_load=load)
    cmp_ = comparison_of(rec, kuka)
    eng = Engine(kuka, cmp_, free_steady=False)
    terms = [_terms_for("normal_load", cmp_), _terms_for("cyclic_softening", cmp_)]
    truth = [{"alpha": 0.8}, {"h": -0.4, "n_c": 6.0}]
    u = np.concatenate([[0.0, math.log(1.3)]] + [_entry_to_u(tm, {**tm.fixed, **p}) for tm, p in zip(terms, truth)])
    clean = eng.predict(*_unpack(u, terms, True, 1.0))
    sd = 0.01 * float(np.std(clean))
    cmp_.measured = clean + sd * rng.standard_normal(len(t))
    return eng, terms, u, sd


def test_a_chord_jacobian_is_scipys_at_its_anchor_and_a_refit_along_it_simulates_once_a_step(kuka, rng):
    # The stiffness entries' columns (κ0, h, n_c) come from simulations made once at the
    # anchor. There the Jacobian is the forward-difference one scipy's least_squares makes
    # with the same relative step, to rounding. A refit from a start moved off the truth
    # then asks for one simulation per function value (and none per Jacobian), where the
    # plain refit simulates every stiffness column of every Jacobian again (it may take
    # fewer steps); both leave the noise, the function values being the exact simulation.
    from scipy.optimize._numdiff import approx_derivative
    from leuven_friction.identify.diagnose import (DIFF_STEP, StiffnessChord, _fit, _fit_bounds, _thinned, _unpack)

    eng, terms, u, sd = _softening_record(kuka, rng)
    lo, hi = _fit_bounds(terms, True)
    mask = np.ones(len(eng.c.time), bool)
    idx = _thinned(mask)

    def resid(w):
        return eng.residual_at(eng.predict(*_unpack(w, terms, True, 1.0)), idx)

    chord = StiffnessChord.at(eng, terms, u, True, 1.0)
    assert sorted(chord.columns) == [1, 3, 4]  # κ0, h, n_c; not the level nor the load's α
    J_chord = chord.jacobian(eng, terms, True, 1.0, idx, resid)(u)
    J_scipy = approx_derivative(resid, u, method="2-point", rel_step=DIFF_STEP, bounds=(lo, hi))
    assert np.max(np.abs(J_chord - J_scipy)) <= 1e-9 * np.max(np.abs(J_scipy))

    start = u + np.array([0.05, -0.1, 0.05, 0.05, 0.2])
    before = eng.sims
    along = _fit(eng, terms, start, mask, fit_k0=True, k0=1.0, max_nfev=10, chord=chord)
    sims_along = eng.sims - before
    before = eng.sims
    plain = _fit(eng, terms, start, mask, fit_k0=True, k0=1.0, max_nfev=10)
    sims_plain = eng.sims - before
    assert sims_along <= 10 + 1  # one per function value (and the final prediction's, cached)
    assert sims_plain > 2 * sims_along
    for fit in (along, plain):
        rms = math.sqrt(fit.rss / len(eng.c.time))
        assert rms < 1.1 * sd


def _friction_under_a_force_name(path, name: str, n: int):
    """A file of friction alone (no I·ẍ in it) logged under the column ``name`` [N*m]: a motion
    reversing every 2 s at about 0.02 rad/s, friction 2 N·m·tanh(v/1e-3) and 0.01 N·m of noise."""
    t = np.arange(n) * 1e-3
    v = 0.02 * (1 + 0.1 * np.sin(2 * np.pi * 1.3 * t)) * np.tanh(5 * np.sin(2 * np.pi * t / 4))
    x = np.cumsum(v) * 1e-3
    f = 2.0 * np.tanh(v / 1e-3) + 0.01 * np.random.default_rng(3).standard_normal(len(t))
    np.savetxt(path, np.column_stack([t, x, f]), delimiter=",", fmt=["%.4f", "%.8f", "%.5f"],
               header=f"time [s],angle [rad],{name} [N*m]", comments="")
    return path


def test_the_hint_that_a_force_column_is_measured_friction_is_not_given_where_its_name_says_applied(tmp_path):
    # friction alone (no I·ẍ in it) under a force's name: the regression finds no inertia, and
    # "if it is measured friction, name it so" is the hint — not for a column named as a drive's
    # torque, which is applied by its name (a pitch bearing made apart got the hint every time)
    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import recording_inertia

    whys = {}
    for name in ("torque", "drive torque"):
        path = _friction_under_a_force_name(tmp_path / f"{name.replace(' ', '_')}.csv", name, 120000)
        est, whys[name], _ = recording_inertia(load_recording(path))
        assert est is None and "gives no positive inertia" in whys[name], whys[name]
    assert "if it is measured friction, name it so" in whys["torque"]
    assert "measured friction" not in whys["drive torque"], whys["drive torque"]


def test_fit_warns_where_the_column_read_as_applied_force_carries_no_inertial_term(tmp_path):
    # measured friction under a force's name (a rig's torque sensor, `torque`): the whole fit
    # takes it as applied, which a note among the inertia's had not made plain. One warning line
    # names the file and the column and says how to read it as friction; none where the column's
    # name says it is applied, and none once it is read as friction
    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.fit import fit_recordings

    warned = {}
    for name, cols in (("torque", None), ("drive torque", None), ("torque", {"friction": "torque [N*m]"})):
        path = _friction_under_a_force_name(tmp_path / f"{name.replace(' ', '_')}.csv", name, 60000)
        res = fit_recordings([load_recording(path, columns=cols)], refine=False)
        warned[(name, bool(cols))] = res.warnings
    assert warned[("torque", False)] == [
        f"{tmp_path / 'torque.csv'}: column 'torque [N*m]' was read as the applied force, but it carries no inertial "
        f"term (I·ẍ, eq. (8)) — measured friction carries none: if it is measured friction, name it so (friction, "
        f"friction_torque) or pass --columns friction=<column>, and fit again"]
    assert warned[("drive torque", False)] == [] and warned[("torque", True)] == []


def test_the_warning_says_a_doubt_as_a_doubt_and_keeps_the_loads_alternative():
    # an inertia read but not told from 0 (a slow rig's applied torque may read so) is no
    # finding that the column has no inertial term; a load changing along the record is the
    # other reason the inertia reading gives, and the warning keeps it. The warning is built
    # from the reading itself, not from its sentence in the notes
    from types import SimpleNamespace

    from leuven_friction.identify.diagnose import InertiaEstimate, InertiaNote, LikeFriction
    from leuven_friction.identify.fit import force_like_friction

    r = SimpleNamespace(source="rig.csv", columns={"force": "torque [N*m]"})
    doubt = InertiaNote(InertiaEstimate(0.01, 0.03), "read as …", LikeFriction(doubt=True, load_span=0.4))
    none = InertiaNote(None, "not read: …", LikeFriction(doubt=False))
    (w_doubt,), (w_none,) = force_like_friction([r], [doubt]), force_like_friction([r], [none])
    assert "is not told from 0" in w_doubt and "carries no inertial term" not in w_doubt
    assert "normal load" in w_doubt and "normal load" not in w_none
    assert "carries no inertial term" in w_none
    assert force_like_friction([r], [InertiaNote(InertiaEstimate(0.04, 0.001), "read as 0.0400 ± 0.001")]) == []


def test_a_load_changing_along_a_force_with_no_inertial_term_is_read_into_the_reading(tmp_path):
    # measured friction under a force's name, beside a normal load logged as ramped by half
    # along the record: the reading says the column looks like friction and carries the load's
    # span (0.5 of its largest value), and the fit's one warning line keeps the load's
    # alternative (friction following a load the regression does not model can hide I·ẍ too)
    import pandas as pd

    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import recording_inertia
    from leuven_friction.identify.fit import force_like_friction

    path = _friction_under_a_force_name(tmp_path / "torque.csv", "torque", 60000)
    df = pd.read_csv(path)
    load = np.linspace(100.0, 200.0, len(df))  # N: spans half its largest value
    df["normal_load [N]"] = load
    df.to_csv(path, index=False)
    rec = load_recording(path)
    note = recording_inertia(rec)
    assert note.like_friction is not None and note.like_friction.load_span is not None, note
    assert abs(note.like_friction.load_span - 0.5) < 1e-3, note.like_friction
    assert "spans 50 %" in note.why, note.why
    (w,) = force_like_friction([rec], [note])
    assert "following the normal load" in w and "'torque [N*m]'" in w, w


def test_a_set_with_a_load_effect_is_compared_without_it_on_a_recording_without_a_load():
    # a set a load recording's diagnosis extended, beside a recording without a load column: the
    # explorer draws it without the load effect and says so (it had shown "Could not draw")
    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import drivable, friction_compared
    from leuven_friction.model import default_params

    t = np.arange(3000) * 1e-3
    x = 0.02 * np.sin(2 * np.pi * t)
    f = 30.0 * np.tanh(np.gradient(x, t) / 1e-3)
    text = "time [s],position [rad],friction [N*m]\n" + "".join(f"{a},{b},{c}\n" for a, b, c in zip(t, x, f))
    rec = load_recording(text, name="noload.csv")
    loaded = default_params().replace(effects=({"name": "normal_load", "params": {"N0": 500.0, "alpha": 0.6}},))
    plain, left = drivable(loaded, has_load=False)
    assert left == ("normal_load",) and plain.effects == ()
    assert drivable(loaded, has_load=True) == (loaded, ())
    got, base = friction_compared(rec, loaded), friction_compared(rec, default_params())
    assert got.left_out == ("normal_load",) and base.left_out == ()
    np.testing.assert_array_equal(got.model, base.model)  # the set without its load effect, as given


def test_the_explorers_gap_is_the_noise_where_the_set_is_the_truth_and_the_log_starts_mid_slide():
    # a log that starts while the contact slides one way: the model as given starts from no
    # memory, which the log does not show. The gap the explorer's proposal states is the one `fit`
    # reports and a diagnosis starts from (``gap_as_given``): with the set that made the data, the
    # friction's noise. Over every sample, the start included, a spindle's fit had read 0.018 N·m
    # where `fit` and `diagnose` said 0.0023
    from leuven_friction.app.explorer.data_tab import gap
    from leuven_friction.identify.data import Recording
    from leuven_friction.identify.diagnose import gap_as_given
    from leuven_friction.model import default_params, simulate_displacement

    p, noise = default_params(), 0.3
    t = np.arange(0, 40, 0.002)
    x = np.where(t < 5, 0.02 * t, 0.1 + 0.05 * np.sin(2 * np.pi * (t - 5) / 6.0))  # a slide, then strokes
    F = simulate_displacement(p, t, x).friction_force
    seen = t >= 4.0  # the log starts mid-slide
    rec = Recording(time=t[seen] - 4.0, position=x[seen],
                    friction=F[seen] + np.random.default_rng(3).normal(0, noise, int(seen.sum())),
                    units={"time": "s", "position": "rad", "friction": "N*m"})
    assert gap(rec, p) == pytest.approx(noise, rel=0.1)
    assert gap(rec, p) == gap_as_given(rec, p).total
    said = gap_as_given(rec, p).said()
    assert said.startswith(f"RMS {gap(rec, p):.3g} N*m")
    # each regime is set against the floor as well, which is the friction's noise here: none is
    # above it, and the sliding ones (most of the samples) are at it
    ratios = dict(re.findall(r"(presliding|sliding, v [<>] 0) [0-9.e-]+ \(([0-9.]+) ×\)", said))
    assert len(ratios) == len(gap_as_given(rec, p).regimes) >= 2, said
    assert all(float(r) < 1.25 for r in ratios.values()), said
    assert all(0.8 < float(r) for k, r in ratios.items() if k.startswith("sliding")), said


# ---------------------------------------------------------------- one round's choice among rivals
class _Cand:
    """A passing candidate as ``choose_winner`` sees it: a name (they come best held out first);
    unhashable, as the evidence (a dataclass compared by value) is."""

    __hash__ = None

    def __init__(self, name):
        self.name = name


def _choose(names, alike_pairs, verdicts, beside=None, before=()):
    """``choose_winner`` over candidates named ``names``; ``alike_pairs``: unordered pairs whose
    corrections are alike; ``verdicts[(e, o)]``: what judging each beside the other says;
    ``beside[(c, e)]``: (passes, gain) of ``c`` judged beside ``e`` confounded (None: not asked);
    ``before``: names of the better ones of pairs confounded when the round was run before."""
    from leuven_friction.identify.diagnose import choose_winner
    cands = [_Cand(n) for n in names]
    alike = {frozenset(p) for p in alike_pairs}
    asked = []

    def told_apart(e, o):
        asked.append((e.name, o.name))
        return verdicts.get((e.name, o.name))

    def stands_apart(c, e):
        asked.append(("beside", c.name, e.name))
        return beside[(c.name, e.name)]
    c = choose_winner(cands, lambda e, o: frozenset((e.name, o.name)) in alike, told_apart,
                      None if beside is None else stands_apart, tuple(_Cand(n) for n in before))
    return (c.winner.name if c.winner else None, sorted(o.name for o in c.beaten), sorted(c.blocked),
            [(p.e.name, p.o.name) + ((p.beside_gain,) if p.stood_in else ()) for p in c.confounded], asked)


def test_three_candidates_two_alike_the_best_beating_its_rival_is_named_and_the_third_stays():
    # drift (best) and load alike, the load gaining nothing beside the drift; the ripple unlike both
    assert _choose(["drift", "load", "ripple"], [("drift", "load")], {("drift", "load"): "e"}) == (
        "drift", ["load"], ["load"], [], [("drift", "load")])


def test_three_candidates_two_alike_and_not_told_apart_are_confounded_and_the_third_is_named():
    assert _choose(["drift", "load", "ripple"], [("drift", "load")], {}) == (
        "ripple", [], ["drift", "load"], [("drift", "load")], [("drift", "load")])


def test_the_best_gaining_nothing_beside_its_alike_rival_gives_way_to_it():
    # the drift gains nothing beside the load: out; the load is looked at in its turn, and the
    # drift, out already, is not asked again
    assert _choose(["drift", "load", "ripple"], [("drift", "load")], {("drift", "load"): "o"}) == (
        "load", [], ["drift"], [], [("drift", "load")])


def test_two_alike_each_showing_a_part_of_its_own_leave_the_second_for_the_next_round():
    assert _choose(["drift", "load", "ripple"], [("drift", "load")], {("drift", "load"): "both"}) == (
        "drift", [], [], [], [("drift", "load")])


def test_a_winner_confounded_with_one_rival_takes_the_rival_it_beat_into_the_confounding():
    # all three alike: the drift beats the load, but is not told apart from the ripple, so
    # nothing is named and all three are reported with the drift
    assert _choose(["drift", "load", "ripple"], [("drift", "load"), ("drift", "ripple"), ("load", "ripple")],
                   {("drift", "load"): "e"}) == (
        None, [], ["drift", "load", "ripple"], [("drift", "ripple"), ("drift", "load")],
        [("drift", "load"), ("drift", "ripple")])


def test_without_telling_apart_every_alike_pair_with_the_best_is_confounded():
    assert _choose(["a", "b", "c"], [("a", "b"), ("a", "c")], {}) == (
        None, [], ["a", "b", "c"], [("a", "b"), ("a", "c")], [("a", "b"), ("a", "c")])


def test_a_third_candidate_after_a_confounded_pair_is_named_only_if_it_passes_beside_the_pair():
    # load and drift alike, not told apart; the ripple, unlike both, passed judged without their
    # part: beside the load it gains 0.4 % held out and does not pass, so it stood in for that part
    assert _choose(["load", "drift", "ripple"], [("load", "drift")], {}, {("ripple", "load"): (False, 0.004)}) == (
        None, [], ["drift", "load", "ripple"], [("load", "drift"), ("load", "ripple", 0.004)],
        [("load", "drift"), ("beside", "ripple", "load")])
    # … and one that still passes beside it shows a part of its own, and is named
    assert _choose(["load", "drift", "ripple"], [("load", "drift")], {}, {("ripple", "load"): (True, 0.2)}) == (
        "ripple", [], ["drift", "load"], [("load", "drift")], [("load", "drift"), ("beside", "ripple", "load")])


def test_a_candidate_standing_in_for_a_confounded_pair_leaves_those_it_beat_to_their_own_turn():
    # load and drift confounded; the ripple beat the softening (alike) but stood in for the load's
    # part: the softening, out only with the ripple named, is judged in its turn beside the load
    assert _choose(["load", "drift", "ripple", "softening"], [("load", "drift"), ("ripple", "softening")],
                   {("ripple", "softening"): "e"},
                   {("ripple", "load"): (False, 0.004), ("softening", "load"): (True, 0.05)}) == (
        "softening", [], ["drift", "load", "ripple"], [("load", "drift"), ("load", "ripple", 0.004)],
        [("load", "drift"), ("ripple", "softening"), ("beside", "ripple", "load"), ("beside", "softening", "load")])


def test_without_a_confounded_pair_the_winner_is_not_judged_again():
    # nothing confounded this round: no candidate is asked beside another (``beside`` has no entry)
    assert _choose(["drift", "load", "ripple"], [("drift", "load")], {("drift", "load"): "e"}, {}) == (
        "drift", ["load"], ["load"], [], [("drift", "load")])


def test_a_round_run_again_after_a_take_back_judges_its_winner_beside_the_pair_confounded_before():
    # the round first found load and drift confounded and named the ripple beside the load; the
    # next round took the ripple back (with the softening it had not clearly beaten). Run again,
    # the load and drift are out of the running and not found again, but the friction effect left
    # passing was judged without their part: beside the load it gains 0.3 % and stood in for it
    assert _choose(["wear"], [], {}, {("wear", "load"): (False, 0.003)}, before=["load"]) == (
        None, [], ["wear"], [("load", "wear", 0.003)], [("beside", "wear", "load")])
    # … one passing beside it is named; with no pair before, nothing is asked
    assert _choose(["wear"], [], {}, {("wear", "load"): (True, 0.1)}, before=["load"]) == (
        "wear", [], [], [], [("beside", "wear", "load")])
    assert _choose(["wear"], [], {}, {}) == ("wear", [], [], [], [])


def test_the_better_ones_of_confounded_pairs_are_each_taken_once_by_identity():
    from leuven_friction.identify.diagnose import Pair, confounded_leaders
    load, drift, ripple, wear = (_Cand(n) for n in ("load", "drift", "ripple", "wear"))
    load_again = _Cand("load")  # equal by name, another evidence: a round's own, kept apart
    pairs = [Pair(load, drift), Pair(load, ripple), Pair(load, wear, True, 0.01)]
    assert [c.name for c in confounded_leaders(pairs)] == ["load"]
    got = confounded_leaders(pairs, (load_again, load))
    assert len(got) == 2 and got[0] is load_again and got[1] is load


# ---------------------------------------------------------------- a force along the travel, averaged
def test_a_force_along_the_travel_is_read_at_every_speed_through_the_comparisons_averaging():
    """A ball screw's additive cogging A·sin(2πx/λ + φ), λ = π rad, in friction taken from the
    applied force and averaged over 211 samples at 4 kHz (0.05 s): at 100 rad/s the motor passes
    5 rad in one average, more than a period, so the fast runs hold a fraction of the wave. Read
    with the averaging (as the measurement sees it), its period, amplitude and phase come back
    within 3 σ at the slow and the fast half alike."""
    from types import SimpleNamespace

    from leuven_friction.identify.diagnose import travel_force

    rng = np.random.default_rng(5)
    rate, L = 4000.0, 211
    lam, A, phi, noise = math.pi, 0.04, 0.3, 0.004
    # runs one way then back, 2 s each at speeds from 1 to 100 rad/s, a short rest between: the
    # faster half of the sliding is at 40–100 rad/s, where one average spans 2–5 rad
    v_runs = []
    for speed in (1.0, 3.0, 10.0, 40.0, 70.0, 100.0):
        for sign in (1.0, -1.0):
            v_runs += [np.full(int(2.0 * rate), sign * speed), np.zeros(int(0.2 * rate))]
    v = np.concatenate(v_runs)
    x = np.cumsum(v) / rate
    t = np.arange(len(x)) / rate
    force = A * np.sin(2 * math.pi * x / lam + phi)
    # the comparison's moving average, written out here as a convolution (edges held, as "nearest")
    padded = np.concatenate([np.full(L // 2, force[0]), force, np.full(L // 2, force[-1])])
    resid = np.convolve(padded, np.ones(L) / L, mode="valid") + noise * rng.standard_normal(len(x))
    cmp_ = SimpleNamespace(space="friction", velocity=v, v_rest=0.5, path=x, time=t, windows=[],
                           filtered=lambda f: uniform_filter1d(f, L, mode="nearest"))
    tf = travel_force(cmp_, resid, np.ones(len(x), bool), 0.05)
    assert tf is not None and tf.shown, tf
    assert abs(tf.wavelength - lam) < 1e-3 * lam
    assert abs(tf.amplitude - A) < 3 * tf.sd + 1e-3 * A, (tf.amplitude, tf.sd)
    (slow, s_sd), (fast, f_sd) = tf.halves
    assert abs(slow - A) < 3 * s_sd + 1e-3 * A and abs(fast - A) < 3 * f_sd + 1e-3 * A, tf.halves
    assert abs(math.remainder(tf.phase - phi, 2 * math.pi)) < 0.05
    assert tf.following < 0.1 * A  # nothing follows the motion's sign


# ---------------------------------------------------------------- the base off, nothing named
def test_a_base_off_with_candidates_seen_does_not_say_no_candidate_takes_its_rest_up():
    # 20 noise floors left by the base refitted alone: with nothing seen, no candidate took it up;
    # with a pair confounded (a load ramp and a drift, 75 % held out each), part of it may be theirs
    from leuven_friction.identify.diagnose import base_off_verdict
    names = ("time_drift", "normal_load")
    alone = base_off_verdict(0.2, 0.01, names)
    seen = base_off_verdict(0.2, 0.01, names, seen=True)
    assert "no candidate takes up" in alone and "20.0 × the noise floor" in alone, alone
    assert "no candidate takes up" not in seen and "may hold part of it" in seen and "20.0 ×" in seen, seen
    # within two noise floors the base alone is off, seen or not
    assert base_off_verdict(0.015, 0.01, names, seen=True) == base_off_verdict(0.015, 0.01, names) == (
        "the base, not a missing effect, is what is off")


def test_a_named_effect_whose_size_is_not_told_from_none_is_said_so():
    from leuven_friction.identify.diagnose import size_not_shown
    # a drift's b at 1.8 σ from none: said, with the σ counted; at 5 σ it is not
    assert "b = -0.25 ± 0.14 is 1.8 σ from 0" in size_not_shown("time_drift", {"b": -0.25, "tau": 60.0, "t0": 0.0},
                                                               {"b": 0.14, "tau": 40.0})
    assert size_not_shown("time_drift", {"b": -0.25, "tau": 60.0, "t0": 0.0}, {"b": 0.05, "tau": 10.0}) is None
    # a ripple whose fundamental shows and whose second harmonic does not: its size is shown
    ripple = {"a": 0.06, "wavelength": 0.0113, "phase": 1.0, "a2": 0.0007, "phase2": 0.2, "x0": 0.0}
    assert size_not_shown("position_ripple", ripple, {"a": 0.005, "phase": 0.02, "a2": 0.0012, "phase2": 2.0}) is None
    # a load's exponent has no amplitude of that kind (α = 0 is a level, not no effect's shape)
    assert size_not_shown("normal_load", {"alpha": 0.1, "N0": 500.0}, {"alpha": 0.2}) is None


def test_a_logged_temperature_course_is_read_as_one_way_or_turning_back():
    from leuven_friction.identify.diagnose import temperature_course
    rng = np.random.default_rng(5)
    t = np.linspace(0.0, 75.0, 15001)
    noise = rng.normal(0, 0.3, t.size)  # a sensor's noise, a tenth of the range: no turn of its own
    # a winding warmed to 30 °C by 36 s and cooled to 24: turned back, with its peak's time
    warm_cool = 22 + 8 * np.exp(-((t - 36) / 18) ** 2) + 2 * (t > 36) * (1 - np.exp(-(t - 36) / 5))
    said, turns = temperature_course(t, warm_cool + noise, "°C")
    assert turns and said.startswith("rises from") and "then falls to" in said, said
    peak = float(said.split(" by ")[1].split(" s")[0])
    assert abs(peak - t[np.argmax(warm_cool)]) < 3.0, (said, t[np.argmax(warm_cool)])
    # a first-order warm-up: one way, however noisy; the same in kelvin
    warm = 22 + 8 * (1 - np.exp(-t / 20))
    said, turns = temperature_course(t, warm + noise, "°C")
    assert not turns and said.startswith("goes from 2") and "°C" in said, said
    assert temperature_course(t, warm + 273.15 + noise, "K")[1] is False
    # a cooling that comes back up
    assert temperature_course(t, 40 - 10 * np.sin(np.pi * t / 75), "")[0].startswith("falls from")
    # a column with blanks: read on what it has; nothing to read, nothing said
    blanks = warm.copy()
    blanks[::3] = np.nan
    assert temperature_course(t, blanks, "°C")[1] is False
    assert temperature_course(t, np.full(t.size, np.nan), "°C") is None


def test_a_model_that_does_not_simulate_is_refused_in_one_line_not_diagnosed_to_nan():
    # n < 1 (a Maxwell-slip curve fitted by an older `fit --fit-n` to n = 0.63): eq. (5)'s implicit
    # step meets |r|^(n−1) at r = 0 at the first reversal, and the simulation is NaN; the file's
    # schema refuses such an n, a set made in code reaches the diagnosis and is refused there
    from leuven_friction.identify.data import DataError
    from leuven_friction.identify.diagnose import diagnose
    from leuven_friction.model.params import ParameterError
    from synth.hidden import make_case, oracle_params, to_recording

    df, truth, _ = make_case("tribometer", 4243, ())
    rec = to_recording(df.iloc[:20000], "n06.csv")
    bad = oracle_params(truth).replace(n=0.6)
    with pytest.raises(DataError, match=r"^n06.csv: the model as given does not simulate along this recording .*n = 0.6"):
        diagnose(rec, bad)
    with pytest.raises(ParameterError, match="n: must be >= 1"):
        bad.validate()


def test_a_load_ramping_under_its_noise_per_sample_counts_as_changing():
    # a joint's load ramped 800 → 1200 N over 10 s at 500 Hz (0.16 N a sample, under the load
    # cell's 5 N noise), then held, then stepped down: the ramp is changing throughout, the
    # step within a window's half of it (a 200th of the record), the holds nowhere
    rng = np.random.default_rng(0)
    t = np.arange(0.0, 150.0, 1 / 500)
    load = np.full(len(t), 800.0)
    ramp = (t > 12) & (t < 22)
    load[ramp] = 800 + 40 * (t[ramp] - 12)
    load[t >= 22] = 1200.0
    load[t >= 60] = 400.0
    changing = load_changing(load + 5.0 * rng.standard_normal(len(t)))
    assert changing[ramp].all()
    half_window = len(t) / 400 / 500  # s
    near_step = np.abs(t - 60) <= half_window + 0.01
    assert changing[near_step].mean() > 0.9
    holds = ~ramp & ~near_step & ~((t > 22 - half_window - 0.01) & (t < 22 + half_window + 0.01)) & \
        ~((t > 12 - half_window - 0.01) & (t < 12 + half_window + 0.01))
    assert changing[holds].mean() < 0.001, changing[holds].sum()
    assert not load_changing(np.full(1000, 5.0)).any()


def test_a_force_against_the_motion_both_ways_is_told_from_a_weight_held_one_way():
    # sliding dissipates: an applied force pushing the way the position increases has the
    # velocity's sign in sliding, on both sides; a weight the drive holds turns one side only
    from leuven_friction.identify.diagnose import force_against_motion

    rng = np.random.default_rng(3)
    v = np.concatenate([np.full(400, 0.02), np.zeros(200), np.full(400, -0.02)]) + rng.normal(0, 1e-3, 1000)
    friction = 5.0 * np.sign(v) + rng.normal(0, 0.5, 1000)
    assert not force_against_motion(friction, v, 5e-3)
    assert force_against_motion(-friction, v, 5e-3)
    weight = 20.0  # more than the friction: the force holds it up both ways
    assert not force_against_motion(weight + friction, v, 5e-3)
    assert not force_against_motion(-(weight + friction), v, 5e-3)
    # too few samples either way: not told
    assert not force_against_motion(-friction[:430], v[:430], 5e-3)


def test_an_effect_parameter_held_at_an_end_of_its_range_is_said_with_that_range():
    import math

    from leuven_friction.identify.diagnose import Term

    load = Term("normal_load", {"N0": 100.0}, (("alpha", "lin", 0.0, 3.0),))
    said = load.pinned(np.array([3.0]))
    assert said is not None and "alpha at 3 (its range 0 … 3)" in said and "no σ" in said, said
    assert load.pinned(np.array([0.7])) is None
    # the settling scale at its bound, and the size of the change it settles to, are
    # ``unsettled``'s to say, not this
    term = Term("cyclic_softening", {}, (("h", "lin", -0.9, 5.0), ("n_c", "log", math.log(0.05), math.log(5.0))),
                settles="n_c", refs={"n_c": 10.0})
    assert term.pinned(np.array([-0.3, 0.0])) is None
    assert term.pinned(np.array([-0.3, math.log(5.0)])) is None
    assert term.pinned(np.array([-0.9, 0.0])) is None and "h is at a bound" in term.unsettled(np.array([-0.9, 0.0]))


def test_a_velocity_column_of_the_other_sign_does_not_turn_a_correct_force_round():
    # a force of the right sign and a velocity column logged the other way: the position's own
    # slope is used, the inertia reads positive, and nothing is refused
    from leuven_friction.identify.data import Recording
    from leuven_friction.identify.diagnose import recording_inertia

    rng = np.random.default_rng(5)
    t = np.arange(60000) * 1e-3
    v = 0.05 * np.sign(np.sin(2 * np.pi * t / 20.0)) * (1 + 0.05 * np.sin(2 * np.pi * t * 0.3))
    v = np.convolve(v, np.ones(50) / 50, mode="same")
    x = np.cumsum(v) * 1e-3 + rng.normal(0, 1e-7, len(t))
    a = np.gradient(v, t)
    f = 5.0 * a + 20.0 * np.tanh(v / 1e-3) + rng.normal(0, 0.05, len(t))
    rec = Recording(time=t, position=x, force=f, velocity=-v, columns={"force": "F [N]", "velocity": "v [m/s]"},
                    units={"time": "s", "position": "m", "force": "N", "velocity": "m/s"}, source="turned_v.csv")
    est, why, _ = recording_inertia(rec)
    assert est is not None and abs(est.value - 5.0) < 3 * est.stderr + 0.5, (est, why)


# ---------------------------------------------------------------- a force in proportion to the travel
def _strokes_with(rate_keeping, rate_following, *, seed):
    """Strokes over ±10 mm at 2–40 mm/s, each speed rising 30 % along its stroke (a positioner
    lagging its ramp), and a residual holding: k·x keeping its sign (a spring taken off the force
    at a wrong rate), a slope following the motion's sign, S(v)'s slope off by 2 kN·s/m, an
    inertia off by 2 kg, each run's own offset and white noise."""
    from types import SimpleNamespace

    rng = np.random.default_rng(seed)
    rate = 1000.0
    v_runs = []
    for speed in (0.002, 0.005, 0.01, 0.02, 0.04):
        for sign in (1.0, -1.0):
            n = int(0.02 / speed * rate)
            prof = speed * np.linspace(0.87, 1.13, n)
            v_runs += [sign * prof * 0.02 / (prof.sum() / rate), np.zeros(200)]
    v = np.concatenate(v_runs)
    x = np.cumsum(v) / rate - 0.01
    t = np.arange(len(x)) / rate
    acc = np.gradient(v, t)
    moving = np.abs(v) > 0
    run = np.cumsum(np.r_[True, np.diff(np.sign(v)) != 0])
    offset = rng.normal(0.0, 5.0, run.max() + 1)[run]
    resid = (rate_keeping * x + rate_following * np.sign(v) * x + 2000.0 * v - 2.0 * acc
             + offset + rng.normal(0.0, 1.0, len(x)))
    cmp_ = SimpleNamespace(space="friction", velocity=v, v_rest=5e-4, path=x, time=t, windows=[], acceleration=acc,
                           filtered=lambda f: f)
    return cmp_, resid, moving


def test_a_spring_along_the_travel_is_read_whichever_way_the_motion_goes():
    """A spring rate 2 kN/m off, left in friction taken from an applied force, beside friction's
    own slopes (a slope following the motion's sign, S(v) misfit where the speed varies along a
    stroke, an inertia misfit): read within 3 σ at the slow and the fast half alike, and said."""
    from leuven_friction.identify.diagnose import travel_spring

    for seed in range(5):
        cmp_, resid, mask = _strokes_with(2000.0, 500.0, seed=seed)
        ts = travel_spring(cmp_, resid, mask)
        assert ts is not None and ts.shown, ts
        # within 3 σ and 2 %: read without S(v)'s and the inertia's slopes beside it, the rate is 7.6 % high
        assert abs(ts.rate - 2000.0) < min(3 * ts.sd, 0.02 * 2000.0), (ts.rate, ts.sd)
        assert abs(ts.following - 500.0) < 0.05 * 500.0, ts.following
        (slow, s_sd), (fast, f_sd) = ts.halves
        assert abs(slow - 2000.0) < 3 * s_sd and abs(fast - 2000.0) < 3 * f_sd, ts.halves
        assert abs(ts.span - 0.02) < 1e-3 and ts.gain > 0.5


def test_a_slope_that_follows_the_motions_sign_is_no_force_along_the_travel():
    """Friction rising along the travel (its sign the motion's), S(v) misfit and an inertia
    misfit, no spring: nothing said, over seeds."""
    from leuven_friction.identify.diagnose import travel_spring

    for seed in range(5):
        cmp_, resid, mask = _strokes_with(0.0, 500.0, seed=seed)
        ts = travel_spring(cmp_, resid, mask)
        assert ts is not None and not ts.shown and abs(ts.rate) < 5 * ts.sd, ts
