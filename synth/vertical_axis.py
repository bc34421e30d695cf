"""Vertical Z axis on a ball screw: independent simulator (numpy only).

Written from the leuven-friction README alone; nothing imported from the package.

Plant (x up, metres):
    M*a = F_motor - m*g + F_gs(x) - F_fric
    M   = m + J*(2*pi/lead)**2   (carriage 40 kg + motor rotor/screw J = 2e-4 kg m^2 reflected)
    F_gs = F0 + k_gs*(x0 - x)    (gas-spring counterbalance; case C: none)
    F_fric: LuGre, dz/dt = v - sigma0*|v|*z/g(v), F = sigma0*z + sigma1*dz/dt + sigma2*v
            g(v) = Fc_dir + (Fs - Fc_dir)*exp(-(|v|/vs)^2), Fc_dir 120 N up / 100 N down
    case B: g and sigma2 x (1 + 0.2*(1 - exp(-t/30 s)))  (warm-up)
Motor: current loop (first-order, tau 0.2 ms), F = I*Kt*2*pi/lead.
Sensors: rotary encoder on the screw, 4096 counts/rev, logged as motor angle [deg];
         current logged in A with 0.5 % of 3 A full scale noise (15 mA rms) and +20 mA offset.
Log: time [ms] at 2 kHz, a few rows dropped.

Usage: python -m synth.vertical_axis CASE OUT.csv [seed]     CASE in A, B, C
"""
import math
import sys

import numpy as np

# ---- truth ----------------------------------------------------------------
m = 40.0
g0 = 9.81
J = 2e-4
lead = 0.010
Kt = 0.8
KF = Kt * 2 * math.pi / lead          # N per A  (502.65)
M = m + J * (2 * math.pi / lead) ** 2  # 118.96 kg
k_gs = 3000.0
x0 = 0.150
F0 = 400.0                            # ~ m*g = 392.4 N
sigma0 = 2e7
sigma1 = 2 * math.sqrt(sigma0 * m) * 0.2
Fs = 160.0
Fc_up, Fc_dn = 120.0, 100.0
vs = 0.005
delta = 2.0
sigma2 = 800.0
counts_per_rev = 4096
step_m = lead / counts_per_rev        # 2.44 um
deg_per_count = 360.0 / counts_per_rev

DT = 5e-5          # physics 20 kHz
CTRL = 5           # controller every 5 steps: 4 kHz
LOG = 10           # log every 10 steps: 2 kHz


def build_reference(rng, x_start):
    """Position reference (at controller rate) for the constant-velocity strokes."""
    dtc = DT * CTRL
    speeds = np.geomspace(0.001, 0.100, 8)
    jobs = [(s, d) for s in speeds for d in (+1, -1)]
    order = rng.permutation(len(jobs))
    lo, hi = 0.020, 0.280
    acc = 2.0
    ref = []
    pos = x_start

    def hold(T):
        ref.extend([pos] * int(round(T / dtc)))

    def smooth_move(target):
        nonlocal pos
        d = target - pos
        T = max(0.6, 2.0 * abs(d) / 0.15)
        n = int(round(T / dtc))
        s = np.arange(1, n + 1) / n
        ref.extend(list(pos + d * (10 * s**3 - 15 * s**4 + 6 * s**5)))
        pos = target

    def stroke(v, L, d):
        nonlocal pos
        ta = v / acc
        T = L / v + ta                 # trapezoid: total travel L
        n = int(round(T / dtc))
        t = np.arange(1, n + 1) * dtc
        # travel of trapezoid with accel ta and decel ta
        tr = np.where(t < ta, 0.5 * acc * t**2,
                      np.where(t < T - ta, 0.5 * acc * ta**2 + v * (t - ta),
                               L - 0.5 * acc * np.clip(T - t, 0, None) ** 2))
        ref.extend(list(pos + d * tr))
        pos = pos + d * L

    hold(0.5)
    for j in order:
        v, d = jobs[j]
        L = min(0.260, v * 5.0)
        if d > 0 and pos + L > hi:
            smooth_move(lo)
            hold(0.3)
        if d < 0 and pos - L < lo:
            smooth_move(hi)
            hold(0.3)
        stroke(v, L, d)
        hold(0.3)
    smooth_move(x0)
    hold(0.5)
    return np.array(ref), [(float(jobs[j][0]), jobs[j][1]) for j in order]


