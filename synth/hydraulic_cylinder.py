"""A hydraulic linear axis (servo cylinder) with seal friction, simulated apart from the project.

Written without the project's code or generators (numpy only), for a trial of `fit` then
`diagnose` on recordings made apart from them (README, Diagnosis, "On recordings made apart
from this project"); kept so that trial can be run again and the slow tests can hold it
(``tests/slow/test_diagnose_cylinder.py``).

    python -m synth.hydraulic_cylinder OUTDIR [CASE ...]   # control drift ripple load control5

Plant
  m x'' = F_act - F_fric
  F_act' = (F_cmd - F_act) / tau_a        pressure build-up of the servo valve (first-order lag)
  F_cmd: digital PID position loop at the integration rate with acceleration feed-forward,
         or, during the presliding blocks, an open-loop force sine (force-controlled mode).

Friction (seals): a bank of M regularised elasto-plastic elements ("Dahl elements of exponent 2")
  dF_i/dt = k_i v (1 - sgn(v) * r_i |r_i|),   r_i = F_i / (phi_i S_sgn(F_i)(|v|))
  F_fric = mult(t, x, N) * ( sum F_i + sigma1/K * sum dF_i/dt + sigma2 v )
  with a Lorentzian Stribeck limit S_pm(|v|) = Fc_pm + (Fs_pm - Fc_pm) / (1 + (|v|/vs)^2)
  (asymmetric: rod side vs cap side), so steady sliding gives mult * (S(v) + sigma2 v).

Effects (multiplier on the whole friction):
  control : 1
  drift   : 1 + b (1 - exp(-t/tau))
  ripple  : 1 + a sin(2 pi x / lam)
  load    : (N/N0)^alpha, N(t) non-monotone, logged
  control5: every force-like parameter x5, vs x5, mass, stiffness, damping and gains x5

Integration: classical RK4 at 20 kHz (state x, v, F_act, F_1..F_M), controller as a ZOH at the
same rate; logged at 1 kHz (every 20th step).

Logged file (units a hydraulic-press user might log): time in ms, position in mm quantised to a
1 um glass scale, cylinder force in kN (from pressures; 4 N white noise, 12 N offset, 0.1 N
written resolution), chamber pressures in bar (extra columns), the commanded speed (a reference
column), and for the load case the side load in kN.
Sign convention: + position = extension; + force pushes to extend (the applied force, "action").
"""
import json
import math
import sys

import numpy as np

DT = 5e-5           # 20 kHz
LOG_EVERY = 20      # -> 1 kHz

BASE = dict(
    mass=250.0,                     # kg
    Fs_p=2400.0, Fs_n=2700.0,       # N (magnitudes)
    Fc_p=1600.0, Fc_n=1800.0,       # N
    vs=0.004,                       # m/s
    sigma2=12000.0,                 # N s/m
    phi=[0.30, 0.25, 0.20, 0.15, 0.10],
    delta=[10e-6, 18e-6, 30e-6, 50e-6, 80e-6],   # break displacement of each element at Fs_p
    zeta1=0.3,                      # micro-damping as a damping ratio of the stuck plant
    tau_a=0.001,                    # s
    kd_per_kg=800.0,                # velocity gain (N s/m per kg): damps the Stribeck dip
    f_bw=15.0,                      # Hz, position-loop corner Kp/Kd
    force_noise=4.0, force_offset=12.0,   # N
    enc=1e-6,                       # m
)

SPEEDS = [0.5e-3, 1e-3, 2e-3, 4e-3, 8e-3, 16e-3, 32e-3, 64e-3, 120e-3]  # m/s


def scaled(p, s):
    q = dict(p)
    for k in ("mass", "Fs_p", "Fs_n", "Fc_p", "Fc_n", "vs", "sigma2"):
        q[k] = p[k] * s
    return q


