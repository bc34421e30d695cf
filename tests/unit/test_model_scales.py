"""Per-sample friction and stiffness scales inside the simulation loop.

``friction_scale`` s multiplies the friction force of eq. (3); ``stiffness_scale`` κ evaluates
the transition curve at κ·z (LuGre: κ·σ0). The expectations below come from the paper's
equations and Tables I–II, not from a run of the simulator with the scale applied.
"""

import numpy as np
import pytest

from leuven_friction.model import (
    SignalError,
    as_model,
    simulate_closed_loop,
    simulate_displacement,
    simulate_force,
)
from tests.paper import TABLE_II_F, TABLE_II_Z, table_one


@pytest.mark.parametrize("kind", ["leuven", "lugre", "static"])
@pytest.mark.parametrize("v", [0.02, -0.004])
def test_constant_friction_scale_multiplies_steady_sliding_force(kuka, kind, v):
    p = as_model(kuka, kind)
    t = np.arange(0.0, 1.5, 1e-4)
    s = 0.37
    r = simulate_displacement(p, t, v * t, friction_scale=np.full(len(t), s))
    # eq. (6) times s
    assert r.friction_force[-1] == pytest.approx(s * table_one(v), abs=1e-3)


def test_absent_scales_equal_scales_of_one(kuka):
    t = np.arange(0.0, 2.0, 1e-4)
    x = 2e-4 * np.sin(2 * np.pi * 0.5 * t) + 6e-5 * np.sin(2 * np.pi * 2.3 * t)
    a = simulate_displacement(kuka, t, x)
    b = simulate_displacement(kuka, t, x, friction_scale=np.ones(len(t)), stiffness_scale=np.ones(len(t)))
    np.testing.assert_array_equal(a.friction_force, b.friction_force)
    f = 30.0 * np.sin(2 * np.pi * 0.5 * t)
    a = simulate_force(kuka, t, f)
    b = simulate_force(kuka, t, f, friction_scale=1.0, stiffness_scale=1.0)
    np.testing.assert_array_equal(a.position, b.position)


def _breakaway_friction(p, s, rate=1.0):
    """Peak friction before the first slide (|v| reaches 0.05 rad/s) under a slow force ramp."""
    t = np.arange(0.0, 1.5 * s * p.stribeck.positive.Fs / rate, 1e-4)
    r = simulate_force(p, t, rate * t, friction_scale=np.full(len(t), s))
    i = np.flatnonzero(r.velocity >= 0.05)[0]
    return float(np.max(r.friction_force[: i + 1])), float(rate * t[i])


@pytest.mark.parametrize("s", [0.6, 0.3])
def test_force_driven_plant_slips_earlier_at_scaled_breakaway(kuka, s):
    full, f_slip_full = _breakaway_friction(kuka, 1.0)
    peak, f_slip = _breakaway_friction(kuka, s)
    # a slow ramp breaks away near F_s+ (Table I: 36 N·m); with s the plant feels s·F, so
    # the stuck phase ends at s times the unscaled break-away force
    assert full == pytest.approx(kuka.stribeck.positive.Fs, rel=0.04)
    assert peak == pytest.approx(s * full, rel=0.02)
    assert f_slip == pytest.approx(s * f_slip_full, rel=0.02)  # slips earlier: at s times the applied force


def _virgin_x_at_force(p, kap, F_levels, x_end=1.2e-4):
    """Slow displacement ramp from rest: the x at which the friction force first reaches F."""
    t = np.arange(0.0, 10.0, 1e-3)
    x = x_end * t / t[-1]
    r = simulate_displacement(p, t, x, stiffness_scale=np.full(len(t), kap))
    return np.array([np.interp(F, r.friction_force, x) for F in F_levels])


