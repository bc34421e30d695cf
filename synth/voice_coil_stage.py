"""A voice-coil micro-positioning stage on crossed-roller bearings, simulated on its own terms
(numpy and numba only: it imports nothing of the tool). The recording is force-driven.

Friction: a generalised Maxwell-slip bank (8 elements, force-state formulation) whose slip
limits follow a Gaussian Stribeck curve (F_c 40 mN, F_s 55 mN, v_s 0.5 mm/s), plus viscous
2 N·s/m and a small damping of the stuck elements. Plant: m·ẍ = F_coil − F, m = 0.35 kg.
Semi-implicit Euler at 50 kHz. The session: open-loop force ramps in presliding, then a
position/velocity loop (10 kHz) makes the stage slide at shuffled speeds of 0.05–20 mm/s; the
logged input is the coil force it applied.

Logged as a lab's interferometer log is: ``t [ms]`` at a nominal 5 kHz with 0.5 % of the rows
dropped and jitter, ``x_interf [nm]`` quantised to 0.3 nm with 1 nm of noise and ~20 nm of thermal
drift, ``F_coil [mN]`` with 0.5 mN of noise and a 1 mN offset. The interferometer is mounted
reversed: a positive force pushes the logged position down (``session(..., reversed_sensor=False)``
logs it the usual way).

Effects (``EFFECTS``): ripple, friction × (1 + 0.12·sin(2πx/0.8 mm + 0.7)) (the roller pitch);
warmup, friction × (1 − 0.2·(1 − e^(−t/40 s))); softening, every spring × (1 − 0.3·n/(n + 5)),
n the true position's reversals over 0.3 µm of back-travel; ripple_warmup, both.

usage: python -m synth.voice_coil_stage EFFECT SEED OUT.csv (EFFECT: control, ripple, warmup,
softening, ripple_warmup). Writes OUT.csv, OUT.truth.json and OUT.truth.npz.
"""
import json
import sys

import numpy as np

try:
    from numba import njit
except ImportError:  # plain Python works too, only slower
    def njit(*a, **k):
        if a and callable(a[0]):
            return a[0]
        return lambda f: f

M = 0.35            # kg
FC = 0.040          # N
FS = 0.055          # N
VS = 0.5e-3         # m/s
DELTA = 2.0         # Gaussian Stribeck
SIGMA2 = 2.0        # N s/m
D_BREAK = np.array([0.3, 0.8, 1.6, 2.8, 4.2, 6.0, 8.5, 12.0]) * 1.4e-6   # element break displacement at FS
ALPHA = np.array([0.08, 0.10, 0.12, 0.13, 0.14, 0.14, 0.14, 0.15])
ALPHA = ALPHA / ALPHA.sum()
K_EL = ALPHA * FS / D_BREAK           # N/m, total ~2.35e4
C_TOTAL = 5.0                          # N s/m, damping of stuck elements (total)
C_EL = K_EL * C_TOTAL / K_EL.sum()

DT = 2e-5           # 50 kHz
CTRL_EVERY = 5      # controller at 10 kHz
REV_THRESH = 0.3e-6  # back-travel that counts as a reversal (softening)

EFFECTS = {
    "control": dict(ripple=0.0, warm=0.0, soft=0.0),
    "ripple": dict(ripple=0.12, warm=0.0, soft=0.0),
    "warmup": dict(ripple=0.0, warm=0.2, soft=0.0),
    "softening": dict(ripple=0.0, warm=0.0, soft=0.3),
    "ripple_warmup": dict(ripple=0.12, warm=0.2, soft=0.0),
}
LAMBDA = 0.8e-3     # m, roller pitch
RIPPLE_PHASE = 0.7  # rad
TAU_WARM = 40.0     # s
SOFT_NC = 5.0       # reversals


