"""A wind turbine's blade pitch bearing (a four-point-contact slewing ring) turned by its pitch
drive, simulated on its own terms (numpy only: it imports nothing of the tool).

Plant: J·ω̇ = u − F, J = 8000 kg·m². Friction: a four-element Maxwell-slip contact breaking
away at 0.004–0.035°, each element slipping at its share of a rational Stribeck limit
S(ω) = F_c + (F_s − F_c)/(1 + (ω/ω_s)²) (F_s 42/37, F_c 30/26 kN·m, ω_s 0.5/0.4 °/s), the stuck
elements damped, plus viscous 1.5/1.3 kN·m per °/s. An effect's factor m multiplies the slip
limits and the viscous term. Semi-implicit Euler at 2 kHz; open-loop torque ramps to 0.4, 0.7,
0.85 and 1.04 F_s (a safety cut past 1 °/s), then a P-position/PI-velocity cascade runs nine
speeds of 0.05–8 °/s both ways in a shuffled order within 0–86°, each followed by three
±0.08° moves.

Logged at 100 Hz as a pitch system writes it: ``t [s]``, ``pitch angle [deg]`` (a 0.005°
absolute encoder), ``drive torque [kN*m]`` (averaged over 10 ms, 0.2 kN·m of white noise and an
offset wandering by 0.35 kN·m) and, where the load moves, ``bending moment [kN*m]``: the
blade's bending moment, the bearing's load, in slow ramps and gust steps between 2000 and
6000 kN·m.

Effects: ``none``; ``warmup``: m = 1 − 0.3·(1 − e^(−t/τ)), τ a quarter of the session (the
grease warming, friction falling); ``load``: m = (M/4000 kN·m)^0.5; ``load+warmup``;
``ripple``: m = 1 + 0.08·sin(2π·θ/λ + 1.1), λ = 360°/132 (the drive pinion's teeth on the ring).

``python -m synth.pitch_bearing EFFECT SEED OUT.csv`` writes one recording.
"""
import math
import sys

import numpy as np

D2R = math.pi / 180.0

# ---------------- truth ------------------------------------------------------------
J = 8000.0                       # kg m^2
FS_P, FC_P = 42e3, 30e3          # N m  (positive direction)
FS_N, FC_N = 37e3, 26e3          # N m  (magnitudes, negative direction)
WS_P, WS_N = 0.5 * D2R, 0.4 * D2R            # rad/s  (half-drop speed of the rational curve)
SIG2_P = 1.5e3 / D2R             # N m s/rad  (1.5 kN m per deg/s)
SIG2_N = 1.3e3 / D2R             # N m s/rad  (1.3 kN m per deg/s)
# Maxwell-slip elements: weights and break displacements (deg) at the static level
W = [0.30, 0.30, 0.25, 0.15]
DBREAK_DEG = [0.004, 0.010, 0.020, 0.035]
K = [W[i] * 0.5 * (FS_P + FS_N) / (DBREAK_DEG[i] * D2R) for i in range(4)]
KTOT = sum(K)
C_D = 2 * 0.3 * math.sqrt(KTOT * J)   # stuck-element damping (damping ratio 0.3)

ENC_DEG = 0.005
DT = 1.0 / 2000.0
LOG_EVERY = 20                   # 100 Hz

M0 = 4000.0                      # kN m
RIPPLE_LAM_DEG = 360.0 / 132.0
RIPPLE_A, RIPPLE_PHI = 0.08, 1.1
WARM_B = 0.3


def stribeck(w, side):
    a = abs(w)
    if side > 0:
        return FC_P + (FS_P - FC_P) / (1.0 + (a / WS_P) ** 2)
    return FC_N + (FS_N - FC_N) / (1.0 + (a / WS_N) ** 2)


