"""A camera gimbal's pan axis, simulated apart from leuven-friction (numpy only; it imports
nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_gimbal.py``).

Plant: a direct-drive BLDC, J = 2.5e-3 kg·m² (camera and yoke), no gravity (a vertical pan axis).
Friction: a generalized Maxwell-slip bank (6 elastoplastic elements, a play operator's update,
each saturating at alpha_i·S(v)), plus viscous sigma2·v and a small micro-damping
c_d·v/(1 + (v/v_d)²); S(v) = Fc + (Fs − Fc)·exp(−|v/vs|^delta), its own parameters per sign.
Integration: semi-implicit (symplectic) Euler at 10 kHz, the elements updated exactly with dx.
Drive: (1) open-loop torque triangles below break-away (presliding), (2) a PID position loop at
5 kHz tracking trapezoidal constant-velocity strokes, 9 speeds of 0.3–80 °/s swept up then down,
(3) the torque triangles again. Logged at 500 Hz: time in ms, the angle in mrad from a 19-bit
encoder (quantised), the motor torque in mN·m (current-sensor noise 0.4 mN·m and a 0.02 mN·m ADC
step), and a velocity estimate in °/s (not friction truth).

Sessions: ``control`` (no effect); ``warmup`` (a hidden effect in a form of its own: Fs and Fc
scaled by 1 − 0.15(1 − exp(−t/50 s)), sigma2 by 1 − 0.35(1 − exp(−t/50 s))).

``python -m synth.gimbal OUT_DIR [SESSION …]`` writes them.
"""
import math
import os
import sys

import numpy as np

J = 2.5e-3
SP = dict(Fs=0.035, Fc=0.025, vs=0.02, delta=1.5, sigma2=0.010)      # positive side, SI
SN = dict(Fs=0.032, Fc=0.023, vs=0.025, delta=1.5, sigma2=0.011)      # negative side (magnitudes)
ALPHA = np.array([0.25, 0.20, 0.20, 0.15, 0.10, 0.10])
DSLIP = np.array([0.01, 0.03, 0.07, 0.15, 0.30, 0.60]) * 1e-3          # rad at which element i slips (at Fs+)
K = ALPHA * SP['Fs'] / DSLIP                                           # N m / rad
CD, VD = 0.5, 0.002
ENC = 2 * math.pi / 2 ** 19                                            # rad per count
DT = 1e-4
LOG_EVERY = 20                                                          # 500 Hz


def S(v, side, g):
    p = SP if side > 0 else SN
    return g * (p['Fc'] + (p['Fs'] - p['Fc']) * math.exp(-abs(v / p['vs']) ** p['delta']))


def triangles(t, levels):
    """Open-loop torque ramps at 15 mN*m/s from t through levels x |Fs-|, then 1 s at 0: their
    knots (t, tau) and the time they end."""
    knots = []
    prev = 0.0
    for a in levels:
        tgt = a * SN['Fs']
        t += abs(tgt - prev) / 0.015
        knots.append((t, tgt))
        prev = tgt
    t += 1.0
    knots.append((t, 0.0))
    return knots, t


def schedule():
    """list of segments: ('torque', [(t, tau) knots]) or ('track', [(t, x) knots])."""
    segs = []
    t = 2.0
    # presliding triangles, open loop, 15 mN*m/s
    ramps, t = triangles(t, [0.85, -0.85, 0.6, -0.6, 0.35, -0.35, 0.0])
    segs.append(('torque', [(0.0, 0.0), (2.0, 0.0)] + ramps))
    speeds = [0.3, 0.6, 1.2, 2.5, 5, 10, 20, 40, 80]        # deg/s
    order = speeds + speeds[::-1]
    x = 0.0
    kn = []
    t += 0.5
    kn.append((t, x))
    for vdeg in order:
        v = math.radians(vdeg)
        dur = 4.0 if vdeg < 2 else (3.0 if vdeg < 20 else 1.6)
        for sgn in (1, -1):
            # accel limited trapezoid: 300 deg/s^2
            a = math.radians(300.0)
            ta = v / a
            kn.append(('move', t, sgn * v, ta, dur))
            t += dur + 2 * ta + 0.3
    segs.append(('track', kn, t))
    return segs


SESSIONS = {"control": ("none", 1), "warmup": ("warmup", 2)}  # session: (effect, the noise's seed)
WARMUP_TAU, WARMUP_FS, WARMUP_SIGMA2 = 50.0, 0.15, 0.35  # s; the drops of Fs and Fc, and of sigma2


