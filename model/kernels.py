"""Compiled kernels: the friction models and the three simulation drivers, on plain arrays.

Conventions shared by every kernel (the layout itself lives in ``model.layout``):

``p``  float64 parameter vector, indices ``P_*`` (``model.simulate.pack`` builds it);
``kind, tz, tF``  the transition curve (``CurveKind.PIECEWISE_LINEAR``: knots (tz, tF);
    ``CurveKind.TANH_LINEAR``: ``tF = [A, z0, k]``);
``st``  float64 state vector, indices ``S_*``: a header, then the stacks m and M;
``fsc, ksc``  friction and stiffness scales per sample, or one value for all samples.

The hysteresis memory is three functions, side by side, as the paper lists them:
``velocity_reversal``, ``close_internal_loops`` and ``reset_to_outer_loop``.
"""

from __future__ import annotations

import math

from numba import njit

from .layout import (
    HEADER,
    P_INERTIA,
    P_N,
    P_NINT,
    P_REVTOL,
    P_SIGMA0,
    P_SIGMA1,
    P_SIZE,
    P_SP,
    S_CLOSINGS,
    S_DEPTH,
    S_DIR,
    S_DROPPED,
    S_FB,
    S_NMAX,
    S_NMIN,
    S_RESETS,
    S_REVERSALS,
    S_SV,
    S_Z,
    STRIBECK_SIDE,
    CurveKind,
    ModelKind,
    new_state,
)

__all__ = ["P_SIZE", "new_state"]  # the layout is re-exported for the kernels' callers

# Compiled without numba's reference counting (_nrt=False): no kernel allocates (every output
# array is passed in), and with reference counting each call of a helper that takes an array
# costs atomic increments and decrements on every step, more than the arithmetic of a step at
# rest. error_model="numpy": divisions follow IEEE rules instead of raising (no per-division
# check in the hot loop). nogil: a long simulation in one thread (the web app's experiment
# tab) must not stall another (its live plots). Small helpers are inlined at the Numba IR level.
kernel = njit(cache=True, error_model="numpy", nogil=True, _nrt=False)
helper = njit(cache=True, error_model="numpy", inline="always", nogil=True, _nrt=False)

LEUVEN, LUGRE, STATIC = int(ModelKind.LEUVEN), int(ModelKind.LUGRE), int(ModelKind.STATIC)
PIECEWISE_LINEAR = int(CurveKind.PIECEWISE_LINEAR)
NEG = P_SP + STRIBECK_SIDE  # first Stribeck value of the negative side

# F_h within this fraction of S(v) - F_b counts as "dz/dt has become zero" (reset to sliding).
# Eq. (5) only approaches S(v) asymptotically; without a tolerance the reset of Section
# III-B would never fire in floating point.
RESET_TOL = 1e-9


# ---------------------------------------------------------------- constant-velocity curve
@helper
def stribeck(p, v, side):
    """Eq. (7) on the side ``side`` (+1/-1); |v/vs| because Table I's negative vs is negative.
    delta = 1/2 (Table I's positive side) is a square root, not a general power."""
    o = P_SP if side > 0 else NEG
    Fs, Fc, vs, dl = p[o], p[o + 1], p[o + 2], p[o + 3]
    if v == 0.0:
        return Fs
    u = abs(v / vs)
    e = math.sqrt(u) if dl == 0.5 else u**dl
    return Fc + (Fs - Fc) * math.exp(-e)


@helper
def viscous_coefficient(p, side):
    return p[P_SP + 4] if side > 0 else p[NEG + 4]


