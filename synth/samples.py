"""Make the sample recordings from the paper's parameter values (Tables I, II; n = 7,
σ1 = 1500, I = 5 kg·m²) with realistic noise. Run: ``python synth/samples.py``.

Every function returns a DataFrame, so tests can make fresh noisy copies with other seeds.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from leuven_friction.model import default_params, simulate_displacement, simulate_force

HERE = Path(__file__).resolve().parent.parent / "sample_data"
SPEEDS = np.array([0.001, 0.002, 0.004, 0.008, 0.015, 0.03, 0.06, 0.12, 0.25, 0.5, 1.0])


def constant_velocity(params=None, seed: int = 1, torque_noise: float = 0.5, speeds=SPEEDS, rate: float = 500.0,
                      t_acc: float = 0.0):
    """Constant-velocity tests, positive then negative: each level long enough to settle
    (≥ 6e-3 rad or 1 s), torque with Gaussian noise ``torque_noise`` N·m, sampled at ``rate`` (500 Hz).

    ``t_acc = 0``: the velocity steps between levels and the torque is the friction (a torque
    sensor at the contact). ``t_acc > 0``: the velocity ramps between levels over ``t_acc``
    seconds and the torque is the applied one, I·ẍ + F (a motor torque)."""
    p = params or default_params()
    rng = np.random.default_rng(seed)
    vel = np.concatenate([speeds, -speeds])
    durations = np.maximum(1.0, 6e-3 / np.abs(vel))
    dt = 1e-4
    t = np.arange(0.0, durations.sum(), dt)
    edges = np.concatenate([[0], np.cumsum(durations)])
    v = vel[np.clip(np.searchsorted(edges, t, side="right") - 1, 0, len(vel) - 1)]
    if t_acc > 0:
        n_acc = int(round(t_acc / dt))
        v = np.convolve(np.concatenate([np.zeros(n_acc), v]), np.ones(n_acc) / n_acc, mode="full")[n_acc:n_acc + len(t)]
    x = np.concatenate([[0.0], np.cumsum(v[1:] * dt)])
    r = simulate_displacement(p, t, x)
    k = int(round(1.0 / (rate * dt)))
    sel = slice(0, None, k)
    torque = r.applied_force if t_acc > 0 else r.friction_force
    return pd.DataFrame({
        "time": t[sel],
        "position": x[sel],
        "torque": torque[sel] + rng.normal(0.0, torque_noise, len(t[sel])),
    })


def force_ramps(levels, rate: float = 2.0, params=None, dt: float = 1e-4, sample: float = 5e-3):
    """Applied torque ramped through ``levels`` at ``rate`` N·m/s on I·ẍ = f − F."""
    p = params or default_params()
    times = np.concatenate([[0.0], np.cumsum(np.abs(np.diff(levels)) / rate)])
    t = np.arange(0.0, times[-1], dt)
    f = np.interp(t, times, levels)
    r = simulate_force(p, t, f)
    k = int(round(sample / dt))
    return t[::k], r.position[::k], f[::k]


PRESLIDING_LEVELS = [0, 20, 5, 30, -10, 10, -40, -20, -50, 25, 0, 33]


def presliding_proximity(params=None, seed: int = 2, sigma: float = 5e-8):
    """Presliding force ramps with internal loops, position from a proximity sensor
    (Gaussian noise σ = 5e-8 rad, the paper's resolution)."""
    rng = np.random.default_rng(seed)
    t, x, f = force_ramps(PRESLIDING_LEVELS, params=params)
    return pd.DataFrame({"time": t, "position": x + rng.normal(0.0, sigma, len(t)), "applied_torque": f})


def presliding_encoder(params=None, seed: int = 3, step: float = 1.6e-5, jitter: float = 4e-6):
    """The same kind of ramps read by the motor encoder: 1.6e-5 rad steps (the paper's);
    the true angle carries a small vibration (Gaussian, 4e-6 rad) before quantisation."""
    rng = np.random.default_rng(seed)
    t, x, f = force_ramps([0, 30, -10, 25, -55, 0, -45], params=params)
    q = step * np.round((x + rng.normal(0.0, jitter, len(t))) / step)
    return pd.DataFrame({"t": t, "q": q, "tau": f})


def mixed_session(params=None, seed: int = 4):
    """One test session: presliding ramps, then constant-velocity runs in both directions
    (velocity ramped between levels over 50 ms), the applied torque logged throughout,
    headers with units (angle in mrad, time in s)."""
    a = presliding_proximity(params, seed)
    b = constant_velocity(params, seed + 100, t_acc=0.05)
    b = b.assign(time=b["time"] + a["time"].iloc[-1] + 1e-3,
                 position=b["position"] + a["position"].iloc[-1])
    b = b.rename(columns={"torque": "applied_torque"})
    df = pd.concat([a, b], ignore_index=True)
    return pd.DataFrame({"Time (s)": df["time"], "Angle [mrad]": df["position"] * 1e3,
                         "Torque [Nm]": df["applied_torque"]})


FILES = {
    "constant_velocity.csv": constant_velocity,
    "presliding_proximity.csv": presliding_proximity,
    "presliding_encoder.csv": presliding_encoder,
    "session_mixed.csv": mixed_session,
}


def main():
    for name, make in FILES.items():
        df = make()
        df.to_csv(HERE / name, index=False, float_format="%.10g")
        print(f"{name}: {len(df)} rows")


if __name__ == "__main__":
    main()
