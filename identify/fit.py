"""The headless fit: recordings in, a complete parameter set with uncertainties out.

Connects the parts: ``segment`` prepares each recording (thresholds from the data, velocity,
friction sign, normal-load plateau) and finds constant-velocity levels and presliding
branches of both kinds; ``markov`` fits S(v) per sign, holding what the levels cannot
determine; ``mle`` fits the transition curve from all presliding branches of all files at
once, each with its own noise model. Every parameter is either *estimated* (with a 1-σ
uncertainty) or *held* (with the value it was held at and the reason); the report and the
YAML's provenance say which.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
import math
from dataclasses import dataclass, field

import numpy as np
from scipy.stats import chi2 as chi2_dist
from scipy.stats import spearmanr

from ..model import FrictionParams, Stribeck, StribeckSide, TransitionCurve, default_params
from ..model.params import REACH_WITHIN, get_value, reaching_knots, spec_of
from ..model.simulate import stribeck_curve

from .data import Recording, units_of_recordings
from .errors import IdentificationError
from .markov import (MISFIT_P, NAMES, STRIBECK_MIN_SPEEDS, Levels, distinct_speeds, fit_sides_honest, misfit_scale,
                     misfits, stribeck_plus_viscous, widened_stderr)
from .mle import Gaussian, PreslidingData, fit_transition_curve
from .segment import (GROSS_SLIDING, MIN_BRANCH_POINTS, MIN_REACH_CROSSINGS, TREND_BESIDE, TREND_NOT_SPEED, Prepared,
                      beyond_levels, constant_velocity_levels, crossing_range, crossings, fast_runs, force_branches,
                      motion_branches, noise_sd, prepare, presliding_reach, runs_under_window, sliding_levels,
                      steady_runs)
from .threads import one_blas_thread

KNOT_FRACTIONS = (0.2, 0.4, 0.6, 0.8, 0.9, 1.0)  # of the force change of the branch reaching furthest in z
RESOLVED = 2.0  # position-noise σ (or encoder steps) a displacement must exceed to be told from none
BRANCH_SPAN_RATIO = 100.0  # a branch moving this many times the median branch has slid (see ``sliding_branches``)


@dataclass
class FitResult:
    params: FrictionParams
    stribeck_fit: dict | None = None  # side -> markov.SideFit (None: the side is held)
    transition_fit: object | None = None
    levels: Levels | None = None
    n_branches: int = 0
    notes: list = field(default_factory=list)
    datasets: list = field(default_factory=list)
    thresholds: dict = field(default_factory=dict)  # source -> segment.Thresholds
    held: dict = field(default_factory=dict)  # dotted parameter path -> reason
    decisions: dict = field(default_factory=dict)  # side -> markov.SideDecision
    refinement: dict = field(default_factory=dict)
    branches_tried: int = 0  # branches the transition curve's likelihood was maximised over (0: never ran)
    # what must be read before the result is used, one line each (``force_like_friction``)
    warnings: list = field(default_factory=list)

    @property
    def status(self) -> dict:
        """dotted path -> 'estimated' or 'held'."""
        out = {k: "estimated" for k in self.params.uncertainty}
        out.update({k: "held" for k in self.held})
        return out

    def report(self) -> str:
        return fit_report(self)


def _level_lines(res: FitResult) -> list[str]:
    """The Markov estimator's points, each with the S(v) + σ2·v written at its speed and how many
    of its σ apart: where a side misfits, the levels that do (a haptic joint made apart was told
    its levels misfit Coulomb + viscous, χ² 41.6 for 4, without being shown which)."""
    lv = res.levels
    vu, fu = (spec_of(res.params, f"stribeck.positive.{k}").unit for k in ("vs", "Fc"))
    order = np.argsort(lv.velocity)
    model = stribeck_curve(res.params, lv.velocity)
    sd = np.sqrt(np.maximum(lv.variance, 0.0))
    out = ["[[Levels of S(v): the Markov estimator's points, and S(v) + σ2·v as written there]]",
           f"    {'v (' + vu + ')':>14s} {'friction (' + fu + ')':>18s} {'± σ':>10s} {'written':>12s} {'off (σ)':>8s}"]
    for i in order:
        off = (lv.friction[i] - model[i]) / sd[i] if sd[i] > 0 else float("nan")
        out.append(f"    {lv.velocity[i]:>14.4g} {lv.friction[i]:>18.5g} {sd[i]:>10.2g} {model[i]:>12.5g} {off:>+8.1f}")
    return out


def _merge_levels(parts: list[Levels]) -> Levels:
    if not parts:
        return Levels(*(np.zeros(0) for _ in range(4)))
    if len(parts) == 1:
        return parts[0]
    # (the levels' times are each recording's own clock: not kept across recordings)
    return dataclasses.replace(Levels.joined(parts), time=None)


TREND_P = 0.01  # the levels' residuals follow their time at this significance (Spearman): said in the notes


def misfit_in_time(levels: Levels, fit, sign: int) -> str:
    """Where a side's S(v) misfits its levels: whether the misfit follows the time the levels
    were run in, in words ("" if not, or their times are not known). A drift in time along the
    session (a warm-up, a wear-in) leaves the levels above and below any curve of the speed in
    the order they were run, which the χ² alone does not say (a slide made apart, its friction
    rising 25 % over the first minute, was fitted F_s = F_c and a viscous slope a quarter of the
    other side's, with only χ² = 2.3·10⁵ for a hint)."""
    if levels.time is None:
        return ""
    m = levels.velocity * sign > 0
    if m.sum() < 5:
        return ""
    v, t = levels.velocity[m], levels.time[m]
    theta = [fit.values[k] for k in NAMES]
    r = (levels.friction[m] - stribeck_plus_viscous(theta, v)) * sign / np.sqrt(np.maximum(levels.variance[m], 1e-300))
    rho, p = spearmanr(t, r)
    if not np.isfinite(p) or p >= TREND_P:
        return ""
    rho_v = spearmanr(t, np.abs(v))[0]
    return (f"; the misfit follows the time the levels were run in (Spearman ρ {rho:+.2f} between their times and "
            f"their friction above the curve, over {int(m.sum())} levels, p = {p:.2g}): the force logged changed "
            f"during the session, by the contact (a warm-up, a wear-in, a load) or by the sensor (a drifting offset: "
            f"a slow noise of the force does it alone), which no S(v) holds"
            + (f" — here the levels were run in order of speed (ρ {rho_v:+.2f}), so a form that misfits their "
               f"speeds trends with time as well" if abs(rho_v) >= 0.8 else "")
            + "; `diagnose` tests a drift in time")


def form_untested(side: str, dec) -> str | None:
    """The note for a side whose S(v) form has as many free parameters as it has levels (a
    ``markov.fit_side_honest`` decision, χ² for 0 degrees of freedom), else None: the χ² cannot
    test the form then (a valve made apart, two levels a side, wrote σ2 2404 ± 160 N·s/m for
    2000: its Stribeck tail and a spring left in the force were in the two levels, unsaid)."""
    if dec.fit.dof != 0:
        return None
    return (f"{side} side: {dec.model} passes through its levels exactly (0 degrees of freedom): its σ count the "
            f"levels' noise alone and nothing tests the form, which takes up whatever else moves the levels (a force "
            f"along the travel, a drift); more speeds on this side would test it")


def left_out(levels: Levels, unit: str = "") -> str:
    """The runs of steady velocity the segmentation did not take as settled levels, in words ("" if none)."""
    parts, said = [], ""
    if levels.opposing:
        parts.append(f"{levels.opposing} run(s) whose friction opposes their velocity (a presliding spring giving "
                     f"back, not sliding"
                     + (f"; {levels.opposing_strokes} of them over a tenth of the travel or more, which no presliding "
                        f"spring gives back over: the force holds a constant force beyond friction — a weight on a "
                        f"vertical axis, a counterbalance, a force sensor's offset — which the model has no term for: "
                        f"write the column less it (m·g, or the force read at rest with the drive off)"
                        if levels.opposing_strokes else "") + ")")
    if levels.creep:
        parts.append(f"{levels.creep} run(s) of creep (weak or short beside the other levels, or starting within twice "
                     f"the presliding range of a reversal: segment.sliding_only, constant_velocity_levels)")
    if levels.trend_alone:
        parts.append(f"{levels.trend_alone} run(s) whose friction trends, on a side with under {TREND_BESIDE} settled "
                     f"levels and too few speeds to make a sweep of their own")
    if levels.speed_trend:
        parts.append(f"{levels.speed_trend} run(s) whose friction trends while their speed moves too, by under "
                     f"{TREND_NOT_SPEED:g} times its share: a creep, a stroke of a sinusoidal force, not a steady run "
                     f"— or friction moving along the run for another reason while the speed moves a little (a "
                     f"drift; a force along the travel left in the applied one, a spring's: `diagnose` says one)")
    if parts:
        said = "; left out: " + " and ".join(parts)
    if levels.trended is not None:
        # said with their speeds: where they are a sweep's slow end, S(v)'s Stribeck part rests
        # on them (``segment.constant_velocity_levels``)
        sp = np.abs(levels.velocity[levels.trended])
        lo, hi = f"{sp.min():.3g}", f"{sp.max():.3g}"
        said += (f"; {len(sp)} of them run(s) whose friction trends within the run (its halves differ by over 4 σ "
                 f"while the speed held: a ripple along the travel, a drift, a load changing), at |v| "
                 f"{lo if lo == hi else f'{lo}–{hi}'}{' ' + unit + '/s' if unit else ''}: points of S(v) with half "
                 f"that change in their σ, not steady speeds")
    return said


def sign_hint(prep: Prepared, levels: Levels) -> str:
    """What to try when every steady run of a measured friction, or of an applied force,
    opposed its velocity: sliding dissipates, so the column's sign is then the likelier fault
    ("" otherwise)."""
    if len(levels.velocity) or levels.opposing < 2:
        return ""
    if prep.rec.friction is None:
        # an applied force is read as pushing the way the position increases (eq. (8)); no
        # convention is guessed for it (a vertical axis holds a weight both ways), so say it
        return (f"every steady run's applied force ({levels.opposing}) opposes its velocity, where sliding takes a "
                f"force pushing the way it moves: the force column likely has the other sign (the model's applied "
                f"force pushes the position up): negate the column in the file (or turn its sign with "
                f"{prep.rec.sign_mend('force')})")
    taken = "reaction (flipped)" if prep.sign_flipped else "action"
    return (f"every steady run's friction ({levels.opposing}) opposes its velocity with the friction "
            f"taken as {taken}: the column likely has the other sign (--friction-sign auto detects it, or force "
            f"the other one)")


def _speeds_per_side(levels: Levels) -> tuple[int, int]:
    """Distinct speeds of the constant-velocity levels, (positive, negative)."""
    v = levels.steady().velocity
    return tuple(distinct_speeds(v[v * s > 0]) for s in (1.0, -1.0))


def has_speed_sweep(levels: Levels) -> bool:
    """Whether a recording's constant-velocity levels show two distinct speeds in either
    direction. A sweep in one direction leaves the other's few levels as they are: a load or a
    temperature moving along the session can break its runs, and its sliding would pool over
    them."""
    return max(_speeds_per_side(levels)) >= 2


REL_TOL_WIDER = (0.12, 0.25)  # a run's velocity tolerance tried, in turn, where the derived one finds too few speeds
WIDER_GAIN = 2.0  # … and kept only if it finds this many times the distinct speeds (both directions)


def widened_levels(prep: Prepared, levels: Levels) -> tuple[Levels, str]:
    """A recording's constant-velocity levels where a run's velocity wanders more than
    rel_tol allows: a controller holding a speed against a friction that changes along the
    travel (a ripple) or in time lets the velocity vary by 10–20 % within a commanded level, and
    at the derived rel_tol (6 %) each level falls apart into pieces shorter than min_run — on a
    stage under a PI velocity loop with a 12 % friction ripple, 2 levels of its 20 were left.
    Where a direction shows fewer than STRIBECK_MIN_SPEEDS speeds (``markov``: what a Stribeck
    curve needs), the wider tolerances REL_TOL_WIDER are tried and the one giving the most
    speeds over both directions is kept if it gives at least WIDER_GAIN times the derived one's
    (the smallest at a tie; the runs' other tests — a friction trend between halves, the
    settling part dropped — stay as they are):
    ``prep.th.rel_tol`` is set to it, so the report's thresholds show it, and the words say why
    ("" if unchanged). Levels that fall apart lose most of their speeds; a gain of one or two
    is runs at the margin of any tolerance, and on the hidden-effect suite's robot joints
    (2064: 8 → 10 speeds, 1067: 6 → 9) those made the fit worse (the model as given left 6.67
    where it left 3.33), so they are not taken."""
    before = _speeds_per_side(levels)
    if min(before) >= STRIBECK_MIN_SPEEDS:
        return levels, ""
    best, best_tol, best_speeds = levels, prep.th.rel_tol, before
    for tol in REL_TOL_WIDER:
        if tol <= best_tol:
            continue
        trial = constant_velocity_levels(dataclasses.replace(prep, th=dataclasses.replace(prep.th, rel_tol=tol)))
        speeds = _speeds_per_side(trial)
        if sum(speeds) > sum(best_speeds):
            best, best_tol, best_speeds = trial, tol, speeds
    if best is levels or sum(best_speeds) < WIDER_GAIN * sum(before):
        return levels, ""
    derived, prep.th.rel_tol = prep.th.rel_tol, best_tol
    return best, (f"rel_tol widened from {derived:g} to {best_tol:g}: at {derived:g} the constant-velocity runs "
                  f"held {len(levels.velocity)} level(s) at {before[0]} + {before[1]} distinct speeds (positive + "
                  f"negative), at {best_tol:g} {len(best.velocity)} at {best_speeds[0]} + {best_speeds[1]} "
                  f"— the velocity wanders within its runs (a controller holding a speed against a friction "
                  f"that changes); set --threshold rel_tol to choose")


def wavering_levels(prep: Prepared, levels: Levels) -> str:
    """Where ``widened_levels`` keeps the derived rel_tol (each direction shows enough
    speeds), the speeds a wider tolerance (REL_TOL_WIDER) would add, in words ("" if
    none): runs held at a commanded speed whose velocity wavers beyond rel_tol break into
    pieces shorter than min_run and are lost unsaid otherwise — a harmonic-drive wrist made
    apart, its friction rippling by 12 % along the travel under a PID loop, kept 14 of its 20
    speeds, the six between 0.06 and 0.22 rad/s (the ripple at 2–7 Hz) gone with no word. The
    wider tolerance said is the one of REL_TOL_WIDER that adds the most runs. Said, not taken:
    runs at the margin of any tolerance made the suite's fits worse (see ``widened_levels``);
    the user chooses with --threshold rel_tol."""
    steady = levels.steady().velocity
    have = np.log(np.abs(steady))
    best, tol = [], None
    for wider_tol in (t for t in REL_TOL_WIDER if t > prep.th.rel_tol):
        wider = constant_velocity_levels(dataclasses.replace(prep, th=dataclasses.replace(prep.th, rel_tol=wider_tol)))
        # a speed within 10 % of a level of its side is that level again (``markov.distinct_speeds``)
        new = [v for v in wider.steady().velocity
               if not np.any((np.sign(steady) == np.sign(v)) & (np.abs(have - math.log(abs(v))) < math.log(1.1)))]
        if len(new) > len(best):
            best, tol = new, wider_tol
    if not best:
        return ""
    return (f"{len(best)} more run(s) hold a speed at rel_tol {tol:g} that at {prep.th.rel_tol:g} are no level (|v| "
            f"{speeds_said(best)}): their velocity wavers beyond {prep.th.rel_tol:g} within the run (a controller "
            f"holding a speed against a friction that changes along the travel or in time), so each breaks into "
            f"pieces under min_run; --threshold rel_tol={tol:g} takes them")


def with_fastest_levels(prep: Prepared, levels: Levels, friction_sign: str = "auto",
                        thresholds: dict | None = None) -> tuple[Levels, str]:
    """A recording's levels with its fastest speeds added where a sweep held them for less
    than ``min_run`` (two windows: ``segment.fast_runs``), and what was done, in
    words ("" if nothing). The window is derived from the recording's length (n/1000 samples at
    least), so a long session's short top speeds fall under it: a nanopositioning stage made
    apart, 174,000 rows at 2 kHz, held its fastest speeds for 64 samples against a window of
    173, and its S(v) was held at Coulomb + viscous (F_c 0.151 N for 0.12). Those runs are
    taken again at the windows NARROWER, NARROWER², … of the derived one (odd, at least 5
    samples), each adding the levels it makes beyond every level so far, until no faster
    steady run is left: only those levels are added, so the others, and the presliding, keep the
    derived window's lower velocity noise."""
    found = fast_runs(prep, levels)
    # runs held for less than the window itself show no steady run there at all: seen at a
    # shorter one (``segment.runs_under_window``)
    under = not found and bool(found := runs_under_window(prep, levels))
    if not found:
        return levels, ""
    taken, w, tried, left = [], prep.th.window, prep.th.window, found
    # each window in turn, narrower until no steady run faster than every level so far is
    # left (cut short, or too short to settle within): a sweep's speeds above the one a window
    # takes are held for shorter still
    while left and (w := (int(w * NARROWER) - 1) | 1) >= 5:
        tried = w
        narrow = prepare(prep.rec, friction_sign=friction_sign, overrides={**(thresholds or {}), "window": w})
        narrow.th.rel_tol = prep.th.rel_tol  # (as ``widened_levels`` left it)
        more = constant_velocity_levels(narrow)
        beyond = beyond_levels(more.velocity, levels)
        if beyond.any():
            added = more.kept(beyond, opposing=0, opposing_strokes=0, creep=0, trend_alone=0, speed_trend=0)
            levels = Levels.joined([levels, added])
            taken.append((int(beyond.sum()), f"at a window of {w} (|v| {speeds_said(added.velocity)})"))
        left = fast_runs(narrow, levels, cut_short=False) or runs_under_window(narrow, levels)
    said = (f"{len(found)} run(s) faster than every level of their side held their speed for {min(n for _, n in found)}"
            f"–{max(n for _, n in found)} samples, too short to be steady at the window of {prep.th.window} the "
            f"velocity is smoothed over (seen at a quarter of it)" if under else
            f"{len(found)} steady run(s) faster than every level of their side were averaged over under min_run = "
            f"{prep.th.min_run} samples (two windows of {prep.th.window}; a level leaves out a run's first 30 % and "
            f"its last half window; the longest run {max(n for _, n in found)})")
    if not taken:
        return levels, said + " and no window down to 5 samples made levels of them"
    lost = (f"; {len(left)} faster run(s) (up to |v| {max(left)[0]:.3g}) are not levels even at a window of {tried}"
            if left else "")
    # (a run held long at a narrow window makes several levels: they are counted as levels)
    return levels, (f"{said}: {sum(k for k, _ in taken)} level(s) taken from them, "
                    f"{'; '.join(f'{k} {at}' for k, at in taken)}, the others at {prep.th.window}{lost}; "
                    f"set --threshold window to choose one for all")


def speeds_said(velocity) -> str:
    """Speeds as read, rising, a repeated one counted: "0.008 ×6, 0.012 ×4, 0.02"."""
    said = [f"{v:.3g}" for v in np.sort(np.abs(np.asarray(velocity, dtype=np.float64)))]
    seen = list(dict.fromkeys(said))
    return ", ".join(v + (f" ×{said.count(v)}" if said.count(v) > 1 else "") for v in seen)


NARROWER = 2.0 / 3.0  # each window tried for a sweep's fastest runs is this fraction of the one before


def with_sliding_levels(prep: Prepared, levels: Levels) -> tuple[Levels, str]:
    """A recording's levels where it holds no speed sweep — in neither direction do its
    constant-velocity levels show two distinct speeds (none, or a sinusoidal stroke's top:
    S(v) + σ2·v at one speed) — each direction taken instead from its steady gross sliding
    (``segment.sliding_levels``) where that shows more speeds, and what was done, in words
    ("" if nothing). Gross sliding starts past twice the presliding range, the median travel
    over which the friction crossed to sliding after a reversal, to the sliding friction at the
    speed reached (``segment.presliding_reach``; at least
    MIN_REACH_CROSSINGS crossings). The paper's Markov estimator takes constant-velocity runs; a
    recording made without them (a crank-driven tribometer, a sinusoidal force) still shows
    S(v) wherever its velocity changes slowly against the friction's lag, and that is used
    instead of holding one speed's value or another machine's S(v). Without a measured friction
    the applied force less I·ẍ stands for it where the force alone reads the inertia
    (``friction_by_eq8``)."""
    sides = {1.0: "positive", -1.0: "negative"}
    if has_speed_sweep(levels):
        return levels, ""
    of_force = ""
    if prep.friction is None:
        # an applied force, no friction logged: the friction is the force less I·ẍ where the
        # force alone reads the inertia (eq. (8)); a mass under a sinusoidal force made apart
        # had its S(v) held at one speed's, the top of its swing (F_c 1.38 N for a friction of
        # 1.06 there), where its gross sliding spans every speed of the swing
        taken = friction_by_eq8(prep)
        if taken is None:
            return levels, ""
        prep, of_force = taken
    z_range = prep.reach or presliding_reach(prep)  # (a friction taken by eq. (8) was not there when prepared)
    if not z_range > 0:
        return levels, ""
    extra = sliding_levels(prep, z_range)
    taken = [s for s in sides if distinct_speeds(extra.velocity[extra.velocity * s > 0])
             > distinct_speeds(levels.velocity[levels.velocity * s > 0])]
    if not taken:
        return levels, ""
    mine = np.isin(np.sign(levels.velocity), taken)
    new = np.isin(np.sign(extra.velocity), taken)

    def held_at(s):
        mine_s = levels.velocity * s > 0
        return (f"{sides[s]} velocity (its {int(mine_s.sum())} constant-velocity level(s) at "
                f"{distinct_speeds(levels.velocity[mine_s])} distinct speed(s))")

    words = " and ".join(held_at(s) for s in taken)
    # (the runs left out are the constant-velocity ones' alone; the sliding has no times)
    joined = Levels.joined([levels.kept(~mine), extra.kept(new)])
    return (dataclasses.replace(joined, opposing=levels.opposing, opposing_strokes=levels.opposing_strokes,
                                creep=levels.creep, speed_trend=levels.speed_trend, time=None),
            f"{words}: S(v) from {int(new.sum())} speed level(s) of steady gross sliding instead{of_force} (past "
            f"{GROSS_SLIDING:g} × {z_range:.3g} of travel after each reversal, the median range over which the "
            f"friction crossed to sliding; the velocity changing by under 5 % over that range; binned in log|v|)")


def friction_by_eq8(prep: Prepared) -> tuple[Prepared, str] | None:
    """``prep`` with its friction taken from the applied force by eq. (8), F = f − I·ẍ (ẍ the
    mean acceleration over the velocity's window, centred), and the words that say so, where
    the force alone reads a usable inertia (``diagnose.recording_inertia``: no model enters);
    else None."""
    from .diagnose import mean_acceleration, recording_inertia

    if prep.force is None:
        return None
    est = recording_inertia(prep.rec).estimate
    if est is None or not est.usable:
        return None
    acc = mean_acceleration(prep.velocity, prep.rec.time, max(prep.th.window, 5) | 1)
    friction = np.asarray(prep.force, dtype=np.float64) - est.value * acc
    return (dataclasses.replace(prep, friction=friction),
            f", of the applied force less I·ẍ (eq. (8); I = {est.value:.4g} ± {est.stderr:.2g}, read from the force)")


MAX_BRANCHES, MAX_POINTS = 10, 100


SPAN_TIE = 1e-9  # branch spans within this fraction of the longest are tied (``_thin``)


def _thin(branches):
    """At most MAX_BRANCHES branches per data set (the longest) and MAX_POINTS samples per
    branch (evenly spaced, the reversal kept): the likelihood stays a likelihood of the
    samples used, and its cost stays bounded on long recordings. The spans are compared to
    SPAN_TIE of the longest: on an encoder's grid many branches span the same number of steps,
    and which of them were kept had turned on the last bit of their rounding (a stage written in
    m and in µm kept two different branches of the same recording, and its curve's first knot
    moved 6 σ); tied, the earlier in the record is kept (``sorted`` is stable)."""
    spans = [float(np.ptp(b.displacement)) for b in branches]
    top = max(spans, default=0.0) or 1.0
    order = sorted(range(len(branches)), key=lambda i: -round(spans[i] / top / SPAN_TIE))
    keep = [branches[i] for i in order[:MAX_BRANCHES]]
    out = []
    for b in keep:
        if len(b.force) > MAX_POINTS:
            idx = np.unique(np.linspace(0, len(b.force) - 1, MAX_POINTS).astype(int))
            b = dataclasses.replace(b, force=b.force[idx], displacement=b.displacement[idx])
        out.append(b)
    return out


def sliding_branches(datasets) -> list:
    """Leave out the presliding branches that moved more than BRANCH_SPAN_RATIO times the
    median branch of the recordings: they slid (a slow slide below the speed that ends a
    branch — under a smooth applied force, gross sliding can start slowly), and one such
    displacement would outweigh every real branch in the likelihood. Presliding branches
    span a few times each other at most (up to 17× on the shipped samples: an internal loop
    against a full one). Returns "name: span" of each one left out."""
    spans = [float(np.ptp(b.displacement)) for d in datasets for b in d.branches]
    if len(spans) < 3:
        return []
    limit = BRANCH_SPAN_RATIO * float(np.median(spans))
    out = []
    for d in datasets:
        out += [f"{d.name}: {np.ptp(b.displacement):.3g}" for b in d.branches if np.ptp(b.displacement) > limit]
        d.branches = [b for b in d.branches if np.ptp(b.displacement) <= limit]
    return out


def check_n(n) -> float:
    try:
        x = float(n)
    except (TypeError, ValueError):
        raise IdentificationError(f"n: expected a number, got {n!r}") from None
    if not math.isfinite(x) or x <= 0:
        raise IdentificationError(f"n: the exponent of eq. (5) must be a finite number > 0, got {n!r}")
    return x


def branch_z(b, n: float) -> np.ndarray:
    """The state z along a presliding branch: eq. (5) at presliding speeds gives dz = (1 −
    (ΔF/D)^n)·dx, so near D the displacement runs ahead of z."""
    x = b.displacement - (b.displacement[0] if b.driven == "force" else 0.0)
    w = 1.0 - np.clip(b.force / b.D, 0.0, 1.0) ** n
    return np.maximum.accumulate(np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * np.diff(x))]))


