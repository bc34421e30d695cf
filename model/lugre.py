"""LuGre's bristle stiffness sigma0 for a model given by a Leuven transition curve.

The paper gives no sigma0 for the robot. Fig. 4 fits sigma0 so that LuGre's transition
curve matches the measured one in the least-squares sense; we do the same against the
Leuven outer transition curve: starting from sliding in the negative direction
(F = F_s-) and reversing slowly, LuGre gives (eq. (1) with g = |S|/σ0, v → 0+)

    F(x) - F_s- = (F_s+ - F_s-)·(1 - exp(-σ0·x / F_s+)),

and the Leuven model, in presliding where z ≈ x, gives F_d(x). sigma0 minimises the squared
difference on a uniform grid of x over the whole outer curve, 0 ≤ x ≤ F_d^{-1}(F_s+ - F_s-).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize_scalar

from .kernels import transition_curve_array, transition_curve_inverse


def lugre_sigma0_from_transition_curve(p, n_grid: int = 400) -> float:
    kind, tz, tF = p.curve_arrays()
    fs_pos = p.stribeck.positive.Fs
    span = fs_pos - p.stribeck.negative.Fs
    x_end = transition_curve_inverse(kind, tz, tF, span)
    x = np.linspace(0.0, x_end, n_grid)
    target = np.empty_like(x)
    transition_curve_array(kind, tz, tF, x, target)

    def cost(log_sigma0: float) -> float:
        s0 = np.exp(log_sigma0)
        return float(np.sum((span * (1.0 - np.exp(-s0 * x / fs_pos)) - target) ** 2))

    k0 = np.log(span / x_end)
    res = minimize_scalar(cost, bounds=(k0 - 5.0, k0 + 15.0), method="bounded", options={"xatol": 1e-6})
    return float(np.exp(res.x))
