"""Recordings of machines the project has never seen: an independent generator for testing the fit.

Nothing here calls ``leuven_friction.model``. The friction is a *generalized Maxwell-slip*
model (an assembly of elasto-slide elements), not the Leuven model the fit assumes:

* element i is a spring of stiffness k_i whose force F_i is limited to α_i·S(v) (Σα_i = 1), with
  S(v) = Fc + (Fs − Fc)·exp(−|v/vs|^δ) per velocity sign (asymmetric sides); at v = 0 the limits
  are α_i·Fs⁺ and α_i·Fs⁻. Presliding hysteresis with non-local memory (Masing's rules, internal
  loops wiped out) follows from the elements themselves, not from a stack;
* F = m(t)·(ΣF_i + σ1·κ_stick·v + σ2·v), where κ_stick is the stiffness fraction of the elements
  still sticking (a micro-damping that vanishes in gross sliding) and m(t) a friction multiplier;
* steady sliding saturates every element, so F = S(v) + σ2·v exactly: the truth for S(v);
* the plant I·ẍ = u − F is integrated with a fixed-step semi-implicit Euler scheme (damping and
  viscous terms implicit), the step chosen well inside the stability limit of the stiffest
  presliding spring; a velocity PI controller runs at the sample rate (sample-and-hold).

Kinds (``make_recording(kind, seed)``):

``robot_joint``  rad, N·m: open-loop presliding torque ramps with internal loops, then a
    closed-loop constant-velocity sweep (PI on a noisy tachometer); encoder-quantised position,
    tachometer ``velocity`` column, noisy applied torque. Action sign.
``linear_stage`` mm, N: presliding force ramps and a closed-loop velocity sweep; position from
    a scale with Gaussian noise, no velocity column. Action sign.
``tribometer``   mm, µN: imposed reciprocating strokes with dwells, measured friction logged as
    a *reaction* (positive while the position decreases), a ``Normal [uN]`` column ramped
    0 → N0 before the first stroke and back after the last while the contact sticks;
    friction ∝ load.

Options: ``rate`` (100 Hz … 10 kHz), ``one_sided`` (velocity levels on the positive side
only), ``irregular`` (jittered time steps and a few gaps), ``normal_load`` (a schedule
N(t) in newtons logged as a column), and the hidden-effect hooks ``friction_modifier(ctx)``
and ``stiffness_modifier(ctx)``: called inside the simulation loop, block by block (a block
is ``HOOK_BLOCK`` samples), with ``ctx`` a :class:`Context` of arrays over that block — t, x,
v (the state at the block start, x extrapolated along v), N and the running count of
velocity reversals — returning a multiplier (scalar or array) for the friction force and for
the presliding stiffness (the element stiffnesses; their force limits stay).

Each call returns ``(DataFrame, Truth)``: the table as it would be written to CSV (the kind's
headers and units), and the truth in SI.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from numba import njit

KINDS = ("robot_joint", "linear_stage", "tribometer")
HOOK_BLOCK = 16  # samples per hook evaluation


@dataclass
class Context:
    """What a hidden effect may depend on, over one block of samples (SI units)."""

    t: np.ndarray
    x: np.ndarray
    v: np.ndarray
    N: np.ndarray
    reversals: int


@dataclass
class Truth:
    """The generator's truth, SI units, Table I sign convention (negative side negative)."""

    kind: str
    stribeck: dict  # {'positive': {Fs, Fc, vs, delta, sigma2}, 'negative': {...}}
    sigma1: float
    inertia: float
    element_stiffness: np.ndarray
    element_weight: np.ndarray
    units: dict  # signal -> unit written in the header
    factors: dict  # signal -> SI value of one file unit
    columns: dict  # signal -> header
    sign: str  # 'action' (friction opposes the motion, positive for v > 0) or 'reaction'
    rate: float
    noise: dict = field(default_factory=dict)
    normal_load_N0: float | None = None
    seed: int = 0
    segments: dict = field(default_factory=dict)  # experiment -> (t_start, t_end) in s
    levels: tuple = ()  # commanded velocity levels (SI)
    hidden: dict = field(default_factory=dict)

    def S(self, v) -> np.ndarray:
        """Steady sliding friction S(v) + σ2·v (0 at v = 0)."""
        v = np.asarray(v, dtype=float)
        out = np.zeros_like(v)
        for side, sg in (("positive", 1), ("negative", -1)):
            p = self.stribeck[side]
            m = v * sg > 0
            out[m] = p["Fc"] + (p["Fs"] - p["Fc"]) * np.exp(-np.abs(v[m] / p["vs"]) ** p["delta"]) + p["sigma2"] * v[m]
        return out

    def transition_curve(self, z) -> np.ndarray:
        """Force change after a reversal from gross sliding in the negative direction, at
        displacement z ≥ 0 from the reversal (static limits): Σ min(k_i·z, α_i·(Fs⁺ − Fs⁻))."""
        z = np.asarray(z, dtype=float)
        span = self.stribeck["positive"]["Fs"] - self.stribeck["negative"]["Fs"]
        return np.sum(np.minimum(np.multiply.outer(z, self.element_stiffness), self.element_weight * span), axis=-1)

    @property
    def presliding_range(self) -> float:
        """Displacement over which the last element breaks away (from a reversal at Fs⁻)."""
        span = self.stribeck["positive"]["Fs"] - self.stribeck["negative"]["Fs"]
        return float(np.max(self.element_weight * span / self.element_stiffness))