def simulate(case, seed):
    rng = np.random.default_rng(seed)
    gas = case in ("A", "B")
    warm = case == "B"
    bias_F = 0.0 if gas else m * g0       # the user's gravity feed-forward (constant)

    x, v, z = x0 + 0.0003, 0.0, 0.0
    I_act = 0.0
    tau_i = 2e-4
    ki = math.exp(-DT / tau_i)

    log_t, log_x, log_I = [], [], []
    t = 0.0
    step = 0
    I_cmd = bias_F / KF

    def plant_steps(nsteps):
        nonlocal x, v, z, I_act, t, step
        for _ in range(nsteps):
            fac = 1.0 + 0.2 * (1.0 - math.exp(-t / 30.0)) if warm else 1.0
            I_act = I_cmd + (I_act - I_cmd) * ki
            Fm = KF * I_act
            av = abs(v)
            Fc = Fc_up if v >= 0 else Fc_dn
            gv = (Fc + (Fs - Fc) * math.exp(-(av / vs) ** delta)) * fac
            a = sigma0 * av / gv
            if a * DT < 1e-9:
                zn = z + v * DT
            else:
                zss = v / a
                zn = zss + (z - zss) * math.exp(-a * DT)
            zd = (zn - z) / DT
            z = zn
            Ff = sigma0 * z + sigma1 * zd + sigma2 * fac * v
            Fext = -m * g0 + ((F0 + k_gs * (x0 - x)) if gas else 0.0)
            v += DT * (Fm + Fext - Ff) / M
            x += DT * v
            t += DT
            step += 1
            if step % LOG == 0:
                log_t.append(t)
                log_x.append(x)
                log_I.append(I_act)

    def enc():
        return math.floor(x / step_m) * step_m

    # ---- 1. slow current ramps that break loose (trip at 1 mm, ramp back) ----
    for direction in (+1, -1, +1, -1):
        xs = enc()
        F = 0.0
        rate = 60.0      # N/s
        while abs(enc() - xs) < 0.001 and abs(F) < 400:
            F += direction * rate * DT * CTRL
            I_cmd = (bias_F + F) / KF
            plant_steps(CTRL)
        while F * direction > 0:
            F -= direction * 300.0 * DT * CTRL
            I_cmd = (bias_F + F) / KF
            plant_steps(CTRL)
        I_cmd = bias_F / KF
        plant_steps(int(1.0 / DT))

    # ---- 2. small presliding oscillations (force sines, no gross sliding) ----
    for amp, freq, cycles in ((110.0, 0.5, 3), (60.0, 1.0, 3), (130.0, 0.25, 2)):
        n = int(round(cycles / freq / (DT * CTRL)))
        for i in range(n):
            tt = (i + 1) * DT * CTRL
            I_cmd = (bias_F + amp * math.sin(2 * math.pi * freq * tt)) / KF
            plant_steps(CTRL)
        I_cmd = bias_F / KF
        plant_steps(int(0.5 / DT))

    # ---- 3. PID position loop, constant-velocity strokes --------------------
    ref, plan = build_reference(rng, enc())
    wn = 2 * math.pi * 25.0
    Kp = M * wn**2
    Kd = 2 * 0.8 * wn * M
    Ki = Kp * wn / 8
    dtc = DT * CTRL
    integ = 0.0
    vf = 0.0
    alpha = math.exp(-dtc * 2 * math.pi * 300.0)  # derivative filter 300 Hz
    xprev = enc()
    Imax = 4.0
    for r in ref:
        xm = enc()
        vraw = (xm - xprev) / dtc
        xprev = xm
        vf = alpha * vf + (1 - alpha) * vraw
        e = r - xm
        integ += e * dtc
        u = bias_F + Kp * e + Ki * integ - Kd * vf
        I_cmd = max(-Imax, min(Imax, u / KF))
        plant_steps(CTRL)

    tt = np.array(log_t)
    xx = np.array(log_x)
    II = np.array(log_I)
    counts = np.floor(xx / step_m)
    angle = counts * deg_per_count
    Imeas = II + 0.015 * rng.standard_normal(II.size) + 0.020
    keep = np.ones(tt.size, bool)
    drop = rng.choice(np.arange(100, tt.size - 100), size=12, replace=False)
    keep[drop] = False
    return tt[keep], angle[keep], Imeas[keep], plan


SEEDS = {"A": 11, "B": 12, "C": 13}


def write(case: str, out: str, seed: int | None = None) -> None:
    """Simulate ``case`` and write the user's CSV (time in ms, the motor's angle in degrees,
    its current in A) to ``out``."""
    t, ang, cur, _ = simulate(case, SEEDS[case] if seed is None else seed)
    with open(out, "w") as f:
        f.write("time [ms],motor_angle [deg],motor_current [A]\n")
        for a, b, c in zip(t, ang, cur):
            f.write(f"{a*1e3:.1f},{b:.6f},{c:.5f}\n")


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4) or sys.argv[1] not in SEEDS:
        sys.exit("usage: python -m synth.vertical_axis {A,B,C} OUT.csv [seed]")
    write(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else None)
