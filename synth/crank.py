"""A crank-driven tribometer, simulated on its own terms (it imports nothing of the tool).

The motion is prescribed, x = A·sin(2π f t) (a crank or a voice coil on a reciprocating
tribometer): there is no run of constant velocity in either direction, only the slow top of
each stroke. The friction is Dahl's presliding hysteresis, integrated along the motion in
sub-steps,

    dF_h/dx = σ0·g(t)·(1 − F_h/(F_c·g(t))·sgn ẋ),

plus viscous friction σ2·ẋ, read by a force sensor with Gaussian noise; the position is read
in µm with Gaussian noise. Dahl's curve is an exponential, not eq. (5)'s hysteresis, and its
contact has neither a Stribeck term nor micro-damping σ1.

Effects, imposed through the factor g(t) on both F_c and σ0 (a contact that grows stiffer as it
grips harder, so the presliding range stays):

* ``"time_drift"``: g = 1 + b·(1 − e^(−t/τ)) (running-in, warming);
* ``"normal_load"``: a ``normal_load [N]`` column cycling slowly about N0 (not monotone in
  time, so a drift cannot stand in for it), g = (N/N0)^α.

``crank_recording(seed, effect)`` returns the DataFrame (as a file would hold it) and the
values used.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
from numba import njit

FC, SIGMA0, SIGMA2 = 4.0, 4e5, 150.0  # N, N/m, N·s/m: Dahl's presliding reaches 90 % in ln(10)·F_c/σ0 = 23 µm
AMPLITUDE, FREQ = 2e-3, 2.0  # m, Hz
X_NOISE, F_NOISE = 5e-8, 0.02  # m, N
SUBSTEPS = 10


@njit(cache=True)
def _dahl(x, g, fc, sigma0, substeps):
    h = 0.0
    out = np.zeros(len(x))
    for i in range(1, len(x)):
        dx = (x[i] - x[i - 1]) / substeps
        level = fc * g[i]
        for _ in range(substeps):
            s = 1.0 if dx > 0 else (-1.0 if dx < 0 else 0.0)
            h += sigma0 * g[i] * dx * (1.0 - h / level * s)
        out[i] = h
    return out


def crank_recording(seed: int, effect: str | None = None, *, duration: float = 40.0, rate: float = 2000.0):
    rng = np.random.default_rng([seed, 4411])
    t = np.arange(int(duration * rate)) / rate
    x = AMPLITUDE * np.sin(2 * np.pi * FREQ * t)
    v = AMPLITUDE * 2 * np.pi * FREQ * np.cos(2 * np.pi * FREQ * t)
    g = np.ones(len(t))
    truth = {"Fc": FC, "sigma0": SIGMA0, "sigma2": SIGMA2}
    load = None
    if effect == "time_drift":
        b, tau = rng.uniform(0.2, 0.4) * rng.choice([-1.0, 1.0]), duration * rng.uniform(0.15, 0.4)
        g = 1.0 + b * -np.expm1(-t / tau)
        truth.update(b=b, tau=tau)
    elif effect == "normal_load":
        n0, alpha = rng.uniform(5.0, 20.0), rng.uniform(0.6, 0.95)
        load = n0 * (1.0 + 0.5 * np.sin(2 * np.pi * t / (duration * rng.uniform(0.5, 0.8)) + rng.uniform(0, 2 * np.pi)))
        g = (load / n0) ** alpha
        truth.update(N0=n0, alpha=alpha)
    elif effect is not None:
        raise ValueError(f"effect: one of None, 'time_drift', 'normal_load'; got {effect!r}")
    friction = _dahl(x, g, FC, SIGMA0, SUBSTEPS) + SIGMA2 * v
    df = pd.DataFrame({"time [s]": t, "position [um]": (x + rng.normal(0, X_NOISE, len(t))) * 1e6,
                       "friction [N]": friction + rng.normal(0, F_NOISE, len(t))})
    if load is not None:
        df["normal_load [N]"] = load + rng.normal(0, 0.01 * np.mean(load), len(t))
    return df, truth
