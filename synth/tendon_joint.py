"""A tendon (cable)-driven rotary joint of a surgical instrument's test bench, simulated apart
from leuven-friction (numpy only: it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_tendon_joint.py``).

Plant: J = 2·10⁻⁵ kg·m², a PID position loop at 2 kHz on a 0.01° encoder, its output torque
saturated at ±0.2 N·m. Friction: four elasto-plastic (Maxwell-slip) elements, each with
stiffness k_i and slip limit α_i·s(v)·g(t), plus viscous σ2·v·g(t), where g is the friction
scale (the cable's pretension to the power 0.7 and/or a warm-up), and s(v) a Lorentzian
Stribeck curve (not eq. (7)'s exponential): s(v) = F_c + (F_s − F_c)/(1 + (v/v_s)²). Element
update per step (semi-implicit Euler at 10 kHz): F_i ← clip(F_i + κ·k_i·dx, ±α_i·s(v)·g).
Softening: κ(n) = 1 − 0.35·n/(n + 6), n the reversals with over 1 mrad of back-travel.

Logged as the bench logs it: time with 10 µs of jitter, the angle in degrees to 0.01°, the
motor current in mA with 5 mA of noise (the torque constant 0.05 N·m/A in a comment line; the
header may carry it as the column's unit, ``kt_header``), the pretension in N with 0.15 N of
noise. ``python synth/tendon_joint.py OUT_DIR [kind …]`` writes the trial's files.
"""

import numpy as np
import sys

J = 2.0e-5            # kg m^2
FC = 8.0e-3           # N m
FS = 11.0e-3           # N m
VS = 0.1             # rad/s
SIG2 = 2.0e-3         # N m s/rad
ALPHA = [0.1, 0.2, 0.3, 0.4]
BREAK = [0.2e-3, 0.5e-3, 1.2e-3, 3.0e-3]   # rad: element slip displacement at Fs
K = [a * FS / d for a, d in zip(ALPHA, BREAK)]  # N m / rad
KT = 0.05             # N m / A  (motor torque constant x capstan ratio, at the joint)
T0 = 20.0
ENC = np.deg2rad(0.01)
DT = 1e-4             # sim step (10 kHz)
DEC = 5               # log every 5th step -> 2 kHz
KP, KD, KI = 0.8, 0.012, 15.0
DFILT = 2 * np.pi * 300   # derivative filter (rad/s)


def s_of_v(v):
    return FC + (FS - FC) / (1.0 + (v / VS) ** 2)


def reference(rng):
    """Build the reference trajectory (rad) at sim rate. Returns array."""
    segs = []
    pos = 0.0

    def dwell(T):
        segs.append(np.full(int(round(T / DT)), pos))

    def move(v, T, acc=20.0):
        # trapezoid speed profile: ramp to v with acc, hold, ramp down
        nonlocal pos
        ta = abs(v) / acc
        t = np.arange(int(round((T + 2 * ta) / DT))) * DT
        vel = np.where(t < ta, v * t / ta, np.where(t > T + ta, v * np.clip((T + 2 * ta - t) / ta, 0, 1), v))
        x = pos + np.cumsum(vel) * DT
        segs.append(x)
        pos = x[-1]

    def sine(A, f, T):
        nonlocal pos
        t = np.arange(int(round(T / DT))) * DT
        x = pos + A * np.sin(2 * np.pi * f * t)
        segs.append(x)
        pos = x[-1]

    dwell(2.0)
    sine(np.deg2rad(30), 0.1, 10.0)
    dwell(1.0)
    sine(np.deg2rad(20), 1.0, 5.0)
    dwell(1.0)
    speeds = [0.004, 0.008, 0.015, 0.03, 0.06, 0.12, 0.25, 0.5, 1.0, 2.0]
    for v in speeds:
        T = min(4.0, max(0.6, 0.6 / v))
        move(+v, T)
        dwell(0.5)
        move(-v, T)
        dwell(0.5)
    # small reversals (presliding): triangle-ish sines of 0.5..5 mrad
    for A in [0.5e-3, 1e-3, 2e-3, 3.5e-3, 5e-3, 8e-3]:
        sine(A, 0.5, 4.0)
        dwell(0.5)
    dwell(1.5)
    return np.concatenate(segs)