# ------------------------------------------------------------------------------------------
# the simulation loop (compiled; plain arrays in)

@njit(cache=True)
def _limits(v, sp, sn):
    """(upper, lower) force limits per unit weight at velocity v: S⁺(max(v,0)), S⁻(min(v,0))."""
    if v > 0:
        up = sp[1] + (sp[0] - sp[1]) * np.exp(-(abs(v / sp[2]) ** sp[3]))
    else:
        up = sp[0]
    if v < 0:
        lo = sn[1] + (sn[0] - sn[1]) * np.exp(-(abs(v / sn[2]) ** sn[3]))
    else:
        lo = sn[0]
    return up, lo


@njit(cache=True)
def _run(mode, n_out, sub, dt, u_ff, v_ref, x_ref, kp, ki, tach_noise, fmod, kmod,
         k, a, sp, sn, sigma1, inertia, state, X, V, F, U):
    """Advance ``n_out`` samples of ``sub`` internal steps each.

    mode 0: applied force u_ff (open loop); mode 1: PI velocity control on v_ref (+ u_ff);
    mode 2: imposed position x_ref (friction only). ``state`` = [x, v, integ, reversals,
    last_sign, F_1..F_M] is updated in place. Outputs per sample: X, V, F (friction), U."""
    M = len(k)
    Ktot = 0.0
    for i in range(M):
        Ktot += k[i]
    x = state[0]
    v = state[1]
    integ = state[2]
    rev = state[3]
    last = state[4]
    Fe = state[5:5 + M]
    for j in range(n_out):
        m = fmod[j]
        kk = kmod[j]
        if mode != 1:
            u = u_ff[j]
        for s in range(sub):
            if mode == 1:  # the velocity loop runs at the internal rate; the log decimates
                e = v_ref[j] - (v + tach_noise[j])
                integ += e * dt
                u = kp * e + ki * integ + u_ff[j]
            # sticking stiffness fraction (for the micro-damping)
            up, lo = _limits(v, sp, sn)
            kst = 0.0
            fsum = 0.0
            for i in range(M):
                fsum += Fe[i]
                if Fe[i] < a[i] * up * (1 - 1e-9) and Fe[i] > a[i] * lo * (1 - 1e-9):
                    kst += k[i]
            c = sigma1 * kst / Ktot
            if mode == 2:
                if s == 0:
                    step = (x_ref[j] - x) / sub
                vn = step / dt
            else:
                s2 = sp[4] if v >= 0 else sn[4]
                vn = (v + dt * (u - m * fsum) / inertia) / (1.0 + dt * m * (c + s2) / inertia)
            dx = vn * dt
            if vn != 0.0:
                sg = 1.0 if vn > 0 else -1.0
                if last != 0.0 and sg != last:
                    rev += 1.0
                last = sg
            x += dx
            v = vn
            up, lo = _limits(v, sp, sn)
            for i in range(M):
                f = Fe[i] + kk * k[i] * dx
                if f > a[i] * up:
                    f = a[i] * up
                elif f < a[i] * lo:
                    f = a[i] * lo
                Fe[i] = f
        fsum = 0.0
        kst = 0.0
        up, lo = _limits(v, sp, sn)
        for i in range(M):
            fsum += Fe[i]
            if Fe[i] < a[i] * up * (1 - 1e-9) and Fe[i] > a[i] * lo * (1 - 1e-9):
                kst += k[i]
        s2 = sp[4] if v >= 0 else sn[4]
        X[j] = x
        V[j] = v
        F[j] = m * (fsum + sigma1 * kst / Ktot * v + s2 * v)
        U[j] = u
    state[0] = x
    state[1] = v
    state[2] = integ
    state[3] = rev
    state[4] = last


