"""A rodless pneumatic cylinder with a guide carriage, simulated apart from leuven-friction (numpy
only; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_pneumatic_slide.py``).

Plant: an 18 kg carriage, m·a = u − F_f, under a position PID loop at 1 kHz (with mass
feed-forward and a filtered velocity) and open-loop force ramps of ±120 N at 100 N/s. Friction:
six Maxwell-slip elements (limits 30/25/18/12/10/5 % of S(v), breaking at 6–140 µm, 1.4·10⁷ N/m in
all) whose limits follow a Stribeck curve with δ = 1.3 (F_s 160/145 N, F_c 110/100 N, v_s
12/10 mm/s), damping on the stuck elements and viscous friction 250/230 N·s/m. Symplectic Euler
at 10 kHz, all sessions at once (vectorised over them), logged at 1 kHz for 150 s: a sweep of 9
speeds of 1–200 mm/s both ways in a shuffled order, triangular excursions of 40 µm–1.5 mm, force
ramps, a second partial sweep. The position is a magnetostrictive sensor with 2 µm of Gaussian
noise written in inches to 10⁻⁶ in; the force, p_cap·A_cap − p_rod·A_rod with 0.9 N of noise, in
lbf; time in ms.

Effects, inside the loop: ``warmup``, dry friction × (1 − 0.22 (1 − e^{−t/28 s})) and viscous
× (1 − 0.35 (…)); ``load``, the whole friction × (N/450 N)^0.6 with a ``normal_load [lbf]`` column
stepping among 250/450/700 N in the rests; ``ripple``, the element limits × (1 + 0.07 sin(2πx/25 mm
+ 0.9)).

``python synth/pneumatic_slide.py OUT_DIR [SESSION …]`` writes the trial's files.
"""
import sys, os
import numpy as np

IN = 0.0254
LBF = 4.4482216152605
FS = 1000.0          # log and controller rate, Hz
SUB = 10             # plant substeps per sample
DT = 1.0 / FS / SUB
M = 18.0             # kg
POS = dict(Fs=160.0, Fc=110.0, vs=0.012, delta=1.3, sigma2=250.0)
NEG = dict(Fs=145.0, Fc=100.0, vs=0.010, delta=1.3, sigma2=230.0)
FRACTIONS = np.array([0.3, 0.25, 0.18, 0.12, 0.1, 0.05])
BREAK = np.array([6, 10, 22, 45, 80, 140]) * 1e-6    # m
DAMPING = 9500.0     # N s/m over the stuck elements
POS_NOISE, FORCE_NOISE, LOAD_NOISE = 2e-6, 0.9, 2.0  # m, N, N
KP, KD, KI, M_HAT, VFILT_HZ = 4e5, 4000.0, 4e6, 17.0, 50.0
WARM_DRY, WARM_VISCOUS, WARM_TAU = -0.22, -0.35, 28.0
LOAD_ALPHA, LOAD_N0 = 0.6, 450.0
RIPPLE_A, RIPPLE_LAMBDA, RIPPLE_PHASE = 0.07, 0.025, 0.9
SESSIONS = {"control_a": 11, "control_b": 22, "warmup": 33, "load": 44, "ripple": 55}  # name: noise seed


def programme():
    """Per-sample arrays: mode (0 position control, 1 force ramp), reference speed, its
    acceleration, the force ramps' force."""
    vr, fr, mode = [], [], []

    def rest(T):
        n = int(round(T * FS))
        vr.extend([0.0] * n); fr.extend([0.0] * n); mode.extend([0] * n)

    def move(v, d, amax=1.5):  # a trapezoid of signed speed v over a travel |d|
        tr = abs(v) / amax
        dr = 0.5 * abs(v) * tr
        tc = max(abs(d) - 2 * dr, 0) / abs(v)
        t = np.arange(0, 2 * tr + tc, 1 / FS)
        prof = np.where(t < tr, t / tr, np.where(t < tr + tc, 1.0, np.clip((2 * tr + tc - t) / tr, 0, 1))) * v
        vr.extend(prof.tolist()); fr.extend([0.0] * len(t)); mode.extend([0] * len(t))

    def excursion(A, v, cycles):
        for _ in range(cycles):
            move(v, A); move(-v, 2 * A); move(v, A)

    def force_ramp(Fmax, rate, cycles):
        t = np.arange(0, Fmax / rate, 1 / FS)
        for _ in range(cycles):
            seg = np.concatenate([t * rate, Fmax - t * rate, -t * rate, -Fmax + t * rate])
            vr.extend([0.0] * len(seg)); fr.extend(seg.tolist()); mode.extend([1] * len(seg))

    rest(0.5)
    move(-0.05, -0.16); rest(1.0)
    for v in [0.016, 0.001, 0.12, 0.004, 0.032, 0.2, 0.002, 0.064, 0.008]:  # not monotone in time
        d = min(0.32, v * 2.6)
        move(v, d); rest(0.6); move(-v, -d); rest(0.6)
    move(0.05, 0.16); rest(1.0)
    for A, cyc in [(40e-6, 3), (120e-6, 3), (400e-6, 3), (1.5e-3, 2)]:
        excursion(A, 0.5e-3 if A < 1e-3 else 1e-3, cyc); rest(0.7)
    force_ramp(120.0, 100.0, 2); rest(1.0)
    for A in [1.5e-3, 120e-6]:
        excursion(A, 1e-3 if A > 1e-3 else 0.5e-3, 2); rest(0.5)
    move(-0.05, -0.16); rest(0.6)
    for v in [0.2, 0.003, 0.05, 0.09]:
        d = min(0.32, v * 2.5)
        move(v, d); rest(0.6); move(-v, -d); rest(0.6)
    move(0.05, 0.16); rest(0.3)
    vr, fr, mode = np.array(vr), np.array(fr), np.array(mode)
    return mode, vr, np.gradient(vr, 1 / FS), fr


