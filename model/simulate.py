"""The Python face of the simulator: validated inputs in, a ``SimResult`` out.

Three drivers, one per way the paper drives its system:
``simulate_displacement`` (prescribed x(t) → friction, used for feedforward and fitting),
``simulate_force`` (prescribed applied force on I·ẍ = f - F, eq. (8)) and
``simulate_closed_loop`` (P/PI position control with optional feedforward).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from . import kernels as K
from . import layout as L
from .errors import SignalError
from .params import FrictionParams, Stribeck

COLUMNS = ("time", "position", "velocity", "applied_force", "friction_force", "hysteresis_force", "z")


@dataclass
class SimResult:
    """Time series of one simulation (SI units unless the parameters say otherwise)."""

    time: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    applied_force: np.ndarray
    friction_force: np.ndarray
    hysteresis_force: np.ndarray
    z: np.ndarray
    model: str = "leuven"
    memory: dict = field(default_factory=dict)

    def columns(self) -> dict:
        return {c: getattr(self, c) for c in COLUMNS}

    def __len__(self) -> int:
        return len(self.time)


def pack(params: FrictionParams) -> tuple[int, np.ndarray, int, np.ndarray, np.ndarray]:
    """(model code, parameter vector, transition kind, tz, tF) for ``model.kernels``."""
    p = np.zeros(L.P_SIZE)
    p[L.P_SP : L.P_SP + 2 * L.STRIBECK_SIDE] = params.stribeck.as_array()
    p[L.P_N] = params.n
    p[L.P_NINT] = params.n if (float(params.n).is_integer() and 1 <= params.n <= 32) else 0
    p[L.P_SIGMA1] = params.sigma1
    p[L.P_SIGMA0] = params.sigma0 or 0.0
    p[L.P_REVTOL] = params.reversal_tol
    p[L.P_INERTIA] = params.inertia
    kind, tz, tF = params.curve_arrays()
    return int(L.ModelKind.parse(params.model)), p, kind, tz, tF


def initial_state(params: FrictionParams, fh0: float = 0.0, stack_depth: int = 64) -> np.ndarray:
    """At rest, hysteresis force ``fh0``, memory holding only the outer loop F_s- … F_s+."""
    _, p, *_ = pack(params)
    st = L.new_state(stack_depth)
    K.init_state(st, p, fh0)
    if params.model == "lugre" and params.sigma0:
        L.State(st).z = fh0 / params.sigma0
    return st


def memory_summary(st: np.ndarray) -> dict:
    """The hysteresis memory of a state vector as a JSON-able record."""
    return L.State(st).summary()


def _time(t) -> np.ndarray:
    t = np.ascontiguousarray(t, dtype=np.float64)
    if t.ndim != 1 or len(t) < 2:
        raise SignalError(f"time: need a 1-D series of at least 2 samples, got shape {t.shape}")
    if not np.all(np.isfinite(t)):
        raise SignalError(f"time: non-finite value at sample {int(np.argmin(np.isfinite(t)))}")
    bad = np.flatnonzero(np.diff(t) <= 0)
    if len(bad):
        raise SignalError(f"time: must increase strictly, but sample {bad[0] + 1} is not after sample {bad[0]}")
    return t


def _series(name: str, a, n: int) -> np.ndarray:
    a = np.ascontiguousarray(a, dtype=np.float64)
    if a.shape != (n,):
        raise SignalError(f"{name}: expected {n} samples like time, got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise SignalError(f"{name}: non-finite value at sample {int(np.argmin(np.isfinite(a)))}")
    return a


_ONE = np.ones(1)


def _scale(name: str, a, n: int) -> np.ndarray:
    """A per-sample scale factor (or one number for all samples); absent means 1."""
    if a is None:
        return _ONE
    a = np.ascontiguousarray(np.atleast_1d(a), dtype=np.float64)
    if a.shape == (1,):
        a = np.full(n, a[0])
    if a.shape != (n,):
        raise SignalError(f"{name}: expected {n} samples like time (or one number), got shape {a.shape}")
    if not np.all(np.isfinite(a)):
        raise SignalError(f"{name}: non-finite value at sample {int(np.argmin(np.isfinite(a)))}")
    if name == "stiffness_scale" and np.any(a <= 0):
        raise SignalError(f"{name}: must be > 0, but sample {int(np.argmax(a <= 0))} is {a[a <= 0][0]}")
    if name == "friction_scale" and np.any(a < 0):
        raise SignalError(f"{name}: must be >= 0, but sample {int(np.argmax(a < 0))} is {a[a < 0][0]}")
    return a


@dataclass(frozen=True, eq=False)
class SteadyAlong:
    """v (the backward difference of x) and S(v) of eq. (7) along one prescribed path, for one
    S(v) (``steady_along``; read-only copies): what every simulation along that path with that
    S(v) shares. A fit that varies the presliding stiffness, n or σ1 simulates one path many
    times, and S(v) (an exp and a power per moving sample) is a quarter of each simulation.
    ``steady[0]``, at rest before the first step, is F_s of the positive side (never used)."""

    time: np.ndarray
    position: np.ndarray
    curve: tuple  # ``steady_curve_key`` of the S(v) it holds
    velocity: np.ndarray
    steady: np.ndarray

    def same_curve(self, params: FrictionParams) -> bool:
        """Whether ``params`` have the S(v) this holds (σ2, which eq. (7) does not hold, aside)."""
        return self.curve == steady_curve_key(params.stribeck)

    def serves(self, params: FrictionParams, t: np.ndarray, x: np.ndarray) -> bool:
        """Whether this is the v and S(v) of ``params`` along (t, x)."""
        return (self.same_curve(params) and (self.time is t or np.array_equal(self.time, t))
                and (self.position is x or np.array_equal(self.position, x)))


def steady_curve_key(stribeck: Stribeck) -> tuple:
    """What of S(v) the steady pass reads: F_s, F_c, v_s, δ of each side (eq. (7))."""
    return tuple((sd.Fs, sd.Fc, sd.vs, sd.delta) for sd in (stribeck.positive, stribeck.negative))


def steady_along(params: FrictionParams, t, x) -> SteadyAlong:
    """v and S(v) of ``params`` along the prescribed path x(t), for ``simulate_displacement``'s
    ``steady`` along the same path."""
    t = _time(t).copy()
    x = _series("position", x, len(t)).copy()
    _, p, *_ = pack(params)
    V, S = np.empty(len(t)), np.empty(len(t))
    K.stribeck_pass(p, t, x, V, S)
    for a in (t, x, V, S):
        a.setflags(write=False)
    return SteadyAlong(t, x, steady_curve_key(params.stribeck), V, S)


def simulate_displacement(params: FrictionParams, t, x, *, state: np.ndarray | None = None,
                          friction_scale=None, stiffness_scale=None, steady: SteadyAlong | None = None) -> SimResult:
    """Friction predicted along a prescribed displacement x(t).

    The applied force reported is the one that would produce this motion, I·ẍ + F.
    ``state`` (from ``initial_state``) lets a caller start from a chosen memory and read it
    back afterwards; it is updated in place.

    ``friction_scale`` (per sample, default 1) multiplies the friction force of eq. (3) (and
    the reported F_h); ``stiffness_scale`` κ (per sample, default 1) multiplies the presliding
    stiffness: F_d is evaluated at κ·z (same maximum force, abscissas divided by κ), LuGre's
    σ0 becomes κ·σ0. Both act inside the time loop, so a plant driven by force feels them.

    ``steady`` (from ``steady_along`` on this path, for this S(v)) skips the pass that
    computes v and S(v).
    """
    t = _time(t)
    x = _series("position", x, len(t))
    n = len(t)
    fsc = _scale("friction_scale", friction_scale, n)
    ksc = _scale("stiffness_scale", stiffness_scale, n)
    code, p, kind, tz, tF = pack(params)
    st = initial_state(params) if state is None else state
    F, Fh, Z = (np.empty(n) for _ in range(3))
    if steady is None:
        V = np.empty(n)
        K.run_displacement(code, p, kind, tz, tF, st, t, x, fsc, ksc, F, Fh, Z, V)
    else:
        if not steady.serves(params, t, x):
            raise ValueError("steady: computed for another path or another S(v) (steady_along)")
        V = steady.velocity.copy()
        K.run_displacement_along(code, p, kind, tz, tF, st, t, x, fsc, ksc, V, steady.steady, F, Fh, Z)
    acc = np.zeros(n)
    acc[1:] = np.diff(V) / np.diff(t)
    return SimResult(t, x, V, params.inertia * acc + F, F, Fh, Z, params.model, memory_summary(st))


def friction_along(params: FrictionParams, steady: SteadyAlong, *, stiffness_scale=None) -> np.ndarray:
    """The friction force of ``simulate_displacement(params, steady.time, steady.position,
    steady=steady, stiffness_scale=...)`` alone, from rest: the path was checked when ``steady``
    was made, and no velocity copy, applied force or memory record is built — a fit that
    simulates one path hundreds of times spent a fifth of each simulation on those."""
    if not steady.same_curve(params):
        raise ValueError("steady: computed for another S(v) (steady_along)")
    n = len(steady.time)
    ksc = _scale("stiffness_scale", stiffness_scale, n)
    code, p, kind, tz, tF = pack(params)
    F, Fh, Z = np.empty(n), np.empty(n), np.empty(n)
    K.run_displacement_along(code, p, kind, tz, tF, initial_state(params), steady.time, steady.position, _ONE, ksc,
                             steady.velocity, steady.steady, F, Fh, Z)
    return F


def simulate_force(params: FrictionParams, t, f, *, x0: float = 0.0, v0: float = 0.0,
                   state: np.ndarray | None = None, friction_scale=None, stiffness_scale=None) -> SimResult:
    """The plant I·ẍ = f - F (eq. (8)) under a prescribed applied force f(t).

    ``friction_scale`` and ``stiffness_scale``: as in ``simulate_displacement``; the plant
    feels the scaled friction.
    """
    t = _time(t)
    f = _series("applied_force", f, len(t))
    n = len(t)
    fsc = _scale("friction_scale", friction_scale, n)
    ksc = _scale("stiffness_scale", stiffness_scale, n)
    code, p, kind, tz, tF = pack(params)
    st = initial_state(params) if state is None else state
    X, V, F, Fh, Z = (np.zeros(n) for _ in range(5))
    X[0], V[0] = x0, v0
    K.run_force(code, p, kind, tz, tF, st, t, f, fsc, ksc, X, V, F, Fh, Z)
    return SimResult(t, X, V, f.copy(), F, Fh, Z, params.model, memory_summary(st))


def simulate_closed_loop(params: FrictionParams, t, x_ref, *, kp: float, ki: float = 0.0, feedforward=None,
                         encoder_step: float = 0.0, ctrl_every: int = 1, x0: float = 0.0,
                         state: np.ndarray | None = None, friction_scale=None,
                         stiffness_scale=None) -> SimResult:
    """Position control: u = Kp·e + Ki·∫e + feedforward, e = x_ref - quantised x.

    ``friction_scale`` and ``stiffness_scale``: as in ``simulate_displacement``.
    """
    t = _time(t)
    x_ref = _series("x_ref", x_ref, len(t))
    ff = np.zeros(len(t)) if feedforward is None else _series("feedforward", feedforward, len(t))
    if ctrl_every < 1:
        raise SignalError(f"ctrl_every: must be >= 1, got {ctrl_every}")
    n = len(t)
    fsc = _scale("friction_scale", friction_scale, n)
    ksc = _scale("stiffness_scale", stiffness_scale, n)
    code, p, kind, tz, tF = pack(params)
    st = initial_state(params) if state is None else state
    X, V, U, F, Fh, Z = (np.zeros(n) for _ in range(6))
    X[0] = x0
    K.run_closed_loop(code, p, kind, tz, tF, st, t, x_ref, ff, float(kp), float(ki), float(encoder_step),
                      int(ctrl_every), fsc, ksc, X, V, U, F, Fh, Z)
    return SimResult(t, X, V, U, F, Fh, Z, params.model, memory_summary(st))


def stribeck_curve(params: FrictionParams, v) -> np.ndarray:
    """Steady-state friction S(v) + σ2·v, eq. (6), vectorised (0 at v = 0)."""
    v = np.asarray(v, dtype=np.float64)
    out = np.zeros_like(v)
    for side, sp in ((1, params.stribeck.positive), (-1, params.stribeck.negative)):
        m = v * side > 0
        vv = v[m]
        out[m] = sp.Fc + (sp.Fs - sp.Fc) * np.exp(-np.abs(vv / sp.vs) ** sp.delta) + sp.sigma2 * vv
    return out


def transition_curve_values(params: FrictionParams, z) -> np.ndarray:
    """F_d(z), vectorised."""
    kind, tz, tF = params.curve_arrays()
    z = np.ascontiguousarray(np.atleast_1d(z), dtype=np.float64)
    out = np.empty_like(z)
    K.transition_curve_array(kind, tz, tF, z, out)
    return out