def observed_branches(datasets) -> list:
    """Branches that start at a reversal in the record: only they tell z (one continued on the
    outer loop starts at an unknown z)."""
    return [b for d in datasets for b in d.branches if b.observed and len(b.force) > 1]


def knots_from_data(datasets, n: float = 7.0) -> np.ndarray:
    """Abscissas where the branch that reaches furthest in z has gone KNOT_FRACTIONS of its
    force change (so every segment holds data, densest where F_d is steepest), dropping any
    closer to its neighbour than two position-noise σ (knots the data cannot tell apart).
    Refuses if fewer than one knot remains."""
    # z, not the displacement (``branch_z``): a top knot at the largest displacement would lie
    # beyond every datum's z and F_d there would be an extrapolation
    observed = observed_branches(datasets)
    if not observed:
        raise IdentificationError("no presliding branch starts at a reversal in the record: the abscissas of the "
                                  "transition curve cannot be placed (give them with knots=...)")
    zs = [branch_z(b, n) for b in observed]
    k = int(np.argmax([zb[-1] for zb in zs]))
    zb, fb = zs[k], np.maximum.accumulate(observed[k].force)
    reach = float(zb[-1])
    resolution = min(d.x_noise for d in datasets)
    z = [0.0]
    for f in KNOT_FRACTIONS:
        # where the force change first reaches the fraction (the top knot: the end of the data)
        zi = reach if f >= 1.0 else float(zb[int(np.searchsorted(fb, f * fb[-1]))])
        if zi - z[-1] >= RESOLVED * resolution:
            z.append(zi)
    if len(z) < 2:
        raise UnresolvedCurve(reach, resolution)
    return np.array(z)


