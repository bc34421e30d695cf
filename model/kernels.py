"""Compiled kernels: the friction models and the three simulation drivers, on plain arrays.

Conventions shared by every kernel:

``p``  float64 parameter vector, layout ``P_*`` below (``model.simulate.pack`` builds it);
``kind, tz, tF``  the transition curve (kind 0 piecewise linear through knots (tz, tF);
    kind 1 tanh_linear with ``tF = [A, z0, k]``);
``st``  float64 state vector: the header ``S_*`` then the two stacks of extrema of
    Section III-B, stack m (minima of F_h, ascending) and stack M (maxima, descending),
    each of capacity ``(len(st) - HEADER) // 2``.

The hysteresis memory is three functions, side by side, as the paper lists them:
``velocity_reversal``, ``close_internal_loops`` and ``reset_to_outer_loop``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

# error_model="numpy": divisions follow IEEE rules instead of raising (no per-division check
# in the hot loop). Small helpers are inlined at the Numba IR level: a call that passes
# arrays otherwise costs reference counting on every step.
# nogil: a long simulation in one thread (the web app's experiment tab) must not stall
# another (its live plots).
kernel = njit(cache=True, error_model="numpy", nogil=True)
helper = njit(cache=True, error_model="numpy", inline="always", nogil=True)

LEUVEN, LUGRE, STATIC = 0, 1, 2

# parameter vector
P_SP = 0  # 10 Stribeck values: Fs+, Fc+, vs+, delta+, sigma2+, Fs-, Fc-, vs-, delta-, sigma2-
P_N = 10
P_NINT = 11  # n when it is a small integer (fast power), else 0
P_SIGMA1 = 12
P_SIGMA0 = 13
P_REVTOL = 14
P_INERTIA = 15
P_SIZE = 16

# state vector header
S_Z, S_FB, S_DIR, S_NMIN, S_NMAX = 0, 1, 2, 3, 4
S_REVERSALS, S_CLOSINGS, S_RESETS, S_DEPTH, S_DROPPED = 5, 6, 7, 8, 9
S_SV = 10  # S(v) of the last step (reused by the plant's linearisation)
HEADER = 11

# F_h within this fraction of S(v) - F_b counts as "dz/dt has become zero" (reset to sliding).
# Eq. (5) only approaches S(v) asymptotically; without a tolerance the reset of Section
# III-B would never fire in floating point.
RESET_TOL = 1e-9


# ---------------------------------------------------------------- constant-velocity curve
@helper
def stribeck(p, v, side):
    """Eq. (7) on the side ``side`` (+1/-1); |v/vs| because Table I's negative vs is negative."""
    o = P_SP if side > 0 else P_SP + 5
    Fs, Fc, vs, dl = p[o], p[o + 1], p[o + 2], p[o + 3]
    if v == 0.0:
        return Fs
    return Fc + (Fs - Fc) * math.exp(-(abs(v / vs) ** dl))


@helper
def viscous_coefficient(p, side):
    return p[P_SP + 4] if side > 0 else p[P_SP + 9]


# ---------------------------------------------------------------- transition curve F_d
@helper
def _segment(knots, a):
    i = 1
    last = knots.shape[0] - 1
    while i < last and a > knots[i]:
        i += 1
    return i


@helper
def _odd_interp(xk, yk, u):
    """Point-symmetric linear interpolation through knots (xk, yk) starting at (0, 0),
    extended past the last knot; with the knots swapped it is its own inverse."""
    a = abs(u)
    i = _segment(xk, a)
    y = yk[i - 1] + (yk[i] - yk[i - 1]) / (xk[i] - xk[i - 1]) * (a - xk[i - 1])
    return y if u >= 0.0 else -y


@helper
def transition_curve(kind, tz, tF, z):
    """F_d(z), point-symmetric; piecewise linear extended past the last knot."""
    if kind == 0:
        return _odd_interp(tz, tF, z)
    return tF[0] * math.tanh(z / tF[1]) + tF[2] * z


@helper
def transition_slope(kind, tz, tF, z):
    """dF_d/dz; at a knot the slope of the segment on the far side of the origin's."""
    if kind == 0:
        i = _segment(tz, abs(z))
        return (tF[i] - tF[i - 1]) / (tz[i] - tz[i - 1])
    c = math.cosh(z / tF[1])
    return tF[0] / (tF[1] * c * c) + tF[2]


