"""Markov estimator of the constant-velocity curve S(v) + σ2·v, eq. (7), per velocity sign.

Section IV-A: weighted least squares over constant-velocity levels, the weights being the
inverse variances of the measured friction at each level. We weight by the variance of each
level's *mean* (sample variance / number of samples), so that the covariance
(JᵀWJ)⁻¹ of the estimate is the one the data support.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares
from scipy.stats import chi2 as chi2_dist

from .errors import IdentificationError

NAMES = ("Fs", "Fc", "vs", "delta", "sigma2")
# a side of S(v) is fitted in its Stribeck form only from this many levels at this many distinct speeds
STRIBECK_MIN_LEVELS, STRIBECK_MIN_SPEEDS = 6, 4


# a Coulomb + viscous fit whose slope came out negative, refitted as Coulomb alone (σ2 held at 0)
COULOMB_SLOPE_HELD = "Coulomb (σ2 held at 0: a negative viscous slope)"


@dataclass
class Levels:
    """Constant-velocity levels: mean velocity, mean friction, variance of that mean; and how
    many runs of steady velocity the segmentation left out as not being points of S(v)."""

    velocity: np.ndarray
    friction: np.ndarray
    variance: np.ndarray
    count: np.ndarray
    opposing: int = 0  # runs whose friction opposes their velocity (``segment.constant_velocity_levels``)
    opposing_strokes: int = 0  # … of them, over a tenth of the travel or more (no presliding spring's give-back)
    creep: int = 0  # runs of presliding creep (``segment.sliding_only``)
    trend_alone: int = 0  # trending runs on a side with under 3 settled levels and no sweep of their own
    # runs whose friction trended with their speed, under TREND_NOT_SPEED times its relative change
    # (``segment.constant_velocity_levels``): a creep, a stroke of a sinusoidal force
    speed_trend: int = 0
    time: np.ndarray | None = None  # each level's mean time (one recording's clock), where known
    # per level: its run's friction trended (``segment.constant_velocity_levels``), and its
    # variance holds that trend; None where none did
    trended: np.ndarray | None = None

    def kept(self, keep: np.ndarray, **kw) -> "Levels":
        """The levels ``keep`` selects, with their times and marks; ``kw`` sets the counts of runs left out."""
        return Levels(*(a[keep] for a in (self.velocity, self.friction, self.variance, self.count)),
                      time=None if self.time is None else self.time[keep],
                      trended=None if self.trended is None or not self.trended[keep].any() else self.trended[keep],
                      **{"opposing": self.opposing, "opposing_strokes": self.opposing_strokes, "creep": self.creep,
                         "trend_alone": self.trend_alone, "speed_trend": self.speed_trend, **kw})

    @property
    def is_trended(self) -> np.ndarray:
        return np.zeros(len(self.velocity), bool) if self.trended is None else self.trended

    def steady(self) -> "Levels":
        """The levels whose friction settled: the steady speeds that end presliding branches,
        count a sweep's speeds and scale σ1 (a trended run is a point of S(v) alone)."""
        return self if self.trended is None else self.kept(~self.trended)

    def slowest_steady_speed(self) -> float:
        """|v| of the slowest settled level (``steady``): where presliding ends and σ1's data
        scale is taken; inf without one."""
        v = self.steady().velocity
        return float(np.min(np.abs(v))) if len(v) else np.inf

    @classmethod
    def joined(cls, parts: list) -> "Levels":
        """Levels of several sets together (times only where every part has them), their
        runs left out summed."""
        arrays = (np.concatenate([getattr(p, k) for p in parts]) for k in ("velocity", "friction", "variance", "count"))
        marks = [p.is_trended for p in parts]
        return cls(*arrays, opposing=sum(p.opposing for p in parts), creep=sum(p.creep for p in parts),
                   opposing_strokes=sum(p.opposing_strokes for p in parts),
                   trend_alone=sum(p.trend_alone for p in parts), speed_trend=sum(p.speed_trend for p in parts),
                   time=None if any(p.time is None for p in parts) else np.concatenate([p.time for p in parts]),
                   trended=np.concatenate(marks) if any(m.any() for m in marks) else None)