# ----------------------------------------------------------------------------- reference
def plan(seed=0, acc=1.5, run_time=1.6, dwell=0.3, stroke_half=0.08):
    """Segments -> per-step arrays (mode, x_ref, v_ref, a_ref, force amplitude envelope)."""
    rng = np.random.default_rng(seed)
    segs = []
    x = -stroke_half
    segs.append(("hold", 1.0, x))

    def sweep(order, first_sign, x0):
        out = []
        for v in order:
            d = min(v * run_time, 2 * stroke_half)
            out.append(("move", first_sign * d, v, x0))
            out.append(("hold", dwell, x0 + first_sign * d))
            out.append(("move", -first_sign * d, v, x0 + first_sign * d))
            out.append(("hold", dwell, x0))
        return out

    segs += sweep(SPEEDS, +1, -stroke_half)
    segs.append(("hold", 0.5, -stroke_half))
    # move to the middle for the presliding block
    segs.append(("move", stroke_half, 0.02, -stroke_half))
    segs.append(("hold", 0.5, 0.0))
    segs.append(("force", [0.55, 0.45, 0.35, 0.25, 0.15], 0.5, 0.0))
    segs.append(("hold", 1.0, 0.0))
    segs.append(("move", stroke_half, 0.02, 0.0))
    segs.append(("hold", 0.5, stroke_half))
    order = list(SPEEDS)
    rng.shuffle(order)
    segs += sweep(order, -1, stroke_half)
    segs.append(("hold", 0.5, stroke_half))
    segs.append(("move", -stroke_half, 0.02, stroke_half))
    segs.append(("hold", 0.5, 0.0))
    segs.append(("force", [0.5, 0.2, 0.4, 0.3, 0.1], 0.4, 0.0))
    segs.append(("hold", 1.0, 0.0))

    mode, xr, vr, ar, fa = [], [], [], [], []
    for s in segs:
        if s[0] == "hold":
            n = int(round(s[1] / DT))
            mode += [0] * n; xr += [s[2]] * n; vr += [0.0] * n; ar += [0.0] * n; fa += [0.0] * n
        elif s[0] == "move":
            d, v, x0 = s[1], s[2], s[3]
            sg = 1.0 if d > 0 else -1.0
            L = abs(d)
            ta = v / acc
            if L < v * ta:            # triangular
                ta = math.sqrt(L / acc); v = acc * ta; tc = 0.0
            else:
                tc = (L - v * ta) / v
            T = 2 * ta + tc
            n = int(math.ceil(T / DT))
            t = np.arange(n) * DT
            pos = np.where(t < ta, 0.5 * acc * t ** 2,
                  np.where(t < ta + tc, 0.5 * acc * ta ** 2 + v * (t - ta),
                           L - 0.5 * acc * np.clip(T - t, 0, None) ** 2))
            vel = np.where(t < ta, acc * t, np.where(t < ta + tc, v, acc * np.clip(T - t, 0, None)))
            a = np.where(t < ta, acc, np.where(t < ta + tc, 0.0, -acc))
            mode += [0] * n; xr += list(x0 + sg * pos); vr += list(sg * vel); ar += list(sg * a)
            fa += [0.0] * n
        elif s[0] == "force":
            amps, f, x0 = s[1], s[2], s[3]
            for A in amps:
                n = int(round(1.0 / f / DT))
                t = np.arange(n) * DT
                mode += [1] * n; xr += [x0] * n; vr += [0.0] * n; ar += [0.0] * n
                fa += list(A * np.sin(2 * math.pi * f * t))
    return (np.array(mode, np.int8), np.array(xr), np.array(vr), np.array(ar), np.array(fa))


