"""A machine-tool slide on sliding guideways, simulated apart from leuven-friction (numpy only;
it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_machine_tool_slide.py``).

Plant: an 85 kg table driven by a ball screw, force-driven by a servo (the force command is
logged). Friction: Maxwell-slip presliding (5 elements, stiffnesses summing to 4e7 N/m, breaking
at 1.35–27 µm) whose element limits follow a Gaussian Stribeck curve (F_s 230/238 N, F_c
180/186 N, v_s 4.0/4.2 mm/s), plus viscous friction 900/930 N·s/m. All sessions are integrated
at once (vectorised over sessions) with semi-implicit Euler at 20 kHz, the servo at 4 kHz, logged
at 1 kHz for 112 s: force ramps below break-away, then ten speeds of 0.05–50 mm/s both ways in a
shuffled order, then sinusoids. A 0.1 µm scale logged in mm and counting NEGATIVE when the table
moves in the motor's positive force direction; the force in kN with 1.5 N of noise and a 3 N offset.

Effects, applied to every element's limit and the viscous term inside the loop: ``load``,
friction ∝ (N/2 kN)^0.8 with a ``normal_load [kN]`` column stepping 2.0 → 3.0 → 1.4 → 2.6 →
2.0 kN; ``ripple``, × (1 + 0.05 sin(2πx/5 mm)); ``warming``, × (1 + 0.12 (1 − e^{−t/35 s})).

``python synth/machine_tool_slide.py OUT_DIR [SESSION …]`` writes the trial's files.
"""
import sys, os
import numpy as np

# ---------------- truth (SI) ----------------
M = 85.0
FC_P, FC_N = 180.0, 186.0          # Coulomb, N (positive / negative direction)
FS_P, FS_N = 230.0, 238.0          # static, N
VS_P, VS_N = 4.0e-3, 4.2e-3        # Stribeck speed, m/s
SG2_P, SG2_N = 900.0, 930.0        # viscous, N s/m
DELTA = 2.0                        # Stribeck shape exponent (Gaussian)
K_EL = np.array([1.6e7, 1.0e7, 0.7e7, 0.45e7, 0.25e7])   # sum 4.0e7 N/m
D_EL = np.array([1.35, 3.4, 6.7, 13.5, 27.0]) * 1e-6      # breakaway displacements, m
W_EL = K_EL * D_EL / np.sum(K_EL * D_EL)                  # weight of each element's limit

FS_RATE = 20000
SERVO_DIV = 5          # servo at 4 kHz
LOG_DIV = 20           # log at 1 kHz
Q = 1e-7               # scale quantum 0.1 um
F_NOISE = 1.5          # force sensor noise, N
F_OFFSET = 3.0         # force sensor offset, N

SESSIONS = ["control_a", "control_b", "load", "ripple", "warming", "ripple_warming"]
SEEDS = [11, 22, 33, 44, 55, 66]
N0 = 2000.0
LOAD_STEPS = [(0.0, 2000.0), (28.0, 3000.0), (52.0, 1400.0), (78.0, 2600.0), (101.0, 2000.0)]
ALPHA = 0.8
RIP_A, RIP_L = 0.05, 5e-3
DRIFT_B, DRIFT_TAU = 0.12, 35.0


def stribeck(v_abs, pos):
    if pos:
        return FC_P + (FS_P - FC_P) * np.exp(-(v_abs / VS_P) ** DELTA)
    return FC_N + (FS_N - FC_N) * np.exp(-(v_abs / VS_N) ** DELTA)


def programme(rng):
    """List of segments: ('force', t_dur, f0, f1) open loop ramps, ('vel', ...)"""
    segs = []
    # 1. slow presliding reversals: force ramps below breakaway, open loop
    pts = [0, 120, -80, 160, -40, 180, -175, 100, -140, 60, 0]
    for a, b in zip(pts[:-1], pts[1:]):
        segs.append(("force", abs(b - a) / 200.0, float(a), float(b)))
    segs.append(("force", 0.5, 0.0, 0.0))
    # 2. constant-velocity strokes in shuffled order
    speeds = np.array([0.05, 0.1, 0.2, 0.5, 1, 2, 5, 10, 20, 50]) * 1e-3
    order = rng.permutation(len(speeds))
    for i in order:
        v = speeds[i]
        T = min(4.0, max(1.2, 0.06 / v))
        first = rng.choice([1, -1])
        for s in (first, -first):
            segs.append(("vel", T, s * v))
            segs.append(("vel", 0.4, 0.0))
    # 3. sinusoidal back-and-forth (position reference)
    segs.append(("sine", 10.0, 5e-3, 0.4))
    segs.append(("vel", 0.5, 0.0))
    segs.append(("sine", 5.0, 0.5e-3, 1.0))
    segs.append(("vel", 0.5, 0.0))
    segs.append(("sine", 4.0, 0.03e-3, 0.5))
    segs.append(("vel", 1.0, 0.0))
    return segs