@dataclass
class SideFit:
    """Estimate for one velocity sign: values, 1-σ, correlation matrix, weighted cost."""

    values: dict
    stderr: dict
    correlation: np.ndarray
    chi2: float
    dof: int
    names: tuple = NAMES
    notes: list = field(default_factory=list)
    # the part of each σ that is not the levels' noise (``with_delta_spread``: how far a value
    # moves with δ held elsewhere in its range), added in quadrature; {} where there is none
    spread: dict = field(default_factory=dict)


def stribeck_plus_viscous(theta, v):
    Fs, Fc, vs, delta, sigma2 = theta
    return Fc + (Fs - Fc) * np.exp(-np.abs(v / vs) ** delta) + sigma2 * v


def _jacobian(theta, v):
    """d(S(v) + σ2·v)/dθ for θ = (Fs, Fc, vs, delta, sigma2)."""
    Fs, Fc, vs, delta, sigma2 = theta
    a = np.abs(v / vs)
    ad = a**delta
    e = np.exp(-ad)
    la = np.log(np.maximum(a, 1e-300))
    return np.column_stack([e, 1.0 - e, (Fs - Fc) * e * ad * delta / vs, -(Fs - Fc) * e * ad * la, v])


def fit_side(levels: Levels, sign: int, start: dict | None = None, hold: dict | None = None) -> SideFit:
    """Weighted least squares for one sign (scipy ``least_squares``, trust-region reflective).

    ``hold`` maps parameter names to fixed values; the rest are estimated (at least one
    degree of freedom is needed). Without ``start`` it tries nine starting points (S(v) has
    local minima in vs and δ); with one, only that."""
    hold = dict(hold or {})
    free = [i for i, k in enumerate(NAMES) if k not in hold]
    m = levels.velocity * sign > 0
    v, F, var = levels.velocity[m], levels.friction[m], levels.variance[m]
    word = "positive" if sign > 0 else "negative"
    if len(v) < len(free) + 1:
        raise IdentificationError(f"Markov estimator: only {len(v)} constant-velocity level(s) with {word} velocity; "
                                  f"need at least {len(free) + 1}")
    w = 1.0 / np.sqrt(np.maximum(var, 1e-18 * np.max(np.abs(F)) ** 2))
    order = np.argsort(np.abs(v))
    v, F, w = v[order], F[order], w[order]
    a = np.abs(v)
    # starting point: σ2 from the fastest levels, F_c from the middle, F_s from the slowest
    hi = a >= np.quantile(a, 0.7)
    with warnings.catch_warnings():
        # levels a few parts in 10⁴ apart (repeated visits of one speed) make polyfit warn "poorly
        # conditioned"; its truncated solution is a start, and a sound one, so the warning is not
        # the user's (the exact slope about the means starts elsewhere and moved later refits)
        warnings.simplefilter("ignore", getattr(np, "exceptions", np).RankWarning)
        s2 = max(0.0, np.polyfit(v[hi], F[hi], 1)[0]) if hi.sum() >= 2 and np.ptp(v[hi]) > 0 else 0.0

    def from_slope(s2):
        """F_s and F_c to start from beside the slope ``s2``."""
        Fc0 = np.min(np.abs(F - s2 * v)) * sign
        Fs0 = (F[0] - s2 * v[0])
        return (Fc0 * 1.1 if abs(Fs0) <= abs(Fc0) else Fs0), Fc0

    Fs0, Fc0 = from_slope(s2)
    # Table I convention: negative-side Fs, Fc, vs are negative
    big = np.inf
    tiny = 1e-300
    if sign > 0:
        lo_b = np.array([tiny, tiny, tiny, 0.05, 0.0])
        hi_b = np.array([big, big, big, 5.0, big])
    else:
        lo_b = np.array([-big, -big, -big, 0.05, 0.0])
        hi_b = np.array([-tiny, -tiny, -tiny, 5.0, big])
    full0 = np.array([hold.get(k, np.nan) for k in NAMES])
    # the optimiser works on the parameters in units of the side's own force and speed (Fs, Fc
    # in max|F|, vs in max|v|, σ2 in their ratio): its stopping test weighs a step against |θ|,
    # and in the file's units the same levels written in N or mN, m/s or mm/s stopped elsewhere
    f_unit, v_unit = float(np.max(np.abs(F))) or 1.0, float(np.max(a)) or 1.0
    unit = np.array([f_unit, f_unit, v_unit, 1.0, f_unit / v_unit])[free]

    def expand(theta):
        th = full0.copy()
        th[free] = theta * unit
        return th

    def resid(theta):
        return w * (F - stribeck_plus_viscous(expand(theta), v))

    def jac(theta):
        return -w[:, None] * _jacobian(expand(theta), v)[:, free] * unit

    lo_f, hi_f = lo_b[free] / unit, hi_b[free] / unit
    lo_f[lo_b[free] == tiny], hi_f[hi_b[free] == -tiny] = tiny, -tiny  # (a sign bound stays one in any unit)
    fin_lo, fin_hi = np.isfinite(lo_f), np.isfinite(hi_f)
    lo_pad, hi_pad = lo_f.copy(), hi_f.copy()
    lo_pad[fin_lo] += np.abs(lo_f[fin_lo]) * 1e-9 + 1e-300
    hi_pad[fin_hi] -= np.abs(hi_f[fin_hi]) * 1e-9 + 1e-300
    pad = lambda x0: np.clip(x0, lo_pad, hi_pad)  # noqa: E731
    if start is not None:
        starts = [pad(np.array([start[k] for k in NAMES])[free] / unit)]
    else:
        starts = [pad(np.array([Fs0, Fc0, sign * vs0, d0, s2])[free] / unit)
                  for vs0 in np.quantile(a, [0.1, 0.3, 0.6]) for d0 in (0.5, 1.0, 2.0)]
        uniq = []
        for x0 in starts:
            if not any(np.allclose(x0, u) for u in uniq):
                uniq.append(x0)
        starts = uniq
    best = None
    for x0 in starts:
        r = least_squares(resid, x0, jac=jac, bounds=(lo_f, hi_f), method="trf", x_scale="jac", max_nfev=300)
        if best is None or r.cost < best.cost:
            best = r
    s2_speeds = slope_start(v, F)
    if start is None and not np.isclose(s2_speeds, s2):
        # nine more starts from the slope over the distinct speeds (``slope_start``), taken only
        # where they end clearly lower: where the slope over the levels came from repeated
        # visits of one speed, every start above could run off (one side of a tribometer made
        # apart: F_s 1.8·10⁵ N, χ² 4.5·10⁶ where the generator's values leave 21); elsewhere the
        # fit stays the one those starts gave, to the bit (the refinement and the diagnosis
        # downstream move with its last digits)
        Fs1, Fc1 = from_slope(s2_speeds)
        for vs0 in np.quantile(a, [0.1, 0.3, 0.6]):
            for d0 in (0.5, 1.0, 2.0):
                x0 = pad(np.array([Fs1, Fc1, sign * vs0, d0, s2_speeds])[free] / unit)
                r = least_squares(resid, x0, jac=jac, bounds=(lo_f, hi_f), method="trf", x_scale="jac", max_nfev=300)
                if r.cost < best.cost * (1.0 - CLEARLY_LOWER):
                    best = r
    J = best.jac / unit  # d(residual)/d(parameter in the file's units)
    notes = []
    sd_full = np.zeros(5)
    cov = None
    try:
        cov = np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        notes.append("the information matrix is singular: some parameters are not identifiable from these levels")
    corr = np.eye(5)
    if cov is not None:
        d = np.diag(cov)
        sd_full[free] = np.sqrt(np.abs(d))
        neg = [NAMES[free[i]] for i in range(len(free)) if d[i] < 0]
        if neg:
            notes.append(f"negative variance for {', '.join(neg)}: not identifiable from these levels")
        s = np.where(sd_full[free] > 0, sd_full[free], 1)
        corr[np.ix_(free, free)] = cov / np.outer(s, s)
    else:
        sd_full[free] = np.inf
    x = expand(best.x)
    for i in free:
        if np.any(np.isclose(x[i], [lo_b[i], hi_b[i]])):
            notes.append(f"{NAMES[i]} is at its bound: its error bar is not meaningful")
    return SideFit(
        values=dict(zip(NAMES, map(float, x))),
        stderr=dict(zip(NAMES, map(float, sd_full))),
        correlation=corr,
        chi2=float(2 * best.cost),
        dof=int(len(v) - len(free)),
        notes=notes,
    )