def test_stiffness_scale_divides_presliding_displacement(kuka):
    F_levels = [5.0, 10.0, 16.0]
    # Table II's virgin curve: x = F_d^{-1}(F) (z ≈ x far below S(v) - F_b ≈ F_s+)
    x_table = np.interp(F_levels, TABLE_II_F, TABLE_II_Z)
    for kap in (0.5, 2.0, 4.0):
        x = _virgin_x_at_force(kuka, kap, F_levels)
        np.testing.assert_allclose(x, x_table / kap, rtol=0.01)


def test_stiffness_scale_leaves_sliding_force_unchanged(kuka):
    t = np.arange(0.0, 1.0, 1e-4)
    v = 0.02
    r = simulate_displacement(kuka, t, v * t, stiffness_scale=np.full(len(t), 3.0))
    assert r.friction_force[-1] == pytest.approx(table_one(v), abs=1e-3)


def test_lugre_stiffness_scale_multiplies_sigma0(kuka_lugre):
    # LuGre from rest: F ≈ σ0·x while x << F_s/σ0
    t = np.arange(0.0, 1.0, 1e-3)
    x = 1e-7 * t
    for kap in (0.25, 3.0):
        r = simulate_displacement(kuka_lugre, t, x, stiffness_scale=kap)
        slope = r.hysteresis_force[-1] / x[-1]
        assert slope == pytest.approx(kap * kuka_lugre.sigma0, rel=0.01)


def test_time_varying_friction_scale_acts_from_its_sample(kuka):
    t = np.arange(0.0, 2.0, 1e-4)
    v = 0.02
    s = np.where(t < 1.0, 1.0, 0.5)
    r = simulate_displacement(kuka, t, v * t, friction_scale=s)
    steady = table_one(v)
    assert r.friction_force[np.searchsorted(t, 0.99)] == pytest.approx(steady, abs=1e-3)
    assert r.friction_force[np.searchsorted(t, 1.0)] == pytest.approx(0.5 * steady, abs=1e-3)


@pytest.mark.parametrize("s", [1.0, 0.4])
def test_closed_loop_plant_feels_friction_scale(kuka, s):
    # P control of a ramp reference: in steady sliding Kp·e = s·(S(v) + σ2·v), so the
    # following error scales with s. The lightly damped plant (σ2 only) rings at
    # sqrt(Kp/I) = 2π·50 rad/s: the reference eases into its speed (no stick at start) and
    # the error is averaged over whole periods of that ringing.
    v, tau = 0.3, 0.1
    kp = kuka.inertia * (2 * np.pi * 50.0) ** 2
    t = np.arange(0.0, 4.0, 1e-4)
    x_ref = v * (t - tau * (1.0 - np.exp(-t / tau)))
    r = simulate_closed_loop(kuka, t, x_ref, kp=kp, friction_scale=np.full(len(t), s))
    assert np.all(r.velocity[t >= 1.0] > 0)  # sliding throughout the averaging window
    e = (x_ref - r.position)[t >= 2.0]
    assert np.mean(e) == pytest.approx(s * table_one(v) / kp, rel=0.005)


def test_bad_scales_are_signal_errors(kuka):
    t = np.arange(0.0, 0.1, 1e-3)
    with pytest.raises(SignalError, match="friction_scale: expected 100 samples"):
        simulate_displacement(kuka, t, 0 * t, friction_scale=np.ones(7))
    with pytest.raises(SignalError, match="stiffness_scale: must be > 0"):
        simulate_force(kuka, t, 0 * t, stiffness_scale=np.zeros(len(t)))
    with pytest.raises(SignalError, match="friction_scale: non-finite"):
        simulate_closed_loop(kuka, t, 0 * t, kp=1.0, friction_scale=np.full(len(t), np.nan))


