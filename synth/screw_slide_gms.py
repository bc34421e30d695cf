"""A machine-tool slide on a ball screw, simulated apart from leuven-friction (numpy, and numba
for the loop; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_screw_slide.py``).

Plant, at the motor: J = 2·10⁻³ kg·m², a PID position loop with velocity feedforward at 4 kHz
on a 40,000-count encoder (0.009°). Friction: a generalized Maxwell-slip model of six elements,
each clipped at α_i·s(v)·g, s(v) an exponential Stribeck curve with exponent 1.3 (0.50/0.53 N·m
static, 0.35/0.37 N·m Coulomb, v_s 1.5 rad/s), plus σ2·v; integrated by semi-implicit Euler at
40 kHz and logged at 4 kHz. The friction scale g is a warm-up, 1 − b(1 − e^(−t/τ)), a load
(L/L0)^0.6, or a ripple 1 + a·sin(θ + φ) along the screw; an additive cogging torque
A·sin(hθ + φ) is no friction at all. The motor torque is logged with 0.004 N·m of noise and a
0.006 N·m offset. ``python synth/screw_slide_gms.py OUT_DIR [kind …]`` writes the trial's files.
"""

import math
import sys

import numpy as np
from numba import njit

FS_SIM, FS_LOG = 40000, 4000
DEC = FS_SIM // FS_LOG
J = 2.0e-3                       # kg m^2 at the motor
STEP_DEG = 360.0 / 40000         # encoder step
POS = (0.35, 0.50, 1.5, 1.3, 0.0020)   # Fc, Fs, vs, delta, sigma2 (N*m, rad/s)
NEG = (0.37, 0.53, 1.5, 1.3, 0.0020)
ALPHA = np.array([0.25, 0.2, 0.18, 0.15, 0.12, 0.10])
DBREAK = np.array([0.25, 0.5, 0.9, 1.5, 2.4, 4.0]) * 1e-3   # rad at break (with Fs)
K = ALPHA * 0.5 / DBREAK         # element stiffnesses N*m/rad
NOISE, OFFSET = 0.004, 0.006     # torque sensor noise (N*m rms) and offset
L0 = 1500.0
KINDS = ("control", "ripple", "warmup", "load", "pair", "cogging", "cogging1", "loadramp")
SEEDS = dict(control=11, ripple=12, warmup=13, load=14, pair=15, cogging=17, cogging1=18, loadramp=19)
RIPPLE = dict(a=0.12, phi=0.7)             # once per motor turn
WARMUP = dict(b=0.25, tau=30.0)
COGGING = dict(amp=0.04, phi=0.3)          # harmonic 2 (cogging) or 1 (cogging1)


def stribeck(v):
    """The simulator's S(v) + σ2·v (N·m), for either sign of v."""
    v = np.asarray(v, float)
    fc, fs, vs, d, s2 = (np.where(v >= 0, a, b) for a, b in zip(POS, NEG))
    return np.sign(v) * (fc + (fs - fc) * np.exp(-(np.abs(v) / vs) ** d)) + s2 * v


def reference(rng, repeats=2):
    """Reference position and velocity at FS_LOG: small triangles for presliding, moves at 0.2
    to 100 rad/s both ways in a shuffled order, two sines."""
    x, pos, dtl = [], 0.0, 1.0 / FS_LOG

    def hold(T):
        x.extend([pos] * int(T * FS_LOG))

    hold(0.5)
    for amp in (0.5e-3, 1e-3, 2e-3, 4e-3, 8e-3, 2e-3, 1e-3):
        n = FS_LOG
        ph = np.arange(n) / n
        tri = amp * np.where(ph < 0.25, 4 * ph, np.where(ph < 0.75, 2 - 4 * ph, 4 * ph - 4))
        for _ in range(2):
            x.extend(list(pos + tri))
        hold(0.2)
    moves = [s * d for s in (0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0) for d in (1, -1)] * repeats
    rng.shuffle(moves)
    for v in moves:
        T = min(max(15.0 / abs(v), 1.0), 2.4)
        n_acc = max(int(abs(v) / 800.0 * FS_LOG), 1)
        vel = np.concatenate([np.linspace(0, v, n_acc), np.full(int(T * FS_LOG), v), np.linspace(v, 0, n_acc)])
        seg = pos + np.cumsum(vel) * dtl
        x.extend(list(seg))
        pos = seg[-1]
        hold(0.3)
    for A, f, T in ((3.0, 0.5, 8.0), (0.05, 2.0, 4.0)):
        tt = np.arange(int(T * FS_LOG)) / FS_LOG
        x.extend(list(pos + A * np.sin(2 * math.pi * f * tt)))
        hold(0.3)
    x = np.array(x)
    return x, np.gradient(x, dtl)


