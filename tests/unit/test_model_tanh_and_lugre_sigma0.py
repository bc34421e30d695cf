"""The smooth transition curve F_d(z) = A·tanh(z/z0) + k·z in simulation, and LuGre's σ0 as
the README states it; each checked against an expectation computed here, independently of the
model's kernels."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from leuven_friction.model import TransitionCurve, as_model, default_params, simulate_displacement

A, Z0, K = 20.0, 2e-5, 2e4  # N·m, rad, N·m/rad: initial stiffness A/z0 + k = 1.02e6 N·m/rad
N = 7.0


def tanh_curve(z):
    return A * np.tanh(z / Z0) + K * z


@pytest.fixture(scope="module")
def tanh_params():
    return default_params().replace(transition_curve=TransitionCurve(kind="tanh_linear", shape={"A": A, "z0": Z0, "k": K})).validate()


def test_tanh_virgin_curve_follows_eq5_integrated_independently(tanh_params):
    # from rest (F_b = 0) at a slow constant velocity: eq. (5) gives dz/dx = 1 - (F_d(z)/(S(v) - F_b))^n,
    # integrated here with an adaptive Runge-Kutta on the closed-form curve
    v = 1e-3
    S = 27.0 + (36.0 - 27.0) * np.exp(-abs(v / 0.007) ** 0.5)  # eq. (7), Table I positive side
    t = np.arange(0.0, 0.4, 1e-4)
    x = v * t
    r = simulate_displacement(tanh_params, t, x)
    sol = solve_ivp(lambda _, z: 1.0 - (tanh_curve(z) / S) ** N, (0.0, x[-1]), [0.0], t_eval=x, rtol=1e-10, atol=1e-14)
    expected = tanh_curve(sol.y[0])
    assert expected[-1] > 0.8 * S  # the check reaches well into the transition to sliding
    np.testing.assert_allclose(r.hysteresis_force, expected, atol=2e-3 * S)
    # right after the start the spring has its initial stiffness A/z0 + k
    i = np.searchsorted(x, 1e-7)
    assert r.hysteresis_force[i] / x[i] == pytest.approx(A / Z0 + K, rel=0.01)


def test_tanh_model_slides_at_the_paper_steady_state(tanh_params):
    for v, (Fs, Fc, vs, delta, sigma2) in ((0.02, (36.0, 27.0, 0.007, 0.5, 7.7)), (-0.02, (-63.0, -52.0, -0.004, 0.9, 8.0))):
        t = np.arange(0.0, 0.5, 1e-4)
        r = simulate_displacement(tanh_params, t, v * t)
        expected = Fc + (Fs - Fc) * np.exp(-abs(v / vs) ** delta) + sigma2 * v  # eqs. (6)-(7)
        assert r.friction_force[-1] == pytest.approx(expected, abs=1e-3)


def test_lugre_sigma0_is_the_readme_value_and_the_least_squares_fit_of_fig4():
    # Table II's curve and its inverse by plain interpolation; LuGre's curve from the negative
    # outer loop: (F_s+ - F_s-)(1 - exp(-σ0·x/F_s+)); σ0 minimises the squared gap over the whole curve
    z = np.array([0.0, 1.80e-6, 1.41e-4, 2.66e-4, 5.21e-4])
    F = np.array([0.0, 16.4, 75.1, 87.5, 100.0])
    span, fs_pos = 36.0 + 63.0, 36.0
    x = np.linspace(0.0, np.interp(span, F, z), 400)
    target = np.interp(x, z, F)
    cost = lambda log_s0: np.sum((span * (1.0 - np.exp(-np.exp(log_s0) * x / fs_pos)) - target) ** 2)  # noqa: E731
    independent = float(np.exp(minimize_scalar(cost, bounds=(np.log(1e3), np.log(1e9)), method="bounded",
                                               options={"xatol": 1e-8}).x))
    sigma0 = as_model(default_params(), "lugre").sigma0
    assert sigma0 == pytest.approx(independent, rel=1e-3)
    assert sigma0 == pytest.approx(3.17e5, rel=5e-3)  # the README's "σ0 = 3.17e5 N·m/rad"


def test_a_tanh_curve_short_of_the_outer_loop_is_warned_of_and_does_not_settle(kuka):
    """A tanh curve topping below F_s⁺ − F_s⁻ with a small k reaches that span only far past
    its bend: said by ``sanity_warnings``, and true of the simulation (a curve that reaches it is
    not warned of, and settles)."""
    from leuven_friction.model.params import TanhShape, sanity_warnings

    def after_reversal(p, v=0.01):
        T1 = 0.02 / v
        t = np.arange(0.0, 2 * T1, 2e-6 / v)
        x = np.where(t < T1, -v * t, -v * T1 + v * (t - T1))
        return simulate_displacement(p, t, x).friction_force[-1]

    S_plus = 27.0 + 9.0 * np.exp(-(0.01 / 0.007) ** 0.5) + 7.7 * 0.01  # Table I, v = 0.01 rad/s
    short = kuka.replace(transition_curve=TransitionCurve(kind="tanh_linear", shape=TanhShape(A=60.0, z0=1e-4, k=1.0)))
    assert any("reaches the outer loop's span 99 only past" in w for w in sanity_warnings(short))
    assert abs(after_reversal(short) - S_plus) > 0.1 * S_plus  # 0.02 rad on: not settled
    reaching = kuka.replace(transition_curve=TransitionCurve(kind="tanh_linear", shape=TanhShape(A=90.0, z0=1e-4, k=1e5)))
    assert not any("outer loop" in w for w in sanity_warnings(reaching))
    assert after_reversal(reaching) == pytest.approx(S_plus, rel=1e-3)
