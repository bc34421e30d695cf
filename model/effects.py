"""Effects the base model does not hold, owned by the model (Section VI's remark and the
conclusion: "a scaling function or factor in the friction force (3) or in the state equation
(5)").

Every effect is one ``Effect`` object: its name, what it describes, its parameters (unit kind,
bounds, meaning) and how it acts on the model:

- ``acts_on="friction"``: a per-sample factor on the friction force F of eq. (3), inside the
  simulation loop, so a force-driven or closed-loop plant feels it (``friction_scale`` of
  ``model.simulate``);
- ``acts_on="stiffness"``: a per-sample factor κ on the presliding stiffness, F_d evaluated at
  κ·z in eqs. (4)–(5): the transition curve's abscissas divided by κ, same maximum force
  (``stiffness_scale`` of ``model.simulate``).

The factor is a function of a ``Context`` — time, position, velocity, normal load and the
running count of significant reversals along the motion — and of the effect's parameters.
``predict`` drives the model, with every effect of a parameter set, by a displacement, an
applied force or a position controller; ``leuven-friction simulate``, the explorer and the
diagnosis all predict through it. Adding an effect means adding one ``Effect`` to ``EFFECTS``.

An effect is stored in a parameter file as ``{name: ..., params: {...}}``;
``validate_effect_entry`` checks such an entry against its ``Effect``.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from .errors import ParameterError, SignalError


@dataclass(frozen=True)
class EffectParam:
    """One parameter of an effect. ``unit`` is a unit kind resolved against the parameter
    set's units (``time``, ``position``, ``load``) or a literal ("1", "rad", "reversals")."""

    name: str
    unit: str
    lo: float
    hi: float
    description: str
    lo_open: bool = False  # the bound itself is excluded
    default: float | None = None  # the value a parameter file may leave out (None: required)
    # the amplitudes this shape parameter means nothing without, all of them (a ripple's phase
    # without its amplitude, its wavelength without either harmonic, a drift's τ without its
    # change): ``Effect.undetermined``
    shape_of: tuple[str, ...] = ()
    # for an amplitude that is the magnitude of a sine and cosine pair, the phase of that pair
    # (``Effect.undetermined`` judges it as a magnitude, not as a signed value)
    polar_with: str | None = None

    def unit_in(self, units: Mapping[str, str]) -> str:
        """This parameter's unit in a parameter set's ``units`` ("" for a pure number)."""
        if self.unit == "time":
            return units.get("time", "s")
        if self.unit == "position":
            return units.get("position", "")
        if self.unit == "velocity":
            return f"{units.get('position', '')}/{units.get('time', 's')}"
        if self.unit == "load":
            return units.get("normal_load", "N")
        return "" if self.unit == "1" else self.unit

    def check(self, value, path: str) -> float:
        try:
            x = float(value)
        except (TypeError, ValueError):
            raise ParameterError(f"{path}: expected a number, got {value!r}") from None
        if not math.isfinite(x):
            raise ParameterError(f"{path}: must be finite, got {value!r}")
        if x < self.lo or (self.lo_open and x == self.lo) or x > self.hi:
            lo = f"({self.lo:g}" if self.lo_open else f"[{self.lo:g}"
            raise ParameterError(f"{path}: must lie in {lo}, {self.hi:g}] ({self.description}), got {x:g}")
        return x


