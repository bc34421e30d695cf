"""Direct-drive rotary indexing table, simulated apart from leuven-friction (numpy only).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_rotary_table.py``): nothing from leuven-friction is imported, and
nothing here follows ``synth/``'s other generators.

    python -m synth.rotary_table CASE --outdir DIR   # CASE: control_a control_b load ripple
                                                     #       drift drift_ripple load_ripple

Plant: J*dw/dt = u - F.  Contact: 4-element Maxwell-slip (elasto-plastic elements, each with
stiffness k_i and a slip level w_i*S(w), damping c_i while stuck), sliding curve
S(w) = Fc + (Fs - Fc)*exp(-(|w|/ws)^delta) per direction sign, plus viscous sigma2*w.
Effects multiply the slip levels and sigma2 (the friction), not the element stiffnesses:
    m = (N/N0)^alpha * (1 + a sin(2 pi x/lam + phi)) * (1 + b (1 - exp(-t/tau)))
Integration: semi-implicit (symplectic) Euler at 10 kHz with the elements updated exactly per
sub-step displacement; controller at 5 kHz (zero-order hold); logged at 1 kHz.
Schedule: open-loop torque ramps with reversals below break-away, then a PID position loop
tracking velocity holds at 9 speeds in shuffled order, each level both directions.
Logged: t [ms], angle [deg] through a 2^20-count encoder, motor_torque [mN*m] with white +
AR(1) noise, and optionally normal_load [N] with noise.
"""
import argparse
import math
import numpy as np

J = 0.0187                     # kg m^2
FS_P, FC_P, WS_P = 0.437, 0.318, 0.0617   # N m, N m, rad/s  (positive side)
FS_N, FC_N, WS_N = 0.452, 0.301, 0.0553   # magnitudes, negative side
DELTA = 1.33
SIGMA2 = 0.0214                # N m s/rad
K_EL = [248.0, 164.0, 96.0, 52.0]      # N m / rad
W_EL = [0.18, 0.27, 0.31, 0.24]
C_EL = [0.53, 0.35, 0.21, 0.11]        # N m s/rad while stuck
ENC = 2 * math.pi / 2 ** 20    # rad per count
DT = 1e-4
CTRL_EVERY = 2
LOG_EVERY = 10
TORQUE_WHITE = 0.0023         # N m, white part of the torque noise
TORQUE_AR_E, TORQUE_AR = 0.0009, 0.96   # N m innovation and coefficient of its AR(1) part
LEVELS = [0.0031, 0.0068, 0.0147, 0.0322, 0.0705, 0.154, 0.338, 0.741, 1.62]


def S(w):
    aw = abs(w)
    if w >= 0:
        return FC_P + (FS_P - FC_P) * math.exp(-(aw / WS_P) ** DELTA)
    return FC_N + (FS_N - FC_N) * math.exp(-(aw / WS_N) ** DELTA)


def S_pair(aw):
    up = FC_P + (FS_P - FC_P) * math.exp(-(aw / WS_P) ** DELTA)
    lo = FC_N + (FS_N - FC_N) * math.exp(-(aw / WS_N) ** DELTA)
    return up, lo


def ramp_schedule():
    """Open-loop torque turning points (N m) at a fixed rate; all below break-away."""
    pts = [0.0, 0.52, -0.11, 0.61, 0.27, 0.74, -0.33, -0.79, -0.41, -0.63, 0.08, 0.35, 0.0]
    fs = 0.5 * (FS_P + FS_N)
    pts = [p * fs if abs(p) > 0 else 0.0 for p in pts]
    rate = 0.0913   # N m / s
    t, u = [0.0], [0.0]
    for p in pts[1:]:
        t.append(t[-1] + abs(p - u[-1]) / rate)
        u.append(p)
    t.append(t[-1] + 0.8)
    u.append(0.0)
    return np.array(t), np.array(u)


def velocity_schedule(rng, t_start):
    """Piecewise velocity reference: list of (t, v) breakpoints (linear between)."""
    acc = 14.0
    order = rng.permutation(len(LEVELS))
    tt, vv = [t_start, t_start + 0.4], [0.0, 0.0]
    for i in order:
        v = LEVELS[i]
        hold = float(np.clip(2.4 / v, 1.2, 3.2))
        signs = [1, -1] if rng.random() < 0.5 else [-1, 1]
        for s in signs:
            tr = v / acc
            tt += [tt[-1] + tr, tt[-1] + tr + hold, tt[-1] + 2 * tr + hold, tt[-1] + 2 * tr + hold + 0.3]
            vv += [s * v, s * v, 0.0, 0.0]
    return np.array(tt), np.array(vv), [LEVELS[i] for i in order]


def load_profile(t, steps):
    """steps: list of (t_change, new_load, ramp_duration); first entry (0, N_start, 0)."""
    n = np.full_like(t, steps[0][1])
    for tc, nl, dur in steps[1:]:
        prev = n.copy()
        f = np.clip((t - tc) / dur, 0, 1)
        n = prev * (1 - f) + nl * f
    return n


