"""The headless fit: recordings in, a complete parameter set with uncertainties out.

Connects the parts: ``segment`` finds constant-velocity levels and presliding branches,
``markov`` fits S(v) per sign, ``mle`` fits the transition curve; whatever the data cannot
determine keeps the default (the paper's value) and the report says so.
"""

from __future__ import annotations

import datetime as _dt
from dataclasses import dataclass, field

import numpy as np

from ..model import FrictionParams, Stribeck, StribeckSide, TransitionCurve, default_params

from .data import Recording
from .markov import NAMES, Levels, fit_stribeck
from .mle import PreslidingData, fit_transition_curve
from .segment import constant_velocity_levels, detect_noise, presliding_branches
from .errors import IdentificationError

KNOT_FORCE_FRACTIONS = (0.2, 0.45, 0.7, 1.0)


def default_knots(datasets) -> np.ndarray:
    """Four segments, like Table II: abscissas where the longest branch of the least noisy
    data set has reached 20, 45, 70 and 100 % of its force change (every segment holds data)."""
    best = min(datasets, key=lambda d: getattr(d.noise, "sigma", None) or d.noise.step)
    br = max(best.branches, key=lambda b: b.force[-1])
    x = np.maximum.accumulate(br.displacement - br.displacement[0])
    z = np.interp(np.array(KNOT_FORCE_FRACTIONS) * br.force[-1], br.force, x)
    z = np.maximum.accumulate(np.maximum(z, 1e-12)) * (1.0 + 1e-9 * np.arange(len(z)))
    return np.concatenate([[0.0], z])


@dataclass
class FitResult:
    params: FrictionParams
    stribeck_fit: dict | None = None
    transition_fit: object | None = None
    levels: Levels | None = None
    n_branches: int = 0
    notes: list = field(default_factory=list)
    datasets: list = field(default_factory=list)

    def report(self) -> str:
        return fit_report(self)


def _merge_levels(parts: list[Levels]) -> Levels:
    return Levels(*(np.concatenate([getattr(p, k) for p in parts]) for k in ("velocity", "friction", "variance", "count")))