# ------------------------------------------------------------------------------------------
# random machines, far from the paper's KUKA joint

def _random_machine(kind: str, rng) -> dict:
    """Friction and plant parameters in SI. The paper's joint has Fc ≈ 27/−52 N·m,
    vs ≈ 0.004–0.007 rad/s, δ ≈ 0.5–0.9, presliding range ≈ 5e-4 rad; these are not."""
    if kind == "robot_joint":
        Fc = rng.uniform(3.0, 12.0)
        vs = rng.uniform(0.02, 0.08)
        s2 = rng.uniform(0.5, 3.0)
        inertia = rng.uniform(1.0, 4.0)
        zr = rng.uniform(1.5e-3, 4e-3)
    elif kind == "linear_stage":
        Fc = rng.uniform(8.0, 40.0)
        vs = rng.uniform(0.5e-3, 3e-3)  # m/s
        s2 = rng.uniform(200.0, 1500.0)  # N·s/m
        inertia = rng.uniform(2.0, 15.0)  # kg
        zr = rng.uniform(4e-6, 1.5e-5)  # m
    else:
        Fc = rng.uniform(0.6, 2.0)  # N at full load
        vs = rng.uniform(0.5e-4, 2e-4)
        s2 = rng.uniform(50.0, 300.0)
        inertia = 1.0
        zr = rng.uniform(5e-6, 1.2e-5)
    asym = rng.uniform(0.6, 1.5)
    side = lambda sg, fc, vsv: {  # noqa: E731
        "Fs": sg * fc * rng.uniform(1.25, 1.7), "Fc": sg * fc, "vs": sg * vsv,
        "delta": rng.uniform(0.7, 2.0), "sigma2": s2 * rng.uniform(0.7, 1.4)}
    stribeck = {"positive": side(1, Fc, vs), "negative": side(-1, Fc * asym, vs * rng.uniform(0.6, 1.6))}
    M = 6
    w = rng.dirichlet(np.full(M, 2.0))
    span = stribeck["positive"]["Fs"] - stribeck["negative"]["Fs"]
    breakaway = np.sort(np.exp(rng.uniform(np.log(zr / 40), np.log(zr), M)))
    breakaway[-1] = zr
    k = w * span / breakaway
    K = k.sum()
    sigma1 = 2 * 0.6 * np.sqrt(K * inertia)  # damping ratio 0.6 of the stuck plant
    return {"stribeck": stribeck, "k": k, "alpha": w, "sigma1": sigma1, "inertia": inertia, "zr": zr}


KIND_UNITS = {
    "robot_joint": ({"time": "s", "position": "rad", "velocity": "rad/s", "force": "N*m"},
                    {"time": 1.0, "position": 1.0, "velocity": 1.0, "force": 1.0}),
    "linear_stage": ({"time": "s", "position": "mm", "force": "N"}, {"time": 1.0, "position": 1e-3, "force": 1.0}),
    "tribometer": ({"time": "s", "normal_load": "uN", "position": "mm", "friction": "uN"},
                   {"time": 1.0, "normal_load": 1e-6, "position": 1e-3, "friction": 1e-6}),
}


def _schedule_force_ramps(Fs_pos, Fs_neg, rate_force, dt, rng):
    """Applied-force turning points inside the static limits, with internal loops."""
    fp, fn = Fs_pos, -Fs_neg  # magnitudes
    pts = [0.0, 0.85 * fp, 0.35 * fp, 0.7 * fp, 0.5 * fp, 0.88 * fp, -0.8 * fn, -0.3 * fn, -0.65 * fn, 0.2 * fp,
           -0.86 * fn, 0.8 * fp, 0.0]
    pts = [p * rng.uniform(0.97, 1.0) for p in pts]
    seg = []
    for a, b in zip(pts[:-1], pts[1:]):
        n = max(int(abs(b - a) / rate_force / dt), 2)
        seg.append(np.linspace(a, b, n, endpoint=False))
    seg.append(np.full(int(0.3 / dt), 0.0))
    return np.concatenate(seg)


