"""Recordings with a hidden effect, for testing the discrepancy workflow (``leuven-friction
diagnose``). ``python synth/effects.py [--all]`` writes the example CSV (or
one per effect and the control).

A recording is a prescribed motion (a tribometer or a servo-driven slide) with the friction
measured: constant-velocity strokes in both directions over a 0.4 rad range, each followed
by a dwell and a presliding episode (small, decaying oscillations: internal loops). The base
friction comes from the simulator with a parameter set unrelated to the defaults (S(v)
perturbed by up to ±15 %, seeded); the effect is then imposed by its own physical rule
below, written independently of the workflow's candidate library, and Gaussian noise is
added. The truth is returned beside the data and never written into the CSV.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
from scipy.signal import lfilter

from leuven_friction.model import Stribeck, StribeckSide, default_params, simulate_displacement, transition_curve_values
from leuven_friction.model.effects import stiffness_scaled

HERE = Path(__file__).resolve().parent.parent / "sample_data"
SPEEDS = (0.003, 0.006, 0.012, 0.025, 0.05, 0.1, 0.2, 0.4)
EFFECT_NAMES = ("position_periodic", "position_smooth", "time_drift", "normal_load", "sign_asymmetry",
                "viscous_shape", "presliding_stiffness", "cyclic_softening", "frictional_lag")

def unrelated_params(rng):
    p = default_params()
    sides = {}
    for name in ("positive", "negative"):
        s = getattr(p.stribeck, name)
        f = 1.0 + rng.uniform(-0.15, 0.15, 5)
        Fc = s.Fc * f[1]
        Fs = Fc + (s.Fs - s.Fc) * f[0]
        sides[name] = StribeckSide(Fs=Fs, Fc=Fc, vs=s.vs * f[2], delta=s.delta * f[3], sigma2=s.sigma2 * f[4])
    return p.replace(stribeck=Stribeck(**sides))

def motion(rng, rate: float = 1000.0, samples: int = 100_000):
    """Strokes, dwells and presliding episodes until ``samples`` samples at ``rate`` Hz."""
    dt = 1.0 / rate
    speeds = list(SPEEDS)
    x_lo, x_hi = 0.0, 0.4
    xs = [np.array([0.2])]
    x = 0.2
    k = 0
    while sum(len(a) for a in xs) < samples:
        v = speeds[k % len(speeds)] * (1 if (k // len(speeds)) % 2 == 0 else -1)
        if k % len(speeds) == 0:
            rng.shuffle(speeds)
        k += 1
        target_dist = max(0.03, min(0.25, abs(v) * 2.0))
        direction = np.sign(v) if x_lo < x + np.sign(v) * target_dist < x_hi else -np.sign(v)
        n = int(target_dist / abs(v) / dt)
        xs.append(x + direction * abs(v) * dt * np.arange(1, n + 1))
        x = xs[-1][-1]
        xs.append(np.full(int(0.3 / dt), x))  # dwell
        m = int(1.5 / dt)
        tt = np.arange(1, m + 1) * dt
        amp = rng.uniform(4e-5, 2e-4)
        xs.append(x + amp * np.sin(2 * np.pi * 2.0 * tt) * np.exp(-tt / 0.8))
        x = xs[-1][-1]
        if k % len(speeds) == 0:
            # a sinusoidal sweep: velocities between the strokes' levels and up to 0.8
            m = int(2.0 / dt)
            tt = np.arange(1, m + 1) * dt
            xs.append(x + 0.8 / (2 * np.pi * 0.5) * (1 - np.cos(2 * np.pi * 0.5 * tt)) * np.sign(0.2 - x))
            x = xs[-1][-1]
    pos = np.concatenate(xs)[:samples]
    return np.arange(samples) * dt, pos

def make_recording(effect: str | None = None, seed: int = 0, samples: int = 100_000, noise: float = 0.3):
    """(DataFrame with time, position, friction[, normal_load]; truth dict)."""
    rng = np.random.default_rng(seed)
    p = unrelated_params(rng)
    t, x = motion(rng, samples=samples)
    sim_p = stiffness_scaled(p, 2.5) if effect == "presliding_stiffness" else p
    x_sim = x
    if effect == "sign_asymmetry":
        # an asymmetric contact: the presliding spring 1.8× softer in the positive direction
        dx = np.diff(x)
        x_sim = np.concatenate([[x[0]], x[0] + np.cumsum(np.where(dx > 0, dx / 1.8, dx))])
    r = simulate_displacement(sim_p, t, x_sim)
    F = r.friction_force.copy()
    v = r.velocity
    cols = {"time": t, "position": x}
    truth = {"effect": effect, "params": None}
    if effect == "position_periodic":
        F *= 1.0 + 0.06 * np.sin(2 * np.pi * x / 0.04 + 0.7)
    elif effect == "position_smooth":
        F *= 1.0 + 0.25 * (x - 0.2) / 0.4
    elif effect == "time_drift":
        F *= 1.0 - 0.12 * (1.0 - np.exp(-t / 40.0))
    elif effect == "normal_load":
        steps = rng.uniform(0.75, 1.25, size=int(t[-1] / 5) + 1)
        load = 1000.0 * steps[(t / 5).astype(int)]
        F *= load / 1000.0
        cols["normal_load"] = load
    elif effect == "sign_asymmetry":
        pass  # simulated above along the warped path
    elif effect == "viscous_shape":
        F += 15.0 * v * np.abs(v)
    elif effect == "presliding_stiffness":
        pass  # simulated above with the transition curve stretched 2.5× along z
    elif effect == "cyclic_softening":
        fd = transition_curve_values(p, r.z)
        s = np.sign(np.where(np.abs(v) > 0, v, np.nan))
        s = pd.Series(s).ffill().fillna(0).to_numpy()
        nrev = np.concatenate([[0], np.cumsum(np.abs(np.diff(s)) > 0)])
        F -= 0.35 * (nrev / max(nrev[-1], 1)) * fd
    elif effect == "frictional_lag":
        a = np.exp(-(t[1] - t[0]) / 0.08)
        F = lfilter([1 - a], [1, -a], F, zi=[a * F[0]])[0]
    elif effect is not None:
        raise ValueError(f"unknown effect {effect!r}")
    cols["friction"] = F + rng.normal(0.0, noise, len(F))
    return pd.DataFrame(cols), truth

def main(argv=None):
    """Writes effect_position_periodic.csv (the README's example); ``--all`` writes every effect
    and the control (effect_none.csv)."""
    import sys

    names = (None,) + EFFECT_NAMES if "--all" in (argv or sys.argv[1:]) else ("position_periodic",)
    for name in names:
        df, _ = make_recording(name, seed=11)
        fname = f"effect_{name or 'none'}.csv"
        df.to_csv(HERE / fname, index=False, float_format="%.9g")
        print(fname, len(df))

if __name__ == "__main__":
    main()