@kernel
def transition_curve_array(kind, tz, tF, z, out):
    for i in range(z.shape[0]):
        out[i] = transition_curve(kind, tz, tF, z[i])


@kernel
def transition_curve_inverse(kind, tz, tF, F):
    """F_d^{-1}(F): needed by loop closing and reset."""
    if kind == 0:
        return _odd_interp(tF, tz, F)
    A, z0, k = tF[0], tF[1], tF[2]
    a = abs(F)
    # A·tanh(z/z0) + k·z is increasing and concave for z > 0: the root lies in
    # [max(0, (a - A)/k), a/k]; safeguarded Newton inside that bracket.
    lo = max(0.0, (a - A) / k)
    hi = a / k
    z = min(hi, a / (A / z0 + k)) if a < A else 0.5 * (lo + hi)
    for _ in range(100):
        c = math.cosh(z / z0)
        g = A * math.tanh(z / z0) + k * z - a
        if g > 0.0:
            hi = z
        else:
            lo = z
        zn = z - g / (A / (z0 * c * c) + k)
        if zn <= lo or zn >= hi:
            zn = 0.5 * (lo + hi)
        if abs(zn - z) <= 1e-15 * (abs(z) + 1e-300):
            z = zn
            break
        z = zn
    return z if F >= 0.0 else -z


# ---------------------------------------------------------------- hysteresis memory (III-B)
@helper
def hysteresis_force(st, kind, tz, tF, kap):
    """Eq. (4): F_h = F_b + F_d(κ·z) (κ: the stiffness scale, 1 for the model as given)."""
    return st[S_FB] + transition_curve(kind, tz, tF, kap * st[S_Z])


@kernel
def _drop_oldest_internal_pair(st, cap):
    # Stack depth is finite in a compiled kernel. When a stack is full the oldest internal
    # extrema (just inside the outer loop F_s- ... F_s+) are forgotten: the memory stays
    # nested, and only the largest internal loop loses its closing point.
    nmin = int(st[S_NMIN])
    nmax = int(st[S_NMAX])
    if nmin >= 2:
        for i in range(1, nmin - 1):
            st[HEADER + i] = st[HEADER + i + 1]
        st[S_NMIN] = nmin - 1
    if nmax >= 2:
        for i in range(1, nmax - 1):
            st[HEADER + cap + i] = st[HEADER + cap + i + 1]
        st[S_NMAX] = nmax - 1
    st[S_DROPPED] += 1


@kernel
def velocity_reversal(st, p, kind, tz, tF, side, kap=1.0):
    """Mechanism 1: push F_h at the reversal onto m (now ascending) or M (now descending),
    start a new transition curve there (F_b = F_h, z = 0).

    Numerical choice: a sign change of v before the current curve has moved more than
    ``reversal_tol`` (force units) from its start is not a new extremum; it undoes the
    previous reversal instead (a loop smaller than the resolution is closed at once). This
    keeps round-off chatter around v = 0 from filling the stacks with empty loops.
    The first motion from rest (direction 0) is a reversal from the initial F_h.
    """
    cap = (st.shape[0] - HEADER) // 2
    d = st[S_DIR]
    fd = transition_curve(kind, tz, tF, kap * st[S_Z])
    fh = st[S_FB] + fd
    nmin = int(st[S_NMIN])
    nmax = int(st[S_NMAX])
    if d != 0.0 and abs(fd) <= p[P_REVTOL]:
        if d > 0.0 and nmin >= 2:
            st[S_NMIN] = nmin - 1
            fb = st[HEADER + cap + nmax - 1]
            st[S_FB] = fb
            st[S_Z] = transition_curve_inverse(kind, tz, tF, fh - fb) / kap
            st[S_DIR] = side
            return
        if d < 0.0 and nmax >= 2:
            st[S_NMAX] = nmax - 1
            fb = st[HEADER + nmin - 1]
            st[S_FB] = fb
            st[S_Z] = transition_curve_inverse(kind, tz, tF, fh - fb) / kap
            st[S_DIR] = side
            return
    if side > 0.0:
        if nmin >= cap:
            _drop_oldest_internal_pair(st, cap)
            nmin = int(st[S_NMIN])
        st[HEADER + nmin] = fh
        st[S_NMIN] = nmin + 1
    else:
        if nmax >= cap:
            _drop_oldest_internal_pair(st, cap)
            nmax = int(st[S_NMAX])
        st[HEADER + cap + nmax] = fh
        st[S_NMAX] = nmax + 1
    depth = max(st[S_NMIN], st[S_NMAX])
    if depth > st[S_DEPTH]:
        st[S_DEPTH] = depth
    st[S_FB] = fh
    st[S_Z] = 0.0
    st[S_DIR] = side
    st[S_REVERSALS] += 1