@dataclass(frozen=True)
class Context:
    """What an effect may depend on, sample by sample, along one motion."""

    time: np.ndarray
    position: np.ndarray | None = None
    velocity: np.ndarray | None = None
    load: np.ndarray | None = None
    reversals: np.ndarray | None = None  # running count of significant reversals above ``min_excursion``
    min_excursion: float = 0.0
    # the product of the friction effects' factors, for an effect on the stiffness that follows
    # them (``presliding_range``); ``effect_scales`` sets it (``with_friction_factor``)
    friction_factor: np.ndarray | None = None
    # counts above other thresholds, made once per context (a softening's own min_excursion)
    _counts: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    # the ripple's phase at the last wavelengths asked for: a fit varies the amplitudes far more
    # often than the wavelength (a Jacobian's columns), and the sines are most of a ripple's cost
    _phase: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    # ln(max(|v|, v_floor)/v_ref) per (v_floor, v_ref): a speed-dependent stiffness's fixed abscissa
    _log_speed: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    # ln(clip(travel, floor, cap)/ref) per (floor, cap, ref, min_excursion): a travel-dependent stiffness's abscissa
    _log_travel: dict = field(default_factory=dict, init=False, repr=False, compare=False)
    # the last FACTORS_KEPT factors made (``Effect.scale``), by the effect's factor and its values
    _factors: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def with_friction_factor(self, m: np.ndarray) -> "Context":
        """This context with the friction effects' factor ``m``, sharing its caches (the
        reversal counts and the ripple's sines are the same along the same motion)."""
        out = dataclasses.replace(self, friction_factor=m)
        object.__setattr__(out, "_counts", self._counts)
        object.__setattr__(out, "_phase", self._phase)
        object.__setattr__(out, "_log_speed", self._log_speed)
        object.__setattr__(out, "_log_travel", self._log_travel)
        object.__setattr__(out, "_factors", self._factors)
        return out

    def signal(self, name: str, effect: str) -> np.ndarray:
        a = getattr(self, name)
        if a is None:
            raise ParameterError(f"effects.{effect}: needs the {name.replace('_', ' ')} signal, which this drive does not have")
        return a

    def reversals_above(self, min_excursion: float, effect: str) -> np.ndarray:
        """The running count of reversals whose back-travel exceeds ``min_excursion``: the
        context's own count at its threshold, else counted along its position once."""
        if min_excursion == self.min_excursion and self.reversals is not None:
            return self.reversals
        key = float(min_excursion)
        if key not in self._counts:
            self._counts[key] = significant_reversals(self.signal("position", effect), key)
        return self._counts[key]

    def factor_of(self, effect: "Effect", values: Mapping[str, float]) -> np.ndarray:
        """``effect``'s factor at ``values`` along this motion (read-only), kept for the last
        FACTORS_KEPT asked for. Not for an effect that follows the friction effects, whose
        factor also depends on theirs."""
        assert not _follows(effect), effect.name
        return _kept(self._factors, (effect.factor, tuple(sorted(values.items()))), FACTORS_KEPT, self.time.size,
                     lambda: effect.along(values, self))

    def log_speed(self, v_floor: float, v_ref: float, effect: str) -> np.ndarray:
        """ℓ = ln(max(|v|, v_floor)/v_ref) along the context's velocity, kept for the last
        pairs asked for (a speed-dependent stiffness's abscissa: its v_floor, v_ref are fixed)."""
        key = (float(v_floor), float(v_ref))
        return _kept(self._log_speed, key, 2, self.time.size,
                     lambda: np.log(np.maximum(np.abs(self.signal("velocity", effect)), key[0]) / key[1]))

    def log_travel(self, floor: float, cap: float, ref: float, min_excursion: float, effect: str) -> np.ndarray:
        """ℓ = ln(clip(s, floor, cap)/ref), s the travel of the stroke before the one each sample
        lies on (reversals whose back-travel exceeds ``min_excursion``: ``stroke_travel``), kept
        for the last two settings asked for (a travel-dependent stiffness's abscissa is fixed)."""
        key = (float(floor), float(cap), float(ref), float(min_excursion))

        def make():
            counts = self.reversals_above(key[3], effect)
            return np.log(np.clip(stroke_travel(self.signal("position", effect), counts), key[0], key[1]) / key[2])

        return _kept(self._log_travel, key, 2, self.time.size, make)

    def phase_along_position(self, wavelength: float, origin: float, effect: str) -> tuple[np.ndarray, np.ndarray]:
        """(sin θ, cos θ) of θ = 2π·(x − x0)/λ along the context's position, kept for the last
        PHASES_KEPT (λ, x0): a finite-difference Jacobian moves λ and comes back to it for the
        next column."""
        key = (float(wavelength), float(origin))

        def make():
            th = 2.0 * np.pi * (self.signal("position", effect) - key[1]) / key[0]
            return np.sin(th), np.cos(th)

        return _kept(self._phase, key, PHASES_KEPT, 2 * self.time.size, make)


def _sigmas(d: float, s: float) -> str:
    """|d| in units of s, as said: "1.8 σ"."""
    return f"{d / s:.2g} σ" if s > 0 else ("0 σ" if d == 0 else "∞ σ")


SHAPE_SIGMAS = 2.0  # an amplitude within this many σ of no effect leaves its shape parameters undetermined
POLAR_SHOWN = 2.45  # … a magnitude within this many σ of its parts (√ of χ²₂'s 95 % point, 5.99)
# a relative amplitude (a drift's b, a softening's h) whose σ exceeds this — the whole of the
# friction or stiffness it scales — is not an estimate at all: its interval bounds nothing
RELATIVE_SD_UNBOUNDED = 1.0
PHASES_KEPT = 3  # wavelengths whose sines a context keeps
FACTORS_KEPT = 6  # effects' factors a context keeps
CACHE_FLOATS = 8_000_000  # … and at most this many floats per cache (64 MB), however long the motion


