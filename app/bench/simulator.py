"""Simulator throughput: the compiled kernel against a plain-C port of the same step and
against ``scipy.integrate.solve_ivp``, each run in the same process.

Two prescribed motions, sampled at dt = 1e-4 s:

* *smooth*: x(t) = 2e-4·sin(2π·0.5·t) + 6e-5·sin(2π·2.3·t) rad, presliding with velocity
  reversals, nested internal loops and their closing, up to ~90 % of the break-away force;
* *encoder*: the same motion read through a 4096-line encoder in quadrature behind a 100:1
  gear (q = 2π/1 638 400 rad): x is constant between counts, so ~98 % of steps have dx = 0
  and the rest are jumps of one count.

The C port (``leuven_step.c``, compiled with ``cc -O2``) runs the same passes and the same
Newton solve; its output is checked bit for bit against the kernel's before it is timed.
Kernel and C runs alternate, and each keeps its best of several, so that load from other
processes on the machine affects both alike.

The solve_ivp baseline integrates eq. (5) with LSODA between velocity reversals, with events
for loop closing and reset, and uses the same memory functions as the compiled simulator;
both are compared on the sample grid with a reference of the compiled simulator at a 100×
finer step, so the speed-up is quoted at matched accuracy.
"""

from __future__ import annotations

import time

import numpy as np

from ...model import default_params, initial_state, simulate_displacement, simulate_force
from ...model import kernels as K
from ...model.layout import State
from ...model.simulate import pack

DT = 1e-4
ENCODER_STEP = 2 * np.pi / (4 * 4096 * 100)


def displacement(t):
    return 2e-4 * np.sin(2 * np.pi * 0.5 * t) + 6e-5 * np.sin(2 * np.pi * 2.3 * t)


def velocity(t):
    return 2e-4 * np.pi * np.cos(2 * np.pi * 0.5 * t) + 6e-5 * 2 * np.pi * 2.3 * np.cos(2 * np.pi * 2.3 * t)


def motions(n: int) -> dict:
    t = np.arange(n) * DT
    x = displacement(t)
    return {"smooth": (t, x), "encoder": (t, ENCODER_STEP * np.round(x / ENCODER_STEP))}


# ---------------------------------------------------------------- kernel vs C
def _run_kernel(code, p, kind, tz, tF, params, t, x, out):
    st = initial_state(params)
    one = np.ones(1)
    t0 = time.perf_counter()
    K.run_displacement(code, p, kind, tz, tF, st, t, x, one, one, *out)
    return time.perf_counter() - t0, st


def _run_c(cport, code, p, tz, tF, params, t, x, out):
    st = initial_state(params)
    t0 = time.perf_counter()
    cport.run_displacement(code, p, tz, tF, st, t, x, *out)
    return time.perf_counter() - t0, st


def kernel_vs_c(n_steps: int, repeat: int, progress=print) -> dict:
    from .cport import build

    cport = build()
    note = cport if isinstance(cport, str) else None
    if note:
        progress(note)
    res: dict = {"kernel_steps": n_steps}
    if note:
        res["c_port_note"] = note
    for model in ("leuven", "lugre"):
        params = default_params(model)
        code, p, kind, tz, tF = pack(params)
        for name, (t, x) in motions(n_steps).items():
            outs_k = [np.empty(n_steps) for _ in range(4)]
            outs_c = [np.empty(n_steps) for _ in range(4)]
            _run_kernel(code, p, kind, tz, tF, params, t[:100], x[:100], [o[:100] for o in outs_k])  # load/compile
            best_k = best_c = np.inf
            identical = None
            for _ in range(repeat):
                dt_k, st_k = _run_kernel(code, p, kind, tz, tF, params, t, x, outs_k)
                best_k = min(best_k, dt_k)
                if not note:
                    dt_c, st_c = _run_c(cport, code, p, tz, tF, params, t, x, outs_c)
                    best_c = min(best_c, dt_c)
                    identical = bool(all(np.array_equal(a, b) for a, b in zip(outs_k, outs_c))
                                     and np.array_equal(st_k, st_c))
            key = f"{model}_{name}"
            res[f"{key}_steps_per_s"] = n_steps / best_k
            res[f"{key}_moving_fraction"] = float(np.mean(np.diff(x) != 0))
            if not note:
                res[f"{key}_c_steps_per_s"] = n_steps / best_c
                res[f"{key}_ratio_to_c"] = best_k / best_c
                res[f"{key}_bit_identical_to_c"] = identical
            progress(f"{key}: {n_steps / best_k / 1e6:.1f} M steps/s"
                     + ("" if note else f", C {n_steps / best_c / 1e6:.1f} M steps/s, ratio {best_k / best_c:.2f}"))
    return res


# ---------------------------------------------------------------- solve_ivp baseline
RESET_MARGIN = K.RESET_TOL