@dataclass
class SideDecision:
    """The fit of one side with what was held and why."""

    fit: SideFit | None
    held: dict  # name -> reason
    model: str  # "Stribeck + viscous", "Stribeck + viscous (δ held)" (or "(δ from the … side)"), "Stribeck (σ2 held at 0)", "Coulomb + viscous", COULOMB_SLOPE_HELD, "Coulomb", "held"


def _trouble(fit: SideFit, names) -> list:
    """Names whose estimate is not informative: σ above half the value, or a bound hit."""
    bad = []
    for k in names:
        val, sd = fit.values[k], fit.stderr[k]
        if not np.isfinite(sd) or sd > 0.5 * abs(val) or any(k in m and ("bound" in m or "negative" in m) for m in fit.notes):
            bad.append(k)
    return bad


DELTA_RANGE = (0.5, 2.0)  # δ of eq. (7) as contacts show it (Table I: 0.5 and 0.9; a Gaussian Stribeck curve: 2)


def with_delta_spread(fit: SideFit, levels: Levels, sign: int, delta_range: tuple = DELTA_RANGE) -> SideFit:
    """A fit with δ held, its σ widened by how far each estimate moves when δ is held
    anywhere in ``delta_range`` (default ``DELTA_RANGE``) instead (half the spread, in
    quadrature): δ is held because the levels do not determine it, so an error bar conditional
    on the one value chosen would claim what the data do not say. (On an independent robot
    joint whose slow holds stick and slip, F_s came out 13.1 ± 0.33 with δ held at 1 for a
    contact's 9.98.)"""
    others = [fit_side(levels, sign, hold={"delta": d}) for d in delta_range]
    stderr, spread = dict(fit.stderr), {}
    for k in ("Fs", "Fc", "vs", "sigma2"):
        vals = [fit.values[k]] + [f.values[k] for f in others]
        spread[k] = 0.5 * (max(vals) - min(vals))
        stderr[k] = float(np.hypot(fit.stderr[k], spread[k]))
    notes = fit.notes + [f"σ of Fs, Fc, vs and σ2 include how far they move with δ held anywhere in "
                         f"{delta_range[0]:.3g}–{delta_range[1]:.3g} (δ is not determined by the levels)"]
    return SideFit(fit.values, stderr, fit.correlation, fit.chi2, fit.dof, fit.names, notes, spread)