@helper
def close_internal_loops(st, kind, tz, tF, fh, kap=1.0):
    """Mechanism 2: when F_h reaches the extremum where the current internal loop began,
    remove both extrema of that loop (wiping out) and continue the older curve:
    F_b = S_m(i-1) (ascending) and z = F_d^{-1}(S_M(i) - S_m(i-1)).

    The outer bounds F_s-/F_s+ at the bottom of the stacks are never removed. z is
    computed from the current F_h (equal to S_M(i) at the crossing itself) so that F_h is
    continuous when the crossing falls inside a time step. Several nested loops may close
    in one step.
    """
    cap = (st.shape[0] - HEADER) // 2
    while True:
        nmin = int(st[S_NMIN])
        nmax = int(st[S_NMAX])
        if nmin < 2 or nmax < 2:
            return
        if st[S_DIR] > 0.0 and fh >= st[HEADER + cap + nmax - 1]:
            fb = st[HEADER + nmin - 2]
        elif st[S_DIR] < 0.0 and fh <= st[HEADER + nmin - 1]:
            fb = st[HEADER + cap + nmax - 2]
        else:
            return
        st[S_NMIN] = nmin - 1
        st[S_NMAX] = nmax - 1
        st[S_FB] = fb
        st[S_Z] = transition_curve_inverse(kind, tz, tF, fh - fb) / kap
        st[S_CLOSINGS] += 1


@kernel
def reset_to_outer_loop(st, p, kind, tz, tF, side, fh, kap=1.0):
    """Mechanism 3: going to sliding wipes the memory: m = [F_s-], M = [F_s+], F_b = F_s-
    (moving +) or F_s+ (moving -), z = F_d^{-1}(F_h - F_b) so F_h and F are unchanged."""
    cap = (st.shape[0] - HEADER) // 2
    fb = p[P_SP + 5] if side > 0.0 else p[P_SP]
    if st[S_NMIN] == 1.0 and st[S_NMAX] == 1.0 and st[S_FB] == fb:
        return  # already on the outer loop
    st[HEADER] = p[P_SP + 5]
    st[HEADER + cap] = p[P_SP]
    st[S_NMIN] = 1.0
    st[S_NMAX] = 1.0
    st[S_FB] = fb
    st[S_Z] = transition_curve_inverse(kind, tz, tF, fh - fb) / kap
    st[S_DIR] = side
    st[S_RESETS] += 1


@kernel
def init_state(st, p, fh0):
    """At rest with hysteresis force ``fh0`` and only the outer loop in memory."""
    cap = (st.shape[0] - HEADER) // 2
    st[:] = 0.0
    st[HEADER] = p[P_SP + 5]
    st[HEADER + cap] = p[P_SP]
    st[S_NMIN] = 1.0
    st[S_NMAX] = 1.0
    st[S_DEPTH] = 1.0
    st[S_FB] = fh0
    st[S_Z] = 0.0
    st[S_DIR] = 0.0


# ---------------------------------------------------------------- state equation (5)
@helper
def _abs_pow(a, p):
    """|a|^(n-1) with a fast path for the integer n of the paper (n = 7)."""
    ni = int(p[P_NINT])
    if ni > 0:
        r = 1.0
        for _ in range(ni - 1):
            r *= a
        return r
    return a ** (p[P_N] - 1.0)