def build_schedule(rng):
    """Returns arrays at 50 kHz: mode (0 open loop, 1 closed loop), F_open, x_ref offset, v_ref, a_ref."""
    segs = []  # list of (mode, F array or (x, v, a) arrays)
    # --- presliding: slow force ramps, reversals below breakaway (~55 mN) ---
    rate = 0.020  # N/s
    pts = [0.0, 0.015, -0.012, 0.030, 0.008, 0.028, -0.030, 0.045, 0.010, 0.040, -0.045, -0.005, -0.040, 0.0]
    F = [np.zeros(int(0.5 / DT))]
    for a, b in zip(pts[:-1], pts[1:]):
        n = max(2, int(abs(b - a) / rate / DT))
        F.append(np.linspace(a, b, n, endpoint=False))
    F.append(np.zeros(int(1.0 / DT)))
    segs.append((0, np.concatenate(F)))
    # --- sliding at several speeds, shuffled ---
    amax = 0.5  # m/s^2
    order = [2, 0.2, 10, 0.05, 5, 0.5, 20, 0.1, 1, 0.5, 5, 0.2, 2, 20]  # mm/s
    xs, vs, as_ = [], [], []
    x0 = 0.0
    direction = 1.0
    for vmm in order:
        v = vmm * 1e-3
        L = float(np.clip(v * 3.5, 0.15e-3, 5e-3))
        for sgn in (direction, -direction):
            ta = v / amax
            tc = max(L - v * ta, 0) / v
            t = np.arange(0, 2 * ta + tc, DT)
            vel = np.where(t < ta, amax * t, np.where(t < ta + tc, v, np.maximum(v - amax * (t - ta - tc), 0)))
            acc = np.where(t < ta, amax, np.where(t < ta + tc, 0.0, -amax))
            pos = x0 + sgn * np.cumsum(vel) * DT
            xs.append(pos); vs.append(sgn * vel); as_.append(sgn * acc)
            x0 = pos[-1]
            dwell = int(rng.uniform(0.3, 0.6) / DT)
            xs.append(np.full(dwell, x0)); vs.append(np.zeros(dwell)); as_.append(np.zeros(dwell))
        direction = -direction
    segs.append((1, (np.concatenate(xs), np.concatenate(vs), np.concatenate(as_))))
    n0 = len(segs[0][1]); n1 = len(segs[1][1][0])
    N = n0 + n1
    mode = np.zeros(N, np.int8); mode[n0:] = 1
    Fo = np.zeros(N); Fo[:n0] = segs[0][1]
    xr = np.zeros(N); vr = np.zeros(N); ar = np.zeros(N)
    xr[n0:], vr[n0:], ar[n0:] = segs[1][1]
    return mode, Fo, xr, vr, ar


@njit(cache=True)
def integrate(mode, Fo, xr, vr, ar, k_el, c_el, alpha, fc, fs, vs, sigma2, m, dt,
              ripple, lam, phase, warm, tau, soft, nc, rev_thresh, ctrl_every):
    N = mode.shape[0]
    ne = k_el.shape[0]
    x = 0.0; v = 0.0
    Fe = np.zeros(ne)
    X = np.empty(N); V = np.empty(N); FF = np.empty(N); FA = np.empty(N); NR = np.empty(N)
    Kp = m * (2 * np.pi * 30.0) ** 2
    Kd = 2 * 0.7 * m * 2 * np.pi * 30.0
    Ki = Kp * 2 * np.pi * 5.0
    integ = 0.0
    x_sw = 0.0
    switched = False
    Fapp = 0.0
    nrev = 0
    ext = 0.0      # extremum of current excursion
    dirn = 0       # current motion direction (+1/-1), 0 unknown
    for i in range(N):
        t = i * dt
        # ---- coil force ----
        if mode[i] == 0:
            Fapp = Fo[i]
        else:
            if not switched:
                switched = True
                x_sw = x
                integ = Fapp / Ki if Ki > 0 else 0.0
            if i % ctrl_every == 0:
                e = x_sw + xr[i] - x
                integ += e * dt * ctrl_every
                Fapp = m * ar[i] + Kp * e + Kd * (vr[i] - v) + Ki * integ
        # ---- friction ----
        av = abs(v)
        s = fc + (fs - fc) * np.exp(-(av / vs) ** 2)
        kfac = 1.0 - soft * nrev / (nrev + nc)
        ff = 0.0
        for j in range(ne):
            Fe[j] += k_el[j] * kfac * v * dt
            lim = alpha[j] * s
            if Fe[j] > lim:
                Fe[j] = lim
            elif Fe[j] < -lim:
                Fe[j] = -lim
            else:
                ff += c_el[j] * v
            ff += Fe[j]
        ff += sigma2 * v
        g = (1.0 + ripple * np.sin(2 * np.pi * x / lam + phase)) * (1.0 - warm * (1.0 - np.exp(-t / tau)))
        ff *= g
        # ---- semi-implicit Euler ----
        v += dt * (Fapp - ff) / m
        x += dt * v
        # ---- reversal count (true position, back-travel over rev_thresh) ----
        if dirn == 0:
            if x - ext > rev_thresh:
                dirn = 1; ext = x
            elif ext - x > rev_thresh:
                dirn = -1; ext = x
        elif dirn == 1:
            if x > ext:
                ext = x
            elif ext - x > rev_thresh:
                dirn = -1; ext = x; nrev += 1
        else:
            if x < ext:
                ext = x
            elif x - ext > rev_thresh:
                dirn = 1; ext = x; nrev += 1
        X[i] = x; V[i] = v; FF[i] = ff; FA[i] = Fapp; NR[i] = nrev
    return X, V, FF, FA, NR