class UnresolvedCurve(IdentificationError):
    """The presliding branches reach no further than two position-noise σ (or encoder steps):
    the transition curve's abscissas cannot be placed; ``reach`` is how far they went."""

    def __init__(self, reach: float, resolution: float, limit: str = "two position-noise σ"):
        super().__init__(f"the presliding displacement range ({reach:.3g}) is within {limit} "
                         f"({resolution:.3g}): the transition curve cannot be resolved")
        self.reach, self.resolution = reach, resolution


def held_curve_for(curve: TransitionCurve, stribeck: Stribeck, reach: float) -> TransitionCurve:
    """The paper's transition curve, held for a machine the data could not give one for, brought
    to this machine's scale: F_d's top at F_s⁺ − F_s⁻ of the fitted S(v) (the outer loop's
    span, as Table II's 100 N·m is Table I's 36 + 63) and its last knot at ``reach``, how far
    the branches showed presliding to reach. A held value, not an estimate: the
    KUKA joint's 100 N·m over 5.2·10⁻⁴ rad means nothing on a 10 N·m joint."""
    span = stribeck.positive.Fs - stribeck.negative.Fs
    if (curve.kind != "piecewise_linear" or not curve.F or not span > 0 or not curve.F[-1] > 0
            or not reach > 0 or not curve.z[-1] > 0):
        return curve  # nothing to scale by: the curve as it was (the caller says so)
    fz, zz = span / curve.F[-1], reach / curve.z[-1]
    return TransitionCurve(kind="piecewise_linear", z=tuple(float(v * zz) for v in curve.z),
                           F=tuple(float(v * fz) for v in curve.F))


