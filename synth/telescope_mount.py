"""A telescope mount's axis, driven through a worm gear and seen at the output, simulated on its
own terms (numpy only: it imports nothing of the tool).

Plant: J·a = τ − F, J = 40 kg·m². Friction from a generalised Maxwell-slip contact: five
elements with shares α = 0.30 … 0.10 of a Lorentzian Stribeck limit per direction,
S(v) = F_c + (F_s − F_c)/(1 + (v/v_s)²) (F_c 3.0/2.6, F_s 4.2/3.7 N·m, v_s 120/90″/s), each
element sticking (with damping) until its spring reaches its slip limit, the elements slipping at
1, 3, 8, 20 and 50″; plus viscous 100 N·m·s/rad. An effect's friction factor m multiplies the
slip limits and the viscous term (not the springs: the presliding range follows it); a
softening multiplies the springs. Semi-implicit Euler at 5 kHz; a P-position/PI-velocity cascade
at 1 kHz on a 0.05″ encoder; logged at 250 Hz.

The session: 60 s of open-loop torque ramps (±1 … 3.1 N·m, reversals of a few arc-seconds),
then ten speeds of 15–3000″/s (sidereal to slew), both ways in a shuffled order, each followed
by a 15–25″ move back and forth. Written as a mount's log is: ``time [ms]``, ``position
[arcsec]``, ``torque [mN*m]`` (the commanded torque with 15 mN·m of white noise and an offset
wandering by 25 mN·m over a minute), and ``load [N]`` where the load moves.

Cases (``CASES``): a_control; b_softening, every spring × 1 − 0.35·(1 − e^(−n/8)), n the true
position's reversals over 3″ of back-travel; c_load, the load 500 → 800 → 400 → 700 N at the
quarters of the session, friction × (N/500 N)^0.6; d_load_softening; e_drift_ripple, friction ×
(1 + 0.25·(1 − e^(−t/40 s))) × (1 + 0.1·sin(2π·x/7200″ + 0.7)), the worm's 180 teeth.

``python -m synth.telescope_mount DIR`` writes the five recordings.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ARCSEC = math.pi / (180 * 3600)  # rad

TRUTH = dict(
    J=40.0,
    pos=dict(Fc=3.0, Fs=4.2, vs_arcsec=120.0),
    neg=dict(Fc=2.6, Fs=3.7, vs_arcsec=90.0),
    sigma2=100.0,  # N*m*s/rad  (= 4.85e-4 N*m per arcsec/s)
    alpha=[0.30, 0.25, 0.20, 0.15, 0.10],
    # displacement (arcsec) at which each element slips at Fs+ (sets stiffness)
    slip_disp_arcsec=[1.0, 3.0, 8.0, 20.0, 50.0],
    zeta_stick=0.3,
    enc_arcsec=0.05,
    torque_noise=0.015,  # N*m white
    offset_sigma=0.025,  # N*m, OU wandering offset
    offset_tau=60.0,
    rev_back_arcsec=3.0,
    soft_h=-0.35, soft_nc=8.0,
    load_N0=500.0, load_alpha=0.6, load_steps=[500.0, 800.0, 400.0, 700.0],
    drift_b=0.25, drift_tau=40.0,
    ripple_a=0.10, ripple_lambda_arcsec=7200.0, ripple_phase=0.7,
)


def lorentz(v, side):
    return side["Fc"] + (side["Fs"] - side["Fc"]) / (1.0 + (v / (side["vs_arcsec"] * ARCSEC)) ** 2)


def build_profile(rng, dt_c):
    """Return per-controller-tick arrays: mode (0 open loop, 1 closed), tau_ol, v_ref, a_ref."""
    mode, tau_ol, vref = [], [], []

    def hold_ol(tau_from, tau_to, T):
        n = int(round(T / dt_c))
        tau_ol.extend(np.linspace(tau_from, tau_to, n, endpoint=False))
        mode.extend([0] * n)
        vref.extend([0.0] * n)

    # 1) open-loop torque ramps (presliding back-and-forth), amplitudes below breakaway
    hold_ol(0, 0, 1.0)
    last = 0.0
    for amp in [1.0, 1.8, 2.6, 3.1, 2.2, 1.4]:
        for target in (amp, -amp * 0.9):
            T = abs(target - last) / 0.8  # 0.8 N*m/s
            hold_ol(last, target, T)
            last = target
    hold_ol(last, 0.0, abs(last) / 0.8)
    hold_ol(0, 0, 1.0)

    def move(v, T_hold, acc):
        # trapezoid in velocity from 0 to v and back to 0
        Ta = abs(v) / acc
        na = max(1, int(round(Ta / dt_c)))
        nh = int(round(T_hold / dt_c))
        up = np.linspace(0, v, na, endpoint=False)
        seq = np.concatenate([up, np.full(nh, v), np.linspace(v, 0, na, endpoint=False)])
        vref.extend(seq.tolist())
        mode.extend([1] * len(seq))
        tau_ol.extend([0.0] * len(seq))

    def dwell(T):
        n = int(round(T / dt_c))
        vref.extend([0.0] * n)
        mode.extend([1] * n)
        tau_ol.extend([0.0] * n)

    levels = np.geomspace(15, 3000, 10)  # arcsec/s
    runs = [(s * v) for v in levels for s in (+1, -1)]
    order = rng.permutation(len(runs))
    dwell(0.5)
    for k in order:
        v = runs[k]
        T = float(np.clip(600.0 / abs(v), 6.0, 25.0))
        move(v * ARCSEC, T, 3000 * ARCSEC)
        dwell(0.4)
        # small back-and-forth: back 15-25 arcsec then forward again
        s = rng.uniform(15, 25)
        d = -np.sign(v)
        vv = 40.0
        move(d * vv * ARCSEC, s / vv - vv / 400.0, 400 * ARCSEC)
        dwell(0.3)
        move(-d * vv * ARCSEC, s / vv - vv / 400.0, 400 * ARCSEC)
        dwell(0.4)
    vref = np.array(vref)
    aref = np.gradient(vref, dt_c)
    return np.array(mode), np.array(tau_ol), vref, aref


def simulate(seed, softening=False, load=False, drift=False, ripple=False,
             f_sim=5000, f_ctl=1000, f_log=250):
    tr = TRUTH
    rng = np.random.default_rng(seed)
    dt = 1.0 / f_sim
    dt_c = 1.0 / f_ctl
    sub = f_sim // f_ctl
    logevery = f_sim // f_log
    mode, tau_ol, vref, aref = build_profile(rng, dt_c)
    xref = np.concatenate([[0.0], np.cumsum(vref[:-1] * dt_c)])
    nctl = len(mode)
    nsim = nctl * sub
    T_total = nsim * dt

    J = tr["J"]
    alpha = np.array(tr["alpha"])
    Fs_p = tr["pos"]["Fs"]
    k0 = alpha * Fs_p / (np.array(tr["slip_disp_arcsec"]) * ARCSEC)
    c0 = 2 * tr["zeta_stick"] * np.sqrt(k0 * J) / len(k0)
    sig2 = tr["sigma2"]
    q = tr["enc_arcsec"] * ARCSEC
    P, Nn = tr["pos"], tr["neg"]

    # load schedule (smooth 0.5 s steps at quarters of the session), logged with noise
    def load_at(t):
        steps = tr["load_steps"]
        val = steps[0]
        for j in range(1, len(steps)):
            tj = T_total * j / len(steps)
            w = min(max((t - tj) / 0.5, 0.0), 1.0)
            val += (steps[j] - steps[j - 1]) * w
        return val

    # controller (cascade P-position / PI-velocity on encoder reading)
    Kx = 15.0
    wv = 40.0
    Kv = J * wv
    Ki = Kv * wv / 4
    wf = 2 * math.pi * 50.0
    integ = 0.0
    v_est = 0.0
    x_enc_prev = 0.0

    x = 0.0
    v = 0.0
    z = np.zeros(len(k0))
    stuck = np.ones(len(k0), dtype=bool)
    # softening reversal counter on true position
    nrev = 0
    rdir = 1
    xext = 0.0
    back = tr["rev_back_arcsec"] * ARCSEC

    # measurement offset (OU)
    off = 0.0
    a_ou = math.exp(-dt_c / tr["offset_tau"])
    s_ou = tr["offset_sigma"] * math.sqrt(1 - a_ou ** 2)

    nlog = -(-nsim // logevery)
    out_t = np.empty(nlog)
    out_x = np.empty(nlog)
    out_tau = np.empty(nlog)
    out_N = np.empty(nlog)
    out_F = np.empty(nlog)  # true friction (not written to the recording)
    out_n = np.empty(nlog)
    tau = 0.0
    tau_meas = 0.0
    li = 0
    kz = k0.copy()
    ctl_active_start = None
    xref_offset = 0.0
    for i in range(nsim):
        t = i * dt
        if i % sub == 0:
            ic = i // sub
            x_enc = math.floor(x / q) * q
            v_raw = (x_enc - x_enc_prev) / dt_c
            x_enc_prev = x_enc
            v_est += (v_raw - v_est) * (1 - math.exp(-wf * dt_c))
            if mode[ic] == 0:
                tau = tau_ol[ic]
                integ = 0.0
            else:
                if ctl_active_start is None:
                    ctl_active_start = ic
                    xref_offset = x_enc - xref[ic]
                    v_est = 0.0
                xr = xref[ic] + xref_offset
                vc = vref[ic] + Kx * (xr - x_enc)
                e = vc - v_est
                integ += Ki * e * dt_c
                tau = Kv * e + integ + J * aref[ic]
                tau = max(-15.0, min(15.0, tau))
            off = a_ou * off + s_ou * rng.standard_normal()
            tau_meas = tau + off + tr["torque_noise"] * rng.standard_normal()
        # friction factor m
        m = 1.0
        Nload = load_at(t) if load else tr["load_N0"]
        if load:
            m *= (Nload / tr["load_N0"]) ** tr["load_alpha"]
        if drift:
            m *= 1 + tr["drift_b"] * (1 - math.exp(-t / tr["drift_tau"]))
        if ripple:
            m *= 1 + tr["ripple_a"] * math.sin(2 * math.pi * (x / ARCSEC) / tr["ripple_lambda_arcsec"] + tr["ripple_phase"])
        # stiffness factor
        if softening:
            kap = 1 + tr["soft_h"] * (1 - math.exp(-nrev / tr["soft_nc"]))
            kz = k0 * kap
        av = abs(v)
        Sp = lorentz(av, P) * m
        Sn = lorentz(av, Nn) * m
        # element states: slip limits in displacement
        hi = alpha * Sp / kz
        lo = -alpha * Sn / kz
        F = float(np.dot(kz, z) + v * np.dot(c0, stuck)) + m * sig2 * v
        a = (tau - F) / J
        v += a * dt
        x += v * dt
        z += v * dt
        zc = np.clip(z, lo, hi)
        stuck = zc == z
        z = zc
        # reversal counting (true position, back-travel > back)
        if rdir >= 0:
            if x > xext:
                xext = x
            elif xext - x > back:
                if rdir == 1:
                    nrev += 1
                rdir = -1
                xext = x
        if rdir <= 0:
            if x < xext:
                xext = x
            elif x - xext > back:
                if rdir == -1:
                    nrev += 1
                rdir = 1
                xext = x
        if i % logevery == 0:
            out_t[li] = t
            out_x[li] = math.floor(x / q) * q
            out_tau[li] = tau_meas
            out_N[li] = Nload + 2.0 * rng.standard_normal()
            out_F[li] = F
            out_n[li] = nrev
            li += 1
    return dict(t=out_t[:li], x=out_x[:li], tau=out_tau[:li], N=out_N[:li], F=out_F[:li], n=out_n[:li])


def recording(case: str):
    """(the log as a data frame in the mount's units, the truth) of one of ``CASES``."""
    if case not in CASES:
        raise ValueError(f"case: one of {', '.join(CASES)}; got {case!r}")
    kw = CASES[case]
    r = simulate(**kw)
    cols = {"time [ms]": np.round(r["t"] * 1e3, 1),
            "position [arcsec]": np.round(np.round(r["x"] / ARCSEC / 0.05) * 0.05, 2),
            "torque [mN*m]": np.round(r["tau"] * 1e3, 1)}
    if kw.get("load"):
        cols["load [N]"] = np.round(r["N"], 1)
    truth = dict(TRUTH, case=case, reversals=float(r["n"][-1]))
    return pd.DataFrame(cols), truth


CASES = {
    "a_control": dict(seed=1),
    "b_softening": dict(seed=2, softening=True),
    "c_load": dict(seed=3, load=True),
    "d_load_softening": dict(seed=4, load=True, softening=True),
    "e_drift_ripple": dict(seed=5, drift=True, ripple=True),
}


if __name__ == "__main__":
    out = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    out.mkdir(parents=True, exist_ok=True)
    for name in CASES:
        recording(name)[0].to_csv(out / f"{name}.csv", index=False)
