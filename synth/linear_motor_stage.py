"""A linear-motor positioning stage on profile rail guides, simulated apart from leuven-friction (numpy only).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on
motor cogging (a force along the travel, not friction) beside a friction ripple; kept so that
trial runs again (``tests/slow/test_diagnose_linear_motor_stage.py``). Nothing from
leuven-friction is imported.

Plant: carriage mass M, LuGre contact with an exponential Stribeck curve (asymmetric), viscous
friction; optional motor cogging (additive, keeps its sign both ways) and friction ripple
(a factor on friction along the travel).
Integration: 20 kHz semi-implicit Euler, bristle state z relaxed exactly over each step.
Controller: 5 kHz PID on the quantised scale with filtered derivative, velocity and
acceleration feedforward; open loop during the presliding force ramps.
Logging: 1 kHz, 0.1 um scale, motor force from current (noise + offset).

    python -m synth.linear_motor_stage OUT.csv --seed S [--cog] [--ripple]
"""
import argparse
import math

import numpy as np

# ---- plant (my own numbers) -------------------------------------------------------------
M = 11.3            # kg carriage + payload
FC_P, FC_N = 23.5, 21.8      # N Coulomb level per direction
FS_P, FS_N = 31.0, 28.9      # N static (Stribeck) level
VS = 0.0042                  # m/s Stribeck velocity
DELTA = 0.85                 # Stribeck exponent
SIG2 = 118.0                 # N s/m viscous
SIG0 = 3.1e6                 # N/m bristle stiffness
SIG1 = 0.3 * 2 * math.sqrt(SIG0 * M)   # N s/m bristle damping (~3.5e3)

# cogging (B): F_cog(x) = c1 sin(2 pi x/p + phi1) + c2 sin(4 pi x/p + phi2)
COG_P, COG_C1, COG_C2, COG_PHI1, COG_PHI2 = 0.024, 1.15, 0.40, 0.7, -1.9   # m, N, N, rad, rad
# ripple (C): friction * (1 + a sin(2 pi x/p + phi))
RIP_P, RIP_A, RIP_PHI = 0.0115, 0.05, 0.4

DT = 1.0 / 20000.0
CTRL_DIV = 4          # controller at 5 kHz
LOG_DIV = 20          # log at 1 kHz
QUANT = 1e-7          # 0.1 um scale
F_NOISE = 0.09        # N white noise on the force from current
F_OFFSET = 0.17       # N offset


def g_curve(v):
    if v >= 0:
        return FC_P + (FS_P - FC_P) * math.exp(-abs(v / VS) ** DELTA)
    return FC_N + (FS_N - FC_N) * math.exp(-abs(v / VS) ** DELTA)


def build_schedule(rng_sched):
    """List of segments: ('ramp', [(t, F)...]) open loop, or ('move', x_target, v, a), ('dwell', T)."""
    segs = []
    x0 = 0.020
    # presliding block 1: open-loop force ramps below breakaway, slow, back and forth
    pts = [0.0, 12.0, -6.0, 17.0, 4.0, -15.0, 8.0, -19.0, 0.0]   # N
    rate = 8.0   # N/s
    segs.append(('ramp', pts, rate))
    segs.append(('close', x0))
    segs.append(('dwell', 0.5))
    speeds = np.geomspace(0.0004, 0.15, 16)    # m/s
    runs = [(v, d) for v in speeds for d in (+1, -1)]
    order = rng_sched.permutation(len(runs))
    lo, hi = 0.010, 0.150
    for k in order:
        v, d = runs[k]
        dist = min(v * 2.0, 0.140)
        acc = 1.5
        segs.append(('run', v, d, dist, acc, lo, hi))
        segs.append(('dwell', 0.25))
    # presliding block 2 at the end, at another place
    segs.append(('open',))
    segs.append(('ramp', [0.0, -10.0, 14.0, -16.0, 6.0, 0.0], 8.0))
    return segs