def check_knots(knots, datasets) -> np.ndarray:
    z = np.asarray(knots, dtype=float)
    if z.ndim != 1 or len(z) < 2 or z[0] != 0.0 or np.any(~np.isfinite(z)) or np.any(np.diff(z) <= 0):
        raise IdentificationError("knots: abscissas must start at 0 and increase strictly")
    resolution = min(d.x_noise for d in datasets)
    close = np.flatnonzero(np.diff(z) < resolution)
    if len(close):
        i = int(close[0]) + 1
        raise IdentificationError(f"knots: z[{i}] = {z[i]:.3g} is closer than the position noise ({resolution:.3g}) "
                                  f"to z[{i - 1}]: the data cannot tell these knots apart")
    return z


@one_blas_thread
def fit_recordings(recordings: list[Recording], *, base: FrictionParams | None = None, knots=None,
                   n: float = 7.0, fit_n: bool = False, progress=None, thresholds: dict | None = None,
                   friction_sign: str = "auto", refine: bool = True) -> FitResult:
    """Fit S(v) (Markov) and F_d (maximum likelihood) from one or more recordings.

    ``thresholds`` overrides derived segmentation thresholds by name (see
    ``segment.Thresholds``); ``friction_sign`` is 'auto', 'action' or 'reaction'."""
    say = progress or (lambda frac, msg: None)
    n = check_n(n)
    if friction_sign not in ("auto", "action", "reaction"):
        raise IdentificationError(f"friction sign: one of auto, action, reaction; got {friction_sign!r}")
    if not recordings:
        raise IdentificationError("nothing to fit: no recordings given")
    # the starting set gives values only: every σ written is this fit's (a value kept from it is
    # held, named so, and has none)
    p = (base or default_params()).replace(uncertainty={})
    # what is held comes from the file the user gave, or else from the paper's robot joint,
    # whose values mean nothing for another machine: the report says which
    start = ("from the starting parameter file" if base is not None else
             "from the built-in default, the paper's KUKA IR 361 axis 1 in its units (give --params with this "
             "machine's values)")
    # σ1 and the inertia a starting file gave: one that left them out holds the built-in
    # defaults (``FrictionParams.defaulted``), another machine's as much as without a file
    given = {k: base is not None and k not in base.defaulted for k in ("sigma1", "inertia")}
    kept_from = {k: start if given[k] or base is None else f"at the built-in default (the starting parameter file has "
                 f"no {k}: give this machine's)" for k in given}
    notes: list = []
    held: dict = {}
    if p.effects:
        # the fit estimates the model without effects (none enters its estimators), so the start's
        # effects are not carried into it: written beside a base fitted to these recordings they
        # would count twice what the fit took up, or need a signal these recordings lack (a web
        # session's ripple accepted on one file, then a fit of another: its diagnosis failed on a
        # load effect the new file had no column for)
        notes.append(f"the starting set's effects ({', '.join(e['name'] for e in p.effects)}) are not carried into "
                     f"this fit: it estimates the model without effects; `diagnose` names and fits them")
        p = p.replace(effects=())
    say(0.05, "deriving thresholds and finding constant-velocity levels")
    preps: list[Prepared] = []
    for r in recordings:
        try:
            preps.append(prepare(r, friction_sign=friction_sign, overrides=thresholds))
        except IdentificationError as e:
            raise IdentificationError(str(e) if str(e).startswith(r.source) else f"{r.source}: {e}") from None
    for pr in preps:
        notes.extend(f"{pr.source}: {m}" for m in pr.notes + pr.th.notes)
    per_file = []
    for pr in preps:
        lv = constant_velocity_levels(pr)
        if "rel_tol" not in (thresholds or {}):
            lv, widened = widened_levels(pr, lv)
            if widened:
                notes.append(f"{pr.source}: {widened}")
            elif wavering := wavering_levels(pr, lv):
                notes.append(f"{pr.source}: {wavering}")
        if "window" not in (thresholds or {}) and "min_run" not in (thresholds or {}):
            lv, fastest = with_fastest_levels(pr, lv, friction_sign, thresholds)
            if fastest:
                notes.append(f"{pr.source}: {fastest}")
        hint = sign_hint(pr, lv)
        notes.append(f"{pr.source}: {len(lv.velocity)} constant-velocity level(s) "
                     f"({int(np.sum(lv.velocity > 0))} positive, {int(np.sum(lv.velocity < 0))} negative)"
                     + left_out(lv, pr.rec.units.get("position", "")) + (f"; {hint}" if hint else ""))
        lv, filled = with_sliding_levels(pr, lv)
        if filled:
            notes.append(f"{pr.source}: {filled}")
        per_file.append(lv)
    levels = _merge_levels(per_file)
    # presliding branches are picked against S(v)'s F_s: where few speeds set it, branches that
    # reach nothing may be rests picked against a wrong F_s, not presliding the sensor misses
    speeds = _speeds_per_side(levels)
    picked_on_few = ("" if min(speeds) >= STRIBECK_MIN_SPEEDS else
                     f"; the branches were picked against an S(v) resting on "
                     f"{speeds[0]} + {speeds[1]} speed(s) (positive + negative): if the "
                     f"sweep holds more levels than were found, see rel_tol and the levels' notes")

    # --- S(v): Markov estimator per side, honest about what the levels determine ------------
    say(0.2, f"Markov estimator on {len(levels.velocity)} levels")
    decisions = fit_sides_honest(levels)
    sides = {}
    for side, sign in (("positive", 1), ("negative", -1)):
        dec = decisions[side]
        other = decisions["negative" if sign > 0 else "positive"]
        if dec.fit is None:
            why = dec.held["Fc"]  # no levels, or levels that show no sliding (``fit_side_honest``)
            if other.fit is not None:
                vals = {k: -v if k in ("Fs", "Fc", "vs") else v for k, v in other.fit.values.items()}
                reason = f"{why}: mirrored from the {'negative' if sign > 0 else 'positive'} side"
            else:
                vals = {k: getattr(getattr(p.stribeck, side), k) for k in NAMES}
                reason = f"{why}: kept {start}"
            held.update({f"stribeck.{side}.{k}": reason for k in NAMES})
            sides[side] = StribeckSide(**vals)
        else:
            held.update({f"stribeck.{side}.{k}": why for k, why in dec.held.items()})
            sides[side] = StribeckSide(**dec.fit.values)
    p = p.replace(stribeck=Stribeck(**sides))
    stribeck_fit = {s: d.fit for s, d in decisions.items()}

    # --- presliding: both kinds of branches, one likelihood --------------------------------
    say(0.4, "finding presliding branches")
    datasets = []
    short = []  # (crossing range, resolution) of recordings whose reversals resolve no presliding
    slow = levels.slowest_steady_speed()
    branch_ends = []  # each recording's speed above which a branch has ended (``curve_coverage``)
    for pr in preps:
        # presliding ends where gross sliding begins: below the slowest level; without levels
        # only the 97 % of D cut (F_s from the starting file) bounds the branches
        v_max = max(pr.th.v_floor, 0.3 * slow) if np.isfinite(slow) else np.inf
        branch_ends.append(v_max)
        fb = force_branches(pr, p.stribeck.positive.Fs, p.stribeck.negative.Fs, v_max)
        if fb:
            ds = PreslidingData(fb, pr.position_noise, name=f"{pr.source} (force-driven)")
            # resolution: one encoder step, or one σ of a Gaussian sensor
            ds.x_noise = getattr(pr.position_noise, "step", None) or noise_sd(pr.position_noise)
            datasets.append(ds)
        mb = motion_branches(pr)
        if mb:
            ds = PreslidingData(mb, Gaussian(pr.th.f_noise), name=f"{pr.source} (motion-driven)")
            ds.x_noise = getattr(pr.position_noise, "step", None) or max(pr.th.x_noise, 1e-300)
            datasets.append(ds)
        seen = [] if fb or mb else [(r, float(c.dx[min(MIN_BRANCH_POINTS, len(c.dx)) - 1])) for c in crossings(pr)
                                    if math.isfinite(r := crossing_range(c, pr.th))]
        if len(seen) >= MIN_REACH_CROSSINGS:
            # reversals whose crossing to sliding is over within the turn threshold, or within the
            # first samples after the turn: presliding the sensor or the sampling does not resolve
            # (a contact that sticks, then slips); their median range, as ``presliding_reach``
            # takes it (``pr.reach`` is 0 where the friction was taken by eq. (8) after preparing)
            reach = float(np.median([r for r, _ in seen]))
            resolution = max(pr.th.x_turn, float(np.median([q for _, q in seen])))
            short.append((reach, resolution))
            notes.append(f"{pr.source}: no presliding branches: {len(seen)} reversals of the motion, each crossing to "
                         f"sliding within {reach:.3g} (median), no further than the turn threshold x_turn "
                         f"({pr.th.x_turn:.3g}) or the travel of its first {MIN_BRANCH_POINTS} samples "
                         f"({resolution:.3g}, median)")
        elif not fb and not mb:
            notes.append(f"{pr.source}: no presliding branches (no applied-force ramps with reversals in presliding, "
                         f"no reversals of a prescribed motion with measured friction)")
        else:
            notes.append(f"{pr.source}: {len(fb)} force-driven and {len(mb)} motion-driven presliding branch(es)")
    for d in datasets:
        found = len(d.branches)
        d.branches = _thin(d.branches)
        if found > len(d.branches):
            notes.append(f"{d.name}: the {len(d.branches)} longest of its {found} presliding branches enter the "
                         f"transition curve's likelihood (at most {MAX_BRANCHES} per data set)")
    slid = sliding_branches(datasets)
    if slid:
        notes.append(f"{len(slid)} presliding branch(es) moved over {BRANCH_SPAN_RATIO:g}× the median branch "
                     f"({'; '.join(slid)}): they slid, left out of the transition curve's likelihood")
    n_br = sum(len(d.branches) for d in datasets)
    tried = 0
    tfit = None
    unresolved = None
    sensor_resolution = min((d.x_noise for d in datasets), default=math.nan)  # the finest position sensor's
    if n_br and knots is None:
        try:
            z = knots_from_data(datasets, n)
            if len(z) - 1 < len(KNOT_FRACTIONS):
                # the sensor's resolution, not the contact, set how many segments the curve has
                notes.append(f"transition curve: {len(z) - 1} knot(s), not {len(KNOT_FRACTIONS)}: the others fell "
                             f"within {RESOLVED:g} × the position resolution ({sensor_resolution:.3g}) of a knot already "
                             f"placed, and the sensor does not tell them apart")
        except UnresolvedCurve as e:
            # presliding shorter than the position sensor resolves (an encoder step as long as the
            # whole transition): the curve is held, said so, and S(v) is still fitted
            unresolved = e
            notes.append(f"transition curve: {e} (held, not estimated){picked_on_few}")
            n_br = 0
    elif n_br:
        z = check_knots(knots, datasets)
    elif short and knots is None:
        unresolved = UnresolvedCurve(max(r for r, _ in short), max(q for _, q in short),
                                     f"the turn threshold x_turn or the travel of {MIN_BRANCH_POINTS} samples")
        notes.append(f"transition curve: {unresolved} (held, not estimated)")
    if n_br:
        say(0.5, f"maximum-likelihood estimator on {n_br} branches")

        def refit(knots_z):
            return fit_transition_curve(datasets, knots_z, n=n, fit_n=fit_n)

        tfit = refit(z)
        tried = n_br
        if knots is not None and tfit.beyond:
            # knots the user placed are kept as given, and what the data say of them is said
            notes.append(f"transition curve: the knot(s) given at z = {', '.join(f'{z[i]:.3g}' for i in tfit.beyond)} "
                         f"lie above every force change the branches reach ({tfit.asked:.3g}): F_d there is not "
                         f"determined by the data (its value and σ are no estimate)")
        for _ in range(len(z)):
            beyond = list(tfit.beyond)
            if not beyond or knots is not None or len(z) - len(beyond) < 2:
                break
            # segments above every force change the branches reach: no datum depends on their
            # rise (``TransitionFit.beyond``); the curve ends at the last knot the data reach into
            # and goes on with that segment's slope (the branches' top knot sits where the
            # furthest one stopped moving in force, and may lie above what any of them asked)
            z, tfit = dropped_knots(z, beyond, refit, notes,
                                    f"transition curve: knot(s) at z = {', '.join(f'{z[i]:.3g}' for i in beyond)} lie "
                                    f"above every force change the branches reach ({tfit.asked:.3g}): not determined "
                                    f"by the data, dropped (the curve goes on with the slope of its last segment)")
        flat = list(tfit.flat)
        if flat and knots is None and len(z) - len(flat) >= 2:
            # a segment the likelihood makes flat (its increment at the lower limit, 10⁻⁶ of the
            # largest force change, below which no increment can go): the data do not resolve
            # that knot; drop it and refit
            z, tfit = dropped_knots(z, flat, refit, notes,
                                    f"transition curve: knot(s) at z = {', '.join(f'{z[i]:.3g}' for i in flat)} not "
                                    f"resolved by the data (flat segment): dropped")
        loose = list(tfit.loose)
        if loose and knots is None and len(z) - len(loose) >= 2:
            # a rise the branches leave undetermined is not written as an estimate: its knot is
            # dropped (a last one ends the curve at the knot before it) and the curve refitted
            z, tfit = dropped_knots(z, loose, refit, notes,
                                    f"transition curve: the rise to knot(s) at z = "
                                    f"{', '.join(f'{z[i]:.3g} (F_d {tfit.F[i]:.3g} ± {tfit.stderr[i]:.2g})' for i in loose)} "
                                    f"is not determined by the branches (σ over half of it): dropped")
    if tfit is not None and tfit.unbounded:
        # the likelihood pushed a segment to the limit of 20× the largest force change of any
        # branch: the branches do not bound F_d there, and the curve is no estimate
        notes.append(f"transition curve: the segment(s) up to knot(s) {list(tfit.unbounded)} ran to their limit of "
                     f"20× the largest force change of any branch: the branches do not bound F_d (not written as "
                     f"an estimate)")
        tfit = None
        n_br = 0
        reaches = np.array([branch_z(b, n)[-1] for b in observed_branches(datasets)])
        if knots is None and len(reaches) and np.median(reaches) < RESOLVED * sensor_resolution:
            # most branches never left two encoder steps (or noise σ): the few that did went
            # further than presliding reaches (they slid, under a controller's push) and bound
            # nothing; the presliding is not resolved
            unresolved = UnresolvedCurve(float(np.median(reaches)), sensor_resolution)
            notes.append(f"transition curve: half the branches or more reach {unresolved.reach:.3g} at most: "
                         f"{unresolved}" + picked_on_few)
            unbounded = 0.0
        else:
            unbounded = float(reaches.max())  # how far in z the furthest branch reached: a scale for the held curve
    else:
        unbounded = 0.0
    why_curve = ("the branches do not bound F_d" if unbounded else
                 "presliding shorter than the position sensor resolves" if unresolved else "no presliding data")
    if tfit is not None:
        if misfits(tfit):
            # as for S(v): the σ of a curve whose shape misfits its branches are the noise's spread only
            notes.append(f"transition curve: its shape misfits the branches with Gaussian readings (χ² = {tfit.chi2:.3g} "
                         f"for {tfit.dof} degrees of freedom, p < {MISFIT_P:g}, χ²/dof = {tfit.chi2 / tfit.dof:.3g}): "
                         f"its σ say how far the noise moves F_d, not how far the contact's curve is from this "
                         f"piecewise-linear one")
        bad = [i for i in range(1, len(tfit.F)) if not (tfit.stderr[i] < 0.5 * (tfit.F[i] - tfit.F[i - 1]) + 0.5 * tfit.F[i])]
        if bad:
            notes.append(f"transition curve: F_d at knot(s) {bad} has σ comparable to its value: weakly determined")
        p = p.replace(transition_curve=TransitionCurve(kind="piecewise_linear", z=tuple(map(float, tfit.z)),
                                                      F=tuple(map(float, tfit.F))), n=float(tfit.n))
        notes.extend(tfit.notes)
        if not fit_n:
            held["n"] = f"fixed at {n:g} (the paper's choice; --fit-n estimates it)"
        elif tfit.n_stderr is None:
            held["n"] = (f"at its lower bound {tfit.n:g}: the branches run into sliding more gradually than eq. (5) "
                         f"does at n = 1 (n ≥ 1: below it the simulation fails)")
    elif base is None and (unresolved or unbounded):
        # no file of this machine's to hold from, but branches that show how far presliding
        # reaches: the paper's curve, brought to this machine's scale
        # (branches that never left one encoder step reach 0: the range is then of the step's order;
        # branches that do not bound F_d still reach somewhere in z)
        reach = max(unresolved.reach, unresolved.resolution) if unresolved else unbounded
        scaled = held_curve_for(p.transition_curve, p.stribeck, reach)
        held["transition_curve"] = (
            f"{why_curve}: the paper's KUKA IR 361 curve, its F_d scaled to this fit's F_s⁺ − F_s⁻ and its last "
            f"knot to the presliding reach seen" + (", or the sensor's resolution where larger" if unresolved else "")
            + f" ({reach:.3g}) (give --params with this machine's curve)"
            if scaled is not p.transition_curve else f"{why_curve}: kept {start}")
        p = p.replace(transition_curve=scaled)
        # n has no units: the paper's value, not "in its units" (it is the held curve's exponent)
        held["n"] = (f"{why_curve}: held at the paper's {p.n:g}, the exponent of the curve held beside it"
                     if base is None else f"{why_curve}: kept {start}")
    else:
        # a curve kept from another machine beside this fit's F_s (a valve's 539 N·m beside the
        # paper's curve topping at 100 N·m was written unsaid, which `diagnose` then warned of):
        # said as ``curve_coverage`` says a fitted curve that stops short
        short = curve_coverage(p.replace(units=units_of_recordings(recordings)), math.inf)  # in the recordings' units
        under = (f"; {short.removeprefix('transition curve: ')} (presliding recorded — slow force ramps, or small "
                 f"reversals of a motion with measured friction — would set this machine's)" if short else "")
        held["transition_curve"] = f"{why_curve}: kept {start}{under}"
        held["n"] = f"{why_curve}: kept {start}"
    if all(d.fit is None for d in decisions.values()) and tfit is None:
        files = ", ".join(str(pr.source) for pr in preps)
        # a sign that hid every level is the cause to mend: what else failed follows from it
        hints = "; ".join(f"{pr.source}: {h}" for pr, lv in zip(preps, per_file) if (h := sign_hint(pr, lv)))
        if hints:
            raise IdentificationError(f"nothing to fit: {hints}")
        if unresolved:
            raise IdentificationError(f"{files}: nothing to fit: no constant-velocity levels, and {unresolved} (a finer "
                                      f"position sensor, or --params to start from)")
        if unbounded:
            raise IdentificationError(f"{files}: nothing to fit: no constant-velocity levels, and {why_curve} (the segments "
                                      f"ran to their limit): more presliding cycles, or --params to start from")
        raise IdentificationError(f"{files}: nothing to fit: the data hold neither constant-velocity levels nor presliding "
                                  "branches (force ramps with reversals, or reversals of a motion with measured friction)")
    # the model an inertia is read beside takes σ1 at the data's scale (``_held_inertia``): the σ1
    # held below, at the stuck plant's damping ratio, needs the inertia being read, and the
    # built-in default is another machine's; imported here, as the refinement below is, so
    # that importing the fit does not load the optimiser
    from .refine import STUCK_DAMPING_RATIO, sigma1_at_damping_ratio, sigma1_at_data_scale

    reading_sigma1 = None if given["sigma1"] else sigma1_at_data_scale(p.stribeck, levels)
    from .diagnose import recording_inertia  # the diagnosis owns eq. (8)'s reading of a record

    inertia_notes = [recording_inertia(r) for r in recordings]
    p, inertia_sd = _with_inertia(p, recordings, inertia_notes, given["inertia"], held, notes, kept_from["inertia"],
                                  reading_sigma1)
    if not given["sigma1"] and not any(pr.friction is not None for pr in preps):
        # friction taken from an applied force alone (eq. (8)): the refinement below does not
        # estimate σ1 (force ramps do not determine it) but simulates with it, and so does the
        # diagnosis: hold it at the stuck plant's scale, not at the paper's robot joint's
        s1 = sigma1_at_damping_ratio(p.transition_curve, p.inertia)
        held["sigma1"] = (f"not estimated by this fit: held at {s1:.4g}, 2ζ·√(K0·I) with ζ = {STUCK_DAMPING_RATIO:g}, "
                          f"a damping ratio of the stuck plant (K0 = {p.transition_curve.initial_stiffness():.4g}, the "
                          f"slope of F_d at 0; I = {p.inertia:.4g}), not at the built-in {p.sigma1:.4g}, another "
                          f"machine's (give --params with this machine's)")
        p = p.replace(sigma1=s1)
    held.setdefault("sigma1", f"not estimated by this fit: kept {kept_from['sigma1']}")

    unc = {} if inertia_sd is None else {"inertia": inertia_sd}
    widened = {}  # "stribeck.<side>.<name>" -> √(χ²/dof) its σ were widened by
    misfit_notes = {}  # side -> its misfit note, with {said} for what became of its σ
    for side, dec in decisions.items():
        if dec.fit is not None:
            # where the form misfits its levels (slow holds that stick and slip, a drift or a load
            # along the sweep, a contact whose S(v) is not eq. (7)'s shape), the noise's σ would
            # claim what the form does not give: they are widened by √(χ²/dof)
            scale, sds = misfit_scale(dec.fit), widened_stderr(dec.fit)
            for k in NAMES:
                path = f"stribeck.{side}.{k}"
                if path not in held:
                    unc[path] = sds[k]
                    if scale > 1.0:
                        widened[path] = scale
            notes.extend(f"{side}: {m}" for m in dec.fit.notes)
            notes.append(f"{side} side: {dec.model}")
            notes.extend(filter(None, [form_untested(side, dec)]))
            if scale > 1.0:
                # (said after the refinement, which may replace these σ by its own: below)
                misfit_notes[side] = (scale, f"{side} side: this form misfits the levels (χ² = {dec.fit.chi2:.3g} for "
                                      f"{dec.fit.dof} degrees of freedom, p < {MISFIT_P:g}): its σ "
                                      f"{{said}}; see the levels against the curve"
                                      + misfit_in_time(levels, dec.fit, 1 if side == "positive" else -1))
    if tfit is not None:
        for i in range(1, len(tfit.F)):
            unc[f"transition_curve.F.{i}"] = float(tfit.stderr[i])
        if tfit.n_stderr is not None:
            unc["n"] = tfit.n_stderr

    # the refinement starts from this fit's σ (a parameter it cannot move keeps them)
    res = FitResult(p.replace(uncertainty=unc), stribeck_fit, tfit, levels, n_br, notes, datasets,
                    {pr.source: pr.th for pr in preps}, held, decisions, branches_tried=tried,
                    warnings=force_like_friction(recordings, inertia_notes) + over_loads(preps) + springs_in(preps))
    if refine:
        try:
            from .refine import refine_fit

            say(0.7, "output-error refinement: trying")
            res = refine_fit(res, preps, sigma1_given=given["sigma1"])
            if not (res.refinement or {}).get("done"):
                say(0.95, "output-error refinement: not done (the report says why)")
            elif (chi2_red := res.refinement.get("chi2_reduced", 1.0)) > MISFIT_CHI2_RED:
                # the σ are (JᵀJ)⁻¹ scaled by χ²/dof: that counts the residuals as independent,
                # which a misfit of the curve's shape, repeated at every reversal, is not — two
                # controls of a guideway made apart read one knot 184.55 ± 0.21 and 173.48 ± 0.11
                res.notes.append(f"the refined model leaves χ²/dof = {chi2_red:.3g} (its RMS {math.sqrt(chi2_red):.3g} × "
                                 f"the noise floor): the σ are scaled by that, but still count the residuals as "
                                 f"independent, and a misfit of the model's shape that repeats at every reversal is "
                                 f"not — two recordings of one machine may differ by many of these σ (`diagnose "
                                 f"--params` tells what the gap is made of)")
        except ImportError:
            res.refinement = {"done": False, "reason": "output-error refinement is not available in this version"}
    else:
        res.refinement = {"done": False, "reason": "skipped (--no-refine)"}
    # in the recordings' units (written into the parameters only below): a stage in m and N read "N*m"
    units = units_of_recordings(recordings)
    # the σ written: the refinement's where it was kept, else the Markov ones (widened where the
    # form misfits); a value whose widened σ is over half of it is held, not written with it
    final_unc = {**unc, **res.params.uncertainty} if res.refinement.get("done") else unc
    still = {k: w for k, w in widened.items() if final_unc.get(k) == unc[k]}
    loose = undetermined_once_widened(res.params, final_unc, still)
    if loose:
        res.held.update(loose)
        final_unc = {k: v for k, v in final_unc.items() if k not in loose}
    for side, (scale, said) in misfit_notes.items():
        mine = [k for k in widened if k.startswith(f"stribeck.{side}.")]
        kept = [k for k in mine if k in still]
        res.notes.append(said.replace("{said}", (
            f"are widened by √(χ²/dof) = {scale:.3g}, beyond the levels' noise" if len(kept) == len(mine) else
            f"({', '.join(k.rsplit('.', 1)[1] for k in kept)}) are widened by √(χ²/dof) = {scale:.3g}, beyond the "
            f"levels' noise; the others are the refinement's" if kept else
            f"are the refinement's (the levels' widened by √(χ²/dof) = {scale:.3g} are replaced)")))
    in_units = res.params.replace(units=units, uncertainty=final_unc)
    if tfit is not None and (said := curve_coverage(in_units, min(branch_ends, default=np.inf))):
        res.notes.append(said)  # of the curve written (the refinement moves its knots' F_d)
    if tfit is not None and (said := curve_continued(in_units)):
        res.notes.append(said)
    if said := direction_asymmetry(in_units):
        res.notes.append(said)

    cost = {}
    if any(d.fit is not None for d in decisions.values()):
        cost["markov_chi2"] = {k: d.fit.chi2 for k, d in decisions.items() if d.fit is not None}
        cost["markov_dof"] = {k: d.fit.dof for k, d in decisions.items() if d.fit is not None}
    if tfit is not None:
        cost["ml_negative_log_likelihood"] = tfit.nll
    prov = {
        "data": [r.source for r in recordings],
        "estimator": "Markov (weighted least squares) for S(v); maximum likelihood for the transition curve",
        "noise_models": {d.name: repr(d.noise) for d in datasets},
        "cost": cost,
        "held": dict(res.held),
        "thresholds": {src: {k: (float(v) if isinstance(v, (float, np.floating)) else v) for k, v in th.values().items()}
                       for src, th in res.thresholds.items()},
        "refinement": {k: v for k, v in res.refinement.items() if isinstance(v, (bool, int, float, str))},
        "date": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
    }
    say(1.0, "done")
    res.params = res.params.replace(uncertainty=final_unc, provenance=prov, units=units).validate()
    return res


