"""A linear guideway (carriage on rails) with LuGre friction, simulated apart from the project.

Written from the README alone for a trial of `fit` then `diagnose` as a new user runs them
(README, Diagnosis, "On recordings made apart from this project"); kept so that trial can be
run again. numpy + stdlib only: nothing from leuven-friction is imported, and nothing here
follows the project's own generators (another friction law, integrator, sensor and schedule).

    python -m synth.guideway OUTDIR [CASE ...]   # CASE: a_control b_drift_ripple c_control2 d_load
                                                 #       b2_drift_ripple_fastramps

Plant: m = 8.5 kg, m*a = u - k(t,x,N) * F_lugre.
LuGre: g(v) = Fc + (Fs-Fc) exp(-(v/vs)^2); dz/dt = v - sigma0 |v| z / g(v);
       F = sigma0 z + sigma1 dz/dt + sigma2 v.
Integration: semi-implicit Euler at 20 kHz (z implicit in its own decay, then v, then x with v_new).
Drive: open-loop force ramps (|u| <= 0.8 Fs, with internal loops), then a PI velocity loop
over 12 speed levels 0.5..150 mm/s in shuffled order (fixed seed), ~3.5 s held per direction,
strokes within +-60 mm.
Sensors (logged at 1 kHz): position from a 1 um linear scale (quantised, floor), force =
motor force + white noise (sd 0.3 N) + random-walk offset (sd 0.05 N at the session end).
"""
import math
import os
import sys

import numpy as np

M = 8.5
S0, S1, S2 = 2e6, 800.0, 60.0
FC, FS, VS = 18.0, 24.0, 4e-3
DT = 1.0 / 20000.0
DEC = 20                       # 20 kHz -> 1 kHz
SCALE = 1e-6                   # 1 um
KP, KI = 3000.0, 3000.0 * 30.0
AMAX = 2.0                     # m/s^2, reference rate limit
SCHEDULE_SEED = 7
LEVELS = np.geomspace(0.5e-3, 150e-3, 12)
HOLD = 3.5                     # s per direction per level
XMAX = 0.060                   # +-60 mm


def force_ramp_points():
    """Open-loop force turning points (N): below break-away (|u| <= 0.8 Fs), with internal loops."""
    a = 0.8 * FS
    return [0.0, a, 0.35 * a, 0.75 * a, 0.15 * a, a, -a, -0.3 * a, -0.7 * a, -0.1 * a, -a,
            0.5 * a, 0.1 * a, a, 0.0]


def build_schedule(rate=5.0):
    """List of segments: ('force', F_from, F_to, duration) or ('vel', target, duration)."""
    segs = []
    pts = force_ramp_points()
    segs.append(('force', 0.0, 0.0, 1.0))
    for f0, f1 in zip(pts[:-1], pts[1:]):
        segs.append(('force', f0, f1, abs(f1 - f0) / rate))
    segs.append(('force', 0.0, 0.0, 1.0))
    order = np.random.default_rng(SCHEDULE_SEED).permutation(len(LEVELS))
    for i in order:
        v = float(LEVELS[i])
        L = min(HOLD * v, 2 * XMAX)                # stroke length, strokes within +-XMAX
        k = max(1, int(round(HOLD * v / L)))         # stroke pairs (~HOLD s per direction)
        strokes = [+L / 2] + sum([[-L, +L] for _ in range(k - 1)], []) + [-L, +L / 2]
        for s in strokes:
            segs.append(('vel', math.copysign(v, s), abs(s) / v))
        segs.append(('vel', 0.0, 0.8))
    return segs, order


