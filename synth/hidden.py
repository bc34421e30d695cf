"""Recordings with hidden effects, for testing ``leuven-friction diagnose`` on data it has never seen.

Built on ``synth/recordings.py`` (its own Maxwell-slip simulator, its own machines far from the
paper's): every effect is imposed *inside* the simulation loop through the generator's
``friction_modifier`` / ``stiffness_modifier`` hooks, by a rule written here, in a shape that
is not the candidate's and with parameters drawn from continuous ranges (no grid):

``time_drift``        the lubricant warms up: a temperature rise ΔT·(1 − e^{−t/τ_T}) and a
                      viscosity-like law friction × exp(−β·ΔT(t)) (the candidate is linear in
                      the first-order approach, this is its exponential);
``normal_load``       a normal load that moves up and down on a random piecewise-linear
                      schedule (logged as a column), friction × (N/N_ref)^α, α in 0.55 … 0.9
                      (on the tribometer, which already has friction ∝ N, the exponent is
                      changed to α);
``position_ripple``   a non-sinusoidal periodic profile along the position (fundamental plus a
                      second harmonic of random phase), wavelength a random fraction of the
                      travel;
``cyclic_softening``  the presliding springs soften with the number of reversals counted by
                      the hook itself (back-travel beyond a third of the presliding range),
                      saturating like 1 − h·(1 − 1/(1 + n/n_h)) (hyperbolic, not
                      exponential).

``make_case(kind, seed, effects)`` returns (DataFrame as written to CSV, Truth, Case).
The ``tribometer`` kind's own load ramps (0 → N0 before the strokes, back after them, while
the contact sticks) are a normal-load dependence by construction; ``Case.expected`` says so.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from synth import recordings as R

HIDDEN = ("time_drift", "normal_load", "position_ripple", "cyclic_softening")
KINDS = R.KINDS
PAIRS = (("time_drift", "position_ripple"), ("normal_load", "cyclic_softening"), ("position_ripple", "normal_load"))


@dataclass
class Case:
    kind: str
    seed: int
    effects: tuple
    params: dict = field(default_factory=dict)  # effect -> the drawn parameters (SI)
    load_ramps: bool = False  # tribometer: the generator's own load ramps while sticking

    @property
    def expected(self) -> set:
        return set(self.effects) | ({"normal_load"} if self.load_ramps else set())

    @property
    def label(self) -> str:
        return f"{self.kind}/{self.seed}/{'+'.join(self.effects) or 'none'}"


def _duration(kind: str, seed: int, gen: dict) -> float:
    """Length of the schedule (a first pass without hooks)."""
    df, _ = R.make_recording(kind, seed, **gen)
    return float(df.iloc[-1, 0] - df.iloc[0, 0])


def _load_schedule(rng, T: float, N_ref: float, spread: float):
    """Piecewise-linear load through random knots, up and down (never monotone)."""
    m = int(rng.integers(7, 12))
    tk = np.sort(np.concatenate([[0.0, T * 1.05], rng.uniform(0, T, m)]))
    levels = 1.0 + spread * np.where(np.arange(len(tk)) % 2 == 0, -1, 1) * rng.uniform(0.4, 1.0, len(tk))
    vals = N_ref * levels

    def load(t):
        return np.interp(t, tk, vals)

    return load


class _ReversalCounter:
    """The hook's own count of reversals: direction changes whose back-travel exceeds ``th``,
    on the block-start positions the generator passes in."""

    def __init__(self, th: float):
        self.th = th
        self.dir = 0.0
        self.ext = None
        self.count = 0
        self.last_t = -np.inf

    def update(self, t0: float, x: float) -> int:
        if t0 <= self.last_t:
            return self.count
        self.last_t = t0
        if self.ext is None:
            self.ext = x
            return 0
        if self.dir == 0.0:
            if abs(x - self.ext) > self.th:
                self.dir = 1.0 if x > self.ext else -1.0
                self.ext = x
        elif (x - self.ext) * self.dir > 0:
            self.ext = x
        elif (self.ext - x) * self.dir > self.th:
            self.count += 1
            self.dir = -self.dir
            self.ext = x
        return self.count


def make_case(kind: str, seed: int, effects=(), *, load_ramps: bool | None = None, **gen):
    """One recording of ``kind`` with the ``effects`` hidden in it (see the module docstring)."""
    effects = tuple(effects)
    for e in effects:
        if e not in HIDDEN:
            raise ValueError(f"unknown hidden effect {e!r}")
    mach = R._random_machine(kind, np.random.default_rng(seed))  # the machine make_recording will draw
    rng = np.random.default_rng([seed, 9173])
    T = _duration(kind, seed, gen)
    zr = float(np.max(mach["alpha"] * (mach["stribeck"]["positive"]["Fs"] - mach["stribeck"]["negative"]["Fs"])
                      / mach["k"]))
    case = Case(kind, seed, effects)
    fmods, kmods = [], []
    normal_load = None
    if kind == "tribometer":
        ramps = False if load_ramps is None else (load_ramps and "normal_load" not in effects)
        case.load_ramps = ramps
        if not ramps and "normal_load" not in effects:
            N0 = rng.uniform(3.0, 6.0)
            normal_load = (lambda t, N0=N0: np.full(np.shape(t), N0))
    if "time_drift" in effects:
        tau = T * rng.uniform(0.12, 0.5)
        beta_dT = rng.choice([-1, 1]) * rng.uniform(0.18, 0.4)
        case.params["time_drift"] = {"tau_T": tau, "beta_dT": beta_dT}
        fmods.append(lambda c, tau=tau, k=beta_dT: np.exp(-k * (1.0 - np.exp(-c.t / tau))))
    if "normal_load" in effects:
        alpha = rng.uniform(0.55, 0.9)
        N_ref = {"robot_joint": rng.uniform(300, 2000), "linear_stage": rng.uniform(50, 400),
                 "tribometer": rng.uniform(3.0, 6.0)}[kind]
        normal_load = _load_schedule(rng, T, N_ref, rng.uniform(0.25, 0.45))
        case.params["normal_load"] = {"alpha": alpha, "N_ref": N_ref}
        if kind == "tribometer":
            # the generator already scales by N/N_max: turn that into (N/N_max)^alpha
            n_max = float(np.max(normal_load(np.linspace(0.0, 1.1 * T, 4000))))
            fmods.append(lambda c, a=alpha, m=n_max: (np.maximum(c.N, 1e-12 * m) / m) ** (a - 1.0))
        else:
            fmods.append(lambda c, a=alpha, n=N_ref: (np.maximum(c.N, 0.0) / n) ** a)
    if "position_ripple" in effects:
        lam = {"robot_joint": rng.uniform(0.08, 0.4), "linear_stage": rng.uniform(2e-3, 9e-3),
               "tribometer": rng.uniform(0.03e-3, 0.08e-3)}[kind]
        a1 = rng.uniform(0.08, 0.2)
        a2 = a1 * rng.uniform(0.1, 0.35)
        ph1, ph2 = rng.uniform(0, 2 * np.pi, 2)
        case.params["position_ripple"] = {"wavelength": lam, "a1": a1, "a2": a2}
        fmods.append(lambda c, lam=lam, a1=a1, a2=a2, p1=ph1, p2=ph2:
                     1.0 + a1 * np.sin(2 * np.pi * c.x / lam + p1) + a2 * np.sin(4 * np.pi * c.x / lam + p2))
    if "cyclic_softening" in effects:
        h = rng.uniform(0.3, 0.6)
        n_h = {"robot_joint": rng.uniform(2.0, 8.0), "linear_stage": rng.uniform(2.0, 8.0),
               "tribometer": rng.uniform(1.5, 5.0)}[kind]
        counter = _ReversalCounter(zr / 3.0)
        case.params["cyclic_softening"] = {"h": h, "n_h": n_h, "threshold": zr / 3.0}

        def soften(c, h=h, n_h=n_h, counter=counter):
            n = counter.update(float(c.t[0]), float(c.x[0]))
            return 1.0 - h * (1.0 - 1.0 / (1.0 + n / n_h))

        kmods.append(soften)

    def fmod(c):
        out = 1.0
        for f in fmods:
            out = out * f(c)
        return out

    df, truth = R.make_recording(kind, seed, friction_modifier=fmod if fmods else None,
                                 stiffness_modifier=kmods[0] if kmods else None, normal_load=normal_load, **gen)
    return df, truth, case


def oracle_params(truth):
    """The machine's own friction without any hidden effect, seen through the Leuven model:
    the generator's S(v), a piecewise-linear transition curve through the Maxwell-slip
    elements' break-away points, its σ1 and inertia. A base model as good as a fit can be,
    yet not of the generator's form."""
    from leuven_friction.model import Stribeck, StribeckSide, TransitionCurve, default_params

    st = truth.stribeck
    side = lambda d: StribeckSide(**{k: float(d[k]) for k in ("Fs", "Fc", "vs", "delta", "sigma2")})  # noqa: E731
    span = st["positive"]["Fs"] - st["negative"]["Fs"]
    zb = np.sort(truth.element_weight * span / truth.element_stiffness)
    z = np.concatenate([[0.0], zb])
    F = truth.transition_curve(z)
    units = {"position": "m" if truth.kind != "robot_joint" else "rad", "force": "N" if truth.kind != "robot_joint" else "N*m",
             "time": "s"}
    return default_params().replace(stribeck=Stribeck(side(st["positive"]), side(st["negative"])),
                                    transition_curve=TransitionCurve(kind="piecewise_linear", z=tuple(map(float, z)),
                                                                     F=tuple(map(float, F))),
                                    sigma1=float(truth.sigma1), inertia=float(truth.inertia), units=units, n=16.0)