CLEARLY_LOWER = 1e-6  # a start's cost must end this fraction under the best so far to replace it (``fit_side``)


def slope_start(v: np.ndarray, F: np.ndarray) -> float:
    """σ2 to start the Stribeck fit from too: the slope of F over the fastest 30 % of the distinct
    speeds (at least two), each speed's levels averaged (within 10 %, as ``distinct_speeds``
    counts them), 0 where the side shows fewer than two or the slope is negative. Over the
    levels themselves, a tribometer whose fastest 30 % were six visits of one speed, 0.02 m/s a
    few parts in 10⁴ apart, took a slope of its noise, and every start of one side ran off
    (F_s 1.8·10⁵ N, χ² 4.5·10⁶ where the generator's values leave 21)."""
    a = np.abs(v)
    order = np.argsort(a)
    a, v, F = a[order], v[order], F[order]
    if len(a) < 2:
        return 0.0
    groups = np.split(np.arange(len(a)), np.flatnonzero(np.diff(np.log(a)) > np.log(1.1)) + 1)
    if len(groups) < 2:
        return 0.0
    gv = np.array([v[g].mean() for g in groups])
    gF = np.array([F[g].mean() for g in groups])
    top = max(2, int(math.ceil(0.3 * len(groups))))
    return max(0.0, float(np.polyfit(gv[-top:], gF[-top:], 1)[0]))


