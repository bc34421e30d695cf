"""A reciprocating ball-on-flat tribometer's export, simulated apart from leuven-friction
(numpy and scipy only; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
file shaped like a commercial instrument's, and kept so that trial runs again
(``tests/slow/test_diagnose_tribometer_export.py``).

Contact: a Maxwell-slip bank (4 elasto-plastic elements) whose break forces follow a
Stribeck curve s(v) = mu_c + (mu_s - mu_c) exp(-(|v|/v_s)^2), times N, plus a viscous term.
Steady sliding friction: F(v) = N s(v) sign(v) + sigma2 v  (times m(t) for running-in).
Drive: sine strokes of 0.2–5 Hz over 1–4 mm and triangles at 0.5–20 mm/s, every block
visited twice, the second pass reversed.

Nuisances: force-sensor offset drifting slowly, analog noise, first-order low-pass 200 Hz;
LVDT position noise 0.5 um; 1 kHz sampling with jittered instants; two dropouts; Fn noise.
Export: metadata lines above the header (no # comments), ';'-separated, decimal comma,
cp1252, CRLF line ends.

Sessions: ``steady`` (no effect beyond the nuisances); ``runin`` (the bank's friction × 1 +
0.25(1 − e^(−t/τ))/(1 − e^(−T/τ)), τ a third of the session T: a running-in).

usage: python -m synth.tribometer_export OUTDIR [--session steady|runin|both] [--seed S]
"""
import json
import argparse
import numpy as np

# ---- truth --------------------------------------------------------------------------------
N_LOAD = 10.0          # N, dead weight
MU_C = 0.12
MU_S = 0.16
V_S = 3.0e-3           # m/s, Stribeck speed
SIGMA2 = 2.0           # N s/m, viscous
W = np.array([0.15, 0.30, 0.35, 0.20])          # element weights (sum 1)
D_BREAK = np.array([0.4e-6, 1.2e-6, 3.0e-6, 8.0e-6])  # break displacement of each element, m
K = W * MU_C * N_LOAD / D_BREAK                  # element stiffnesses, N/m (fixed)

FS_SIM = 10_000.0      # internal rate
FS_LOG = 1000.0        # logging rate
JITTER = 40e-6         # s, std of sampling-instant jitter
LP_FC = 200.0          # Hz, force-sensor low-pass
F_NOISE = 0.004        # N, analog noise on Ff
FN_NOISE = 0.025       # N, noise on Fn
X_NOISE = 0.5e-6       # m, LVDT noise
RUNIN_GAIN = 0.25      # COF rises by 25 % over the session
# -------------------------------------------------------------------------------------------


def min_jerk(p0, p1, T, dt):
    n = max(int(round(T / dt)), 2)
    s = np.arange(n) / n
    return p0 + (p1 - p0) * (10 * s**3 - 15 * s**4 + 6 * s**5)