def shuffled_levels(kind: str, seed: int) -> np.ndarray | None:
    """The sweep levels ``make_recording`` would visit in rising order for this machine, in an
    order shuffled by the seed: the separating experiment the diagnosis proposes when a sweep
    orders its speeds in time (a drift and the shape of S(v) are then confounded). Pass as
    ``make_case(..., levels=...)``. None for a tribometer, whose strokes cycle through their
    speeds already."""
    if kind == "tribometer":
        return None
    levels = R.sweep_levels(R._random_machine(kind, np.random.default_rng(seed))["stribeck"])
    return levels[np.random.default_rng([seed, 555]).permutation(len(levels))]


SUITE_RATE = {"robot_joint": 250.0, "linear_stage": 400.0, "tribometer": 200.0}  # Hz, to keep the suite short


def suite(seeds_per_effect: int = 10, controls: int = 20, pair_seeds: int = 4, start: int = 1000) -> list:
    """The case list: every single effect on ``seeds_per_effect`` seeds (kinds in turn),
    ``controls`` seeds with nothing hidden, each pair on ``pair_seeds`` seeds, and the
    tribometer's own load ramps as the real-data shape."""
    cases = []
    s = start
    for e in HIDDEN:
        for i in range(seeds_per_effect):
            cases.append((KINDS[i % 3], s, (e,)))
            s += 1
    for i in range(controls):
        cases.append((KINDS[i % 3], s, ()))
        s += 1
    for pair in PAIRS:
        for i in range(pair_seeds):
            cases.append((KINDS[i % 3], s, pair))
            s += 1
    return cases


def to_recording(df, name: str = "case.csv"):
    import io

    from leuven_friction.identify.data import load_recording

    buf = io.StringIO()
    df.to_csv(buf, index=False, float_format="%.10g")
    cols = {"normal_load": "Normal [uN]"} if "Normal [uN]" in df.columns else None
    return load_recording(buf.getvalue().encode(), name=name, columns=cols)
