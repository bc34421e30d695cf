"""Effects the base model does not hold (Section VI's remark and the conclusion): each a
physically meaningful extension with a few parameters, applied to a simulation's output.

The paper suggests "a scaling function or factor in the friction force (3) or in the state
equation (5)". Here every effect is a function of the simulated signals (F, F_d(z), x, v, t,
normal load, reversal count) and its parameters, and most are linear in their parameters
given one nonlinear shape parameter (a period, a time constant), which the diagnosis scans.
Two presliding effects instead change what is simulated: the stiffness effect rescales the
transition curve's abscissas (``stiffness_scaled``), the direction asymmetry rescales the
positive displacement increments (``direction_scaled_path``).

An effect is stored in the parameter file as ``{name: ..., params: {...}}``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .params import FrictionParams, TransitionCurve


@dataclass
class Signals:
    """What an effect may depend on, sample by sample."""

    time: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    friction: np.ndarray  # the base model's friction force
    transition: np.ndarray  # F_d(z) = F_h - F_b, the presliding part of the hysteresis force
    reversals: np.ndarray  # cumulative count of velocity reversals
    load: np.ndarray | None = None


def reversal_count(velocity: np.ndarray, v_min: float = 0.0) -> np.ndarray:
    """Cumulative number of sign changes of the velocity (ignoring |v| <= v_min)."""
    s = np.sign(np.where(np.abs(velocity) > v_min, velocity, 0.0))
    idx = np.flatnonzero(s)
    if len(idx) < 2:
        return np.zeros(len(s))
    changes = np.zeros(len(s))
    changes[idx[1:]] = s[idx[1:]] != s[idx[:-1]]
    return np.cumsum(changes)


def _unit(a: np.ndarray) -> np.ndarray:
    span = float(np.ptp(a))
    return (a - float(np.mean(a))) / span if span > 0 else np.zeros_like(a)


def lowpass(F: np.ndarray, t: np.ndarray, tau: float) -> np.ndarray:
    """First-order lag of time constant tau (exact for piecewise-constant input)."""
    dt = np.diff(t)
    if len(dt) and np.ptp(dt) <= 1e-9 * dt[0]:
        from scipy.signal import lfilter

        a = float(np.exp(-dt[0] / tau)) if tau > 0 else 0.0
        return lfilter([1 - a], [1, -a], F, zi=[a * F[0]])[0]
    out = np.empty_like(F)
    y = F[0]
    out[0] = y
    a = np.exp(-dt / tau) if tau > 0 else np.zeros_like(dt)
    for i in range(1, len(F)):
        y = a[i - 1] * y + (1.0 - a[i - 1]) * F[i]
        out[i] = y
    return out


# Each entry: (description, basis(signals, shape) -> columns, shape grid or None, parameter names)
def _position_periodic(s: Signals, wavelength: float):
    ph = 2 * math.pi * s.position / wavelength
    return np.column_stack([s.friction * np.sin(ph), s.friction * np.cos(ph)])


def _position_smooth(s: Signals, _):
    xi = _unit(s.position)
    return np.column_stack([s.friction * xi, s.friction * xi**2])


def _time_drift(s: Signals, _):
    # level, slope and curvature of a slow scaling: the level too, because a drift moves the
    # presliding forces with the sliding ones, and refitting S(v) only takes out the latter
    tau = _unit(s.time)
    return np.column_stack([s.friction, s.friction * tau, s.friction * tau**2])


def _normal_load(s: Signals, _):
    if s.load is None:
        return None
    mean = float(np.mean(s.load))
    return (s.friction * (s.load - mean) / (abs(mean) if mean else 1.0))[:, None]


def direction_scaled_path(x: np.ndarray, c_up: float) -> np.ndarray:
    """The displacement path with every increment in the positive direction divided by
    ``c_up``. Driving the model with it gives ascending transition curves F_d(z/c_up) — a
    presliding spring ``c_up`` times softer in the positive direction than in the negative
    one — because eq. (5) for w = z/c_up is eq. (5) with the displacement scaled by 1/c_up."""
    dx = np.diff(x)
    return np.concatenate([[x[0]], x[0] + np.cumsum(np.where(dx > 0, dx / c_up, dx))])


def _viscous_shape(s: Signals, _):
    vmax = float(np.max(np.abs(s.velocity))) or 1.0
    u = s.velocity / vmax
    return np.column_stack([u * np.abs(u), u * np.abs(u) * np.abs(u)])


def _cyclic_softening(s: Signals, _):
    n = float(np.max(s.reversals)) or 1.0
    return (s.transition * s.reversals / n)[:, None]


def _frictional_lag(s: Signals, tau: float):
    return (lowpass(s.friction, s.time, tau) - s.friction)[:, None]


EFFECTS = {
    "position_periodic": ("friction varies periodically with position (gear teeth, ball circulation, a "
                          "wavy guide)", _position_periodic, ("a_sin", "a_cos")),
    "position_smooth": ("friction varies smoothly along the stroke (uneven preload, wear, lubrication)",
                        _position_smooth, ("c1", "c2")),
    "time_drift": ("friction drifts over time (temperature, warm-up of the lubricant)", _time_drift,
                   ("d0", "d1", "d2")),
    "normal_load": ("friction scales with the normal load", _normal_load, ("k",)),
    "sign_asymmetry": ("the presliding spring differs between the two directions of motion (an "
                       "asymmetric contact; S(v) per sign already holds the sliding asymmetry)",
                       None, ("c_up",)),
    "viscous_shape": ("the sliding friction has a shape S(v) + σ2·v cannot follow (non-linear viscous "
                      "friction)", _viscous_shape, ("q2", "q3")),
    "presliding_stiffness": ("the presliding spring is stiffer or softer than the transition curve", None, ("scale",)),
    "cyclic_softening": ("the presliding spring softens (or hardens) with the number of reversals",
                         _cyclic_softening, ("h",)),
    "frictional_lag": ("the friction lags the motion more than the model does", _frictional_lag, ("gain",)),
}

SHAPE = {"position_periodic": "wavelength", "frictional_lag": "tau"}


def basis(name: str, s: Signals, shape: float | None = None):
    """Columns whose linear combination is the effect's change of the friction force."""
    return EFFECTS[name][1](s, shape)


def stiffness_scaled(params: FrictionParams, scale: float) -> FrictionParams:
    """The transition curve stretched along z by ``scale`` (> 1: softer presliding spring)."""
    tc = params.transition_curve
    if tc.kind == "piecewise_linear":
        new = TransitionCurve(kind=tc.kind, z=tuple(v * scale for v in tc.z), F=tc.F)
    else:
        new = TransitionCurve(kind=tc.kind, shape=dict(tc.shape, z0=tc.shape["z0"] * scale, k=tc.shape["k"] / scale))
    return params.replace(transition_curve=new)


def apply_effects(effects, s: Signals) -> np.ndarray:
    """The friction with the stored output effects added (the stiffness effect is already
    in the transition curve of the parameters)."""
    F = s.friction.copy()
    for eff in effects:
        name = eff["name"]
        if name not in EFFECTS or EFFECTS[name][1] is None:
            continue
        B = basis(name, s, eff["params"].get(SHAPE.get(name, ""), None))
        if B is None:
            continue
        coef = np.array([eff["params"][k] for k in EFFECTS[name][2]])
        F = F + B @ coef
    return F
