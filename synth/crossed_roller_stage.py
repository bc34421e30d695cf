"""A crossed-roller linear stage, simulated apart from leuven-friction (numpy and the standard
library; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_crossed_roller_stage.py``).

Plant: 4.5 kg on a linear motor whose force command is logged. Friction: four elasto-plastic
Maxwell-slip elements (weights 0.30/0.30/0.25/0.15 of F_s, breaking at 0.3, 1, 3 and 8 µm), each
clipped at its share of a stretched-exponential Stribeck limit (exponent 1.4; F_s 9.0/8.4 N,
F_c 6.5/6.1 N, v_s 2.0/2.3 mm/s), damping on each stuck element's deflection rate, and viscous
friction 60/55 N·s/m. Semi-implicit Euler at 20 kHz, logged at 2 kHz: force ramps below
break-away first, then a PI velocity loop over 12 speeds of 0.2–80 mm/s both ways in a shuffled
order. A 0.05 µm scale (position in mm); the force with 0.05 N of noise and a 0.08 N offset.

Effects, applied to the friction inside the loop: ``drift``, a warm-up that comes and goes (the
friction rises by 20 % over the first half and falls back towards +5 % in the second, a
``temperature [°C]`` column following it); ``cam``, a normal load 600 ± 300 N over a 7 s cam,
friction ∝ (N/600)^0.7, logged as ``normal_load [N]``; ``ripple``, × (1 + 0.06 sin(2πx/11.3 mm + 1)).

``python synth/crossed_roller_stage.py OUT_DIR [KIND …]`` writes the trial's files.
"""

from __future__ import annotations

import math
import random
import sys

import numpy as np

MASS = 4.5
POS = dict(Fs=9.0, Fc=6.5, vs=2.0e-3, delta=1.4, sigma2=60.0)
NEG = dict(Fs=8.4, Fc=6.1, vs=2.3e-3, delta=1.4, sigma2=55.0)
WEIGHTS = (0.30, 0.30, 0.25, 0.15)  # Maxwell-slip elements: shares of F_s
BREAK = (0.3e-6, 1.0e-6, 3.0e-6, 8.0e-6)  # m, each element's deflection at F_s
C_STUCK = 3000.0  # N·s/m, the stuck elements' damping, shared by weight
DT, DEC = 5e-5, 10  # 20 kHz, logged at 2 kHz
STEP = 0.05e-6  # the scale's step (m)
NOISE, OFFSET = 0.05, 0.08  # force noise (N rms) and offset
SPEEDS_MM_S = (0.2, 0.5, 1, 2, 4, 7, 12, 20, 30, 45, 60, 80)
LOAD = dict(N0=600.0, amp=300.0, period=7.0, alpha=0.7)
RIPPLE = dict(a=0.06, wavelength_mm=11.3, phase=1.0)
KINDS = dict(control=("none", 1, 101), control2=("none", 2, 202), warm_then_cool=("drift", 3, 303),
             cam_load=("cam", 4, 404), ripple_far=("ripple", 5, 505), warm_ripple=("drift+ripple", 6, 606))


def limit(side: dict, speed: float) -> float:
    """The Stribeck limit F_c + (F_s − F_c)·exp(−(|v|/v_s)^δ) of one side, in N."""
    return side["Fc"] + (side["Fs"] - side["Fc"]) * math.exp(-(speed / side["vs"]) ** side["delta"])


def schedule(order_seed: int, ramp_scale: float = 1.0):
    """(force ramp points, their end time, [(speed, hold time)]): force ramps to ±0.8 … ±0.1 of
    F_s twice, then every speed both ways in a shuffled order that keeps the travel within ±0.15 m."""
    fs = min(POS["Fs"], NEG["Fs"])
    amps = [a * ramp_scale for a in (0.8, -0.7, 0.55, -0.4, 0.25, -0.1)] + [0.0]
    pts, t = [(0.0, 0.0), (0.5, 0.0)], 0.5
    for _ in range(2):
        for a in amps:
            t += 1.2 * (0.5 + abs(a - pts[-1][1] / fs))
            pts.append((t, a * fs))
        t += 1.0
        pts.append((t, 0.0))
    holds = [s * m * 1e-3 for m in SPEEDS_MM_S for s in (1, -1)]
    rng, order, x = random.Random(order_seed), [], 0.0

    def hold_time(v):
        return min(2.3, max(1.2, 0.05 / abs(v)))

    while holds:
        rng.shuffle(holds)
        pick = next((v for v in holds if abs(x + v * hold_time(v)) < 0.15), None)
        if pick is None:
            pick = min(holds, key=lambda v: abs(x + v * hold_time(v)))
        x += pick * hold_time(pick)
        order.append((pick, hold_time(pick)))
        holds.remove(pick)
    return pts, t, order