def sweep_levels(stribeck: dict) -> np.ndarray:
    """A joint's or stage's constant-velocity levels (magnitudes, rising): below and above the
    Stribeck velocity."""
    return abs(stribeck["positive"]["vs"]) * np.geomspace(0.1, 25.0, 9)


def _schedule_velocity_sweep(levels, dt, rng, one_sided, vs, t_acc=0.2):
    """v_ref: 0 → level in t_acc, hold 1–2.5 s (plus 2·sqrt(vs/level) s: breakaway under
    PI control takes longer at low speed), back to 0, short rest; levels positive then
    negative (unless one-sided)."""
    out = []
    signs = (1,) if one_sided else (1, -1)
    for lv in levels:
        for sg in signs:
            hold = rng.uniform(1.0, 2.5) + 2.0 * np.sqrt(vs / lv)
            out.append(np.linspace(0, sg * lv, int(t_acc / dt), endpoint=False))
            out.append(np.full(int(hold / dt), sg * lv))
            out.append(np.linspace(sg * lv, 0, int(t_acc / dt), endpoint=False))
            out.append(np.zeros(int(0.3 / dt)))
    return np.concatenate(out)


def _schedule_strokes(L, speeds, dt, dwell, t_acc, n_strokes):
    """Imposed reciprocating position: trapezoidal-velocity strokes of length L, dwells."""
    xs = []
    x = 0.0
    for i in range(n_strokes):
        V = speeds[i % len(speeds)]
        for sg in (1, -1):
            T = L / V + t_acc
            n = int(T / dt)
            tt = np.arange(n) * dt
            vel = V * np.clip(np.minimum(tt, T - tt) / t_acc, 0, 1)
            xx = x + sg * np.cumsum(vel) * dt * (L / max(np.sum(vel) * dt, 1e-30))
            xs.append(xx)
            x = xx[-1]
            xs.append(np.full(int(dwell / dt), x))
    return np.concatenate(xs)


