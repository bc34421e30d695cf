"""The paper's experiments (Sections II, V, VI) as named, parameterised simulations.

Each experiment returns an ``ExperimentResult``: the simulated runs (one ``SimResult`` each)
and a ``summary`` of the numbers the paper's figure or table shows. Choices the paper leaves
open (inertia, rates, velocity bands, controller gains and sample rate) are the defaults of
the functions below and are listed in the README.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .params import FrictionParams, Stribeck, StribeckSide, as_model, default_params, kuka_stribeck
from .simulate import SimResult, simulate_closed_loop, simulate_displacement, simulate_force

DT = 1e-4  # the paper's simulation step (Section IV-B)


@dataclass
class ExperimentResult:
    name: str
    runs: list[SimResult]
    labels: list[str]
    summary: dict = field(default_factory=dict)


def _ramp(points_t, points_f, dt=DT):
    t = np.arange(0.0, points_t[-1] + 0.5 * dt, dt)
    return t, np.interp(t, points_t, points_f)


def force_scale(params: FrictionParams) -> float:
    """This parameter set's F_s⁺ over Table I's 36 N·m: the paper's applied-force levels are
    fractions of its joint's break-away force, and a machine ten times weaker, driven by the
    same newtons, slides off where the experiment means it to stay in presliding (a 14 N stage
    ran 9.4 m through the A → B → C → D ramp). 1 for the paper's parameters."""
    return abs(params.stribeck.positive.Fs) / abs(kuka_stribeck().positive.Fs)


def abcd_levels(params: FrictionParams) -> tuple:
    """Fig. 10's A → B → C → D force levels (0, 20, 5, 30 N·m for F_s⁺ = 36) × ``force_scale``."""
    k = force_scale(params)
    return tuple(k * v for v in (0.0, 20.0, 5.0, 30.0))


def stick_slip_setup(params: FrictionParams) -> dict:
    """Fig. 11's loop (Kp = 1000 N·m/rad, reference 0.1 rad/s, for v_s⁺ = 0.007 and F_s⁺ = 36)
    in this parameter set's own scales: the reference as many v_s⁺ fast, Kp as stiff against
    its F_s⁺ (a 14 N stage under 1000 N/m and 0.1 m/s is another experiment)."""
    v = abs(params.stribeck.positive.vs) * (0.1 / abs(kuka_stribeck().positive.vs))
    return {"velocity": v, "kp": 1000.0 * force_scale(params) * (0.1 / v)}


def symmetric_ramp(params: FrictionParams, amplitude: float | None = None, rate: float | None = None) -> ExperimentResult:
    """Fig. 1: applied force ramped 0 → +a → -a → +a; a loop appears only for symmetric extremes.
    Default a = 25 N·m at 5 N·m/s, both × ``force_scale``."""
    k = force_scale(params)
    amplitude = 25.0 * k if amplitude is None else amplitude
    rate = 5.0 * k if rate is None else rate
    T = amplitude / rate
    t, f = _ramp([0, T, 3 * T, 5 * T], [0, amplitude, -amplitude, amplitude])
    r = simulate_force(params, t, f)
    u = params.units
    return ExperimentResult("symmetric_ramp", [r], [params.model], {
        "amplitude": amplitude, "rate": rate,
        "drive": f"applied force 0 → ±{amplitude:.4g} {u.force} at {rate:.4g} {u.force}/{u.time}"})


def loop_area(x: np.ndarray, F: np.ndarray) -> float:
    """|∮ F dx| over a closed path: the energy dissipated in one loop (trapezoid rule)."""
    return float(abs(np.sum(0.5 * (F[1:] + F[:-1]) * np.diff(x))))


