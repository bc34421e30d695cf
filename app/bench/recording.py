"""A test session of any length for the scale benchmark, at one sample rate: presliding force
ramps with internal loops, then constant-velocity runs in both directions, simulated with the
paper's model; position noise 5e-8 rad on the ramps (a proximity sensor), torque noise 0.05 N·m
on the ramps (commanded) and 0.5 N·m on the runs (measured).

This is load for timing, not evidence about the estimators (their tests use an independent
generator): what matters here is that every size has the same mix of regimes, so that cost
per row can be compared across sizes.
"""

from __future__ import annotations

import numpy as np

from ...model import default_params, simulate_displacement, simulate_force

LEVELS = [0, 20, 5, 30, -10, 10, -40, -20, -50, 25, 0, 33]
SPEEDS = np.array([0.001, 0.002, 0.004, 0.008, 0.015, 0.03, 0.06, 0.12, 0.25, 0.5, 1.0])
RAMP_RATE = 2.0  # N·m/s


def _grid(duration: float, rows: int) -> tuple[np.ndarray, int, np.ndarray]:
    """Sample times, and a simulation grid at most 1e-4 s a step that contains them."""
    t = np.linspace(0.0, duration, rows)
    sub = max(1, int(np.ceil((t[1] - t[0]) / 1e-4)))
    return t, sub, np.linspace(0.0, duration, (rows - 1) * sub + 1)


def session(rows: int, seed: int = 5) -> dict:
    """Columns time (s), position (rad), torque (N·m) of ``rows`` samples at one sample rate:
    the force ramps first, then the constant-velocity runs (each at least 1 s or 6e-3 rad)."""
    rng = np.random.default_rng(seed)
    p = default_params()
    knots = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(LEVELS)) / RAMP_RATE)])
    vel = np.concatenate([SPEEDS, -SPEEDS])
    durations = np.maximum(1.0, 6e-3 / np.abs(vel))
    edges = np.concatenate([[0.0], np.cumsum(durations)])
    n_pre = int(round(rows * knots[-1] / (knots[-1] + edges[-1])))
    if n_pre < 100 or rows - n_pre < 100:
        raise ValueError(f"rows: need at least a few hundred, got {rows}")
    t1, sub, tf = _grid(knots[-1], n_pre)
    x1 = simulate_force(p, tf, np.interp(tf, knots, LEVELS)).position[::sub]
    f1 = np.interp(t1, knots, LEVELS)
    t2, sub, tf = _grid(edges[-1], rows - n_pre)
    v = vel[np.clip(np.searchsorted(edges, tf, side="right") - 1, 0, len(vel) - 1)]
    xf = np.concatenate([[0.0], np.cumsum(v[1:] * np.diff(tf))])
    f2 = simulate_displacement(p, tf, xf).friction_force[::sub]
    dt = t1[1] - t1[0]
    return {
        "time": np.concatenate([t1, t1[-1] + dt + t2]),
        "position": np.concatenate([x1 + rng.normal(0.0, 5e-8, n_pre), x1[-1] + xf[::sub]]),
        "torque": np.concatenate([f1 + rng.normal(0.0, 0.05, n_pre), f2 + rng.normal(0.0, 0.5, len(f2))]),
    }


def session_files(rows: int, seed: int = 5) -> dict:
    """The same session as two recordings, as a test campaign would store it: the force ramps
    and the constant-velocity runs (each file gets its own noise floors and thresholds)."""
    c = session(rows, seed)
    t = c["time"]
    # the runs start where the ramps end: the first sample after the last ramp knot's time
    knots_end = float(np.sum(np.abs(np.diff(LEVELS))) / RAMP_RATE)
    split = int(np.searchsorted(t, knots_end, side="right"))
    ramps = {k: v[:split] for k, v in c.items()}
    runs = {k: v[split:] for k, v in c.items()}
    runs["time"] = runs["time"] - runs["time"][0]
    return {"ramps": ramps, "runs": runs}
