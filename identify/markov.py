"""Markov estimator of the constant-velocity curve S(v) + σ2·v, eq. (7), per velocity sign.

Section IV-A: weighted least squares over constant-velocity levels, the weights being the
inverse variances of the measured friction at each level. We weight by the variance of each
level's *mean* (sample variance / number of samples), so that the covariance
(JᵀWJ)⁻¹ of the estimate is the one the data support.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from .errors import IdentificationError

NAMES = ("Fs", "Fc", "vs", "delta", "sigma2")


@dataclass
class Levels:
    """Constant-velocity levels: mean velocity, mean friction, variance of that mean."""

    velocity: np.ndarray
    friction: np.ndarray
    variance: np.ndarray
    count: np.ndarray


@dataclass
class SideFit:
    """Estimate for one velocity sign: values, 1-σ, correlation matrix, weighted cost."""

    values: dict
    stderr: dict
    correlation: np.ndarray
    chi2: float
    dof: int
    names: tuple = NAMES
    notes: list = field(default_factory=list)


def stribeck_plus_viscous(theta, v):
    Fs, Fc, vs, delta, sigma2 = theta
    return Fc + (Fs - Fc) * np.exp(-np.abs(v / vs) ** delta) + sigma2 * v


def _jacobian(theta, v):
    """d(S(v) + σ2·v)/dθ for θ = (Fs, Fc, vs, delta, sigma2)."""
    Fs, Fc, vs, delta, sigma2 = theta
    a = np.abs(v / vs)
    ad = a**delta
    e = np.exp(-ad)
    la = np.log(np.maximum(a, 1e-300))
    return np.column_stack([e, 1.0 - e, (Fs - Fc) * e * ad * delta / vs, -(Fs - Fc) * e * ad * la, v])


def fit_side(levels: Levels, sign: int, start: dict | None = None) -> SideFit:
    """Weighted least squares for one sign (scipy ``least_squares``, trust-region reflective).

    Needs at least 6 levels (5 parameters and one degree of freedom). Without ``start`` it
    tries nine starting points (S(v) has local minima in vs and δ); with one, only that."""
    m = levels.velocity * sign > 0
    v, F, var = levels.velocity[m], levels.friction[m], levels.variance[m]
    word = "positive" if sign > 0 else "negative"
    if len(v) < 6:
        raise IdentificationError(f"Markov estimator: only {len(v)} constant-velocity level(s) with {word} velocity; need at least 6")
    w = 1.0 / np.sqrt(np.maximum(var, 1e-18 * np.max(np.abs(F)) ** 2))
    order = np.argsort(np.abs(v))
    v, F, w = v[order], F[order], w[order]
    a = np.abs(v)
    # starting point: σ2 from the fastest levels, F_c from the middle, F_s from the slowest
    hi = a >= np.quantile(a, 0.7)
    s2 = max(0.0, np.polyfit(v[hi], F[hi], 1)[0]) if hi.sum() >= 2 else 0.0
    Fc0 = np.min(np.abs(F - s2 * v)) * sign
    Fs0 = (F[0] - s2 * v[0])
    if abs(Fs0) <= abs(Fc0):
        Fs0 = Fc0 * 1.1
    # Table I convention: negative-side Fs, Fc, vs are negative
    big = np.inf
    if sign > 0:
        lo_b = np.array([1e-12, 1e-12, 1e-12, 0.05, 0.0])
        hi_b = np.array([big, big, big, 5.0, big])
    else:
        lo_b = np.array([-big, -big, -big, 0.05, 0.0])
        hi_b = np.array([-1e-12, -1e-12, -1e-12, 5.0, big])

    def resid(theta):
        return w * (F - stribeck_plus_viscous(theta, v))

    def jac(theta):
        return -w[:, None] * _jacobian(theta, v)

    if start is not None:
        starts = [np.clip([start[k] for k in NAMES], lo_b + 1e-12, hi_b - 1e-12)]
    else:
        starts = [np.clip([Fs0, Fc0, sign * vs0, d0, s2], lo_b + 1e-12, hi_b - 1e-12)
                  for vs0 in np.quantile(a, [0.1, 0.3, 0.6]) for d0 in (0.5, 1.0, 2.0)]
    best = None
    for x0 in starts:
        r = least_squares(resid, x0, jac=jac, bounds=(lo_b, hi_b), method="trf", x_scale="jac", max_nfev=2000)
        if best is None or r.cost < best.cost:
            best = r
    J = best.jac
    notes = []
    try:
        cov = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        cov = np.linalg.pinv(J.T @ J)
        notes.append("the information matrix is singular: some parameters are not identifiable from these levels")
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    corr = cov / np.outer(np.where(sd > 0, sd, 1), np.where(sd > 0, sd, 1))
    for i, name in enumerate(NAMES):
        if np.any(np.isclose(best.x[i], [lo_b[i], hi_b[i]])):
            notes.append(f"{name} is at its bound: its error bar is not meaningful")
    return SideFit(
        values=dict(zip(NAMES, map(float, best.x))),
        stderr=dict(zip(NAMES, map(float, sd))),
        correlation=corr,
        chi2=float(2 * best.cost),
        dof=int(len(v) - 5),
        notes=notes,
    )


def fit_stribeck(levels: Levels, start=None) -> dict:
    """Both signs: {'positive': SideFit, 'negative': SideFit}; ``start`` optionally a
    ``model.Stribeck`` to start from (one start instead of nine)."""
    out = {}
    for side, sign in (("positive", 1), ("negative", -1)):
        st = None if start is None else {k: getattr(getattr(start, side), k) for k in NAMES}
        out[side] = fit_side(levels, sign, st)
    return out