# ----------------------------------------------------------------------------- simulation
def simulate(p, effect="control", eff=None, seed=1):
    eff = eff or {}
    mode, xr, vr, ar, famp = plan(seed=seed)
    N = len(mode)
    m = p["mass"]
    Fs_p, Fs_n, Fc_p, Fc_n, vs, s2 = p["Fs_p"], p["Fs_n"], p["Fc_p"], p["Fc_n"], p["vs"], p["sigma2"]
    phi = p["phi"]
    k = [ph * Fs_p / d for ph, d in zip(phi, p["delta"])]
    K = sum(k)
    M = len(k)
    s1K = 2 * p["zeta1"] * math.sqrt(K * m) / K
    tau_a = p["tau_a"]
    w = 2 * math.pi * p["f_bw"]
    Kd = p["kd_per_kg"] * m
    Kp = Kd * w
    Ki = Kp * w / 4
    Fmin = min(Fs_p, Fs_n)
    famp = famp * Fmin
    fa_l = famp.tolist(); xr_l = xr.tolist(); vr_l = vr.tolist(); ar_l = ar.tolist(); mode_l = mode.tolist()
    phi_l = list(phi)

    # effect multiplier
    b = eff.get("b", 0.0); tau = eff.get("tau", 1.0)
    a_r = eff.get("a", 0.0); lam = eff.get("lam", 1.0); ph_r = eff.get("phase", 0.0)
    alpha = eff.get("alpha", 0.0); N0 = eff.get("N0", 1.0)

    def load_of(t):
        return N0 * (1 + 0.35 * math.sin(2 * math.pi * t / 47.0 + 0.5) + 0.15 * math.sin(2 * math.pi * t / 17.0 + 2.0))

    def deriv(x, v, Fa, Fi, Fcmd, mt):
        av = abs(v)
        q = (av / vs) ** 2
        Sp = Fc_p + (Fs_p - Fc_p) / (1 + q)
        Sn = Fc_n + (Fs_n - Fc_n) / (1 + q)
        sv = 1.0 if v > 0 else (-1.0 if v < 0 else 0.0)
        dF = [0.0] * M
        sF = 0.0; sdF = 0.0
        for i in range(M):
            f = Fi[i]
            W = phi_l[i] * (Sp if f >= 0 else Sn)
            r = f / W
            d = k[i] * v * (1.0 - sv * r * abs(r))
            dF[i] = d
            sF += f; sdF += d
        mult = mt
        if a_r:
            mult *= 1 + a_r * math.sin(2 * math.pi * x / lam + ph_r)
        Ff = mult * (sF + s1K * sdF + s2 * v)
        return v, (Fa - Ff) / m, (Fcmd - Fa) / tau_a, dF, Ff

    x = xr_l[0]; v = 0.0; Fa = 0.0; Fi = [0.0] * M; I = 0.0
    prev_mode = 0
    nlog = N // LOG_EVERY
    L_t = np.empty(nlog); L_x = np.empty(nlog); L_F = np.empty(nlog); L_Ff = np.empty(nlog)
    L_N = np.empty(nlog); L_vc = np.empty(nlog); L_mult = np.empty(nlog)
    j = 0
    for n in range(N):
        t = n * DT
        md = mode_l[n]
        if md == 0:
            e = xr_l[n] - x
            ed = vr_l[n] - v
            if prev_mode == 1:
                I = (Fa - Kp * e - Kd * ed) / Ki
            I += e * DT
            Fcmd = m * ar_l[n] + Kp * e + Kd * ed + Ki * I
        else:
            Fcmd = fa_l[n]
        prev_mode = md
        mt = 1.0
        if b:
            mt *= 1 + b * (1 - math.exp(-t / tau))
        Nt = 0.0
        if alpha:
            Nt = load_of(t)
            mt *= (Nt / N0) ** alpha
        # RK4
        k1x, k1v, k1a, k1F, Ff = deriv(x, v, Fa, Fi, Fcmd, mt)
        if n % LOG_EVERY == 0 and j < nlog:
            L_t[j] = t; L_x[j] = x; L_F[j] = Fa; L_Ff[j] = Ff; L_N[j] = Nt; L_vc[j] = vr_l[n]
            L_mult[j] = mt
            j += 1
        h2 = 0.5 * DT
        k2x, k2v, k2a, k2F, _ = deriv(x + h2 * k1x, v + h2 * k1v, Fa + h2 * k1a,
                                      [Fi[i] + h2 * k1F[i] for i in range(M)], Fcmd, mt)
        k3x, k3v, k3a, k3F, _ = deriv(x + h2 * k2x, v + h2 * k2v, Fa + h2 * k2a,
                                      [Fi[i] + h2 * k2F[i] for i in range(M)], Fcmd, mt)
        k4x, k4v, k4a, k4F, _ = deriv(x + DT * k3x, v + DT * k3v, Fa + DT * k3a,
                                      [Fi[i] + DT * k3F[i] for i in range(M)], Fcmd, mt)
        h6 = DT / 6.0
        x += h6 * (k1x + 2 * k2x + 2 * k3x + k4x)
        v += h6 * (k1v + 2 * k2v + 2 * k3v + k4v)
        Fa += h6 * (k1a + 2 * k2a + 2 * k3a + k4a)
        Fi = [Fi[i] + h6 * (k1F[i] + 2 * k2F[i] + 2 * k3F[i] + k4F[i]) for i in range(M)]
    return dict(t=L_t[:j], x=L_x[:j], F=L_F[:j], Ffric=L_Ff[:j], N=L_N[:j], vcmd=L_vc[:j], mult=L_mult[:j])


