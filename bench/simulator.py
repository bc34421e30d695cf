"""Simulator throughput, against a plain ``scipy.integrate.solve_ivp`` implementation of the
same model and experiment, run in the same process.

The experiment: a prescribed displacement x(t) = 2e-4·sin(2π·0.5·t) + 6e-5·sin(2π·2.3·t) rad
sampled at dt = 1e-4 s: presliding with velocity reversals, nested internal loops and their
closing (wiping out), up to ~90 % of the break-away force.

The baseline integrates eq. (5) with ``solve_ivp`` (LSODA, stiff-capable) between velocity
reversals, with events for loop closing and reset, and uses the same memory functions as the
compiled simulator. Both outputs are compared on the sample grid with a reference of the
compiled simulator at a 100× finer step, so the speed-up is quoted at matched accuracy.
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp

from leuven_friction.model import default_params, initial_state, simulate_displacement
from leuven_friction.model import kernels as K
from leuven_friction.model.simulate import pack

DT = 1e-4


def displacement(t):
    return 2e-4 * np.sin(2 * np.pi * 0.5 * t) + 6e-5 * np.sin(2 * np.pi * 2.3 * t)


def velocity(t):
    return 2e-4 * np.pi * np.cos(2 * np.pi * 0.5 * t) + 6e-5 * 2 * np.pi * 2.3 * np.cos(2 * np.pi * 2.3 * t)


def leuven_solve_ivp(params, t_eval, rtol=1e-8, atol=1e-13):
    """Friction along ``displacement`` with solve_ivp, segment by segment between reversals."""
    code, p, kind, tz, tF = pack(params)
    st = initial_state(params)
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
            fb = st[K.S_FB]

            def rhs(t, y):
                v = velocity(t)
                if v * side <= 0:
                    return [0.0]
                r = K.transition_curve(kind, tz, tF, y[0]) / (K.stribeck(p, v, side) - fb)
                return [v * (1.0 - np.sign(r) * abs(r) ** params.n)]

            def closing(t, y):
                nmin, nmax = int(st[K.S_NMIN]), int(st[K.S_NMAX])
                if nmin < 2 or nmax < 2:
                    return 1.0
                cap = (len(st) - K.HEADER) // 2
                target = st[K.HEADER + cap + nmax - 1] if side > 0 else st[K.HEADER + nmin - 1]
                return side * (target - fb - K.transition_curve(kind, tz, tF, y[0]))

            def reset(t, y):
                v = velocity(t)
                if v * side <= 0:
                    return 1.0
                return 1.0 - RESET_MARGIN - K.transition_curve(kind, tz, tF, y[0]) / (K.stribeck(p, v, side) - fb)

            closing.terminal = True
            reset.terminal = True
            mask = (t_eval >= t0) & (t_eval <= b)
            sol = solve_ivp(rhs, (t0, b), [st[K.S_Z]], method="LSODA", t_eval=t_eval[mask],
                            events=(closing, reset), rtol=rtol, atol=atol, dense_output=True)
            ts = sol.t
            zs = sol.y[0]
            for ti, zi in zip(ts, zs):
                i = int(round((ti - t_eval[0]) / DT))
                dz = rhs(ti, [zi])[0]
                v = velocity(ti)
                out[i] = fb + K.transition_curve(kind, tz, tF, zi) + sig1 * dz + K.viscous_coefficient(p, side) * v
            if sol.status == 1:  # an event: apply the mechanism and go on from there
                te = sol.t_events[0][0] if len(sol.t_events[0]) else sol.t_events[1][0]
                ze = sol.sol(te)[0]
                st[K.S_Z] = ze
                fh = fb + K.transition_curve(kind, tz, tF, ze)
                if len(sol.t_events[0]):
                    K.close_internal_loops(st, kind, tz, tF, fh + side * 1e-12)
                else:
                    K.reset_to_outer_loop(st, p, kind, tz, tF, side, fh)
                t0 = te + 1e-12
            else:
                st[K.S_Z] = sol.sol(b)[0]
                t0 = b
    return out


RESET_MARGIN = K.RESET_TOL


def _compiled(params, t):
    return simulate_displacement(params, t, displacement(t)).friction_force


def _rate(fn, steps, repeat=3):
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return steps / best, best


def bench_simulator(quick: bool = False, progress=print) -> dict:
    leuven = default_params("leuven")
    lugre = default_params("lugre")
    n_steps = 1_000_000 if quick else 4_000_000
    t = np.arange(n_steps) * DT
    x = displacement(t)
    _compiled(leuven, t[:100])  # compile / load cache outside the timing
    _compiled(lugre, t[:100])
    progress(f"compiled simulator: {n_steps} steps per run")
    leu_rate, _ = _rate(lambda: simulate_displacement(leuven, t, x), n_steps)
    lug_rate, _ = _rate(lambda: simulate_displacement(lugre, t, x), n_steps)

    # force-driven plant (eq. (8)), A -> B -> C -> D style ramp repeated
    f = 30.0 * np.sin(2 * np.pi * 0.05 * t) + 5.0 * np.sin(2 * np.pi * 0.37 * t)
    from leuven_friction.model import simulate_force

    simulate_force(leuven, t[:100], f[:100])
    force_rate, _ = _rate(lambda: simulate_force(leuven, t, f), n_steps, repeat=1)

    # baseline on a shorter span at matched accuracy
    span = 2.0 if quick else 4.0
    tb = np.arange(int(span / DT)) * DT
    progress(f"solve_ivp baseline over {len(tb)} steps")
    t0 = time.perf_counter()
    # tolerances loosened until the baseline's error matches the compiled simulator's
    # (both about 0.4 N·m at the reversals, where sampling at dt dominates)
    F_ivp = leuven_solve_ivp(leuven, tb, rtol=1e-2, atol=1e-8)
    ivp_time = time.perf_counter() - t0
    ivp_rate = len(tb) / ivp_time
    fine = np.arange(int(span / DT) * 100) * (DT / 100)
    F_ref = _compiled(leuven, fine)[::100]
    F_c = _compiled(leuven, tb)
    skip = 10  # the first samples differ by the derivative start-up of the backward difference
    err_compiled = float(np.max(np.abs(F_c[skip:] - F_ref[skip:])))
    err_ivp = float(np.max(np.abs(F_ivp[skip:] - F_ref[skip:])))
    return {
        "leuven_steps_per_s": leu_rate,
        "lugre_steps_per_s": lug_rate,
        "leuven_force_driven_steps_per_s": force_rate,
        "solve_ivp_steps_per_s": ivp_rate,
        "speedup_vs_solve_ivp": leu_rate / ivp_rate,
        "max_abs_error_compiled_Nm": err_compiled,
        "max_abs_error_solve_ivp_Nm": err_ivp,
        "steps": n_steps,
    }


def run_all(quick: bool = False, progress=print) -> dict:
    results = {"simulator": bench_simulator(quick, progress)}
    flat = dict(results["simulator"])
    from bench.diagnosis import bench_diagnosis
    from bench.identification import bench_identification

    flat.update(bench_diagnosis(quick, progress))
    flat.update(bench_identification(quick, progress))
    return flat
