"""A reciprocating tribometer rig, simulated apart from the project (plain numpy).

Written from the README alone for a trial of `fit` then `diagnose` as a new user runs them;
kept so that trial can be run again. Nothing from leuven-friction is imported.

    python -m synth.reciprocating_rig OUTDIR   # a_loadsteps.csv, b_const35.csv, c_reaction_ms.csv

A stiff PID position loop drives a 1.5 kg carriage; friction = a 4-element Maxwell-slip model
under a Stribeck curve (F_s 9.1 N, F_c 7.0 N at 35 N, v_s 0.5 mm/s, δ 1.5) + 40 N·s/m viscous,
scaled by (N/35)^0.8; friction measured directly (noise 0.02 N, an offset drifting 0.12 N),
position in µm (0.01 µm steps), 2 kHz; loads 20 → 35 → 50 → 30 N in (a) and (c), 35 N in (b);
(c) is (a) with friction of the reaction sign and time in ms. Measured on this project's
version of 2026-12-02: (b) fitted F_s 9.14/−9.0, F_c 7.06/−6.94, v_s 0.507 mm/s, nothing
named; (a) normal_load named, α = 0.765 ± 0.091 (0.8)."""
import sys

import numpy as np

ALPHA = 0.8; N0 = 35.0
MU_S, MU_C = 0.26, 0.20
FS, FC = MU_S * N0, MU_C * N0          # 9.1, 7.0 N at 35 N
VS, DELTA, SIG2 = 0.5e-3, 1.5, 40.0     # m/s, -, N s/m
W = [0.35, 0.30, 0.20, 0.15]
DBR = [0.5e-6, 1.5e-6, 4e-6, 10e-6]     # element break displacements at Fs
K = [w * FS / d for w, d in zip(W, DBR)]
M = 1.5
FSIM, FLOG = 20000, 2000

def S(v):
    return FC + (FS - FC) * np.exp(-(abs(v) / VS) ** DELTA) + 0.0

def trapezoid(dist, vmax, amax, dt):
    """velocity samples of a trapezoidal move of signed distance dist."""
    d = abs(dist); s = np.sign(dist)
    ta = vmax / amax
    if amax * ta * ta > d:                      # triangular
        ta = np.sqrt(d / amax); vmax = amax * ta; tc = 0.0
    else:
        tc = (d - amax * ta * ta) / vmax
    T = 2 * ta + tc
    t = np.arange(0, T, dt)
    v = np.minimum.reduce([amax * t, np.full_like(t, vmax), amax * (T - t)])
    v = np.clip(v, 0, None)
    v *= d / (v.sum() * dt)                     # exact distance
    return s * v

def schedule(rng, dt):
    speeds = [0.3e-3, 1e-3, 2e-3, 5e-3, 10e-3]
    stroke = {0.3e-3: 0.6e-3, 1e-3: 2e-3, 2e-3: 3e-3, 5e-3: 3e-3, 10e-3: 3e-3}
    loads = [20.0, 35.0, 50.0, 30.0]
    vel, plateau = [], []
    def dwell(T):
        vel.append(np.zeros(int(round(T / dt))))
    for p, _ in enumerate(loads):
        dwell(0.5)
        # presliding: small back-and-forth strokes of a few um
        for amp in rng.permutation([1e-6, 2e-6, 4e-6, 8e-6]):
            for _ in range(2):
                vel.append(trapezoid(+2 * amp, 25e-6, 5e-3, dt)); dwell(0.05)
                vel.append(trapezoid(-2 * amp, 25e-6, 5e-3, dt)); dwell(0.05)
        dwell(0.3)
        for v in rng.permutation(speeds):
            L = stroke[v]
            vel.append(trapezoid(+L, v, 0.2, dt)); dwell(0.1)
            vel.append(trapezoid(-L, v, 0.2, dt)); dwell(0.1)
        plateau.append(sum(len(a) for a in vel))
        dwell(1.0)   # load is changed during this dwell
    vref = np.concatenate(vel)
    return vref, plateau, loads

def run(load_steps, seed=1):
    rng = np.random.default_rng(seed)
    dt = 1.0 / FSIM
    vref, plateau_end, loads = schedule(np.random.default_rng(7), dt)
    n = len(vref)
    t = np.arange(n) * dt
    xref = np.cumsum(vref) * dt
    aref = np.gradient(vref, dt)
    # true load
    if load_steps:
        Ltrue = np.full(n, loads[0])
        for i, e in enumerate(plateau_end[:-1]):
            t0 = (e + int(0.3 * FSIM)) * dt
            ramp = np.clip((t - t0) / 0.3, 0, 1)
            Ltrue = Ltrue + (loads[i + 1] - loads[i]) * ramp
    else:
        Ltrue = np.full(n, 35.0)
    wn = 2 * np.pi * 250
    Kp, Kd, Ki = M * wn**2, 20000.0, M * wn**2 * 2 * np.pi * 20
    x = v = ie = 0.0
    z = [0.0] * 4
    xs = np.empty(n); Fs_ = np.empty(n); vs_ = np.empty(n)
    for i in range(n):
        lf = (Ltrue[i] / N0) ** ALPHA
        sv = S(v) / FS * lf
        Ff = SIG2 * v
        for j in range(4):
            zj = z[j] + v * dt
            thr = W[j] * FS * sv / K[j]
            if zj > thr: zj = thr
            elif zj < -thr: zj = -thr
            z[j] = zj
            Ff += K[j] * zj
        e = xref[i] - x
        ie += e * dt
        u = Kp * e + Kd * (vref[i] - v) + Ki * ie + M * aref[i]
        v += (u - Ff) / M * dt
        x += v * dt
        xs[i] = x; Fs_[i] = Ff; vs_[i] = v
    k = FSIM // FLOG
    t, xs, Fs_, Ltrue, vs_ = t[::k], xs[::k], Fs_[::k], Ltrue[::k], vs_[::k]
    T = t[-1]
    offset = 0.12 * t / T + 0.04 * np.sin(2 * np.pi * t / 45.0)
    fmeas = Fs_ + offset + rng.normal(0, 0.02, len(t))
    xmeas = np.round((xs + rng.normal(0, 5e-9, len(t))) / 1e-8) * 1e-8
    lmeas = Ltrue + rng.normal(0, 0.15, len(t))
    return dict(t=t, x=xmeas, F=fmeas, L=lmeas, Ftrue=Fs_, Ltrue=Ltrue, v=vs_, xtrue=xs,
                xref=xref[::k])

if __name__ == "__main__":
    import time as _t
    import os

    out = sys.argv[1].rstrip("/") + "/"
    os.makedirs(out + "sim", exist_ok=True)
    for name, steps in [("a_loadsteps", True), ("b_const35", False)]:
        t0 = _t.time(); r = run(steps)
        np.savez(out + "sim/" + name + "_truth.npz", **r)
        with open(out + name + ".csv", "w") as f:
            f.write("time [s],x [um],friction [N],normal_load [N]\n")
            for a, b, c, d in zip(r["t"], r["x"] * 1e6, r["F"], r["L"]):
                f.write(f"{a:.4f},{b:.3f},{c:.4f},{d:.3f}\n")
        if steps:
            with open(out + "c_reaction_ms.csv", "w") as f:
                f.write("t [ms],x [um],friction [N],normal_load [N]\n")
                for a, b, c, d in zip(r["t"], r["x"] * 1e6, -r["F"], r["L"]):
                    f.write(f"{a*1e3:.2f},{b:.3f},{c:.4f},{d:.3f}\n")
        print(name, len(r["t"]), "rows", r["t"][-1], "s", "%.1fs" % (_t.time() - t0))