def simulate(seed, load=None, alpha=0.0, n0=1.0, ripple=None, drift=None, out=None,
             max_rows=120000):
    rng = np.random.default_rng(seed)
    tr, ur = ramp_schedule()
    t_cl = tr[-1]
    tv, vv, order = velocity_schedule(rng, t_cl)
    # integrate the velocity reference to a position reference (relative)
    t_end = tv[-1] + 0.5
    nsub = int(round(t_end / DT))
    nlog = nsub // LOG_EVERY
    assert nlog <= max_rows, nlog
    tsub = np.arange(nsub) * DT
    vref = np.interp(tsub, tv, vv)
    xref_rel = np.concatenate([[0.0], np.cumsum(0.5 * (vref[1:] + vref[:-1]) * DT)])
    u_ol = np.interp(tsub, tr, ur)
    if load is not None:
        Nsub = load_profile(tsub, load)
    else:
        Nsub = None

    # controller (PID on position, tracking xref; velocity from an interpolated encoder)
    wn = 2 * math.pi * 22.0
    kp = J * wn * wn * 1.6
    kd = 2 * 0.8 * J * wn + 0.0
    ki = kp * wn / 6.0
    umax = 3.0
    Fi = [0.0] * 4
    x = 0.0
    w = 0.0
    u = 0.0
    integ = 0.0
    x0_cl = None
    logs = np.zeros((nlog, 5))
    li = 0
    kel, wel, cel = K_EL, W_EL, C_EL
    stuck = [True] * 4
    ctrl_noise = rng.normal(0, 2e-4, nsub // CTRL_EVERY + 2)   # rad/s on the speed feedback
    for k in range(nsub):
        t = k * DT
        # effect multiplier on friction
        m = 1.0
        if Nsub is not None:
            m *= (Nsub[k] / n0) ** alpha
        if ripple is not None:
            a, lam, ph = ripple
            m *= 1.0 + a * math.sin(2 * math.pi * x / lam + ph)
        if drift is not None:
            b, tau = drift
            m *= 1.0 + b * (1.0 - math.exp(-t / tau))
        # control
        if k % CTRL_EVERY == 0:
            if t < t_cl:
                u = u_ol[k]
            else:
                if x0_cl is None:
                    x0_cl = x
                    integ = u / ki if ki else 0.0
                e = x0_cl + xref_rel[k] - x
                integ += e * DT * CTRL_EVERY
                u = kp * e + ki * integ + kd * (vref[k] - (w + ctrl_noise[k // CTRL_EVERY]))
                u = max(-umax, min(umax, u))
        # friction at the current state
        F = m * SIGMA2 * w
        for i in range(4):
            F += Fi[i]
            if stuck[i]:
                F += cel[i] * w
        # semi-implicit Euler
        w = w + DT * (u - F) / J
        dx = w * DT
        x += dx
        up, lo = S_pair(abs(w))
        for i in range(4):
            f = Fi[i] + kel[i] * dx
            hi = wel[i] * up * m
            lw = -wel[i] * lo * m
            if f > hi:
                f = hi
                stuck[i] = False
            elif f < lw:
                f = lw
                stuck[i] = False
            else:
                stuck[i] = True
            Fi[i] = f
        if (k + 1) % LOG_EVERY == 0 and li < nlog:
            Ftot = sum(Fi) + m * SIGMA2 * w
            logs[li] = (t + DT, x, u, Nsub[k] if Nsub is not None else 0.0, Ftot)
            li += 1
    logs = logs[:li]
    # measurement
    t_ms = logs[:, 0] * 1e3
    ang_deg = np.floor(logs[:, 1] / ENC) * ENC * 180 / math.pi
    ar = np.zeros(li)
    e = rng.normal(0, TORQUE_AR_E, li)
    for i in range(1, li):
        ar[i] = TORQUE_AR * ar[i - 1] + e[i]
    torque_mNm = (logs[:, 2] + rng.normal(0, TORQUE_WHITE, li) + ar) * 1e3
    cols = [t_ms, ang_deg, torque_mNm]
    header = ["t [ms]", "angle [deg]", "motor_torque [mN*m]"]
    if Nsub is not None:
        cols.append(logs[:, 3] + rng.normal(0, 1.7, li))
        header.append("normal_load [N]")
    data = np.column_stack(cols)
    if out:
        np.savetxt(out, data, delimiter=",", header=",".join(header), comments="", fmt="%.10g")
        np.save(out.replace(".csv", "_truth.npy"), logs)
    return data, logs, order


CASES = {
    "control_a": dict(seed=11),
    "control_b": dict(seed=12),
    "load": dict(seed=22, load=[(0, 563.0, 0), (31.7, 742.0, 1.4), (49.3, 418.0, 1.7),
                               (68.2, 655.0, 1.2), (86.9, 489.0, 1.5)], alpha=0.68, n0=563.0),
    "ripple": dict(seed=31, ripple=(0.094, 7.3 * math.pi / 180, 1.13)),
    "drift": dict(seed=52, drift=(0.213, 44.3)),
    "drift_ripple": dict(seed=54, drift=(0.187, 31.6), ripple=(0.107, 5.9 * math.pi / 180, -0.62)),
    "load_ripple": dict(seed=23, load=[(0, 371.0, 0), (27.4, 508.0, 1.1), (46.1, 312.0, 1.3),
                                      (63.8, 455.0, 0.9), (79.5, 337.0, 1.6)], alpha=0.74, n0=371.0,
                        ripple=(0.083, 4.7 * math.pi / 180, 2.41)),
}

if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("case", choices=list(CASES))
    ap.add_argument("--outdir", default=".")
    a = ap.parse_args()
    d, logs, order = simulate(out=f"{a.outdir}/{a.case}.csv", **CASES[a.case])
    print(a.case, "rows", len(d), "T", d[-1, 0] / 1e3, "s; level order", order,
          "angle range deg", d[:, 1].min(), d[:, 1].max())
