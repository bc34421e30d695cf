#!/usr/bin/env python3
"""Capstan-driven rotary joint of a haptic device, simulated apart from leuven-friction.

Written for a trial of `fit` then `diagnose` as a new user runs them, from the README alone,
and kept so that trial runs again (``tests/slow/test_diagnose_haptic_joint.py``): nothing from
leuven-friction is imported, and nothing here follows ``synth/``'s other generators.

    python -m synth.haptic_apart OUT.tsv SEED [--soften]

Plant: J = 2·10⁻⁴ kg·m²; a 4-element generalized Maxwell-slip contact (breakaway shares
0.4/0.3/0.2/0.1 of a Gaussian Stribeck limit, F_s 0.016, F_c 0.012 N·m, v_s 0.05 rad/s; the
elements slip at 0.2, 0.6, 1.5 and 3 mrad; 0.02 N·m·s/rad micro-damping while stuck) plus
2·10⁻⁴ N·m·s/rad viscous. PD position control at 1 kHz (velocity from a 60 Hz filtered encoder
difference) on a reference of small triangles (±2/4/8 mrad) and nine speeds of 0.005–2 rad/s
both ways. Physics at 20 kHz (semi-implicit Euler), logged at 1 kHz: a 4096-count encoder
(1.53 mrad, coarser than most of the presliding) and the motor current in A (k_t 0.025 N·m/A,
2 mA of noise): the file's `current_A` needs its torque constant (`--units "force=0.025 N*m"`).
``--soften``: every element's stiffness × (1 − 0.35·(1 − e^(−N/25))), N the reversals of the
true motion over 2 mrad of travel.
"""

import sys
import numpy as np
from numba import njit

# ---------------- truth ----------------
J = 2.0e-4            # kg m^2
FS = 0.016            # N m, static (breakaway) level, sum of element breakaways at v=0
FC = 0.012            # N m, Coulomb level
VS = 0.05             # rad/s, Stribeck velocity
DELTA = 2.0           # Stribeck exponent
SIGMA2 = 2.0e-4       # N m s/rad, viscous
ALPHA = np.array([0.4, 0.3, 0.2, 0.1])            # breakaway fractions (sum 1)
ZMAX = np.array([0.2e-3, 0.6e-3, 1.5e-3, 3.0e-3])  # rad, element slip displacement at v=0
K0 = ALPHA * FS / ZMAX                             # N m/rad element stiffnesses
SIGMA1 = 0.02        # N m s/rad, micro-damping (split over sticking elements by k_i/K)
KT = 0.025           # N m/A
CPR = 4096           # counts/rev after 4x
Q = 2 * np.pi / CPR  # rad per count
I_NOISE = 2e-3       # A rms
# controller
KP = 8.0             # N m/rad
KD = 0.03            # N m s/rad
F_VEL = 60.0         # Hz, first-order filter of the differentiated encoder
# softening
SOFT_DEPTH = 0.35
SOFT_N = 25.0
REV_TRAVEL = 2e-3    # rad travel needed for a reversal to count
REV_DEBOUNCE = 0.5e-3  # backtrack that confirms a turn (PD jitter on the 1.5 mrad encoder is smaller)

DT_PHYS = 1.0 / 20000
DT_CTRL = 1.0 / 1000
SUB = 20


def reference(a_max=20.0):
    """Velocity-hold segments -> rate-limited velocity -> integrated position, at 1 kHz."""
    segs = [(1.0, 0.0)]

    def tri(amp, period, cycles):
        v = 4 * amp / period
        out = [(period / 4, v)]
        for _ in range(cycles - 1):
            out += [(period / 2, -v), (period / 2, v)]
        out += [(period / 2, -v), (period / 4, v), (0.3, 0.0)]
        return out

    def block():
        return tri(2e-3, 1.0, 3) + tri(4e-3, 1.2, 3) + tri(8e-3, 1.6, 3)

    segs += block()
    for v in [0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0]:
        T = min(3.0, 1.0 / v)
        segs += [(T, v), (0.3, 0.0), (T, -v), (0.3, 0.0)]
        segs += tri(3e-3, 0.8, 2)
    segs += block()
    segs += [(0.5, 0.0)]
    n = int(round(sum(d for d, _ in segs) / DT_CTRL))
    vt = np.empty(n)
    i = 0
    for d, v in segs:
        m = int(round(d / DT_CTRL))
        vt[i:i + m] = v
        i += m
    vt[i:] = 0.0
    vr = np.empty(n)
    cur = 0.0
    for k in range(n):
        dv = np.clip(vt[k] - cur, -a_max * DT_CTRL, a_max * DT_CTRL)
        cur += dv
        vr[k] = cur
    qr = np.concatenate([[0.0], np.cumsum(0.5 * (vr[1:] + vr[:-1]) * DT_CTRL)])
    return qr, vr


