"""A belt-driven pick-and-place gantry axis, simulated apart from the project (numpy + numba).

Written from the README alone for a trial of `fit` then `diagnose` as a new user runs them;
kept so that trial can be run again. Nothing from leuven-friction is imported. Recordings:
a_control, b_runin (a seal running in: friction × (1 + 0.25·(1 − e^(−t/40 s)))), c_ripple (the
belt's teeth: 5 mm, 8 % and a second harmonic of 4 %), each as *_raw.csv (motor current in A)
and *.csv (the force constant as its unit). Measured on this project's version of 2026-12-02,
with `--columns force=motor_current`: (a) nothing named; (b) time_drift, b 0.233 ± 0.02,
τ 36.6 ± 3.8 s; (c) position_ripple, λ 4.986 mm, a 0.088, a2 0.050.


Carriage 3.7 kg (+ reflected motor/pulley inertia 0.06 kg), friction: 4 Maxwell-slip elements
(GMS-like, damped while stuck) whose slip limits follow an exponential Stribeck curve
(exponent 1.6), plus viscous friction. Motor: force constant 5.9 N/A, first-order current loop
(0.25 ms), current saturated at 8 A. PD position controller at 5 kHz on a 1 um encoder, velocity
from the difference filtered at 150 Hz. Semi-implicit Euler at 50 kHz, logged at 1 kHz.

usage: python -m synth.belt_axis OUTDIR
"""
import sys, os
import numpy as np
import numba

TRUTH = dict(
    m=3.7, m_motor=0.06, Kf=5.9,
    Fs_pos=14.0, Fc_pos=11.0, Fs_neg=13.5, Fc_neg=10.6, vs=4e-3, delta=1.6, sigma2=25.0,
    alpha=np.array([0.35, 0.30, 0.20, 0.15]),
    brk=np.array([1.5e-6, 5e-6, 14e-6, 35e-6]),  # breakaway displacement of each element at Fs
)
DT = 2e-5
CTRL_EVERY = 10       # 5 kHz
LOG_EVERY = 50        # 1 kHz


def make_reference(rng, ctrl_dt=DT * CTRL_EVERY):
    """Reference velocity on the control grid: two shuffled speed sweeps and two presliding blocks."""
    speeds = np.array([0.4, 1.0, 2.0, 3.5, 6.0, 10.0, 16.0, 25.0, 40.0, 65.0, 100.0]) * 1e-3
    acc = 1.0
    vel = []

    def dwell(T):
        vel.extend([0.0] * int(round(T / ctrl_dt)))

    def move(dist, v):
        # trapezoid (or triangle) of signed distance dist at speed |v|
        s = np.sign(dist); d = abs(dist); v = abs(v)
        ta = v / acc
        if acc * ta ** 2 > d:
            ta = np.sqrt(d / acc); v = acc * ta; tc = 0.0
        else:
            tc = (d - acc * ta ** 2) / v
        n_a = int(np.ceil(ta / ctrl_dt)); n_c = int(round(tc / ctrl_dt))
        up = np.linspace(0, v, n_a + 1)[1:]
        prof = np.concatenate([up, np.full(n_c, v), up[::-1]])
        prof *= d / (prof.sum() * ctrl_dt)   # exact distance
        vel.extend(list(s * prof))

    def sweep(order):
        for v in order:
            d = float(np.clip(v * 1.2, 1.5e-3, 80e-3))
            move(+d, v); dwell(0.25); move(-d, v); dwell(0.25)

    def presliding(amps):
        # triangles of the reference about the current point, 1 Hz, 2 cycles each
        for a in amps:
            for _ in range(2):
                v = 4 * a / 1.0   # 1 s period, amplitude a
                for sgn in (+1, -1, -1, +1):
                    vel.extend([sgn * v] * int(round(0.25 / ctrl_dt)))
            dwell(0.5)

    dwell(0.5)
    sweep(rng.permutation(speeds))
    dwell(0.5)
    presliding([30e-6, 5e-6, 100e-6, 15e-6, 60e-6])
    sweep(rng.permutation(speeds))
    dwell(0.5)
    presliding([60e-6, 15e-6, 5e-6, 100e-6, 30e-6])
    dwell(0.5)
    vref = np.array(vel)
    xref = np.concatenate([[0.0], np.cumsum(vref[:-1] * ctrl_dt)])
    return xref, vref