def write(rec, path, p, seed=7, with_load=False):
    rng = np.random.default_rng(seed)
    n = len(rec["t"])
    x_q = np.round(rec["x"] / p["enc"]) * p["enc"]
    F_meas = rec["F"] + p["force_offset"] + p["force_noise"] * rng.standard_normal(n)
    # chamber pressures (extra columns, bar): A_cap = 50 cm^2, A_rod = 30 cm^2
    A_cap, A_rod = 50e-4, 30e-4
    pB = 40e5 + 2e5 * np.sin(2 * np.pi * rec["t"] / 9.0)
    pA = (F_meas + pB * A_rod) / A_cap
    cols = ["time [ms]", "pos [mm]", "force [kN]", "p_A [bar]", "p_B [bar]", "v_cmd [mm/s]"]
    data = [rec["t"] * 1e3, x_q * 1e3, F_meas / 1e3, pA / 1e5, pB / 1e5, rec["vcmd"] * 1e3]
    fmts = ["%.1f", "%.3f", "%.4f", "%.2f", "%.2f", "%.3f"]
    if with_load:
        Nm = rec["N"] + 0.01 * np.mean(rec["N"]) * rng.standard_normal(n)
        cols.append("normal_load [kN]"); data.append(Nm / 1e3); fmts.append("%.4f")
    arr = np.column_stack(data)
    with open(path, "w") as fh:
        fh.write(",".join(cols) + "\n")
        np.savetxt(fh, arr, fmt=fmts, delimiter=",")


CASES = {
    "control": (1.0, {}),
    "drift": (1.0, dict(b=0.25, tau=31.0)),
    "ripple": (1.0, dict(a=0.08, lam=0.006, phase=0.0)),
    "load": (1.0, dict(alpha=0.75, N0=20000.0)),
    "control5": (5.0, {}),
}


def truth(case):
    s, eff = CASES[case]
    p = scaled(BASE, s)
    return dict(case=case, scale=s, params_SI=p, effect=eff,
                note="S(v) = Fc + (Fs-Fc)/(1+(v/vs)^2) + sigma2 v, Lorentzian; vs is where the "
                     "Stribeck part is halfway; mass kg; forces N")


def record(path, case):
    """Simulate ``case`` (one of CASES) and write its recording to ``path``; returns its truth."""
    s, eff = CASES[case]
    p = scaled(BASE, s)
    write(simulate(p, case, eff), path, p, with_load=(case == "load"))
    return truth(case)


if __name__ == "__main__":
    import os
    import time

    out, only = sys.argv[1], sys.argv[2:] or list(CASES)
    os.makedirs(out, exist_ok=True)
    for case in only:
        t0 = time.time()
        tr = record(os.path.join(out, f"{case}.csv"), case)
        with open(os.path.join(out, f"{case}_truth.json"), "w") as fh:
            json.dump(tr, fh, indent=1)
        print(case, f"{time.time() - t0:.1f} s", flush=True)
