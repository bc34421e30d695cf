"""A robot joint with effects outside the diagnosis's candidates, simulated apart from leuven-friction.

Written from the README alone, numpy only, as a new user would, for a trial of `fit` then
`diagnose` on effects the library has no candidate for; kept so that trial runs again
(``tests/slow/test_diagnose_joint_outside.py``). Nothing from leuven-friction is imported.

    python -m synth.joint_outside CASE SEED OUT.csv      # CASE in A B C D E F G

A 4-element Maxwell-slip contact (slip limits following a Stribeck curve) plus viscous friction,
integrated by semi-implicit Euler at 10 kHz, controlled and logged at 1 kHz: open-loop torque
ramps, small sine moves, then 15 speeds in shuffled order, each both ways.
A control; B an additive gravity torque mgl·sin(q + φ0); C friction × (1 + 0.2 sin(2πt/T));
D a backlash between the motor-side encoder and the load-side contact;
E friction × (1 + 0.25 (1 − e^(−t/30 s)));
F a cogging torque 0.12·sin(36q + 0.3) N·m added (a force along the travel, not friction);
G friction × (1 + 0.05 sin(36q + 0.3)) (a friction ripple, for comparison with F).
Logged: t [s], q [deg] (motor-side encoder, 2^19 counts per turn), tau [N*m] (commanded torque + noise).
"""
import sys
import math
import numpy as np

# ---- true friction (far from the paper's KUKA joint) ----
FS, FC, VS, DELTA, SIG2 = 3.4, 2.3, 0.06, 1.6, 1.7          # N*m, N*m, rad/s, -, N*m*s/rad
ALPHA = [0.35, 0.30, 0.20, 0.15]                              # share of the slip limit
KEL = [900.0, 350.0, 170.0, 80.0]                             # element stiffness N*m/rad
DEL = [2.0, 1.2, 0.8, 0.5]                                    # element damping while stuck
J = 0.045                                                     # kg m^2
JM, JL = 0.015, 0.030                                         # case D: motor / load inertia
KG, CG = 3.0e4, 6.0                                           # case D: gear mesh stiffness/damping
CNT = 2 ** 19
QSTEP = 2 * math.pi / CNT                                     # encoder step, rad
BACKLASH = 300 * QSTEP                                        # case D: total dead zone (300 counts)
MGL, PHI0 = 0.9, 0.5                                          # case B
T_CYC = 55.0                                                  # case C period (s)
COG_N, COG_PHI = 36, 0.3                                      # cases F, G: 36 periods per turn
COG_A = 0.12                                                  # case F: cogging torque amplitude, N*m
RIP_A = 0.05                                                  # case G: friction ripple, relative
DT_LOG, NSUB = 1e-3, 10


def stribeck(v):
    return FC + (FS - FC) * math.exp(-abs(v / VS) ** DELTA)


def build_schedule(rng):
    """list of segments: ('ramp', [torque knots], rate) open loop, or ('ref', array of positions)."""
    segs = []
    # 1. open-loop torque ramps 0 -> +a1 -> -a1 -> +a2 ... -> 0, at 2 N*m/s
    knots = [0.0]
    for a in (0.4, 0.55, 0.65, 0.72):
        knots += [a * FS, -a * FS]
    knots += [0.0]
    segs.append(("ramp", knots, 2.0))
    # 2. closed loop: hold, then small sinusoidal back-and-forth of 0.4, 1, 2.5 mrad at 0.5 Hz
    segs.append(("hold", 1.0))
    for amp in (0.4e-3, 1.0e-3, 2.5e-3):
        segs.append(("sine", amp, 1.0, 2))
    segs.append(("hold", 0.5))
    # 3. 15 speed levels, shuffled order, both directions, random start positions
    speeds = np.geomspace(0.005, 1.6, 15)
    order = rng.permutation(15)
    for i in order:
        v = speeds[i]
        L = min(max(v * 2.0, 0.022), 1.5)
        first = rng.choice([-1.0, 1.0])
        lo, hi = -1.5, 1.5
        if first > 0:
            x0 = rng.uniform(lo, hi - L)
        else:
            x0 = rng.uniform(lo + L, hi)
        segs.append(("move", x0))
        segs.append(("hold", 0.25))
        segs.append(("cv", first * v, L))
        segs.append(("hold", 0.25))
        segs.append(("cv", -first * v, L))
        segs.append(("hold", 0.25))
    return segs