def simulate(kind, seed=7):
    rng = np.random.default_rng(seed)
    xr = reference(rng)
    n = len(xr)
    t = np.arange(n) * DT
    Tend = t[-1]
    # pretension (true) and friction scale
    if kind in ("control", "warmup", "softening"):
        T = np.full(n, 20.0)
    elif kind == "load":
        # steps and ramps 10 -> 40 N over the session
        T = np.interp(t, [0, 0.15 * Tend, 0.15 * Tend + 1e-3, 0.4 * Tend, 0.6 * Tend, 0.6 * Tend + 1e-3, Tend],
                      [10, 10, 18, 26, 30, 36, 40])
    elif kind == "load_warmup":
        T = 15.0 + 20.0 * t / Tend
    g_load = (T / T0) ** 0.7
    if kind in ("warmup", "load_warmup"):
        g_warm = 1 - 0.25 * (1 - np.exp(-t / 30.0))
    else:
        g_warm = np.ones(n)
    g = g_load * g_warm
    soft = kind == "softening"

    x = 0.0; v = 0.0
    Fi = [0.0, 0.0, 0.0, 0.0]
    u = 0.0; integ = 0.0; dfilt = 0.0; prev_meas = 0.0
    nrev = 0; ext = 0.0; dirn = 0; kappa = 1.0
    X = np.empty(n); V = np.empty(n); U = np.empty(n); FF = np.empty(n); KAP = np.empty(n); NREV = np.empty(n)
    dt_c = DT * DEC
    for k in range(n):
        if k % DEC == 0:
            meas = np.round(x / ENC) * ENC
            e = xr[k] - meas
            integ += e * dt_c
            draw = (meas - prev_meas) / dt_c if k else 0.0
            prev_meas = meas
            dfilt += (draw - dfilt) * (1 - np.exp(-DFILT * dt_c))
            # derivative on measurement (reference rate via finite difference)
            vr = (xr[k] - xr[k - DEC]) / dt_c if k >= DEC else 0.0
            u = KP * e + KI * integ + KD * (vr - dfilt)
            u = max(-0.2, min(0.2, u))
        gk = g[k]
        sv = s_of_v(v) * gk
        F = Fi[0] + Fi[1] + Fi[2] + Fi[3] + SIG2 * gk * v
        a = (u - F) / J
        v += a * DT
        dx = v * DT
        x += dx
        for i in range(4):
            lim = ALPHA[i] * sv
            f = Fi[i] + kappa * K[i] * dx
            if f > lim:
                f = lim
            elif f < -lim:
                f = -lim
            Fi[i] = f
        if soft:
            if dirn >= 0:
                if x > ext:
                    ext = x; dirn = 1 if dirn == 0 and x > 1e-3 else dirn
                elif ext - x > 1e-3 and dirn == 1:
                    nrev += 1; dirn = -1; ext = x
            if dirn == -1:
                if x < ext:
                    ext = x
                elif x - ext > 1e-3:
                    nrev += 1; dirn = 1; ext = x
            kappa = 1 - 0.35 * nrev / (nrev + 6.0)
        X[k] = x; V[k] = v; U[k] = u; FF[k] = F; KAP[k] = kappa; NREV[k] = nrev
    # log at 2 kHz
    idx = np.arange(0, n, DEC)
    tl = t[idx] + rng.normal(0, 1e-5, len(idx))
    tl[0] = max(tl[0], 0.0)
    tl = np.maximum.accumulate(tl + np.arange(len(idx)) * 1e-9)
    q_deg = np.round(np.rad2deg(X[idx]) / 0.01) * 0.01
    i_mA = np.round(U[idx] / KT * 1000 + rng.normal(0, 5.0, len(idx)), 1)   # 5 mA noise
    T_log = np.round(T[idx] + rng.normal(0, 0.15, len(idx)), 2)
    out = dict(t=tl, q_deg=q_deg, i_mA=i_mA, T=T_log, x=X[idx], v=V[idx], u=U[idx], F=FF[idx],
               g=g[idx], kappa=KAP[idx], nrev=NREV[idx])
    return out


def write_csv(path, d, kt_header=True, load=True):
    """The bench's CSV: a comment line with the torque constant, then the columns; with
    ``kt_header`` the current's header carries the constant per mA as its unit
    (``motor_current [0.05 mN*m]``), as the README asks, else ``[mA]``."""
    cols = ["t [s]", "angle [deg]", f"motor_current [{KT:g} mN*m]" if kt_header else "motor_current [mA]"]
    data = [d["t"], d["q_deg"], d["i_mA"]]
    if load:
        cols.append("pretension [N]")
        data.append(d["T"])
    with open(path, "w") as f:
        f.write(f"# tendon joint bench, 2 kHz; torque constant at the joint Kt = {KT} N*m/A\n")
        f.write(",".join(cols) + "\n")
        fmts = ["%.6f", "%.2f", "%.1f", "%.2f"]
        np.savetxt(f, np.column_stack(data), fmt=fmts[:len(cols)], delimiter=",")


KINDS = ("control", "load", "warmup", "softening", "load_warmup")
SEEDS = {k: 100 + i for i, k in enumerate(KINDS)}  # the trial's seeds


if __name__ == "__main__":
    import os

    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for kind in sys.argv[2:] or KINDS:
        d = simulate(kind, seed=SEEDS[kind])
        write_csv(os.path.join(out, f"{kind}_kt.csv"), d)
        print(kind, "rows", len(d["t"]), "reversals", d["nrev"][-1], "kappa at the end", d["kappa"][-1], flush=True)