@kernel
def stribeck_pass(p, t, x, V, S):
    """Velocity (backward difference of x) and S(v) of a prescribed motion, in one pass ahead
    of the state loop: no step depends on another here, so the exp and pow of eq. (7) of
    successive steps overlap in the pipeline instead of queueing behind the Newton solve.
    A velocity equal to the previous one reuses its S (an encoder-quantised motion repeats a
    handful of velocities)."""
    V[0] = 0.0
    vlast = 0.0
    slast = p[P_SP]
    S[0] = slast  # at rest: F_s+ (no step reads it)
    for k in range(1, t.shape[0]):
        v = (x[k] - x[k - 1]) / (t[k] - t[k - 1])
        V[k] = v
        if v != vlast:
            vlast = v
            slast = stribeck(p, v, 1.0 if v > 0.0 else -1.0)
        S[k] = slast


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
    if kind == PIECEWISE_LINEAR:
        return _odd_interp(tz, tF, z)
    return tF[0] * math.tanh(z / tF[1]) + tF[2] * z


@helper
def transition_slope(kind, tz, tF, z):
    """dF_d/dz; at a knot the slope of the segment on the far side of the origin's."""
    if kind == PIECEWISE_LINEAR:
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
    if kind == PIECEWISE_LINEAR:
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
    """a^(n-1) for a >= 0. For an integer n, multiplications by repeated squaring: for the
    paper's n = 7, a^6 = (a·a·a)², three multiplications deep instead of six."""
    ni = int(p[P_NINT])
    if ni == 7:
        a3 = a * a * a
        return a3 * a3
    if ni > 0:
        m = ni - 1
        r = 1.0
        b = a
        while m > 0:
            if m & 1:
                r *= b
            b *= b
            m >>= 1
        return r
    return a ** (p[P_N] - 1.0)


@helper
def solve_state_equation(p, kind, tz, tF, z0, fd0, dx, D, kap):
    """Backward-Euler step of eq. (5) written per unit displacement,
    z1 = z0 + dx·(1 - sign(r)|r|^n), r = F_d(κ·z1)/D, D = S(v) - F_b; ``fd0`` = F_d(κ·z0).

    Eq. (5) is stiff in sliding (rate |v|·n·κF_d'/|D|); the implicit step is unconditionally
    stable there. With dx/D > 0 the residual g is strictly increasing in z1, so the root is
    unique. The first guess is the linearly implicit step (one Newton step from z0 with the
    Jacobian at z0): in presliding it is the explicit step, in sliding it lands within O(dx²)
    of the root instead of overshooting by the stiffness ratio, so most steps need one
    correction. Each evaluation of g narrows a bracket; a Newton step leaving it bisects.
    The bracket's far end, [z0, z0 + dx] below the steady state and [F_d^{-1}(D)/κ, z0]
    above it, costs an inversion of the curve and is only computed when a step needs more
    than one correction (large steps, e.g. encoder jumps).
    """
    n = p[P_N]
    r0 = fd0 / D
    rn0 = _abs_pow(abs(r0), p)
    ph0 = rn0 * r0
    below = ph0 < 1.0
    g0 = -dx * (1.0 - ph0)
    dg0 = 1.0 + dx * n * rn0 * kap * transition_slope(kind, tz, tF, kap * z0) / D
    z = z0 - g0 / dg0
    # z0 bounds the root on one side (g(z0) = g0); z0 + dx on the other below the steady state
    if g0 < 0.0:
        lo, hi = z0, math.inf
    else:
        lo, hi = -math.inf, z0
    if below:  # [z0, z0 + dx] is free
        if dx > 0.0:
            hi = z0 + dx
        else:
            lo = z0 + dx
    # 1e-7 of the step: far below the O(dt) error of the time step itself
    tol = 1e-7 * abs(dx) + 1e-300
    far_known = below
    for it in range(60):
        fd = transition_curve(kind, tz, tF, kap * z)
        r = fd / D
        rn1 = _abs_pow(abs(r), p)
        g = z - z0 - dx * (1.0 - rn1 * r)
        if g == 0.0:
            break
        if g > 0.0:
            hi = min(hi, z)
        else:
            lo = max(lo, z)
        dg = 1.0 + dx * n * rn1 * kap * transition_slope(kind, tz, tF, kap * z) / D
        zn = z - g / dg
        if abs(zn - z) <= tol:
            z = zn
            break
        if not far_known:
            far_known = True
            zs = transition_curve_inverse(kind, tz, tF, D) / kap
            if dx > 0.0:
                lo = max(lo, zs)
            else:
                hi = min(hi, zs)
        if zn <= lo or zn >= hi:
            zn = 0.5 * (lo + hi)
        z = zn
    return z