def stribeck(av, side):
    return side["Fc"] + (side["Fs"] - side["Fc"]) * np.exp(-(av / side["vs"]) ** side["delta"])


def load_schedule(vr):
    """The normal load, N: stepped among 250/450/700 N 0.3 s before every other stroke starts,
    reached with a 80 ms lag."""
    N = len(vr)
    moving = np.abs(vr) > 0
    starts = np.flatnonzero(np.diff(moving.astype(int)) == 1)
    rl = np.random.default_rng(7)
    changes = {int(i0) - 300: [250.0, 450.0, 700.0][rl.integers(3)] for j, i0 in enumerate(starts) if j % 2 == 0}
    load, cur, tgt = np.full(N, LOAD_N0), LOAD_N0, LOAD_N0
    for i in range(N):
        tgt = changes.get(i, tgt)
        cur += (tgt - cur) * (1 - np.exp(-1 / FS / 0.08))
        load[i] = cur
    return load


def simulate(outdir, sessions=None):
    """Write the ``sessions`` (all of SESSIONS by default) as CSV files into ``outdir``; each
    session has its own noise, all share the programme."""
    names = [s for s in SESSIONS if sessions is None or s in sessions]
    mode, vr, ar, fr = programme()
    N, S = len(vr), len(names)
    k = FRACTIONS * POS["Fs"] / BREAK
    c = DAMPING * k / k.sum()
    load = load_schedule(vr)
    rngs = [np.random.default_rng(SESSIONS[n]) for n in names]
    noise_x = np.stack([r.normal(0, POS_NOISE, N) for r in rngs])
    is_w = np.array([n == "warmup" for n in names])
    is_l = np.array([n == "load" for n in names])
    is_r = np.array([n == "ripple" for n in names])
    x, v = np.zeros(S), np.zeros(S)
    z = np.zeros((S, len(k)))
    xm_log, u_log = np.zeros((S, N)), np.zeros((S, N))
    integ, vf, xprev, xr = np.zeros(S), np.zeros(S), np.zeros(S), np.zeros(S)
    u_last = np.zeros(S)
    alpha_f = 1 - np.exp(-2 * np.pi * VFILT_HZ / FS)
    prev_mode = 0
    for i in range(N):
        xm = x + noise_x[:, i]
        if i > 0:
            vf += alpha_f * ((xm - xprev) * FS - vf)
        xprev = xm
        if mode[i] == 0:
            if prev_mode == 1:
                xr[:] = xm
                integ[:] = u_last / KI  # bumpless back to position control
            xr += vr[i] / FS
            e = xr - xm
            integ += e / FS
            u = M_HAT * ar[i] + KP * e + KD * (vr[i] - vf) + KI * integ
        else:
            u = np.full(S, fr[i])
        u_last = u.copy()
        prev_mode = mode[i]
        xm_log[:, i], u_log[:, i] = xm, u
        wu = 1 - np.exp(-(i / FS) / WARM_TAU)
        lf = (load[i] / LOAD_N0) ** LOAD_ALPHA
        for _ in range(SUB):
            av = np.abs(v)
            sp = np.where(v >= 0, stribeck(av, POS), stribeck(av, NEG))
            s2 = np.where(v >= 0, POS["sigma2"], NEG["sigma2"])
            gd = np.where(is_w, 1 + WARM_DRY * wu, np.where(is_l, lf, 1.0))
            gv = np.where(is_w, 1 + WARM_VISCOUS * wu, np.where(is_l, lf, 1.0))
            gd = np.where(is_r, 1 + RIPPLE_A * np.sin(2 * np.pi * x / RIPPLE_LAMBDA + RIPPLE_PHASE), gd)
            lim = (sp * gd)[:, None] * FRACTIONS[None, :] / k[None, :]
            zn = np.clip(z, -lim, lim)
            stuck = zn == z
            ff = (k * zn).sum(1) + (c[None, :] * stuck).sum(1) * v * gd + s2 * v * gv
            v = v + (u - ff) / M * DT
            dx = v * DT
            x = x + dx
            z = zn + dx[:, None]
    tms = np.arange(N) * 1000.0 / FS
    A_cap, A_rod = 1.257e-3, 1.056e-3
    for j, name in enumerate(names):
        rng = np.random.default_rng(SESSIONS[name] + 1000)
        f = u_log[j] + rng.normal(0, FORCE_NOISE, N)
        p_rod = 300e3 + rng.normal(0, 400, N)
        p_cap = (f + p_rod * A_rod) / A_cap
        cols = [tms, xm_log[j] / IN, f / LBF, p_cap / 1e3, p_rod / 1e3]
        head = "time [ms],pos [in],F_net [lbf],p_cap [kPa],p_rod [kPa]"
        fmt = ["%.1f", "%.6f", "%.4f", "%.2f", "%.2f"]
        if name == "load":
            cols.append((load + rng.normal(0, LOAD_NOISE, N)) / LBF)
            head += ",normal_load [lbf]"
            fmt.append("%.3f")
        np.savetxt(os.path.join(outdir, f"{name}.csv"), np.column_stack(cols), fmt=fmt, delimiter=",",
                   header=head, comments="")


if __name__ == "__main__":
    os.makedirs(sys.argv[1], exist_ok=True)
    simulate(sys.argv[1], sys.argv[2:] or None)
