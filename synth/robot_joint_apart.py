#!/usr/bin/env python3
"""Robot joint under a cascade controller, simulated apart from leuven-friction (numpy only).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
session shaped like the ones the diagnosis issue was reported on (a robot joint, 74,000 samples
at 500 Hz, a quantised encoder, friction not logged), and kept so that trial runs again
(``tests/slow/test_diagnose_robot_joint_apart.py``): nothing from leuven-friction is imported,
and nothing here follows ``synth/``'s other generators.

    python -m synth.robot_joint_apart --effect {none,ripple,drift,load,softening} --seed S --out FILE.csv

Plant: J * dw/dt = u - F_fric, theta' = w.
Friction: a Maxwell-slip (Iwan) bank of 5 elasto-plastic elements whose slip limits follow
a stretched-exponential Stribeck curve, elastic elements with stick damping that fades as an
element nears its limit, plus linear viscous and a |v|^1.5 term.
Controller: cascade P position loop around a PI velocity loop at 1 kHz (ZOH), velocity from
a low-passed encoder difference; open-loop torque ramps first.
Integration: symplectic (semi-implicit) Euler at 10 kHz; elements updated by increments and
clipped at their (effect-modulated) limits.  Logged at 500 Hz: quantised encoder position
(2^17 counts per turn), applied torque + white + AR(1) noise.
Effects, imposed inside the loop: ripple, drift and load multiply every slip limit and the
viscous terms; softening multiplies each element's stiffness increment by a factor falling
with the count of the true position's reversals of more than 0.1 mrad.
"""
import argparse
import math

import numpy as np

# ---------------------------------------------------------------- parameters
J = 0.23                 # kg m^2
FC = 1.37                # N m, Coulomb level of the slip limits
FS = 1.93                # N m, static level
VS = 0.031               # rad/s, Stribeck velocity
DELTA = 0.83             # Stribeck shape exponent (stretched exponential)
SIG2 = 0.64              # N m s/rad, linear viscous
C15 = 0.11               # N m (s/rad)^1.5, nonlinear viscous term c*|v|^1.5
W = [0.31, 0.24, 0.19, 0.15, 0.11]          # element shares of the limit
DBREAK = [2.4e-4, 6.0e-4, 1.35e-3, 2.4e-3, 4.8e-3]  # rad, element break displacements at FS
K = [W[i] * FS / DBREAK[i] for i in range(5)]   # N m/rad
KTOT = sum(K)
ZETA = 0.2
DTOT = 2 * ZETA * math.sqrt(KTOT * J)
D = [k * DTOT / KTOT for k in K]             # stick damping per element

FSIM = 10000.0
FCTRL = 1000.0
FLOG = 500.0
T_END = 148.0
T_OL = 22.0              # open-loop torque ramp phase

ENC_STEP = 2 * math.pi / 2 ** 17

KV = J * 2 * math.pi * 15.0      # velocity loop P gain, N m s/rad
KI = KV * 2 * math.pi * 15.0 / 5  # velocity loop I gain, N m/rad
KP = 20.0                         # position loop, 1/s
VEL_LPF_HZ = 60.0
USAT = 8.0
ACC = 5.0                         # rad/s^2 reference acceleration

# effects
RIP_A, RIP_LAM, RIP_PHI = 0.1, 0.173, 0.6
DR_B, DR_TAU = 0.25, 35.0
LOAD_N0, LOAD_ALPHA = 800.0, 0.7
SOFT_H, SOFT_NC, SOFT_THR = 0.4, 12.0, 1.0e-4


def stribeck(v):
    return FC + (FS - FC) * math.exp(-((abs(v) / VS) ** DELTA))


def load_profile(t):
    """Normal load, N: 800 -> 1100 -> 600 -> 1000, with 1.5 s ramps (not monotone)."""
    knots = [(0.0, 800.0), (38.0, 800.0), (39.5, 1100.0), (72.0, 1100.0), (73.5, 600.0),
             (106.0, 600.0), (107.5, 1000.0), (T_END + 1, 1000.0)]
    ts = [k[0] for k in knots]
    ns = [k[1] for k in knots]
    return float(np.interp(t, ts, ns))


