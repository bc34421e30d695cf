"""Sliding: eq. (6), F = S(v) + σ2·v, at constant velocity for both signs (Fig. 8)."""

import numpy as np
import pytest

from leuven_friction.model import as_model, simulate_displacement
from leuven_friction.model.experiments import constant_velocity_sweep
from tests.paper import TABLE_ONE

VELOCITIES = [0.001, 0.004, 0.02, 0.3, -0.001, -0.004, -0.02, -0.3]


def paper_steady_state(v: float) -> tuple[float, float]:
    """Eqs. (6)-(7): (S(v), σ2) at constant velocity v."""
    Fs, Fc, vs, delta, sigma2 = TABLE_ONE[1 if v > 0 else -1]
    return Fc + (Fs - Fc) * np.exp(-abs(v / vs) ** delta), sigma2


@pytest.mark.parametrize("kind", ["leuven", "lugre", "static"])
@pytest.mark.parametrize("v", VELOCITIES)
def test_steady_sliding_force_is_stribeck_plus_viscous(kuka, kind, v):
    p = as_model(kuka, kind)
    # the approach to sliding has a time constant ~ 2.6e-4 rad / |v| (n = 7, Table II)
    T = max(0.5, 6e-3 / abs(v))
    t = np.arange(0.0, T, 1e-4)
    r = simulate_displacement(p, t, v * t)
    S, sigma2 = paper_steady_state(v)
    # 1e-3 N·m: far below Table I's uncertainties, far above the residual transient
    assert r.friction_force[-1] == pytest.approx(S + sigma2 * v, abs=1e-3)
    # and the hysteresis force F_h carries S(v) alone, the viscous σ2·v being outside it (eq. (6))
    assert r.hysteresis_force[-1] == pytest.approx(S, abs=1e-3)


def test_sweep_reproduces_table_one_shape(kuka):
    res = constant_velocity_sweep(kuka)
    v = np.array(res.summary["velocity"])
    F = np.array(res.summary["mean_friction"])
    expected = [S + sigma2 * vv for vv in v for S, sigma2 in [paper_steady_state(vv)]]
    np.testing.assert_allclose(F, expected, atol=0.05)
    # Stribeck effect: friction falls from F_s towards F_c as speed rises, then σ2·v takes over
    pos = v > 0
    assert F[pos][0] > F[pos][4] and F[pos][-1] > F[pos][5]
    neg = v < 0
    assert F[neg][0] < F[neg][4] and F[neg][-1] < F[neg][5]


@pytest.mark.parametrize("v", [0.004, 0.3, -0.004, -0.3])
def test_sliding_settles_when_the_curve_tops_short_of_the_outer_loop(kuka, v):
    """A fitted F_d may end flat below F_s⁺ − F_s⁻ (branches stopping where the contact starts
    to slide). Eq. (5) must still settle after a reversal from the other sliding direction:
    F → S(v) + σ2·v within presliding's scale, and σ1·dz/dt never more than the forces at play."""
    from leuven_friction.model.params import TransitionCurve

    p = kuka.replace(transition_curve=TransitionCurve(kind="piecewise_linear", z=(0.0, 1e-4, 2e-4),
                                                      F=(0.0, 60.0, 60.001)))
    assert p.outer_loop_span > 90.0  # Table I: 36 + 63, well above the curve's top
    # slide against v for 0.05 rad, then with it for 0.05 rad (250 curve lengths each way)
    dt = 2e-5 / abs(v)
    t = np.arange(0.0, 0.1 / abs(v), dt)
    T1 = 0.05 / abs(v)
    x = np.where(t < T1, -v * t, -v * T1 + v * (t - T1))
    r = simulate_displacement(p, t, x)
    S, sigma2 = paper_steady_state(v)
    back = t > 0.05 / abs(v)
    assert r.friction_force[-1] == pytest.approx(S + sigma2 * v, abs=1e-3)
    # settled within 50 curve lengths of the reversal (0.01 rad; the span is reached at 20): before
    # the curve was made to reach it, z ran on for metres there and σ1·dz/dt read −600 N on a
    # guideway's fit
    past = back & (np.abs(x + v * T1) > 1e-2)
    assert np.max(np.abs(r.friction_force[past] - (S + sigma2 * v))) < 1e-2 * abs(S)
    # a curve that reaches the span (Table II's) is evaluated as given
    from leuven_friction.model.params import reaching_knots

    z, F = reaching_knots(kuka.transition_curve.z, kuka.transition_curve.F, kuka.outer_loop_span)
    assert tuple(z) == tuple(kuka.transition_curve.z) and tuple(F) == tuple(kuka.transition_curve.F)