def undetermined_once_widened(p: FrictionParams, unc: dict, widened: dict) -> dict:
    """The S(v) entries whose σ, widened by their side's misfit (``widened``: path → √(χ²/dof)),
    exceed half the value: not determined by the levels in this form, so held at the Markov
    fit's value with the reason ({path: why}) rather than written as an estimate (a hydraulic
    cylinder whose load swung ±50 % through its sweep, χ²/dof 2,290: δ 1.31 ± 1.73)."""
    out = {}
    for path, scale in widened.items():
        _, side, name = path.split(".")
        value = getattr(getattr(p.stribeck, side), name)
        if unc[path] > 0.5 * abs(value):
            out[path] = (f"not determined by the levels in this form: its σ {unc[path]:.3g}, widened by √(χ²/dof) = "
                         f"{scale:.3g} for the form's misfit, is over half the value; held at the Markov fit's value")
    return out


CURVE_COVERS = 0.5  # a transition curve topping below this share of F_s⁺ − F_s⁻ is said to stop short


def curve_continued(p: FrictionParams) -> str:
    """A note where the model evaluates the curve written through one more knot than the file
    holds (``model.params.reaching_knots``: its last segment too flat to reach the outer loop's
    span by ``REACH_WITHIN`` times its last knot), or ""."""
    tc = p.transition_curve
    if tc.kind != "piecewise_linear" or len(tc.z) < 2:
        return ""
    z, F = reaching_knots(tc.z, tc.F, p.outer_loop_span)
    if len(z) == len(tc.z):
        return ""
    unit = f" {p.units.force}" if p.units.force else ""
    return (f"transition curve: its last segment ({tc.F[-2]:.4g} → {tc.F[-1]:.4g}{unit}) is too flat to reach the outer "
            f"loop's span {F[-1]:.4g}{unit} (S(v) − F_b in sliding) by {REACH_WITHIN:g} times its last knot; the model goes on through "
            f"({z[-1]:.3g}, {F[-1]:.4g}) so that sliding settles (README, the model's choices: transition curves) — "
            f"not an estimate: the branches end before it")