@helper
def solve_state_equation(p, kind, tz, tF, z0, dx, D, kap):
    """Backward-Euler step of eq. (5) written per unit displacement,
    z1 = z0 + dx·(1 - sign(r)|r|^n), r = F_d(z1)/D, D = S(v) - F_b.

    Eq. (5) is stiff in sliding (rate |v|·n·F_d'/|D|); the implicit step is unconditionally
    stable there. With dx/D > 0 the residual is strictly increasing in z1, so the root is
    unique and is bracketed by [z0, z0 + dx] below the steady state and by
    [F_d^{-1}(D), z0] above it; Newton, falling back to bisection inside the bracket.
    """
    fd0 = transition_curve(kind, tz, tF, kap * z0)
    r0 = fd0 / D
    a0 = abs(r0)
    ph0 = _abs_pow(a0, p) * r0
    if ph0 < 1.0:
        lo, hi = z0, z0 + dx
    else:
        lo, hi = transition_curve_inverse(kind, tz, tF, D) / kap, z0
    if lo > hi:
        lo, hi = hi, lo
    z = z0 + dx * (1.0 - ph0)
    if z < lo or z > hi:
        z = 0.5 * (lo + hi)
    # 1e-7 of the step: far below the O(dt) error of the time step itself, and usually reached
    # by the first Newton correction of the explicit guess
    tol = 1e-7 * abs(dx) + 1e-300
    n = p[P_N]
    for _ in range(60):
        fd = transition_curve(kind, tz, tF, kap * z)
        r = fd / D
        rn1 = _abs_pow(abs(r), p)
        g = z - z0 - dx * (1.0 - rn1 * r)
        if g == 0.0:
            break
        if g > 0.0:
            hi = z
        else:
            lo = z
        dg = 1.0 + dx * n * rn1 * kap * transition_slope(kind, tz, tF, kap * z) / D
        zn = z - g / dg
        if abs(zn - z) <= tol:
            z = zn
            break
        if zn <= lo or zn >= hi:
            zn = 0.5 * (lo + hi)
        z = zn
    return z


# ---------------------------------------------------------------- one step of each model
@helper
def leuven_advance(st, p, kind, tz, tF, dx, side, s, kap):
    """Advance the Leuven state over displacement ``dx`` moving in direction ``side`` with
    S(v) = ``s``.

    Returns the continuous change of z (for sigma1·dz/dt); the jumps of z made by reset and
    loop closing leave F_h unchanged and are not part of dz/dt.
    """
    if side != st[S_DIR]:
        velocity_reversal(st, p, kind, tz, tF, side, kap)
    fb = st[S_FB]
    z = st[S_Z]
    D = s - fb
    fd = transition_curve(kind, tz, tF, kap * z)
    # Reset when F_h has reached S(v) while moving (dz/dt = 0 in eq. (5)). This also covers
    # S(v) - F_b of the wrong sign (a reversal point beyond S(v), e.g. a minimum above F_c+
    # followed by fast motion), where eq. (5) as written would push F_h away from S(v):
    # the system is sliding, so it gets the sliding memory and relaxes onto S(v).
    if side * D <= 0.0 or fd / D >= 1.0 - RESET_TOL:
        reset_to_outer_loop(st, p, kind, tz, tF, side, fb + fd, kap)
        fb = st[S_FB]
        z = st[S_Z]
        D = s - fb
    z1 = solve_state_equation(p, kind, tz, tF, z, dx, D, kap)
    st[S_Z] = z1
    close_internal_loops(st, kind, tz, tF, fb + transition_curve(kind, tz, tF, kap * z1), kap)
    return z1 - z


@helper
def lugre_advance(st, p, dx, side, s, kap):
    """Eq. (1) with g(v) = |S(v)|/σ0 (steady state σ0·z = S(v)), backward Euler in x:
    z1 = (z0 + dx)/(1 + |dx|·σ0/|S(v)|), linear in z1 so solved exactly. The stiffness
    scale κ multiplies σ0."""
    z0 = st[S_Z]
    z1 = (z0 + dx) / (1.0 + abs(dx) * kap * p[P_SIGMA0] / abs(s))
    st[S_Z] = z1
    if side != st[S_DIR]:
        st[S_REVERSALS] += 1
        st[S_DIR] = side
    return z1 - z0


@helper
def advance(model, st, p, kind, tz, tF, dx, v, kap):
    """Advance the friction state over one step; returns the continuous change of z.

    S(v) is evaluated once here for all three models (it is the costly part of a step: one
    exp and one non-integer power). The static model keeps S(v) in the F_b slot of the state.
    """
    if dx == 0.0 or v == 0.0:
        return 0.0
    side = 1.0 if v > 0.0 else -1.0
    s = stribeck(p, v, side)
    st[S_SV] = s
    if model == LEUVEN:
        return leuven_advance(st, p, kind, tz, tF, dx, side, s, kap)
    if model == LUGRE:
        return lugre_advance(st, p, dx, side, s, kap)
    st[S_FB] = s
    return 0.0