# ---------------------------------------------------------------- one step of each model
@helper
def hysteresis(model, st, p, kind, tz, tF, kap):
    """F_h of the current state: eq. (4) for Leuven, σ0·z for LuGre (κ·σ0 with a stiffness
    scale), the last S(v) or the stuck force for the static model."""
    if model == LEUVEN:
        return hysteresis_force(st, kind, tz, tF, kap)
    if model == LUGRE:
        return kap * p[P_SIGMA0] * st[S_Z]
    return st[S_FB]


@helper
def leuven_advance(st, p, kind, tz, tF, dx, side, s, kap):
    """Advance the Leuven state over displacement ``dx`` moving in direction ``side`` with
    S(v) = ``s``.

    Returns (continuous change of z, F_h after the step); the continuous change is what
    σ1·dz/dt sees: the jumps of z made by reset and loop closing leave F_h unchanged and are
    not part of dz/dt.
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
        fd = transition_curve(kind, tz, tF, kap * z)
    z1 = solve_state_equation(p, kind, tz, tF, z, fd, dx, D, kap)
    st[S_Z] = z1
    fh = fb + transition_curve(kind, tz, tF, kap * z1)
    nmin = st[S_NMIN]
    nmax = st[S_NMAX]
    if nmin >= 2.0 and nmax >= 2.0:
        close_internal_loops(st, kind, tz, tF, fh, kap)
    return z1 - z, fh


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
def advance_with(model, st, p, kind, tz, tF, dx, side, s, kap):
    """Advance the friction state over one step of length dx ≠ 0 with S(v) = ``s``; returns
    (continuous change of z, F_h after the step). The static model keeps S(v) in the F_b slot."""
    st[S_SV] = s
    if model == LEUVEN:
        return leuven_advance(st, p, kind, tz, tF, dx, side, s, kap)
    if model == LUGRE:
        dz = lugre_advance(st, p, dx, side, s, kap)
        return dz, kap * p[P_SIGMA0] * st[S_Z]
    st[S_FB] = s
    return 0.0, s


@helper
def advance(model, st, p, kind, tz, tF, dx, v, kap):
    """Advance the friction state over one step; returns the continuous change of z."""
    if dx == 0.0 or v == 0.0:
        return 0.0
    side = 1.0 if v > 0.0 else -1.0
    dz, _ = advance_with(model, st, p, kind, tz, tF, dx, side, stribeck(p, v, side), kap)
    return dz


@helper
def friction_output(model, st, p, kind, tz, tF, dz, dt, v, sc, kap):
    """(F, F_h): eq. (3) for Leuven, eq. (2) for LuGre, S(v) + σ2·v for the static model
    (which reports its last S, or the stuck force, at v = 0); both times the friction scale
    ``sc`` (1 for the model as given), which multiplies the whole of eq. (3)."""
    fh = hysteresis(model, st, p, kind, tz, tF, kap)
    side = 1.0 if v >= 0.0 else -1.0
    return sc * (fh + p[P_SIGMA1] * dz / dt + viscous_coefficient(p, side) * v), sc * fh


# ---------------------------------------------------------------- driver 1: prescribed x(t)
@helper
def _displacement_step(model, p, kind, tz, tF, st, t, x, S, F, Fh, Z, V, k, sc, kap, kap_last, fh, sig1, c_pos, c_neg):
    """Step k of ``run_displacement_along``; returns F_h after it (unscaled). σ1 and σ2± come in
    as scalars: read from ``p`` they would be reloaded every step (the output arrays may alias it)."""
    v = V[k]
    if v == 0.0:
        if kap != kap_last:
            fh = hysteresis(model, st, p, kind, tz, tF, kap)
        F[k] = sc * fh
        Fh[k] = sc * fh
    else:
        side = 1.0 if v > 0.0 else -1.0
        dz, fh = advance_with(model, st, p, kind, tz, tF, x[k] - x[k - 1], side, S[k], kap)
        F[k] = sc * (fh + sig1 * dz / (t[k] - t[k - 1]) + (c_pos if side > 0.0 else c_neg) * v)
        Fh[k] = sc * fh
    Z[k] = st[S_Z]
    return fh


@kernel
def run_displacement(model, p, kind, tz, tF, st, t, x, fsc, ksc, F, Fh, Z, V):
    """Friction along a prescribed displacement; v is the backward difference of x.

    S(v) is evaluated for the whole motion first (``stribeck_pass``, into ``Fh`` as scratch:
    step k reads S(v_k) there before writing F_h), then ``run_displacement_along``.
    """
    stribeck_pass(p, t, x, V, Fh)
    run_displacement_along(model, p, kind, tz, tF, st, t, x, fsc, ksc, V, Fh, F, Fh, Z)


@kernel
def run_displacement_along(model, p, kind, tz, tF, st, t, x, fsc, ksc, V, S, F, Fh, Z):
    """``run_displacement`` with v and S(v) given (``stribeck_pass``'s V and S, which many
    simulations along one path with one S(v) share). ``S`` may be ``Fh`` itself.

    A step at rest (dx = 0, most steps of an encoder-quantised motion) only copies F_h.
    Scales given as one value are read once, outside the loop.
    """
    n = t.shape[0]
    fh = hysteresis(model, st, p, kind, tz, tF, ksc[0])
    F[0] = fsc[0] * fh
    Fh[0] = fsc[0] * fh
    Z[0] = st[S_Z]
    sig1 = p[P_SIGMA1]
    c_pos = p[P_SP + 4]
    c_neg = p[NEG + 4]
    if fsc.shape[0] == 1 and ksc.shape[0] == 1:
        sc = fsc[0]
        kap = ksc[0]
        for k in range(1, n):
            fh = _displacement_step(model, p, kind, tz, tF, st, t, x, S, F, Fh, Z, V, k, sc, kap, kap, fh,
                                    sig1, c_pos, c_neg)
    else:
        fstep = 1 if fsc.shape[0] > 1 else 0
        kstep = 1 if ksc.shape[0] > 1 else 0
        kap_last = ksc[0]
        for k in range(1, n):
            kap = ksc[k * kstep]
            fh = _displacement_step(model, p, kind, tz, tF, st, t, x, S, F, Fh, Z, V, k, fsc[k * fstep], kap,
                                    kap_last, fh, sig1, c_pos, c_neg)
            kap_last = kap


# ---------------------------------------------------------------- along a motion
@kernel
def count_significant_reversals(x, min_excursion, out):
    """``out`` (zeros, like ``x``) gets the running count of the direction changes of ``x``
    whose back-travel exceeds ``min_excursion``, stepping up at the turning point itself (the
    extremum), once the back-travel has confirmed it (``model.effects.significant_reversals``)."""
    n = x.shape[0]
    direction = 0.0
    ext = x[0]
    ext_i = 0
    for i in range(1, n):
        xi = x[i]
        if xi == x[i - 1]:
            continue
        if direction == 0.0:
            if abs(xi - x[0]) > min_excursion:
                direction = 1.0 if xi > x[0] else -1.0
                ext = xi
                ext_i = i
            continue
        if (xi - ext) * direction > 0.0:
            ext = xi
            ext_i = i
        elif (ext - xi) * direction > min_excursion:
            out[ext_i] += 1.0
            direction = -direction
            ext = xi
            ext_i = i
    for i in range(1, n):
        out[i] += out[i - 1]


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