def program(dt):
    """Position (m) and cycle counter on the internal grid."""
    # (kind, stroke p-p [mm], freq [Hz] or speed [mm/s], cycles)
    blocks_a = [
        ("sin", 2.0, 0.2, 2),
        ("tri", 2.0, 0.5, 1),
        ("sin", 2.0, 0.5, 3),
        ("tri", 2.0, 1.5, 2),
        ("sin", 2.0, 1.0, 6),
        ("sin", 1.0, 2.0, 12),
        ("tri", 2.0, 4.0, 4),
        ("sin", 4.0, 2.0, 12),
        ("sin", 1.0, 5.0, 30),
        ("tri", 3.0, 10.0, 8),
        ("sin", 3.0, 1.0, 6),
        ("tri", 4.0, 20.0, 10),
        ("sin", 4.0, 0.5, 3),
    ]
    blocks = blocks_a + blocks_a[::-1]      # every condition visited twice, second pass reversed
    xs, cyc = [np.zeros(int(1.0 / dt))], [np.zeros(int(1.0 / dt))]
    cur, ncyc = 0.0, 0
    plan = []
    for kind, stroke, par, ncy in blocks:
        A = stroke / 2 * 1e-3
        # move to -A, dwell
        mv = min_jerk(cur, -A, 0.6, dt)
        dw = np.full(int(0.3 / dt), -A)
        xs += [mv, dw]
        cyc += [np.full(len(mv) + len(dw), ncyc)]
        if kind == "sin":
            f = par
            T = ncy / f
            t = np.arange(int(round(T / dt))) * dt
            x = -A * np.cos(2 * np.pi * f * t)
            c = ncyc + np.floor(t * f)
        else:
            v = par * 1e-3
            leg = 2 * A / v
            T = ncy * 2 * leg
            t = np.arange(int(round(T / dt))) * dt
            ph = (t % (2 * leg)) / leg
            x = np.where(ph < 1, -A + 2 * A * ph, A - 2 * A * (ph - 1))
            # round the corners: moving average over 20 ms (parabolic corners)
            nk = int(0.02 / dt) | 1
            pad = np.concatenate([np.full(nk, -A), x, np.full(nk, -A)])
            x = np.convolve(pad, np.ones(nk) / nk, mode="same")[nk:-nk]
            c = ncyc + np.floor(t / (2 * leg))
        plan.append(dict(kind=kind, stroke_mm=stroke, par=par, cycles=ncy,
                         t_start=sum(len(a) for a in xs) * dt, duration=T))
        xs.append(x)
        cyc.append(c)
        ncyc += ncy
        cur = -A
        dw = np.full(int(0.3 / dt), -A)
        xs.append(dw)
        cyc.append(np.full(len(dw), ncyc))
    mv = min_jerk(cur, 0.0, 0.6, dt)
    xs += [mv, np.zeros(int(0.5 / dt))]
    cyc += [np.full(len(mv) + int(0.5 / dt), ncyc)]
    return np.concatenate(xs), np.concatenate(cyc), plan


def stribeck(v):
    return MU_C + (MU_S - MU_C) * np.exp(-(np.abs(v) / V_S) ** 2)


def contact(x, v, m):
    """Maxwell-slip bank; returns the friction force on the ball (positive along +v of the flat)."""
    n = len(x)
    cap = stribeck(v) * N_LOAD                 # N, total break force at speed v
    e = np.zeros(len(W))                       # elastic deflection of each element
    F = np.empty(n)
    dx = np.diff(x, prepend=x[0])
    Wl, Kl = W.tolist(), K.tolist()
    e = [0.0] * len(Wl)
    capl, dxl = cap.tolist(), dx.tolist()
    for i in range(n):
        d = dxl[i]
        c = capl[i]
        tot = 0.0
        for j in range(len(Wl)):
            ej = e[j] + d
            lim = Wl[j] * c / Kl[j]
            if ej > lim:
                ej = lim
            elif ej < -lim:
                ej = -lim
            e[j] = ej
            tot += Kl[j] * ej
        F[i] = tot
    return m * F + SIGMA2 * v


def lowpass(sig, fc, dt):
    from scipy.signal import lfilter
    a = np.exp(-2 * np.pi * fc * dt)
    return lfilter([1 - a], [1, -a], sig, zi=[sig[0] * a])[0]


def fmt(a, nd):
    s = np.char.mod(f"%.{nd}f", a)
    return np.char.replace(s, ".", ",")