@helper
def friction_output(model, st, p, kind, tz, tF, dz, dt, v, sc, kap):
    """(F, F_h): eq. (3) for Leuven, eq. (2) for LuGre, S(v) + σ2·v for the static model
    (which reports its last S, or the stuck force, at v = 0); both times the friction scale
    ``sc`` (1 for the model as given), which multiplies the whole of eq. (3)."""
    if model == LEUVEN:
        fh = hysteresis_force(st, kind, tz, tF, kap)
    elif model == LUGRE:
        fh = kap * p[P_SIGMA0] * st[S_Z]
    else:
        fh = st[S_FB]
    side = 1.0 if v >= 0.0 else -1.0
    return sc * (fh + p[P_SIGMA1] * dz / dt + viscous_coefficient(p, side) * v), sc * fh


# ---------------------------------------------------------------- driver 1: prescribed x(t)
@kernel
def run_displacement(model, p, kind, tz, tF, st, t, x, fsc, ksc, F, Fh, Z, V):
    """Friction along a prescribed displacement; v is the backward difference of x.

    ``fsc``, ``ksc``: per-sample friction and stiffness scales, or one value for all samples.
    """
    fstep = 1 if fsc.shape[0] > 1 else 0
    kstep = 1 if ksc.shape[0] > 1 else 0
    F[0], Fh[0] = friction_output(model, st, p, kind, tz, tF, 0.0, 1.0, 0.0, fsc[0], ksc[0])
    Z[0] = st[S_Z]
    V[0] = 0.0
    for k in range(1, t.shape[0]):
        dt = t[k] - t[k - 1]
        dx = x[k] - x[k - 1]
        v = dx / dt
        kap = ksc[k * kstep]
        dz = advance(model, st, p, kind, tz, tF, dx, v, kap)
        F[k], Fh[k] = friction_output(model, st, p, kind, tz, tF, dz, dt, v, fsc[k * fstep], kap)
        Z[k] = st[S_Z]
        V[k] = v


# ---------------------------------------------------------------- plant, eq. (8)
@kernel
def plant_step(model, p, kind, tz, tF, st, x, v, f, dt, sc, kap):
    """One step of I·dv/dt = f - F, linearly implicit Euler.

    The friction is linearised in the new velocity: F(v1) ≈ F_h + (K·a·dt + σ1·a + σ2)·v1,
    with a = dz/dx from eq. (5) (clamped to [0, 1]) and K = dF_d/dz. After a reversal K is
    the initial stiffness of the transition curve (~9e6 N·m/rad for Table II): the update is
    A-stable for that spring–damper, which an explicit step at dt = 1e-4 s is not.
    When the step reverses the velocity, the linearisation of the new curve (z = 0, a = 1) is
    used. The nonlinear state is then advanced exactly (``advance``) with dx = v1·dt.
    The friction scale ``sc`` multiplies the friction the plant feels, the stiffness scale
    ``kap`` the presliding stiffness (F_d(κ·z), LuGre's κ·σ0).
    Returns (x1, v1, F, F_h, dz).
    """
    inertia = p[P_INERTIA]
    if model == STATIC:
        # Karnopp-style stiction: stuck while |f| stays inside [F_s-, F_s+].
        if v == 0.0:
            if sc * p[P_SP + 5] <= f <= sc * p[P_SP]:
                st[S_FB] = f / sc if sc != 0.0 else 0.0
                return x, 0.0, f, f, 0.0
            side = 1.0 if f > 0.0 else -1.0
            fr = sc * stribeck(p, 0.0, side)
            v1 = dt * (f - fr) / inertia
            return x + v1 * dt, v1, fr, fr, 0.0
        side = 1.0 if v > 0.0 else -1.0
        fs = sc * stribeck(p, v, side)
        c = sc * viscous_coefficient(p, side)
        v1 = (inertia * v / dt + f - fs) / (inertia / dt + c)
        if v1 * side <= 0.0:
            st[S_FB] = f / sc if sc != 0.0 else 0.0
            return x, 0.0, fs + c * v, fs, 0.0
        return x + v1 * dt, v1, fs + c * v1, fs, 0.0

    if model == LEUVEN:
        fh = sc * hysteresis_force(st, kind, tz, tF, kap)
    else:
        fh = sc * kap * p[P_SIGMA0] * st[S_Z]
    num = inertia * v / dt + f - fh
    if num == 0.0:
        return x, 0.0, fh, fh, 0.0
    side = 1.0 if num > 0.0 else -1.0
    # S(v) at the start of the step: the last one computed if still moving the same way,
    # else F_s of the new direction (S(0±)).
    s = st[S_SV] if (v * side > 0.0 and side == st[S_DIR]) else p[P_SP] if side > 0.0 else p[P_SP + 5]
    if model == LEUVEN:
        if side == st[S_DIR]:
            r = transition_curve(kind, tz, tF, kap * st[S_Z]) / (s - st[S_FB])
            a = 1.0 - _abs_pow(abs(r), p) * r
            K = kap * transition_slope(kind, tz, tF, kap * st[S_Z])
        else:
            a = 1.0
            K = kap * transition_slope(kind, tz, tF, 0.0)
    else:
        K = kap * p[P_SIGMA0]
        a = 1.0 - side * K * st[S_Z] / abs(s)
    a = min(1.0, max(0.0, a))
    v1 = num / (inertia / dt + sc * (K * a * dt + p[P_SIGMA1] * a + viscous_coefficient(p, side)))
    dx = v1 * dt
    dz = advance(model, st, p, kind, tz, tF, dx, v1, kap)
    Fr, fh1 = friction_output(model, st, p, kind, tz, tF, dz, dt, v1, sc, kap)
    return x + dx, v1, Fr, fh1, dz


