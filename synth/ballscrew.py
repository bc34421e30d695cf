"""A ball-screw axis, simulated apart from the project, logged in inches and pound-force.

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators (README, Diagnosis, "On recordings made apart from
this project"); kept so that trial runs again (``tests/slow/test_diagnose_ballscrew.py``).
numpy + stdlib only: nothing from leuven-friction is imported.

    python -m synth.ballscrew OUTDIR   # writes A (control) and B (friction drifting +15 %
                                       # over the session), each in in/lbf and in mm/N

Plant: effective translating mass m driven by a motor force (reflected through the screw).
Friction: 4-element Maxwell-slip (elasto-plastic elements whose slip limits are alpha_i*S(v),
S(v) = Fc + (Fs-Fc) exp(-(|v|/vs)^delta)), a damping c_i on each *stuck* element, plus viscous
sigma2*v.  Steady sliding friction = S(v) + sigma2 v.  Optional drift: whole friction scaled by
(1 + drift * t / T_session).
Integration: semi-implicit Euler at 10 kHz, logged (decimated) at 500 Hz.
Sensors: linear scale quantised to 2e-5 in; logged motor force with white noise 0.3 lbf.
Schedule: open-loop force ramps with reversals below breakaway, then a PI velocity loop over
8 speed levels (each both ways) in shuffled order.
Output: CSV in inches and pound-force:  time [s], position [in], force [lbf]
"""
import sys
import math
import numpy as np

IN = 0.0254               # m per inch
LBF = 4.4482216152605     # N per lbf

# ---- true parameters (SI) ----
M = 25.0                  # kg
FS, FC, VS, DELTA, SIG2 = 200.0, 150.0, 5e-3, 2.0, 800.0
ALPHA = [0.1, 0.2, 0.3, 0.4]
DELTA_BREAK = [3e-6, 8e-6, 15e-6, 30e-6]            # element break displacement at Fs
K = [a * FS / d for a, d in zip(ALPHA, DELTA_BREAK)]
KTOT = sum(K)
CDAMP = [2 * 0.5 * math.sqrt(KTOT * M) * k / KTOT for k in K]

DT = 1e-4                 # internal step
DEC = 20                  # 10 kHz -> 500 Hz
QUANT = 2e-5 * IN         # scale resolution (m)
FNOISE = 0.3 * LBF        # N


def stribeck(v):
    return FC + (FS - FC) * math.exp(-abs(v / VS) ** DELTA)


def schedule(rng):
    """Return list of segments: ('F', t_len, F0, F1) open loop; ('V', t_len, v0, v1) PI loop."""
    segs = [('F', 1.0, 0.0, 0.0)]
    pts = [0.0, 0.7, 0.2, 0.8, -0.6, -0.2, -0.8, 0.5, 0.1, 0.75, -0.75, 0.0]
    rate = 100.0  # N/s
    for a, b in zip(pts[:-1], pts[1:]):
        segs.append(('F', abs(b - a) * FS / rate, a * FS, b * FS))
    segs.append(('F', 1.0, 0.0, 0.0))
    speeds = np.array([1, 2, 4, 8, 16, 32, 64, 128]) * 1e-3
    rng.shuffle(speeds)
    for v in speeds:
        T = float(np.clip(0.12 / v, 1.5, 4.5))
        for s in (+1, -1):
            segs.append(('V', 0.1, 0.0, s * v))
            segs.append(('V', T, s * v, s * v))
            segs.append(('V', 0.1, s * v, 0.0))
            segs.append(('V', 0.3, 0.0, 0.0))
    return segs, speeds


def simulate(drift, seed):
    rng = np.random.default_rng(seed)
    segs, speeds = schedule(rng)
    total = sum(s[1] for s in segs)
    nsteps = int(round(total / DT))
    x = v = 0.0
    z = [0.0] * 4
    integ = 0.0
    kp, ki = 7850.0, 2.5e5
    log_t, log_x, log_f = [], [], []
    step = 0
    Ff = 0.0
    for kind, tl, a, b in segs:
        n = int(round(tl / DT))
        for j in range(n):
            t = step * DT
            frac = j / n
            if kind == 'F':
                F = a + (b - a) * frac
                integ = F   # bumpless hand-over to the velocity loop
            else:
                vref = a + (b - a) * frac
                e = vref - v
                integ += ki * e * DT
                F = kp * e + integ
            if step % DEC == 0:
                log_t.append(t); log_x.append(x); log_f.append(F)
            # friction from the current state
            scale = 1.0 + drift * t / total
            v = v + DT * (F - Ff) / M
            dx = v * DT
            x += dx
            lim_s = scale * stribeck(v)
            Ff = 0.0
            for i in range(4):
                zmax = ALPHA[i] * lim_s / K[i]
                zn = z[i] + dx
                if zn > zmax:
                    zn = zmax; stuck = False
                elif zn < -zmax:
                    zn = -zmax; stuck = False
                else:
                    stuck = True
                z[i] = zn
                Ff += K[i] * zn + (CDAMP[i] * v if stuck else 0.0)
            Ff += scale * SIG2 * v
            step += 1
    t = np.array(log_t); xs = np.array(log_x); f = np.array(log_f)
    xq = np.round(xs / QUANT) * QUANT
    fm = f + rng.normal(0, FNOISE, f.size)
    return t, xq, fm, speeds


def write(path, t, x, f, units):
    if units == 'in':
        cols = 'time [s],position [in],force [lbf]'
        data = np.column_stack([t, x / IN, f / LBF])
        fmt = ['%.4f', '%.7f', '%.4f']
    else:
        cols = 'time [s],position [mm],force [N]'
        data = np.column_stack([t, x * 1e3, f])
        fmt = ['%.4f', '%.6f', '%.4f']
    np.savetxt(path, data, delimiter=',', header=cols, comments='', fmt=fmt)


if __name__ == '__main__':
    out = sys.argv[1] if len(sys.argv) > 1 else '/tmp/nu'
    for name, drift, seed in (('A', 0.0, 11), ('B', 0.15, 12)):
        t, x, f, speeds = simulate(drift, seed)
        write(f'{out}/{name}.csv', t, x, f, 'in')
        write(f'{out}/{name}_mm.csv', t, x, f, 'mm')
        print(name, len(t), 'samples', f'{t[-1]:.1f} s', 'speeds mm/s', np.round(speeds * 1e3, 1),
              f'x range {x.min()*1e3:.1f}..{x.max()*1e3:.1f} mm')
    print('truth SI: Fs=%g N Fc=%g N vs=%g m/s delta=%g sigma2=%g N s/m m=%g kg' % (FS, FC, VS, DELTA, SIG2, M))
    print('truth in/lbf: Fs=%.4f lbf Fc=%.4f lbf vs=%.5f in/s sigma2=%.4f lbf s/in' % (
        FS / LBF, FC / LBF, VS / IN, SIG2 * IN / LBF))