def _kept(cache: dict, key, most: int, floats: int, make: Callable):
    """``cache[key]``, made by ``make()`` if absent; the cache keeps the most recently used
    entries, at most ``most`` and at most CACHE_FLOATS floats (each entry holds ``floats``)."""
    hit = cache.pop(key, None)
    if hit is None:
        hit = make()
        while cache and len(cache) >= max(1, min(most, CACHE_FLOATS // max(floats, 1))):
            cache.pop(next(iter(cache)))
    cache[key] = hit  # the most recently used last
    return hit


@dataclass(frozen=True)
class Effect:
    name: str
    description: str
    acts_on: str  # "friction" (factor on F, eq. (3)) or "stiffness" (factor on the presliding stiffness, eq. (5))
    params: tuple[EffectParam, ...]
    needs: tuple[str, ...]  # Context signals the factor depends on
    factor: Callable[[Mapping[str, float], Context], np.ndarray] = field(repr=False)
    separated_by: str = ""  # the experiment that isolates this effect from others
    neutral: Mapping[str, float] = field(default_factory=dict)  # values of its amplitudes at which it does nothing
    # (amplitude, word below neutral, word above): which way a signed effect acts, said beside its
    # name — a contact that stiffens is a "cyclic_softening" with h > 0, which reads wrong alone
    sense: tuple[str, str, str] | None = None
    ordered: tuple[tuple[str, str], ...] = ()  # (a, b): a parameter file's a must not exceed its b

    @property
    def param_names(self) -> tuple[str, ...]:
        return tuple(p.name for p in self.params)

    def sense_of(self, values: Mapping[str, float]) -> str:
        """Which way the effect acts at ``values`` ("hardening", "falling"), or ""."""
        if self.sense is None or self.sense[0] not in values:
            return ""
        name, below, above = self.sense
        x, at = values[name], self.neutral.get(name, 0.0)
        return below if x < at else above if x > at else ""

    def scale(self, values: Mapping[str, float], ctx: Context) -> np.ndarray:
        """The factor along the context's motion (read-only). One that does not follow the
        friction effects is kept by the context for its values: a finite-difference Jacobian
        moves one parameter of one effect at a time, and every other effect's factor repeats."""
        return self.along(values, ctx) if _follows(self) else ctx.factor_of(self, values)

    def along(self, values: Mapping[str, float], ctx: Context) -> np.ndarray:
        """The factor made anew along the context's motion (read-only; one number broadcast)."""
        return np.broadcast_to(np.asarray(self.factor(values, ctx), dtype=np.float64), ctx.time.shape)

    def without(self, values: Mapping[str, float]) -> dict:
        """``values`` with the effect's amplitudes at ``neutral``: its shape kept, its factor 1."""
        return {**values, **self.neutral}

    def undetermined(self, values: Mapping[str, float], sd: Mapping[str, float] | None) -> dict[str, str]:
        """{shape parameter: why} for each one whose amplitudes (``EffectParam.shape_of``) are
        not told from no effect (``amplitude_not_shown``): the data then show no such
        term, so neither where it lies nor how fast it comes — a second harmonic's phase at 0.8
        σ of its amplitude once read "1.14 ± 2.4 rad", a number that says nothing; and each
        relative amplitude whose σ exceeds RELATIVE_SD_UNBOUNDED. An amplitude without a σ
        (held) is not judged."""
        sd = sd or {}
        amplitudes = {a for p in self.params for a in p.shape_of}
        weak = {a: why for a in amplitudes if (why := self.amplitude_not_shown(a, values, sd))}
        out = {p.name: "; ".join(weak[a] for a in p.shape_of) for p in self.params
               if p.shape_of and all(a in weak for a in p.shape_of)}
        # a relative amplitude whose σ is over 100 %: b = 0.01 ± 0.02 says the change is small,
        # b = 0.30 ± 2.9 says nothing (a stage's drift named beside its ripple was written so)
        for a in sorted(amplitudes):
            p = next(q for q in self.params if q.name == a)
            s = sd.get(a)
            if p.unit == "1" and s is not None and math.isfinite(s) and s > RELATIVE_SD_UNBOUNDED and a in values:
                out[a] = (f"{a} = {values[a]:.3g} ± {s:.2g}: its σ exceeds the whole "
                          f"({RELATIVE_SD_UNBOUNDED:.0%}) of what it scales")
        # a scale (a drift's τ, a softening's n_c, a ripple's λ: positive, ``lo_open`` at 0) whose σ
        # exceeds it: the change is shown, not how fast it comes or how long it is (a warm-up
        # written "τ = 25.9 ± 71 s" where the decision had read 92.7)
        for p in self.params:
            x, s = values.get(p.name), sd.get(p.name)
            if (p.shape_of and p.lo == 0.0 and p.lo_open and p.name not in out and x is not None and s is not None
                    and math.isfinite(s) and s > abs(x)):
                out[p.name] = f"{p.name} = {x:.3g} ± {s:.2g}: its σ exceeds it"
        return out

    def amplitude_not_shown(self, name: str, values: Mapping[str, float], sd: Mapping[str, float]) -> str | None:
        """Why the amplitude ``name`` is not told from its neutral value, or None. A signed
        amplitude (a drift's b, a softening's h): within SHAPE_SIGMAS σ of it. A magnitude of a
        sine and cosine pair (a ripple's a with its phase φ): its two components have σ_c =
        √((σ_a² + (a·σ_φ)²)/2) each, and with none there the magnitude exceeds POLAR_SHOWN·σ_c
        in 5 % of records only (χ² with two degrees of freedom) — against σ_a alone, noise would
        pass 2 σ in 42 % (a Rayleigh magnitude's mean is 1.9 of its sd)."""
        p = next(q for q in self.params if q.name == name)
        s = sd.get(name)
        if name not in values or s is None or not math.isfinite(s):
            return None
        x = values[name]
        d = abs(x - self.neutral.get(name, 0.0))
        sp = sd.get(p.polar_with) if p.polar_with else None
        if sp is not None and math.isfinite(sp):
            sc = math.sqrt((s * s + (x * sp) ** 2) / 2.0)
            # the σ counted as measured, then the bar it misses ("within 2.45 σ" alone read as the measure)
            return (f"{name} = {x:.2g} is {_sigmas(d, sc)} from 0, within the {POLAR_SHOWN:g} σ a magnitude must pass "
                    f"(σ {sc:.2g} of its sine and cosine parts, from ± {s:.2g} and its phase's ± {sp:.2g})"
                    if d <= POLAR_SHOWN * sc else None)
        return (f"{name} = {x:.2g} ± {s:.2g} is {_sigmas(d, s)} from {self.neutral.get(name, 0.0):g}, within "
                f"{SHAPE_SIGMAS:g} σ" if d <= SHAPE_SIGMAS * s else None)

    def validate(self, values, path: str) -> dict:
        if not isinstance(values, Mapping):
            raise ParameterError(f"{path}: expected a mapping of {', '.join(self.param_names)}")
        unknown = sorted(set(values) - set(self.param_names))
        if unknown:
            raise ParameterError(f"{path}.{unknown[0]}: unknown parameter of {self.name} "
                                 f"(it has {', '.join(self.param_names)})")
        out = {}
        for p in self.params:
            if p.name not in values and p.default is not None:
                out[p.name] = float(p.default)
                continue
            if p.name not in values:
                raise ParameterError(f"{path}.{p.name}: missing ({self.name} needs {', '.join(self.param_names)})")
            out[p.name] = p.check(values[p.name], f"{path}.{p.name}")
        for a, b in self.ordered:
            if out[a] > out[b]:
                raise ParameterError(f"{path}.{a}: {out[a]:g} exceeds {b} {out[b]:g} ({self.name} needs {a} ≤ {b})")
        return out


# ---------------------------------------------------------------- the factors
def _drift(v, ctx):
    # first-order approach of a temperature to its end value: F·(1 + b·(1 − e^{−(t − t0)/τ}))
    t = ctx.signal("time", "time_drift")
    return 1.0 + v["b"] * -np.expm1(-np.maximum(t - v["t0"], 0.0) / v["tau"])


def _load(v, ctx):
    # Amontons-like dependence with a contact exponent: F ∝ (N/N0)^α (α = 1: Coulomb's law,
    # α < 1: elastic asperity contact). A negative load reading counts as no load.
    n = ctx.signal("load", "normal_load")
    return (np.maximum(n, 0.0) / v["N0"]) ** v["alpha"]


def _ripple(v, ctx):
    # a periodic profile along the position (a tooth, a ball circuit, a wave of the guide):
    # fundamental and second harmonic, as a tooth profile is seldom a sine
    # sin(θ + φ) = sin θ·cos φ + cos θ·sin φ, and the second harmonic's sin 2θ, cos 2θ from
    # the same sin θ, cos θ: only these two are evaluated along the position (and kept)
    s, c = ctx.phase_along_position(v["wavelength"], v.get("x0", 0.0), "position_ripple")
    out = 1.0 + v["a"] * (s * math.cos(v["phase"]) + c * math.sin(v["phase"]))
    if v.get("a2", 0.0):
        p2 = v.get("phase2", 0.0)
        out += v["a2"] * (2.0 * s * c * math.cos(p2) + (c * c - s * s) * math.sin(p2))
    return out


def _softening(v, ctx):
    # the contact wears in or work-hardens: κ(n) = 1 + h·(1 − e^{−n/n_c}) over the running
    # count n of significant reversals (h < 0 softens, h > 0 hardens); what counts as one is
    # the effect's own min_excursion, as wear need not follow every small back-travel
    n = ctx.reversals_above(v["min_excursion"], "cyclic_softening")
    return 1.0 + v["h"] * -np.expm1(-n / v["n_c"])


def _rate_stiffness(v, ctx):
    # the presliding stiffness as a smooth function of the log of the sliding speed,
    # κ = e^{c1·ℓ + c2·ℓ²}, ℓ = ln(max(|v|, v_floor)/v_ref): a rate-dependent (viscoelastic)
    # contact, and also what a contact whose transition depends on speed otherwise than eq. (5)
    # says looks like to the model. Quadratic in ℓ: both ends of the speed range may stiffen.
    ell = ctx.log_speed(v["v_floor"], v["v_ref"], "rate_stiffness")
    return np.exp(np.clip(v["c1"] * ell + v["c2"] * ell * ell, -RATE_STIFFNESS_LOG_MAX, RATE_STIFFNESS_LOG_MAX))


RATE_STIFFNESS_LOG_MAX = 3.0  # |ln κ| at most: a factor e³ ≈ 20 either way, the span of a stiffness factor


def _travel_stiffness(v, ctx):
    # the presliding stiffness as a smooth function of the log of the travel of the stroke before
    # (``stroke_travel``), κ = e^{c1·ℓ + c2·ℓ²}, ℓ = ln(clip(s, s_floor, s_cap)/s_ref): a contact
    # that does not keep Masing's rule, which eq. (5)'s memory does — a Dahl-like one, whose
    # stiffness after a reversal grows with the force it turned at, shows the model the branches
    # after small loops softer than those after large ones. Strokes longer than s_cap end in
    # gross sliding alike and count as s_cap (the record's first stroke too).
    ell = ctx.log_travel(v["s_floor"], v["s_cap"], v["s_ref"], v["min_excursion"], "travel_stiffness")
    return np.exp(np.clip(v["c1"] * ell + v["c2"] * ell * ell, -RATE_STIFFNESS_LOG_MAX, RATE_STIFFNESS_LOG_MAX))


def _presliding_range(v, ctx):
    # a friction effect's factor m scales eq. (3)'s F whole, the transition curve's forces
    # with it: the presliding spring stiffens with m and the range to break-away stays. Where
    # the stiffness does not follow (a lubricant's temperature changes the sliding friction, not
    # the elasticity of the asperities in contact; a load that raises friction more than the
    # contact's tangential stiffness), the range grows with m instead: the curve's abscissas
    # times m^e, a stiffness factor κ = m^(−e) (e = 0: as eq. (3) scales it, e = 1: the
    # stiffness unchanged)
    return np.maximum(ctx.signal("friction_factor", "presliding_range"), 1e-6) ** -v["e"]


def _stiffness(v, ctx):
    return v["kappa"]  # one number: ``Effect.scale`` broadcasts it along the motion


EFFECTS: dict[str, Effect] = {e.name: e for e in (
    Effect("time_drift", "friction drifts in time as a first-order approach (warm-up of the lubricant, a "
           "temperature settling with time constant τ)", "friction",
           (EffectParam("b", "1", -0.95, 20.0, "relative change of friction once settled"),
            EffectParam("tau", "time", 0.0, 1e12, "time constant of the approach", lo_open=True, shape_of=("b",)),
            EffectParam("t0", "time", -1e12, 1e12, "start of the approach")),
           ("time",), _drift, "repeat one test at fixed load and position after the machine has warmed up",
           {"b": 0.0}, ("b", "friction falling", "friction rising")),
    Effect("normal_load", "friction scales with the normal load as (N/N0)^α", "friction",
           (EffectParam("alpha", "1", 0.0, 3.0, "load exponent (1: Coulomb's law)"),
            EffectParam("N0", "load", 0.0, 1e12, "reference load at which the base model holds", lo_open=True)),
           ("load",), _load, "vary the load up and down at a fixed temperature (not on a monotone schedule)",
           {"alpha": 0.0}),
    Effect("position_ripple", "friction varies periodically with position (gear teeth, ball circulation, "
           "a wavy guide)", "friction",
           (EffectParam("a", "1", 0.0, 0.95, "relative amplitude", polar_with="phase"),
            EffectParam("wavelength", "position", 0.0, 1e12, "period along the position", lo_open=True,
                        shape_of=("a", "a2")),
            EffectParam("phase", "rad", -1e3, 1e3, "phase at x0", shape_of=("a",)),
            EffectParam("a2", "1", 0.0, 0.5, "relative amplitude of the second harmonic", default=0.0,
                        polar_with="phase2"),
            EffectParam("phase2", "rad", -1e3, 1e3, "phase of the second harmonic at x0", default=0.0,
                        shape_of=("a2",)),
            # where the phases are read: a phase at a position many wavelengths from the data
            # moves with every part in 10⁴ of λ, and its σ says nothing of how well the ripple
            # is seen there (a telescope axis 48 wavelengths from 0 read φ ± 1.8 rad, its
            # amplitude 5.6 σ); the diagnosis writes the middle of the travel
            EffectParam("x0", "position", -1e12, 1e12, "position the phases are read at", default=0.0)),
           ("position",), _ripple, "move over the same positions at different times and speeds",
           {"a": 0.0, "a2": 0.0}),
    Effect("cyclic_softening", "the presliding spring softens (h < 0) or hardens (h > 0) with the number of "
           "significant reversals, saturating", "stiffness",
           (EffectParam("h", "1", -0.95, 20.0, "relative stiffness change once saturated"),
            EffectParam("n_c", "reversals", 0.0, 1e12, "reversals to reach 63 % of the change", lo_open=True,
                        shape_of=("h",)),
            EffectParam("min_excursion", "position", 0.0, 1e12, "smallest back-travel counted as a reversal")),
           ("reversals",), _softening, "alternate presliding cycles with long rests (time) at a fixed load",
           {"h": 0.0}, ("h", "softening", "hardening")),
    Effect("rate_stiffness", "the presliding spring's stiffness varies smoothly with the sliding speed, "
           "κ = exp(c1·ℓ + c2·ℓ²) with ℓ = ln(|v|/v_ref)", "stiffness",
           (EffectParam("c1", "1", -2.0, 2.0, "slope of ln κ against ln|v|"),
            EffectParam("c2", "1", -1.0, 1.0, "curvature of ln κ against ln|v|"),
            EffectParam("v_ref", "velocity", 0.0, 1e12, "speed at which κ = 1", lo_open=True),
            EffectParam("v_floor", "velocity", 0.0, 1e12, "speeds below this count as this (rest)", lo_open=True)),
           ("velocity",), _rate_stiffness, "presliding cycles of one amplitude at several speeds, the slow ones "
           "repeated at the session's end", {"c1": 0.0, "c2": 0.0}),
    Effect("travel_stiffness", "the presliding spring's stiffness varies smoothly with the travel of the stroke "
           "before the last reversal, κ = exp(c1·ℓ + c2·ℓ²) with ℓ = ln(s/s_ref) (a contact that does not keep "
           "Masing's rule: its branches after small loops softer or stiffer than after large ones)", "stiffness",
           (EffectParam("c1", "1", -2.0, 2.0, "slope of ln κ against ln s"),
            EffectParam("c2", "1", -1.0, 1.0, "curvature of ln κ against ln s"),
            EffectParam("s_ref", "position", 0.0, 1e12, "stroke travel at which κ = 1", lo_open=True),
            EffectParam("s_floor", "position", 0.0, 1e12, "shorter strokes count as this", lo_open=True),
            EffectParam("s_cap", "position", 0.0, 1e12, "longer strokes (into gross sliding) count as this",
                        lo_open=True),
            EffectParam("min_excursion", "position", 0.0, 1e12, "smallest back-travel counted as a reversal")),
           ("position",), _travel_stiffness, "presliding cycles of several amplitudes in a shuffled order, the "
           "first ones repeated at the session's end", {"c1": 0.0, "c2": 0.0}, ordered=(("s_floor", "s_cap"),)),
    Effect("presliding_range", "the presliding range follows the friction effects' factor m as m^e (the "
           "presliding stiffness as m^(1−e)): e = 0, the spring stiffens with friction; e = 1, its stiffness "
           "stays and the range to break-away grows with friction; e < 0, the spring stiffens faster than "
           "friction rises and the range shrinks; e > 1, it softens as friction rises", "stiffness",
           (EffectParam("e", "1", -2.0, 3.0, "exponent of the presliding range in the friction effects' factor"),),
           ("friction_factor",), _presliding_range, "presliding cycles of one amplitude repeated as the friction "
           "effect moves (after warm-up, at another load)", {"e": 0.0}),
    Effect("presliding_stiffness", "the presliding spring is uniformly stiffer (κ > 1) or softer than the "
           "transition curve", "stiffness",
           (EffectParam("kappa", "1", 0.01, 100.0, "stiffness factor"),),
           (), _stiffness, "presliding cycles of several amplitudes", {"kappa": 1.0}),
)}


def format_values(name: str, values: Mapping[str, float], units: Mapping[str, str],
                  sd: Mapping[str, float] | None = None, held: Mapping[str, str] | None = None) -> str:
    """"h = -0.589 ± 0.04, n_c = 8.78 ± 1.2 reversals, …": an effect's values with their units,
    and the 1-σ of those that were estimated (``sd``; a value without one was held). A shape
    parameter whose amplitude the data do not tell from no effect (``Effect.undetermined``) is
    said to be not determined instead of given a σ; ``held``: why a value written without a σ
    has none, as a file's provenance.held says (a drift's b, 0.285 ± 3.1 in the model written,
    had been listed as a plain "b = 0.2846")."""
    eff = EFFECTS.get(name)
    unit = {p.name: p.unit_in(units) for p in eff.params} if eff is not None else {}
    sd = sd or {}
    loose = eff.undetermined(values, sd) if eff is not None else {}
    held = {k: str(v) for k, v in (held or {}).items() if k not in loose}
    return ", ".join(f"{k} = {v:.4g}" + (f" ± {sd[k]:.2g}" if k in sd and math.isfinite(sd[k]) and k not in loose else "")
                     + (f" {unit[k]}" if unit.get(k) else "")
                     + (f" (not determined: {loose[k]})" if k in loose else f" ({held[k]})" if k in held else "")
                     for k, v in values.items())


def effect_of(name) -> Effect:
    if name not in EFFECTS:
        raise ParameterError(f"unknown effect {name!r} (known: {', '.join(EFFECTS)})")
    return EFFECTS[name]


def validate_effect_entry(entry, path: str) -> dict:
    """A parameter file's effect entry ``{name, params}`` checked against its ``Effect``:
    every problem is a ParameterError naming the dotted field. Returns the cleaned entry
    (extra descriptive keys such as ``evidence`` are kept as they are)."""
    if not isinstance(entry, Mapping):
        raise ParameterError(f"{path}: expected a mapping with name and params")
    name = entry.get("name")
    if name not in EFFECTS:
        raise ParameterError(f"{path}.name: must be one of {', '.join(EFFECTS)}, got {name!r}")
    if "params" not in entry:
        raise ParameterError(f"{path}.params: missing ({name} needs {', '.join(EFFECTS[name].param_names)})")
    out = dict(entry)
    out["params"] = EFFECTS[name].validate(entry["params"], f"{path}.params")
    return out


# ---------------------------------------------------------------- along a motion
def significant_reversals(x: np.ndarray, min_excursion: float = 0.0) -> np.ndarray:
    """Running count of direction changes of the path ``x`` whose back-travel exceeds
    ``min_excursion`` (a measured position's noise or quantisation step must not count). The
    count steps up at the turning point itself, once the back-travel has confirmed it."""
    from .kernels import count_significant_reversals  # compiled: the model's import stays light

    x = np.ascontiguousarray(x, dtype=np.float64)
    if x.ndim != 1:
        raise SignalError(f"position: need a 1-D series to count reversals along, got shape {x.shape}")
    out = np.zeros(len(x))
    if len(x) >= 2:
        count_significant_reversals(x, float(min_excursion), out)
    return out


def stroke_travel(x: np.ndarray, counts: np.ndarray) -> np.ndarray:
    """For each sample of the path ``x``, the travel (max − min) of the stroke before the one it
    lies on: strokes are the samples between two steps of the running reversal count ``counts``
    (``significant_reversals``, which steps at the turning points), each ending at the turning
    point the next starts at. The stroke before sets the force the contact turned at (a stroke
    into sliding turns at break-away, a small loop near rest), so this is what a stiffness after a
    reversal may follow, and it is known when the stroke starts. Infinite on the first stroke,
    which has none before it in the record."""
    x = np.asarray(x, dtype=np.float64)
    if len(x) == 0:
        return x.copy()
    starts = np.r_[0, np.flatnonzero(np.diff(counts)) + 1]
    hi, lo = np.maximum.reduceat(x, starts), np.minimum.reduceat(x, starts)
    hi[:-1] = np.maximum(hi[:-1], x[starts[1:]])
    lo[:-1] = np.minimum(lo[:-1], x[starts[1:]])
    before = np.r_[np.inf, (hi - lo)[:-1]]
    return np.repeat(before, np.diff(np.r_[starts, len(x)]))


def context_of(time, position=None, load=None, min_excursion: float = 0.0) -> Context:
    """The context along a known motion: velocity as the backward difference of the path
    (as the displacement driver does), reversals counted above ``min_excursion``."""
    t = np.asarray(time, dtype=np.float64)
    v = None
    rev = None
    if position is not None:
        x = np.asarray(position, dtype=np.float64)
        v = np.zeros_like(x)
        v[1:] = np.diff(x) / np.diff(t)
        rev = significant_reversals(x, min_excursion)
    return Context(time=t, position=None if position is None else np.asarray(position, dtype=np.float64),
                   velocity=v, load=None if load is None else np.asarray(load, dtype=np.float64), reversals=rev,
                   min_excursion=float(min_excursion))


def _reversal_threshold(entries) -> float:
    th = [e["params"].get("min_excursion", 0.0) for e in entries if e["name"] == "cyclic_softening"]
    return float(max(th)) if th else 0.0


def _products(pairs, ctx: Context, fs, ss):
    for eff, entry in pairs:
        s = eff.scale(entry["params"], ctx)
        if eff.acts_on == "friction":
            fs = s.copy() if fs is None else fs * s
        else:
            ss = s.copy() if ss is None else ss * s
    return fs, ss


def effect_scales(effects, ctx: Context, follow: np.ndarray | None = None) -> tuple[np.ndarray | None, np.ndarray | None]:
    """(friction_scale, stiffness_scale): the product of every effect's factor, or None where
    no effect acts. An effect that follows the friction effects (``friction_factor`` in its
    ``needs``) is evaluated after them, on their product — or on ``follow``, a factor given
    (``identify.diagnose``'s stiffness candidates follow the one their alternative fitted)."""
    pairs = [(effect_of(e["name"]), e) for e in effects]
    following = [(f, e) for f, e in pairs if _follows(f)]
    fs, ss = _products([(f, e) for f, e in pairs if not _follows(f)], ctx, None, None)
    if following:
        m = follow if follow is not None else (np.ones(ctx.time.shape) if fs is None else fs)
        fs, ss = _products(following, ctx.with_friction_factor(m), fs, ss)
    return fs, ss


def _follows(eff: Effect) -> bool:
    return "friction_factor" in eff.needs


def follows_friction(entries) -> bool:
    """Whether an effect among ``entries`` follows the friction effects' factor (its value
    then changes with theirs: a cached simulation at a stiffness must be keyed by them too)."""
    return any(_follows(effect_of(e["name"])) for e in entries)


def needs_motion(effects) -> bool:
    return any(n in ("position", "velocity", "reversals") for e in effects for n in effect_of(e["name"]).needs)


DRIVES = ("displacement", "force", "closed_loop")
MOTION_PASSES = 8  # fixed-point passes for motion-dependent effects under a force or closed-loop drive


@dataclass(frozen=True)
class Signals:
    """The recorded inputs a prediction is driven by.

    ``displacement``: ``position`` is the prescribed path. ``force``: ``force`` is the applied
    force of eq. (8); ``position``, when given, is the measured motion along which
    position-dependent effects are evaluated (otherwise the motion is simulated once without
    them and they are evaluated along it). ``closed_loop``: ``x_ref`` and the gains, with
    ``force`` as an optional feedforward."""

    time: np.ndarray
    position: np.ndarray | None = None
    force: np.ndarray | None = None
    load: np.ndarray | None = None
    x_ref: np.ndarray | None = None
    kp: float = 0.0
    ki: float = 0.0
    encoder_step: float = 0.0
    ctrl_every: int = 1
    x0: float = 0.0
    v0: float = 0.0
    min_excursion: float | None = None  # reversal threshold for the context (default: the effects')


def _run(params, drive: str, sig: Signals, fs, ss, state):
    from .simulate import simulate_closed_loop, simulate_displacement, simulate_force

    kw = {}
    if fs is not None:
        kw["friction_scale"] = fs
    if ss is not None:
        kw["stiffness_scale"] = ss
    if drive == "displacement":
        return simulate_displacement(params, sig.time, sig.position, state=state, **kw)
    if drive == "force":
        return simulate_force(params, sig.time, sig.force, x0=sig.x0, v0=sig.v0, state=state, **kw)
    return simulate_closed_loop(params, sig.time, sig.x_ref, kp=sig.kp, ki=sig.ki, feedforward=sig.force,
                                encoder_step=sig.encoder_step, ctrl_every=sig.ctrl_every, x0=sig.x0, state=state, **kw)


def predict(params, drive: str, signals: Signals, *, state: np.ndarray | None = None):
    """The model ``params`` with all its effects, driven by ``signals`` (see ``Signals``).
    Returns the ``SimResult`` of ``model.simulate`` (friction, position, velocity, ...)."""
    if drive not in DRIVES:
        raise ParameterError(f"drive: must be one of {', '.join(DRIVES)}, got {drive!r}")
    need = {"displacement": "position", "force": "force", "closed_loop": "x_ref"}[drive]
    if getattr(signals, need) is None:
        raise ParameterError(f"drive {drive}: needs the {need} signal")
    effects = list(params.effects)
    if not effects:
        return _run(params, drive, signals, None, None, state)
    th = _reversal_threshold(effects) if signals.min_excursion is None else signals.min_excursion
    if drive == "displacement" or signals.position is not None or not needs_motion(effects):
        ctx = context_of(signals.time, signals.position, signals.load, th)
        fs, ss = effect_scales(effects, ctx)
        return _run(params, drive, signals, fs, ss, state)
    # the motion is the plant's output: evaluate the motion-dependent factors along the
    # motion of the previous pass (the first without them) until the motion stops changing
    # (fixed-point iteration; the factors act inside the loop of every pass)
    still = [e for e in effects if not any(n in ("position", "velocity", "reversals") for n in effect_of(e["name"]).needs)]
    ctx0 = context_of(signals.time, None, signals.load)
    fs, ss = effect_scales(still, ctx0)
    st0 = None if state is None else state.copy()
    prev = _run(params, drive, signals, fs, ss, None if st0 is None else st0.copy())
    for _ in range(MOTION_PASSES):
        ctx = context_of(signals.time, prev.position, signals.load, th)
        fs, ss = effect_scales(effects, ctx)
        cur = _run(params, drive, signals, fs, ss, None if st0 is None else st0.copy())
        span = float(np.ptp(cur.position)) or 1.0
        done = float(np.max(np.abs(cur.position - prev.position))) <= 1e-9 * span
        prev = cur
        if done:
            break
    if state is not None:
        state[:] = st0
        _run(params, drive, signals, fs, ss, state)
    return prev