def test_stiffness_scale_changing_at_rest_moves_along_the_curve(kuka):
    # presliding to x1, then at rest while κ ramps 1 -> 2: z stays, F_h = F_d(κ·z) (eq. (4) with
    # F_b = 0 on the virgin curve), read off Table II's knots
    t = np.arange(0.0, 20.0, 1e-2)
    x1 = 3e-5
    x = np.minimum(t / 10.0, 1.0) * x1
    kap = np.where(t < 10.0, 1.0, 1.0 + (t - 10.0) / 10.0)
    r = simulate_displacement(kuka, t, x, stiffness_scale=kap)
    rest = t > 10.0
    z = r.z[rest]
    assert np.ptp(z) == 0.0  # the state does not move at rest
    expected = np.interp(kap[rest] * z[0], TABLE_II_Z, TABLE_II_F)
    np.testing.assert_allclose(r.hysteresis_force[rest], expected, rtol=1e-12)
    assert r.hysteresis_force[-1] > 1.2 * r.hysteresis_force[np.searchsorted(t, 9.99)]


@pytest.mark.parametrize("kind", ["leuven", "lugre", "static"])
def test_a_shared_steady_curve_gives_the_simulation_it_replaces(kuka, kind):
    # ``steady_along`` holds v and S(v) of one path for one S(v): every simulation along that
    # path with that S(v) — here at four presliding stiffnesses — must be the one computed
    # without it, to the bit, and S(v) itself eq. (7) (Table I) at each velocity
    from leuven_friction.model import friction_along, steady_along

    p = as_model(kuka, kind)
    t = np.arange(0.0, 2.0, 1e-4)
    x = 2e-4 * np.sin(2 * np.pi * 0.5 * t) + 6e-5 * np.sin(2 * np.pi * 2.3 * t) + 1e-3 * t
    shared = steady_along(p, t, x)
    for side, sp in ((1, p.stribeck.positive), (-1, p.stribeck.negative)):
        v = shared.velocity[shared.velocity * side > 0]
        expected = sp.Fc + (sp.Fs - sp.Fc) * np.exp(-np.abs(v / sp.vs) ** sp.delta)  # eq. (7)
        np.testing.assert_allclose(shared.steady[shared.velocity * side > 0], expected, rtol=1e-12)
    for kappa in (0.3, 1.0, 2.5, np.linspace(0.5, 2.0, len(t))):
        a = simulate_displacement(p, t, x, stiffness_scale=kappa)
        b = simulate_displacement(p, t, x, stiffness_scale=kappa, steady=shared)
        np.testing.assert_array_equal(a.friction_force, b.friction_force)
        np.testing.assert_array_equal(a.velocity, b.velocity)
        # the friction alone (``friction_along``, what the diagnosis's fits call), to the bit
        np.testing.assert_array_equal(a.friction_force, friction_along(p, shared, stiffness_scale=kappa))


def test_a_steady_curve_of_another_s_or_path_is_refused(kuka):
    from leuven_friction.model import friction_along, steady_along

    t = np.arange(0.0, 1.0, 1e-3)
    x = 1e-3 * np.sin(2 * np.pi * t)
    shared = steady_along(kuka, t, x)
    other = kuka.replace(stribeck=kuka.stribeck.__class__(
        kuka.stribeck.positive.__class__(**{**kuka.stribeck.positive.__dict__, "Fc": kuka.stribeck.positive.Fc * 1.1}),
        kuka.stribeck.negative))
    with pytest.raises(ValueError, match="another path or another S"):
        simulate_displacement(other, t, x, steady=shared)
    with pytest.raises(ValueError, match="another S"):
        friction_along(other, shared)
    with pytest.raises(ValueError, match="another path or another S"):
        simulate_displacement(kuka, t, 2.0 * x, steady=shared)
    x *= 3.0  # the caller's path changed in place: the copy kept is not that path any more
    with pytest.raises(ValueError, match="another path or another S"):
        simulate_displacement(kuka, t, x, steady=shared)
    # σ2 is not part of eq. (7)'s S(v): a parameter set differing only there is served
    pos = kuka.stribeck.positive
    viscous = kuka.replace(stribeck=kuka.stribeck.__class__(
        pos.__class__(**{**pos.__dict__, "sigma2": pos.sigma2 * 2.0}), kuka.stribeck.negative))
    assert shared.same_curve(viscous) and not shared.same_curve(other)