@numba.njit(cache=True)
def run(xref, vref, kind, m, Kf, Fsp, Fcp, Fsn, Fcn, vs, delta, sig2, alpha, k, c,
        Kp, Kd, fc_vel, tau_i, Imax, enc, dt, ctrl_every, log_every):
    nctrl = xref.size
    nsteps = nctrl * ctrl_every
    nlog = nsteps // log_every
    x = 0.0; v = 0.0; I = 0.0; Icmd = 0.0
    z = np.zeros(k.size)
    stuck = np.ones(k.size, dtype=np.bool_)
    xm_prev = 0.0; vest = 0.0
    cdt = dt * ctrl_every
    a_lp = 1.0 - np.exp(-2 * np.pi * fc_vel * cdt)
    b_i = 1.0 - np.exp(-dt / tau_i)
    out_x = np.zeros(nlog); out_I = np.zeros(nlog); out_F = np.zeros(nlog); out_t = np.zeros(nlog)
    Ff = 0.0
    j = 0
    for n in range(nsteps):
        t = n * dt
        if n % ctrl_every == 0:
            ic = n // ctrl_every
            xm = np.round(x / enc) * enc
            vraw = (xm - xm_prev) / cdt
            xm_prev = xm
            vest += a_lp * (vraw - vest)
            u = Kp * (xref[ic] - xm) + Kd * (vref[ic] - vest)
            Icmd = min(max(u / Kf, -Imax), Imax)
        I += b_i * (Icmd - I)
        if n % log_every == 0 and j < nlog:
            out_t[j] = t; out_x[j] = x; out_I[j] = I; out_F[j] = Ff
            j += 1
        # hidden multiplier
        mult = 1.0
        if kind == 1:
            mult = 1.0 + 0.25 * (1.0 - np.exp(-t / 40.0))
        elif kind == 2:
            ph = 2 * np.pi * x / 5e-3
            mult = 1.0 + 0.08 * np.sin(ph) + 0.04 * np.sin(2 * ph + 0.7)
        # friction from state (z, v)
        Ff = sig2 * v * mult
        for i in range(k.size):
            Ff += k[i] * z[i]
            if stuck[i]:
                Ff += c[i] * v
        v += dt * (Kf * I - Ff) / m
        x += dt * v
        # Stribeck limit at the new velocity
        if v >= 0:
            s = Fcp + (Fsp - Fcp) * np.exp(-(abs(v) / vs) ** delta)
        else:
            s = Fcn + (Fsn - Fcn) * np.exp(-(abs(v) / vs) ** delta)
        s *= mult
        for i in range(k.size):
            z[i] += v * dt
            lim = alpha[i] * s / k[i]
            if z[i] > lim:
                z[i] = lim; stuck[i] = False
            elif z[i] < -lim:
                z[i] = -lim; stuck[i] = False
            else:
                stuck[i] = True
    return out_t, out_x, out_I, out_F


def simulate(kind, seed=7):
    rng = np.random.default_rng(seed)
    T = TRUTH
    xref, vref = make_reference(np.random.default_rng(1234))  # same profile for all three
    k = T['alpha'] * T['Fs_pos'] / T['brk']
    c = k * 1e-4
    m = T['m'] + T['m_motor']
    t, x, I, F = run(xref, vref, kind, m, T['Kf'], T['Fs_pos'], T['Fc_pos'], T['Fs_neg'], T['Fc_neg'],
                     T['vs'], T['delta'], T['sigma2'], T['alpha'], k, c,
                     3.0e5, 1500.0, 150.0, 2.5e-4, 8.0, 1e-6, DT, CTRL_EVERY, LOG_EVERY)
    pos_mm = np.round(x / 1e-6) * 1e-3
    cur = I + 0.025 + rng.normal(0, 0.012, I.size)
    cur = np.round(cur, 4)
    t_ms = np.round(t * 1e3).astype(int)
    return t_ms, pos_mm, cur, x, I, F


def write(path, t_ms, pos_mm, cur, header=('time [ms]', 'position [mm]', 'motor_current [A]'), sep=',',
          dec='.', units_row=None, comment=None):
    with open(path, 'w', encoding='utf-8') as f:
        if comment:
            for line in comment:
                f.write('# ' + line + '\n')
        f.write(sep.join(header) + '\n')
        if units_row:
            f.write(sep.join(units_row) + '\n')
        for a, b, c_ in zip(t_ms, pos_mm, cur):
            row = f"{a:d}{sep}{b:.3f}{sep}{c_:.4f}"
            if dec != '.':
                row = f"{a:d}{sep}{b:.3f}".replace('.', dec) + sep + f"{c_:.4f}".replace('.', dec)
            f.write(row + '\n')


if __name__ == '__main__':
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for kind, name in [(0, 'a_control'), (1, 'b_runin'), (2, 'c_ripple')]:
        t_ms, pos_mm, cur, x, I, F = simulate(kind, seed=10 + kind)
        write(os.path.join(out, f'{name}_raw.csv'), t_ms, pos_mm, cur)
        write(os.path.join(out, f'{name}.csv'), t_ms, pos_mm, cur,
              header=('time [ms]', 'position [mm]', 'motor_current [5.9 N]'),
              comment=['gantry X axis, belt drive, carriage 3.7 kg; motor force constant Kf = 5.9 N/A',
                       'logged at 1 kHz'])
        np.savez(os.path.join(out, f'{name}_truth.npz'), t=t_ms / 1e3, x=x, I=I, F=F)
        print(name, len(t_ms), 'rows', f'{t_ms[-1]/1e3:.1f} s', 'x range mm', pos_mm.min(), pos_mm.max(),
              'I range', cur.min(), cur.max())