def abcd_ramp(params: FrictionParams, levels=None, rate: float | None = None) -> ExperimentResult:
    """Figs. 2, 3, 10: applied force A → B → C → D at a constant rate; default 0 → 20 → 5 → 30
    N·m at 1 N·m/s, all × ``force_scale``.

    Summary: positions at B, C and where the C→D ramp passes B's force again (the Leuven
    model returns to B and continues the A→B curve; LuGre does not), and the energy of the
    internal loop B→C→(B's force).
    """
    A, B, C, D = abcd_levels(params) if levels is None else levels
    rate = 1.0 * force_scale(params) if rate is None else rate
    tB = abs(B - A) / rate
    tC = tB + abs(B - C) / rate
    tD = tC + abs(D - C) / rate
    t, f = _ramp([0, tB, tC, tD], [A, B, C, D])
    r = simulate_force(params, t, f)
    iB = int(round(tB / DT))
    iC = int(round(tC / DT))
    iBB = iC + int(np.argmax(f[iC:] >= B))
    summary = {
        "x_B": float(r.position[iB]),
        "x_C": float(r.position[iC]),
        "x_back_at_B": float(r.position[iBB]),
        "closure_error_rel": float((r.position[iBB] - r.position[iB]) / (r.position[iB] - r.position[iC]))
        if r.position[iB] != r.position[iC] else float("nan"),
        "loop_energy": loop_area(r.position[iB : iBB + 1], r.friction_force[iB : iBB + 1]),
        "memory": r.memory,
        "drive": f"applied force {A:.4g} → {B:.4g} → {C:.4g} → {D:.4g} {params.units.force} at {rate:.4g} "
                 f"{params.units.force}/{params.units.time}",
    }
    return ExperimentResult("abcd_ramp", [r], [params.model], summary)


def constant_velocity_sweep(params: FrictionParams, velocities=None, settle_distance: float = 3e-3,
                            min_time: float = 0.5) -> ExperimentResult:
    """Fig. 8: constant-velocity runs at both signs; mean friction over the last 20 % of each
    run against S(v) + σ2·v. Each run lasts long enough to cover ``settle_distance`` (the
    approach to sliding is ~1e-3 rad/s · 0.27 s slow at low speed)."""
    if velocities is None:
        mags = np.array([0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0])
        velocities = np.concatenate([mags, -mags])
    runs, labels, means = [], [], []
    for v in velocities:
        T = max(min_time, settle_distance / abs(v))
        dt = min(DT, T / 2000)
        t = np.arange(0.0, T + 0.5 * dt, dt)
        r = simulate_displacement(params, t, v * t)
        tail = t >= 0.8 * T
        runs.append(r)
        labels.append(f"v={v:g}")
        means.append(float(np.mean(r.friction_force[tail])))
    return ExperimentResult("constant_velocity_sweep", runs, labels,
                            {"velocity": [float(v) for v in velocities], "mean_friction": means})


def stick_slip(params: FrictionParams, kp: float | None = None, velocity: float | None = None,
               duration: float = 4.0) -> ExperimentResult:
    """Fig. 11: P position control (Kp = 1000 N·m/rad) of a reference moving at 0.1 rad/s, by
    default in the parameter set's own scales (``stick_slip_setup``; the paper's for its own)."""
    setup = stick_slip_setup(params)
    kp = setup["kp"] if kp is None else kp
    velocity = setup["velocity"] if velocity is None else velocity
    t = np.arange(0.0, duration + 0.5 * DT, DT)
    r = simulate_closed_loop(params, t, velocity * t, kp=kp)
    moving = r.velocity > 0.05 * velocity
    starts = np.flatnonzero(moving[1:] & ~moving[:-1]) + 1
    ends = np.flatnonzero(~moving[1:] & moving[:-1]) + 1
    slips = []
    for s in starts:
        e = ends[ends > s]
        if len(e):
            slips.append(float(r.position[e[0]] - r.position[s]))
    stuck = float(np.mean(np.abs(r.velocity) < 1e-4))
    u = params.units
    return ExperimentResult("stick_slip", [r], [params.model],
                            {"kp": kp, "velocity": velocity, "slip_distances": slips, "stuck_fraction": stuck,
                             "drive": f"P control, Kp = {kp:.4g} {u.force}/{u.position}, reference "
                                      f"{velocity:.4g} {u.position}/{u.time}"})