def distinct_speeds(speed: np.ndarray) -> int:
    """How many distinct speeds the levels hold: levels repeated at one commanded speed (within
    10 %) count once."""
    if not len(speed):
        return 0
    return 1 + int(np.sum(np.diff(np.sort(np.log(np.abs(speed)))) > np.log(1.1)))


def fit_side_honest(levels: Levels, sign: int, *, delta_hold: float = 1.0) -> SideDecision:
    """Fit what the levels of one side determine, hold the rest with a stated reason.

    ≥ 6 levels, two of them below the fitted Stribeck velocity: the full eq. (7) + σ2·v; if σ2
    alone is not determined, it is held at 0 and eq. (7) refitted (kept where that fits the
    levels); if δ
    is not determined, δ is held at ``delta_hold`` and the rest refitted; if vs, Fs still are
    not, or fewer levels, or none below vs: Coulomb + viscous (Fs = Fc, vs and δ held);
    one level: Coulomb only (σ2 held at 0); none: the whole side is held."""
    m = levels.velocity * sign > 0
    k = int(m.sum())
    a = np.abs(levels.velocity[m])
    held = {}
    if k == 0:
        word = "positive" if sign > 0 else "negative"
        return SideDecision(None, {n: f"no {word}-velocity levels" for n in NAMES}, "held")
    speeds = distinct_speeds(a)
    if k >= STRIBECK_MIN_LEVELS and speeds >= STRIBECK_MIN_SPEEDS:
        fit = fit_side(levels, sign)
        below = int(np.sum(a < abs(fit.values["vs"])))
        bad = _trouble(fit, NAMES)
        if below >= 2 and not bad:
            return SideDecision(fit, {}, "Stribeck + viscous")
        if below >= 2 and bad == ["sigma2"]:
            # the levels show the Stribeck dip, but not a viscous slope beside it: σ2·v at the
            # fastest level within the levels' noise (a stage made apart with a 12 % ripple along
            # its travel: σ2 3 N·s/m is 6 mN at 2 mm/s beside σ of 4–5 mN). σ2 is held at 0 and
            # the dip kept — Coulomb + viscous would take F_c up to the slow levels (0.141 N for
            # 0.12, F_s held at it) and lose the dip the levels show
            fit0 = fit_side(levels, sign, hold={"sigma2": 0.0})
            # (kept only where that form fits the levels: a pin-on-disc running in along its
            # sliding distance had levels that no S(v) follows, χ² 4.3·10⁵ for 10, and its dip
            # was the run-in's)
            if (not _trouble(fit0, ("Fs", "Fc", "vs", "delta")) and int(np.sum(a < abs(fit0.values["vs"]))) >= 2
                    and not misfits(fit0)):
                return SideDecision(fit0, {"sigma2": (f"not determined by the levels (σ2 = {fit.values['sigma2']:.3g} ± "
                                                      f"{fit.stderr['sigma2']:.2g} beside the Stribeck curve): held at 0")},
                                    "Stribeck (σ2 held at 0)")
        if below >= 2 and bad:
            fit2 = with_delta_spread(fit_side(levels, sign, hold={"delta": delta_hold}), levels, sign)
            bad2 = _trouble(fit2, ("Fs", "Fc", "vs", "sigma2"))
            held = {"delta": (f"not determined by the levels (σ > half the value); held at {delta_hold:g}" if bad == ["delta"]
                              else f"held at {delta_hold:g}: with δ free, {', '.join(bad)} not determined by the levels "
                                   f"(σ > half the value, a bound or a negative variance)")}
            # with δ free beside more than δ undetermined, the fit may have slid into a corner
            # where δ, v_s and F_c trade off along the levels' scatter (a joint made apart with a
            # ripple along its travel and 3 % of its samples lost: δ 0.26, v_s 3.9 rad/s past
            # every level, F_c at its bound 0); with δ held the rise the levels show is still a
            # Stribeck curve's if at least two levels lie below its v_s (that side: F_c 0.816 ±
            # 0.005, χ² 55 for 11 levels, where Coulomb + viscous left 1,890)
            rise = bad == ["delta"] or int(np.sum(a < abs(fit2.values["vs"]))) >= 2
            if rise and not bad2:
                return SideDecision(fit2, held, "Stribeck + viscous (δ held)")
            if rise and set(bad2) <= {"Fs", "vs"}:
                # the levels show a Stribeck rise (δ alone was undetermined) but not its height
                # and width once δ may be anything in its range: those are held where the fit
                # with δ held put them — the curve still passes through the levels, where
                # Coulomb + viscous would bend F_c and σ2 to reach the slowest ones
                for name in bad2:
                    held[name] = (f"not determined by the levels (σ {fit2.stderr[name]:.2g} with δ anywhere in "
                                  f"{DELTA_RANGE[0]:g}–{DELTA_RANGE[1]:g}): held at the fit's value with δ = {delta_hold:g}")
                return SideDecision(fit2, held, f"Stribeck + viscous (δ, {', '.join(bad2)} held)")
        if below >= 2 and bad == ["delta"]:
            # δ alone was undetermined; what sends the side to Coulomb + viscous is what its
            # spread then leaves undetermined besides F_s and v_s (F_c or σ2)
            why = (f"δ not determined by the levels, and with δ anywhere in {DELTA_RANGE[0]:g}–{DELTA_RANGE[1]:g} "
                   f"neither is {', '.join(n for n in bad2 if n not in ('Fs', 'vs'))} (σ > half the value)")
        else:
            # the v_s the count is against (the Stribeck fit's, which lies below every level when
            # the levels show no dip the curve can follow, e.g. friction that drifted between them)
            vs_fit = abs(fit.values['vs'])
            why = ((f"the Stribeck fit put v_s = {vs_fit:.3g} below every level (the slowest at {np.min(a):.3g}): no "
                    f"level shows the drop from F_s to F_c; levels slower than v_s would" if below == 0 else
                    f"only {below} level below the Stribeck velocity v_s = {vs_fit:.3g} the Stribeck fit put (levels "
                    f"from {np.min(a):.3g}): one point does not show the drop from F_s to F_c") if below < 2
                   else f"the Stribeck fit of these levels left {', '.join(bad)} undetermined (σ > half the value, a bound "
                        f"or a negative variance), so Coulomb + viscous is fitted instead")
    else:
        why = (f"only {speeds} distinct speed(s) in {k} level(s) on this side; the Stribeck curve needs at least "
               f"{STRIBECK_MIN_LEVELS} levels at {STRIBECK_MIN_SPEEDS} or more speeds")
    s2_ok = speeds >= 2 and np.ptp(a) > 0.2 * np.max(a)
    vs_hold = sign * float(np.min(a))
    if s2_ok:
        fit = _coulomb_viscous(levels, sign, viscous=True)
        if _trouble(fit, ("Fc",)) or fit.values["Fc"] * sign <= 0:
            # a Coulomb level not told from 0 (or of the other side's sign) beside a slope through
            # the levels: friction proportional to the speed, which a dry contact shows while it
            # creeps towards sliding, not once it slides (a Dahl contact under force ramps to
            # 0.7 F_s read F_c = 3·10⁻¹⁹ ± 1.5 N and σ2 = 5.8·10⁵ N·s/m); the side is held
            why = (f"the levels ({k}, |v| {np.min(a):.3g}–{np.max(a):.3g}) give a Coulomb level not told from 0 "
                   f"(F_c = {fit.values['Fc']:.3g} ± {fit.stderr['Fc']:.2g}, σ2 = {fit.values['sigma2']:.3g}): "
                   f"friction rising in proportion to the speed, as a contact creeping towards sliding, not sliding")
            return SideDecision(None, {n: why for n in NAMES}, "held")
        held = {"Fs": f"{why}: held at Fc (no Stribeck effect)", "vs": f"{why}: held at the slowest level's speed",
                "delta": f"{why}: held at {delta_hold:g}"}
        fit.values["vs"], fit.values["delta"] = vs_hold, delta_hold
        if any("sigma2 came out negative" in m for m in fit.notes):
            held["sigma2"] = "the levels give a negative viscous slope (not identifiable): held at 0"
            # the form fitted is then Coulomb alone (one parameter: the χ²'s degrees of freedom)
            return SideDecision(fit, held, COULOMB_SLOPE_HELD)
        return SideDecision(fit, held, "Coulomb + viscous")
    fit = _coulomb_viscous(levels, sign, viscous=False)
    fit.values["vs"], fit.values["delta"] = vs_hold, delta_hold
    fit.notes.append(f"Fc is the sliding friction measured at |v| = {abs(vs_hold):.3g} only (S(v) + σ2·v there); it equals "
                     f"the Coulomb friction only if that speed is well above the Stribeck velocity and σ2·v is small")
    held = {"Fs": f"{why}: held at Fc", "vs": f"{why}: held at the slowest level's speed",
            "delta": f"{why}: held at {delta_hold:g}", "sigma2": f"{why}; the levels do not span enough speeds: held at 0"}
    return SideDecision(fit, held, "Coulomb")


