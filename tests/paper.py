"""The paper's tables and equations written out for the tests' expectations, not read from the
model: Table I (S(v) per side), Table II (the transition curve's knots), eqs. (6)-(7)."""

import numpy as np

# Table I: (F_s, F_c, v_s, δ, σ2) per sign of the velocity
TABLE_ONE = {+1: (36.0, 27.0, 0.007, 0.5, 7.7), -1: (-63.0, -52.0, -0.004, 0.9, 8.0)}
# Table II: F_d(z) piecewise linear through these knots
TABLE_II_Z = np.array([0.0, 1.8e-6, 1.41e-4, 2.66e-4, 5.21e-4])
TABLE_II_F = np.array([0.0, 16.4, 75.1, 87.5, 100.0])


def eq6(theta, v):
    """Eqs. (6)-(7) for one side θ = (F_s, F_c, v_s, δ, σ2): S(v) + σ2·v."""
    Fs, Fc, vs, delta, sigma2 = theta
    v = np.asarray(v, dtype=float)
    return Fc + (Fs - Fc) * np.exp(-np.abs(v / vs) ** delta) + sigma2 * v


def two_sided(positive, negative, v):
    """S(v) + σ2·v with each sign of v on its own side's θ, and 0 at rest (v = 0)."""
    v = np.asarray(v, dtype=float)
    return np.where(v > 0, eq6(positive, v), np.where(v < 0, eq6(negative, v), 0.0))


def table_one(v):
    """Steady sliding friction of Table I's joint at velocity v (≠ 0)."""
    return two_sided(TABLE_ONE[1], TABLE_ONE[-1], v)


def table_two(z) -> np.ndarray:
    """F_d(z) of Table II, odd in z."""
    z = np.asarray(z, dtype=float)
    return np.sign(z) * np.interp(np.abs(z), TABLE_II_Z, TABLE_II_F)