def write(out, effect="none", seed=1):
    """One session's CSV at ``out`` (and its true friction beside it, time in ms and N·m, as
    ``*_truthfriction.npy``)."""
    rng = np.random.default_rng(seed)
    segs = schedule()
    tq_knots = segs[0][1]
    t_track0 = tq_knots[-1][0]
    moves = segs[1][1][1:]
    T_end = segs[1][2] + 1.0
    # presliding tail at the end as well (open-loop triangles again)
    ramps, T_total = triangles(T_end, [0.85, -0.85, 0.5, -0.5, 0.0])
    tail = [(T_end, 0.0)] + ramps
    n = int(T_total / DT)

    # reference position profile for the tracking part (piecewise)
    def ref(tnow):
        x = 0.0
        vref = 0.0
        for (_, ts, vv, ta, dur) in moves:
            if tnow <= ts:
                break
            te = tnow - ts
            a = vv / ta
            if te < ta:
                x += 0.5 * a * te * te; vref = a * te; break
            x += 0.5 * vv * ta
            if te < ta + dur:
                x += vv * (te - ta); vref = vv; break
            x += vv * dur
            if te < 2 * ta + dur:
                tb = te - ta - dur
                x += vv * tb - 0.5 * a * tb * tb; vref = vv - a * tb; break
            x += 0.5 * vv * ta
        return x, vref

    Fi = np.zeros(6)
    x = 0.0
    v = 0.0
    # controller
    w = 2 * math.pi * 20
    Kp, Kd, Ki = J * w * w * 1.5, 2 * 0.7 * w * J, J * w * w * w / 8
    integ = 0.0
    vf = 0.0
    xq_prev = 0.0
    x_off = None
    tau = 0.0
    rows = []
    ctrl_every = 2       # controller at 5 kHz
    for k in range(n):
        tnow = k * DT
        if effect == 'warmup':
            e = 1 - math.exp(-tnow / WARMUP_TAU)
            g, h = 1 - WARMUP_FS * e, 1 - WARMUP_SIGMA2 * e
        else:
            g, h = 1.0, 1.0
        xq = math.floor(x / ENC + 0.5) * ENC
        if k % ctrl_every == 0:
            vraw = (xq - xq_prev) / (DT * ctrl_every)
            xq_prev = xq
            vf += (vraw - vf) * (1 - math.exp(-2 * math.pi * 150 * DT * ctrl_every))
            if tnow < t_track0 or tnow >= T_end:
                kn = tq_knots if tnow < t_track0 else tail
                ts = [a for a, _ in kn]
                fs = [b for _, b in kn]
                tau = float(np.interp(tnow, ts, fs))
                integ = 0.0
                x_off = None
            else:
                if x_off is None:
                    x_off = xq
                xr, vr = ref(tnow)
                err = xr + x_off - xq
                integ += err * DT * ctrl_every
                tau = Kp * err + Ki * integ + Kd * (vr - vf)
                tau = max(-0.25, min(0.25, tau))
        # friction: Maxwell-slip bank
        sp = S(v, 1, g)
        sn = S(v, -1, g)
        ff = float(Fi.sum()) + h * (SP['sigma2'] if v >= 0 else SN['sigma2']) * v + CD * v / (1 + (v / VD) ** 2)
        v += DT * (tau - ff) / J
        dx = DT * v
        x += dx
        Fi += K * dx
        np.clip(Fi, -ALPHA * sn, ALPHA * sp, out=Fi)
        if k % LOG_EVERY == 0:
            tau_log = tau + rng.normal(0, 4e-4)              # 0.4 mN*m current noise
            tau_log = round(tau_log / 2e-5) * 2e-5            # 0.02 mN*m ADC step
            rows.append((tnow * 1e3, xq * 1e3, tau_log * 1e3, math.degrees(vf), ff * 1e3))
    a = np.array(rows)
    with open(out, 'w') as f:
        f.write('t_ms,pan_angle [mrad],tau_motor [mN*m],omega_est [deg/s]\n')
        for r in a:
            f.write('%.1f,%.5f,%.2f,%.3f\n' % (r[0], r[1], r[2], r[3]))
    np.save(out.replace('.csv', '_truthfriction.npy'), a[:, [0, 4]])
    return out


def simulate(out_dir, sessions=tuple(SESSIONS)):
    """Write the sessions asked (``SESSIONS``) into ``out_dir``; their paths."""
    return [write(os.path.join(out_dir, f"{s}.csv"), *SESSIONS[s]) for s in sessions]


if __name__ == "__main__":
    for path in simulate(sys.argv[1], sys.argv[2:] or tuple(SESSIONS)):
        print("wrote", path)