def fit_sides_honest(levels: Levels) -> dict:
    """``fit_side_honest`` on both sides ({"positive": SideDecision, "negative": …}), where a
    side one level short of the Stribeck form's STRIBECK_MIN_LEVELS (at STRIBECK_MIN_SPEEDS or
    more speeds) takes δ from the other side, where that side determined it: with δ held, eq.
    (7) + σ2·v has four parameters, which five levels over-determine. The shape of the Stribeck
    dip is the contact's, so it is held at the other side's value, and the σ of the rest are
    widened by how far they move with δ anywhere within that value's ±σ
    (``with_delta_spread``). Kept only where the fit determines F_s, F_c, v_s and σ2 and two
    levels lie below v_s, as ``fit_side_honest`` asks of its own δ-held fit; else that side's
    own decision stands. (A tendon-driven joint made apart, swept both ways, showed a slow
    sine's tops as two more positive levels: the negative side, five levels with a clear dip,
    went to Coulomb + viscous with χ² 5,190 for 4 degrees of freedom and F_c 9.85 mN·m for
    8.6, where δ from the positive side fits them with χ² 0.19.) So does a side of six levels or more
    that went to Coulomb + viscous because its own Stribeck fit put fewer than two of them below
    its v_s, where Coulomb + viscous misfits them (χ² beyond MISFIT_P) and δ from the other side
    fits them better (a pitch bearing made apart, a Gaussian Stribeck curve swept both ways at the
    same speeds: the negative side's slowest two levels at 0.40 and 0.80 v_s, its own fit's v_s
    between them, Coulomb + viscous left χ² 5.98·10⁴ for 5 degrees of freedom)."""
    out = {side: fit_side_honest(levels, sign) for side, sign in (("positive", 1), ("negative", -1))}
    for side, sign in (("positive", 1), ("negative", -1)):
        other = out["negative" if sign > 0 else "positive"]
        m = levels.velocity * sign > 0
        a = np.abs(levels.velocity[m])
        if out[side].model.startswith("Stribeck") or other.model != "Stribeck + viscous" \
                or distinct_speeds(a) < STRIBECK_MIN_SPEEDS:
            continue
        short = len(a) == STRIBECK_MIN_LEVELS - 1
        misfit = (out[side].model in ("Coulomb + viscous", COULOMB_SLOPE_HELD) and len(a) >= STRIBECK_MIN_LEVELS
                  and misfits(out[side].fit))
        if not (short or misfit):
            continue
        d, sd = other.fit.values["delta"], other.fit.stderr["delta"]
        fit = with_delta_spread(fit_side(levels, sign, hold={"delta": d}), levels, sign,
                                (max(d - sd, 1e-3), d + sd))
        if _trouble(fit, ("Fs", "Fc", "vs", "sigma2")) or int(np.sum(a < abs(fit.values["vs"]))) < 2:
            continue
        if misfit and fit.chi2 >= out[side].fit.chi2:
            continue
        word = "negative" if sign > 0 else "positive"
        form = "Coulomb alone" if out[side].model == COULOMB_SLOPE_HELD else "Coulomb + viscous"
        said = (f"{len(a)} levels on this side do not determine it beside F_s, F_c, v_s and σ2" if short else
                f"this side's own Stribeck fit put fewer than two of its {len(a)} levels below its v_s, and {form} "
                f"misfits them (χ² {out[side].fit.chi2:.3g} for {out[side].fit.dof} degrees of freedom, "
                f"{fit.chi2:.3g} with this δ)")
        out[side] = SideDecision(fit, {"delta": (f"{said}: held at the {word} side's {d:.3g} ± {sd:.2g}, identified there "
                                                 f"(the σ of the rest include that ±σ)")},
                                 f"Stribeck + viscous (δ from the {word} side)")
    return out


