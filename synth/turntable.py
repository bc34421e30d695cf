"""A small turntable (rotary stage) with a Dahl-type contact, simulated apart from the project.

Written for a trial of `fit` then `diagnose` on a machine far from the paper's robot joint in
scale (friction under half a N·m, 0.035 kg·m²) and logged in other units. numpy + stdlib only:
nothing from leuven-friction is imported, and nothing here follows the project's generators
(another friction law, integrator, sensor, schedule and units).

    python -m synth.turntable OUTDIR [CASE ...]   # CASE: control, control2, drift

Plant: J dω/dt = u − T_f, J = 0.035 kg·m².
Contact: Dahl's model (exponent 1) with a Stribeck limit g(ω) = T_c + (T_s − T_c)·e^(−|ω|/ω_s)
(an exponential Stribeck curve: δ = 1), dT_d/dθ = σ0·(1 − T_d·sgn(dθ)/g(ω)), integrated exactly
over each step's angle increment with g held (T_d relaxes to ±g as e^(−σ0|Δθ|/g)), plus viscous
friction σ2·ω. No micro-damping: the contact has no σ1.
Integration: semi-implicit Euler at 5 kHz (friction from the step's start, then ω, then θ).
Drive: open-loop torque ramps to ±0.8 T_s with internal loops (presliding), then a PI velocity
loop over 10 speeds 0.004…1.5 rad/s in two passes, each in a shuffled order (fixed seed), each
speed held 2.5 s in each direction a pass.
Sensors (logged at 1 kHz): a 2^16-count encoder (9.6·10⁻⁵ rad a count, floor), written in
degrees; the motor torque command with white noise (1.5 mN·m), written in mN·m; time in ms.
Friction is not logged: `fit` takes it from the torque and the inertia it reads (eq. (8)).
"""
import math
import os
import sys

import numpy as np

J = 0.035                                  # kg·m²
TC, TS, WS = 0.42, 0.55, 0.08              # N·m, N·m, rad/s
SIGMA0, SIGMA2 = 60.0, 0.03                # N·m/rad (presliding over ~g/σ0 = 7 mrad), N·m·s/rad
DT = 1.0 / 5000.0
DEC = 5                                    # 5 kHz -> 1 kHz
COUNT = 2 * math.pi / 2 ** 16              # rad
KP, KI = 2.0, 2.0 * 25.0                   # PI velocity loop, N·m per rad/s
AMAX = 20.0                                # rad/s², reference rate limit
SCHEDULE_SEED = 11
LEVELS = np.geomspace(0.004, 1.5, 10)      # rad/s
HOLD = 2.5                                 # s per direction per level
PASSES = 2                                 # over the levels
RAMP_RATE = 0.1                            # N·m/s


def torque_ramp_points():
    """Open-loop torque turning points (N·m), below break-away (|u| ≤ 0.8 T_s), with internal loops."""
    a = 0.8 * TS
    return [0.0, a, 0.3 * a, 0.8 * a, 0.1 * a, a, -a, -0.4 * a, -0.8 * a, -0.05 * a, -a, 0.6 * a, 0.2 * a, a, 0.0]


def build_schedule(ramp_rate=RAMP_RATE):
    """Segments ('torque', u_from, u_to, duration) or ('vel', target, duration), and the level order."""
    segs = [('torque', 0.0, 0.0, 0.5)]
    pts = torque_ramp_points()
    segs += [('torque', a, b, abs(b - a) / ramp_rate) for a, b in zip(pts[:-1], pts[1:])]
    segs.append(('torque', 0.0, 0.0, 0.5))
    rng = np.random.default_rng(SCHEDULE_SEED)
    # two passes over the levels, each in its own shuffled order: a speed seen at two times
    # tells a change in time from the shape of S(v)
    order = np.concatenate([rng.permutation(len(LEVELS)) for _ in range(PASSES)])
    for i in order:
        w = float(LEVELS[i])
        segs += [('vel', w, HOLD), ('vel', -w, HOLD), ('vel', 0.0, 0.5)]
    return segs, order


