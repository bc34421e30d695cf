#!/usr/bin/env python3
"""
elsewhere.py -- independent synthetic friction recordings ("ground truth elsewhere").

Stand-alone test-data generator for friction identification tools.  It does not
import anything from the tool it is meant to test; it only uses numpy, numba
and pandas (for the returned DataFrame).

Contact model
-------------
Generalized Maxwell-Slip (GMS) model, M = 8 elasto-slide elements in parallel:

    F = sum_i F_i  +  sigma1 * (K_stuck / K0) * v  +  g * sigma2 * v

* element i has stiffness kappa*k_i and a rate-dependent slip level
  alpha_i * g * s_dir(|v|)  (sum alpha_i = 1), with the Stribeck curve

      s_dir(|v|) = Fc_dir + (Fs_dir - Fc_dir) * exp(-(|v|/vs)**delta),

  dir = +/- (direction-asymmetric static and Coulomb levels).
* sticking element:   dF_i/dt = kappa*k_i*v ; it starts to slide when it
  reaches its slip level while moving in that direction.
* sliding element (GMS sliding law, written with a relaxation time):
      dF_i/dt = (dir*alpha_i*g*s_dir(|v|) - F_i) / tau_r
  (frictional lag; integrated exactly over one step); it sticks again as soon
  as v changes sign or becomes zero.
* micro-damping sigma1 acts only through the stuck fraction of the stiffness
  (K_stuck/K0), viscous term g*sigma2*v.
* k_i = alpha_i * Fs_mean / d_i, the element break displacements d_i are
  log-spaced in [d_max/25, d_max]: the presliding (micro-slip) displacement
  before gross sliding is ~d_max from a virgin state and ~2*d_max after a
  reversal (Masing).  Robot: d_max in 2e-5..8e-5 rad.  Tribometer: d_max in
  0.5..3 um (5e-4..3e-3 mm) so that the "few um" oscillations really probe
  presliding.
* Steady sliding at constant v (all elements slipping):
      F_ss(v) = g * ( s_sign(v)(|v|) + sigma2*|v| ) * sign(v)
* g is the product of all effect multipliers (ripple, drift, normal load,
  load ramp); kappa is the cyclic-softening factor of the stiffness.  Both are
  evaluated inside the integration loop at every inner step.

Integrator
----------
Inner step 20 kHz (dt = 50 us).  Robot joint: J*qdd = tau_motor - F.
Linearly-implicit (semi-implicit Euler) step: the new velocity is solved with
the stiffness of the stuck elements, the micro-damping and the viscous term
taken implicitly (stiff-safe for presliding stiffness up to ~1e8), sliding
element forces are explicit (exact exponential relaxation); then the position
and the element states are updated with the new velocity (clip / stick-slip
switching).  The tribometer motion is prescribed: the velocity is linear
between the log samples, the position is its exact integral.

Kinds
-----
robot_joint   74,000 samples @ 500 Hz.  Discrete PID (with velocity
              feed-forward in the D term and a first-order filtered
              backward-difference velocity) at 500 Hz on the motor-side
              encoder (18 bit through a gear ratio 50..160); torque is held
              (ZOH) over the sample interval.  The logged q is the joint-side
              encoder, quantised to 2*pi/2**18 rad (the simulated position is
              continuous).
              Logged: t [s], q [rad] (quantised), tau_motor [N*m]
              (= commanded torque at sample k, applied over [t_k, t_k+1),
              + Gaussian noise 0.5 % Fc).  normal_load adds N [N] (axial
              preload).
tribometer    200..1000 Hz, 30,000..60,000 samples, prescribed reciprocating
              displacement.  Logged: t [ms], x [mm], F_friction [mN] (load
              cell, REACTION force = -F, positive while x decreases, noise
              1 % Fc), N [N] (normal load).  Friction levels ~ N (linear;
              exponent alpha for the normal_load effect).  Option
              load_ramp=True: the load ramps from ~0 to N0 while sticking
              at the start and back down while sticking at the end (the stuck
              element forces are clipped by their N-proportional slip levels,
              so the residual reaction force falls with N once the level
              reaches it).

Seeding: machine parameters and trajectory depend only on (seed, kind[,
load_ramp]); effect parameters and noise also on the effect, so the files of
one seed share the same machine and (tribometer: identical) motion.

Effects (all applied inside the integration loop through g or kappa)
  none              control
  position_ripple   g *= 1 + a*sin(2*pi*x/lambda + phi), x the absolute logged
                    position, a in 0.05..0.2, lambda = travel/(3..15)
  time_drift        g *= 1 + b*(1 - exp(-t/tau)), |b| in 0.15..0.4 (random
                    sign), tau in 0.15..0.5 x session length
  normal_load       g *= (N/N_ref)**alpha, alpha in 0.6..1.0, N a smooth random
                    non-monotone schedule within +/-(25..45)% of N_ref (column
                    N [N]; for the robot an axial preload, N_ref 1..5 kN)
  cyclic_softening  kappa = 1 - h*(1 - exp(-n/n0)), h in 0.3..0.6, n0 in 2..8;
                    n counts significant reversals: a reversal is counted when
                    the true position has moved back by more than 0.25*d_max
                    from the last extremum (hysteretic extremum tracker; the
                    very first move is not a reversal).
Every effect's parameters, the reversal times and all machine parameters are
returned in the truth dict (and written to the .json sidecar).

Trajectories
  robot_joint: 1 s dwell; 3 presliding blocks (at the start, after 1/3 and
  2/3 of the stroke visits) of one-sided cosine excursions +A,-A,+A,-A for 3
  amplitudes A in 200..600 urad (period 1.2..1.8 s); 16 stroke visits = 8
  speeds {0.002 .. 0.5 rad/s} x 2, shuffled (no speed twice in a row, rank
  correlation with speed < 0.45): cosine ramp up, constant speed, cosine-
  blended reversal, constant speed, ramp down, back at the start position,
  then a dwell.  Leg time <= 2.5 s, leg length <= 0.6 rad.
  tribometer: same structure in mm with 7 log-spaced speeds (v_lo 0.01..0.03
  mm/s to v_hi <= 25 mm/s; fewer speeds if a short session needs it), stroke
  S in 2..8 mm, 2 or 4 reversals per visit, tiny oscillations of 1..5 um.

Usage
-----
    python synth/elsewhere.py OUTDIR --seeds 1 2 3 --kinds robot_joint tribometer \
        --effects none position_ripple time_drift normal_load cyclic_softening \
        [--load-ramp] [--check]
writes <kind>_<effect>_<seed>.csv + .json (tribometer with --load-ramp:
tribometer_<effect>_loadramp_<seed>.csv).
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np
import pandas as pd
from numba import njit

KINDS = ("robot_joint", "tribometer")
EFFECTS = ("none", "position_ripple", "time_drift", "normal_load", "cyclic_softening")
_KIND_ID = {"robot_joint": 1, "tribometer": 2}
_EFF_ID = {e: i for i, e in enumerate(EFFECTS)}
ENCODER_BITS = 18
INNER_RATE_HZ = 20000.0
N_ELEM = 8


# ----------------------------------------------------------------------------
# numba kernels
# ----------------------------------------------------------------------------
@njit(inline="always")
def _strib(va, Fc, Fs, vs, dl):
    return Fc + (Fs - Fc) * math.exp(-((va / vs) ** dl))


@njit
def _gms_step(F, st, sd, k, alpha, kappa, g, v, dt, Fcp, Fsp, Fcn, Fsn, vs, dl, decay):
    va = abs(v)
    sp = g * _strib(va, Fcp, Fsp, vs, dl)
    sn = g * _strib(va, Fcn, Fsn, vs, dl)
    for i in range(F.shape[0]):
        if st[i] == 0:
            if v * sd[i] > 0.0:
                if sd[i] > 0:
                    tgt = alpha[i] * sp
                else:
                    tgt = -alpha[i] * sn
                F[i] = tgt + (F[i] - tgt) * decay
                continue
            st[i] = 1
        F[i] += kappa * k[i] * v * dt
        cp = alpha[i] * sp
        cn = alpha[i] * sn
        if F[i] >= cp:
            F[i] = cp
            if v > 0.0:
                st[i] = 0
                sd[i] = 1
        elif F[i] <= -cn:
            F[i] = -cn
            if v < 0.0:
                st[i] = 0
                sd[i] = -1


@njit(inline="always")
def _rev_update(x, rs, dsig):
    """rs = [dir, extremum, count]; returns True when a reversal is counted."""
    d = rs[0]
    if d == 0.0:
        if x - rs[1] > dsig:
            rs[0] = 1.0
            rs[1] = x
        elif rs[1] - x > dsig:
            rs[0] = -1.0
            rs[1] = x
        return False
    if d > 0.0:
        if x > rs[1]:
            rs[1] = x
        elif rs[1] - x > dsig:
            rs[0] = -1.0
            rs[1] = x
            rs[2] += 1.0
            return True
    else:
        if x < rs[1]:
            rs[1] = x
        elif x - rs[1] > dsig:
            rs[0] = 1.0
            rs[1] = x
            rs[2] += 1.0
            return True
    return False


@njit
def _sim_robot(qref, vref, T, nsub, J, Kp, Ki, Kd, afilt, quantum, cquantum, q0,
               k, alpha, Fcp, Fsp, Fcn, Fsn, vs, dl, tau_r, sig1, sig2,
               gtime, rip_a, rip_lam, rip_phi, soft_h, soft_n0, dsig):
    n = qref.shape[0]
    M = k.shape[0]
    dt = T / nsub
    decay = math.exp(-dt / tau_r)
    K0 = 0.0
    for i in range(M):
        K0 += k[i]
    F = np.zeros(M)
    st = np.ones(M, np.int64)
    sd = np.zeros(M, np.int64)
    q = q0
    v = 0.0
    I = 0.0
    vf = 0.0
    qm_prev = math.floor(q / cquantum + 0.5) * cquantum
    q_meas = np.empty(n)
    tau = np.empty(n)
    q_true = np.empty(n)
    v_true = np.empty(n)
    F_true = np.empty(n)
    g_log = np.empty(n)
    kap_log = np.empty(n)
    rs = np.array([0.0, q0, 0.0])
    revt = np.empty(100000)
    nrev = 0
    Ff = 0.0
    g = gtime[0]
    kappa = 1.0
    for kk in range(n):
        qm = math.floor(q / cquantum + 0.5) * cquantum
        e = qref[kk] - qm
        vm = (qm - qm_prev) / T
        vf = afilt * vf + (1.0 - afilt) * vm
        I += e * T
        u = Kp * e + Ki * I + Kd * (vref[kk] - vf)
        qm_prev = qm
        q_meas[kk] = math.floor(q / quantum + 0.5) * quantum
        tau[kk] = u
        q_true[kk] = q
        v_true[kk] = v
        F_true[kk] = Ff
        g_log[kk] = g
        kap_log[kk] = kappa
        g0 = gtime[kk]
        g1 = gtime[kk + 1] if kk + 1 < n else g0
        for j in range(nsub):
            g = g0 + (g1 - g0) * (j / nsub)
            if rip_a != 0.0:
                g *= 1.0 + rip_a * math.sin(2.0 * math.pi * q / rip_lam + rip_phi)
            kappa = 1.0
            if soft_h > 0.0:
                kappa = 1.0 - soft_h * (1.0 - math.exp(-rs[2] / soft_n0))
            Kst = 0.0
            Fsum = 0.0
            for i in range(M):
                Fsum += F[i]
                if st[i] == 1:
                    Kst += k[i]
            c1 = sig1 * Kst / K0
            vn = (J * v / dt + u - Fsum) / (J / dt + kappa * Kst * dt + c1 + g * sig2)
            q += vn * dt
            v = vn
            _gms_step(F, st, sd, k, alpha, kappa, g, v, dt, Fcp, Fsp, Fcn, Fsn, vs, dl, decay)
            Ff = c1 * v + g * sig2 * v
            for i in range(M):
                Ff += F[i]
            if _rev_update(q, rs, dsig):
                if nrev < revt.shape[0]:
                    revt[nrev] = kk * T + (j + 1) * dt
                nrev += 1
    return q_meas, tau, q_true, v_true, F_true, g_log, kap_log, revt[:min(nrev, revt.shape[0])]


@njit
def _sim_kinematic(vlog, T, nsub, x0, k, alpha, Fcp, Fsp, Fcn, Fsn, vs, dl, tau_r, sig1, sig2,
                   gtime, rip_a, rip_lam, rip_phi, soft_h, soft_n0, dsig):
    n = vlog.shape[0]
    M = k.shape[0]
    dt = T / nsub
    decay = math.exp(-dt / tau_r)
    K0 = 0.0
    for i in range(M):
        K0 += k[i]
    F = np.zeros(M)
    st = np.ones(M, np.int64)
    sd = np.zeros(M, np.int64)
    x = x0
    x_log = np.empty(n)
    F_log = np.empty(n)
    g_log = np.empty(n)
    kap_log = np.empty(n)
    rs = np.array([0.0, x0, 0.0])
    revt = np.empty(100000)
    nrev = 0
    Ff = 0.0
    g = gtime[0]
    kappa = 1.0
    for kk in range(n):
        x_log[kk] = x
        F_log[kk] = Ff
        g_log[kk] = g
        kap_log[kk] = kappa
        v0 = vlog[kk]
        v1 = vlog[kk + 1] if kk + 1 < n else v0
        g0 = gtime[kk]
        g1 = gtime[kk + 1] if kk + 1 < n else g0
        for j in range(nsub):
            fr = (j + 0.5) / nsub
            v = v0 + (v1 - v0) * fr
            g = g0 + (g1 - g0) * fr
            xm = x + 0.5 * v * dt
            if rip_a != 0.0:
                g *= 1.0 + rip_a * math.sin(2.0 * math.pi * xm / rip_lam + rip_phi)
            kappa = 1.0
            if soft_h > 0.0:
                kappa = 1.0 - soft_h * (1.0 - math.exp(-rs[2] / soft_n0))
            x += v * dt
            _gms_step(F, st, sd, k, alpha, kappa, g, v, dt, Fcp, Fsp, Fcn, Fsn, vs, dl, decay)
            Kst = 0.0
            Ff = g * sig2 * v
            for i in range(M):
                Ff += F[i]
                if st[i] == 1:
                    Kst += k[i]
            Ff += sig1 * Kst / K0 * v
            if _rev_update(x, rs, dsig):
                if nrev < revt.shape[0]:
                    revt[nrev] = kk * T + (j + 1) * dt
                nrev += 1
    return x_log, F_log, g_log, kap_log, revt[:min(nrev, revt.shape[0])]


# ----------------------------------------------------------------------------
# trajectories (analytic piecewise velocity profiles)
# ----------------------------------------------------------------------------
class _Traj:
    """Piecewise analytic motion: dwell, const, ramp (cosine blend v0->v1), osc
    (one-sided cosine excursion x = A(1-cos(2 pi s/T))/2)."""

    def __init__(self):
        self.segs = []
        self.t = 0.0
        self.x = 0.0

    def add(self, typ, T, a=0.0, b=0.0, tag="", **info):
        T = float(T)
        if T <= 0:
            return
        seg = dict(type=typ, t0=self.t, T=T, a=float(a), b=float(b), x0=self.x, tag=tag)
        seg.update(info)
        self.segs.append(seg)
        if typ == "const":
            dx = a * T
        elif typ == "ramp":
            dx = 0.5 * (a + b) * T
        else:
            dx = 0.0
        self.t += T
        self.x += dx

    def evaluate(self, t):
        t = np.asarray(t, float)
        t0 = np.array([s["t0"] for s in self.segs])
        idx = np.clip(np.searchsorted(t0, t, side="right") - 1, 0, len(self.segs) - 1)
        x = np.empty_like(t)
        v = np.empty_like(t)
        for i, s in enumerate(self.segs):
            m = idx == i
            if not m.any():
                continue
            ss = np.clip(t[m] - s["t0"], 0.0, s["T"])
            T, a, b = s["T"], s["a"], s["b"]
            if s["type"] == "dwell":
                x[m] = s["x0"]
                v[m] = 0.0
            elif s["type"] == "const":
                x[m] = s["x0"] + a * ss
                v[m] = a
            elif s["type"] == "ramp":
                v[m] = a + (b - a) * 0.5 * (1 - np.cos(np.pi * ss / T))
                x[m] = s["x0"] + a * ss + 0.5 * (b - a) * (ss - T / np.pi * np.sin(np.pi * ss / T))
            elif s["type"] == "osc":
                x[m] = s["x0"] + 0.5 * a * (1 - np.cos(2 * np.pi * ss / T))
                v[m] = a * np.pi / T * np.sin(2 * np.pi * ss / T)
        last = self.segs[-1]
        after = t > last["t0"] + last["T"]
        x[after] = self.x
        v[after] = 0.0
        return x, v


def _visit(tr, v, L, n_rev, sgn, a_max, Ta_min, visit_id):
    Ta = max(Ta_min, math.pi * v / (2 * a_max))
    Tb = max(2 * Ta_min, math.pi * v / a_max)
    T2 = max(L / v, 1.05 * Ta)
    T1 = 0.5 * (T2 - Ta)
    sv = sgn * v
    info = dict(visit=visit_id, speed=v)
    tr.add("ramp", Ta, 0.0, sv, tag="accel", **info)
    tr.add("const", T1, sv, tag="cv", **info)
    for r in range(n_rev):
        tr.add("ramp", Tb, sv, -sv, tag="rev", **info)
        sv = -sv
        if r < n_rev - 1:
            tr.add("const", T2, sv, tag="cv", **info)
    tr.add("const", T1, sv, tag="cv", **info)
    tr.add("ramp", Ta, sv, 0.0, tag="decel", **info)


def _visit_time(v, L, n_rev, a_max, Ta_min):
    Ta = max(Ta_min, math.pi * v / (2 * a_max))
    Tb = max(2 * Ta_min, math.pi * v / a_max)
    T2 = max(L / v, 1.05 * Ta)
    return 2 * Ta + (T2 - Ta) + n_rev * Tb + (n_rev - 1) * T2


def _shuffled_visits(rng, speeds, reps=2):
    """Non-monotone order, every speed `reps` times, never twice in a row."""
    base = np.repeat(np.arange(len(speeds)), reps)
    for _ in range(10000):
        p = rng.permutation(base)
        if np.any(p[1:] == p[:-1]):
            continue
        first = [int(np.where(p == s)[0][0]) for s in range(len(speeds))]
        rho = np.corrcoef(first, np.arange(len(speeds)))[0, 1]
        if abs(rho) > 0.45:
            continue
        # second visit of each speed well separated from the first
        sep = [np.ptp(np.where(p == s)[0]) for s in range(len(speeds))]
        if min(sep) < 3:
            continue
        return [int(i) for i in p]
    raise RuntimeError("could not shuffle")


def _build_session(rng, D, speeds, L_max, leg_T, a_max, Ta_min, n_rev_fn, osc_blocks, Tc,
                   lead_in, lead_out, dwell_min=0.3, L_min=0.0, leg_T_min=0.8):
    """lead_in / lead_out: lists of (type, T, tag) dwell-like segments.
    Leg length per speed: L = min(L_max, max(v*leg_T, L_min)); leg_T is shrunk
    until the session fits into D (RuntimeError below leg_T_min)."""

    def leg(v):
        return min(L_max, max(v * leg_T, L_min))
    order = _shuffled_visits(rng, speeds)
    signs = rng.choice([-1.0, 1.0], size=len(order))
    nv = len(order)
    block_at = {0: 0, nv // 3: 1, (2 * nv) // 3: 2}
    fixed = sum(s[1] for s in lead_in) + sum(s[1] for s in lead_out)
    fixed += sum(4 * len(b) * Tc for b in osc_blocks)
    ngaps = nv + len(osc_blocks)
    while True:
        tv = 0.0
        for i in order:
            v = speeds[i]
            L = leg(v)
            tv += _visit_time(v, L, n_rev_fn(v, L), a_max, Ta_min)
        total = fixed + tv + ngaps * dwell_min
        if total <= 0.97 * D:
            break
        leg_T *= 0.95
        if leg_T < leg_T_min:
            raise RuntimeError("session does not fit")
    extra = D - total
    w = rng.dirichlet(np.full(ngaps + 1, 4.0)) * extra
    tr = _Traj()
    for s in lead_in:
        tr.add("dwell", s[1], tag=s[2])
    gi = 0
    for vi, i in enumerate(order):
        if vi in block_at:
            b = block_at[vi]
            for A in osc_blocks[b]:
                for rep in range(2):
                    tr.add("osc", Tc, A, tag="osc", block=b, amp=A, rep=rep, sign=1)
                    tr.add("osc", Tc, -A, tag="osc", block=b, amp=A, rep=rep, sign=-1)
            tr.add("dwell", dwell_min + w[gi], tag="dwell")
            gi += 1
        v = speeds[i]
        L = leg(v)
        _visit(tr, v, L, n_rev_fn(v, L), signs[vi], a_max, Ta_min, vi)
        tr.add("dwell", dwell_min + w[gi], tag="dwell")
        gi += 1
    for s in lead_out:
        tr.add("dwell", s[1], tag=s[2])
    if tr.t < D:
        tr.add("dwell", D - tr.t + 1.0, tag="dwell")
    assert abs(tr.x) < 1e-9 * max(1.0, L_max), tr.x
    return tr, order, signs, leg_T


def _smooth_schedule(rng, D, amp, n_knots):
    """Random non-monotone smooth schedule u(t) in [-amp, amp] (cosine
    interpolation between knots, zero slope at the knots)."""
    tk = np.sort(np.concatenate([[0.0, D], rng.uniform(0.05 * D, 0.95 * D, n_knots - 2)]))
    lv = rng.uniform(-1, 1, n_knots)
    j = rng.permutation(np.arange(1, n_knots - 1))
    lv[j[0]], lv[j[1]] = 1.0, -1.0
    lv[0] = rng.uniform(-0.3, 0.3)
    lv = amp * lv

    def u(t):
        t = np.asarray(t, float)
        i = np.clip(np.searchsorted(tk, t, side="right") - 1, 0, n_knots - 2)
        s = (t - tk[i]) / (tk[i + 1] - tk[i])
        s = np.clip(s, 0, 1)
        return lv[i] + (lv[i + 1] - lv[i]) * 0.5 * (1 - np.cos(np.pi * s))

    return u, tk, lv


def _rng(seed, kind_id, stream):
    return np.random.default_rng([int(seed), int(kind_id), int(stream)])


def _loguni(rng, a, b):
    return float(np.exp(rng.uniform(np.log(a), np.log(b))))


def _gms_params(rng, Fs_mean, d_max):
    d = np.geomspace(d_max / 25.0, d_max, N_ELEM) * np.exp(rng.uniform(-0.15, 0.15, N_ELEM))
    d = np.sort(d)
    d[-1] = d_max
    alpha = rng.dirichlet(np.full(N_ELEM, 2.0))
    k = alpha * Fs_mean / d
    return d, alpha, k


def _friction_levels(rng, Fc_mean, asym_max, vs_rng, delta_rng):
    asym = rng.uniform(-asym_max, asym_max)
    Fcp = Fc_mean * (1 + asym / 2)
    Fcn = Fc_mean * (1 - asym / 2)
    r = rng.uniform(1.1, 1.6)
    rp = float(np.clip(r * rng.uniform(0.95, 1.05), 1.1, 1.6))
    rn = float(np.clip(r * rng.uniform(0.95, 1.05), 1.1, 1.6))
    vs = _loguni(rng, *vs_rng)
    dl = rng.uniform(*delta_rng)
    return dict(Fc_pos=Fcp, Fc_neg=Fcn, Fs_pos=Fcp * rp, Fs_neg=Fcn * rn, vs=vs, delta=dl)


def _effect_params(re, effect, D, travel, N_ref):
    ep = {}
    if effect == "position_ripple":
        ep = dict(a=re.uniform(0.05, 0.2), wavelength=travel / re.uniform(3, 15),
                  phase=re.uniform(0, 2 * np.pi),
                  formula="g_x = 1 + a*sin(2*pi*x/wavelength + phase), x = absolute logged position")
    elif effect == "time_drift":
        b = re.uniform(0.15, 0.4) * re.choice([-1.0, 1.0])
        ep = dict(b=b, tau=re.uniform(0.15, 0.5) * D,
                  formula="g_t = 1 + b*(1 - exp(-t/tau)), t in seconds from start of the recording")
    elif effect == "normal_load":
        amp = re.uniform(0.25, 0.45)
        ep = dict(amplitude=amp, alpha=re.uniform(0.6, 1.0), N_ref=N_ref,
                  n_knots=int(re.integers(8, 13)),
                  formula="g_N = (N/N_ref)**alpha ; N = N_ref*(1+u(t)), u smooth random in [-amplitude, amplitude]")
    elif effect == "cyclic_softening":
        ep = dict(h=re.uniform(0.3, 0.6), n0=re.uniform(2, 8),
                  formula="k_i -> k_i*(1 - h*(1-exp(-n/n0))), n = counted significant reversals so far")
    return ep


def _stat_ss(v, fr, g=1.0):
    """Steady-state friction (positive-direction convention) for velocity v."""
    v = np.asarray(v, float)
    va = np.abs(v)
    sp = fr["Fc_pos"] + (fr["Fs_pos"] - fr["Fc_pos"]) * np.exp(-((va / fr["vs"]) ** fr["delta"]))
    sn = fr["Fc_neg"] + (fr["Fs_neg"] - fr["Fc_neg"]) * np.exp(-((va / fr["vs"]) ** fr["delta"]))
    return g * (np.where(v >= 0, sp, -sn) + fr["viscous"] * v)


def steady_state_friction(truth, v, g=1.0):
    """Public helper: steady sliding friction of the simulated machine at
    velocity v (file units, positive-direction convention, i.e. the force
    opposing motion counted positive along +x), times multiplier g."""
    return _stat_ss(v, truth["friction"], g)


# ----------------------------------------------------------------------------
# robot joint
# ----------------------------------------------------------------------------
def _make_robot(seed, effect, debug=False, n_samples=74000, **opts):
    if opts.get("load_ramp"):
        raise ValueError("load_ramp is only supported for the tribometer")
    kid = _KIND_ID["robot_joint"]
    rm = _rng(seed, kid, 0)
    re = _rng(seed, kid, 10 + _EFF_ID[effect])
    rn = _rng(seed, kid, 100 + _EFF_ID[effect])
    fs = 500.0
    T = 1.0 / fs
    n = int(n_samples)
    D = n * T
    # --- machine (joint size correlates inertia and friction level) ---
    u = rm.uniform()
    J = 0.2 * 15.0 ** float(np.clip(u + rm.normal(0, 0.08), 0, 1))
    Fc = 3.0 * (40.0 / 3.0) ** float(np.clip(u + rm.normal(0, 0.08), 0, 1))
    fr = _friction_levels(rm, Fc, 0.15, (0.005, 0.05), (0.7, 2.0))
    fr["Fc_pos"] = float(np.clip(fr["Fc_pos"], 3, 40))
    fr["Fc_neg"] = float(np.clip(fr["Fc_neg"], 3, 40))
    fr["viscous"] = _loguni(rm, 0.5, 10.0)
    Fs_mean = 0.5 * (fr["Fs_pos"] + fr["Fs_neg"])
    d_max = _loguni(rm, 2e-5, 8e-5)
    d, alpha, k = _gms_params(rm, Fs_mean, d_max)
    K0 = float(k.sum())
    tau_r = rm.uniform(0.002, 0.01)
    zeta_mu = rm.uniform(0.05, 0.3)
    sig1 = 2 * zeta_mu * math.sqrt(K0 * J)
    # --- controller ---
    wc = rm.uniform(80, 130)
    zc = rm.uniform(0.7, 1.0)
    wi = wc * rm.uniform(0.25, 0.5)
    Kp = J * wc ** 2
    Kd = 2 * zc * J * wc
    Ki = Kp * wi
    fd = rm.uniform(100, 200)
    afilt = math.exp(-2 * math.pi * fd * T)
    quantum = 2 * math.pi / 2 ** ENCODER_BITS
    gear = rm.uniform(50, 160)
    cquantum = quantum / gear
    q0 = rm.uniform(-0.5, 0.5)
    # --- trajectory ---
    speeds = [0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]
    a_max = rm.uniform(2.0, 5.0)
    Tc = rm.uniform(1.2, 1.8)
    osc_blocks = [rm.uniform(200e-6, 600e-6, 3).tolist() for _ in range(3)]
    tr, order, signs, leg_T = _build_session(
        rm, D, speeds, L_max=0.6, leg_T=2.5, a_max=a_max, Ta_min=0.05,
        n_rev_fn=lambda v, L: 2, osc_blocks=osc_blocks, Tc=Tc,
        lead_in=[("dwell", 1.0, "dwell")], lead_out=[("dwell", 1.0, "dwell")])
    t = np.arange(n) * T
    xr, vr = tr.evaluate(t)
    qref = q0 + xr
    travel = float(np.ptp(xr))
    # --- effects ---
    N_ref = rm.uniform(1000, 5000)
    ep = _effect_params(re, effect, D, travel, N_ref)
    gtime = np.ones(n)
    Nt = None
    if effect == "time_drift":
        gtime *= 1 + ep["b"] * (1 - np.exp(-t / ep["tau"]))
    if effect == "normal_load":
        ufun, tk, lv = _smooth_schedule(re, D, ep["amplitude"], ep["n_knots"])
        Nt = N_ref * (1 + ufun(t))
        ep["knots_t"] = tk
        ep["knots_u"] = lv
        gtime *= (Nt / N_ref) ** ep["alpha"]
    rip_a = ep.get("a", 0.0)
    rip_lam = ep.get("wavelength", 1.0)
    rip_phi = ep.get("phase", 0.0) + 0.0
    soft_h = ep.get("h", 0.0)
    soft_n0 = ep.get("n0", 1.0)
    dsig = 0.25 * d_max
    nsub = int(round(INNER_RATE_HZ / fs))
    out = _sim_robot(qref, vr, T, nsub, J, Kp, Ki, Kd, afilt, quantum, cquantum, q0,
                     k, alpha, fr["Fc_pos"], fr["Fs_pos"], fr["Fc_neg"], fr["Fs_neg"],
                     fr["vs"], fr["delta"], tau_r, sig1, fr["viscous"],
                     gtime, rip_a, rip_lam, rip_phi, soft_h, soft_n0, dsig)
    q_meas, tau, q_true, v_true, F_true, g_log, kap_log, revt = out
    if not np.all(np.isfinite(q_true)) or np.max(np.abs(q_true - qref)) > 1.0:
        raise RuntimeError("robot simulation ran away")
    sig_tau = 0.005 * Fc
    cols = {"t [s]": t, "q [rad]": q_meas, "tau_motor [N*m]": tau + rn.normal(0, sig_tau, n)}
    sig_N = 0.002 * N_ref
    if Nt is not None:
        cols["N [N]"] = Nt + rn.normal(0, sig_N, n)
    df = pd.DataFrame(cols)
    truth = dict(
        kind="robot_joint", effect=effect, seed=int(seed), options=dict(n_samples=n),
        generator="synth/elsewhere.py",
        columns=list(cols.keys()),
        units=dict(time="s", position="rad", torque="N*m", velocity="rad/s", normal_load="N",
                   stiffness="N*m/rad", viscous="N*m*s/rad"),
        sign_convention=("tau_motor drives the joint in +q. Friction torque F opposes motion: "
                         "J*qdd = tau_motor - F, F > 0 while q increases. At steady speed "
                         "tau_motor ~= F_ss(v) (positive for v>0, negative for v<0). tau_motor[k] is "
                         "the PID command computed from q[k] and held over [t_k, t_k+1)."),
        sample_rate_hz=fs, n_samples=n, duration_s=D,
        plant=dict(J=J, gravity="none (horizontal joint)"),
        friction=dict(model="GMS, 8 elements, rate-dependent sliding law (see module docstring)",
                      **fr, stribeck_formula="s(v)=Fc+(Fs-Fc)*exp(-(|v|/vs)**delta), per direction",
                      steady_state="F_ss(v) = g*(sign(v)*s_dir(|v|) + viscous*v)",
                      n_elements=N_ELEM, alpha=alpha, k=k, break_displacement=d,
                      presliding_d_max=d_max, K0=K0, tau_r=tau_r, sigma1_microdamping=sig1,
                      microdamping_zeta=zeta_mu),
        controller=dict(type=("discrete PID at 500 Hz on the motor-side encoder (18-bit motor encoder "
                              "through the gear: resolution quantum_rad/gear_ratio), velocity "
                              "feed-forward in D; the LOGGED q is the joint-side 18-bit encoder"),
                        gear_ratio=gear, control_position_resolution_rad=cquantum,
                        law=("u=Kp*e+Ki*sum(e)*T+Kd*(v_ref - v_f), e=q_ref-q_c; "
                             "v_f=a*v_f+(1-a)*(q_c[k]-q_c[k-1])/T; q_c = motor-side measured position"),
                        Kp=Kp, Ki=Ki, Kd=Kd, a_filter=afilt, f_derivative_hz=fd, wc=wc, zeta=zc, wi=wi),
        encoder=dict(bits=ENCODER_BITS, quantum_rad=quantum, rounding="nearest"),
        noise=dict(tau_sigma=sig_tau, N_sigma=sig_N if Nt is not None else None),
        effect_params=ep,
        trajectory=dict(
            description=("q_ref = q0 + x(t): 1 s dwell, 3 presliding blocks (one-sided cosine "
                         "excursions +A,-A,+A,-A for three amplitudes each, period Tc) at visits 0, "
                         "n/3, 2n/3, and 16 stroke visits (8 speeds x 2, shuffled): ramp up, "
                         "const, blended reversal, const (2 legs of length L), ramp down, "
                         "dwell. Each visit returns to q0."),
            q0=q0, speeds=speeds, visit_order=[speeds[i] for i in order], visit_signs=signs,
            a_max=a_max, presliding_amplitudes=osc_blocks, presliding_period=Tc,
            leg_time_max=leg_T, travel=travel, segments=tr.segs),
        reversals=dict(rule="counted when the true position moves back by more than threshold "
                            "from the last extremum", threshold=dsig, count=int(len(revt)),
                       times_s=revt),
        integrator=dict(inner_rate_hz=INNER_RATE_HZ, scheme="linearly-implicit Euler, ZOH torque"),
        tracking=dict(max_abs_error_rad=float(np.max(np.abs(qref - q_true))),
                      rms_error_rad=float(np.sqrt(np.mean((qref - q_true) ** 2)))),
    )
    if debug:
        truth["_debug"] = dict(t=t, qref=qref, vref=vr, q_true=q_true, v_true=v_true,
                               F_true=F_true, g=g_log, kappa=kap_log, tau_cmd=tau, N=Nt)
    return df, truth


# ----------------------------------------------------------------------------
# tribometer
# ----------------------------------------------------------------------------
def _make_tribometer(seed, effect, debug=False, load_ramp=False, **opts):
    kid = _KIND_ID["tribometer"]
    rm = _rng(seed, kid, 0)
    re = _rng(seed, kid, 10 + _EFF_ID[effect] + (50 if load_ramp else 0))
    rn = _rng(seed, kid, 100 + _EFF_ID[effect] + (50 if load_ramp else 0))
    fs = float(opts.get("fs", rm.choice([200.0, 250.0, 400.0, 500.0, 1000.0])))
    n_lo = int(max(30000, 60 * fs))
    n_hi = int(min(60000, 240 * fs))
    n = int(opts.get("n_samples", rm.integers(n_lo, n_hi + 1)))
    T = 1.0 / fs
    D = n * T
    N0 = rm.uniform(2, 10)
    mu_c = rm.uniform(0.1, 0.5)
    Fc = mu_c * N0 * 1000.0  # mN
    fr = _friction_levels(rm, Fc, 0.1, (0.05, 0.5), (0.7, 2.0))
    S = rm.uniform(2, 8)
    v_lo = _loguni(rm, 0.01, 0.03)
    v_hi = min(rm.uniform(10, 25), S / 0.3)
    fr["viscous"] = rm.uniform(0.05, 0.2) * Fc / v_hi
    Fs_mean = 0.5 * (fr["Fs_pos"] + fr["Fs_neg"])
    d_max = _loguni(rm, 5e-4, 3e-3)
    d, alpha, k = _gms_params(rm, Fs_mean, d_max)
    K0 = float(k.sum())
    tau_r = rm.uniform(0.002, 0.01)
    tau_mu = rm.uniform(0.05e-3, 0.3e-3)
    sig1 = K0 * tau_mu
    x0 = rm.uniform(-1, 1)
    jit = np.exp(rm.uniform(-0.05, 0.05, 7))
    a_max = rm.uniform(200, 800)
    Tc = float(np.clip(D / 100.0, 0.6, 2.0)) * rm.uniform(0.9, 1.1)
    osc_blocks = [rm.uniform(1e-3, 5e-3, 2).tolist() for _ in range(3)]
    T_r = rm.uniform(2.0, 5.0)
    if load_ramp:
        lead_in = [("dwell", 0.5, "preload"), ("dwell", T_r, "load_up"), ("dwell", 1.0, "dwell")]
        lead_out = [("dwell", 1.0, "dwell"), ("dwell", T_r, "load_down"), ("dwell", 0.5, "unloaded")]
    else:
        lead_in = [("dwell", 1.0, "dwell")]
        lead_out = [("dwell", 0.5, "dwell")]
    # 7 log-spaced speeds; fewer (same range) if a short session cannot hold them
    # with legs of >= 1 s and >= 14*d_max of travel
    rs = np.random.default_rng([int(seed), kid, 7])
    for n_sp in (7, 6, 5, 4):
        speeds = np.geomspace(v_lo, v_hi, n_sp) * jit[:n_sp]
        speeds = [float(f"{s:.3g}") for s in speeds]
        try:
            tr, order, signs, leg_T = _build_session(
                np.random.default_rng(rs.integers(2**31)), D, speeds, L_max=S,
                leg_T=min(6.0, D / 25.0), a_max=a_max, Ta_min=0.03,
                n_rev_fn=lambda v, L: 4 if L / v < 1.0 else 2, osc_blocks=osc_blocks, Tc=Tc,
                lead_in=lead_in, lead_out=lead_out, L_min=14 * d_max, leg_T_min=1.0)
            break
        except RuntimeError:
            continue
    else:
        raise RuntimeError("tribometer session does not fit")
    t = np.arange(n) * T
    xr, vr = tr.evaluate(t)
    travel = float(np.ptp(xr))
    # --- load & effects ---
    ep = _effect_params(re, effect, D, travel, N0)
    r = np.ones(n)
    N_start = 0.02 * N0
    if load_ramp:
        su = [s for s in tr.segs if s["tag"] == "load_up"][0]
        sdn = [s for s in tr.segs if s["tag"] == "load_down"][0]
        f0 = N_start / N0

        def ramp(tt, s, up):
            z = np.clip((tt - s["t0"]) / s["T"], 0, 1)
            c = 0.5 * (1 - np.cos(np.pi * z))
            return f0 + (1 - f0) * (c if up else 1 - c)

        r = np.where(t < su["t0"] + su["T"], ramp(t, su, True), 1.0)
        r = np.where(t >= sdn["t0"], ramp(t, sdn, False), r)
    Nt = N0 * r
    alpha_N = 1.0
    if effect == "normal_load":
        ufun, tk, lv = _smooth_schedule(re, D, ep["amplitude"], ep["n_knots"])
        Nt = Nt * (1 + ufun(t))
        ep["knots_t"] = tk
        ep["knots_u"] = lv
        alpha_N = ep["alpha"]
    gtime = (Nt / N0) ** alpha_N
    if effect == "time_drift":
        gtime = gtime * (1 + ep["b"] * (1 - np.exp(-t / ep["tau"])))
    rip_a = ep.get("a", 0.0)
    rip_lam = ep.get("wavelength", 1.0)
    rip_phi = ep.get("phase", 0.0) + 0.0
    soft_h = ep.get("h", 0.0)
    soft_n0 = ep.get("n0", 1.0)
    dsig = 0.25 * d_max
    nsub = int(round(INNER_RATE_HZ / fs))
    x_log, F_log, g_log, kap_log, revt = _sim_kinematic(
        vr, T, nsub, x0, k, alpha, fr["Fc_pos"], fr["Fs_pos"], fr["Fc_neg"], fr["Fs_neg"],
        fr["vs"], fr["delta"], tau_r, sig1, fr["viscous"], gtime, rip_a, rip_lam, rip_phi,
        soft_h, soft_n0, dsig)
    sig_F = 0.01 * Fc
    sig_N = 0.002 * N0
    cols = {"t [ms]": t * 1000.0, "x [mm]": np.round(x_log, 7),
            "F_friction [mN]": -F_log + rn.normal(0, sig_F, n),
            "N [N]": Nt + rn.normal(0, sig_N, n)}
    df = pd.DataFrame(cols)
    truth = dict(
        kind="tribometer", effect=effect, seed=int(seed),
        options=dict(load_ramp=bool(load_ramp), fs=fs, n_samples=n),
        generator="synth/elsewhere.py",
        columns=list(cols.keys()),
        units=dict(time="ms (column t); all rates and time constants in this json are in s",
                   position="mm", force="mN", velocity="mm/s", normal_load="N",
                   stiffness="mN/mm", viscous="mN/(mm/s)"),
        sign_convention=("F_friction [mN] is the load-cell REACTION force = -F, where F is the "
                         "friction force counted positive along +x while x increases. So "
                         "F_friction < 0 while x increases and > 0 while x decreases; at steady "
                         "speed F_friction ~= -F_ss(v)."),
        sample_rate_hz=fs, n_samples=n, duration_s=D,
        normal_load=dict(N0=N0, mu_coulomb=mu_c, friction_scaling="levels and viscous ~ (N/N0)**alpha_N",
                         alpha_N=alpha_N, load_ramp=bool(load_ramp), N_start=N_start if load_ramp else None,
                         ramp_time_s=T_r if load_ramp else None,
                         stiffness_scaling="presliding stiffness independent of N"),
        friction=dict(model="GMS, 8 elements, rate-dependent sliding law (see module docstring)",
                      **fr, stribeck_formula="s(v)=Fc+(Fs-Fc)*exp(-(|v|/vs)**delta), per direction",
                      steady_state="F_ss(v) = g*(sign(v)*s_dir(|v|) + viscous*v), levels at N0",
                      n_elements=N_ELEM, alpha=alpha, k=k, break_displacement=d,
                      presliding_d_max=d_max, K0=K0, tau_r=tau_r, sigma1_microdamping=sig1),
        noise=dict(F_sigma=sig_F, N_sigma=sig_N, x="exact prescribed position rounded to 1e-7 mm"),
        effect_params=ep,
        trajectory=dict(
            description=("prescribed x = x0 + x(t): dwell, 3 blocks of tiny one-sided cosine "
                         "oscillations (+A,-A,+A,-A for two amplitudes of 1-5 um, period Tc), "
                         f"{2 * len(speeds)} stroke visits ({len(speeds)} speeds x 2, shuffled, 2 or 4 "
                         "blended reversals, legs of length <= stroke S), dwells"
                         + ("; load ramps from ~0 to N0 at the start and back at the end while "
                            "the contact sticks (x constant)" if load_ramp else "")),
            x0=x0, stroke=S, speeds=speeds, visit_order=[speeds[i] for i in order],
            visit_signs=signs, a_max=a_max, osc_amplitudes=osc_blocks, osc_period=Tc,
            leg_time_max=leg_T, travel=travel, segments=tr.segs),
        reversals=dict(rule="counted when the position moves back by more than threshold "
                            "from the last extremum", threshold=dsig, count=int(len(revt)),
                       times_s=revt),
        integrator=dict(inner_rate_hz=INNER_RATE_HZ,
                        scheme="prescribed motion, v linear between samples, exact GMS relaxation"),
    )
    if debug:
        truth["_debug"] = dict(t=t, x_true=x_log, v_true=vr, F_true=F_log, g=g_log,
                               kappa=kap_log, N=Nt)
    return df, truth


# ----------------------------------------------------------------------------
# public API
# ----------------------------------------------------------------------------
def make(kind, seed, effect="none", **opts):
    """Simulate one recording. Returns (pandas.DataFrame, truth dict).

    kind: 'robot_joint' | 'tribometer'; effect: one of EFFECTS.
    opts: load_ramp=True (tribometer), debug=True (adds truth['_debug'] with the
    noiseless internal signals), n_samples=..., fs=... (tribometer)."""
    if effect not in EFFECTS:
        raise ValueError(f"unknown effect {effect!r}")
    if kind == "robot_joint":
        return _make_robot(seed, effect, **opts)
    if kind == "tribometer":
        return _make_tribometer(seed, effect, **opts)
    raise ValueError(f"unknown kind {kind!r}")


def _jsonable(o):
    if isinstance(o, dict):
        return {str(k): _jsonable(v) for k, v in o.items() if not str(k).startswith("_")}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, np.ndarray):
        return [_jsonable(v) for v in o.tolist()]
    if isinstance(o, (np.floating,)):
        return float(o)
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, (np.bool_,)):
        return bool(o)
    return o


def file_stem(kind, seed, effect, load_ramp=False):
    return f"{kind}_{effect}_{'loadramp_' if load_ramp else ''}{seed}"


def write(kind, seed, effect, folder, df_truth=None, **opts):
    """Write <kind>_<effect>_<seed>.csv and .json (truth) into folder."""
    os.makedirs(folder, exist_ok=True)
    df, truth = df_truth if df_truth is not None else make(kind, seed, effect, **opts)
    stem = file_stem(kind, seed, effect, opts.get("load_ramp", False))
    csv = os.path.join(folder, stem + ".csv")
    df.to_csv(csv, index=False, float_format="%.10g")
    with open(os.path.join(folder, stem + ".json"), "w") as fh:
        json.dump(_jsonable(truth), fh, indent=1)
    return csv, df, truth


# ----------------------------------------------------------------------------
# sanity checks (use the noiseless internals from debug=True)
# ----------------------------------------------------------------------------
def _windows(truth, t, min_T, skip=0.4):
    out = []
    for s in truth["trajectory"]["segments"]:
        if s["tag"] == "cv" and s["T"] >= min_T:
            a = s["t0"] + skip * s["T"]
            b = s["t0"] + 0.95 * s["T"]
            m = (t >= a) & (t <= b)
            if m.sum() >= 10:
                out.append((s, m))
    return out


def _closure_test(truth):
    """Drive this machine's contact model (g=1) with prescribed presliding
    cycles (peak 0.7*d_max and nested 0.35*d_max, i.e. below gross sliding) and
    report the loop-closure error max|dF|/Fc and the force swing/Fc."""
    fr = truth["friction"]
    Fc = 0.5 * (fr["Fc_pos"] + fr["Fc_neg"])
    A = 0.7 * fr["presliding_d_max"]
    tr = _Traj()
    tr.add("dwell", 0.2)
    seq = [A, -A, A, -A, 0.5 * A, -0.5 * A, 0.5 * A, -0.5 * A, A, -A]
    for a in seq:
        tr.add("osc", 1.0, a)
    tr.add("dwell", 0.2)
    fs = 1000.0
    t = np.arange(int(tr.t * fs)) / fs
    x, v = tr.evaluate(t)
    k = np.asarray(fr["k"], float)
    al = np.asarray(fr["alpha"], float)
    _, F, _, _, _ = _sim_kinematic(v, 1 / fs, 20, 0.0, k, al, fr["Fc_pos"], fr["Fs_pos"], fr["Fc_neg"],
                                   fr["Fs_neg"], fr["vs"], fr["delta"], fr["tau_r"], 0.0,
                                   fr["viscous"], np.ones(len(t)), 0.0, 1.0, 0.0, 0.0, 1.0, 1e9)
    seg = [s for s in tr.segs if s["type"] == "osc"]

    def cyc(i, a=0.0):
        s = seg[i]
        return np.interp(s["t0"] + np.linspace(a, 1, 101) * s["T"], t, F)

    # Masing / memory rules: a loop that starts at a reversal point returns to
    # it; compare the branches that must coincide.
    e1 = np.max(np.abs(cyc(3, 0.5) - cyc(1, 0.5)))    # back at -A after the outer loop
    e2 = np.max(np.abs(cyc(9) - cyc(3)))              # outer loop after nested inner loops
    e3 = np.max(np.abs(cyc(7, 0.5) - cyc(5, 0.5)))    # inner loop closes at -A/2
    swing = np.ptp(F[(t > seg[2]["t0"]) & (t < seg[3]["t0"] + 1)])
    return dict(outer=round(float(e1 / Fc), 6), after_inner=round(float(e2 / Fc), 6),
                inner=round(float(e3 / Fc), 6), swing_over_Fc=round(float(swing / Fc), 3))


def sanity(df, truth, csv=None):
    """Return a dict of plausibility numbers for one recording."""
    dbg = truth["_debug"]
    kind = truth["kind"]
    eff = truth["effect"]
    fr = truth["friction"]
    Fc = 0.5 * (fr["Fc_pos"] + fr["Fc_neg"])
    t = dbg["t"]
    res = {}
    if kind == "robot_joint":
        xt = dbg["q_true"]
        meas = df["tau_motor [N*m]"].to_numpy()
        xlog = df["q [rad]"].to_numpy()
        res["track_max_err_rad"] = float(np.max(np.abs(dbg["qref"] - xt)))
        res["track_rms_err_rad"] = float(np.sqrt(np.mean((dbg["qref"] - xt) ** 2)))
        cv = []
        for s, m in _windows(truth, t, 0.3):
            cv.append(np.max(np.abs(dbg["qref"][m] - xt[m])))
        res["track_max_err_in_cv_rad"] = float(np.max(cv))
        qd = truth["encoder"]["quantum_rad"]
        q_src = pd.read_csv(csv)["q [rad]"].to_numpy() if csv else xlog
        res["encoder_max_frac_dev"] = float(np.max(np.abs(q_src / qd - np.round(q_src / qd))))
        res["encoder_distinct_steps"] = int(len(np.unique(np.round(np.diff(q_src) / qd))))
    else:
        xt = dbg["x_true"]
        meas = -df["F_friction [mN]"].to_numpy()
        xlog = df["x [mm]"].to_numpy()
    g = dbg["g"]
    # --- Stribeck reproduction from the logged data in constant-velocity windows ---
    rows = {}
    tt = t
    for s, m in _windows(truth, t, 0.3 if kind == "robot_joint" else 0.15):
        vfit = np.polyfit(tt[m], xlog[m], 1)[0]
        model = _stat_ss(vfit, fr, 1.0) * np.mean(g[m])
        ratio = np.mean(meas[m]) / model
        vcv = np.std(dbg["v_true"][m]) / abs(np.mean(dbg["v_true"][m]))
        key = (s["speed"], int(np.sign(s["a"])))
        rows.setdefault(key, []).append((ratio, vcv))
    tab = []
    for (v, sg), lst in sorted(rows.items()):
        rr = np.array(lst)
        tab.append((v, sg, float(np.median(rr[:, 0])), float(np.max(rr[:, 1]))))
    res["stribeck_table(v,dir,meas/model,vel_cv)"] = [
        (f"{v:.3g}", sg, round(r, 3), round(c, 3)) for v, sg, r, c in tab]
    steady = [r for v, sg, r, c in tab if c < 0.1]
    res["stribeck_ratio_steady_range"] = (round(min(steady), 3), round(max(steady), 3)) if steady else None
    res["stribeck_n_unsteady(vel_cv>=0.1)"] = int(sum(c >= 0.1 for *_, c in tab))
    # --- presliding loop closure: compare cycle pair rep 0 vs rep 1 in each osc block ---
    segs = truth["trajectory"]["segments"]
    clo = []
    for s in segs:
        if s["tag"] == "osc" and s["rep"] == 1 and s["sign"] == -1:
            s0 = [z for z in segs if z["tag"] == "osc" and z["block"] == s["block"]
                  and z["amp"] == s["amp"] and z["rep"] == 0 and z["sign"] == s["sign"]][0]
            ph = np.linspace(0.5, 0.98, 50) * s["T"]   # from the -A reversal back to 0
            F1 = np.interp(s0["t0"] + ph, t, dbg["F_true"])
            F2 = np.interp(s["t0"] + ph, t, dbg["F_true"])
            x1 = np.interp(s0["t0"] + ph, t, xt)
            x2 = np.interp(s["t0"] + ph, t, xt)
            clo.append((np.max(np.abs(F2 - F1)) / Fc, np.max(np.abs(x2 - x1))))
    clo = np.array(clo)
    res["data_loop_closure_max_dF/Fc"] = float(np.max(clo[:, 0]))
    res["data_loop_closure_max_dx"] = float(np.max(clo[:, 1]))
    res["model_presliding_closure"] = _closure_test(truth)
    # presliding excursion actually reached (true) in osc blocks
    ex = []
    for s in segs:
        if s["tag"] == "osc":
            m = (t >= s["t0"]) & (t <= s["t0"] + s["T"])
            ex.append(np.ptp(xt[m]))
    res["osc_true_excursion_range"] = (float(np.min(ex)), float(np.max(ex)))
    Fr = []
    for s in segs:
        if s["tag"] == "osc":
            m = (t >= s["t0"]) & (t <= s["t0"] + s["T"])
            Fr.append(np.ptp(dbg["F_true"][m]) / Fc)
    res["osc_force_swing/Fc_range"] = (round(float(np.min(Fr)), 3), round(float(np.max(Fr)), 3))
    res["reversals_total"] = truth["reversals"]["count"]
    revt = np.asarray(truth["reversals"]["times_s"])
    osc_mask = np.zeros_like(revt, bool)
    for s in segs:
        if s["tag"] == "osc":
            osc_mask |= (revt >= s["t0"]) & (revt <= s["t0"] + s["T"] + 0.05)
    res["reversals_in_presliding_blocks"] = int(osc_mask.sum())
    # --- effect visibility ---
    wins = _windows(truth, t, 0.3 if kind == "robot_joint" else 0.15)
    pts = []
    for s, m in wins:
        vfit = np.polyfit(tt[m], xlog[m], 1)[0]
        if abs(vfit) < 2 * fr["vs"]:
            continue
        base = _stat_ss(vfit, fr, 1.0)
        pts.append((tt[m], xlog[m], meas[m] / base, m))
    if eff == "time_drift":
        ep = truth["effect_params"]
        D = truth["duration_s"]
        e_ = [np.mean(r) for tw, xw, r, m in pts if tw[0] < 0.3 * D]
        l_ = [np.mean(r) for tw, xw, r, m in pts if tw[0] > 0.7 * D]
        te = np.mean([np.mean(tw) for tw, xw, r, m in pts if tw[0] < 0.3 * D])
        tl = np.mean([np.mean(tw) for tw, xw, r, m in pts if tw[0] > 0.7 * D])
        gt = lambda x: 1 + ep["b"] * (1 - np.exp(-x / ep["tau"]))
        res["drift_late/early_measured"] = round(float(np.mean(l_) / np.mean(e_)), 3)
        res["drift_late/early_truth"] = round(float(gt(tl) / gt(te)), 3)
    if eff == "position_ripple":
        ep = truth["effect_params"]
        X = np.concatenate([xw for tw, xw, r, m in pts])
        R = np.concatenate([r for tw, xw, r, m in pts])
        ph = 2 * np.pi * X / ep["wavelength"]
        A = np.column_stack([np.ones_like(X), np.sin(ph), np.cos(ph)])
        c = np.linalg.lstsq(A, R, rcond=None)[0]
        res["ripple_amp_measured"] = round(float(np.hypot(c[1], c[2]) / c[0]), 4)
        res["ripple_amp_truth"] = round(ep["a"], 4)
        res["ripple_phase_measured"] = round(float(np.arctan2(c[2], c[1]) % (2 * np.pi)), 3)
        res["ripple_phase_truth"] = round(ep["phase"] % (2 * np.pi), 3)
    if eff == "normal_load":
        ep = truth["effect_params"]
        Ncol = df["N [N]"].to_numpy()
        Nref = ep["N_ref"]
        L = np.concatenate([np.log(np.mean(r)) * np.ones(1) for tw, xw, r, m in pts])
        Ln = np.array([np.log(np.mean(Ncol[m]) / Nref) for tw, xw, r, m in pts])
        c = np.polyfit(Ln, L, 1)
        res["load_alpha_measured"] = round(float(c[0]), 3)
        res["load_alpha_truth"] = round(ep["alpha"], 3)
        res["load_N_range/N_ref"] = (round(float(Ncol.min() / Nref), 3), round(float(Ncol.max() / Nref), 3))
        d = np.diff(np.sign(np.diff(dbg["N"][:: max(1, len(t) // 2000)])))
        res["load_n_turning_points"] = int(np.sum(d != 0))
    # secant stiffness after reversals in the presliding blocks (noiseless internals):
    # from the position extremum to the first sample with |dF| >= 0.3 Fc
    Ft = dbg["F_true"]
    ks = {}
    nwin = int(0.5 * truth["sample_rate_hz"])
    for trv in revt[osc_mask]:
        i1 = int(np.searchsorted(t, trv))
        i0 = max(0, i1 - nwin)
        if i1 - i0 < 3 or i1 + nwin > len(t):
            continue
        seg_x = xt[i0:i1]
        up = xt[i1] < seg_x.max() - 1e-15 and np.argmax(seg_x) >= np.argmin(seg_x)
        j = i0 + (int(np.argmax(seg_x)) if up else int(np.argmin(seg_x)))
        dF = np.abs(Ft[j:j + 2 * nwin] - Ft[j])
        hit = np.nonzero(dF >= 0.3 * Fc)[0]
        if len(hit) == 0:
            continue
        h = hit[0]
        dx = abs(xt[j + h] - xt[j])
        if dx > 0:
            b = [s["block"] for s in segs if s["tag"] == "osc" and s["t0"] <= trv <= s["t0"] + s["T"] + 0.05]
            ks.setdefault(b[0], []).append(dF[h] / dx)
    res["presliding_secant_k/K0_per_block"] = [round(float(np.median(ks[b]) / fr["K0"]), 3)
                                               for b in sorted(ks)]
    kap = []
    for b in sorted(ks):
        s0 = [s for s in segs if s["tag"] == "osc" and s["block"] == b][0]
        kap.append(round(float(np.interp(s0["t0"], t, dbg["kappa"])), 3))
    res["kappa_truth_at_block_start"] = kap
    if kind == "tribometer" and truth["options"]["load_ramp"]:
        sdn = [s for s in segs if s["tag"] == "load_down"][0]
        m = (t >= sdn["t0"]) & (t <= sdn["t0"] + sdn["T"])
        Ncol = df["N [N]"].to_numpy()
        Fm = df["F_friction [mN]"].to_numpy()
        c = np.polyfit(Ncol[m], Fm[m], 1)
        res["loadramp_down_F_vs_N_slope_mN/N"] = round(float(c[0]), 2)
        res["loadramp_down_F_vs_N_intercept_mN"] = round(float(c[1]), 2)
        res["loadramp_down_corr"] = round(float(np.corrcoef(Ncol[m], Fm[m])[0, 1]), 4)
        res["loadramp_residual_F_before/after_mN"] = (round(float(np.mean(Fm[m][:20])), 1),
                                                      round(float(np.mean(Fm[m][-20:])), 1))
    return res


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    ap.add_argument("outdir")
    ap.add_argument("--seeds", type=int, nargs="+", default=[1])
    ap.add_argument("--kinds", nargs="+", default=list(KINDS), choices=KINDS)
    ap.add_argument("--effects", nargs="+", default=list(EFFECTS), choices=EFFECTS)
    ap.add_argument("--load-ramp", action="store_true",
                    help="(tribometer) also write load-ramp variants")
    ap.add_argument("--check", action="store_true", help="print sanity numbers")
    a = ap.parse_args(argv)
    for seed in a.seeds:
        for kind in a.kinds:
            for eff in a.effects:
                variants = [False, True] if (a.load_ramp and kind == "tribometer") else [False]
                for lr in variants:
                    opts = dict(load_ramp=True) if lr else {}
                    t0 = time.perf_counter()
                    df, truth = make(kind, seed, eff, debug=a.check, **opts)
                    dt = time.perf_counter() - t0
                    csv, _, _ = write(kind, seed, eff, a.outdir, df_truth=(df, truth), **opts)
                    print(f"{csv}  rows={len(df)}  fs={truth['sample_rate_hz']:g}Hz  "
                          f"reversals={truth['reversals']['count']}  sim={dt:.1f}s", flush=True)
                    if a.check:
                        for k_, v_ in sanity(df, truth, csv).items():
                            print(f"    {k_}: {v_}")


if __name__ == "__main__":
    main()