def curve_coverage(p: FrictionParams, v_end: float) -> str:
    """A note where the fitted transition curve tops out below CURVE_COVERS of the outer loop's
    span F_s⁺ − F_s⁻ (the force F_d climbs towards over presliding: Table II's 100 N·m against
    Table I's 36 + 63), or "": beyond its last knot the last segment's slope goes on (or the
    slope that reaches the span at 20 times the last knot, ``model.params.reaching_knots``),
    stiffer than a curve bending into sliding. ``v_end``: the speed at which a branch was ended (0.3 ×
    the slowest steady level), said because a position loop's presliding sines pass it — a
    joint made apart had its curve stop at 0.168 mrad and 8.5 N·m of a 32 N·m span, its
    sines reaching 4 mrad, and nothing said."""
    tc = p.transition_curve
    span = p.stribeck.positive.Fs - p.stribeck.negative.Fs
    if tc.kind != "piecewise_linear" or not tc.F or not span > 0 or tc.F[-1] >= CURVE_COVERS * span:
        return ""
    unit = p.units.force
    ends = (f"; a branch ends where its speed passes {v_end:.3g} {p.units.position}/{p.units.time} (0.3 × the slowest steady level), and "
            f"presliding moved faster (a position loop's sines) is not read as one" if math.isfinite(v_end) else "")
    return (f"transition curve: its knots reach F_d = {tc.F[-1]:.4g}{(' ' + unit) if unit else ''} at z = {tc.z[-1]:.3g}, "
            f"{tc.F[-1] / span:.0%} of F_s⁺ − F_s⁻ ({span:.4g}), towards which F_d climbs over presliding: beyond, its "
            f"last segment's slope goes on (or, if that reaches the span only past {REACH_WITHIN * tc.z[-1]:.3g}, the slope that "
            f"reaches it there), stiffer than a curve bending into sliding, so wider presliding is not "
            f"estimated{ends}")


