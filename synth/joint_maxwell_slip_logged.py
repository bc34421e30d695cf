"""A rotary robot joint whose friction torque is measured, simulated apart from the project.

Written without the project's code or generators, for a trial of `fit` then `diagnose` on
recordings made apart from them (README, Diagnosis, "On recordings made apart from this
project"); kept so that trial can be run again. numpy only.

Contact: a generalized Maxwell-slip of five elasto-plastic elements (weights 0.3 … 0.1, slip
limits 0.0008–0.02° at 1 N·m, each breaking away at wᵢ·S(v)); S(v) = F_c + (F_s − F_c)·
exp(−(|v|/v_s)^0.8), asymmetric (+1100/800 N·mm at v_s 2°/s, −1000/−700 N·mm at 1.5°/s);
viscous 15 N·mm/(°/s). The angle follows a commanded profile through a 60 Hz, ζ = 0.9 drive at
5 kHz: speed levels 0.05–30 °/s in random order with reversals, and oscillations of
0.002–0.02°; 120 s logged at 1 kHz. A 19-bit encoder, 4 N·mm sensor noise and a slow ±3 N·mm
offset; the friction logged with the reaction sign, in N·mm, the angle in degrees.

    python -m synth.joint_maxwell_slip_logged OUTDIR [CASE ...]   # control drift ripple softening control2
"""
import numpy as np, json, sys

FS = 1000.0
CNT = 360.0 / 2**19


def schedule(rng, T=120.0):
    """Commanded angle: speed levels 0.05..30 deg/s in random order with reversals,
    interleaved with small presliding oscillations (0.002..0.02 deg)."""
    levels = np.geomspace(0.05, 30.0, 12)
    order = rng.permutation(len(levels))
    amps = rng.permutation(np.geomspace(0.002, 0.02, 6))
    dt = 1 / FS
    v_cmd = []
    def ramp_hold(v, hold, acc=150.0):
        n_r = max(1, int(abs(v) / acc / dt))
        v_cmd.extend(np.linspace(0, v, n_r)); v_cmd.extend([v] * int(hold / dt))
        v_cmd.extend(np.linspace(v, 0, n_r))
    def dwell(t): v_cmd.extend([0.0] * int(t / dt))
    def osc(a, f, ncyc):
        t = np.arange(int(ncyc / f / dt)) * dt
        v_cmd.extend(a * 2 * np.pi * f * np.cos(2 * np.pi * f * t))   # position a*sin
    k = 0
    dwell(0.5)
    for i, j in enumerate(order):
        v = levels[j]
        hold = float(np.clip(40.0 / v, 0.8, 2.5))
        s = 1 if rng.random() < 0.5 else -1
        ramp_hold(s * v, hold); dwell(0.2); ramp_hold(-s * v, hold); dwell(0.2)
        if i % 2 == 1:  # presliding block
            a = amps[k % len(amps)]; k += 1
            osc(a, rng.uniform(0.5, 2.0), 4); dwell(0.3)
    n = int(T * FS)
    v_cmd = np.array(v_cmd)
    while len(v_cmd) < n:  # fill the rest with presliding oscillations and slow moves
        a = amps[k % len(amps)]; k += 1
        extra = []
        t = np.arange(int(4 / 1.0 / dt)) * dt
        extra = a * 2 * np.pi * np.cos(2 * np.pi * t)
        v_cmd = np.concatenate([v_cmd, extra, np.zeros(300)])
    v_cmd = v_cmd[:n]
    th_cmd = np.cumsum(v_cmd) * dt
    return th_cmd


