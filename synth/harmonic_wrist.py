"""A robot wrist joint with a harmonic drive, simulated apart from leuven-friction (numpy only;
it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_harmonic_wrist.py``).

Plant (output side): J * dv/dt = tau_motor - F_fric, J = 0.08 kg·m².
Friction: a generalized Maxwell-slip bank (5 elasto-plastic elements whose slip limits follow
a Lorentzian steady curve, F_c + (F_s − F_c)/(1 + (v/v_s)²), the side chosen by the element's
sign) plus a viscous term, each side with its own parameters (``TRUTH``).
Integration: semi-implicit Euler at 10 kHz. Control: PID position loop with velocity and
acceleration feed-forward at 2 kHz on the quantised 17-bit output encoder. Drive: presliding
sines of 0.2–0.7 mrad, then 20 speed levels (±0.005–1.5 rad/s) in a shuffled order, then
presliding sines again. Logged at 1 kHz: time [s], output angle [deg] (quantised), the motor
current in A with 1 % of the break-away current as noise, written with the header unit
'11 N*m' (k_t 0.11 N·m/A × a gear of 100: the torque constant as the unit, as the README asks).

Sessions: ``control`` (no effect); ``ripple`` (friction × (1 + 0.12·sin(200·θ)): twice per
wave-generator turn, which turns 100 times the output, so a wavelength of 2π/200 rad at the
output); ``warm`` (the Coulomb and Stribeck levels fall by 20 % and the viscous term by 30 %,
each × (1 − e^(−t/40 s))).

``python -m synth.harmonic_wrist OUT_DIR [SESSION …]`` writes them.
"""
import math
import sys

import numpy as np

# ---------------------------------------------------------------- truth
J = 0.08                      # kg m^2 output-side
KT, GEAR = 0.11, 100.0        # N*m/A motor side, ratio
TRUTH = {
    "pos": dict(Fs=3.2, Fc=2.4, vs=0.06, sigma2=0.9),
    "neg": dict(Fs=3.0, Fc=2.15, vs=0.045, sigma2=0.8),
}
ALPHA = np.array([0.30, 0.25, 0.20, 0.15, 0.10])          # share of the limit
DBREAK = np.array([1.5e-4, 3e-4, 6e-4, 1.2e-3, 2.4e-3])  # rad, + side break-away
KEL = ALPHA * TRUTH["pos"]["Fs"] / DBREAK                  # N*m/rad per element

ENC_Q = 2 * math.pi / 2 ** 17        # rad per count
DT = 1e-4                            # 10 kHz integration
CTRL_DIV = 5                         # control at 2 kHz
LOG_DIV = 10                         # log at 1 kHz
I_BREAK = TRUTH["pos"]["Fs"] / (KT * GEAR)
I_NOISE = 0.01 * I_BREAK             # 1 % of break-away current


def stribeck(v_abs, side, scale_c=1.0):
    p = TRUTH[side]
    return scale_c * (p["Fc"] + (p["Fs"] - p["Fc"]) / (1.0 + (v_abs / p["vs"]) ** 2))


# ---------------------------------------------------------------- reference
def build_reference(seed):
    """The presliding sines (amplitude, frequency, cycles) and the speed levels, shuffled by ``seed``."""
    rng = np.random.default_rng(seed)
    # presliding block: sines of small amplitude, nested-ish
    presl = [(7e-4, 0.4, 2), (3.5e-4, 0.4, 2), (6e-4, 0.5, 1), (2e-4, 0.5, 2)]
    # sweep: 10 speeds, both directions, shuffled
    speeds = np.geomspace(0.005, 1.5, 10)
    levels = [s for s in speeds] + [-s for s in speeds]
    order = rng.permutation(len(levels))
    levels = [levels[i] for i in order]
    return presl, levels


def make_profile(seed):
    presl, levels = build_reference(seed)
    # build x_ref as piecewise function sampled at DT
    xs = []
    x0 = 0.0
    # rest
    xs.append(np.zeros(int(1.0 / DT)))
    # presliding sines (start from zero phase, position continuous and velocity continuous-ish: use 1-cos)
    for amp, f, cyc in presl:
        nn = int(round(cyc / f / DT))
        tt = np.arange(nn) * DT
        xs.append(x0 + amp * np.sin(2 * math.pi * f * tt))
    xs.append(np.full(int(0.5 / DT), x0))
    # sweep
    amax = 4.0
    x = x0
    v = 0.0
    seg_x = []
    level_times = []
    for vl in levels:
        hold = 5.0 if abs(vl) < 0.05 else 3.0
        # ramp
        dv = vl - v
        nr = max(1, int(round(abs(dv) / amax / DT)))
        acc = dv / (nr * DT)
        xr = np.empty(nr)
        for i in range(nr):
            x += v * DT + 0.5 * acc * DT * DT
            v += acc * DT
            xr[i] = x
        seg_x.append(xr)
        nh = int(round(hold / DT))
        xh = x + vl * DT * np.arange(1, nh + 1)
        x = xh[-1]
        v = vl
        seg_x.append(xh)
        level_times.append((vl, hold))
    # decelerate to rest
    nr = max(1, int(round(abs(v) / amax / DT)))
    acc = -v / (nr * DT)
    xr = np.empty(nr)
    for i in range(nr):
        x += v * DT + 0.5 * acc * DT * DT
        v += acc * DT
        xr[i] = x
    seg_x.append(xr)
    seg_x.append(np.full(int(0.5 / DT), x))
    xs.extend(seg_x)
    # final presliding block
    xe = x
    for amp, f, cyc in [(5e-4, 0.4, 2), (2.5e-4, 0.4, 2)]:
        nn = int(round(cyc / f / DT))
        tt = np.arange(nn) * DT
        xs.append(xe + amp * np.sin(2 * math.pi * f * tt))
    xs.append(np.full(int(1.0 / DT), xe))
    x_ref = np.concatenate(xs)
    v_ref = np.gradient(x_ref, DT)
    a_ref = np.gradient(v_ref, DT)
    return x_ref, v_ref, a_ref, levels