def fit_recordings(recordings: list[Recording], *, base: FrictionParams | None = None, knots=None,
                   n: float = 7.0, fit_n: bool = False, progress=None) -> FitResult:
    """Fit S(v) (Markov) and F_d (maximum likelihood) from one or more recordings."""
    say = progress or (lambda frac, msg: None)
    p = base or default_params()
    notes = []
    say(0.05, "finding constant-velocity levels")
    levels = _merge_levels([constant_velocity_levels(r) for r in recordings if r.force is not None or r.friction is not None])
    stribeck_fit = None
    if np.sum(levels.velocity > 0) >= 6 and np.sum(levels.velocity < 0) >= 6:
        say(0.2, f"Markov estimator on {len(levels.velocity)} levels")
        stribeck_fit = fit_stribeck(levels)
        sides = {k: StribeckSide(**fit.values) for k, fit in stribeck_fit.items()}
        p = p.replace(stribeck=Stribeck(**sides))
    else:
        notes.append(f"S(v) not fitted: {int(np.sum(levels.velocity > 0))} positive and "
                     f"{int(np.sum(levels.velocity < 0))} negative constant-velocity levels found, need 6 of each; "
                     f"kept the parameter file's values")
    say(0.4, "finding presliding branches")
    datasets = []
    for r in recordings:
        if r.force is None or r.position is None:
            continue
        br = presliding_branches(r, p.stribeck.positive.Fs, p.stribeck.negative.Fs)
        if br:
            # the noise of the position signal where it matters: on the presliding branches
            datasets.append(PreslidingData(br, detect_noise([b.displacement for b in br]), name=r.source))
    n_br = sum(len(d.branches) for d in datasets)
    tfit = None
    if n_br:
        if knots is None:
            knots = default_knots(datasets)
        say(0.5, f"maximum-likelihood estimator on {n_br} branches")
        tfit = fit_transition_curve(datasets, knots, n=n, fit_n=fit_n)
        p = p.replace(transition_curve=TransitionCurve(kind="piecewise_linear", z=tuple(map(float, tfit.z)),
                                                      F=tuple(map(float, tfit.F))), n=float(tfit.n))
        notes.extend(tfit.notes)
    else:
        notes.append("transition curve not fitted: no presliding force ramps found; kept the parameter file's curve")
    if stribeck_fit is None and tfit is None:
        raise IdentificationError("nothing to fit: the data hold neither constant-velocity levels in both directions "
                         "nor presliding force ramps")
    unc = {}
    if stribeck_fit:
        for side, fit in stribeck_fit.items():
            for k in NAMES:
                unc[f"stribeck.{side}.{k}"] = fit.stderr[k]
            notes.extend(f"{side}: {m}" for m in fit.notes)
    if tfit is not None:
        for i in range(1, len(tfit.F)):
            unc[f"transition_curve.F.{i}"] = float(tfit.stderr[i])
        if tfit.n_stderr is not None:
            unc["n"] = tfit.n_stderr
    cost = {}
    if stribeck_fit:
        cost["markov_chi2"] = {k: v.chi2 for k, v in stribeck_fit.items()}
        cost["markov_dof"] = {k: v.dof for k, v in stribeck_fit.items()}
    if tfit is not None:
        cost["ml_negative_log_likelihood"] = tfit.nll
    prov = {
        "data": [r.source for r in recordings],
        "estimator": "Markov (weighted least squares) for S(v); maximum likelihood for the transition curve",
        "noise_models": {d.name: repr(d.noise) for d in datasets},
        "cost": cost,
        "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    say(1.0, "done")
    p = p.replace(uncertainty=unc, provenance=prov).validate()
    return FitResult(p, stribeck_fit, tfit, levels, n_br, notes, datasets)


def fit_report(res: FitResult) -> str:
    """Table I / Table II style summary, correlations above 0.5, and what was assumed."""
    lines = ["[[Fit statistics]]"]
    if res.levels is not None:
        lines.append(f"    constant-velocity levels : {len(res.levels.velocity)}")
    lines.append(f"    presliding branches      : {res.n_branches}")
    if res.stribeck_fit:
        for side, fit in res.stribeck_fit.items():
            lines.append(f"    Markov chi2 ({side})  : {fit.chi2:.3g} for {fit.dof} degrees of freedom")
        lines.append("[[S(v), eq. (7) — Table I form]]")
        lines.append(f"    {'parameter':10s} {'positive velocity':>24s} {'negative velocity':>24s}")
        for k in NAMES:
            pos, neg = res.stribeck_fit["positive"], res.stribeck_fit["negative"]
            lines.append(f"    {k:10s} {pos.values[k]:>12.4g} ± {pos.stderr[k]:<9.2g} {neg.values[k]:>12.4g} ± {neg.stderr[k]:<9.2g}")
        lines.append("[[Correlations (|C| > 0.5)]]")
        for side, fit in res.stribeck_fit.items():
            C = fit.correlation
            pairs = sorted(((abs(C[i, j]), NAMES[i], NAMES[j], C[i, j]) for i in range(5) for j in range(i + 1, 5)), reverse=True)
            for a, ni, nj, c in pairs:
                if a > 0.5:
                    lines.append(f"    {side:8s} C({ni}, {nj}) = {c:+.3f}")
    tf = res.transition_fit
    if tf is not None:
        lines.append("[[Transition curve F_d — Table II form]]")
        lines.append(f"    {'z':>12s} {'F_d(z)':>12s}")
        for i, (z, F) in enumerate(zip(tf.z, tf.F)):
            err = f" ± {tf.stderr[i]:.2g}" if i else "   (fixed)"
            lines.append(f"    {z:>12.4g} {F:>12.5g}{err}")
        lines.append(f"    n = {tf.n:g}" + (f" ± {tf.n_stderr:.2g}" if tf.n_stderr is not None else " (fixed)"))
    if res.notes:
        lines.append("[[Notes]]")
        lines.extend(f"    {m}" for m in res.notes)
    return "\n".join(lines)