@njit(cache=True)
def run(qr, vr, noise, soften, kp=8.0, kd=0.03, fvel=60.0, deb=0.5e-3, qres=2 * np.pi / 4096):
    n = qr.shape[0]
    t_log = np.empty(n)
    q_log = np.empty(n)
    i_log = np.empty(n)
    q_true = np.empty(n)
    ffric = np.empty(n)
    nrev_log = np.empty(n)
    K0 = np.array([0.4, 0.3, 0.2, 0.1]) * 0.016 / np.array([0.2e-3, 0.6e-3, 1.5e-3, 3.0e-3])
    alpha = np.array([0.4, 0.3, 0.2, 0.1])
    Ktot0 = K0.sum()
    z = np.zeros(4)
    q = 0.0
    v = 0.0
    vhat = 0.0
    qm_prev = 0.0
    a_f = np.exp(-2 * np.pi * fvel * 1e-3)
    # reversal counter state
    nrev = 0
    d = 0          # current direction of travel, 0 = unknown
    q_ext = 0.0    # extreme in current direction
    q_last = 0.0   # position of last counted reversal
    F = 0.0
    for k in range(n):
        # sensors at t_k
        qm = np.floor(q / qres + 0.5) * qres
        if k == 0:
            qm_prev = qm
        vraw = (qm - qm_prev) / 1e-3
        vhat = a_f * vhat + (1 - a_f) * vraw
        qm_prev = qm
        tau = kp * (qr[k] - qm) + kd * (vr[k] - vhat)
        t_log[k] = k * 1e-3
        q_log[k] = qm
        i_log[k] = tau / 0.025 + noise[k]
        q_true[k] = q
        ffric[k] = F
        nrev_log[k] = nrev
        # physics over the control period
        for s in range(20):
            fac = 1.0
            if soften:
                fac = 1.0 - 0.35 * (1.0 - np.exp(-nrev / 25.0))
            av = abs(v)
            sv = 0.012 + (0.016 - 0.012) * np.exp(-(av / 0.05) ** 2)
            F = 2e-4 * v
            for e in range(4):
                ke = K0[e] * fac
                lim = alpha[e] * sv
                fe = ke * z[e]
                stick = abs(fe) < lim
                if stick:
                    fe += 0.02 * (K0[e] / Ktot0) * v
                if fe > lim:
                    fe = lim
                elif fe < -lim:
                    fe = -lim
                F += fe
            v += 5e-5 * (tau - F) / J_
            dq = 5e-5 * v
            q += dq
            # elements: elastic, clamped at breakaway (slip)
            av = abs(v)
            sv = 0.012 + (0.016 - 0.012) * np.exp(-(av / 0.05) ** 2)
            for e in range(4):
                ke = K0[e] * fac
                zl = alpha[e] * sv / ke
                z[e] += dq
                if z[e] > zl:
                    z[e] = zl
                elif z[e] < -zl:
                    z[e] = -zl
            # reversal counting on the true motion
            if d >= 0 and q > q_ext:
                q_ext = q
                if d == 0 and q - q_last > 0.2e-3:
                    d = 1
            elif d <= 0 and q < q_ext:
                q_ext = q
                if d == 0 and q_last - q > 0.2e-3:
                    d = -1
            if d == 1 and q < q_ext - deb:
                if abs(q_ext - q_last) > 2e-3:
                    nrev += 1
                    q_last = q_ext
                d = -1
                q_ext = q
            elif d == -1 and q > q_ext + deb:
                if abs(q_ext - q_last) > 2e-3:
                    nrev += 1
                    q_last = q_ext
                d = 1
                q_ext = q
    return t_log, q_log, i_log, q_true, ffric, nrev_log


J_ = J


def recording(seed: int, soften: bool = False) -> tuple[str, dict]:
    """The TSV text of one session and its truth (inertia, K0 sum, reversals counted)."""
    qr, vr = reference()
    noise = np.random.default_rng(seed).normal(0.0, I_NOISE, qr.shape[0])
    t, qm, i, qt, ff, nrev = run(qr, vr, noise, soften)
    text = "t_s\tangle_rad\tcurrent_A\n" + "".join(f"{a:.3f}\t{b:.9f}\t{c:.6f}\n" for a, b, c in zip(t, qm, i))
    return text, {"inertia": J, "K0": float(K0.sum()), "reversals": int(nrev[-1]), "Fc": FC, "Fs": FS}


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out = sys.argv[1]
    seed = int(sys.argv[2])
    soften = "--soften" in sys.argv
    qr, vr = reference()
    rng = np.random.default_rng(seed)
    noise = rng.normal(0.0, I_NOISE, qr.shape[0])
    t, qm, i, qt, ff, nrev = run(qr, vr, noise, soften)
    with open(out, "w") as f:
        f.write("t_s\tangle_rad\tcurrent_A\n")
        for a, b, c in zip(t, qm, i):
            f.write(f"{a:.3f}\t{b:.9f}\t{c:.6f}\n")
    np.savez(out + ".truth.npz", t=t, q_true=qt, q_ref=qr, v_ref=vr, friction=ff, nrev=nrev,
             K0=K0, alpha=ALPHA, zmax=ZMAX)
    print(f"{out}: {len(t)} rows, {t[-1]:.1f} s, reversals counted {int(nrev[-1])}, "
          f"track err rms {np.sqrt(np.mean((qt-qr)**2))*1e3:.2f} mrad, "
          f"final stiffness factor {1-0.35*(1-np.exp(-nrev[-1]/25)) if soften else 1.0:.3f}")
    print(f"truth: K0={K0.round(3)} sum={K0.sum():.2f} N m/rad")


if __name__ == "__main__":
    main()
