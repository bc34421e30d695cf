"""A machine-tool feed slide on an ironless linear motor, simulated on its own terms (it imports
nothing of the tool).

Plant: a rigid 180 kg slide; friction from a generalised Maxwell-slip (five elasto-plastic
elements, each slipping at its share α_i of s(v) = F_c + (F_s − F_c)·exp(−(|v|/v_s)^1.4),
their break-away displacements 0.4–22 µm) plus viscous σ2·v, optionally times an effect's
factor; integrated at 10 kHz (semi-implicit Euler). Control: a position-P, velocity-PI cascade
at 2 kHz on a 0.5 µm glass scale, acceleration feed-forward with a mass 6 % short, one tick of
computation delay, ±3 kN saturation. The program: a dwell; reversing strokes of 2 µm to 80 mm
at the speed that takes 0.6 s a stroke (so the short ones cross presliding at 8–130 µm/s under
the controller, not under a force ramp); constant-speed moves at 0.02–50 mm/s both ways in a
shuffled order, with dwells. The travel lies at 412–518 mm, far from position 0.

Logged at 1 kHz as the drive writes it: ``time [s]``, ``position [mm]`` (scale counts),
``force [kN]`` (the motor force averaged over the millisecond, with 1.5 N of white noise and a
0.5 N offset wandering over 8 s). Positive force pushes toward positive position.

Cases: ``"none"``; ``"ripple"``: friction × (1 + 0.12·sin(2πx/6.35 mm + 0.7)) along the absolute
position; ``"drift"``: friction × (1 + b·(1 − e^(−t/τ))), b = −0.25, τ = 40 s; ``"both"``.

``python -m synth.feed_slide DIR`` writes ``a_control.csv``, ``b_ripple.csv``, ``c_drift.csv``
and ``d_ripple_drift.csv``.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

M = 180.0
SCALE = 0.5e-6
FS_POS, FC_POS = 172.0, 122.0
FS_NEG, FC_NEG = 168.0, 118.0
VS = 2.0e-3          # m/s
DELTA = 1.4
SIGMA2 = 400.0
# Maxwell-slip elements: share of the limit and break-away displacement
ALPHA = np.array([0.30, 0.25, 0.20, 0.15, 0.10])
DBREAK = np.array([0.4e-6, 1.2e-6, 3.5e-6, 9e-6, 22e-6])   # m, at the static limit
K_EL = ALPHA * 0.5 * (FS_POS + FS_NEG) / DBREAK             # N/m
C_EL = K_EL * 1.0e-4                                        # micro-damping while stuck
X0 = 0.465                                                  # m, start position
XMIN, XMAX = 0.412, 0.518
RIPPLE = dict(lam=6.35e-3, amp=0.12, phi=0.7)
DRIFT = dict(b=-0.25, tau=40.0)


def s_of_v(v):
    if v >= 0:
        return FC_POS + (FS_POS - FC_POS) * math.exp(-(abs(v) / VS) ** DELTA)
    return FC_NEG + (FS_NEG - FC_NEG) * math.exp(-(abs(v) / VS) ** DELTA)


def steady_friction(v):
    """Friction at constant velocity v (all elements sliding), signed."""
    return math.copysign(s_of_v(v), v) + SIGMA2 * v


def virgin_curve(dx):
    """Presliding virgin curve (from rest, all elements relaxed) at displacement dx >= 0."""
    fs = 0.5 * (FS_POS + FS_NEG)
    return float(np.sum(np.minimum(K_EL * dx, ALPHA * fs)))


# ---------------------------------------------------------------- motion program
def build_reference(rng, ctrl_dt):
    """Piecewise program -> arrays of reference velocity at the control rate; x_r integrated."""
    segs = []   # list of (kind, value, duration): 'v' constant velocity, ramps inserted later
    a_max = 1.0  # m/s^2

    vel = []
    cur_v = [0.0]

    def ramp_to(v_new):
        dv = v_new - cur_v[0]
        if dv == 0:
            return
        tr = max(0.004, 1.5 * abs(dv) / a_max)
        n = max(2, int(round(tr / ctrl_dt)))
        k = np.arange(1, n + 1) / n
        vel.extend(cur_v[0] + dv * 0.5 * (1 - np.cos(np.pi * k)))
        cur_v[0] = v_new

    def hold(v, T):
        ramp_to(v)
        vel.extend([v] * max(1, int(round(T / ctrl_dt))))

    def pos():
        return X0 + np.sum(vel) * ctrl_dt

    # 1) dwell
    hold(0.0, 2.0)
    # 2) reversing strokes, amplitudes 2 um .. 80 mm (stroke length), two cycles each
    amps = [2e-6, 5e-6, 12e-6, 30e-6, 80e-6, 200e-6, 0.6e-3, 2e-3, 6e-3, 20e-3, 50e-3, 80e-3]
    order = list(rng.permutation(len(amps)))
    for j in order:
        A = amps[j]
        vs = min(max(A / 0.6, 4e-6), 40e-3)
        T = A / vs
        # go toward the side with more room first
        d = 1.0 if (XMAX - pos()) > (pos() - XMIN) else -1.0
        if A > 10e-3:   # make room
            centre = 0.5 * (XMIN + XMAX)
            if abs(pos() - centre) > 5e-3:
                dd = centre - pos()
                hold(math.copysign(30e-3, dd), abs(dd) / 30e-3)
                hold(0.0, 0.3)
            d = 1.0
            hold(d * -vs, 0.5 * T)     # start from one end of the stroke, centred
            hold(0.0, 0.2)
        for cyc in range(2):
            hold(d * vs, T)
            hold(0.0, 0.15)
            hold(-d * vs, T)
            hold(0.0, 0.15)
        hold(0.0, 0.5)
    hold(0.0, 3.0)   # dwell
    # 3) constant-speed moves, shuffled, both directions
    speeds = [0.02e-3, 0.05e-3, 0.1e-3, 0.25e-3, 0.6e-3, 1.5e-3, 3e-3, 7e-3, 15e-3, 30e-3, 50e-3]
    moves = [(s, d) for s in speeds for d in (1.0, -1.0)]
    moves = [moves[i] for i in rng.permutation(len(moves))]
    dwell_after = set(rng.choice(len(moves), 3, replace=False))
    for i, (s, d) in enumerate(moves):
        T = min(max(1.5, 0.3e-3 / s), 5.0)
        need = s * T + 3e-3
        room = (XMAX - pos()) if d > 0 else (pos() - XMIN)
        if room < need:
            # reposition to the far side at 40 mm/s
            target = (XMIN + 2e-3) if d > 0 else (XMAX - 2e-3)
            dd = target - pos()
            hold(math.copysign(40e-3, dd), abs(dd) / 40e-3)
            hold(0.0, 0.3)
        hold(d * s, T)
        hold(0.0, 0.3)
        if i in dwell_after:
            hold(0.0, 3.0)
    hold(0.0, 2.0)
    v = np.array(vel)
    x = X0 + np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * ctrl_dt)])
    return x, v


# ---------------------------------------------------------------- simulation
def simulate(effect, seed, rng_prog):
    ctrl_dt = 1 / 2000.0
    sub = 5
    dt = ctrl_dt / sub
    xr, vr = build_reference(rng_prog, ctrl_dt)
    ar = np.gradient(vr, ctrl_dt)
    n = len(xr)
    rng = np.random.default_rng(seed)

    Kv = M * 2 * math.pi * 60.0
    Ki = Kv * 2 * math.pi * 10.0
    Kx = 2 * math.pi * 15.0
    m_hat = 170.0
    wf = 2 * math.pi * 300.0
    af = math.exp(-wf * ctrl_dt)

    x, v = X0, 0.0
    z = [0.0] * 5
    k = list(K_EL)
    c = list(C_EL)
    al = list(ALPHA)
    integ = 0.0
    u_applied = 0.0
    u_prev = 0.0
    x_meas_prev = round(x / SCALE) * SCALE
    v_filt = 0.0

    out_t, out_x, out_u = [], [], []
    f = 0.0
    lam, amp, phi = RIPPLE['lam'], RIPPLE['amp'], RIPPLE['phi']
    b, tau = DRIFT['b'], DRIFT['tau']
    ripple = effect in ('ripple', 'both')
    drift = effect in ('drift', 'both')

    for i in range(n):
        t = i * ctrl_dt
        # --- controller (uses measurement at this tick; output applied next tick)
        x_meas = round(x / SCALE) * SCALE
        v_raw = (x_meas - x_meas_prev) / ctrl_dt
        x_meas_prev = x_meas
        v_filt = af * v_filt + (1 - af) * v_raw
        v_cmd = vr[i] + Kx * (xr[i] - x_meas)
        ev = v_cmd - v_filt
        integ += Ki * ev * ctrl_dt
        integ = max(-2000.0, min(2000.0, integ))
        u_new = Kv * ev + integ + m_hat * ar[i]
        u_new = max(-3000.0, min(3000.0, u_new))
        if i % 2 == 0:   # log at 1 kHz: scale reading at this instant, force averaged over
            out_t.append(t)  # the two control ticks of the millisecond ending here (the drive
            out_x.append(x_meas)  # averages what it logs: no 1 kHz alias of the 2 kHz loop)
            out_u.append(0.5 * (u_applied + u_prev))
        # --- plant, 5 substeps with the previously computed force
        u = u_applied
        for _ in range(sub):
            g = 1.0
            if ripple:
                g *= 1.0 + amp * math.sin(2 * math.pi * x / lam + phi)
            if drift:
                g *= 1.0 + b * (1.0 - math.exp(-(t) / tau))
            sv = s_of_v(v)
            f = 0.0
            for j in range(5):
                fj = k[j] * z[j]
                lim = al[j] * sv
                if -lim * (1 - 1e-9) < fj < lim * (1 - 1e-9):   # stuck: micro-damping acts,
                    fj += c[j] * v                               # element force capped at its limit
                    fj = lim if fj > lim else (-lim if fj < -lim else fj)
                f += fj
            f = g * (f + SIGMA2 * v)
            v += (u - f) / M * dt
            x += v * dt
            for j in range(5):
                zj = z[j] + v * dt
                lim = al[j] * sv / k[j]
                if zj > lim:
                    zj = lim
                elif zj < -lim:
                    zj = -lim
                z[j] = zj
            t += dt
        u_prev = u_applied
        u_applied = u_new

    t = np.array(out_t)
    xm = np.array(out_x)
    u = np.array(out_u)
    # force sensor / logging noise: white 1.5 N, slow offset wander 0.5 N rms (OU, 8 s)
    white = rng.normal(0, 1.5, len(t))
    tc, dtl = 8.0, 1e-3
    a = math.exp(-dtl / tc)
    e = rng.normal(0, 0.5 * math.sqrt(1 - a * a), len(t))
    wander = np.empty(len(t))
    w = rng.normal(0, 0.5)
    for i in range(len(t)):
        w = a * w + e[i]
        wander[i] = w
    f_logged = u + white + wander
    return t, xm, f_logged, u, xr[::2][:len(t)]


def transition_change(dx: float) -> float:
    """The friction's change along a branch after a reversal from gross sliding, at a
    displacement ``dx`` ≥ 0 from the reversal: twice the virgin curve at half of it (each
    element's swing from one slip level to the other, Masing's rule), at the static limit."""
    return 2.0 * virgin_curve(0.5 * dx)


def recording(effect: str = "none", seed: int = 11):
    """(the log as a data frame in the drive's units, the truth): one program for every case."""
    if effect not in ("none", "ripple", "drift", "both"):
        raise ValueError(f"effect: none, ripple, drift or both; got {effect!r}")
    t, xm, f, _, _ = simulate(effect, seed, np.random.default_rng(12345))
    df = pd.DataFrame({"time [s]": np.round(t, 3), "position [mm]": np.round(xm * 1e3, 4),
                       "force [kN]": np.round(f * 1e-3, 6)})
    truth = {"inertia": M, "Fs": (FS_POS, -FS_NEG), "Fc": (FC_POS, -FC_NEG), "vs": VS, "sigma2": SIGMA2,
             "ripple": dict(RIPPLE) if effect in ("ripple", "both") else None,
             "drift": dict(DRIFT) if effect in ("drift", "both") else None}
    return df, truth


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    out.mkdir(parents=True, exist_ok=True)
    for name, effect, seed in (("a_control", "none", 11), ("b_ripple", "ripple", 12), ("c_drift", "drift", 13),
                               ("d_ripple_drift", "both", 14)):
        recording(effect, seed)[0].to_csv(out / f"{name}.csv", index=False)
