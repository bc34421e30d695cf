"""A linear test rig whose friction is measured by a load cell, simulated apart from
leuven-friction (numpy only; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
contact unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_dahl_rig.py``).

A sled on a rail, driven in position by a stiff motion controller (the motion is prescribed):
the load cell between drive and sled reads the friction plus m·a, a slow offset drift (0.2 N over
the session) and 0.3 N of noise. Friction: a Dahl contact, dF_h/dx = k0 (1 − F_h/s(v)), solved
exactly over each step, with s(v) a Stribeck curve per direction (F_s 45/42 N, F_c 30/28 N,
v_s 2 mm/s, δ 1.3), plus viscous 150 N·s/m. A Dahl contact does not keep Masing's rule, which
eq. (5)'s memory does: its stiffness just after a reversal is k0 (1 + |F_b|/s), twice as stiff
turning from break-away as from rest, so its small loops are softer than its large ones.
Programme, 2 kHz, 45 s: triangle loops of growing amplitude (1–20 µm at 50 µm/s) about 0, then
strokes at 12 speeds of 0.1–50 mm/s both ways. The position is an interferometer's, 20 nm of
noise, written in inches; the friction in lbf.

Sessions: ``control`` (no effect); ``shuffled`` (the loops' amplitudes in a shuffled order);
``load`` (the whole friction × (N/250 lbf)^0.75, a ``normal_load [lbf]`` column stepping among
150–400 lbf in an order that does not follow time, with 0.4 s ramps).

``python -m synth.dahl_rig OUT_DIR [SESSION …]`` writes them.
"""
import os
import sys

import numpy as np

IN = 0.0254
LBF = 4.4482216152605
DT = 1 / 2000.0
AMAX = 0.5  # m/s², the strokes' acceleration
POS = dict(Fs=45.0, Fc=30.0)
NEG = dict(Fs=42.0, Fc=28.0)
VS, DELTA, SIGMA2, K0, MASS = 2e-3, 1.3, 150.0, 1.0e7, 2.0
N0_LBF, ALPHA = 250.0, 0.75
AMPLITUDES = np.array([1, 2, 3, 5, 7, 10, 14, 20]) * 1e-6  # m, the loops' in growing order
SHUFFLED = np.array([7, 1, 20, 3, 14, 2, 10, 5]) * 1e-6
SESSIONS = {"control": (False, False, 1), "shuffled": (False, True, 3), "load": (True, False, 2)}


def _S(v: float) -> float:
    side = POS if v >= 0 else NEG
    return side["Fc"] + (side["Fs"] - side["Fc"]) * np.exp(-(abs(v) / VS) ** DELTA)


def _move(dx: float, vmax: float, amax: float = AMAX) -> np.ndarray:
    """The velocity samples of a trapezoidal move of signed length dx (scaled to reach it)."""
    L = abs(dx)
    ta = vmax / amax
    if amax * ta * ta > L:  # triangular
        ta = np.sqrt(L / amax)
        vmax = amax * ta
    T = 2 * ta + (L - amax * ta * ta) / vmax
    n = max(int(np.ceil(T / DT)), 2)
    t = (np.arange(n) + 0.5) * T / n
    v = np.clip(np.minimum.reduce([amax * t, np.full(n, vmax), amax * (T - t)]), 0, None)
    return np.sign(dx) * v * L / (v.sum() * DT)


def _dwell(T: float) -> np.ndarray:
    return np.zeros(int(round(T / DT)))


def _programme(load_steps: bool, shuffled: bool) -> tuple[np.ndarray, np.ndarray]:
    segs, loads = [_dwell(0.5)], [np.full(int(round(0.5 / DT)), 250.0)]
    pre_loads = [250, 150, 400, 200, 325, 175, 375, 275]
    pos = 0.0
    for k, A in enumerate(SHUFFLED if shuffled else AMPLITUDES):
        NL = pre_loads[k] if load_steps else 250.0
        for target in (A, -A, A, -A, 0.0):
            v = _move(target - pos, 50e-6, 0.05)
            pos = target
            segs.append(v)
            loads.append(np.full(len(v), NL))
        segs.append(_dwell(0.3))
        loads.append(np.full(len(segs[-1]), NL))
    stroke_loads = [250, 400, 150, 325, 200, 375, 175, 300, 400, 150, 275, 225]
    for k, v0 in enumerate(np.geomspace(0.1e-3, 50e-3, 12)):
        NL = stroke_loads[k] if load_steps else 250.0
        L = v0 * 1.2 + v0 * v0 / AMAX
        for sgn in (+1, -1):
            for seg in (_dwell(0.1), _move(sgn * L, v0)):
                segs.append(seg)
                loads.append(np.full(len(seg), NL))
    segs.append(_dwell(0.3))
    loads.append(np.full(len(segs[-1]), 250.0))
    return np.concatenate(segs), np.concatenate(loads)


def simulate_session(name: str) -> dict:
    """One session's logged columns (SI inside; ``write`` puts them in inches and lbf)."""
    load_steps, shuffled, seed = SESSIONS[name]
    rng = np.random.default_rng(seed)
    v, N_step = _programme(load_steps, shuffled)
    n = len(v)
    t = np.arange(n) * DT
    k = int(0.4 / DT)  # the load moves in 0.4 s ramps between its steps
    pad = np.concatenate([np.full(k, N_step[0]), N_step, np.full(k, N_step[-1])])
    N_lbf = np.convolve(pad, np.ones(k) / k, mode="same")[k:k + n]
    x = np.concatenate([[0.0], np.cumsum(v[:-1] * DT)])
    dx = np.diff(x, append=x[-1])
    Fh = np.empty(n)
    f = 0.0
    for i in range(n):
        if v[i] != 0.0:
            Sv = _S(v[i])
            s = Sv if v[i] > 0 else -Sv
            f = s + (f - s) * np.exp(-K0 * abs(dx[i]) / Sv)  # Dahl's law over the step, exactly
        Fh[i] = f
    g = (N_lbf / N0_LBF) ** ALPHA if load_steps else np.ones(n)
    F = g * (Fh + SIGMA2 * v)
    measured = F + MASS * np.gradient(v, DT) + 0.2 * t / t[-1] + rng.normal(0, 0.3, n)
    out = {"time [s]": t, "position [in]": (x + rng.normal(0, 20e-9, n)) / IN, "friction [lbf]": measured / LBF}
    if load_steps:
        out["normal_load [lbf]"] = N_lbf + rng.normal(0, 0.5, n)
    return out


def write(path: str, cols: dict) -> None:
    fmt = {"time [s]": "%.4f", "position [in]": "%.9f", "friction [lbf]": "%.5f", "normal_load [lbf]": "%.2f"}
    np.savetxt(path, np.column_stack(list(cols.values())), delimiter=",", header=",".join(cols), comments="",
               fmt=[fmt[c] for c in cols])


def simulate(out_dir: str, names=None) -> list[str]:
    paths = []
    for name in names or list(SESSIONS):
        path = os.path.join(out_dir, f"{name}.csv")
        write(path, simulate_session(name))
        paths.append(path)
    return paths


if __name__ == "__main__":
    for p in simulate(sys.argv[1], sys.argv[2:] or None):
        print(p)