def simulate(effect: str = "none", seed: int = 1, order_seed: int = 101):
    """(rows, header, formats) of one session: time [s], position [mm], motor_force [N], and a
    temperature or load column where the effect has one."""
    rng = np.random.default_rng(seed)
    drift, cam, ripple = "drift" in effect, "cam" in effect, "ripple" in effect
    pts, t_pre, order = schedule(order_seed, 0.55 if cam else 1.0)
    acc, vref, tt, vprev = 0.5, [(t_pre, 0.0), (t_pre + 0.5, 0.0)], t_pre + 0.5, 0.0
    for v, dur in order:  # ramps at 0.5 m/s² between holds
        tt += abs(v - vprev) / acc
        vref.append((tt, v))
        tt += dur
        vref.append((tt, v))
        vprev = v
    tt += abs(vprev) / acc
    vref += [(tt, 0.0), (tt + 0.5, 0.0)]
    T = tt + 0.5
    k = [w * POS["Fs"] / d for w, d in zip(WEIGHTS, BREAK)]
    c = [C_STUCK * w for w in WEIGHTS]
    Fi, zd = [0.0] * 4, [0.0] * 4
    x = v = integ = u = 0.0
    kp = MASS * 2 * math.pi * 30.0
    ki = kp * 2 * math.pi * 5.0
    fp, fv = np.array([p[0] for p in pts]), np.array([p[1] for p in pts])
    vp, vv = np.array([p[0] for p in vref]), np.array([p[1] for p in vref])
    xq_prev, rows = 0.0, []
    for n in range(int(round(T / DT))):
        t = n * DT
        fac, extra = 1.0, None
        if drift:  # rises for half the session, then cools back towards +5 %
            b = (0.20 * (1 - math.exp(-t / 15.0)) / (1 - math.exp(-(T / 2) / 15.0)) if t < T / 2
                 else 0.05 + 0.15 * math.exp(-(t - T / 2) / 10.0))
            fac *= 1 + b
            extra = b
        if cam:
            load = LOAD["N0"] + LOAD["amp"] * math.sin(2 * math.pi * t / LOAD["period"])
            fac *= (load / LOAD["N0"]) ** LOAD["alpha"]
            extra = load
        if ripple:
            fac *= 1 + RIPPLE["a"] * math.sin(2 * math.pi * (x * 1e3) / RIPPLE["wavelength_mm"] + RIPPLE["phase"])
        if n % DEC == 0:  # the controller and the log at 2 kHz
            xq = round(x / STEP) * STEP
            if t < t_pre:
                u, integ = float(np.interp(t, fp, fv)), 0.0
            else:
                e = float(np.interp(t, vp, vv)) - (xq - xq_prev) / (DEC * DT)
                integ += e * DEC * DT
                u = max(-300.0, min(300.0, kp * e + ki * integ))
            xq_prev = xq
            row = [t, xq * 1e3, u + OFFSET + rng.normal(0, NOISE)]
            if drift:
                row.append(22.0 + 40.0 * extra + rng.normal(0, 0.1))
            if cam:
                row.append(extra + rng.normal(0, 2.0))
            rows.append(row)
        up, lo = fac * limit(POS, abs(v)), -fac * limit(NEG, abs(v))
        F = sum(Fi) + sum(ci * z for ci, z in zip(c, zd)) + fac * (POS if v > 0 else NEG)["sigma2"] * v
        v += DT * (u - F) / MASS
        dx = v * DT
        x += dx
        for i in range(4):
            fi = min(max(Fi[i] + k[i] * dx, lo * WEIGHTS[i]), up * WEIGHTS[i])
            zd[i] = (fi - Fi[i]) / (k[i] * DT)
            Fi[i] = fi
    header = "time [s],position [mm],motor_force [N]" + (",temperature [°C]" if drift else "") + (
        ",normal_load [N]" if cam else "")
    fmt = ["%.4f", "%.5f", "%.4f"] + (["%.2f"] if drift else []) + (["%.1f"] if cam else [])
    return np.array(rows), header, fmt


def write_csv(path, session) -> None:
    rows, header, fmt = session
    np.savetxt(path, rows, delimiter=",", header=header, comments="", fmt=fmt, encoding="utf-8")


if __name__ == "__main__":
    out = sys.argv[1]
    for kind in sys.argv[2:] or list(KINDS):
        write_csv(f"{out}/{kind}.csv", simulate(*KINDS[kind]))