def simulate(seed, drift=None, ramp_rate=RAMP_RATE):
    """The logged columns and the level order; ``drift``: (b, τ) multiplies the whole friction by
    1 + b·(1 − e^(−t/τ)) (a warm-up); ``ramp_rate``: of the opening torque ramps (N·m/s)."""
    segs, order = build_schedule(ramp_rate)
    mode, uff, wt = [], [], []
    for s in segs:
        k = int(round(s[-1] / DT))
        if s[0] == 'torque':
            mode += [0] * k
            uff += np.linspace(s[1], s[2], k, endpoint=False).tolist()
            wt += [0.0] * k
        else:
            mode += [1] * k
            uff += [0.0] * k
            wt += [s[1]] * k
    n = len(mode)
    fac = ([1.0 + drift[0] * (1.0 - math.exp(-i * DT / drift[1])) for i in range(n)] if drift else [1.0] * n)
    nlog = (n + DEC - 1) // DEC
    th_log, u_log = np.empty(nlog), np.empty(nlog)
    th = w = td = 0.0
    wref = integ = u = 0.0
    prev = 0
    exp = math.exp
    li = 0
    for i in range(n):
        if mode[i] == 0:
            u, wref = uff[i], 0.0
        else:
            if prev == 0:
                integ = u / KI                 # bumpless transfer from the last torque
            dw = max(-AMAX * DT, min(AMAX * DT, wt[i] - wref))
            wref += dw
            e = wref - w
            integ += e * DT
            u = KP * e + KI * integ
        prev = mode[i]
        if i % DEC == 0:
            th_log[li], u_log[li] = th, u
            li += 1
        tf = fac[i] * (td + SIGMA2 * w)
        w += DT * (u - tf) / J
        dth = DT * w
        th += dth
        if dth != 0.0:
            g = TC + (TS - TC) * exp(-abs(w) / WS)
            s = 1.0 if dth > 0 else -1.0
            td = s * g + (td - s * g) * exp(-SIGMA0 * abs(dth) / g)
    rng = np.random.default_rng(seed)
    cols = {'t [ms]': np.arange(nlog) * DT * DEC * 1e3,
            'angle [deg]': np.degrees(np.floor(th_log / COUNT) * COUNT),
            'torque [mN*m]': (u_log + rng.normal(0.0, 1.5e-3, nlog)) * 1e3}
    return cols, order


def steady_friction(w):
    """The contact's friction while turning steadily at w (rad/s): g(w)·sgn w + σ2·w."""
    w = np.asarray(w, float)
    return np.sign(w) * (TC + (TS - TC) * np.exp(-np.abs(w) / WS)) + SIGMA2 * w


def write(path, cols):
    names = list(cols)
    fmts = {'t [ms]': '%.1f', 'angle [deg]': '%.6f', 'torque [mN*m]': '%.3f'}
    np.savetxt(path, np.column_stack([cols[k] for k in names]), delimiter=',', header=','.join(names),
               comments='', fmt=[fmts[k] for k in names])


# the drift's ramps four times faster (12 s, not 50 s): a warm-up of τ = 40 s is still under way
# when the sliding begins
CASES = {'control': dict(seed=201), 'control2': dict(seed=202), 'drift': dict(seed=203, drift=(0.3, 40.0), ramp_rate=0.4)}

if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit('usage: python -m synth.turntable OUTDIR [CASE ...] (cases: ' + ', '.join(CASES) + ')')
    outdir = sys.argv[1]
    os.makedirs(outdir, exist_ok=True)
    for name in sys.argv[2:] or list(CASES):
        if name not in CASES:
            sys.exit(f'{name}: not a case (one of: {", ".join(CASES)})')
        cols, order = simulate(**CASES[name])
        p = os.path.join(outdir, f'{name}.csv')
        write(p, cols)
        print(f'{name}: {len(cols["t [ms]"])} rows, {cols["t [ms]"][-1] / 1e3:.1f} s, '
              f'level order (rad/s): {np.round(LEVELS[order], 4).tolist()}')