# ---------------------------------------------------------------- simulation
def simulate(session, seed=7):
    x_ref, v_ref, a_ref, levels = make_profile(seed)
    N = len(x_ref)
    rng = np.random.default_rng(seed + {"control": 0, "ripple": 1, "warm": 2}[session])

    omega = 80.0
    Kp = J * omega ** 2          # 512
    Kd = 2.4 * J * omega         # 15.4
    Ki = Kp * omega / 4.0
    dtc = DT * CTRL_DIV
    lp = 1.0 - math.exp(-2 * math.pi * 50.0 * dtc)   # velocity filter 50 Hz

    kel = KEL.tolist()
    alpha = ALPHA.tolist()
    ne = len(kel)
    z = [0.0] * ne
    th = 0.0
    v = 0.0
    tau = 0.0
    integ = 0.0
    th_q_prev = 0.0
    v_hat = 0.0
    pos_p, neg_p = TRUTH["pos"], TRUTH["neg"]

    nlog = N // LOG_DIV
    log_t = np.empty(nlog)
    log_th = np.empty(nlog)
    log_tau = np.empty(nlog)
    log_fric = np.empty(nlog)
    li = 0
    for k in range(N):
        t = k * DT
        # ---- effect factors
        if session == "warm":
            e = 1.0 - math.exp(-t / 40.0)
            wc = 1.0 - 0.20 * e
            wv = 1.0 - 0.30 * e
        else:
            wc = wv = 1.0
        # ---- controller (2 kHz) on the quantised encoder
        if k % CTRL_DIV == 0:
            th_q = round(th / ENC_Q) * ENC_Q
            v_raw = (th_q - th_q_prev) / dtc if k > 0 else 0.0
            th_q_prev = th_q
            v_hat += lp * (v_raw - v_hat)
            err = x_ref[k] - th_q
            integ += err * dtc
            tau = J * a_ref[k] + Kp * err + Ki * integ + Kd * (v_ref[k] - v_hat)
        # ---- friction
        va = abs(v)
        fs = 0.0
        for i in range(ne):
            zi = z[i]
            if zi >= 0.0:
                p = pos_p
            else:
                p = neg_p
            lim = alpha[i] * wc * (p["Fc"] + (p["Fs"] - p["Fc"]) / (1.0 + (va / p["vs"]) ** 2))
            zl = lim / kel[i]
            if zi > zl:
                zi = zl
            elif zi < -zl:
                zi = -zl
            z[i] = zi
            fs += kel[i] * zi
        s2 = pos_p["sigma2"] if v >= 0.0 else neg_p["sigma2"]
        fr = fs + wv * s2 * v
        if session == "ripple":
            fr *= 1.0 + 0.12 * math.sin(200.0 * th)
        # ---- log (instantaneous samples at 1 kHz)
        if k % LOG_DIV == 0 and li < nlog:
            log_t[li] = t
            log_th[li] = th
            log_tau[li] = tau
            log_fric[li] = fr
            li += 1
        # ---- semi-implicit Euler
        v += DT * (tau - fr) / J
        dth = v * DT
        th += dth
        for i in range(ne):
            z[i] += dth
    th_q = np.round(log_th[:li] / ENC_Q) * ENC_Q
    cur = log_tau[:li] / (KT * GEAR) + rng.normal(0.0, I_NOISE, li)
    return dict(t=log_t[:li], th_true=log_th[:li], th_q=th_q, cur=cur,
                tau=log_tau[:li], fric=log_fric[:li], levels=levels)


def write_csv(path, r):
    deg = np.degrees(r["th_q"])
    with open(path, "w") as fh:
        fh.write("time [s],angle [deg],motor_current [11 N*m]\n")
        for t, a, c in zip(r["t"], deg, r["cur"]):
            fh.write(f"{t:.4f},{a:.9f},{c:.6f}\n")


SESSIONS = ("control", "ripple", "warm")
RIPPLE_WAVELENGTH, RIPPLE_A = 2 * math.pi / 200.0, 0.12  # the ripple session's, at the output


def simulate_to(out_dir, sessions=SESSIONS):
    """Write the sessions asked (``SESSIONS``) into ``out_dir`` as CSV; their paths."""
    paths = []
    for s in sessions:
        path = f"{out_dir}/{s}.csv"
        write_csv(path, simulate(s))
        paths.append(path)
    return paths


if __name__ == "__main__":
    for path in simulate_to(sys.argv[1] if len(sys.argv) > 1 else ".", sys.argv[2:] or SESSIONS):
        print("wrote", path)