# ---------------- schedule ---------------------------------------------------------
def build_schedule(rng):
    """Returns list of segments. Torque segments: ('u', dur, u0, u1).
    Position segments: ('move', dist_deg, v_deg_s) / ('hold', dur) relative to ref."""
    segs = []
    # open-loop torque ramps (N m), back and forth
    rate = 3e3  # N m/s
    for frac in (0.4, 0.7):
        for sgn, fs in ((1, FS_P), (-1, FS_N)):
            peak = sgn * frac * fs
            d = abs(peak) / rate
            segs.append(('u', d, 0.0, peak))
            segs.append(('u', 1.0, peak, peak))
            segs.append(('u', d, peak, 0.0))
            segs.append(('u', 1.0, 0.0, 0.0))
    # once more to 0.85, then just past breakaway (1.04 Fs), quickly down
    for sgn, fs in ((1, FS_P), (-1, FS_N)):
        peak = sgn * 0.85 * fs
        d = abs(peak) / rate
        segs += [('u', d, 0.0, peak), ('u', d, peak, 0.0), ('u', 1.0, 0.0, 0.0)]
    for sgn, fs in ((1, FS_P), (-1, FS_N)):
        peak = sgn * 1.04 * fs
        d = abs(peak) / rate
        segs += [('u', d, 0.0, peak), ('u', abs(peak) / 40e3, peak, 0.0), ('u', 2.0, 0.0, 0.0)]
    # closed loop: constant-speed moves
    speeds = [0.05, 0.1, 0.2, 0.4, 0.8, 1.5, 3.0, 5.0, 8.0]
    moves = [(v, s) for v in speeds for s in (1, -1)]
    order = rng.permutation(len(moves))
    moves = [moves[i] for i in order]
    pos = 40.0  # planned (deg), approximately where the ramps leave it
    lo, hi = 0.0, 86.0
    segs.append(('hold', 2.0))
    for v, s in moves:
        dur = min(max(6.0 / v, 6.0), 40.0)
        dist = v * dur
        if not (lo <= pos + s * dist <= hi):
            target = lo + 2.0 if s > 0 else hi - 2.0
            segs.append(('move', target - pos, 4.0))
            segs.append(('hold', 1.5))
            pos = target
        segs.append(('move', s * dist, v))
        pos += s * dist
        segs.append(('hold', 2.0))
        # short back-and-forth moves
        amp = 0.08
        for _ in range(3):
            segs.append(('move', amp, 0.2))
            segs.append(('move', -amp, 0.2))
        segs.append(('hold', 1.5))
    return segs


def expand(segs, acc_deg=10.0):
    """Sample the schedule at DT: mode (0 torque, 1 position), u, ref offset (rad), vref."""
    mode, u, r, vr = [], [], [], []
    off = 0.0
    for sg in segs:
        if sg[0] == 'u':
            n = max(1, int(round(sg[1] / DT)))
            mode += [0] * n
            u += list(np.linspace(sg[2], sg[3], n))
            r += [0.0] * n
            vr += [0.0] * n
        elif sg[0] == 'hold':
            n = int(round(sg[1] / DT))
            mode += [1] * n; u += [0.0] * n; r += [off] * n; vr += [0.0] * n
        else:
            dist, v = sg[1] * D2R, sg[2] * D2R
            a = acc_deg * D2R
            s = 1.0 if dist > 0 else -1.0
            L = abs(dist)
            ta = v / a
            if a * ta * ta > L:            # triangle
                ta = math.sqrt(L / a); v = a * ta; tc = 0.0
            else:
                tc = (L - a * ta * ta) / v
            T = 2 * ta + tc
            n = int(math.ceil(T / DT))
            t = np.arange(1, n + 1) * DT
            t = np.minimum(t, T)
            pos = np.where(t < ta, 0.5 * a * t * t,
                  np.where(t < ta + tc, 0.5 * a * ta * ta + v * (t - ta),
                           L - 0.5 * a * (T - t) ** 2))
            vel = np.where(t < ta, a * t, np.where(t < ta + tc, v, np.maximum(a * (T - t), 0.0)))
            mode += [1] * n; u += [0.0] * n
            r += list(off + s * pos); vr += list(s * vel)
            off += s * L
    return (np.array(mode, dtype=np.int8), np.array(u), np.array(r), np.array(vr))


def load_profile(rng, n):
    """Blade bending moment (kN m): slow ramps and steps between 2000 and 6000."""
    T = n * DT
    t_knots, v_knots = [0.0], [4000.0]
    t = 0.0
    while t < T:
        dur = rng.uniform(25, 70)
        new = rng.uniform(2000, 6000)
        if rng.random() < 0.4:                       # step (gust front), 0.5 s
            t_knots += [t + dur, t + dur + 0.5]
            v_knots += [v_knots[-1], new]
            t += dur + 0.5
        else:                                        # slow ramp
            t_knots.append(t + dur)
            v_knots.append(new)
            t += dur
    tt = np.arange(n) * DT
    return np.interp(tt, t_knots, v_knots)


