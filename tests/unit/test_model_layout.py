"""The Python/kernel boundary (model.layout) and the implicit step of eq. (5) on its own."""

import numpy as np
import pytest
from scipy.optimize import brentq

from leuven_friction.model import initial_state, simulate_displacement
from leuven_friction.model import kernels as K
from leuven_friction.model.layout import MODEL_NAMES, CurveKind, ModelKind, State
from leuven_friction.model.params import MODEL_KINDS, TRANSITION_KINDS
from leuven_friction.model.simulate import pack


def test_model_and_curve_names_come_from_the_enums():
    assert MODEL_KINDS == MODEL_NAMES == ("leuven", "lugre", "static")
    assert TRANSITION_KINDS == ("piecewise_linear", "tanh_linear")
    assert ModelKind.parse("lugre") is ModelKind.LUGRE and ModelKind.LUGRE.label == "lugre"
    assert CurveKind(0).label == "piecewise_linear"


def test_state_view_reads_the_memory_after_a_loop(kuka):
    # 0 -> 5e-5 -> 2e-5 (slow): one maximum on M, the start (0) on m, descending from it
    x = np.concatenate([np.linspace(0, 5e-5, 2000, endpoint=False), np.linspace(5e-5, 2e-5, 2001)])
    t = np.arange(len(x)) * 1e-2
    st = initial_state(kuka)
    r = simulate_displacement(kuka, t, x, state=st)
    s = State(st)
    assert s.direction == -1
    assert s.reversals == 2  # from rest, and at the top
    assert s.stack_m == [kuka.stribeck.negative.Fs, 0.0]
    assert s.stack_M[0] == kuka.stribeck.positive.Fs and len(s.stack_M) == 2
    assert s.F_b == s.stack_M[-1]  # a descending curve starts at the newest maximum
    assert s.z == r.z[-1]


def _residual(p, kind, tz, tF, z0, dx, D, n):
    def g(z):
        r = K.transition_curve(kind, tz, tF, z) / D
        return z - z0 - dx * (1.0 - np.sign(r) * abs(r) ** n)
    return g


@pytest.mark.parametrize("seed", range(4))
def test_implicit_step_finds_the_root_for_small_and_large_steps(kuka, seed):
    """The Newton solve with its bracketed fallback against scipy's brentq on the same
    backward-Euler residual: presliding and sliding, steps from 1e-9 rad to encoder-sized jumps
    of 1e-3 rad (far beyond the curve's last knot), from below and above the steady state."""
    rng = np.random.default_rng(seed)
    code, p, kind, tz, tF = pack(kuka)
    for _ in range(200):
        side = rng.choice([-1.0, 1.0])
        dx = side * 10 ** rng.uniform(-9, -3)
        D = side * rng.uniform(5.0, 120.0)  # S(v) - F_b has the sign of the motion
        # z0 anywhere from the start of a curve to beyond its steady state F_d(z) = D
        z_ss = K.transition_curve_inverse(kind, tz, tF, D)
        z0 = z_ss * rng.uniform(0.0, 1.5)
        fd0 = K.transition_curve(kind, tz, tF, z0)
        z1 = K.solve_state_equation(p, kind, tz, tF, z0, fd0, dx, D, 1.0)
        g = _residual(p, kind, tz, tF, z0, dx, D, kuka.n)
        a, b = sorted((z0 - 2 * abs(dx) - abs(z_ss), z0 + 2 * abs(dx) + abs(z_ss)))
        root = brentq(g, a, b, xtol=1e-16, rtol=1e-15)
        # the solver stops when its Newton correction is below 1e-7 of the step
        assert abs(z1 - root) <= 1e-6 * abs(dx) + 1e-15 * abs(root)