def breakaway(params: FrictionParams, rates=None, v_slide: float = 0.05) -> ExperimentResult:
    """Figs. 12, 13: applied force ramped from zero at constant rates; the break-away force is
    the peak friction before the joint slides (|v| reaches ``v_slide``)."""
    if rates is None:
        rates = np.logspace(0, 3, 7)
    runs, labels, peaks = [], [], []
    fs = params.stribeck.positive.Fs
    for rate in rates:
        T = 2.0 * fs / rate
        dt = min(DT, T / 20000)
        t = np.arange(0.0, T + 0.5 * dt, dt)
        r = simulate_force(params, t, rate * t)
        slid = np.flatnonzero(r.velocity >= v_slide)
        end = slid[0] if len(slid) else len(t) - 1
        peaks.append(float(np.max(r.friction_force[: end + 1])))
        runs.append(r)
        labels.append(f"rate={rate:g}")
    return ExperimentResult("breakaway", runs, labels, {"rate": [float(x) for x in rates], "breakaway_force": peaks})


def frictional_lag(params: FrictionParams, frequencies=(0.01, 0.1, 0.25), v_mean: float = 0.01,
                   v_amp: float = 0.009, periods: int = 2) -> ExperimentResult:
    """Fig. 14: velocity v0 + va·sin(2πft) inside the Stribeck region.

    Loop width: the largest vertical distance between the rising-velocity branch and the
    falling one over the velocity band, in the last period (friction is larger while the
    velocity rises: the lag of Fig. 14). Above ~0.009 rad/s the σ1·dz/dt term makes the
    loop narrow and invert, so the width is taken where it is largest.
    """
    runs, labels, widths = [], [], []
    for fr in frequencies:
        T = periods / fr
        dt = min(1e-3, 1.0 / (fr * 4000))
        t = np.arange(0.0, T + 0.5 * dt, dt)
        w = 2 * np.pi * fr
        x = v_mean * t + v_amp / w * (1 - np.cos(w * t))
        r = simulate_displacement(params, t, x)
        last = t >= T - 1.0 / fr
        phase = (t * fr) % 1.0
        rising = last & ((phase < 0.25) | (phase > 0.75))
        falling = last & (phase > 0.25) & (phase < 0.75)
        grid = np.linspace(v_mean - 0.95 * v_amp, v_mean + 0.95 * v_amp, 200)
        branch = []
        for m in (rising, falling):
            order = np.argsort(r.velocity[m])
            branch.append(np.interp(grid, r.velocity[m][order], r.friction_force[m][order]))
        widths.append(float(np.max(branch[0] - branch[1])))
        runs.append(r)
        labels.append(f"f={fr:g} Hz")
    return ExperimentResult("frictional_lag", runs, labels, {"frequency": list(frequencies), "loop_width": widths})


def triangle(t: np.ndarray, period: float, velocity: float) -> np.ndarray:
    """Triangular reference starting at 0 going up: slope ±velocity, given period."""
    ph = (t % period) / period
    amp = velocity * period / 2
    return np.where(ph < 0.5, amp * 2 * ph, amp * 2 * (1 - ph))



def identified_feedforward_params(params: FrictionParams, seed: int = 7) -> FrictionParams:
    """The model the feedforward uses: the plant's S(v) and transition curve as an
    identification with Table I's 1-σ uncertainties returns them (one fixed draw), not the
    plant's own values."""
    rng = np.random.default_rng(seed)
    sigma = {  # Table I, in the order Fs, Fc, vs, delta, sigma2
        "positive": (4.0, 1.0, 0.003, 0.2, 0.2),
        "negative": (6.0, 1.0, 0.002, 0.3, 0.2),
    }
    sides = {}
    for name in ("positive", "negative"):
        side = getattr(params.stribeck, name)
        vals = []
        for key, sd in zip(("Fs", "Fc", "vs", "delta", "sigma2"), sigma[name]):
            v0 = getattr(side, key)
            # a draw of relative size sd/|Table I value|, keeping the sign rules of Table I
            v = v0 * (1.0 + rng.normal() * sd / abs(getattr(default_params().stribeck, name).__dict__[key]))
            vals.append(v if v * v0 > 0 else v0)
        Fs, Fc, vs, dl, s2 = vals
        if abs(Fs) < abs(Fc):
            Fs = Fc
        sides[name] = StribeckSide(Fs, Fc, vs, dl, max(s2, 0.0))
    F = np.asarray(params.transition_curve.F) if params.transition_curve.kind == "piecewise_linear" else None
    tc = params.transition_curve
    if F is not None:
        Fn = np.maximum.accumulate(F * (1.0 + 0.02 * rng.normal(size=len(F))))
        Fn[0] = 0.0
        Fn = Fn + 1e-9 * np.arange(len(Fn))
        tc = tc.__class__(kind=tc.kind, z=tc.z, F=tuple(float(v) for v in Fn))
    return params.replace(stribeck=Stribeck(**sides), transition_curve=tc).validate()