# ---------------------------------------------------------------- driver 2: prescribed f(t)
@kernel
def run_force(model, p, kind, tz, tF, st, t, f, fsc, ksc, X, V, F, Fh, Z):
    """Plant driven by a prescribed applied force; X[0], V[0] hold the initial state."""
    fstep = 1 if fsc.shape[0] > 1 else 0
    kstep = 1 if ksc.shape[0] > 1 else 0
    F[0], Fh[0] = friction_output(model, st, p, kind, tz, tF, 0.0, 1.0, V[0], fsc[0], ksc[0])
    Z[0] = st[S_Z]
    x = X[0]
    v = V[0]
    for k in range(1, t.shape[0]):
        x, v, F[k], Fh[k], _ = plant_step(model, p, kind, tz, tF, st, x, v, f[k], t[k] - t[k - 1],
                                          fsc[k * fstep], ksc[k * kstep])
        X[k] = x
        V[k] = v
        Z[k] = st[S_Z]


# ---------------------------------------------------------------- driver 3: closed loop
@kernel
def run_closed_loop(model, p, kind, tz, tF, st, t, x_ref, ff, kp, ki, q, ctrl_every, fsc, ksc, X, V, U, F, Fh, Z):
    """Position control of the plant: u = Kp·e + Ki·∫e + ff, e = x_ref - Q(x), where Q
    quantises to the encoder step q (q = 0: exact). The controller runs every
    ``ctrl_every`` simulation steps and holds its output in between (zero-order hold)."""
    fstep = 1 if fsc.shape[0] > 1 else 0
    kstep = 1 if ksc.shape[0] > 1 else 0
    F[0], Fh[0] = friction_output(model, st, p, kind, tz, tF, 0.0, 1.0, V[0], fsc[0], ksc[0])
    Z[0] = st[S_Z]
    x = X[0]
    v = V[0]
    integral = 0.0
    u = 0.0
    for k in range(1, t.shape[0]):
        dt = t[k] - t[k - 1]
        if (k - 1) % ctrl_every == 0:
            xm = q * math.floor(x / q + 0.5) if q > 0.0 else x
            e = x_ref[k - 1] - xm
            integral += e * dt * ctrl_every
            u = kp * e + ki * integral + ff[k - 1]
        x, v, F[k], Fh[k], _ = plant_step(model, p, kind, tz, tF, st, x, v, u, dt, fsc[k * fstep], ksc[k * kstep])
        X[k] = x
        V[k] = v
        U[k] = u
        Z[k] = st[S_Z]
    U[0] = U[1] if t.shape[0] > 1 else 0.0


def new_state(cap: int = 64) -> np.ndarray:
    return np.zeros(HEADER + 2 * cap)