def simulate(seed, drift=False, ripple=False, load=False, ramp_rate=5.0):
    segs, order = build_schedule(ramp_rate)
    total = sum(s[-1] for s in segs)
    n = int(total / DT)
    # per-step drive arrays
    mode = np.zeros(n, dtype=np.int8)     # 0 force, 1 velocity
    uff = np.zeros(n)
    vtgt = np.zeros(n)
    i0 = 0
    for s in segs:
        k = int(round(s[-1] / DT))
        k = min(k, n - i0)
        if k <= 0:
            continue
        if s[0] == 'force':
            mode[i0:i0 + k] = 0
            uff[i0:i0 + k] = np.linspace(s[1], s[2], k, endpoint=False)
        else:
            mode[i0:i0 + k] = 1
            vtgt[i0:i0 + k] = s[1]
        i0 += k
    n = i0
    t_all = np.arange(n) * DT

    # normal load (measured): 4 slow steps between 800 N and 1400 N, N0 = 1000 N
    N0 = 1000.0
    if load:
        lv = [1000.0, 1400.0, 800.0, 1200.0, 900.0]
        tk = np.array([0.2, 0.4, 0.6, 0.8]) * t_all[-1]
        Nt = np.full(n, lv[0])
        for j, tj in enumerate(tk):
            # smooth 2 s transition (raised cosine)
            s_ = np.clip((t_all - tj) / 2.0, 0, 1)
            Nt += (lv[j + 1] - lv[j]) * 0.5 * (1 - np.cos(np.pi * s_))
        load_fac = (Nt / N0) ** 0.7
    else:
        Nt = None
        load_fac = np.ones(n)
    drift_fac = 1 + 0.25 * (1 - np.exp(-t_all / 30.0)) if drift else np.ones(n)
    time_fac = (drift_fac * load_fac).tolist()

    mode_l = mode.tolist(); uff_l = uff.tolist(); vt_l = vtgt.tolist()
    nlog = (n + DEC - 1) // DEC
    x_log = np.empty(nlog); u_log = np.empty(nlog); t_log = np.empty(nlog)
    x = v = z = 0.0
    vref = 0.0
    integ = 0.0
    u = 0.0
    twopi_l = 2 * math.pi / 5e-3
    exp = math.exp; sin = math.sin
    li = 0
    prev_mode = 0
    for i in range(n):
        # controller
        if mode_l[i] == 0:
            u = uff_l[i]
            vref = 0.0
        else:
            if prev_mode == 0:
                integ = u / KI          # bumpless transfer
            tgt = vt_l[i]
            dv = tgt - vref
            lim = AMAX * DT
            if dv > lim:
                dv = lim
            elif dv < -lim:
                dv = -lim
            vref += dv
            e = vref - v
            integ += e * DT
            u = KP * e + KI * integ
        prev_mode = mode_l[i]
        if i % DEC == 0:
            x_log[li] = x; u_log[li] = u; t_log[li] = i * DT; li += 1
        # friction (semi-implicit)
        av = v if v >= 0 else -v
        r = v / VS
        g = FC + (FS - FC) * exp(-r * r)
        zn = (z + DT * v) / (1.0 + DT * S0 * av / g)
        dz = (zn - z) / DT
        z = zn
        F = S0 * z + S1 * dz + S2 * v
        fac = time_fac[i]
        if ripple:
            fac *= 1 + 0.08 * sin(twopi_l * x + 0.4)
        F *= fac
        v = v + DT * (u - F) / M
        x = x + DT * v
    rng = np.random.default_rng(seed)
    pos = np.floor(x_log / SCALE) * SCALE
    offset = np.cumsum(rng.normal(0, 0.05 / math.sqrt(nlog), nlog))
    force = u_log + rng.normal(0, 0.3, nlog) + offset
    out = {'time [s]': t_log, 'position [mm]': pos * 1e3, 'force [N]': force}
    if load:
        out['normal_load [N]'] = Nt[::DEC][:nlog] + rng.normal(0, 2.0, nlog)
    return out, order


def write(path, cols):
    names = list(cols)
    fmts = {'time [s]': '%.3f', 'position [mm]': '%.3f', 'force [N]': '%.4f',
            'normal_load [N]': '%.2f'}
    arr = np.column_stack([cols[k] for k in names])
    np.savetxt(path, arr, delimiter=',', header=','.join(names), comments='',
               fmt=[fmts[k] for k in names])


CASES = {
    'a_control': dict(seed=101),
    'b_drift_ripple': dict(seed=102, drift=True, ripple=True),
    'c_control2': dict(seed=103),
    'd_load': dict(seed=104, load=True),
    # as (b) but force ramps at 20 N/s instead
    # of 5 N/s, so the ramps end at ~12 s and most of the tau = 30 s drift happens during the sweep
    'b2_drift_ripple_fastramps': dict(seed=102, drift=True, ripple=True, ramp_rate=20.0),
}
DEFAULT = ['a_control', 'b_drift_ripple', 'c_control2', 'd_load']

if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit('usage: python -m synth.guideway OUTDIR [CASE ...] (cases: ' + ', '.join(CASES) + ')')
    outdir = sys.argv[1]
    os.makedirs(outdir, exist_ok=True)
    which = sys.argv[2:] or DEFAULT
    for name in which:
        if name not in CASES:
            sys.exit(f'{name}: not a case (one of: {", ".join(CASES)})')
        cols, order = simulate(**CASES[name])
        p = os.path.join(outdir, f'{name}.csv')
        write(p, cols)
        x = cols['position [mm]']
        print(f'{name}: {len(x)} rows, {cols["time [s]"][-1]:.1f} s, x in [{x.min():.3f}, {x.max():.3f}] mm,'
              f' level order (mm/s): {np.round(LEVELS[order] * 1e3, 2).tolist()}')