def tracking(params: FrictionParams, period: float = 10.0, velocity: float = 2e-4, cycles: int = 2,
             encoder_step: float = 1.63e-5, kp: float = 3.0e5, ki: float = 3.0e6, kp_only: float = 3.0e5,
             ctrl_rate: float = 1000.0, ff_params: FrictionParams | None = None) -> ExperimentResult:
    """Figs. 16, 17, Table III: triangular reference (period 10 s, 2e-4 rad/s), encoder
    1.63e-5 rad, controllers P, PI, PI + Coulomb feedforward, PI + model feedforward.

    The controller runs at ``ctrl_rate`` (zero-order hold); the model feedforward is the
    Leuven model of ``ff_params`` (default ``identified_feedforward_params``) driven by the
    reference trajectory, the Coulomb feedforward F_c± of the same identified set.
    Errors are measured on the true (unquantised) position over the last cycle.
    """
    t = np.arange(0.0, cycles * period + 0.5 * DT, DT)
    x_ref = triangle(t, period, velocity)
    ffp = identified_feedforward_params(params) if ff_params is None else ff_params
    v_ref = np.gradient(x_ref, t)
    coulomb = np.where(v_ref > 0, ffp.stribeck.positive.Fc, np.where(v_ref < 0, ffp.stribeck.negative.Fc, 0.0))
    model_ff = simulate_displacement(as_model(ffp, "leuven"), t, x_ref).friction_force
    every = max(1, int(round(1.0 / (ctrl_rate * DT))))
    cases = [
        ("P", kp_only, 0.0, None),
        ("PI", kp, ki, None),
        ("PI+Coulomb FF", kp, ki, coulomb),
        ("PI+model FF", kp, ki, model_ff),
    ]
    runs, labels, table = [], [], {}
    last = t >= (cycles - 1) * period
    for label, p_gain, i_gain, ff in cases:
        r = simulate_closed_loop(params, t, x_ref, kp=p_gain, ki=i_gain, feedforward=ff,
                                 encoder_step=encoder_step, ctrl_every=every)
        err = x_ref - r.position
        table[label] = {"rms_error": float(np.sqrt(np.mean(err[last] ** 2))), "max_error": float(np.max(np.abs(err[last])))}
        runs.append(r)
        labels.append(label)
    return ExperimentResult("tracking", runs, labels, {"table": table, "reference": x_ref})


EXPERIMENTS: dict[str, tuple[Callable[[FrictionParams], ExperimentResult], str]] = {
    "symmetric_ramp": (symmetric_ramp, "Fig. 1: force ramped between ±25 N·m (× F_s⁺/36 of the file; loop only for "
                                       "symmetric extremes)"),
    "abcd_ramp": (abcd_ramp, "Figs. 2/3/10: force 0 → 20 → 5 → 30 N·m at 1 N·m/s (× F_s⁺/36 of the file), internal "
                             "loop closing"),
    "constant_velocity_sweep": (constant_velocity_sweep, "Fig. 8: steady friction S(v) + σ2·v at ±(0.001 … 1) rad/s"),
    "stick_slip": (stick_slip, "Fig. 11: P control, Kp = 1000 N·m/rad, reference 0.1 rad/s (in the file's own "
                               "scales: × v_s⁺/0.007 and F_s⁺/36)"),
    "breakaway": (breakaway, "Figs. 12/13: break-away force vs applied-force rate 1 … 1000 N·m/s"),
    "frictional_lag": (frictional_lag, "Fig. 14: sinusoidal velocity 0.001 … 0.019 rad/s at 0.01/0.1/0.25 Hz"),
    "tracking": (tracking, "Figs. 16/17, Table III: low-velocity tracking, P / PI / PI+Coulomb FF / PI+model FF"),
}


def run_experiment(name: str, params: FrictionParams | None = None) -> ExperimentResult:
    if name not in EXPERIMENTS:
        raise KeyError(f"unknown experiment {name!r}; known: {', '.join(EXPERIMENTS)}")
    return EXPERIMENTS[name][0](params if params is not None else default_params())