def build_reference(rng):
    """Reference velocity at controller rate for the closed-loop phase."""
    speeds = np.geomspace(0.002, 1.0, 10)
    rng.shuffle(speeds)
    dwell = 0.4
    max_travel = 1.4
    t_avail = T_END - T_OL - 1.0 - 0.5   # settle 0.5 s at start, hold 1 s at end

    def total(ts):
        tot = 0.0
        for v in speeds:
            travel = min(v * ts, max_travel)
            tot += 2 * (travel / v + v / ACC + dwell)
        return tot

    lo, hi = 0.5, 60.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if total(mid) > t_avail:
            hi = mid
        else:
            lo = mid
    t_stroke = lo
    dt = 1.0 / FCTRL
    vref = [0.0] * int(0.5 * FCTRL)
    strokes = []
    first = 1.0
    for v in speeds:
        travel = min(v * t_stroke, max_travel)
        for sgn in (first, -first):
            ta = v / ACC
            tc = travel / v - ta          # constant-speed time (trapezoid area = travel)
            n_a = max(1, int(round(ta * FCTRL)))
            n_c = max(1, int(round(tc * FCTRL)))
            prof = [sgn * v * (k + 0.5) / n_a for k in range(n_a)] + [sgn * v] * n_c + \
                   [sgn * v * (n_a - k - 0.5) / n_a for k in range(n_a)]
            strokes.append((T_OL + len(vref) * dt, sgn * v, travel))
            vref += prof
            vref += [0.0] * int(dwell * FCTRL)
        first = -first
    n_total = int(round((T_END - T_OL) * FCTRL)) + 2
    vref += [0.0] * max(0, n_total - len(vref))
    return np.array(vref[:n_total]), speeds, t_stroke, strokes