def build_reference(segs):
    dt = 1.0 / FS_RATE
    mode, fff, vref = [], [], []
    for s in segs:
        n = int(round(s[1] * FS_RATE))
        t = np.arange(n) * dt
        if s[0] == "force":
            mode.append(np.zeros(n, bool)); fff.append(s[2] + (s[3] - s[2]) * t / s[1]); vref.append(np.zeros(n))
        elif s[0] == "vel":
            mode.append(np.ones(n, bool)); fff.append(np.zeros(n)); vref.append(np.full(n, s[2]))
        else:  # sine: x = A sin(2 pi f t)
            A, f = s[2], s[3]
            mode.append(np.ones(n, bool)); fff.append(np.zeros(n)); vref.append(A * 2 * np.pi * f * np.cos(2 * np.pi * f * t))
    mode = np.concatenate(mode); fff = np.concatenate(fff); vref = np.concatenate(vref)
    # acceleration limit on velocity reference (0.5 m/s^2), via rate limiting
    amax = 0.5 * dt
    # simple rate limiter (vectorised-ish by loop on changes only)
    out = np.empty_like(vref); prev = 0.0
    for i in range(len(vref)):
        d = vref[i] - prev
        if d > amax: d = amax
        elif d < -amax: d = -amax
        prev = prev + d; out[i] = prev
    return mode, fff, out


def simulate(outdir, sessions=None):
    """Write the ``sessions`` (all of SESSIONS by default) as CSV files into ``outdir``; each
    session keeps its own noise seed whichever others are simulated beside it."""
    os.makedirs(outdir, exist_ok=True)
    names = [s for s in SESSIONS if sessions is None or s in sessions]
    rng0 = np.random.default_rng(2026)
    segs = programme(rng0)
    mode, fff, vref = build_reference(segs)
    n = len(vref); dt = 1.0 / FS_RATE
    S = len(names)
    rngs = [np.random.default_rng(SEEDS[SESSIONS.index(s)]) for s in names]
    # per-session effect switches
    is_load = np.array([s == "load" for s in names])
    is_rip = np.array(["ripple" in s for s in names])
    is_drift = np.array(["warming" in s for s in names])
    # disturbance force (small, band-limited) per session, at servo rate
    x = np.zeros(S); v = np.zeros(S)
    anchor = np.zeros((S, len(K_EL)))
    xref = np.zeros(S); vfilt = np.zeros(S); pq_prev = np.zeros(S)
    F = np.zeros(S); dist = np.zeros(S)
    Kp, Ki = 4.0e4, 6.0e6
    alpha_f = 1 - np.exp(-2 * np.pi * 300 / (FS_RATE / SERVO_DIV))
    nlog = n // LOG_DIV
    log_t = np.zeros(nlog); log_x = np.zeros((S, nlog)); log_F = np.zeros((S, nlog)); log_N = np.zeros(nlog)
    load_t = np.array([a for a, _ in LOAD_STEPS]); load_v = np.array([b for _, b in LOAD_STEPS])
    was_closed = False
    for i in range(n):
        t = i * dt
        # servo
        if i % SERVO_DIV == 0:
            pq = np.round(x / Q) * Q
            vraw = (pq - pq_prev) * (FS_RATE / SERVO_DIV); pq_prev = pq
            vfilt += alpha_f * (vraw - vfilt)
            for k in range(S):
                dist[k] = 0.995 * dist[k] + 0.1 * rngs[k].standard_normal()
            if mode[i]:
                if not was_closed:
                    xref = pq.copy(); was_closed = True
                xref = xref + vref[i] * dt * SERVO_DIV
                F = Kp * (vref[i] - vfilt) + Ki * (xref - pq)
            else:
                was_closed = False
                F = np.full(S, fff[i])
            Fapp = F + dist
        # friction multiplier
        Nnow = load_v[np.searchsorted(load_t, t, side="right") - 1]
        mult = np.ones(S)
        mult = np.where(is_load, (Nnow / N0) ** ALPHA, mult)
        mult = mult * np.where(is_rip, 1 + RIP_A * np.sin(2 * np.pi * x / RIP_L), 1.0)
        mult = mult * np.where(is_drift, 1 + DRIFT_B * (1 - np.exp(-t / DRIFT_TAU)), 1.0)
        # elements: force of each, saturating at weight * S(|v|) of the side it pulls
        fel = K_EL[None, :] * (x[:, None] - anchor)
        av = np.abs(v)[:, None]
        lim = np.where(fel >= 0, stribeck(av, True), stribeck(av, False)) * W_EL[None, :] * mult[:, None]
        over = np.abs(fel) > lim
        if over.any():
            fel = np.where(over, np.sign(fel) * lim, fel)
            anchor = np.where(over, x[:, None] - fel / K_EL[None, :], anchor)
        ffric = fel.sum(axis=1) + mult * np.where(v >= 0, SG2_P, SG2_N) * v
        # semi-implicit Euler
        v = v + dt * (Fapp - ffric) / M
        x = x + dt * v
        if i % LOG_DIV == 0:
            j = i // LOG_DIV
            if j < nlog:
                log_t[j] = t; log_x[:, j] = x; log_F[:, j] = F; log_N[j] = Nnow
    for k, name in enumerate(names):
        r = rngs[k]
        pos_mm = -np.round(log_x[k] / Q) * Q * 1e3          # scale counts negative
        f_kN = (log_F[k] + F_OFFSET + F_NOISE * r.standard_normal(nlog)) * 1e-3
        path = os.path.join(outdir, name + ".csv")
        with open(path, "w") as fh:
            if is_load[k]:
                nl = (log_N + 5.0 * r.standard_normal(nlog)) * 1e-3
                fh.write("t [s],position [mm],force [kN],normal_load [kN]\n")
                for a, b, c, d in zip(log_t, pos_mm, f_kN, nl):
                    fh.write(f"{a:.3f},{b:.4f},{c:.6f},{d:.5f}\n")
            else:
                fh.write("t [s],position [mm],force [kN]\n")
                for a, b, c in zip(log_t, pos_mm, f_kN):
                    fh.write(f"{a:.3f},{b:.4f},{c:.6f}\n")


if __name__ == "__main__":
    simulate(sys.argv[1], sys.argv[2:] or None)