def simulate(seed, effect=None, stiff_scale=1.0, fric_scale=1.0, T=120.0):
    rng = np.random.default_rng(seed)
    th_cmd = schedule(rng, T)
    n = len(th_cmd)
    # --- truth parameters (N*mm, deg, s)
    st = dict(Fs_p=1100.0, Fc_p=800.0, vs_p=2.0, Fs_n=-1000.0, Fc_n=-700.0, vs_n=1.5,
              expo=0.8, visc=15.0)
    for kk in ('Fs_p', 'Fc_p', 'Fs_n', 'Fc_n'): st[kk] *= fric_scale
    st['visc'] *= fric_scale
    w = np.array([0.3, 0.25, 0.2, 0.15, 0.1])
    zmax_ref = np.array([0.0008, 0.002, 0.005, 0.01, 0.02])   # deg at S=1000
    k0 = w * 1000.0 / zmax_ref * stiff_scale * fric_scale        # N*mm/deg
    if effect == 'control2':
        w = np.array([0.45, 0.2, 0.15, 0.12, 0.08])
    def S(v, sgn):
        if sgn >= 0:
            return st['Fc_p'] + (st['Fs_p'] - st['Fc_p']) * np.exp(-(abs(v) / st['vs_p']) ** st['expo'])
        return -(abs(st['Fc_n']) + (abs(st['Fs_n']) - abs(st['Fc_n'])) * np.exp(-(abs(v) / st['vs_n']) ** st['expo']))
    # --- stiff drive: critically-damped-ish 2nd-order follower, 60 Hz, zeta .9, 5 substeps
    wn, ze, sub = 2 * np.pi * 60, 0.9, 5
    h = 1 / FS / sub
    th, om = 0.0, 0.0
    z = np.zeros(5)
    F = np.zeros(n); TH = np.zeros(n); OM = np.zeros(n)
    sgn_last, nrev = 1, 0
    for i in range(n):
        for _ in range(sub):
            acc = wn**2 * (th_cmd[i] - th) - 2 * ze * wn * om
            om += acc * h; dth = om * h; th += dth
            if abs(om) > 1e-4:
                s_now = 1 if om > 0 else -1
                if s_now != sgn_last:
                    nrev += 1; sgn_last = s_now
            k = k0
            if effect == 'softening':
                k = k0 * (1 - 0.35 * (1 - np.exp(-nrev / 2.0)))
            lim = w * abs(S(om, sgn_last))
            z = np.clip(z + dth, -lim / k, lim / k)
        f = np.sum(k * z) + st['visc'] * om
        if effect == 'drift':
            f *= 1 + 0.2 * (1 - np.exp(-(i / FS) / 40.0))
        if effect == 'ripple':
            f *= 1 + 0.08 * np.sin(2 * np.pi * th / 12.0)
        F[i] = f; TH[i] = th; OM[i] = om
    t = np.arange(n) / FS
    noise = rng.normal(0, 4.0 * fric_scale ** 0.5, n)
    offset = 3.0 * np.sin(2 * np.pi * t / 400.0 + rng.uniform(0, 6.28)) + 0.5
    meas = -(F + noise + offset)                    # reaction sign
    enc = np.round(TH / CNT) * CNT
    truth = dict(seed=seed, effect=effect, stribeck=st, weights=w.tolist(), k0=k0.tolist(),
                 zmax_at_S1000_deg=(w * 1000 / k0).tolist(), nrev_total=nrev,
                 noise_Nmm=4.0 * fric_scale ** 0.5, encoder_count_deg=CNT)
    return t, enc, meas, truth, F


def write(path, t, angle, torque, decimals=7):
    """The recording as logged: time [s], the encoder angle [deg] to ``decimals`` places (7 holds
    a 19-bit count), the measured torque [N·mm]."""
    with open(path, 'w') as fh:
        fh.write('time [s],joint_angle [deg],friction_torque [N·mm]\n')
        fh.writelines(f'{a:.3f},{b:.{decimals}f},{c:.3f}\n' for a, b, c in zip(t, angle, torque))


if __name__ == '__main__':
    cases = [('control', 11, None, 1, 1), ('drift', 12, 'drift', 1, 1), ('ripple', 13, 'ripple', 1, 1),
             ('softening', 14, 'softening', 1, 1), ('control2', 77, 'control2', 5, 3)]
    import os

    out, only = sys.argv[1], sys.argv[2:]
    os.makedirs(out, exist_ok=True)
    for name, seed, eff, ks, fs in cases:
        if only and name not in only: continue
        t, enc, meas, truth, F = simulate(seed, eff, ks, fs)
        write(os.path.join(out, f'{name}.csv'), t, enc, meas)
        json.dump(truth, open(os.path.join(out, f'{name}_truth.json'), 'w'), indent=1)
        print(name, len(t), 'range deg', enc.min(), enc.max(), 'nrev', truth['nrev_total'],
              '|F| max', np.abs(F).max())