ASYMMETRY_SIGMAS = 3.0  # sides' Coulomb levels whose sizes differ by more σ than this are said to


def direction_asymmetry(p: FrictionParams) -> str:
    """A note where |F_c⁺| and |F_c⁻| differ by over ASYMMETRY_SIGMAS σ, or "". A friction that
    depends on the direction does this, and so does an offset c of the force signal, which is not
    part of the model: it adds c to the friction read both ways, so |F_c⁺| − |F_c⁻| = 2c, and
    |F_s⁺| − |F_s⁻| the same 2c. The levels cannot tell the two apart, so both are said, with
    whether the F_s agree with an offset (a belt axis made apart, its current read with an
    offset, came out asymmetric and nothing was said)."""
    diff = {}
    for k in ("Fc", "Fs"):
        sd = [p.uncertainty.get(f"stribeck.{side}.{k}") for side in ("positive", "negative")]
        if None not in sd:
            diff[k] = (abs(getattr(p.stribeck.positive, k)) - abs(getattr(p.stribeck.negative, k)), math.hypot(*sd))
    if "Fc" not in diff:
        return ""
    d, sd = diff["Fc"]
    if not (sd > 0 and abs(d) > ASYMMETRY_SIGMAS * sd):
        return ""
    unit = f" {p.units.force}" if p.units.force else ""
    alike = ""
    if "Fs" in diff:
        ds, sds = diff["Fs"]
        agree = abs(ds - d) <= 2.0 * math.hypot(sd, sds)
        alike = (f"; |F_s⁺| − |F_s⁻| = {ds:.3g} ± {sds:.2g}{unit}, "
                 + ("as an offset would make it too" if agree else "which an offset alone would make equal to it"))
    return (f"S(v): |F_c⁺| − |F_c⁻| = {d:.3g} ± {sd:.2g}{unit} ({abs(d) / sd:.0f} σ): a friction that differs by "
            f"direction does this, and so does an offset of {d / 2:.3g}{unit} in the force signal (not part of the "
            f"model, it adds to the friction read both ways){alike}; the force read at rest with the drive off tells "
            f"them apart")


MISFIT_CHI2_RED = 4.0  # a refinement leaving its residuals twice the noise floor: its σ are said to be of a misfit


def to_its_sd(value: float, sd: float) -> str:
    """``value`` written to the digit its σ's second significant digit reaches (at least four
    significant digits, at most ten), trailing zeros kept: 0.054 ± 5.2e-06 is "0.0540000",
    where a plain 4-digit form wrote "0.054", as if it were known to two digits."""
    if not (math.isfinite(value) and math.isfinite(sd)) or sd <= 0 or value == 0:
        return f"{value:.4g}"
    digits = math.floor(math.log10(abs(value))) - math.floor(math.log10(sd)) + 2
    return f"{value:#.{min(max(digits, 4), 10)}g}".rstrip(".")


def dropped_knots(z: np.ndarray, drop: list, refit, notes: list, why: str):
    """The knots ``z`` without those at ``drop`` (the data do not determine them: ``why`` is
    noted) and the transition curve ``refit`` on the rest."""
    notes.append(why)
    z = np.delete(z, drop)
    return z, refit(z)


def force_like_friction(recordings: list[Recording], inertia_notes: list) -> list[str]:
    """One line per recording whose column read as the applied force looks like measured
    friction (``diagnose.recording_inertia``'s ``like_friction``, one ``InertiaNote`` per
    recording in ``inertia_notes``): no inertial term (I·ẍ of eq. (8)) in it, as measured
    friction has none, unless the column's name says it is applied. The whole fit took it as
    applied, which a note alone had not made plain (a rig's torque sensor, named `torque`, read
    so: its transition curve not resolved, the paper's held, and a 20 % drift lost in the noise
    floor that curve made)."""
    from .diagnose import NAME_IT_FRICTION

    out = []
    for r, said in zip(recordings, inertia_notes):
        like = said.like_friction
        if like is None:
            continue
        col = r.columns.get("force", "force")
        # no inertial term found at all, or one read but not told from 0 (a slow rig's applied
        # torque may be that too: said as a doubt, not as a finding)
        found = "the inertial term read in it is not told from 0" if like.doubt else "it carries no inertial term"
        load = ("; or friction following the normal load hides that term (`diagnose` tells whether the load is an "
                "effect)" if like.load_span is not None else "")
        out.append(f"{r.source}: column {col!r} was read as the applied force, but {found} (I·ẍ, eq. (8)) — "
                   f"measured friction carries none: {NAME_IT_FRICTION}, and fit again{load}")
    return out


def springs_in(preps: list[Prepared]) -> list[str]:
    """One line per recording whose column rises along the travel whichever way the motion
    goes (``diagnose.travel_spring`` on the column itself, in its steady runs: at a steady speed
    S(v) is one value, which each run's offset takes, so no model enters): a spring, a gas
    spring's counterbalance, gravity near one angle, which the model has no term for. Its levels
    then sit wherever each run lies on the spring (a vertical axis made apart, a 3 kN/m gas
    spring over 260 mm beside 120 N of friction: F_c⁺ 89.6 ± 20 N, levels from 0.17 to 369 N,
    a presliding range of 110 mm, and nothing said)."""
    from .diagnose import AlongTravel, travel_spring

    out = []
    for pr in preps:
        col = pr.friction if pr.friction is not None else pr.force
        if col is None:
            continue
        steady = np.zeros(len(col), dtype=bool)
        for a, s0, e0 in steady_runs(pr):
            steady[a + s0:a + e0] = True
        acc = np.zeros_like(pr.velocity)
        for a, b in pr.chunks:
            if b - a >= 3:
                acc[a:b] = np.gradient(pr.velocity[a:b], pr.rec.time[a:b])
        ts = travel_spring(AlongTravel(pr.rec.position, pr.velocity, pr.th.v_floor, acc, pr.rec.time), col,
                           steady & pr.usable)
        if ts is None or not ts.shown:
            continue
        what = "friction" if pr.friction is not None else "force"
        fu, pu = pr.rec.units.get(what, ""), pr.rec.units.get("position", "")
        out.append(f"{pr.source}: the {'friction' if what == 'friction' else 'applied force'} rises by "
                   f"{ts.rate:.4g} ± {ts.sd:.2g} {fu}/{pu} along the travel whichever way the motion goes "
                   f"({abs(ts.rate) * ts.span:.3g} {fu} over the {ts.span:.3g} {pu} of its steady runs, beside a "
                   f"median |{what}| of {np.median(np.abs(col[steady])):.3g} {fu} there): a spring, a counterbalance, gravity "
                   f"near one angle, which the model has no term for — S(v)'s levels sit wherever each run lies on "
                   f"it; write the column less it (`diagnose` reads it again beside the model)")
    return out


def over_loads(preps: list[Prepared]) -> list[str]:
    """One line per recording whose normal load was not held at one plateau, so that every
    sample entered and S(v) and the transition curve average over its loads
    (``segment.prepare``'s ``load_range``): the parameters are no load's own, which the S(v)
    table does not show (a guide made apart, its load ramped 1.0–3.5 kN with friction ∝ N^0.7,
    read F_c⁺ 9.29 N for 18 at 2 kN, σ2⁺ 365 N·s/m for 60, exit 0 and a note among many)."""
    out = []
    for pr in preps:
        if pr.load_range is not None:
            lo, hi = pr.load_range
            unit = pr.rec.units.get("normal_load", "N")
            out.append(f"{pr.source}: the normal load ranges {lo:.4g}–{hi:.4g} {unit}, held at no one plateau: S(v) and "
                       f"the transition curve are averaged over the loads, no load's own — a diagnosis with these "
                       f"parameters fits friction following the load (normal_load) where it does, and writes S(v) at "
                       f"one load")
    return out


def _with_inertia(p: FrictionParams, recordings: list[Recording], inertia_notes: list, from_file: bool, held: dict,
                  notes: list, start: str, reading_sigma1: float | None = None) -> tuple[FrictionParams, float | None]:
    """Eq. (8)'s inertia I, read from the recordings that log an applied force
    (``diagnose.recording_inertia``: the force regressed on the mean acceleration beside a free
    steady curve while sliding steadily, no model entering; ``inertia_notes``, one per
    recording, are its readings). Written with its σ where it is
    usable (σ under a quarter of the value; several recordings pooled by inverse variance) and
    no parameter file was given: the built-in default is another machine's. A file's inertia
    is kept (a value from the drawings is usually better than a regression on a log), and the
    notes say what the recording reads. Without a file and without a usable reading, it is held
    at the data's own reading where there is one (``_held_inertia``: ``reading_sigma1`` is the
    σ1 of the model read beside), else at the built-in default; named as held either way."""

    from .diagnose import inertia_ceiling

    reads, loose = [], []  # usable readings; readings too uncertain to write as an estimate
    for r, (est, why, _) in zip(recordings, inertia_notes):
        if r.force is not None and r.friction is None:
            notes.append(f"{r.source}: inertia {why}")  # "inertia read as …" / "inertia not read: …"
        if est is not None:
            (reads if est.usable else loose).append(est)
    if not any(r.force is not None and r.friction is None for r in recordings):
        held["inertia"] = f"not needed: no recording takes friction from an applied force (eq. (8)): kept {start}"
        return p, None
    if not reads and not from_file:
        held_at = _held_inertia(p if reading_sigma1 is None else p.replace(sigma1=reading_sigma1), recordings, loose)
        if held_at is not None:
            value, why = held_at
            held["inertia"] = (f"{why}: held at that reading, not at the built-in default {p.inertia:.4g} (another "
                               f"machine's; give --params with this machine's)")
            return p.replace(inertia=value), None
    if not reads and not from_file:
        ceilings = [c for r in recordings if (c := inertia_ceiling(r)) is not None]
        if ceilings and min(ceilings) < p.inertia:
            # the built-in default is another machine's: where the force could not accelerate it as
            # the record moves, it is no value for this one (a haptic joint made apart, 2·10⁻⁴
            # kg·m², had 5 held, and σ1 derived from it 150 times its own)
            value = min(ceilings)
            held["inertia"] = (f"not determined by the recordings (see the notes); the built-in default {p.inertia:.4g} "
                               f"is more than the applied force's span can accelerate as this record does: held at "
                               f"that ceiling, {value:.4g} — an upper bound, not an estimate (give --params with this "
                               f"machine's)")
            return p.replace(inertia=value), None
    if not reads:
        held["inertia"] = f"not determined by the recordings (see the notes): kept {start}"
        return p, None
    value, sd, agree = _pooled(reads)
    if not agree:
        held["inertia"] = (f"the recordings read {', '.join(f'{e.value:.4g} ± {e.stderr:.2g}' for e in reads)}, "
                           f"which disagree beyond their σ: kept {start}")
        return p, None
    if from_file:
        off = abs(value - p.inertia) / sd
        held["inertia"] = (f"kept from the parameters the fit started from ({p.inertia:.4g}); the recordings read "
                           f"{value:.4g} ± {sd:.2g}" + (f", {off:.1f} σ from it" if off > 3 else ""))
        return p, None
    notes.append(f"inertia {value:.4g} ± {sd:.2g} read from the applied force (eq. (8)), replacing the built-in "
                 f"default {p.inertia:.4g}")
    return p.replace(inertia=value), sd