def simulate(seed, cog=False, ripple=False, sched_seed=20240611):
    rng = np.random.default_rng(seed)
    segs = build_schedule(np.random.default_rng(sched_seed))

    x, v, z = 0.020, 0.0, 0.0
    t = 0.0
    step = 0
    log_t, log_x, log_f = [], [], []
    offset = F_OFFSET
    # controller state
    mode = 'open'
    u = 0.0
    integ = 0.0
    x_ref, v_ref, a_ref = x, 0.0, 0.0
    xm_prev = None
    dfilt = 0.0
    KP = M * (2 * math.pi * 25) ** 2
    KD = 2 * 0.8 * M * (2 * math.pi * 25)
    KI = KP * (2 * math.pi * 4)
    tau_d = 1.0 / (2 * math.pi * 120)
    alpha_d = (CTRL_DIV * DT) / (tau_d + CTRL_DIV * DT)
    # drift of the current sensor offset: slow random walk
    noise_f = rng.normal(0.0, F_NOISE, size=2_000_000)
    ni = 0

    def plant_step(u_applied):
        nonlocal x, v, z
        # friction (LuGre), z relaxed exactly for the step's velocity
        gv = g_curve(v)
        if abs(v) > 1e-12:
            zss = gv / SIG0 * (1.0 if v > 0 else -1.0)
            k = SIG0 * abs(v) / gv
            z_new = zss + (z - zss) * math.exp(-k * DT)
        else:
            z_new = z
        zdot = (z_new - z) / DT
        z = z_new
        F = SIG0 * z + SIG1 * zdot + SIG2 * v
        if ripple:
            F *= 1.0 + RIP_A * math.sin(2 * math.pi * x / RIP_P + RIP_PHI)
        Fc = 0.0
        if cog:
            Fc = (COG_C1 * math.sin(2 * math.pi * x / COG_P + COG_PHI1)
                  + COG_C2 * math.sin(4 * math.pi * x / COG_P + COG_PHI2))
        acc = (u_applied - F + Fc) / M
        v += acc * DT
        x += v * DT

    def measure():
        return math.floor(x / QUANT + 0.5) * QUANT

    def tick(u_cmd_fn):
        """one physics step; controller every CTRL_DIV, log every LOG_DIV"""
        nonlocal step, t, u, ni
        if step % CTRL_DIV == 0:
            u = u_cmd_fn()
        plant_step(u)
        step += 1
        t = step * DT
        if step % LOG_DIV == 0:
            log_t.append(t)
            log_x.append(measure())
            log_f.append(u + offset + noise_f[ni])
            ni += 1

    def pid():
        nonlocal integ, xm_prev, dfilt
        xm = measure()
        e = x_ref - xm
        if xm_prev is None:
            xm_prev = xm
        vm = (xm - xm_prev) / (CTRL_DIV * DT)
        xm_prev = xm
        dfilt += alpha_d * (vm - dfilt)
        integ += KI * e * CTRL_DIV * DT
        return KP * e + KD * (v_ref - dfilt) + integ + M * a_ref

    def profile(dist, vmax, acc):
        """trapezoid: returns total time and function s(tau) -> (pos, vel, acc)"""
        ta = vmax / acc
        if acc * ta * ta >= dist:      # triangle
            ta = math.sqrt(dist / acc)
            vmax = acc * ta
            tc = 0.0
        else:
            tc = (dist - acc * ta * ta) / vmax
        T = 2 * ta + tc

        def s(tau):
            if tau < ta:
                return 0.5 * acc * tau * tau, acc * tau, acc
            if tau < ta + tc:
                return 0.5 * acc * ta * ta + vmax * (tau - ta), vmax, 0.0
            if tau < T:
                r = T - tau
                return dist - 0.5 * acc * r * r, acc * r, -acc
            return dist, 0.0, 0.0
        return T, s

    def do_move(target, vmax, acc):
        nonlocal x_ref, v_ref, a_ref
        start = x_ref
        dist = abs(target - start)
        sgn = 1.0 if target >= start else -1.0
        if dist < 1e-9:
            return
        T, s = profile(dist, vmax, acc)
        t0 = t
        while t - t0 < T:
            p, vv, aa = s(t - t0)
            x_ref, v_ref, a_ref = start + sgn * p, sgn * vv, sgn * aa
            tick(pid)
        x_ref, v_ref, a_ref = target, 0.0, 0.0

    def do_dwell(T):
        t0 = t
        while t - t0 < T:
            tick(pid)

    for seg in segs:
        kind = seg[0]
        if kind == 'ramp':
            pts, rate = seg[1], seg[2]
            for a, b in zip(pts[:-1], pts[1:]):
                T = abs(b - a) / rate
                t0 = t
                while t - t0 < T:
                    frac = (t - t0) / T
                    uval = a + (b - a) * frac
                    tick(lambda uval=uval: uval)
            # hold at end 1 s
            t0 = t
            while t - t0 < 1.0:
                tick(lambda: pts[-1])
        elif kind == 'close':
            x_ref = measure()
            v_ref = a_ref = 0.0
            integ = u
            xm_prev = None
            dfilt = 0.0
            # slowly bring to the requested start position
            do_move(seg[1], 0.01, 0.5)
        elif kind == 'open':
            pass
        elif kind == 'dwell':
            do_dwell(seg[1])
        elif kind == 'run':
            vv, d, dist, acc, lo, hi = seg[1:]
            target = x_ref + d * dist
            if target > hi or target < lo:
                # reposition first at a moderate speed to the end it must start from
                start = lo if d > 0 else hi
                do_move(start, 0.025, 1.0)
                do_dwell(0.3)
                target = x_ref + d * dist
            do_move(target, vv, acc)
        # a little wander of the current offset
        offset += rng.normal(0.0, 0.005)
    return np.array(log_t), np.array(log_x), np.array(log_f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('out')
    ap.add_argument('--seed', type=int, required=True)
    ap.add_argument('--cog', action='store_true')
    ap.add_argument('--ripple', action='store_true')
    a = ap.parse_args()
    tt, xx, ff = simulate(a.seed, cog=a.cog, ripple=a.ripple)
    with open(a.out, 'w') as fh:
        fh.write('time [s],pos [mm],motor_force [N]\n')
        for ti, xi, fi in zip(tt, xx, ff):
            fh.write(f'{ti:.4f},{xi * 1e3:.4f},{fi:.4f}\n')
    print(f'{a.out}: {len(tt)} samples, {tt[-1]:.1f} s, x {xx.min()*1e3:.3f}..{xx.max()*1e3:.3f} mm')


if __name__ == '__main__':
    main()