def expand(segs):
    """-> per-tick arrays: mode (0 open loop, 1 closed), u_ol, x_ref, v_ref"""
    mode, uol, xr, vr = [], [], [], []
    x_last = 0.0
    AMAX = 6.0
    for s in segs:
        if s[0] == "ramp":
            knots, rate = s[1], s[2]
            for a, b in zip(knots[:-1], knots[1:]):
                n = int(round(abs(b - a) / rate / DT_LOG))
                for k in range(n):
                    mode.append(0); uol.append(a + (b - a) * k / n); xr.append(np.nan); vr.append(0.0)
            x_last = 0.0  # references are relative to the position at switch-over
        elif s[0] == "hold":
            n = int(round(s[1] / DT_LOG))
            for k in range(n):
                mode.append(1); uol.append(0.0); xr.append(x_last); vr.append(0.0)
        elif s[0] == "sine":
            amp, f, cyc = s[1], s[2], s[3]
            n = int(round(cyc / f / DT_LOG))
            for k in range(n):
                t = k * DT_LOG
                mode.append(1); uol.append(0.0)
                xr.append(x_last + amp * math.sin(2 * math.pi * f * t))
                vr.append(amp * 2 * math.pi * f * math.cos(2 * math.pi * f * t))
        elif s[0] == "move":
            x0 = s[1]
            d = x0 - x_last
            T = max(0.4, 1.3 * abs(d) / 1.2)
            n = int(round(T / DT_LOG))
            for k in range(1, n + 1):
                p = k / n
                mode.append(1); uol.append(0.0)
                xr.append(x_last + d * (1 - math.cos(math.pi * p)) / 2)
                vr.append(d * math.pi / (2 * T) * math.sin(math.pi * p))
            x_last = x0
        elif s[0] == "cv":
            v, L = s[1], s[2]
            ta = abs(v) / AMAX
            tc = L / abs(v) - ta
            T = 2 * ta + tc
            n = int(round(T / DT_LOG))
            sg = math.copysign(1.0, v)
            for k in range(1, n + 1):
                t = k * DT_LOG
                if t < ta:
                    vv = AMAX * t; xx = 0.5 * AMAX * t * t
                elif t < ta + tc:
                    vv = abs(v); xx = 0.5 * AMAX * ta * ta + abs(v) * (t - ta)
                else:
                    tt = min(t - ta - tc, ta)
                    vv = abs(v) - AMAX * tt
                    xx = 0.5 * AMAX * ta * ta + abs(v) * tc + abs(v) * tt - 0.5 * AMAX * tt * tt
                mode.append(1); uol.append(0.0); xr.append(x_last + sg * xx); vr.append(sg * vv)
            x_last = x_last + sg * L
    return (np.array(mode), np.array(uol), np.array(xr), np.array(vr))


def simulate(case, seed):
    rng_sched = np.random.default_rng(12345)       # same session schedule for every case
    rng = np.random.default_rng(seed)              # noise
    mode, uol, xr, vr = expand(build_schedule(rng_sched))
    N = len(mode)
    dt = DT_LOG / NSUB
    two_mass = case == "D"
    # states
    x = v = 0.0                      # load (contact) side
    xm = vm = 0.0                    # motor side (case D)
    z = [0.0] * 4
    # controller
    kv, ki, kp = 25.0, 1500.0, 40.0   # N*m*s/rad, N*m/rad, 1/s  (cascade P-PI)
    integ = 0.0
    vfilt = 0.0
    qprev = 0.0
    wlp = 2 * math.pi * 250.0
    alp = wlp * DT_LOG / (1 + wlp * DT_LOG)
    xref_off = None
    ar = 0.0
    t_out = np.arange(N) * DT_LOG
    q_out = np.empty(N)
    u_out = np.empty(N)
    for k in range(N):
        t = k * DT_LOG
        xs = xm if two_mass else x
        qm = math.floor(xs / QSTEP + 0.5) * QSTEP           # encoder reading
        vraw = (qm - qprev) / DT_LOG if k else 0.0
        qprev = qm
        vfilt += alp * (vraw - vfilt)
        if mode[k] == 0:
            u = uol[k]
            integ = u                                           # bumpless transfer
            xref_off = None
        else:
            if xref_off is None:                                # first closed-loop tick: hold here
                xref_off = qm
            xrk = xr[k]
            if np.isnan(xrk):
                xrk = 0.0
            xrk = xrk + xref_off
            vcmd = vr[k] + kp * (xrk - qm)
            e = vcmd - vfilt
            integ += ki * e * DT_LOG
            u = kv * e + integ
            u = max(-15.0, min(15.0, u))
        # friction multiplier
        if case == "C":
            g = 1 + 0.2 * math.sin(2 * math.pi * t / T_CYC)
        elif case == "E":
            g = 1 + 0.25 * (1 - math.exp(-t / 30.0))
        else:
            g = 1.0
        for _ in range(NSUB):
            gg = g * (1 + RIP_A * math.sin(COG_N * x + COG_PHI)) if case == "G" else g
            s = stribeck(v) * gg
            F = SIG2 * gg * v
            for i in range(4):
                lim = ALPHA[i] * s
                fi = KEL[i] * z[i]
                if fi > lim:
                    fi = lim; z[i] = lim / KEL[i]
                elif fi < -lim:
                    fi = -lim; z[i] = -lim / KEL[i]
                else:
                    fi += DEL[i] * v
                F += fi
            if two_mass:
                d = xm - x
                hb = 0.5 * BACKLASH
                if d > hb:
                    tg = KG * (d - hb) + CG * (vm - v)
                    tg = max(tg, 0.0)
                elif d < -hb:
                    tg = KG * (d + hb) + CG * (vm - v)
                    tg = min(tg, 0.0)
                else:
                    tg = 0.0
                vm += (u - tg - 0.01 * vm) / JM * dt
                v += (tg - F) / JL * dt
                xm += vm * dt
                x += v * dt
            else:
                grav = (MGL * math.sin(x + PHI0) if case == "B" else
                        COG_A * math.sin(COG_N * x + COG_PHI) if case == "F" else 0.0)
                v += (u - F - grav) / J * dt
                x += v * dt
            for i in range(4):
                z[i] += v * dt
        # record the commanded torque with noise (white + slow AR(1))
        ar = 0.995 * ar + rng.normal(0, 0.004)
        q_out[k] = qm
        u_out[k] = u + rng.normal(0, 0.012) + ar
    return t_out, q_out, u_out


def main():
    case, seed, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    t, q, u = simulate(case, seed)
    qd = np.degrees(q)
    with open(out, "w") as fh:
        fh.write("t [s],q [deg],tau [N*m]\n")
        for a, b, c in zip(t, qd, u):
            fh.write(f"{a:.3f},{b:.9f},{c:.5f}\n")
    print(f"{out}: {len(t)} rows, {t[-1]:.1f} s, q range {qd.min():.2f}..{qd.max():.2f} deg")


if __name__ == "__main__":
    main()
