"""A galvanometer-scanner axis and a ship's rudder stock: friction at the two ends of the scale,
simulated apart from leuven-friction.

Written for a trial of `fit` then `diagnose` as a new user runs them, and kept so that trial
runs again: numpy only, nothing from leuven-friction is imported, and nothing here follows
``synth/``'s other generators. Pure-Python loops: the galvanometer's 10 s take minutes.

    python -m synth.scale_extremes OUTDIR galvo|rudder control|effect

Both: a 4-element generalized Maxwell-slip contact (breakaway shares 0.4/0.3/0.2/0.1 of a
Gaussian Stribeck limit, δ = 2) plus viscous friction and a presliding damping gated off while
sliding, semi-implicit Euler.

* galvo: J = 10⁻⁷ kg·m², F_c 2·10⁻⁵, F_s 2.6·10⁻⁵ N·m, v_s 0.05 rad/s, σ2 10⁻⁶ N·m·s/rad; the
  elements slip at 4–30 µrad. 20 kHz for 10 s: torque ramps below breakaway with internal loops,
  a PI velocity loop over 0.01–2 rad/s alternating in sign, a 3 Hz sinusoidal torque. A 2²⁰
  counts/rev encoder in µrad, the torque in mN·m with 10⁻⁷ N·m of noise. ``effect``: friction ×
  (1 + 0.1·sin(2πθ/3 mrad)).
* rudder: J = 2·10⁴ kg·m², F_c 4·10⁴, F_s 5.2·10⁴ N·m, v_s 0.002 rad/s, σ2 2·10⁵ N·m·s/rad;
  the elements slip at 0.05–0.5 mrad. A hydraulic actuator (oil spring and damping) under a PI
  velocity loop through nine speeds of 0.001–0.05 rad/s both ways, in a shuffled order, three
  times, with position oscillations at rest; 20 Hz for about two hours, the angle in degrees
  (0.002° of noise), the torque in kN·m (100 N·m of noise). ``effect``: friction × (1 − 0.15·(1 −
  e^(−t/1800 s))), a warm-up.

Each writes ``OUTDIR/{galvo,rudder}_{control,effect}.csv`` with its truth beside it (``.json``,
and the true motion and friction in ``_truth.npz``).
"""
import json
import math
import os
import sys
import numpy as np

def stribeck(v, Fc, Fs, vs, delta=2.0):
    return Fc + (Fs - Fc) * math.exp(-abs(v / vs) ** delta)

def maxwell_slip(z, k, w, s, v, dt):
    """The elements' forces after a step (each elastic, k·v·dt, until it slips at its share w of
    the Stribeck limit s), updated in place; their sum."""
    f = 0.0
    for j in range(len(z)):
        zj = z[j] + k[j] * v * dt
        lim = w[j] * s
        if zj > lim: zj = lim
        elif zj < -lim: zj = -lim
        z[j] = zj
        f += zj
    return f