def torque_ramp(t):
    """Open-loop slow triangular torque ramps (fraction of FS), t in [0, T_OL)."""
    amps = [0.35, -0.35, 0.55, -0.55, 0.7, -0.7, 0.7, -0.7]
    seg = T_OL / len(amps)
    i = min(int(t // seg), len(amps) - 1)
    tau = (t - i * seg) / seg          # 0..1
    up, hold, down = 0.42, 0.08, 0.42  # rest of the segment at zero
    if tau < up:
        s = tau / up
    elif tau < up + hold:
        s = 1.0
    elif tau < up + hold + down:
        s = 1.0 - (tau - up - hold) / down
    else:
        s = 0.0
    return amps[i] * FS * s


def simulate(effect, seed):
    rng = np.random.default_rng(seed)
    vref_arr, speeds, t_stroke, strokes = build_reference(rng)
    dt = 1.0 / FSIM
    n_steps = int(round(T_END * FSIM))
    ctrl_every = int(FSIM / FCTRL)
    log_every = int(FSIM / FLOG)
    n_log = n_steps // log_every

    th = 0.0
    w = 0.0
    s = [0.0] * 5                    # element spring forces
    u = 0.0
    # controller state
    integ = 0.0
    v_est = 0.0
    th_meas_prev = 0.0
    th_ref = None
    a_lpf = 1.0 - math.exp(-2 * math.pi * VEL_LPF_HZ / FCTRL)
    # softening state
    n_rev = 0
    direction = 0
    extreme = 0.0
    kscale = 1.0

    log_t = np.empty(n_log)
    log_th = np.empty(n_log)
    log_u = np.empty(n_log)
    log_N = np.empty(n_log)
    log_F = np.empty(n_log)          # true friction, for checks only (not written by default)
    j = 0
    for step in range(n_steps):
        t = step * dt
        # ------------- effect multiplier on all slip levels and the viscous part
        m = 1.0
        N = LOAD_N0
        if effect == "ripple":
            m = 1.0 + RIP_A * math.sin(2 * math.pi * th / RIP_LAM + RIP_PHI)
        elif effect == "drift":
            m = 1.0 + DR_B * (1.0 - math.exp(-t / DR_TAU))
        elif effect == "load":
            N = load_profile(t)
            m = (N / LOAD_N0) ** LOAD_ALPHA
        # ------------- controller (ZOH at 1 kHz)
        if step % ctrl_every == 0:
            th_meas = round(th / ENC_STEP) * ENC_STEP
            v_raw = (th_meas - th_meas_prev) * FCTRL
            th_meas_prev = th_meas
            v_est += a_lpf * (v_raw - v_est)
            if t < T_OL:
                u = torque_ramp(t)
            else:
                k = int(round((t - T_OL) * FCTRL))
                if th_ref is None:
                    th_ref = th_meas
                    integ = 0.0
                vr = vref_arr[min(k, len(vref_arr) - 1)]
                th_ref += vr / FCTRL
                vcmd = vr + KP * (th_ref - th_meas)
                e = vcmd - v_est
                integ += KI * e / FCTRL
                integ = max(-USAT, min(USAT, integ))
                u = max(-USAT, min(USAT, KV * e + integ))
        # ------------- friction
        g = stribeck(w) * m
        F = 0.0
        for i in range(5):
            L = W[i] * g
            r = abs(s[i]) / L
            fade = 1.0 - r ** 8 if r < 1.0 else 0.0
            F += s[i] + D[i] * w * fade
        F += (SIG2 * w + C15 * math.copysign(abs(w) ** 1.5, w)) * m
        # ------------- symplectic Euler
        w += dt * (u - F) / J
        dx = w * dt
        th += dx
        # softening: count significant direction reversals of the true position
        if effect == "softening":
            if direction == 0:
                if abs(th - extreme) > SOFT_THR:
                    direction = 1 if th > extreme else -1
                    extreme = th
            elif direction * (th - extreme) > 0:
                extreme = th
            elif direction * (extreme - th) > SOFT_THR:
                n_rev += 1
                direction = -direction
                extreme = th
            kscale = 1.0 - SOFT_H * (1.0 - math.exp(-n_rev / SOFT_NC))
        # element update (limits at the new velocity)
        g2 = stribeck(w) * m
        for i in range(5):
            L = W[i] * g2
            si = s[i] + K[i] * kscale * dx
            if si > L:
                si = L
            elif si < -L:
                si = -L
            s[i] = si
        if step % log_every == 0 and j < n_log:
            log_t[j] = t
            log_th[j] = th
            log_u[j] = u
            log_N[j] = N
            log_F[j] = F
            j += 1
    # ------------- measurement
    pos = np.round(log_th / ENC_STEP) * ENC_STEP
    white = rng.normal(0.0, 0.012, n_log)
    ar = np.empty(n_log)
    rho = 0.998
    innov = rng.normal(0.0, 0.006 * math.sqrt(1 - rho ** 2), n_log)
    acc = 0.0
    for k in range(n_log):
        acc = rho * acc + innov[k]
        ar[k] = acc
    tq = log_u + white + ar
    info = dict(speeds=speeds, t_stroke=t_stroke, n_rev=n_rev, kscale=kscale,
                strokes=strokes)
    return log_t, pos, tq, log_N, log_F, log_th, info


def write_csv(path, effect, t, pos, tq, N):
    """The recording as a user gets it: time, encoder angle, applied torque (and the normal
    load where the load effect is imposed), units in the header."""
    with open(path, "w") as f:
        if effect == "load":
            f.write("time [s],position [rad],torque [N*m],normal_load [N]\n")
            for k in range(len(t)):
                f.write(f"{t[k]:.4f},{pos[k]:.9e},{tq[k]:.6f},{N[k]:.2f}\n")
        else:
            f.write("time [s],position [rad],torque [N*m]\n")
            for k in range(len(t)):
                f.write(f"{t[k]:.4f},{pos[k]:.9e},{tq[k]:.6f}\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--effect", choices=["none", "ripple", "drift", "load", "softening"],
                    default="none")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--out", required=True)
    ap.add_argument("--truth", help="also write true position/friction to this npz")
    a = ap.parse_args()
    t, pos, tq, N, F, th, info = simulate(a.effect, a.seed)
    write_csv(a.out, a.effect, t, pos, tq, N)
    if a.truth:
        np.savez(a.truth, t=t, theta=th, F=F, N=N, tq=tq)
    print(f"{a.out}: {len(t)} rows, effect={a.effect}, seed={a.seed}")
    print("speed order [rad/s]:", np.array2string(info["speeds"], precision=4))
    print(f"stroke time {info['t_stroke']:.2f} s; reversals counted {info['n_rev']}; "
          f"final stiffness scale {info['kscale']:.3f}")
    print(f"K_tot {KTOT:.0f} N m/rad, stick damping {DTOT:.2f} N m s/rad, "
          f"J {J} kg m^2, breakaway {FS} N m")


if __name__ == "__main__":
    main()