def make(session, outdir, seed):
    rng = np.random.default_rng(seed)
    dt = 1.0 / FS_SIM
    x, cyc, plan = program(dt)
    n = len(x)
    t = np.arange(n) * dt
    Ttot = t[-1]
    v = np.gradient(x, dt)
    if session == "runin":
        tau = Ttot / 3
        m = 1 + RUNIN_GAIN * (1 - np.exp(-t / tau)) / (1 - np.exp(-Ttot / tau))
    else:
        tau = None
        m = np.ones(n)
    Ff = contact(x, v, m)
    # sensor: offset drifting slowly + low-pass + noise
    wander = np.cumsum(rng.normal(0, 1, n))
    wander = lowpass(wander - wander.mean(), 0.02, dt)
    wander = 0.004 * wander / (np.abs(wander).max() + 1e-12)
    offset = 0.035 + 0.02 * t / Ttot + wander          # ~3 -> 5 % of F_c, drifting
    Fsens = lowpass(Ff, LP_FC, dt) + offset
    # sampling instants: 1 kHz with jitter
    nlog = int(Ttot * FS_LOG)
    tl = np.arange(nlog) / FS_LOG + rng.normal(0, JITTER, nlog)
    tl = np.clip(tl, 0, Ttot)
    tl = np.maximum.accumulate(tl)
    Ff_l = np.interp(tl, t, Fsens) + rng.normal(0, F_NOISE, nlog)
    x_l = np.interp(tl, t, x) + rng.normal(0, X_NOISE, nlog)
    Fn_l = N_LOAD + rng.normal(0, FN_NOISE, nlog)
    cyc_l = np.interp(tl, t, cyc).astype(int)
    cof = Ff_l / Fn_l
    # dropouts
    keep = np.ones(nlog, bool)
    drops = []
    for start_frac, length in [(0.31, 57), (0.77, 212)]:
        s = int(start_frac * nlog)
        keep[s:s + length] = False
        drops.append((float(tl[s]), length))
    tl, x_l, Ff_l, Fn_l, cof, cyc_l = (a[keep] for a in (tl, x_l, Ff_l, Fn_l, cof, cyc_l))
    cols = [fmt(tl, 5), fmt(x_l * 1e3, 5), fmt(Ff_l, 4), fmt(Fn_l, 3), fmt(cof, 5),
            np.char.mod("%d", cyc_l)]
    lines = np.char.add(cols[0], ";")
    for c in cols[1:-1]:
        lines = np.char.add(np.char.add(lines, c), ";")
    lines = np.char.add(lines, cols[-1])
    head = [
        "Instrument: UMT TriboLab, reciprocating module (S/N 41-0273)",
        "Test: ball-on-flat, 100Cr6 ball Ø 6 mm on AISI 52100 flat, dry, 23 °C",
        "Operator: K. Vermeulen",
        "Date: 14.03.2024 10:22:05",
        "Load: 10 N",
        "Sample rate: 1000 Hz",
        "",
        "Time [s];Stroke position [mm];Ff [N];Fn [N];COF [-];Cycle [-]",
    ]
    path = f"{outdir}/{session}.csv"
    with open(path, "w", encoding="cp1252", newline="\r\n") as fh:
        fh.write("\n".join(head) + "\n")
        fh.write("\n".join(lines.tolist()) + "\n")
    truth = dict(
        session=session, rows=int(keep.sum()), duration_s=float(Ttot),
        N=N_LOAD, mu_c=MU_C, mu_s=MU_S, v_s=V_S, delta=2.0, sigma2=SIGMA2,
        Fc=MU_C * N_LOAD, Fs=MU_S * N_LOAD,
        element_weights=W.tolist(), element_break_um=(D_BREAK * 1e6).tolist(),
        element_k_N_per_m=K.tolist(),
        sensor=dict(offset_start=float(offset[0]), offset_end=float(offset[-1]),
                    noise=F_NOISE, lowpass_hz=LP_FC, x_noise_m=X_NOISE, jitter_s=JITTER),
        dropouts=drops, friction_sign="positive along the flat's velocity",
        runin=(dict(form="m(t)=1+0.25(1-exp(-t/tau))/(1-exp(-T/tau)), scales the Maxwell bank "
                    "(not the viscous term)", tau_s=tau, m_end=float(m[-1]),
                    Fc_end=MU_C * N_LOAD * float(m[-1]), Fs_end=MU_S * N_LOAD * float(m[-1]),
                    Fc_mean=MU_C * N_LOAD * float(m.mean()))
               if session == "runin" else None),
        plan=plan,
    )
    with open(f"{outdir}/{session}_truth.json", "w") as fh:
        json.dump(truth, fh, indent=1)
    print(path, truth["rows"], "rows", f"{Ttot:.1f} s")


def simulate_to(outdir, sessions=("steady", "runin"), seed=7):
    """Write the sessions asked into ``outdir`` (each with its ``_truth.json``); their paths."""
    for s in sessions:
        make(s, outdir, seed + (s == "runin"))
    return [f"{outdir}/{s}.csv" for s in sessions]


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("outdir")
    ap.add_argument("--session", default="both")
    ap.add_argument("--seed", type=int, default=7)
    a = ap.parse_args()
    for s in (["steady", "runin"] if a.session == "both" else [a.session]):
        make(s, a.outdir, a.seed + (s == "runin"))