def simulate(effect, seed, out):
    """Write the recording of ``effect`` with ``seed`` to ``out`` (CSV) and return its truth."""
    rng = np.random.default_rng(seed)
    segs = build_schedule(rng)
    mode, u_ol, rref, vref = expand(segs)
    n = len(mode)
    T = n * DT
    tau_w = T / 4.0
    Mload = load_profile(rng, n)
    use_load = 'load' in effect
    use_warm = 'warmup' in effect
    use_ripple = effect == 'ripple'
    lam = RIPPLE_LAM_DEG * D2R

    th = 40.0 * D2R
    w = 0.0
    d = [0.0] * 4
    integ = 0.0
    th_ref0 = None
    KV, KI, KP = 2.0e6, 4.0e7, 5.0
    UMAX = 250e3
    mode_l = mode.tolist(); uol = u_ol.tolist(); rr = rref.tolist(); vv = vref.tolist()
    ML = Mload.tolist()
    nlog = n // LOG_EVERY
    log_th = np.empty(nlog); log_u = np.empty(nlog); log_M = np.empty(nlog); log_F = np.empty(nlog)
    acc_u = 0.0
    F = 0.0
    tripped = False
    u_prev = 0.0
    k = 0
    for i in range(n):
        t = i * DT
        # effect factor
        m = 1.0
        if use_warm:
            m *= 1.0 - WARM_B * (1.0 - math.exp(-t / tau_w))
        if use_load:
            m *= math.sqrt(ML[i] / M0)
        if use_ripple:
            m *= 1.0 + RIPPLE_A * math.sin(2 * math.pi * th / lam + RIPPLE_PHI)
        # drive torque
        if mode_l[i] == 0:
            # operator's safety cut: past breakaway, once the speed exceeds 1 deg/s the
            # torque is ramped down to zero at 40 kN m/s (until the schedule returns to 0)
            us = uol[i]
            if abs(w) > 1.0 * D2R:
                tripped = True
            if us == 0.0:
                tripped = False
            if tripped:
                mag = max(0.0, min(abs(us), abs(u_prev) - 40e3 * DT))
                u = math.copysign(mag, us)
            else:
                u = us
        else:
            if th_ref0 is None:
                th_ref0 = th
                integ = 0.0
            e_pos = th_ref0 + rr[i] - th
            wref = vv[i] + KP * e_pos
            ew = wref - w
            integ += KI * ew * DT
            integ = max(-UMAX, min(UMAX, integ))
            u = KV * ew + integ
            u = max(-UMAX, min(UMAX, u))
        # semi-implicit Euler: velocity first with the friction of the current state
        w_new = w + DT * (u - F) / J
        dth = w_new * DT
        th_new = th + dth
        # Maxwell-slip elements
        fel = 0.0
        stuck = 0.0
        for j in range(4):
            dj = d[j] + dth
            side = 1 if dj >= 0 else -1
            lim = W[j] * stribeck(w_new, side) * m
            if K[j] * abs(dj) > lim:
                dj = side * lim / K[j]
            else:
                stuck += W[j]
            d[j] = dj
            fel += K[j] * dj
        sig2 = SIG2_P if w_new >= 0 else SIG2_N
        F = fel + C_D * w_new * stuck + sig2 * w_new * m
        w, th = w_new, th_new
        acc_u += u
        u_prev = u
        if (i + 1) % LOG_EVERY == 0 and k < nlog:
            log_th[k] = th; log_u[k] = acc_u / LOG_EVERY; log_M[k] = ML[i]; log_F[k] = F
            acc_u = 0.0
            k += 1
    tl = (np.arange(nlog) + 1) * LOG_EVERY * DT
    # encoder: absolute, 0.005 deg
    enc = np.floor(log_th / D2R / ENC_DEG) * ENC_DEG
    # torque: white noise + slowly wandering offset (kN m)
    ou = np.zeros(nlog)
    a = math.exp(-0.01 / 80.0)
    ee = rng.normal(0, 0.25 * math.sqrt(1 - a * a), nlog)
    for q in range(1, nlog):
        ou[q] = a * ou[q - 1] + ee[q]
    offset = 0.35 * np.sin(2 * np.pi * tl / 400.0 + rng.uniform(0, 6.28)) + ou
    torque = log_u / 1e3 + offset + rng.normal(0, 0.2, nlog)
    cols = {'t [s]': tl, 'pitch angle [deg]': enc, 'drive torque [kN*m]': torque}
    fmt = ['%.2f', '%.3f', '%.4f']
    if use_load:
        cols['bending moment [kN*m]'] = log_M + rng.normal(0, 8.0, nlog)
        fmt.append('%.1f')
    hdr = ','.join(cols)
    np.savetxt(out, np.column_stack(list(cols.values())), delimiter=',', header=hdr, comments='', fmt=fmt)
    return {"inertia": J, "Fs": (FS_P, -FS_N), "Fc": (FC_P, -FC_N), "load_alpha": 0.5, "M0": M0 * 1e3,
            "warm_b": -WARM_B, "warm_tau": tau_w, "ripple_lambda": RIPPLE_LAM_DEG * D2R, "ripple_a": RIPPLE_A,
            "rows": int(nlog), "duration": float(T)}


if __name__ == "__main__":
    print(simulate(sys.argv[1], int(sys.argv[2]), sys.argv[3]))
