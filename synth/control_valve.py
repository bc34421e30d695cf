"""Independent simulator of a pneumatic control valve (sliding-stem globe valve,
spring-diaphragm actuator) with packing friction as a 5-element Maxwell-slip bank.

Written from the leuven-friction README only; imports nothing from the package.

    python -m synth.control_valve CASE OUT.csv     # CASE: A control, B packing relaxation,
                                                   # C gland load, D the spring rate 15 % off

Sign: x (stem travel from the seat) grows with chamber pressure.  The user's CSV holds
time [s], x [mm] (LVDT) and applied_force [N] = P_meas*A - k_ds*(x_meas - x0) - preload,
computed with a datasheet spring rate k_ds off the true one.
"""
import math
import sys

import numpy as np


# ---------------------------------------------------------------- plant
M = 1.5            # kg, stem + plug + diaphragm plate
A = 0.05           # m^2 diaphragm
K_TRUE = 5.0e4     # N/m spring
X0 = 0.0           # m, seat (LVDT zero)
F0 = 2000.0        # N, spring force at the seat (preload) -> 60 kPa puts the stem at 20 mm
TAU_IP = 0.3       # s, I/P + chamber lag

# ---------------------------------------------------------------- packing friction
FS, FC, VS, SIGMA2 = 400.0, 300.0, 2.0e-3, 2000.0
ALPHA = [0.30, 0.25, 0.20, 0.15, 0.10]           # share of each element
DSLIP = [5e-6, 12e-6, 22e-6, 35e-6, 55e-6]       # m, element travel to break loose (at FS)
KEL = [a * FS / d for a, d in zip(ALPHA, DSLIP)]  # N/m
KSUM = sum(KEL)
C_MICRO = 2 * 0.3 * math.sqrt(KSUM * M)         # N s/m, damping of the sticking elements
TAU_MEM = 2e-3     # s, frictional memory of the Stribeck threshold (rate-state like lag)


def stribeck(v):
    """Lorentzian Stribeck drop (not the exponential of the Leuven/LuGre form)."""
    return FC + (FS - FC) / (1.0 + (v / VS) ** 2)


def steady_friction(v):
    return math.copysign(stribeck(abs(v)), v) + SIGMA2 * v


# ---------------------------------------------------------------- timing
DT = 5e-5          # 20 kHz
DT_LOG = 1e-3      # 1 kHz
CTRL_EVERY = 20    # positioner at 1 kHz

# ---------------------------------------------------------------- sensors
LVDT_Q = 5e-6
LVDT_SD = 2e-6
P_SD = 0.3e3       # Pa
N_SD = 0.01        # kN on the gland-load sensor