# ------------------------------------------------------------------ galvo
def galvo(effect, seed=1):
    rng = np.random.default_rng(seed)
    J, Fc, Fs, vs, s2 = 1e-7, 2e-5, 2.6e-5, 0.05, 1e-6
    w = [0.4, 0.3, 0.2, 0.1]
    dl = [4e-6, 8e-6, 15e-6, 30e-6]           # presliding over ~20 urad
    k = [wi * Fc / di for wi, di in zip(w, dl)]
    s1, v_damp = 6e-5, 0.01                    # presliding damping, gated off while sliding
    a_rip, lam = 0.1, 3e-3                     # ripple: amplitude, wavelength 3 mrad
    fs_rate, T = 20000.0, 10.0
    sub = 10
    dt = 1.0 / fs_rate / sub
    n = int(T * fs_rate)
    t = np.arange(n) / fs_rate

    # --- program: list of (t_start, kind, data)
    # 0-0.2 rest; 0.2-2.4 open-loop torque ramps below breakaway with internal loops
    wp = np.array([0, 0.85, 0.4, 0.7, -0.85, -0.3, -0.6, 0.9, 0.5, 0.8, -0.8, 0.0]) * Fs
    wt = 0.2 + 0.2 * np.arange(len(wp))        # ends at 2.4 s
    # 2.5-8.9 velocity PI levels, alternating sign (reversals), speeds mixed
    speeds = [0.01, 0.5, 0.02, 1.0, 0.05, 2.0, 0.1, 0.2]
    levels = []
    t0 = 2.5
    for sp in speeds:
        for sg in (1, -1):
            levels.append((t0, t0 + 0.4, sg * sp))
            t0 += 0.4
    t_lv_end = t0                               # 8.9
    # 8.95-10 open-loop sinusoid torque 1.4*Fs at 3 Hz
    Kp = J * 2 * math.pi * 300                  # ~1.9e-4
    Ki = Kp * 2 * math.pi * 40

    x = 0.0; v = 0.0; z = [0.0] * 4; integ = 0.0
    X = np.empty(n); U = np.empty(n); V = np.empty(n); FR = np.empty(n)
    lv_i = 0
    u = 0.0
    for i in range(n):
        ti = t[i]
        # controller / drive at sample rate (zero-order hold)
        if ti < 0.2:
            u = 0.0
        elif ti < wt[-1]:
            u = float(np.interp(ti, wt, wp))
        elif ti < 2.5:
            u = 0.0
        elif ti < t_lv_end:
            # find level
            while levels[lv_i][1] <= ti:
                lv_i += 1
            ta, tb, vr = levels[lv_i]
            # smooth ramp 0.05 s from previous level
            prev = levels[lv_i - 1][2] if lv_i > 0 else 0.0
            r = min(1.0, (ti - ta) / 0.05)
            vref = prev + (vr - prev) * r
            e = vref - v
            integ += Ki * e / fs_rate
            u = Kp * e + integ
        elif ti < 8.95:
            u = 0.0; integ = 0.0
        else:
            u = 1.4 * Fs * math.sin(2 * math.pi * 3.0 * (ti - 8.95))
        X[i] = x; V[i] = v; U[i] = u
        for _ in range(sub):
            f = maxwell_slip(z, k, w, stribeck(v, Fc, Fs, vs), v, dt)
            f += s2 * v + s1 * math.exp(-(v / v_damp) ** 2) * v
            if effect:
                f *= 1.0 + a_rip * math.sin(2 * math.pi * x / lam)
            acc = (u - f) / J
            v += acc * dt
            x += v * dt
        FR[i] = f
    res = 2 * math.pi / 2 ** 20
    Xq = np.round(X / res) * res
    Un = U + rng.normal(0, 1e-7, n)            # torque measurement noise 0.5 % Fc
    truth = dict(J=J, Fc=Fc, Fs=Fs, vs=vs, sigma2=s2, delta=2, presliding_urad=20,
                 effect=("position_ripple a=0.1 lambda=3e-3 rad" if effect else None),
                 encoder_rad=res, torque_noise_Nm=1e-7)
    return t, Xq * 1e6, Un * 1e3, ["time [s]", "Angle [urad]", "Torque [mN*m]"], truth, (X, V, FR)

