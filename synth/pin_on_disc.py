"""A pin-on-disc tribometer, simulated on its own terms (it imports nothing of the tool).

The disc turns one way only, under a speed-controlled spindle: seven speeds from 0.5 to 60 rpm,
each held 15 s, twice over in a shuffled order, with the spindle brought to rest for 3 s before
every third speed. There are no reversals, so no presliding hysteresis to fit, only the starts
from rest. The pin sits at r = 20 mm; its contact is three elasto-plastic elements in parallel
(each a spring k_i that slips at w_i·S(v)·N, S(v) = μ_c + (μ_s − μ_c)/(1 + (v/v_s)²)), plus a
viscous term c_v·v·N, integrated along the prescribed sliding at 2 kHz and logged at 200 Hz.

Logged as a tribometer's software writes it: the time in s, the disc's angle in degrees from a
single-turn encoder (4096 counts a turn, so the angle wraps at 360°), the tangential force on
the pin in N from a load cell (noise 0.4 % of the mean friction and a 50 Hz hum), and the
normal load in N.

Effects:

* ``"run_in"``: the contact runs in over the sliding distance s (not the time), friction ×
  (1 + b·e^(−s/s0)), b = 0.35, s0 = 3 m of the 6.8 m the session slides: it starts 35 % high;
* ``"load"``: dead weights of 5, 10 and 20 N changed between speeds (not monotone in time),
  friction ∝ (N/N0)^α with α = 0.8 (N0 = 10 N).

``python -m synth.pin_on_disc DIR`` writes ``control.csv``, ``run_in.csv`` and ``load.csv``.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
from numba import njit

R = 0.02  # m, the pin's track radius
MU_S, MU_C, V_S, C_V = 0.62, 0.41, 4e-3, 0.35  # -, -, m/s, s/m (per newton of load)
K = np.array([6e5, 2e5, 5e4])  # N/m, the elements' stiffnesses
W = np.array([0.5, 0.3, 0.2])  # shares of the slip level
RPM = np.array([0.5, 1.0, 2.0, 5.0, 10.0, 30.0, 60.0])
HOLD, REST, RAMP = 15.0, 3.0, 0.8  # s
SIM_RATE, LOG_RATE = 2000.0, 200.0
COUNTS = 4096
N0 = 10.0
RUN_IN = {"b": 0.35, "s0": 3.0}
LOAD_ALPHA = 0.8


def schedule(seed: int):
    """Disc speed (rad/s) and normal load (N) at the simulation's rate."""
    rng = np.random.default_rng([seed, 5150])
    order = np.concatenate([rng.permutation(len(RPM)), rng.permutation(len(RPM))])
    loads = np.array([10.0, 20.0, 5.0, 10.0, 20.0, 5.0, 20.0, 10.0, 5.0, 10.0, 5.0, 20.0, 10.0, 20.0])
    w_seg, n_seg = [], []
    w_prev = 0.0
    for k, i in enumerate(order):
        w = RPM[i] * 2 * np.pi / 60.0
        stop = k % 3 == 0
        if stop:
            # ramp down, rest, ramp up
            w_seg.append(np.linspace(w_prev, 0.0, int(RAMP * SIM_RATE)))
            w_seg.append(np.zeros(int(REST * SIM_RATE)))
            w_prev = 0.0
        n = int(HOLD * SIM_RATE)
        ramp = np.linspace(w_prev, w, int(RAMP * SIM_RATE))
        w_seg.append(np.concatenate([ramp, np.full(n, w)]))
        load = loads[k % len(loads)]
        n_seg.extend([np.full(int(RAMP * SIM_RATE) + int(REST * SIM_RATE), load)] if stop else [])
        n_seg.append(np.full(len(ramp) + n, load))
        w_prev = w
    return np.concatenate(w_seg), np.concatenate(n_seg)


def stribeck(v):
    return MU_C + (MU_S - MU_C) / (1.0 + (v / V_S) ** 2)


@njit(cache=True)
def _contact(ds, v, level, k, w, cv):
    """Elements loaded by the sliding increments ds, each slipping at w_i·level."""
    s = np.zeros(len(k))
    out = np.zeros(len(ds))
    for i in range(len(ds)):
        f = 0.0
        for j in range(len(k)):
            s[j] += ds[i]
            lim = w[j] * level[i] / k[j]
            if s[j] > lim:
                s[j] = lim
            elif s[j] < -lim:
                s[j] = -lim
            f += k[j] * s[j]
        out[i] = f + cv[i] * v[i]
    return out


def recording(case: str, seed: int = 3):
    rng = np.random.default_rng([seed, 77])
    omega, load = schedule(seed)
    if case != "load":
        load = np.full(len(omega), N0)
    dt = 1.0 / SIM_RATE
    t = np.arange(len(omega)) * dt
    angle = np.concatenate([[0.0], np.cumsum(0.5 * (omega[1:] + omega[:-1]) * dt)])
    v = R * omega
    s = R * angle  # sliding distance
    g = (load / N0) ** LOAD_ALPHA if case == "load" else np.ones(len(t))
    if case == "run_in":
        g = g * (1.0 + RUN_IN["b"] * np.exp(-s / RUN_IN["s0"]))
    level = stribeck(v) * N0 * g
    ds = np.concatenate([[0.0], np.diff(s)])
    friction = _contact(ds, v, level, K, W, C_V * N0 * g)
    step = int(SIM_RATE / LOG_RATE)
    idx = np.arange(0, len(t), step)
    mean_f = float(np.mean(np.abs(friction)))
    force = (friction[idx] + 0.004 * mean_f * rng.standard_normal(len(idx))
             + 0.01 * mean_f * np.sin(2 * np.pi * 50.0 * t[idx] + 0.3))
    counts = np.floor(angle[idx] / (2 * np.pi) * COUNTS)
    deg = np.mod(counts, COUNTS) * 360.0 / COUNTS
    df = pd.DataFrame({"Time [s]": np.round(t[idx], 4), "Disc angle [deg]": deg, "Ft [N]": np.round(force, 4),
                       "Fn [N]": np.round(load[idx] + 0.02 * rng.standard_normal(len(idx)), 3)})
    truth = {"case": case, "mu_s": MU_S, "mu_c": MU_C, "v_s_m_per_s": V_S, "radius_m": R,
             "omega_s_rad_per_s": V_S / R, "N0": N0,
             "effect": (RUN_IN if case == "run_in" else {"alpha": LOAD_ALPHA} if case == "load" else None)}
    return df, truth


if __name__ == "__main__":
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for case in ("control", "run_in", "load"):
        df, truth = recording(case)
        df.to_csv(out / f"{case}.csv", index=False)
        print(case, len(df), truth)