MISFIT_P = 1e-3  # S(v)'s χ² beyond this tail probability: the form does not fit its levels


def misfits(fit) -> bool:
    """Whether a fit (of S(v)'s side to its levels, or of the transition curve to its branches:
    anything with ``chi2`` and ``dof``) misfits its data: χ² beyond the MISFIT_P tail for its
    degrees of freedom, the data showing what the form does not follow."""
    return fit.dof > 0 and chi2_dist.sf(fit.chi2, fit.dof) < MISFIT_P


def misfit_scale(fit) -> float:
    """The factor a fit's σ are widened by where its form misfits its data (``misfits``):
    √(χ²/dof), as lmfit's ``scale_covar`` does, so that an error bar covers what the form leaves
    unexplained as well as the noise; 1 where the form fits (there χ²/dof scatters about 1 and
    the σ of the noise are the right ones). A tribometer made apart, its contact five Dahl
    elements, had a side read F_c 0.5950 ± 0.00019 N for 0.6 (χ² 6,955 for 13): ± 0.0045 widened."""
    return math.sqrt(fit.chi2 / fit.dof) if misfits(fit) else 1.0


def widened_stderr(fit) -> dict:
    """A side's σ as written: the levels' noise part widened by ``misfit_scale``, the spread
    part (``SideFit.spread``, not noise) added as it is."""
    scale = misfit_scale(fit)
    out = {}
    for k, sd in fit.stderr.items():
        sp = fit.spread.get(k, 0.0)
        noise = math.sqrt(max(sd * sd - sp * sp, 0.0))
        out[k] = math.hypot(noise * scale, sp) if scale > 1.0 else sd
    return out