# ------------------------------------------------------------------ rudder
def rudder(effect, seed=2):
    rng = np.random.default_rng(seed)
    J, Fc, Fs, vs, s2 = 2e4, 4e4, 5.2e4, 0.002, 2e5
    w = [0.4, 0.3, 0.2, 0.1]
    dl = [0.05e-3, 0.15e-3, 0.3e-3, 0.5e-3]     # presliding over ~0.5 mrad
    k = [wi * Fc / di for wi, di in zip(w, dl)]
    s1, v_damp = 2e6, 2e-4
    Kh, ch = 1e8, 1e6                            # hydraulic oil spring and damping
    fs_rate = 20.0
    dt = 1e-3
    sub = int(round(1 / fs_rate / dt))
    # ---- program of velocity references, built as list of segments (duration, kind, arg)
    speeds = [0.001, 0.002, 0.003, 0.005, 0.008, 0.012, 0.02, 0.03, 0.05]
    segs = [("rest", 60.0, None)]
    pos = 0.0
    for p in range(3):
        pairs = [(s, sg) for s in speeds for sg in (1, -1)]
        rng.shuffle(pairs)
        for s, sg in pairs:
            dur = min(0.35 / s, 350.0)
            travel = sg * s * dur
            if abs(pos + travel) > 0.6:            # reposition toward centre
                rp = -math.copysign(min(abs(pos), 0.4), pos)
                segs.append(("move", abs(rp) / 0.02, math.copysign(0.02, rp)))
                pos += rp
                segs.append(("rest", 10.0, None))
            segs.append(("move", dur, sg * s))
            pos += travel
            segs.append(("rest", 10.0, None))
        # presliding oscillations at rest: position sinusoids of decreasing amplitude
        segs.append(("osc", 240.0, [4e-4, 2.5e-4, 1e-4, 2.5e-4]))
        segs.append(("rest", 20.0, None))
    T = sum(sg[1] for sg in segs)
    n = int(T * fs_rate)
    t = np.arange(n) / fs_rate
    # schedule arrays at sample rate: vref and position-offset oscillation
    vref = np.zeros(n)
    tt = 0.0
    for kind, dur, arg in segs:
        i0, i1 = int(round(tt * fs_rate)), int(round((tt + dur) * fs_rate))
        tl = t[i0:i1] - tt
        if kind == "move":
            ramp = np.clip(tl / 2.0, 0, 1) * np.clip((dur - tl) / 2.0, 0, 1)
            vref[i0:i1] = arg * ramp
        elif kind == "osc":
            # 4 cycles, 60 s each (period 60 s), amplitudes as listed
            amp = np.array(arg)[np.minimum((tl // 60).astype(int), 3)]
            om = 2 * math.pi / 60
            vref[i0:i1] = amp * om * np.sin(om * tl)   # position = amp*(1-cos)
        tt += dur
    # velocity PI (acts on actuator flow, i.e. actuator velocity command)
    Kp, Ki = 5.0, 20.0
    x = 0.0; v = 0.0; xa = 0.0; z = [0.0] * 4; xref = 0.0
    X = np.empty(n); TQ = np.empty(n); FR = np.empty(n); V = np.empty(n)
    tq = 0.0; f = 0.0
    for i in range(n):
        ti = t[i]
        X[i] = x; V[i] = v; TQ[i] = tq; FR[i] = f
        vr = vref[i]
        g = (1.0 - 0.15 * (1 - math.exp(-ti / 1800.0))) if effect else 1.0
        for _ in range(sub):
            xref += vr * dt
            e = vr - v
            ua = vr + Kp * e + Ki * (xref - x)        # PI on velocity error (I = position error)
            va = ua
            xa += va * dt
            tq = Kh * (xa - x) + ch * (va - v)
            f = maxwell_slip(z, k, w, stribeck(v, Fc, Fs, vs), v, dt)
            f += s2 * v + s1 * math.exp(-(v / v_damp) ** 2) * v
            f *= g
            v += (tq - f) / J * dt
            x += v * dt
    Xn = X + rng.normal(0, math.radians(0.002), n)
    TQn = TQ + rng.normal(0, 100.0, n)
    truth = dict(J=J, Fc=Fc, Fs=Fs, vs=vs, sigma2=s2, delta=2, presliding_mrad=0.5,
                 effect=("time_drift friction*(1-0.15*(1-exp(-t/1800)))" if effect else None),
                 pos_noise_deg=0.002, torque_noise_Nm=100, duration_s=T)
    return t, np.degrees(Xn), TQn / 1e3, ["time [s]", "rudder_angle [deg]", "Torque [kN*m]"], truth, (X, V, FR)

if __name__ == "__main__":
    outdir, which, kind = sys.argv[1], sys.argv[2], sys.argv[3]
    effect = kind == "effect"
    fn = galvo if which == "galvo" else rudder
    t, x, u, hdr, truth, (X, V, FR) = fn(effect)
    out = os.path.join(outdir, f"{which}_{kind}.csv")
    with open(out, "w") as fh:
        fh.write(",".join(hdr) + "\n")
        np.savetxt(fh, np.column_stack([t, x, u]), delimiter=",", fmt=["%.6f", "%.6f", "%.8g"])
    np.savez(os.path.join(outdir, f"{which}_{kind}_truth.npz"), X=X, V=V, FR=FR)
    json.dump(truth, open(os.path.join(outdir, f"{which}_{kind}_truth.json"), "w"), indent=1)
    print(out, len(t), "rows; |v| max", np.abs(V).max(), "x range", X.min(), X.max())