def session(effect: str, seed: int, log_rate: float = 5000.0, reversed_sensor: bool = True):
    """(columns, truth, true): the logged columns ``{"t [ms]": …, "x_interf [nm]": …,
    "F_coil [mN]": …}``, the truth as a dict, and the true signals at the logged instants."""
    rng = np.random.default_rng(seed)
    e = EFFECTS[effect]
    mode, Fo, xr, vr, ar = build_schedule(rng)
    X, V, FF, FA, NR = integrate(mode, Fo, xr, vr, ar, K_EL, C_EL, ALPHA, FC, FS, VS, SIGMA2, M, DT,
                                 e["ripple"], LAMBDA, RIPPLE_PHASE, e["warm"], TAU_WARM, e["soft"],
                                 SOFT_NC, REV_THRESH, CTRL_EVERY)
    t50 = np.arange(len(X)) * DT
    T = t50[-1]
    # ---- logger: nominal log_rate, jitter, dropped samples ----
    step = 1.0 / log_rate
    tk = np.arange(0, T - 1e-3, step)
    tk = tk + rng.normal(0, 0.015 * step, tk.size)
    tk[0] = max(tk[0], 0.0)
    keep = np.ones(tk.size, bool)
    ndrop = int(0.005 * tk.size)
    nd = 0
    while nd < ndrop:
        g = int(rng.integers(1, 4))
        s = int(rng.integers(1, tk.size - 4))
        keep[s:s + g] = False
        nd += g
    tk = tk[keep]
    x_true = np.interp(tk, t50, X)
    v_true = np.interp(tk, t50, V)
    f_true = np.interp(tk, t50, FF)
    # the coil force is held between controller updates: sample-and-hold
    idx = np.clip(np.floor(tk / DT).astype(int), 0, len(FA) - 1)
    fa_true = FA[idx]
    n_true = NR[idx]
    drift = 20.0 * (tk / T) ** 1.2 + 2.0 * np.sin(2 * np.pi * tk / 45.0)  # nm
    x_log = (-1.0 if reversed_sensor else 1.0) * x_true * 1e9 + drift + rng.normal(0, 1.0, tk.size)
    x_log = np.round(x_log / 0.3) * 0.3
    f_log = fa_true * 1e3 + 1.0 + rng.normal(0, 0.5, tk.size)
    columns = {"t [ms]": np.round(tk * 1e3, 4), "x_interf [nm]": np.round(x_log, 1), "F_coil [mN]": np.round(f_log, 3)}
    truth = dict(effect=effect, seed=seed, mass_kg=M, Fc_N=FC, Fs_N=FS, vs_m_per_s=VS, delta=DELTA,
                 sigma2_N_s_per_m=SIGMA2, element_k_N_per_m=list(K_EL), element_alpha=list(ALPHA),
                 element_break_m_at_Fs=list(D_BREAK), stuck_damping_N_s_per_m=C_TOTAL,
                 virgin_curve_90pct_Fc_at_m=3.76e-6,
                 ripple_amplitude=e["ripple"], ripple_lambda_m=LAMBDA, ripple_phase_rad_in_true_x=RIPPLE_PHASE,
                 warm_b=e["warm"], warm_tau_s=TAU_WARM,
                 soft_h=e["soft"], soft_nc=SOFT_NC, soft_reversal_backtravel_m=REV_THRESH,
                 reversals_total=int(NR[-1]),
                 reversals_before_first_sliding=int(NR[np.argmax(mode == 1)]),
                 duration_s=float(T), rows=int(tk.size), dropped=int((~keep).sum()),
                 log_sign=("position logged negated (force pushes toward negative logged position)" if reversed_sensor
                           else "position logged as the force pushes"),
                 force_offset_mN=1.0, force_noise_mN=0.5, pos_noise_nm=1.0, pos_quant_nm=0.3,
                 drift_nm="20*(t/T)^1.2 + 2*sin(2*pi*t/45s)")
    true = dict(t=tk, x_true=x_true, v_true=v_true, friction_true=f_true, force_true=fa_true, nrev=n_true)
    return columns, truth, true


def main(effect, seed, out):
    columns, truth, true = session(effect, seed)
    with open(out, "w") as fh:
        fh.write(",".join(columns) + "\n")
        for a, b, c in zip(*columns.values()):
            fh.write(f"{a:.4f},{b:.1f},{c:.3f}\n")
    with open(out.replace(".csv", ".truth.json"), "w") as fh:
        json.dump(truth, fh, indent=1)
    np.savez_compressed(out.replace(".csv", ".truth.npz"), **true)
    print(out, truth["rows"], "rows", f"{truth['duration_s']:.1f} s", "reversals", truth["reversals_total"])


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3])