def _coulomb_viscous(levels: Levels, sign: int, viscous: bool) -> SideFit:
    """Weighted linear least squares F = Fc + σ2·v (or F = Fc), Fs = Fc."""
    m = levels.velocity * sign > 0
    v, F, var = levels.velocity[m], levels.friction[m], levels.variance[m]
    W = 1.0 / np.maximum(var, 1e-30 * np.max(F * F))
    A = np.column_stack([np.ones_like(v), v]) if viscous else np.ones((len(v), 1))
    AtW = A.T * W
    cov = np.linalg.inv(AtW @ A)
    beta = cov @ (AtW @ F)
    r = F - A @ beta
    chi2 = float(np.sum(W * r * r))
    Fc = float(beta[0])
    s2 = float(beta[1]) if viscous else 0.0
    sd_fc = float(np.sqrt(cov[0, 0]))
    values = {"Fs": Fc, "Fc": Fc, "vs": sign * 1.0, "delta": 1.0, "sigma2": max(s2, 0.0)}
    stderr = {"Fs": 0.0, "Fc": sd_fc, "vs": 0.0, "delta": 0.0, "sigma2": float(np.sqrt(cov[1, 1])) if viscous else 0.0}
    if viscous and s2 < 0:
        fit = _coulomb_viscous(levels, sign, viscous=False)  # Fc refitted with σ2 = 0
        fit.notes.append("sigma2 came out negative; held at 0")
        return fit
    return SideFit(values, stderr, np.eye(5), chi2, int(len(v) - A.shape[1]), notes=[])


def fit_stribeck(levels: Levels, start=None) -> dict:
    """Both signs: {'positive': SideFit, 'negative': SideFit}; ``start`` optionally a
    ``model.Stribeck`` to start from (one start instead of nine)."""
    out = {}
    for side, sign in (("positive", 1), ("negative", -1)):
        st = None if start is None else {k: getattr(getattr(start, side), k) for k in NAMES}
        out[side] = fit_side(levels, sign, st)
    return out