def _held_inertia(p: FrictionParams, recordings: list[Recording], loose: list) -> tuple[float, str] | None:
    """The value eq. (8)'s inertia is held at where the force regressed on the acceleration
    alone gives no usable reading, and why: the model-free readings too uncertain to write,
    where there are any and they stand 2 σ clear of 0 (noisy, but no model enters them); else
    the reading beside the model just fitted (``diagnose.inertia_beside_model``), where each
    recording gives one with σ under a quarter of it and they agree; else None (the built-in
    default stays). Not an estimate: noise enters the first, and a misfit of the model that
    follows the acceleration the second (on the robot joints of ``synth/elsewhere.py``, whose
    curve the fit holds, it read 8–35 % high). On the turntable of ``synth/turntable.py`` (0.035 kg·m²), whose every speed is reached
    through a reversal, the model-free windows disagree and the second read 0.0373, where the
    built-in default, the paper's robot joint's, is 5. ``p`` is the model read beside: with the
    built-in σ1 (1500, in the turntable's N·m·s/rad) its damping alone left a gap a thousand
    times the friction there, and no reading."""
    if loose:
        value, sd, _ = _pooled(loose)
        if value > 2.0 * sd:  # a reading within 2 σ of nothing says nothing of the scale
            return value, (f"read as {value:.4g} ± {sd:.2g} from the applied force, too uncertain to write as an "
                           f"estimate (σ over a quarter of the value)")
    from .diagnose import inertia_beside_model

    beside = [inertia_beside_model(r, p) for r in recordings if r.force is not None and r.friction is None]
    if beside and all(e is not None and e.usable for e in beside):
        value, sd, agree = _pooled(beside)
        if agree:
            return value, (f"no usable reading from the applied force alone (notes); beside the model fitted here it "
                           f"reads {value:.4g} ± {sd:.2g}, which a misfit of the model that follows the acceleration "
                           f"would enter too")
    return None


def _pooled(reads: list) -> tuple[float, float, bool]:
    """Inverse-variance mean of inertia readings, its σ, and whether they agree within their σ
    (a χ² of the spread beyond MISFIT_P)."""
    values = np.array([e.value for e in reads])
    w = 1.0 / np.maximum(np.array([e.stderr for e in reads]), 1e-9 * values) ** 2
    value = float(np.sum(w * values) / np.sum(w))
    spread = float(np.sum(w * (values - value) ** 2))
    agree = len(reads) < 2 or chi2_dist.sf(spread, len(reads) - 1) >= MISFIT_P
    return value, float(1.0 / math.sqrt(np.sum(w))), agree


def _held_value(params: FrictionParams, path: str) -> str:
    """" = value" of a held scalar parameter at a dotted path (nothing for a whole curve)."""
    v = get_value(params, path)
    return f" = {v:.4g}" if isinstance(v, (int, float)) else ""


def fit_report(res: FitResult) -> str:
    """Thresholds, Table I / Table II style summary (held values marked), correlations above
    0.5, held parameters with reasons, and what was assumed."""
    lines = ["[[Thresholds (derived from each recording; override with --threshold name=value)]]"]
    for src, th in res.thresholds.items():
        lines.append(f"    {src}:")
        lines.extend(f"        {ln}" for ln in th.lines())
    lines.append("[[Fit statistics]]")
    u = res.params.units
    lines.append(f"    units                    : position {u.get('position')}, force {u.get('force')}, time {u.get('time')}")
    if res.levels is not None:
        lines.append(f"    levels of S(v)           : {len(res.levels.velocity)}")
    lines.append(f"    presliding branches used : {res.n_branches}"
                 + (f" ({res.branches_tried} entered the likelihood, which did not determine the curve from them: see "
                    f"the notes)" if res.branches_tried and not res.n_branches else ""))
    for side, dec in res.decisions.items():
        if dec.fit is not None:
            lines.append(f"    Markov chi2 ({side})  : {dec.fit.chi2:.3g} for {dec.fit.dof} degrees of freedom ({dec.model})")
    lines.append("[[S(v), eq. (7) — Table I form]]")
    lines.append(f"    {'parameter':10s} {'positive velocity':>24s} {'negative velocity':>24s}   unit")
    unc = res.params.uncertainty
    for k in NAMES:
        cells = []
        for side in ("positive", "negative"):
            val = getattr(getattr(res.params.stribeck, side), k)
            path = f"stribeck.{side}.{k}"
            cells.append(f"{val:>12.4g} (held)   " if path in res.held else
                         f"{to_its_sd(val, unc.get(path, float('nan'))):>12s} ± {unc.get(path, float('nan')):<9.2g}")
        # the unit from the parameter schema, in the units of the data (N·m or N, rad/s or m/s, …)
        lines.append(f"    {k:10s} {cells[0]} {cells[1]}   {spec_of(res.params, f'stribeck.positive.{k}').unit}")
    # the χ² above and the correlations below are the Markov step's: where the refinement moved
    # S(v), its values are given beside them (a valve's report read χ² 140 for 11 and "misfits
    # the levels" beside refined values whose fit to the levels was not given)
    moved = [f"{side} " + ", ".join(f"{k} {v:.4g}" for k, v in dec.fit.values.items())
             for side, dec in res.decisions.items() if dec.fit is not None
             and any(not math.isclose(v, getattr(getattr(res.params.stribeck, side), k), rel_tol=1e-9)
                     for k, v in dec.fit.values.items())]
    if moved:
        lines.append("    (the output-error refinement's values; the Markov chi2 above, the correlations and the notes "
                     f"on the levels are of the Markov step's: {'; '.join(moved)})")
    corr_lines = []
    for side, dec in res.decisions.items():
        if dec.fit is None:
            continue
        C = dec.fit.correlation
        for i in range(5):
            for j in range(i + 1, 5):
                if abs(C[i, j]) > 0.5:
                    corr_lines.append(f"    {side:8s} C({NAMES[i]}, {NAMES[j]}) = {C[i, j]:+.3f}")
    if corr_lines:
        lines.append("[[Correlations (|C| > 0.5)]]")
        lines.extend(corr_lines)
    if res.levels is not None and len(res.levels.velocity):
        lines.extend(_level_lines(res))
    tf = res.transition_fit
    if tf is not None:
        lines.append("[[Transition curve F_d — Table II form]]")
        zu, Fu = (spec_of(res.params, f"transition_curve.{c}.1").unit for c in "zF")
        lines.append(f"    {'z (' + zu + ')':>12s} {'F_d(z) (' + Fu + ')':>12s}")
        for i, (z, F) in enumerate(zip(res.params.transition_curve.z, res.params.transition_curve.F)):
            err = f" ± {unc.get(f'transition_curve.F.{i}', float('nan')):.2g}" if i else "   (fixed)"
            lines.append(f"    {z:>12.4g} {to_its_sd(F, unc.get(f'transition_curve.F.{i}', float('nan'))) if i else '0':>12s}{err}")
        lines.append(f"    n = {res.params.n:g}" + (f" ± {unc['n']:.2g}" if "n" in unc else " (held)"))
    if "sigma1" in unc:
        lines.append("[[Micro-viscous damping σ1, eq. (3) — from the output-error refinement]]")
        lines.append(f"    σ1 = {res.params.sigma1:.4g} ± {unc['sigma1']:.2g} {spec_of(res.params, 'sigma1').unit}")
    if "inertia" in unc:
        lines.append("[[Inertia, eq. (8) — from the applied force]]")
        lines.append(f"    I = {res.params.inertia:.4g} ± {unc['inertia']:.2g} {spec_of(res.params, 'inertia').unit}")
    if res.refinement:
        lines.append("[[Output-error refinement]]")
        rf = res.refinement
        if rf.get("done"):
            lines.append(f"    RMS residual {rf['rms_before']:.4g} -> {rf['rms_after']:.4g} ({rf.get('what', '')})")
            if "cost_before" in rf:
                lines.append(f"    kept on its cost, {rf['cost_before']:.4g} -> {rf['cost_after']:.4g} "
                             + (f"(soft L1 beyond {rf['robust_scale']:g} noise σ: a few residuals that grew "
                                f"weigh little)"
                                if rf.get("loss") == "soft_l1" else "(½ Σ r²)")
                             + ", at least 10 % lower, and every experiment's RMS 10 % lower")
        else:
            lines.append(f"    not done: {rf.get('reason', '')}")
    if res.held:
        lines.append("[[Held parameters (not estimated) and why]]")
        lines.extend(f"    {k}{_held_value(res.params, k)}: {why}" for k, why in res.held.items())
    if res.notes:
        lines.append("[[Notes]]")
        lines.extend(f"    {m}" for m in res.notes)
    return "\n".join(lines)