def make_recording(kind: str = "robot_joint", seed: int = 0, *, rate: float | None = None, one_sided: bool = False,
                   irregular: bool = False, friction_modifier=None, stiffness_modifier=None, normal_load=None,
                   levels=None, duration_scale: float = 1.0, params: dict | None = None):
    """One recording of ``kind`` (see the module docstring) → (DataFrame, Truth).

    ``params`` overrides the random machine (same shape as the truth: stribeck, k, alpha,
    sigma1, inertia). ``levels`` sets the constant-velocity levels (SI, magnitudes)."""
    if kind not in KINDS:
        raise ValueError(f"kind: one of {KINDS}")
    rng = np.random.default_rng(seed)
    mach = _random_machine(kind, rng)
    if params:
        mach.update(params)
    st = mach["stribeck"]
    sp = np.array([st["positive"][k] for k in ("Fs", "Fc", "vs", "delta", "sigma2")])
    sn = np.array([st["negative"][k] for k in ("Fs", "Fc", "vs", "delta", "sigma2")])
    k, alpha, inertia, sigma1 = mach["k"], mach["alpha"], mach["inertia"], mach["sigma1"]
    rate = float(rate or {"robot_joint": 500.0, "linear_stage": 1000.0, "tribometer": 200.0}[kind])
    dt_out = 1.0 / rate
    units, factors = KIND_UNITS[kind]
    units, factors = dict(units), dict(factors)

    # --- the experiment schedule, one entry per output sample -------------------------------
    segments = {}
    if kind in ("robot_joint", "linear_stage"):
        vs_mag = abs(st["positive"]["vs"])
        if levels is None:
            levels = sweep_levels(st)
        Fs_p, Fs_n = st["positive"]["Fs"], st["negative"]["Fs"]
        ramp_rate = 0.5 * Fs_p * rng.uniform(0.8, 1.2)  # force per second
        u_pre = _schedule_force_ramps(Fs_p, Fs_n, ramp_rate / duration_scale, dt_out, rng)
        vref = _schedule_velocity_sweep(levels, dt_out, rng, one_sided, vs_mag)
        n_pre, n_cl = len(u_pre), len(vref)
        mode_arr = np.concatenate([np.zeros(n_pre, np.int64), np.ones(n_cl, np.int64)])
        u_ff = np.concatenate([u_pre, np.zeros(n_cl)])
        v_ref = np.concatenate([np.zeros(n_pre), vref])
        x_ref = np.zeros(len(u_ff))
        segments = {"presliding_ramps": (0.0, n_pre * dt_out), "velocity_sweep": (n_pre * dt_out, (n_pre + n_cl) * dt_out)}
        # velocity PI: stiff enough to overcome the negative slope of the Stribeck curve
        # (no stick-slip at the slow levels), integral corner at a tenth of the bandwidth
        slope = max((sp[0] - sp[1]) / abs(sp[2]), (sn[1] - sn[0]) / abs(sn[2]))
        kp = max(inertia * 40.0, 3.0 * slope)
        ki = kp * (kp / inertia) / 10.0
        N_sched = None
    else:
        if levels is None:
            levels = abs(st["positive"]["vs"]) * np.geomspace(0.3, 8.0, 6)  # stroke speeds around the Stribeck velocity
        L = 0.5e-3 if len(levels) > 1 else 0.23e-3
        n_load = int(2.0 / dt_out)
        strokes = _schedule_strokes(L, list(levels), dt_out, dwell=0.5, t_acc=0.02,
                                    n_strokes=max(1, int(round(max(6, 2 * len(levels)) * duration_scale))))
        strokes = np.concatenate([np.zeros(int(0.5 / dt_out)), strokes])
        x_ref = np.concatenate([np.zeros(n_load), strokes, np.full(n_load, strokes[-1])])
        N0 = rng.uniform(3.0, 6.0)
        N_sched = np.concatenate([np.linspace(0, N0, n_load), np.full(len(strokes), N0), np.linspace(N0, 0, n_load)])
        mode_arr = np.full(len(x_ref), 2, np.int64)
        u_ff = np.zeros(len(x_ref))
        v_ref = np.zeros(len(x_ref))
        kp = ki = 0.0
        segments = {"load_up": (0.0, n_load * dt_out), "strokes": (n_load * dt_out, (n_load + len(strokes)) * dt_out),
                    "load_down": ((n_load + len(strokes)) * dt_out, len(x_ref) * dt_out)}
    n = len(mode_arr)
    t = np.arange(n) * dt_out
    # internal step: well inside the stability limits of the stiffest stuck plant (stiffness
    # modifier up to 1.5) and of the velocity loop
    omega = np.sqrt(k.sum() * 1.5 / inertia)
    dt_stable = min(0.25 / omega, 0.3 * inertia / kp if kp > 0 else np.inf) if kind != "tribometer" else dt_out
    sub = max(1, int(np.ceil(dt_out / dt_stable)))
    dt = dt_out / sub
    if normal_load is not None:
        N_sched = np.broadcast_to(np.asarray(normal_load(t), dtype=float), (n,)).copy()
    noise = {
        "robot_joint": {"encoder_step": 2 * np.pi / 2**20 * rng.uniform(0.8, 1.2), "tach_sd": 5e-4, "force_sd": 0.02 * abs(sp[1])},
        "linear_stage": {"scale_sd": 2e-8, "force_sd": 0.01 * abs(sp[1])},
        "tribometer": {"position_step": 1e-7, "force_sd": 0.004 * abs(sp[1])},
    }[kind]
    tach = rng.normal(0, noise.get("tach_sd", 0.0) or 1e-300, n) if kind == "robot_joint" else \
        rng.normal(0, 0.3 * abs(st["positive"]["vs"]) * 0.02, n)

    # --- simulate, block by block so the hooks see the state --------------------------------
    M = len(k)
    state = np.zeros(5 + M)
    X, V, F, U = (np.zeros(n) for _ in range(4))
    ones = np.ones(n)
    N_arr = N_sched if N_sched is not None else np.zeros(n)
    N0_val = float(np.max(N_sched)) if (N_sched is not None and kind == "tribometer") else None
    load_scale = N_sched / N0_val if N0_val else ones
    hooks = friction_modifier is not None or stiffness_modifier is not None
    # split into runs of one mode, then into hook blocks
    bounds = list(np.flatnonzero(np.diff(mode_arr)) + 1)
    starts = [0] + bounds
    ends = bounds + [n]
    for a0, b0 in zip(starts, ends):
        block = HOOK_BLOCK if hooks else (b0 - a0)
        for a in range(a0, b0, block):
            b = min(a + block, b0)
            fm = load_scale[a:b].copy()
            km = ones[a:b]
            if hooks:
                tt = t[a:b]
                ctx = Context(t=tt, x=state[0] + state[1] * (tt - tt[0]), v=np.full(b - a, state[1]), N=N_arr[a:b],
                              reversals=int(state[3]))
                if friction_modifier is not None:
                    fm = fm * np.broadcast_to(np.asarray(friction_modifier(ctx), dtype=float), (b - a,))
                if stiffness_modifier is not None:
                    km = np.broadcast_to(np.asarray(stiffness_modifier(ctx), dtype=float), (b - a,)).copy()
            if mode_arr[a] == 2 and a == 0:
                state[0] = x_ref[0]
            _run(int(mode_arr[a]), b - a, sub, dt, u_ff[a:b], v_ref[a:b], x_ref[a:b], kp, ki, tach[a:b],
                 np.ascontiguousarray(fm), np.ascontiguousarray(km), k, alpha, sp, sn, sigma1, inertia, state,
                 X[a:b], V[a:b], F[a:b], U[a:b])

    # --- sensors ------------------------------------------------------------------------------
    keep = np.arange(n)
    if irregular:
        steps = np.maximum(1, np.round(rng.uniform(0.6, 1.6, n)).astype(int))
        keep = np.cumsum(steps)
        keep = keep[keep < n]
        for _ in range(4):  # gaps of 0.1–0.5 s
            g0 = rng.integers(0, max(len(keep) - 1, 1))
            glen = int(rng.uniform(0.1, 0.5) * rate)
            keep = np.concatenate([keep[:g0], keep[g0 + glen:]])
    tk = t[keep] + (rng.uniform(-0.1, 0.1, len(keep)) * dt_out if irregular else 0.0)
    tk = np.maximum.accumulate(tk)
    tk[1:] = np.maximum(tk[1:], tk[:-1] + 1e-6 * dt_out)
    Xk, Vk, Fk, Uk = X[keep], V[keep], F[keep], U[keep]
    cols = {}
    if kind == "robot_joint":
        q = noise["encoder_step"]
        cols["time [s]"] = tk
        cols["position [rad]"] = q * np.round(Xk / q)
        cols["velocity [rad/s]"] = Vk + rng.normal(0, noise["tach_sd"], len(keep))
        cols["torque [N*m]"] = Uk + rng.normal(0, noise["force_sd"], len(keep))
        colmap = {"time": "time [s]", "position": "position [rad]", "velocity": "velocity [rad/s]", "force": "torque [N*m]"}
        sign = "action"
    elif kind == "linear_stage":
        cols["Time [s]"] = tk
        cols["Position [mm]"] = (Xk + rng.normal(0, noise["scale_sd"], len(keep))) / 1e-3
        cols["Force [N]"] = Uk + rng.normal(0, noise["force_sd"], len(keep))
        colmap = {"time": "Time [s]", "position": "Position [mm]", "force": "Force [N]"}
        sign = "action"
    else:
        q = noise["position_step"]
        cols["Time [s]"] = tk
        cols["Normal [uN]"] = (N_arr[keep] + rng.normal(0, 2e-4 * (N0_val or 1.0), len(keep))) / 1e-6
        cols["Position [mm]"] = q * np.round(Xk / q) / 1e-3
        cols["Friction [uN]"] = -(Fk + rng.normal(0, noise["force_sd"], len(keep))) / 1e-6  # reaction sign
        colmap = {"time": "Time [s]", "normal_load": "Normal [uN]", "position": "Position [mm]", "friction": "Friction [uN]"}
        sign = "reaction"
    if normal_load is not None and kind != "tribometer":
        cols["normal_load [N]"] = N_arr[keep]
        colmap["normal_load"] = "normal_load [N]"
        units["normal_load"], factors["normal_load"] = "N", 1.0
    df = pd.DataFrame(cols)
    truth = Truth(kind=kind, stribeck={s: dict(v) for s, v in st.items()}, sigma1=float(sigma1), inertia=float(inertia),
                  element_stiffness=np.asarray(k, float), element_weight=np.asarray(alpha, float), units=units,
                  factors=factors, columns=colmap, sign=sign, rate=rate, noise=dict(noise), normal_load_N0=N0_val,
                  seed=seed, segments=segments, levels=tuple(np.asarray(levels, float)),
                  hidden={"friction_modifier": friction_modifier is not None, "stiffness_modifier": stiffness_modifier is not None})
    return df, truth


if __name__ == "__main__":
    import sys
    import time

    for kd in KINDS:
        t0 = time.perf_counter()
        d, tr = make_recording(kd, 1)
        print(kd, len(d), f"{time.perf_counter() - t0:.2f} s", list(d.columns), file=sys.stderr)
