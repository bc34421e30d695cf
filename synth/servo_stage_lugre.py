"""A position-servoed precision stage with LuGre friction, simulated apart from the project.

Written without the project's code or generators, for a trial of `fit` then `diagnose` on
recordings made apart from them (README, Diagnosis, "On recordings made apart from this
project"); kept so that trial can be run again and the slow tests can hold it (``tests/slow/test_diagnose_servo_stage.py``).
Nothing from leuven-friction is imported.

Plant: a 0.8 kg carriage under a PID position loop (30 Hz bandwidth); friction from a LuGre
model with an asymmetric Stribeck curve of Lorentzian shape (exponent 1.5), bristle damping
fading with speed and viscous friction. Integrated at 20 kHz (the bristle state updated exactly
for a frozen speed, semi-implicit Euler for the mechanics), logged at 500 Hz: a 50 nm encoder,
and the motor force averaged over each log interval with 4 mN noise and a 12 mN offset.
Written in time [ms], position [um], force [mN] and normal [N]. Schedule: eight speed levels
0.02–9 mm/s in random order with reversals and dwells, and triangle presliding cycles of
0.5–4 µm, 130 s. Effects multiply the Stribeck curve g(v) (load, drift, ripple) or scale σ0
(softening, counted on the commanded direction's reversals).

    python -m synth.servo_stage_lugre OUTDIR   # the six recordings of the trial, and truth.json
"""
import json
import numpy as np
from numba import njit

FS_SIM = 20000.0
FS_LOG = 500.0
M = 0.8                      # kg
TRAVEL = 10e-3               # m (0 .. 10 mm)

# friction truth (SI)
FC_P, FC_N = 0.34, 0.30      # N Coulomb level per direction
FS_P, FS_N = 0.52, 0.47      # N static level
VS = 0.4e-3                  # m/s Stribeck speed
SHAPE = 1.5                  # Lorentzian-like exponent
SIG0 = 2.75e5                # N/m bristle stiffness
SIG1 = 100.0                 # N s/m bristle damping
VD = 1e-3                    # m/s damping fade-out speed
SIG2 = 6.0                   # N s/m viscous


def make_schedule(rng, T=130.0):
    """reference position/velocity at FS_SIM. Random-order speed levels with
    reversals, dwells, and small back-and-forth presliding cycles."""
    speeds = np.array([0.02, 0.05, 0.12, 0.3, 0.8, 2.0, 5.0, 9.0]) * 1e-3
    amax = 40e-3             # m/s^2
    dt = 1.0 / FS_SIM
    segs = []                # list of velocity arrays
    x = 5e-3
    t = 0.0
    order = []
    for rep in range(3):
        order += list(rng.permutation(len(speeds)))
    i = 0
    while t < T - 2.0:
        kind = rng.random()
        if kind < 0.22 and i > 2:
            # presliding cycles: triangle-ish (smoothed) back and forth, 0.5..4 um
            amp = rng.uniform(0.5e-6, 4e-6)
            period = rng.uniform(1.0, 3.0)
            ncyc = rng.integers(2, 5)
            n = int(ncyc * period * FS_SIM)
            tt = np.arange(n) * dt
            # position = amp * tri(t) -> velocity = +-4 amp/period, smoothed
            v = 4 * amp / period * np.sign(np.sin(2 * np.pi * tt / period + 1e-9))
            k = int(0.02 * FS_SIM)
            v = np.convolve(v, np.ones(k) / k, mode="same")
            segs.append(v)
            t += n * dt
        else:
            s = speeds[order[i % len(order)]]
            i += 1
            # choose direction to stay inside travel
            if x > TRAVEL * 0.8:
                d = -1
            elif x < TRAVEL * 0.2:
                d = 1
            else:
                d = rng.choice([-1, 1])
            dur = float(rng.uniform(1.5, 4.0))
            room = (TRAVEL - x - 0.3e-3) if d > 0 else (x - 0.3e-3)
            if room < 0.5 * s:       # not enough room: go the other way
                d = -d
                room = (TRAVEL - x - 0.3e-3) if d > 0 else (x - 0.3e-3)
            dur = min(dur, max(room / s - s / amax, 0.2))
            ta = s / amax
            n_a = max(int(ta * FS_SIM), 1)
            n_c = int(dur * FS_SIM)
            ramp = np.linspace(0, s, n_a)
            v = d * np.concatenate([ramp, np.full(n_c, s), ramp[::-1]])
            segs.append(v)
            x += v.sum() * dt
            t += len(v) * dt
            # dwell
            nd = int(rng.uniform(0.1, 0.8) * FS_SIM)
            segs.append(np.zeros(nd))
            t += nd * dt
    v = np.concatenate(segs)
    n_tot = int(T * FS_SIM)
    if len(v) < n_tot:
        v = np.concatenate([v, np.zeros(n_tot - len(v))])
    v = v[:n_tot]
    xr = 5e-3 + np.cumsum(v) * dt
    return xr, v