def leuven_solve_ivp(params, t_eval, rtol=1e-8, atol=1e-13):
    """Friction along ``displacement`` with solve_ivp, segment by segment between reversals."""
    from scipy.integrate import solve_ivp

    code, p, kind, tz, tF = pack(params)
    st = initial_state(params)
    mem = State(st)
    out = np.zeros(len(t_eval))
    # reversal times: sign changes of the velocity on a fine grid, refined by bisection
    tf = np.linspace(t_eval[0], t_eval[-1], 50 * len(t_eval))
    vf = velocity(tf)
    idx = np.flatnonzero(np.sign(vf[1:]) != np.sign(vf[:-1]))
    bounds = [t_eval[0]] + [0.5 * (tf[i] + tf[i + 1]) for i in idx] + [t_eval[-1]]
    sig1 = params.sigma1
    for a, b in zip(bounds[:-1], bounds[1:]):
        tm = 0.5 * (a + b)
        side = 1.0 if velocity(tm) > 0 else -1.0
        K.velocity_reversal(st, p, kind, tz, tF, side)
        t0 = a
        while t0 < b:
            fb = mem.F_b

            def rhs(t, y):
                v = velocity(t)
                if v * side <= 0:
                    return [0.0]
                r = K.transition_curve(kind, tz, tF, y[0]) / (K.stribeck(p, v, side) - fb)
                return [v * (1.0 - np.sign(r) * abs(r) ** params.n)]

            def closing(t, y):
                m, M = mem.stack_m, mem.stack_M
                if len(m) < 2 or len(M) < 2:
                    return 1.0
                target = M[-1] if side > 0 else m[-1]
                return side * (target - fb - K.transition_curve(kind, tz, tF, y[0]))

            def reset(t, y):
                v = velocity(t)
                if v * side <= 0:
                    return 1.0
                return 1.0 - RESET_MARGIN - K.transition_curve(kind, tz, tF, y[0]) / (K.stribeck(p, v, side) - fb)

            closing.terminal = True
            reset.terminal = True
            mask = (t_eval >= t0) & (t_eval <= b)
            sol = solve_ivp(rhs, (t0, b), [mem.z], method="LSODA", t_eval=t_eval[mask],
                            events=(closing, reset), rtol=rtol, atol=atol, dense_output=True)
            for ti, zi in zip(sol.t, sol.y[0]):
                i = int(round((ti - t_eval[0]) / DT))
                dz = rhs(ti, [zi])[0]
                v = velocity(ti)
                out[i] = fb + K.transition_curve(kind, tz, tF, zi) + sig1 * dz + K.viscous_coefficient(p, side) * v
            if sol.status == 1:  # an event: apply the mechanism and go on from there
                te = sol.t_events[0][0] if len(sol.t_events[0]) else sol.t_events[1][0]
                ze = sol.sol(te)[0]
                mem.z = ze
                fh = fb + K.transition_curve(kind, tz, tF, ze)
                if len(sol.t_events[0]):
                    K.close_internal_loops(st, kind, tz, tF, fh + side * 1e-12)
                else:
                    K.reset_to_outer_loop(st, p, kind, tz, tF, side, fh)
                t0 = te + 1e-12
            else:
                mem.z = sol.sol(b)[0]
                t0 = b
    return out


def _best(fn, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def against_solve_ivp(quick: bool, progress=print) -> dict:
    leuven = default_params("leuven")
    n_steps = 1_000_000 if quick else 4_000_000
    t = np.arange(n_steps) * DT
    x = displacement(t)
    simulate_displacement(leuven, t[:100], x[:100])
    rate = n_steps / _best(lambda: simulate_displacement(leuven, t, x))
    # force-driven plant (eq. (8))
    f = 30.0 * np.sin(2 * np.pi * 0.05 * t) + 5.0 * np.sin(2 * np.pi * 0.37 * t)
    simulate_force(leuven, t[:100], f[:100])
    force_rate = n_steps / _best(lambda: simulate_force(leuven, t, f), repeat=1)

    span = 2.0 if quick else 4.0
    tb = np.arange(int(span / DT)) * DT
    progress(f"solve_ivp baseline over {len(tb)} steps")
    t0 = time.perf_counter()
    # tolerances loosened until the baseline's error matches the compiled simulator's
    # (both about 0.4 N·m at the reversals, where sampling at dt dominates)
    F_ivp = leuven_solve_ivp(leuven, tb, rtol=1e-2, atol=1e-8)
    ivp_rate = len(tb) / (time.perf_counter() - t0)
    fine = np.arange(int(span / DT) * 100) * (DT / 100)
    F_ref = simulate_displacement(leuven, fine, displacement(fine)).friction_force[::100]
    F_c = simulate_displacement(leuven, tb, displacement(tb)).friction_force
    skip = 10  # the first samples differ by the derivative start-up of the backward difference
    return {
        "simulate_displacement_steps_per_s": rate,
        "simulate_force_steps_per_s": force_rate,
        "solve_ivp_steps_per_s": ivp_rate,
        "speedup_vs_solve_ivp": rate / ivp_rate,
        "max_abs_error_compiled_Nm": float(np.max(np.abs(F_c[skip:] - F_ref[skip:]))),
        "max_abs_error_solve_ivp_Nm": float(np.max(np.abs(F_ivp[skip:] - F_ref[skip:]))),
        "steps": n_steps,
    }


def bench_simulator(quick: bool = False, progress=print) -> dict:
    out = kernel_vs_c(1_000_000 if quick else 4_000_000, 3 if quick else 5, progress)
    out.update(against_solve_ivp(quick, progress))
    return out