def build_program(rng):
    """Return (t_end, phases) where phases is a list of callables on time."""
    segs = []   # (t_start, t_end, kind, data)
    t = 0.0

    # --- phase 1: open-loop pressure ramps breaking the stem loose each way (kPa)
    pts = [(0.0, 60.0), (1.0, 60.0)]
    rate = 3.0

    def go(p, hold):
        t0, p0 = pts[-1]
        pts.append((t0 + abs(p - p0) / rate, p))
        pts.append((pts[-1][0] + hold, p))
    go(72.0, 1.0)
    go(48.0, 1.0)
    go(60.0, 0.5)
    go(54.0, 1.0)          # back off ~ Fc/A: friction state towards zero
    t_ramp_end = pts[-1][0]
    segs.append(("ramp", 0.0, t_ramp_end, np.array(pts)))

    # --- phase 2: small pressure sines around the held pressure (presliding)
    f = 0.5
    amps = [3.0, 5.5, 8.0, 5.5, 3.0]          # kPa command, 2 cycles each
    t_sine = len(amps) * 2 / f
    segs.append(("sine", t_ramp_end, t_ramp_end + t_sine, (54.0, f, amps)))
    t = t_ramp_end + t_sine + 1.0            # 1 s hold before the positioner takes over
    segs.append(("hold", t_ramp_end + t_sine, t, 54.0))

    # --- phase 3: positioner tracking constant-velocity strokes, shuffled speeds
    speeds = [0.2, 0.4, 0.8, 1.5, 3.0, 6.0, 12.0, 24.0, 40.0]   # mm/s
    up = list(rng.permutation(speeds))
    dn = list(rng.permutation(speeds))
    ref = [(t, None)]       # None: start from where the stem is
    order = []
    for i in range(len(speeds) * 2):
        d = 1 if i % 2 == 0 else -1
        v = (up if d > 0 else dn)[i // 2]
        L = min(v * 4.0, 25.0)                # mm
        T = L / v
        start = 20.0 - d * L / 2
        ref.append(("move", start, 0.6))     # cosine reposition over 0.6 s
        ref.append(("hold", 0.2))
        ref.append(("ramp", d * v, T))
        order.append(d * v)
    ref.append(("move", 20.0, 0.6))
    ref.append(("hold", 0.5))
    return segs, t, ref, order


class Reference:
    def __init__(self, t0, x_start_mm, ref):
        self.knots = []   # (t0, t1, kind, p0, p1)
        t = t0
        x = x_start_mm
        for item in ref[1:]:
            if item[0] == "move":
                _, target, T = item
                self.knots.append((t, t + T, "cos", x, target))
                t += T
                x = target
            elif item[0] == "hold":
                self.knots.append((t, t + item[1], "lin", x, x))
                t += item[1]
            else:
                _, v, T = item
                self.knots.append((t, t + T, "lin", x, x + v * T))
                t += T
                x += v * T
        self.t_end = t
        self.i = 0

    def __call__(self, t):
        while self.i < len(self.knots) - 1 and t >= self.knots[self.i][1]:
            self.i += 1
        t0, t1, kind, a, b = self.knots[self.i]
        s = min(max((t - t0) / (t1 - t0), 0.0), 1.0)
        if kind == "cos":
            s = 0.5 - 0.5 * math.cos(math.pi * s)
        return a + (b - a) * s


def simulate(case, seed):
    rng = np.random.default_rng(seed)
    segs, t_pos, ref_spec, order = build_program(rng)
    ramp_pts = segs[0][3]
    _, t_s0, t_s1, (p_c, f_sine, amps) = segs[1]

    # positioner
    KP, TI = 3.0, 0.4          # kPa/mm, s
    ref = None
    p_int = 0.0

    # effects
    t_total_guess = 112.0

    def gain(t, load_kN):
        if case == "B":
            return 1.0 - 0.25 * (1.0 - math.exp(-t / 40.0))
        if case == "C":
            return (load_kN / 3.5) ** 0.8
        return 1.0

    k_ds = K_TRUE * (1 - (0.15 if case == "D" else 0.04))

    # state
    x = (60e3 * A - F0) / K_TRUE + X0
    v = 0.0
    P = 60e3
    z = [0.0] * 5
    vmem = 0.0
    t = 0.0
    step = 0
    pcmd = 60e3

    # log instants with jitter (multiples of DT)
    log_rows = []
    next_log_k = 0
    jitter = 20e-6

    def next_log_step(k):
        tj = k * DT_LOG + rng.normal(0.0, jitter)
        return max(int(round(tj / DT)), 0)
    next_log_at = next_log_step(0)
    t_end = None

    while True:
        # ---- command
        if step % CTRL_EVERY == 0:
            xm = (round((x + rng.normal(0, LVDT_SD)) / LVDT_Q) * LVDT_Q)
            if t < t_s0:
                pcmd = np.interp(t, ramp_pts[:, 0], ramp_pts[:, 1]) * 1e3
            elif t < t_s1:
                tt = t - t_s0
                ci = min(int(tt * f_sine / 2), len(amps) - 1)
                pcmd = (p_c + amps[ci] * math.sin(2 * math.pi * f_sine * tt)) * 1e3
            elif t < t_pos:
                pcmd = p_c * 1e3
            else:
                if ref is None:
                    ref = Reference(t, xm * 1e3, ref_spec)
                    p_int = pcmd / 1e3
                    t_end = ref.t_end
                e = ref(t) - xm * 1e3                # mm
                p_int += KP / TI * e * (CTRL_EVERY * DT)
                pk = p_int + KP * e
                pk = min(max(pk, 0.0), 140.0)
                pcmd = pk * 1e3
        if t_end is not None and t >= t_end:
            break

        load = 2.0 + 3.0 * t / t_total_guess if case == "C" else 3.5
        g = gain(t, load)

        # ---- friction (bank output scaled by the effect's factor)
        fb = 0.0
        kst = 0.0
        for i in range(5):
            fb += KEL[i] * z[i]
        # sticking elements' stiffness share for the micro damping
        thr = stribeck(vmem)
        for i in range(5):
            if abs(KEL[i] * z[i]) < ALPHA[i] * thr * 0.999:
                kst += KEL[i]
        ffric = g * (fb + C_MICRO * (kst / KSUM) * v + SIGMA2 * v)

        # ---- log (sample-and-hold at the jittered instant)
        if step >= next_log_at:
            tlog = step * DT
            xm = round((x + rng.normal(0, LVDT_SD)) / LVDT_Q) * LVDT_Q
            pm = P + rng.normal(0, P_SD)
            f_user = pm * A - k_ds * (xm - X0) - F0
            f_true_net = P * A - K_TRUE * (x - X0) - F0
            log_rows.append((tlog, xm * 1e3, f_user, load + rng.normal(0, N_SD),
                             x * 1e3, v * 1e3, ffric, f_true_net, P / 1e3))
            next_log_k += 1
            nl = next_log_step(next_log_k)
            next_log_at = max(nl, step + 1)

        # ---- dynamics: semi-implicit Euler
        fnet = P * A - K_TRUE * (x - X0) - F0 - ffric
        v += fnet / M * DT
        x += v * DT
        if x < 0.0:
            x, v = 0.0, 0.0
        P += (pcmd - P) * DT / TAU_IP
        vmem += (abs(v) - vmem) * DT / TAU_MEM
        thr = stribeck(vmem)
        for i in range(5):
            zi = z[i] + v * DT
            cap = ALPHA[i] * thr / KEL[i]
            if zi > cap:
                zi = cap
            elif zi < -cap:
                zi = -cap
            z[i] = zi
        step += 1
        t = step * DT
    return np.array(log_rows), order


def truth():
    speeds = [0.2e-3, 0.5e-3, 1e-3, 2e-3, 5e-3, 10e-3, 20e-3, 40e-3]
    return {
        "mass_kg": M,
        "Fs_N": FS, "Fc_N": FC, "vs_m_per_s": VS, "sigma2_Ns_per_m": SIGMA2,
        "stribeck_form": "Lorentzian Fc + (Fs-Fc)/(1+(v/vs)^2)",
        "element_k_N_per_m": KEL, "element_alpha": ALPHA, "element_slip_um": [d * 1e6 for d in DSLIP],
        "virgin_presliding_range_um": DSLIP[-1] * 1e6,
        "reversal_transition_range_um": 2 * DSLIP[-1] * 1e6,
        "steady_friction_N": {f"{v*1e3:g} mm/s": steady_friction(v) for v in speeds},
        "spring_bias_N_per_mm": {"A,B,C": 0.04 * K_TRUE / 1e3, "D": 0.15 * K_TRUE / 1e3},
        "effects": {"A": "none", "B": "time_drift b=-0.25 tau=40 s t0=0",
                    "C": "normal_load alpha=0.8 N0=3.5 kN, load 2->5 kN linear in t over 112 s",
                    "D": "none (spring-rate error 15%)"},
    }


SEEDS = {"A": 101, "B": 102, "C": 103, "D": 104}


def write(case: str, path: str, seed: int | None = None) -> np.ndarray:
    """Simulate ``case`` and write the user's CSV to ``path``; returns the log's rows (t,
    x_meas [mm], F_user, load, x_true [mm], v_true [mm/s], friction, net force, P [kPa])."""
    rows, _ = simulate(case, SEEDS[case] if seed is None else seed)
    with open(path, "w") as fh:
        if case == "C":
            fh.write("time [s],x [mm],applied_force [N],normal_load [kN]\n")
            for r in rows:
                fh.write(f"{r[0]:.5f},{r[1]:.3f},{r[2]:.1f},{r[3]:.3f}\n")
        else:
            fh.write("time [s],x [mm],applied_force [N]\n")
            for r in rows:
                fh.write(f"{r[0]:.5f},{r[1]:.3f},{r[2]:.1f}\n")
    return rows


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in SEEDS:
        sys.exit("usage: python -m synth.control_valve {A,B,C,D} OUT.csv")
    write(sys.argv[1], sys.argv[2])