@njit(cache=True)
def simulate(xr, vr, load, n0, alpha, drift_b, drift_tau, rip_a, rip_lam,
             soft_frac, soft_k, dt):
    n = len(xr)
    x = xr[0]
    v = 0.0
    z = 0.0
    integ = 0.0
    kp = M * (2 * np.pi * 30.0) ** 2
    kd = 2 * 0.7 * M * (2 * np.pi * 30.0)
    ki = kp * 2 * np.pi * 3.0
    X = np.empty(n)
    U = np.empty(n)
    FF = np.empty(n)
    rev = 0
    lastdir = 0
    for k in range(n):
        t = k * dt
        # reversal counter on the commanded direction
        if vr[k] > 1e-9:
            d = 1
        elif vr[k] < -1e-9:
            d = -1
        else:
            d = 0
        if d != 0:
            if lastdir != 0 and d != lastdir:
                rev += 1
            lastdir = d
        sig0 = SIG0 * (1.0 - soft_frac * (1.0 - np.exp(-rev / soft_k)))
        # controller (acts on the true state; fine for a stiff encoder loop)
        e = xr[k] - x
        integ += e * dt
        u = kp * e + kd * (vr[k] - v) + ki * integ
        # friction
        av = abs(v)
        if v >= 0:
            fc, fs = FC_P, FS_P
        else:
            fc, fs = FC_N, FS_N
        g = fc + (fs - fc) / (1.0 + (av / VS) ** SHAPE)
        # multiplicative effects
        scale = (load[k] / n0) ** alpha
        scale *= 1.0 + drift_b * (1.0 - np.exp(-t / drift_tau))
        scale *= 1.0 + rip_a * np.sin(2 * np.pi * x / rip_lam)
        g *= scale
        # bristle: exact update for frozen v
        rate = sig0 * av / g
        zss = np.sign(v) * g / sig0
        znew = zss + (z - zss) * np.exp(-rate * dt)
        zdot = (znew - z) / dt
        z = znew
        sig1 = SIG1 * np.exp(-(av / VD) ** 2)
        F = sig0 * z + sig1 * zdot + SIG2 * v
        # mechanics
        v += dt * (u - F) / M
        x += dt * v
        X[k] = x
        U[k] = u
        FF[k] = F
    return X, U, FF


def record(path, seed, sched_seed=7, load_var=False, alpha=0.0, drift_b=0.0,
           drift_tau=1.0, rip_a=0.0, rip_lam=1e-3, soft_frac=0.0, soft_k=1.0):
    rng_s = np.random.default_rng(sched_seed)
    xr, vr = make_schedule(rng_s)
    n = len(xr)
    dt = 1.0 / FS_SIM
    t = np.arange(n) * dt
    n0 = 40.0
    if load_var:
        load = n0 * (1.0 + 0.35 * np.sin(2 * np.pi * t / 55.0 + 0.4)
                     + 0.15 * np.sin(2 * np.pi * t / 23.0))
    else:
        load = np.full(n, n0)
    X, U, FF = simulate(xr, vr, load, n0, alpha, drift_b, drift_tau, rip_a,
                        rip_lam, soft_frac, soft_k, dt)
    rng = np.random.default_rng(seed)
    step = int(FS_SIM / FS_LOG)
    # average force over the log interval (sensor anti-alias), then noise + offset
    Ulog = U[: (n // step) * step].reshape(-1, step).mean(axis=1)
    idx = np.arange(0, (n // step) * step, step)
    tl = t[idx]
    xl = np.round(X[idx] / 50e-9) * 50e-9            # 50 nm encoder
    fl = Ulog + 0.012 + rng.normal(0, 0.004, len(Ulog))  # 12 mN offset, 4 mN noise
    cols = {"time [ms]": tl * 1e3, "position [um]": xl * 1e6,
            "force [mN]": fl * 1e3}
    if load_var:
        cols["normal [N]"] = load[idx] + rng.normal(0, 0.05, len(idx))
    hdr = ",".join(cols)
    data = np.column_stack(list(cols.values()))
    fmt = ["%.1f", "%.2f", "%.2f"] + (["%.3f"] if load_var else [])
    np.savetxt(path, data, delimiter=",", header=hdr, comments="",
               fmt=fmt)
    # revs count for truth
    d = np.sign(vr[np.abs(vr) > 1e-9])
    nrev = int(np.sum(d[1:] != d[:-1]))
    return dict(samples=len(tl), T=float(tl[-1]), nrev=nrev,
                travel_um=[float(xl.min() * 1e6), float(xl.max() * 1e6)],
                track_err_um_max=float(np.max(np.abs(X - xr)) * 1e6),
                f_rms_N=float(np.sqrt(np.mean(FF ** 2))))


if __name__ == "__main__":
    import os
    import sys

    out = sys.argv[1] if len(sys.argv) > 1 else "."
    os.makedirs(out, exist_ok=True)
    T = 130.0
    truth = {"base": dict(m=M, Fc=[FC_P, FC_N], Fs=[FS_P, FS_N], vs=VS,
                          shape=SHAPE, sig0=SIG0, sig1=SIG1, sig2=SIG2)}
    specs = [
        ("rec1_control", 101, {}),
        ("rec2_drift", 202, dict(drift_b=0.25, drift_tau=T / 3)),
        ("rec3_load", 303, dict(load_var=True, alpha=0.7)),
        ("rec4_ripple", 404, dict(rip_a=0.10, rip_lam=1.0e-3)),
        ("rec5_softening", 505, dict(soft_frac=0.40, soft_k=2.5)),
        ("rec6_drift_ripple", 606, dict(drift_b=0.25, drift_tau=T / 3,
                                        rip_a=0.10, rip_lam=1.0e-3)),
    ]
    for name, seed, kw in specs:
        info = record(os.path.join(out, f"{name}.csv"), seed, **kw)
        truth[name] = dict(kw, **info)
        print(name, info)
    with open(os.path.join(out, "truth.json"), "w") as f:
        json.dump(truth, f, indent=1)