@njit(cache=True)
def _run(xr, vr, scale, ripple_a, ripple_phi, cog_amp, cog_h, cog_phi, k, al, pos, neg):
    """The loop: the controller at FS_LOG on the quantised angle, the plant DEC steps each."""
    n = len(xr)
    dt = 1.0 / FS_SIM
    wc = 150.0
    kp, kd, ki = J * wc ** 2, 2 * 0.8 * J * wc, J * wc ** 3 / 8
    th = om = integ = vf = th_prev_q = 0.0
    z = np.zeros(len(k))
    lp = math.exp(-2 * math.pi * 400 / FS_LOG)
    log_th = np.empty(n)
    log_u = np.empty(n)
    for i in range(n):
        q = round(math.degrees(th) / STEP_DEG) * STEP_DEG
        qr = math.radians(q)
        vf = lp * vf + (1 - lp) * (qr - th_prev_q) * FS_LOG
        th_prev_q = qr
        e = xr[i] - qr
        integ += e / FS_LOG
        u = kp * e + kd * (vr[i] - vf) + ki * integ + (0.35 * math.copysign(1.0, vr[i]) if abs(vr[i]) > 0.05 else 0.0)
        log_th[i] = q
        for _ in range(DEC):
            p = pos if om >= 0 else neg
            gg = scale[i] * (1.0 + ripple_a * math.sin(th + ripple_phi))
            s = (p[0] + (p[1] - p[0]) * math.exp(-(abs(om) / p[2]) ** p[3])) * gg
            F = p[4] * om
            for j in range(len(k)):
                F += k[j] * z[j]
            F += cog_amp * math.sin(cog_h * th + cog_phi)
            om += (u - F) / J * dt
            dth = om * dt
            th += dth
            for j in range(len(k)):
                zj = z[j] + dth
                lim = al[j] * s / k[j]
                z[j] = min(max(zj, -lim), lim)
        log_u[i] = u
    return log_th, log_u


def simulate(kind, seed=None, repeats=2):
    """One session: a dict of the logged columns (time_s, motor_angle[deg], motor_torque[N*m],
    and axial_load[N] for the load sessions) and ``truth``."""
    if kind not in KINDS:
        raise ValueError(f"kind: one of {', '.join(KINDS)}")
    rng = np.random.default_rng(SEEDS[kind] if seed is None else seed)
    xr, vr = reference(rng, repeats)
    n = len(xr)
    t = np.arange(n) / FS_LOG
    scale = np.ones(n)
    truth = {"effects": []}
    if kind in ("warmup", "pair"):
        scale *= 1 - WARMUP["b"] * (1 - np.exp(-t / WARMUP["tau"]))
        truth["effects"].append(("warm-up", WARMUP))
    steps = np.array([1500, 3000, 800, 2200, 500, 2600, 1200])
    load = steps[np.minimum((t / (t[-1] / len(steps))).astype(int), len(steps) - 1)].astype(float)
    if kind == "loadramp":
        load = 800.0 + 2000.0 * t / t[-1]
    load = load + 15 * rng.standard_normal(n)   # the load cell's noise
    if kind in ("load", "loadramp"):
        scale *= (np.maximum(load, 50.0) / L0) ** 0.6
        truth["effects"].append(("load", {"L0": L0, "exponent": 0.6}))
    ra = RIPPLE["a"] if kind in ("ripple", "pair") else 0.0
    ca = COGGING["amp"] if kind in ("cogging", "cogging1") else 0.0
    ch = 2.0 if kind == "cogging" else 1.0
    th, u = _run(xr, vr, scale, ra, RIPPLE["phi"], ca, ch, COGGING["phi"], K, ALPHA, np.array(POS), np.array(NEG))
    out = {"time_s": t, "motor_angle[deg]": th, "motor_torque[N*m]": u + OFFSET + NOISE * rng.standard_normal(n)}
    if kind in ("load", "loadramp"):
        out["axial_load[N]"] = load
    out["truth"] = truth
    return out


def write_csv(path, d):
    cols = [c for c in d if c != "truth"]
    fmt = {"time_s": "%.5f", "motor_angle[deg]": "%.3f", "motor_torque[N*m]": "%.5f", "axial_load[N]": "%.1f"}
    np.savetxt(path, np.column_stack([d[c] for c in cols]), delimiter=",", header=",".join(cols), comments="",
               fmt=[fmt[c] for c in cols])


if __name__ == "__main__":
    import os

    for kind in sys.argv[2:] or KINDS:
        write_csv(os.path.join(sys.argv[1], f"{kind}.csv"), simulate(kind))
