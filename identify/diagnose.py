"""The discrepancy workflow: compare where the data are informative, name an effect only on
out-of-sample evidence, add it, refit, look again.

1. **Compare** (``comparison_of``), in friction. A recording with measured friction and a
   prescribed motion is compared in that friction; a recording with an applied force, in the
   friction taken from eq. (8) in integral form — the force averaged over L samples minus
   I·Δv/T across the window (``friction_from_force``), with the inertia read from the
   recording when the parameter file's is off (``inertia_from_force``). The model is driven
   along the recorded path, smoothed to the scale of its noise or encoder step (quantisation
   is a measurement, not motion), and averaged like the measurement. ``space="position"``
   keeps an output-error comparison in position (the plant simulated from the applied force
   in short windows). The hysteresis memory at the start of the record is not assumed
   (``initial_memory``: the first curve is left out, a constant left free until the first
   gross sliding). The noise floor — the log's, and what the position noise carries through
   the model — is estimated from the recording and printed, regime by regime.
2. **The alternative** every effect must beat: the current model with its level g,
   presliding stiffness κ0, n, σ1, S(v) levels and — where that leaves the model alone
   clearly closer to the record — the rise of each segment of a piecewise-linear transition
   curve refitted (``refit_transition``: first as the model alone, then from there), beside a
   free steady curve (``FreeSteadyCurve``: any correction to S(v), a
   level of its own at rest, and for friction taken from an applied force a free inertia),
   which is linear and profiled out of every evaluation. A stiffness effect's alternative also
   holds a stiffness varying with speed, one varying with the travel of the stroke before and,
   beside a friction effect already in the model, a presliding range following that effect
   (``stiffness_alternative``, never named).
3. **Candidates** (``model.effects.EFFECTS``): each is screened (its shape parameter — time
   constant, wavelength from the spectrum of the residual against position, reversal count —
   chosen on a grid with the amplitude solved by a secant step), then fitted with the level by
   least squares through ``model.effects`` itself; a softening once for each back-travel that
   may count as its reversal (``Settings.softening_thresholds``, 6 by default;
   ``softening_thresholds``, ``fit_candidate``) is screened, the SOFTENING_FITTED best fitted,
   the best of them written, and chosen again on the training blocks of every fold of the
   cross-validation. A drift and a load are judged twice, as eq. (3) scales them and with a
   presliding range following them (``range_alternative``), and the one that passes is kept.
4. **Out-of-sample decision.** Blocked cross-validation over time: the record is cut into
   ``folds·blocks_per_fold`` contiguous blocks, dealt round-robin to ``folds`` folds; the
   alternative and each candidate are refitted on the other folds and scored on the held-out
   one. A candidate is named only if it lowers the held-out error in most of the folds where
   it changes the prediction at all, and the pooled held-out RMS by ``min_gain`` — over the
   record and where its physics shows (steady gross sliding for a friction factor, the
   transitions after reversals for a stiffness effect). A BIC with the effective number of
   samples is reported as a second line. A candidate whose saturation scale ends at either
   bound (a softening's n_c: at most half the reversals where the strokes run in order of
   speed, all of them elsewhere, ``softening_nc_max``) has not been seen to settle within the
   session, nor is a drift whose τ ends at either bound or whose b ends at a bound (a step
   at the session's start, a straight trend), nor a softening whose h does (a change the
   range holds, not the data): it is listed as
   seen, not named (``Term.unsettled``; ``Settings.must_settle``, the default: over the
   hidden-effect suite on two seed sets, with the oracle and the fitted base, naming it put a
   false softening on 15 of 80 controls, requiring it on 2). Where the strokes' speeds do not
   follow the reversals (``stroke_order``) the upper bound is still a reason: a stiffness that
   changes with time makes the same trend there (naming it anyway named a stiffness falling
   linearly in time "cyclic_softening" on two of three tribometers).
5. **Confounding.** Two passing candidates whose corrections are alike (correlation above
   ``confound_corr``) and neither of which predicts clearly better out of sample are reported
   as confounded — each one's evidence and the experiment that would separate them — and
   neither is named. So are two whose corrections are unlike (a drift's in the sliding, a
   softening's in the transitions) where the one not named, not clearly beaten, gains nothing
   held out beside the winner in the next round: the naming is then taken back.
6. **Several effects.** Name, add, refit all together, look again, until nothing passes; the
   gap after every step is kept. The model written (``written_fits``) is, at every step, the
   model as given with n, σ1, the S(v) levels, the curve's segments, g, κ0 and that step's
   effects refitted to the recording alone, without the free steady curve (beside a free
   inertia for friction taken from an applied force, which is not written). An effect named
   last that removes under half of ``min_gain`` of that model's gap (``own_gain``: its
   amplitudes at no effect, ``Effect.without``, everything else as fitted) is not named: what
   it explained beside the free curve, the refitted base explains (``Diagnosis.unused``).
"""

from __future__ import annotations

import dataclasses
import math
import os
import re
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from time import perf_counter
from typing import NamedTuple

import numpy as np
from scipy.optimize import least_squares, minimize_scalar
from scipy.ndimage import uniform_filter1d
from scipy.signal import savgol_filter
from scipy.stats import rankdata
from numba import njit

from ..model import (FrictionParams, SteadyAlong, Stribeck, StribeckSide, TransitionCurve, friction_along,
                     simulate_displacement, steady_along)
from ..model.errors import ParameterError
from ..model.params import get_value
from ..model.simulate import stribeck_curve
from ..model.effects import EFFECTS, Context, Signals, effect_scales, follows_friction, format_values, significant_reversals
from .data import DataError, Recording, header_unit, is_mass, may_be_load
from .errors import IdentificationError
from .segment import (GRID_UNDER_NOISE, across_gaps, checked_threshold, gap_threshold, gross_sliding_mask, piecewise_slope,
                      speed_levels, steady_velocity_mask, time_gaps)
from .threads import one_blas_thread


INFORMATIVE = 0.01  # a held-out fold counts if the candidate moves its SSE by this fraction

# ---------------------------------------------------------------- settings (all relative)
@dataclass(frozen=True)
class Settings:
    folds: int = 5
    blocks_per_fold: int = 20
    min_gain: float = 0.03  # pooled held-out RMS must fall by this fraction
    confound_corr: float = 0.7  # corrections this alike explain the same residual
    tell_apart: bool = True  # two alike candidates are each judged beside the other before they are called confounded
    # a candidate passing in a round where a pair is found confounded is named only if it passes
    # beside the pair's better one too (``choose_winner``)
    beside_confounded: bool = True
    # a force along the travel, where shown (``travel_force``), is taken out of the friction
    # compared before the candidates are judged
    travel_force_out: bool = True
    clear_margin: float = 0.25  # the better of two alike candidates must gain this much more (relative)
    max_effects: int = 3
    free_steady: bool = True  # the alternative holds a free correction to S(v) (FreeSteadyCurve)
    rate_nuisance: bool = True  # a stiffness effect is judged beside a stiffness varying with speed (stiffness_alternative)
    # … and beside one varying with the travel of the stroke before (stiffness_alternative). Off by
    # default: it takes a Dahl rig's false hardening away, but on the hidden-effect suite it named
    # two false softenings on controls, and it named one on a servo stage's control and beside a
    # telescope mount's load, recordings made apart (README, "Where it stands")
    travel_nuisance: bool = False
    range_nuisance: bool = True  # … and, beside a friction effect, a presliding range following it (stiffness_alternative)
    range_with_friction: bool = True  # a drift or a load is judged also with a presliding range following it (range_alternative)
    refit_curve: bool = True  # the alternative reshapes a piecewise-linear F_d segment by segment (refit_transition)
    space: str = "friction"  # "position": a force-driven recording compared by output error in position
    must_settle: bool = True  # an effect with a saturation scale is named only if seen to settle (``Term.unsettled``)
    # back-travels tried as a softening's reversal: min_excursion × 1, 2, 4 … (``softening_thresholds``);
    # 1 tries min_excursion alone. All are screened and the SOFTENING_FITTED best fitted, so six
    # cost the speed benchmark's robot joint about 4 s over one (README: speed)
    softening_thresholds: int = 6
    # nothing named: write the base refitted alone (the model written's refit of the level, the
    # stiffness, n, σ1, S(v) and the curve's segments) instead of the file as given
    refit_base: bool = False
    # the user's settings of the motion reading's thresholds, as (name, value) pairs
    # (``reading_overrides``; `diagnose --threshold`): the rest derived from the recording
    reading: tuple = ()
    candidates: tuple = tuple(n for n in EFFECTS if EFFECTS[n].acts_on == "friction" or n == "cyclic_softening")


# ---------------------------------------------------------------- the comparison
@dataclass
class Comparison:
    """What is compared, where, and how noisy it is (everything derived from the recording)."""

    space: str  # "friction" or "position"
    time: np.ndarray
    measured: np.ndarray
    path: np.ndarray  # the smoothed position (the displacement drive / the context)
    velocity: np.ndarray  # smoothed velocity
    load: np.ndarray | None
    force: np.ndarray | None
    noise: float  # noise floor of ``measured`` in its units
    position_noise: float
    window: int  # savgol window (samples) used to smooth the path
    min_excursion: float  # back-travel that counts as a significant reversal
    v_rest: float  # |v| below this counts as presliding / sticking
    windows: list = field(default_factory=list)  # position space: (start, end) sample ranges
    notes: list = field(default_factory=list)
    flipped: bool = False
    z_presliding: float = 0.0  # the model's presliding range (position units)
    params: FrictionParams | None = None  # the model the comparison was set up for
    average: int = 1  # friction from an applied force: predictions averaged over this many samples too
    acceleration: np.ndarray | None = None  # friction from an applied force: the mean acceleration used
    scored: np.ndarray | None = None  # samples compared (None: all); see ``initial_memory``
    memory_offset: np.ndarray | None = None  # 1 where the memory still holds the log's unknown start, else 0
    raw: np.ndarray | None = None  # the logged signal the noise floor comes from (friction, or applied force)
    inertial_noise: float = 0.0  # friction from an applied force: the sd the inertial term I·Δv/T adds
    inertia: float | None = None  # friction from an applied force: the I of eq. (8) it was taken with
    input_noise: np.ndarray | None = None  # the model's friction noise from the position it is driven by
    noise_colour: float = 1.0  # the averaged log's noise over what white noise would leave (``noise_colour``)
    reading: MotionReading | None = None  # how the motion was read (its note is ``notes[0]``)
    position_unit: str = ""  # the recording's position unit, for that note

    def noise_on(self, mask: np.ndarray) -> float:
        """The noise floor from the samples of ``mask`` alone (a recording's noise need not be
        the same in every regime: a force sensor in presliding and in fast sliding, or parts
        logged by different sensors): the log's, from sample-to-sample differences of ``raw``
        through the averaging of eq. (8) (times ``noise_colour`` where that noise is not white)
        and its inertial term, and what the position noise carries through the model
        (``input_noise``, once known)."""
        if self.raw is None:
            return self.noise
        both = mask[1:] & mask[:-1]
        if both.sum() < 20:
            return float("nan")
        sd = _mad_sd(np.diff(self.raw)[both]) / math.sqrt(2.0)
        carried = float(np.mean(self.input_noise[mask] ** 2)) if self.input_noise is not None else 0.0
        return math.sqrt((sd * self.noise_colour) ** 2 / self.average + self.inertial_noise**2 + carried)

    def log_noise(self) -> float:
        """``noise_on`` over every sample, before the carried part is added."""
        return self.noise_on(np.ones(len(self.time), bool))

    def filtered(self, friction: np.ndarray) -> np.ndarray:
        """A predicted friction seen as the measurement sees it (the same moving average)."""
        return friction if self.average <= 1 else uniform_filter1d(friction, self.average, mode="nearest")

    @property
    def unit(self) -> str:
        return "force" if self.space == "friction" else "position"

    def context(self) -> Context:
        # the velocity is the smoothed slope, not the path's backward difference that
        # ``model.effects.context_of`` takes (the only effect reading it, rate_stiffness, would
        # follow the steps a smoothed encoder path still makes)
        return Context(time=self.time, position=self.path, velocity=self.velocity, load=self.load,
                       reversals=significant_reversals(self.path, self.min_excursion), min_excursion=self.min_excursion)


def _mad_sd(a: np.ndarray) -> float:
    a = a[np.isfinite(a)]
    if not len(a):
        return 0.0
    return float(1.4826 * np.median(np.abs(a - np.median(a))))


def position_noise(x: np.ndarray) -> tuple[float, float]:
    """(noise sd, quantisation step) of a measured position: the larger of the step's
    uniform-noise sd (q/√12, q the smallest common non-zero increment) and the white-noise sd
    from second differences (sd·√6 for white noise on a smooth motion)."""
    dx = np.abs(np.diff(x))
    nz = dx[dx > 1e-9 * max(float(np.ptp(x)), 1e-300)]  # not the rounding of a unit conversion
    q = 0.0
    if len(nz):
        q = float(np.min(nz))
        # a lattice: most increments are multiples of q
        if np.median(np.abs(nz / q - np.round(nz / q))) > 0.05:
            q = 0.0
    white = _blockwise_sd(np.diff(x, 2)) / math.sqrt(6.0)
    return max(q / math.sqrt(12.0), white), q


NOISE_BLOCKS = 20  # blocks a noise estimate is taken over
NOISE_QUANTILE = 75  # … and the percentile of the blocks' estimates kept


def _blockwise_sd(d: np.ndarray) -> float:
    """A robust sd of ``d`` that a quiet part of the record cannot pull down: the 75th
    percentile of the MAD estimates of 20 contiguous blocks (a prescribed motion logged
    exactly beside a sensor's noisy part would otherwise halve the noise, and the
    thresholds built on it would let the noise through as reversals)."""
    nb = min(NOISE_BLOCKS, len(d) // 200)
    if nb < 2:
        return _mad_sd(d)
    return float(np.percentile([_mad_sd(b) for b in np.array_split(d, nb)], NOISE_QUANTILE))


COLOUR_SHOWN = 1.5  # over the shortest blocks, noise this much above white counts as coloured
COLOUR_DETECTION = 8  # … over blocks of L/8 samples, at least 8 (``colour_blocks``)
COLOUR_GROWTH = 2.2  # a noise's ratio grows at most this much per doubling of the block (see ``noise_colour``)
COLOUR_MIN_DIFFERENCES = 30  # third differences of block means a ratio is taken over, at least


@dataclass
class NoiseColour:
    """How much noisier a log averaged over ``average`` samples is than white noise of the same
    sample-to-sample sd would leave it (``factor``; 1 where that is not shown), measured where
    the machine rests: over blocks of ``shortest`` samples (``shown``, from ``differences``
    third differences of block means), which decides, then over blocks doubling up to the
    averaging, which size it — up to ``sized_over`` samples, where the growth stopped looking
    like noise's (then the factor is a lower bound)."""

    factor: float
    shown: float
    shortest: int
    sized_over: int
    differences: int
    average: int

    def note(self) -> str:
        where = (f"over blocks of {self.sized_over} samples, as far as the force at rest lets noise be told from "
                 f"its own changes: at least that much" if self.sized_over < self.average else
                 f"{self.shown:.3g} times over {self.shortest} samples")
        return (f"the log's noise is coloured: averaged over {self.average} samples it is {self.factor:.3g} times what "
                f"white noise of the same sample-to-sample sd would leave ({where}; {self.differences} third "
                f"differences of block means at rest); the noise floor counts it")


def _averaged_over_white(raw: np.ndarray, runs: list, white: float, block: int) -> tuple[float, int]:
    """(sd of ``raw`` averaged over ``block`` samples / its white-noise value ``white``/√block,
    third differences counted), from the means of consecutive blocks inside each of the rest
    ``runs`` ((start, end) sample ranges); third differences (variance 20·σ_m² for independent
    means) remove whatever the force does there up to quadratically in time (a ramp, a slow
    swing). Neighbouring means of a noise correlated over many samples are correlated too, and
    their differences read low: an AR(1) noise with ρ = 0.96 averaged over 100 samples reads
    8.5 for 10.3."""
    d3 = []
    for a, b in runs:
        n = (b - a) // block
        if n >= 4:
            d3.append(np.diff(raw[a:a + n * block].reshape(n, block).mean(axis=1), 3))
    count = sum(map(len, d3))
    if count < COLOUR_MIN_DIFFERENCES or white <= 0.0:
        return float("nan"), count
    return _mad_sd(np.concatenate(d3)) / math.sqrt(20.0) / (white / math.sqrt(block)), count


def noise_colour(raw: np.ndarray, rest: np.ndarray, average: int) -> NoiseColour:
    """The noise of ``raw`` averaged over ``average`` samples, against the white-noise value sd/√L.

    Sample-to-sample differences see only the noise's fast part. A sensor whose noise is
    correlated over many samples (a filtered torque estimate, an AR(1) disturbance) keeps most
    of its variance through the average of eq. (8), and a floor taken as white would be several
    times too low. Measured where the machine rests (|v| < v_rest), where neither a ripple along
    the position nor the motion's transitions enter.

    Decided over the shortest blocks (L/8 samples, at least 8 unless L is shorter:
    ``colour_blocks``), short against anything the force itself does at rest: over whole
    blocks of L the presliding cycles of the project's robot joints (white noise) read up to 8
    times white, over the shortest blocks 0.85–1.15 (the suite's 153 recordings with an
    averaging); the rotary table's AR(1) torque 2.0–2.7. Then sized over blocks doubling up to
    L. The variance of a mean over 2B samples is at most that over B, so a noise's ratio grows
    at most √2 per doubling, and as this estimator reads it (low where neighbouring means are
    correlated, less so as blocks grow) at most about 2 (AR(1) noise with ρ up to 0.99:
    1.1–2.0); a doubling that grows it more than COLOUR_GROWTH is the force's own change at
    rest entering, and the sizing stops at the block before: the factor is then a lower bound,
    and the note says so. Noise correlated over longer than the averaging reads low (ρ = 0.96
    over 13 samples: 2.5 for 5.7), and noise slower than the averaging itself is taken for the
    force's changes by the third differences: both are under-counted."""
    L = int(average)
    blocks = colour_blocks(L)
    if blocks[0] < 2:
        return NoiseColour(1.0, float("nan"), blocks[0], blocks[0], 0, L)
    edges = np.diff(np.concatenate([[0], rest.astype(np.int8), [0]]))
    runs = list(zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1)))
    both = rest[1:] & rest[:-1]
    white = _mad_sd(np.diff(raw)[both]) / math.sqrt(2.0) if both.sum() >= 20 else 0.0  # sample-to-sample, at rest
    shown, count = _averaged_over_white(raw, runs, white, blocks[0])
    if not shown >= COLOUR_SHOWN:
        return NoiseColour(1.0, shown, blocks[0], blocks[0], count, L)
    factor, sized = shown, blocks[0]
    for block in blocks[1:]:
        r, _ = _averaged_over_white(raw, runs, white, block)
        if not (np.isfinite(r) and r <= factor * COLOUR_GROWTH):
            break
        factor, sized = max(factor, r), block
    return NoiseColour(factor, shown, blocks[0], sized, count, L)


def colour_blocks(average: int) -> list[int]:
    """The block lengths ``noise_colour`` reads, shortest first: L//8, L//4, L//2, L — each about
    twice the one before and the last the averaging itself — from the first that is at least
    COLOUR_DETECTION samples long (only L itself where L is shorter)."""
    L = int(average)
    k = COLOUR_DETECTION.bit_length() - 1  # 3: blocks of L/8
    while k > 0 and L >> k < min(L, COLOUR_DETECTION):
        k -= 1
    return [L >> j for j in range(k, -1, -1)]


def smoothing_window(x: np.ndarray, dt: float, sd: float) -> int:
    """Odd savgol window (≥ 5) over which the typical motion travels about three noise sds:
    shorter windows leave the noise (or the encoder staircase) in the path, longer ones blur
    reversals."""
    v = np.abs(np.diff(x)) / dt
    moving = v[v > 10 * sd / dt] if sd > 0 else v[v > 0]
    if not len(moving) or sd <= 0:
        return 5
    v_typ = float(np.percentile(moving, 25))
    w = int(math.ceil(3.0 * sd / (v_typ * dt)))
    w = min(max(w, 5), max(5, len(x) // 50), 101)
    return w + 1 - w % 2


def play(x: np.ndarray, h: float) -> np.ndarray:
    """The play (backlash) operator of half-width h: the output follows x only once x has
    moved h past it, so back-and-forth wiggles smaller than 2h — what smoothing leaves of
    noise and of the encoder staircase — do not reach the model as velocity reversals (each
    would restart a transition curve on its steep initial part). It lags x by h while x
    moves: ``centred_play`` is what the model is driven along."""
    if h <= 0:
        return x.copy()
    return _play(np.ascontiguousarray(x, dtype=np.float64), float(h))[0]


@njit(cache=True)
def _play(x, h):
    """The play's output, and its direction (+1, -1, 0 before it first moves) per sample."""
    n = len(x)
    out = np.empty(n)
    d = np.zeros(n)
    y = x[0]
    cur = 0.0
    for i in range(n):
        if x[i] - h > y:
            y = x[i] - h
            cur = 1.0
        elif x[i] + h < y:
            y = x[i] + h
            cur = -1.0
        out[i] = y
        d[i] = cur
    return out, d


@njit(cache=True)
def _centred(x, y, d, h):
    # y + h·d is x itself wherever x pushes the play; across each dead zone — from the turning
    # sample (the extremum of x before the play starts back) to the sample where it does — a
    # straight line, so the path turns where x turned and passes no wiggle under 2h
    n = len(x)
    out = y + h * d
    ext = 0
    for i in range(1, n):
        if d[i] != d[i - 1] and d[i - 1] != 0.0:
            for j in range(ext, i + 1):
                out[j] = x[ext] + (out[i] - x[ext]) * (j - ext) / max(i - ext, 1)
            ext = i
        elif d[i] == 0.0 or (d[i] > 0 and x[i] >= x[ext]) or (d[i] < 0 and x[i] <= x[ext]):
            ext = i
    return out


def centred_play(x: np.ndarray, h: float) -> np.ndarray:
    """The play of half-width h without its lag: x wherever x moves on, x's extremum where
    it turns, a straight line across the 2h dead zone after each turn, and wiggles under 2h
    held flat. The play's own output, h behind x while it moves, drives the model along a
    path displaced by h in the direction of travel: after each reversal the model then runs
    2h behind on its transition curve, and where that curve is steep (a stage's presliding
    over a few µm, with a scale resolving 10⁻⁸ m) the friction is off by slope × 2h, with the
    sign of the motion — ±2 N on a clean linear stage whose force ramps reverse inside
    presliding, five times its noise floor."""
    if h <= 0:
        return np.asarray(x, dtype=np.float64).copy()
    x = np.ascontiguousarray(x, dtype=np.float64)
    y, d = _play(x, float(h))
    return _centred(x, y, d, float(h))


def smoothed_path(x: np.ndarray, window: int, h: float, centred: bool = True) -> np.ndarray:
    """The path the model is driven along: the position smoothed by a quadratic Savitzky–Golay
    window, then wiggles below 2h removed by the play operator — without its lag
    (``centred_play``) where ``centred``, else the play's own output."""
    s = savgol_filter(x, window, 2, mode="interp")
    return centred_play(s, h) if centred else play(s, h)


@dataclass(frozen=True)
class ComparedPath:
    """The logged position as the model is driven along it: sensor noise (sd) and encoder
    steps (step) are the measurement, not motion."""

    path: np.ndarray
    sd: float
    step: float
    window: int
    h: float

    def step_speed(self, dt: float) -> float:
        """One encoder step per window of samples ``dt`` apart: the slowest speed the window's
        slope tells from rest on a quantised position (0 without steps)."""
        return self.step / (self.window * dt) if self.step > 0 else 0.0


def compared_path(x: np.ndarray, dt: float, window: int | None = None) -> ComparedPath:
    """``smoothed_path`` with its window and play width derived from the position's own noise
    and quantisation (``position_noise``): the path the diagnosis compares along, and the one
    ``simulate --smooth-path`` drives. ``window``: the user's, instead of ``smoothing_window``'s."""
    sd, q = position_noise(x)
    w = smoothing_window(x, dt, sd) if window is None else int(window)
    h = 2.0 * max(sd, q / 2.0)
    # a sensor with Gaussian noise: the play's lag removed (``centred_play``). An encoder: the
    # play's own output, as before — a reading there changes only once the contact has crossed
    # a step boundary, and driven along the centred staircase the generator's tribometers (steps
    # of 10⁻⁷ m) were left a clean recording's gap of 7.7 noise floors against 4.6 (median over
    # the controls of seeds 1000–1071), its robot joints 2.5 against 2.6
    return ComparedPath(smoothed_path(x, w, h, centred=q == 0.0), sd, q, w, h)


def savgol_noise_gain(window: int) -> float:
    """The sd of white noise after the quadratic Savitzky–Golay smoothing of ``window``
    samples (the central point), per unit sd: √(3(3w² − 7) / (4w(w² − 4)))."""
    w = float(window)
    return math.sqrt(3.0 * (3.0 * w * w - 7.0) / (4.0 * w * (w * w - 4.0)))


def input_noise(friction: np.ndarray, path: np.ndarray, sd_path: float) -> np.ndarray:
    """The sd, sample by sample, that the model's friction carries from the measured position
    it is driven by, linearised: the local slope dF/dx of the model along the path times the
    noise left in the path (in presliding a few nm move the friction along the steep start of
    F_d; in sliding the slope is S(v)'s, ~0). Where the path rests (the play operator holding
    it, or an encoder between two steps) the true position is still anywhere within the noise
    of it, on the curve it stopped on: the last slope is carried over. A lower bound: an error
    a reversal stores in the hysteresis memory lasts until the loop closes, which this does
    not count."""
    dF = np.abs(np.diff(friction, prepend=friction[0]))
    dx = np.abs(np.diff(path, prepend=path[0]))
    moved = dx > 0
    # a step of the path shorter than the noise does not resolve a slope (the friction also
    # moves with the velocity and time there): the noise cannot move F more than the step did
    slope = np.where(moved, dF / np.maximum(dx, sd_path), 0.0)
    last = np.maximum.accumulate(np.where(moved, np.arange(len(dx)), 0))
    return slope[last] * sd_path


def _with_input_noise(cmp_: Comparison, friction: np.ndarray) -> Comparison:
    d = input_noise(friction, cmp_.path, cmp_.position_noise * savgol_noise_gain(cmp_.window))
    if cmp_.average > 1:  # the moving average of eq. (8) over L samples: variance / L
        d = np.sqrt(np.maximum(uniform_filter1d(d**2, cmp_.average, mode="nearest"), 0.0) / cmp_.average)
    cmp_.input_noise = d
    return cmp_


def settle_noise_floor(cmp_: Comparison, mask: np.ndarray) -> None:
    """The noise floor of what is compared on ``mask``: the log's, and what the position noise
    carries through the model's slope (``input_noise``)."""
    if cmp_.input_noise is None:
        return
    logged = cmp_.noise
    carried = math.sqrt(float(np.mean(cmp_.input_noise[mask] ** 2)))
    cmp_.noise = math.sqrt(logged**2 + carried**2)
    cmp_.notes.append(f"noise floor {cmp_.noise:.3g}: the log's {logged:.3g} and at least {carried:.3g} that the "
                      f"position noise carries through the model's slope dF/dx (per regime below)")


@dataclass(frozen=True)
class MotionReading:
    """The logged motion as the diagnosis reads it: the compared path (``compared_path``), its
    smoothed slope against the actual times, that slope's noise, the speed below which the
    contact counts as at rest, the back-travel a significant reversal needs, and a tachometer
    (velocity, noise) where the file has one quieter than the slope."""

    t: np.ndarray
    x: np.ndarray
    dt: float
    compared: ComparedPath
    velocity: np.ndarray
    v_noise: float
    v_rest: float
    min_excursion: float
    tachometer: tuple | None
    set_by_user: tuple = ()  # the thresholds the user set (``reading_overrides``), not derived

    def note(self, unit: str = "", min_excursion: float | None = None, why: str = "") -> str:
        """The reading in one line, each threshold marked where the user set it; ``unit``: the
        position's (the recording's, SI). ``min_excursion``: the back-travel the diagnosis
        counts reversals from, where it is not the reading's own (``reversal_threshold``), and
        ``why``."""
        cp = self.compared
        mark = lambda k: " (set)" if k in self.set_by_user else ""  # noqa: E731
        used = self.min_excursion if min_excursion is None else min_excursion
        because = f" ({why})" if why else ""
        x = f" {unit}" if unit else ""
        v = f" {unit}/s" if unit else ""
        # a rest speed the encoder's step sets (three steps per window, over the velocity's noise)
        # reads slower sliding as rest: a 0.01° encoder at 2 kHz, 0.21 rad/s, 82 % of a tendon
        # joint's samples, its runs at 0.03–0.12 rad/s among them; the window set longer lowers it
        per_window = cp.step_speed(self.dt)
        coarse = (f" (one encoder step per {cp.window} samples is {per_window:.3g}{v}: slower sliding reads as rest "
                  f"here; a longer window lowers it)"
                  if per_window > self.v_noise and not {"window", "v_rest"} & set(self.set_by_user) else "")
        # a grid finer than the noise on it is the file's digits, not an encoder (as `fit` reads
        # it, ``segment.detect_noise``): a 2 µm sensor written in inches to 10⁻⁶ was said to have
        # an encoder step of 2.54·10⁻⁸ m
        grid = ("no encoder step" if cp.step <= 0 else f"encoder step {cp.step:.3g}{x}" if cp.sd <= GRID_UNDER_NOISE * cp.step
                else f"written to steps of {cp.step:.3g}{x}, finer than its noise: no encoder's")
        return (f"position noise {cp.sd:.3g}{x} ({grid}); "
                f"path smoothed over {cp.window} samples{mark('window')} and wiggles below {2 * cp.h:.3g}{x} removed; "
                f"|v| < {self.v_rest:.3g}{v}{mark('v_rest')} counts as presliding{coarse}; a reversal counts from "
                f"{used:.3g}{x}{mark('min_excursion')}{because} of back-travel (settable: `diagnose --threshold "
                f"NAME=VALUE`, {', '.join(READING_SETTABLE)})")


# the thresholds of the motion reading a user may set instead of their derivation from the
# recording: the smoothing window (samples; it sets the velocity's noise, so the rest speed
# follows it unless set too), the rest speed and the back-travel of a significant reversal
# (SI, in the units the recording is read into)
READING_SETTABLE = ("window", "v_rest", "min_excursion")


def reading_overrides(values: dict | None) -> dict:
    """The user's settings of the motion reading as numbers, each refused in one line unless
    it is settable (READING_SETTABLE) with a finite value in its range: window an odd whole
    number of samples ≥ 5, v_rest and min_excursion > 0."""
    out = {}
    for k, v in (values or {}).items():
        if k not in READING_SETTABLE:
            raise DataError(f"--threshold {k}: not a threshold of the diagnosis's reading "
                            f"(settable: {', '.join(READING_SETTABLE)})")
        out[k] = checked_threshold(k, v, "window" if k == "window" else "positive")
    return out


def motion_reading(rec: Recording, overrides: dict | None = None) -> MotionReading:
    """The motion as the diagnosis reads it, every threshold derived from the recording
    unless ``overrides`` (``reading_overrides``) sets it."""
    user = reading_overrides(overrides)
    t = np.asarray(rec.time, dtype=np.float64)
    x = np.asarray(rec.position, dtype=np.float64)
    if len(t) < 50:
        raise DataError(f"{rec.source}: diagnosis needs at least 50 samples, got {len(t)}")
    if user.get("window", 0) > len(t) // 2:
        raise DataError(f"--threshold window={user['window']}: longer than half of {rec.source}'s {len(t)} samples")
    dt = float(np.median(np.diff(t)))
    cp = compared_path(x, dt, user.get("window"))
    # the sampling may change within a record (parts logged at different rates, samples lost):
    # the slope is taken against the actual times and never across a gap, as the fit does
    vel = piecewise_slope(t, x, cp.window, gap_threshold(t))
    v_noise = cp.sd * math.sqrt(12.0) / (cp.window**1.5 * dt)
    v_rest = user.get("v_rest", 3.0 * max(v_noise, cp.step_speed(dt)))
    tacho = None
    if rec.velocity is not None:
        vt = np.asarray(rec.velocity, dtype=np.float64)
        # use the tachometer where it is quieter than the differentiated position, and runs the
        # way the position does (one logged with the other sign made a correct force read a
        # negative inertia, and be refused as pushing the position down)
        vt_noise = _mad_sd(np.diff(vt)) / math.sqrt(2)
        if vt_noise < v_noise and np.dot(vt, vel) > 0:
            tacho = (vt, vt_noise)
    return MotionReading(t, x, dt, cp, vel, v_noise, v_rest, user.get("min_excursion", 4.0 * max(cp.sd, cp.step)),
                         tacho, tuple(user))


# what to do where a column read as the applied force carries no I·ẍ (measured friction under a force's name)
# words of a force column's name that say it is applied, not measured friction
APPLIED_WORDS = frozenset(("drive", "motor", "applied", "actuator", "servo", "cmd", "command", "commanded", "setpoint",
                           "demand", "control", "input"))
def words_of(column: str) -> set:
    """The lower-case words of a column's name (``APPLIED_WORDS`` are looked for among them)."""
    return set(re.split(r"[^a-z]+", str(column).lower()))


NAME_IT_FRICTION = ("if it is measured friction, name it so (friction, friction_torque) or pass "
                    "--columns friction=<column>")


def _force_reading(rec: Recording) -> tuple[MotionReading, np.ndarray, float, np.ndarray, int]:
    """What eq. (8) is read from in a record of applied force and position, no inertia given:
    the motion reading, the velocity and its noise (a tachometer's where quieter), the force,
    and the shortest averaging (``averaging_length`` at I = 0, within ``averaging_limit``)."""
    m = motion_reading(rec)
    vel, v_noise = m.tachometer or (m.velocity, m.v_noise)
    f = np.asarray(rec.force, dtype=np.float64)
    f_sd = _mad_sd(np.diff(f)) / math.sqrt(2.0)
    longest = averaging_limit(m.t, m.compared.path, m.min_excursion)
    return m, vel, v_noise, f, averaging_length(0.0, f_sd, v_noise, m.dt, m.compared.window, len(m.t), longest)


class LikeFriction(NamedTuple):
    """Why a column read as the applied force may be measured friction (``recording_inertia``):
    the regression on the acceleration finds no inertial term in it (``doubt`` False), or reads
    one not told from 0 (``doubt`` True: a slow rig's applied torque may read so too);
    ``load_span``, where the normal load changes along the record by more than a tenth of its
    largest value, that fraction: friction following the load can hide I·ẍ as well."""

    doubt: bool
    load_span: float | None = None


class InertiaNote(NamedTuple):
    """What ``recording_inertia`` reads: the estimate (None where there is none), the words the
    notes give, and, where the column read as the applied force looks like measured friction,
    why (``LikeFriction``; None where it does not, or its name says it is applied)."""

    estimate: InertiaEstimate | None
    why: str
    like_friction: LikeFriction | None = None


def recording_inertia(rec: Recording) -> InertiaNote:
    """The inertia of eq. (8) that a recording of applied force and position says by itself
    (``inertia_from_force`` at the shortest averaging, no inertia given), and in words why
    there is none (no applied force, a measured friction, no steady sliding to read it in, the
    two windows disagreeing)."""
    if rec.force is None or rec.position is None:
        return InertiaNote(None, "not read: no applied force and position to read it from")
    if rec.friction is not None:
        return InertiaNote(None, "not read: the friction is measured, eq. (8) is not needed")
    if len(rec.time) < 50:
        return InertiaNote(None, f"not read: {len(rec.time)} samples, too few to regress the force on the acceleration")
    m, vel, v_noise, f, L0 = _force_reading(rec)
    reading = inertia_read(f, vel, m.t, L0, m.v_rest, v_motion=m.velocity, v_wide=wider_slope(m, L0))
    reversed_why = reversed_force(rec, reading)
    if reversed_why:
        raise DataError(reversed_why)
    est = reading.estimate
    # the hint that the column is measured friction: where the regression finds no inertial
    # term at all (not where there is too little steady sliding to look: a sweep whose levels
    # the fit could not find), or reads one not told from 0; never of a column whose name says
    # it is applied (a drive's or a motor's torque)
    # (both readings, where the velocity was read twice: σ then holds the rise, and a wrist whose
    # 0.050 rose to 0.085 over the wider slope is not an inertia told from none)
    doubt = (est is not None and not est.usable
             and all(abs(i) < 2.0 * est.stderr for i in (est.value, est.wider) if i is not None))
    no_term = doubt or (est is None and reading.no_inertial_term)
    load_span = None
    if no_term and rec.normal_load is not None:
        # friction that follows a load changing along the record is a slow part of the force the
        # regression on the acceleration does not model, and can hide I·ẍ as well
        n = np.abs(np.asarray(rec.normal_load, dtype=np.float64))
        change = float(np.ptp(n) / np.max(n)) if np.max(n) > 0 else 0.0
        load_span = change if change > 0.1 else None
    like = (LikeFriction(doubt, load_span) if no_term and not words_of(rec.columns.get("force", "")) & APPLIED_WORDS
            else None)
    hint = f"; a column of measured friction read as the applied force shows none: {NAME_IT_FRICTION}" if like else ""
    if load_span is not None:
        hint += (f"; or friction following the normal load, which spans {100 * load_span:.0f} % of its largest value "
                 f"along the record, hides it (`diagnose` tells whether the load is an effect)")
    if est is None:
        return InertiaNote(None, f"not read: {reading.why}" + hint, like)
    # (the σ's part from how the velocity is read, where it rose there: ``inertia_read``)
    wider = ("" if est.wider is None else
             f"; {est.wider:.3g} with the velocity taken over {2 * L0 + 1} samples instead of {m.compared.window}, "
             f"a rise σ includes")
    if not est.usable:
        return InertiaNote(est, f"read as {est.value:.3g} ± {est.stderr:.2g}, too uncertain to write as an estimate "
                                f"(σ over a quarter of the value{wider}{hint})", like)
    return InertiaNote(est, f"read as {est.value:.4g} ± {est.stderr:.2g} (the force regressed on the mean acceleration "
                            f"over {8 * L0 + 1} and {32 * L0 + 1} samples{wider})")


def inertia_ceiling(rec: Recording) -> float | None:
    """The largest inertia of eq. (8) a recording of applied force and position allows, where it
    reads none (``recording_inertia``): I·ā = f̄ − F̄, and the friction lies within the range of
    the force (it equals it while sliding steadily), so I·|ā| ≤ span(f̄) wherever the mean
    acceleration reaches |ā| — taken at its 99th percentile over the reading's first averaging
    (8L + 1 samples), so that one noisy sample does not set it. None where that acceleration is
    within CEILING_NOISE times its own noise (√2·v_noise over the span: the accelerations are not
    seen), or no force and position are logged. An upper bound, not an estimate: a haptic joint
    made apart (2·10⁻⁴ kg·m², current × k_t logged, too little steady sliding to read I) reads
    1.8·10⁻³, where the built-in default, another machine's, is 5."""
    if rec.force is None or rec.position is None or rec.friction is not None or len(rec.time) < 50:
        return None
    m, vel, v_noise, f, L0 = _force_reading(rec)
    n_avg = 8 * L0 + 1
    a_top = float(np.quantile(np.abs(mean_acceleration(vel, m.t, n_avg)), 0.99))
    if a_top <= CEILING_NOISE * math.sqrt(2.0) * v_noise / ((n_avg - 1) * m.dt):
        return None
    return float(np.ptp(uniform_filter1d(f, n_avg, mode="nearest"))) / a_top


CEILING_NOISE = 3.0  # the acceleration that sets ``inertia_ceiling`` must stand this many times over its noise


INERTIA_ATTENUATION = 0.02  # the noise of the mean acceleration may take at most this share of its variance


def inertia_beside_model(rec: Recording, params: FrictionParams) -> InertiaEstimate | None:
    """Eq. (8)'s I read beside a model of the friction: the averaged applied force less the
    model's friction, simulated along the compared path and averaged the same way, regressed on
    the mean acceleration (and a constant) while moving, f̄ − F̄_model = I·ā + c; its σ by the
    jackknife over ten blocks of time. Where ``recording_inertia`` reads nothing because the
    friction follows the acceleration by itself (each speed reached from a reversal, through
    presliding), the model's memory carries that part. A misfit of the model that follows the
    acceleration enters I too, so a caller holds this value rather than estimating with it.

    The averaging doubles from the path's window until the velocity's noise makes at most
    ``INERTIA_ATTENUATION`` of the mean acceleration's variance while moving: a noisy regressor
    pulls the slope towards 0 by that share (an encoder's 5-sample acceleration read a
    0.035 kg·m² turntable as 0.0075). None without an applied force and a position, where
    nothing moves, or where no averaging within 1 % of the record is quiet enough."""
    if rec.force is None or rec.position is None or rec.friction is not None or len(rec.time) < 50:
        return None
    m = motion_reading(rec)
    vel, v_noise = m.tachometer or (m.velocity, m.v_noise)
    moving = np.abs(vel) > m.v_rest  # at rest the friction is what is applied, not what the model's path says
    f = np.asarray(rec.force, dtype=np.float64)
    f_sd = _mad_sd(np.diff(f)) / math.sqrt(2.0)
    # at most 1 % of the record (``averaging_length``'s own cap), not a tenth of a typical stroke:
    # the regression needs no transition resolved, and a presliding resonance's small reversals
    # can make the typical stroke a few samples long
    longest = max(5, len(m.t) // 100)
    L = averaging_length(0.0, f_sd, v_noise, m.dt, m.compared.window, len(m.t))
    while True:
        acc = mean_acceleration(vel, m.t, L)
        if moving.sum() < 50 * L or np.std(acc[moving]) == 0:
            return None
        if 2.0 * v_noise**2 / ((L - 1) * m.dt) ** 2 <= INERTIA_ATTENUATION * float(np.var(acc[moving])):
            break
        if L >= longest:
            return None
        L = min(2 * L - 1, longest + 1 - longest % 2)
    model = simulate_displacement(params.replace(effects=()), m.t, m.compared.path).friction_force
    y = uniform_filter1d(f, L, mode="nearest") - uniform_filter1d(model, L, mode="nearest")
    X = np.column_stack([np.ones(len(y)), acc])

    def slope(mask):
        return float(np.linalg.lstsq(X[mask], y[mask], rcond=None)[0][1])

    block = np.minimum(np.arange(len(y)) * JACKKNIFE_BLOCKS // len(y), JACKKNIFE_BLOCKS - 1)
    full = slope(moving)
    return InertiaEstimate(full, jackknife_sd(full, [slope(moving & (block != k)) for k in range(JACKKNIFE_BLOCKS)]))


def comparison_of(rec: Recording, params: FrictionParams, space: str = "friction",
                  reading: dict | None = None) -> Comparison:
    """Where to compare: in friction when the recording has a friction column or an applied
    force (friction from eq. (8), averaged), in position (``space="position"``) only for an
    applied force; ``reading``: the user's settings of the motion reading (``reading_overrides``)."""
    if rec.position is None:
        raise DataError(f"{rec.source}: diagnosis needs a position column")
    m = motion_reading(rec, reading)
    cmp_ = _compared(rec, params, space, m)
    cmp_.reading, cmp_.position_unit = m, rec.units.get("position", "")
    return cmp_


def reversal_threshold(cmp_: Comparison) -> None:
    """The back-travel that counts as a significant reversal, once the model's presliding range
    is known (``cmp_.z_presliding``): a quarter of that range, smaller ones staying on the
    steep start of the transition curve where they hardly load the contact, or the position's
    noise where that is larger — unless the user set it (``--threshold min_excursion``), which
    then holds. The reading's note says the value used and why."""
    m = cmp_.reading
    quarter = 0.25 * cmp_.z_presliding
    if "min_excursion" in m.set_by_user:
        why = (f"under a quarter of the model's presliding range, {quarter:.3g}, which it would be otherwise"
               if m.min_excursion < quarter else "")
        used = m.min_excursion
    elif quarter > m.min_excursion:
        why = f"a quarter of the model's presliding range; the position's noise allows {m.min_excursion:.3g}"
        used = quarter
    else:
        why, used = "", m.min_excursion
    cmp_.min_excursion = used
    if cmp_.notes:
        cmp_.notes[0] = m.note(cmp_.position_unit, used, why)


def _compared(rec: Recording, params: FrictionParams, space: str, m: MotionReading) -> Comparison:
    """``comparison_of`` on the motion as read (``motion_reading``)."""
    t, x, dt, vel, v_noise, v_rest, min_exc = m.t, m.x, m.dt, m.velocity, m.v_noise, m.v_rest, m.min_excursion
    cp = m.compared
    sdx, w, path = cp.sd, cp.window, cp.path
    notes = [m.note(rec.units.get("position", ""))]  # (made again by ``reversal_threshold``)
    if rec.friction is not None:
        meas = np.asarray(rec.friction, dtype=np.float64)
        cmp_ = Comparison("friction", t, meas, path, vel, rec.normal_load, rec.force, 0.0, sdx, w, min_exc, v_rest,
                          notes=notes, raw=meas)
        cmp_.noise = noise = cmp_.log_noise()
        # a reaction-sign log (friction positive while the position decreases): flip it
        F0 = simulate_displacement(params, t, path).friction_force
        if np.dot(F0 - F0.mean(), meas - meas.mean()) < 0:
            cmp_.measured = -meas
            cmp_.flipped = True
            notes.append("friction logged as a reaction (opposite to the model's sign): flipped")
        notes.append(f"compared in friction; noise of the log {noise:.3g} (from sample-to-sample differences)")
        return _with_input_noise(cmp_, F0)
    if rec.force is None:
        raise DataError(f"{rec.source}: diagnosis needs a friction column, or an applied force column")
    f = np.asarray(rec.force, dtype=np.float64)
    if m.tachometer:
        vel, v_noise = m.tachometer
        notes.append("velocity from the velocity column (quieter than the smoothed position)")
    f_sd = _mad_sd(np.diff(f)) / math.sqrt(2.0)
    longest = averaging_limit(t, path, min_exc)
    L0 = averaging_length(0.0, f_sd, v_noise, dt, w, len(t), longest)
    # the model-free reading (at the shortest window): a force of the other sign is refused in
    # either space, as `fit` refuses it (``reversed_force``)
    reading0 = inertia_read(f, vel, t, L0, v_rest, v_motion=m.velocity, v_wide=wider_slope(m, L0))
    reversed_why = reversed_force(rec, reading0)
    if reversed_why:
        raise DataError(reversed_why)
    if space == "position":
        return _position_comparison(rec, params, t, x, f, vel, sdx, w, min_exc, v_rest, v_noise, path, notes)
    inertia = params.inertia
    L = averaging_length(inertia, f_sd, v_noise, dt, w, len(t), longest)
    model_friction = simulate_displacement(params, t, path).friction_force
    est = inertia_from_force(f, vel, t, L, v_rest, wider_slope(m, L)) if L != L0 else reading0.estimate
    if (est is None or not est.usable) and L0 < L:
        # nothing usable at the L the file's inertia asks for (a held inertia several times the
        # machine's asks for a window too long to read I in): read at the shortest window
        est = reading0.estimate
    if est is not None and est.usable and abs(est.value - inertia) > 3 * est.stderr:
        # a model-free regression can be misled (anything in the friction that follows the
        # acceleration enters I): the recording's value is used only if the model as given then
        # agrees with the data better
        L2 = averaging_length(est.value, f_sd, v_noise, dt, w, len(t), longest)
        gaps = [_rms(friction_from_force(f, vel, i, t, n) - uniform_filter1d(model_friction, n, mode="nearest"))
                for i, n in ((inertia, L), (est.value, L2))]
        if gaps[1] < gaps[0]:
            notes.append(f"inertia: the recording says {est.value:.4g} ± {est.stderr:.2g} against the parameter "
                         f"file's {inertia:.4g}, and the model agrees better with it (RMS {gaps[1]:.3g} against "
                         f"{gaps[0]:.3g}); the recording's value is used to take friction from the applied force")
            inertia, L = est.value, L2
        else:
            notes.append(f"inertia: the recording says {est.value:.4g} ± {est.stderr:.2g} against the parameter "
                         f"file's {inertia:.4g}, but the model agrees better with the file's (RMS {gaps[0]:.3g} "
                         f"against {gaps[1]:.3g}): the file's is kept")
    meas = friction_from_force(f, vel, inertia, t, L)
    cmp_ = Comparison("friction", t, meas, path, vel, rec.normal_load, f, 0.0, sdx, w, min_exc, v_rest, notes=notes,
                      average=L, acceleration=mean_acceleration(vel, t, L), raw=f,
                      inertial_noise=math.sqrt(2.0) * inertia * v_noise / ((L - 1) * dt), inertia=inertia)
    colour = noise_colour(f, np.abs(vel) < v_rest, L)
    cmp_.noise_colour = colour.factor
    if colour.factor > 1.0:
        notes.append(colour.note())
    cmp_.noise = cmp_.log_noise()
    notes.append(f"compared in friction, taken from the applied force by eq. (8) averaged over {L} samples "
                 f"({L * dt:.3g} s): mean force − I·Δv/T (the inertial term in integral form, the position "
                 f"never differentiated twice); the model's friction averaged the same way; noise of the log "
                 f"{cmp_.noise:.3g}")
    return _with_input_noise(cmp_, model_friction)


def averaging_length(inertia: float, f_sd: float, v_sd: float, dt: float, window: int, n: int,
                     longest: int | None = None) -> int:
    """Samples to average eq. (8) over: long enough that the inertial term I·Δv/T, from a
    velocity with noise sd ``v_sd``, is no noisier than the averaged force (√2·I·v_sd/T ≤
    f_sd/√L), and at least the path's smoothing window; odd, at most 1 % of the record and
    at most ``longest`` (``averaging_limit``)."""
    need = (math.sqrt(2.0) * inertia * v_sd / (dt * f_sd)) ** 2 if f_sd > 0 else 1.0
    L = int(math.ceil(max(need, window, 5)))
    L = min(L, max(5, n // 100), max(window, 5, longest or n))
    return L + 1 - L % 2


AVERAGING_PER_STROKE = 10  # eq. (8) is averaged over at most this fraction (1/10) of a typical stroke's time


def averaging_limit(t: np.ndarray, path: np.ndarray, min_excursion: float) -> int:
    """The longest averaging of eq. (8) that still resolves the motion: a tenth of the median
    time between significant reversals, in samples. An encoder's velocity next to a quiet
    torque asks for windows of seconds (a quiet force is no reason to average), and one as long
    as a stroke leaves nothing of its transitions to compare."""
    turns = np.flatnonzero(np.diff(significant_reversals(path, min_excursion)) > 0)
    if len(turns) < 3:
        return len(t)
    dt = float(np.median(np.diff(t)))
    return max(5, int(np.median(np.diff(t[turns])) / (AVERAGING_PER_STROKE * dt)))


JACKKNIFE_BLOCKS = 10


@dataclass(frozen=True)
class InertiaEstimate:
    value: float
    stderr: float
    # (``inertia_read``) the reading with the velocity taken over a wider slope, where it rose
    # there and that rise is part of ``stderr``; None where it was not taken or did not rise
    wider: float | None = None

    @property
    def usable(self) -> bool:
        """σ under a quarter of the value: precise enough to take friction from the force with."""
        return self.stderr < 0.25 * self.value


class InertiaReading(NamedTuple):
    """What ``inertia_read`` found: the estimate, or None and why; ``no_inertial_term`` where
    the regression finds no positive inertia at all (a measured friction read as the applied
    force has none), not where there was too little steady sliding to look or the windows disagree."""

    estimate: InertiaEstimate | None
    why: str = ""
    no_inertial_term: bool = False
    # both windows negative, and each REVERSED_SIGMAS σ clear of 0 or the force against the
    # motion in sliding both ways (``against_motion``): an applied force logged with the other sign
    reversed: InertiaEstimate | None = None
    against_motion: bool = False
    clear: bool = False  # both readings REVERSED_SIGMAS σ clear of 0


def force_against_motion(f: np.ndarray, v: np.ndarray, v_rest: float, least: int = 50) -> bool:
    """Whether the applied force pushes against the motion while sliding, both ways: its median
    times the velocity's sign negative over the samples moving forwards (|v| > ``v_rest``) and
    over those moving backwards. Sliding dissipates, so a force pushing the way the position
    increases (eq. (8)) has the velocity's sign there; a weight the drive holds turns one side,
    not both. False with under ``least`` samples either way."""
    for s in (1.0, -1.0):
        m = s * v > v_rest
        if int(m.sum()) < least or not np.median(s * f[m]) < 0:
            return False
    return True


def wider_slope(m: MotionReading, L: int) -> np.ndarray | None:
    """The position's slope over 2L + 1 samples, for ``inertia_read`` at averaging ``L`` to
    read I again with (``v_wide``); None where the reading takes a tachometer's velocity or
    the path's window is already that wide. Its mean acceleration over 8L + 1 samples or more
    resolves the same motion as the path's few-sample slope, with less of an encoder's steps in
    it."""
    w = 2 * L + 1
    if m.tachometer or w <= m.compared.window:
        return None
    return piecewise_slope(m.t, m.x, w, gap_threshold(m.t))


def inertia_from_force(f: np.ndarray, v: np.ndarray, t: np.ndarray, L: int, v_rest: float,
                       v_wide: np.ndarray | None = None) -> InertiaEstimate | None:
    """``inertia_read``'s estimate (None where it reads none)."""
    return inertia_read(f, v, t, L, v_rest, v_wide=v_wide).estimate


def inertia_read(f: np.ndarray, v: np.ndarray, t: np.ndarray, L: int, v_rest: float,
                 v_motion: np.ndarray | None = None, v_wide: np.ndarray | None = None) -> InertiaReading:
    """The inertia I of eq. (8) from the recording alone (and where there is none, why): while
    sliding steadily the friction is a function of the velocity, S(v), so the averaged applied
    force is I·(mean acceleration) plus the averaged steady curve; it is regressed on the mean
    acceleration beside a free steady curve (a controller's hunting around each speed level is what
    determines I). No model enters: a model's own dynamics (its presliding state lagging the
    motion) would follow the acceleration and bias I. Done over 8L and over 32L samples; the
    estimate of the longer only if both are positive and agree within 10 % (anything else
    that follows the acceleration moves them apart), else none, with the reason; its standard
    error by the jackknife over ten blocks of time. A force logged once a sample from a controller whose
    proportional term moves within the sample reads I low by about kp·dt/2.

    ``v_wide`` (``wider_slope``): the same velocity taken over a wider slope, with less of an
    encoder's steps in it. The regression is read again on its mean acceleration, and where I
    rises there, the rise joins the jackknife's σ in quadrature (``InertiaEstimate.wider``
    says it): a noisy regressor pulls the slope towards 0, an error every block of time
    shares, which the jackknife cannot see. A 17-bit harmonic wrist of 0.08 kg·m² under a PID
    loop reads 0.050 from the path's 5-sample slope, 0.085 from an 11-sample one and 0.083
    from its unquantised angle; with the rise in its σ (0.037, against the jackknife's 0.012)
    that reading is no longer an estimate. The estimate stays the path's slope's: where the
    wider slope reads lower (the hidden-effect suite's robot joints, a hydraulic cylinder) it
    is further from the machine's inertia, not nearer."""
    hats = FreeSteadyCurve(v, v_rest).dense()
    rows = np.arange(len(v))
    dt = float(np.median(np.diff(t)))

    def solve(X, y, mask):
        coef, *_ = np.linalg.lstsq(X[mask], y[mask], rcond=None)
        return float(coef[-1])

    gaps = time_gaps(t)
    est = {}
    for n_avg in (8 * L + 1, 32 * L + 1):
        acc = mean_acceleration(v, t, n_avg)
        steady = (np.abs(v) > v_rest) & (np.abs(acc) * n_avg * dt < 0.1 * np.abs(v))  # dt: the median interval
        steady &= ~across_gaps(len(v), gaps, n_avg // 2 + 1)  # (a mean over samples either side of a gap)
        if steady.sum() < 50 * n_avg or np.std(acc[steady]) == 0:
            return InertiaReading(None, f"too little steady sliding to regress the force on the acceleration in "
                                        f"({int(steady.sum())} samples, at least {50 * n_avg} wanted over "
                                        f"{n_avg}-sample means)")
        # MA(f) = I·(mean acceleration) + MA(S(v)): the steady curve averaged like the force
        # (built once per window: the jackknife below refits the same columns on fewer rows)
        X = np.empty((len(v), hats.shape[1] + 1))
        uniform_filter1d(hats, n_avg, axis=0, mode="nearest", output=X[:, :-1])  # (no column_stack copy)
        X[:, -1] = acc
        y = uniform_filter1d(f, n_avg, mode="nearest")
        est[n_avg] = (solve(X, y, steady), steady)
    (I1, _), (I2, steady) = est.values()  # X, y: the longer window's, for the jackknife

    def jackknife_sd() -> float:
        # (least squares on the rows themselves: from the blocks' normal equations, whose cut of
        # small singular values is coarser, σ moved by up to 40 % where a block holds most of a
        # speed's samples)
        block = np.minimum(rows * JACKKNIFE_BLOCKS // len(v), JACKKNIFE_BLOCKS - 1)
        jk = np.array([solve(X, y, steady & (block != k)) for k in range(JACKKNIFE_BLOCKS)])
        return math.sqrt((JACKKNIFE_BLOCKS - 1) / JACKKNIFE_BLOCKS * float(np.sum((jk - jk.mean()) ** 2)))

    agree = abs(I1 - I2) <= 0.1 * abs(I2)
    if I1 <= 0 or I2 <= 0:
        why = f"the force regressed on the acceleration gives no positive inertia ({I1:.3g} and {I2:.3g})"
        if I1 < 0 and I2 < 0:
            # a measured friction read as the applied force has no inertial term: its readings
            # scatter about 0; a force of the other sign reads −I in both windows, each far from
            # 0 — not within 10 % of each other where something else follows the acceleration,
            # as it moves a positive pair apart (a pneumatic slide's reversed force read −8.15
            # and −9.11, and was fitted as a force with no levels, exit 0)
            sd = jackknife_sd()
            # (or, where the readings are only REVERSED_AGAINST_SIGMAS σ clear of 0, the force
            # against the motion both ways: the same slide's −9.11 was 2.7 σ from 0). The motion's
            # direction is the position's own (``v_motion``), not a velocity column's, whose sign
            # may be the one logged the other way
            clear = min(-I1, -I2) > REVERSED_SIGMAS * sd
            against = (min(-I1, -I2) > REVERSED_AGAINST_SIGMAS * sd
                       and force_against_motion(f, v if v_motion is None else v_motion, v_rest))
            if clear or against:
                return InertiaReading(None, why, no_inertial_term=True, reversed=InertiaEstimate(I2, sd),
                                      against_motion=against, clear=clear)
        return InertiaReading(None, why, no_inertial_term=True)
    if not agree:
        n1, n2 = est
        return InertiaReading(None, f"the force regressed on the acceleration reads {I1:.3g} over {n1}-sample means "
                                    f"and {I2:.3g} over {n2}-sample means, more than 10 % apart: something else "
                                    f"follows the acceleration, and neither reading is used")
    sd = jackknife_sd()
    if v_wide is None:
        return InertiaReading(InertiaEstimate(I2, sd))
    X[:, -1] = mean_acceleration(v_wide, t, 32 * L + 1)  # (the longer window's columns, as the jackknife's)
    wider = solve(X, y, steady)
    # noise in the regressor can only pull the slope towards 0 (errors in variables): a reading
    # that rises with the quieter velocity shows that pull, and the rise joins σ; one that falls
    # shows the wider slope's own smoothing, no pull on the first (a hydraulic cylinder made
    # apart, 250 kg, read 261 from the path's slope and 176 from the wider one)
    pulled = abs(wider) > abs(I2)
    return InertiaReading(InertiaEstimate(I2, math.hypot(sd, I2 - wider) if pulled else sd, wider if pulled else None))


REVERSED_SIGMAS = 5.0  # a negative inertia this many σ from 0 is a force of the other sign, not noise
REVERSED_AGAINST_SIGMAS = 2.0  # … or this many, where the force also pushes against the motion both ways


def reversed_force(rec: Recording, reading: InertiaReading) -> str | None:
    """Why the applied force of ``rec`` has the other sign than eq. (8) takes (pushing the
    position up), or None: the force regressed on the acceleration reads a negative inertia
    (``InertiaReading.reversed``). Said, not mended: the fix is the user's, in one option."""
    r = reading.reversed
    if r is None:
        return None
    col = rec.columns.get("force", "force")
    return (f"{rec.source}: the applied force {col!r} pushes the position down: regressed on the acceleration it reads "
            f"an inertia of {r.value:.3g} ± {r.stderr:.2g}, which is negative (I·ẍ = f − F, eq. (8), takes a force "
            f"pushing the way the position increases)"
            + (", and while sliding it pushes against the motion both ways, where sliding takes a force pushing "
               "the way it moves" if reading.against_motion else "")
            + f": negate the column in the file (or turn its sign with {rec.sign_mend('force')})"
            # a measured friction of the reaction sign also pushes against the motion (and its
            # frictional lag may follow the acceleration): that is said as well, unless the
            # column's name says it is applied (a drive's, a motor's)
            + ("" if (reading.clear and not reading.against_motion) or words_of(col) & APPLIED_WORDS
               else f"; {NAME_IT_FRICTION}"))


def mean_acceleration(v: np.ndarray, t: np.ndarray, L: int) -> np.ndarray:
    """The mean acceleration over the L = 2h + 1 samples centred on each one,
    (v[i + h] − v[i − h])/(t[i + h] − t[i − h]): centred, so a force logged at the sampling
    instants, or as the command held over the interval before or after, is off by at most
    half a sample; over the actual times, so a record whose rate changes is not misread.
    (Near the ends the window is clipped.)"""
    n = len(v)
    h = L // 2
    i = np.arange(n)
    hi, lo = np.minimum(i + h, n - 1), np.maximum(i - h, 0)
    span = t[hi] - t[lo]
    return np.divide(v[hi] - v[lo], span, out=np.zeros(n), where=span > 0)


def friction_from_force(f: np.ndarray, v: np.ndarray, inertia: float, t: np.ndarray, L: int) -> np.ndarray:
    """Eq. (8), I·ẍ = f − F, averaged over L samples: F̄ = f̄ − I·(mean acceleration), so the
    acceleration is never taken from a twice differentiated position."""
    return uniform_filter1d(f, L, mode="nearest") - inertia * mean_acceleration(v, t, L)


def _position_comparison(rec, params, t, x, f, vel, sdx, w, min_exc, v_rest, v_noise, path, notes) -> Comparison:
    """The plant simulated from the applied force in short windows, compared in position."""
    dt = float(np.median(np.diff(t)))
    inertia = params.inertia
    c = 0.5 * (params.stribeck.positive.sigma2 + params.stribeck.negative.sigma2)
    tau_v = inertia / c if c > 0 else (t[-1] - t[0]) / 100
    # short windows: the open-loop plant must not run away from the measured motion (the
    # Stribeck branch is unstable), yet move far enough for the friction to show
    nwin = int(min(max(round(0.5 * tau_v / dt), 10), max(10, len(t) // 20)))
    # no window runs across a time gap of the log: the plant would be integrated over a step
    # whose applied force was not seen
    edges = np.concatenate([[0], time_gaps(t), [len(t)]])
    windows = [(a, min(a + nwin + 1, hi)) for lo, hi in zip(edges[:-1], edges[1:]) for a in range(lo, hi - 1, nwin)]
    windows = [wd for wd in windows if wd[1] - wd[0] >= 3]
    f_sd = _mad_sd(np.diff(f)) / math.sqrt(2.0)
    T = nwin * dt
    floor = math.sqrt(sdx**2 + (f_sd / inertia) ** 2 * dt * T**3 / 3.0 + (v_noise * T) ** 2 / 3.0)
    notes.append(f"compared in position: the plant simulated from the applied force in windows of {nwin} samples "
                 f"({T:.3g} s ≈ I/σ2 / 2), memory carried over; noise floor {floor:.3g}")
    return Comparison("position", t, x, path, vel, rec.normal_load, f, floor, sdx, w, min_exc, v_rest, windows=windows,
                      notes=notes)


# ---------------------------------------------------------------- the model being fitted
@dataclass(frozen=True)
class Term:
    """One effect in a fit: which parameters are free (and how they are transformed)."""

    name: str
    fixed: dict
    free: tuple  # (param name, transform "lin"|"log", lo, hi) in transformed coordinates
    settles: str | None = None  # the free scale over which the effect must be seen to settle (see ``unsettled``)
    # a "log" parameter with a unit is taken relative to a scale of the record, u = ln(value/ref)
    # (a drift's τ in the session's duration, a ripple's λ in the travel): u, its bounds, the
    # optimiser's steps and its stopping test are then the same in any unit — in ln(value) a
    # ripple of 5 mm sat at u = −5.3 written in m and at 1.6 written in mm, and the
    # finite-difference steps, relative to |u|, differed by three times
    refs: Mapping[str, float] = field(default_factory=dict)
    # a softening's reversals (at its own threshold) before the record's first gross sliding,
    # and that sliding's time: what the session's first experiment counts (``unsettled``)
    before_sliding: tuple[float, float] | None = None

    def value(self, pname: str, tr: str, u: float) -> float:
        """The parameter's value at its transformed coordinate ``u``."""
        return float(self.refs.get(pname, 1.0) * math.exp(u)) if tr == "log" else float(u)

    def coordinate(self, pname: str, tr: str, value: float) -> float:
        """The transformed coordinate of the parameter's ``value`` (``value``'s inverse)."""
        return math.log(value / self.refs.get(pname, 1.0)) if tr == "log" else float(value)

    def at_bounds(self, u: np.ndarray) -> set:
        """The free parameters of the term's part ``u`` of a fit that ended at a bound of their
        range (a log scale within SETTLE_TOL of it, a linear one within BOUND_TOL of the range)."""
        out = set()
        for (pname, tr, lo, hi), x in zip(self.free, u):
            tol = SETTLE_TOL if tr == "log" else BOUND_TOL * (hi - lo)
            if x >= hi - tol or x <= lo + tol:
                out.add(pname)
        return out

    def pinned(self, u: np.ndarray) -> str | None:
        """Which of the term's free parameters in its part ``u`` of a fit ended at an end of
        their range, besides the settling scale (``unsettled`` speaks of that), in words, or
        None: the bound holds them there, not the data, and they get no σ (``effect_sds``) — a
        pneumatic slide's load session had a softening named with h = −0.9 and nothing said."""
        if self.name == "position_ripple":  # (its cs, cc are coordinates of its a and phase)
            return None
        held = self.at_bounds(np.asarray(u)) - {self.settles, SETTLED_SIZE.get(self.settles)}
        ends = []  # (a drift's b or a softening's h at a bound, as its settling scale, is ``unsettled``'s to say)
        for (pname, tr, lo, hi), x in zip(self.free, u):
            if pname not in held:
                continue
            a, b = self.value(pname, tr, lo), self.value(pname, tr, hi)
            ends.append(f"{pname} at {a if x <= 0.5 * (lo + hi) else b:.3g} (its range {a:.3g} … {b:.3g})")
        if not ends:
            return None
        return (f"{self.name}: {', '.join(ends)}: the end of the range holds it there, not the data, so it has no σ; "
                f"the residual asks more of this effect's form than it gives, and may be something else's")

    def bound(self, u: np.ndarray) -> str | None:
        """Where the ``settles`` scale of the term's part ``u`` of a fit ended: "upper", "lower"
        (within SETTLE_TOL of a bound of its range) or None (inside it, or no such scale)."""
        if self.settles is None:
            return None
        j = [f[0] for f in self.free].index(self.settles)
        lo, hi = self.free[j][2:4]
        return "upper" if u[j] >= hi - SETTLE_TOL else ("lower" if u[j] <= lo + SETTLE_TOL else None)

    def unsettled(self, u: np.ndarray, strokes: SpeedOrder | None = None) -> str | None:
        """Why the term's part ``u`` of a fit is not seen to settle — its ``settles`` scale at
        the upper bound: a trend along the session's schedule would look the same (where the
        strokes' speeds follow the reversals, ``stroke_order``, a stiffness following the speed;
        where they do not over the session, still one changing with time, and the speed where
        cycles of rising speeds keep them in order within each); at the lower bound: the change is over
        within the first few reversals, and a step between the session's first experiment and
        the next would look the same; a softening's n_c within the reversals before the first
        gross sliding (``before_sliding``): the same, where that first experiment makes many — or None."""
        where = self.bound(u)
        if self.settles == "tau" and where is None and "b" in self.at_bounds(u):
            # a drift whose b ends at a bound of its range (friction falling by 90 %, rising five
            # times, once settled) is a straight trend extrapolated: its bend is not seen either
            j = [f[0] for f in self.free].index("b")
            return (f"its b is at a bound of its range ({u[j]:.3g}): the change is a straight trend in time, its "
                    f"bend towards a settled value not seen, and a trend along the session's schedule would look "
                    f"the same. To tell: {EFFECTS[self.name].separated_by}")
        if self.settles == "n_c" and where is None and "h" in self.at_bounds(u):
            # a softening whose h ends at a bound of its range (the spring losing 90 % of its
            # stiffness, or stiffening six times, once settled) is held there by the range, not
            # by the data: the residual asks for more change than a spring softening with the
            # reversals gives, and a misfit of the transition curve that follows the session's
            # schedule would look the same (a pneumatic slide's load session, made apart, had
            # one named at h = −0.9 beside its load)
            j = [f[0] for f in self.free].index("h")
            return (f"its h is at a bound of its range ({u[j]:.3g}): the range holds the change there, not the data, "
                    f"and a misfit of the transition curve that follows the session's schedule would look the same. "
                    f"To tell: {EFFECTS[self.name].separated_by}")
        if where is None and self.settles == "n_c" and self.before_sliding is not None:
            # most of the change (≥ 63 %, n_c within the reversals counted there) over before the
            # first gross sliding runs its course within the session's first experiment: the
            # sliding after it sees only its end, so a step between that experiment and the rest
            # — or a misfit following that experiment's own schedule of strokes — would look the
            # same (the lower bound's reason, where that experiment makes many reversals: a
            # telescope mount's 60 s of torque ramps, 6 of them, had its load's misfit named a
            # softening of n_c 3.5)
            count, t_sliding = self.before_sliding
            j = [f[0] for f in self.free].index("n_c")
            n_c = self.value("n_c", "log", u[j])
            if count >= 1 and n_c <= count:
                return (f"its n_c {n_c:.3g} is within the {count:.0f} reversals before the first gross sliding (at "
                        f"{t_sliding:.4g} s): {-math.expm1(-count / n_c):.0%} of the change is over within the session's "
                        f"first experiment, and a step between it and the rest (other strokes, other speeds) would look "
                        f"the same. To tell: {EFFECTS[self.name].separated_by}")
        if where is None:
            return None
        lo, hi = next(f[2:4] for f in self.free if f[0] == self.settles)
        if self.settles == "tau":
            # a drift: τ at T/10, its change over early in the session (a step between the first
            # experiments and the rest looks the same); at 20·T, a straight trend in time
            said = ("over within the first tenth of the session, and a step between the session's first experiments "
                    "and the rest would look the same" if where == "lower" else
                    "not seen to settle within the session, and a trend along the session's schedule would look the same")
            at = self.value(self.settles, "log", lo if where == "lower" else hi)
            return (f"its {self.settles} is at its {where} bound {at:.3g} s: the change is {said}. To tell: "
                    f"{EFFECTS[self.name].separated_by}")
        if where == "upper":
            unordered = strokes is not None and abs(strokes.rho) < SPEED_ORDER_RHO
            # "over the session": a schedule that cycles through rising speeds (a tribometer's
            # passes) keeps them in order within each cycle, where the stiffness following the
            # speed that a softening is judged beside takes up part of it
            trend = (f"the strokes' speeds do not follow the reversals over the session (|Spearman ρ| "
                     f"{strokes.rho:.2f} over {strokes.count} strokes), so a stiffness following the speed "
                     f"makes at most a part of it (within passes that run their speeds in order), but one "
                     f"changing with time would look the same" if unordered else
                     "a trend along the session's schedule (time, speed levels in order) would look the same")
            return (f"its {self.settles} is at its bound {self.value(self.settles, 'log', hi):.3g}: the change does not "
                    f"settle within the session, and {trend}. To tell: {EFFECTS[self.name].separated_by}")
        return (f"its {self.settles} is at its lower bound {self.value(self.settles, 'log', lo):.3g}: the change is "
                f"over within the first few reversals, and a step between the session's first experiment and the next (other "
                f"strokes, other speeds) would look the same. To tell: {EFFECTS[self.name].separated_by}")


STEP_LABEL_WIDTH = 44  # the report's column of step labels
SETTLE_TOL = math.log(1.02)  # a scale within 2 % of a bound is at it
# the size of the change a settling scale belongs to: at a bound of its range it is not seen
# settling either (``Term.unsettled``), and ``Term.pinned`` leaves it to that
SETTLED_SIZE = {"tau": "b", "n_c": "h"}
BOUND_TOL = 1e-3  # a linear parameter within this fraction of its range from a bound is at it


def softening_nc_max(strokes: SpeedOrder | None) -> float:
    """The largest n_c of a softening, as a fraction of the session's significant reversals.

    Where the strokes run at speeds in order of the reversals (``stroke_order``, |ρ| ≥
    SPEED_ORDER_RHO) a change still going on late in the session is also a stiffness following
    the speed, so it must be seen nearly complete: n_c ≤ half the reversals (86 % of the change
    by the session's end, its rate down to a seventh). Elsewhere that confound is absent and
    n_c ≤ the reversals suffices (63 %, its rate down to a third): a change whose slowing down
    the session shows. A contact's softening need not be exponential (one hyperbolic in the
    count, 1/(1 + n/n_h), fits an n_c well above n_h), so the stricter bound everywhere left
    true softenings on tribometers, whose passes cycle through their speeds, seen, not named."""
    unordered = strokes is not None and abs(strokes.rho) < SPEED_ORDER_RHO  # (a ρ of too few strokes is NaN)
    return 1.0 if unordered else 0.5


def presliding_range(params: FrictionParams) -> float:
    """Displacement over which the transition curve reaches 90 % of its last knot's force."""
    tc = params.transition_curve
    if tc.kind == "piecewise_linear":
        z, F = np.asarray(tc.z), np.asarray(tc.F)
        return float(np.interp(0.9 * F[-1], F, z))
    return float(2.0 * tc.shape["z0"])


def ripple_min_wavelength(cmp_: Comparison) -> float:
    """A ripple shorter than two presliding ranges cannot be told from the hysteresis that
    follows every reversal, nor one shorter than ten position noise sds from the noise."""
    return max(2.0 * cmp_.z_presliding, 10.0 * cmp_.position_noise)


def _terms_for(name: str, cmp_: Comparison, strokes: SpeedOrder | None = None, threshold: float | None = None) -> Term:
    """The free parameters of effect ``name`` on this comparison; ``strokes`` (``stroke_order``)
    sets how far a softening must be seen to settle (``softening_nc_max``), ``threshold`` the
    back-travel that counts as its reversal (default: the comparison's ``min_excursion``)."""
    t = cmp_.time
    T = float(t[-1] - t[0])
    if name == "time_drift":
        # the drift counts from the first sample compared (``initial_memory``): before it the
        # data say nothing of the friction's course, and a law started earlier trades its b for
        # the level there (a table compared from its first gross sliding at 31 s of 92 read
        # b = 3.1 for 0.21, and the model written ran away along the ramps before it)
        t0 = float(t[int(np.argmax(cmp_.scored))]) if cmp_.scored is not None and cmp_.scored.any() else float(t[0])
        T = float(t[-1] - t0)
        # τ ≥ T/10: a faster "drift" is a transient the first experiments of the session see
        # alone — a step between them and the rest, which a schedule ordered in time makes
        # out of any misfit of the model (a session must see a good part of a drift's course)
        # (one fitted at a bound of τ is not seen settling: ``Term.unsettled``)
        return Term(name, {"t0": t0}, (("b", "lin", -0.9, 5.0), ("tau", "log", math.log(0.1), math.log(20.0))),
                    settles="tau", refs={"tau": T})
    if name == "normal_load":
        n = cmp_.load
        moving = np.abs(cmp_.velocity) > cmp_.v_rest
        ref = float(np.median(n[moving])) if moving.any() else float(np.median(n))
        return Term(name, {"N0": ref if ref > 0 else float(np.max(n))}, (("alpha", "lin", 0.0, 3.0),))
    if name == "position_ripple":
        span = float(np.ptp(cmp_.path))
        lo = min(ripple_min_wavelength(cmp_), span / 4)
        # the phases read at the middle of the travel (``x0``): there they move little with λ,
        # so the sine and cosine parts are nearly apart from it, and their σ is the ripple's
        # own, not λ's times the wavelengths from position 0
        mid = 0.5 * (float(np.min(cmp_.path)) + float(np.max(cmp_.path)))
        return Term(name, {"x0": mid}, (("cs", "lin", -0.9, 0.9), ("cc", "lin", -0.9, 0.9),
                               ("wavelength", "log", math.log(lo / span), math.log(0.5)),
                               ("cs2", "lin", -0.5, 0.5), ("cc2", "lin", -0.5, 0.5)), refs={"wavelength": span})
    if name == "cyclic_softening":
        th = cmp_.min_excursion if threshold is None else float(threshold)
        counted = significant_reversals(cmp_.path, th)
        nrev = float(counted[-1])
        gs = gross_sliding(cmp_)
        i_gs = int(np.argmax(gs)) if gs.any() else None
        before = None if i_gs is None else (float(counted[i_gs]), float(t[i_gs]))
        return Term(name, {"min_excursion": th},
                    # n_c ≥ 3: a change complete within a couple of reversals is a constant
                    # stiffness factor, which the alternative's κ0 already holds; n_c at most a
                    # fraction of the reversals (``softening_nc_max``): a change still far from
                    # saturating at the session's end is a trend in the reversal count, which a
                    # schedule confounds with time and speed; one fitted at either bound has not
                    # been seen settling, and the report says so (``Term.unsettled``; unless
                    # ``Settings.must_settle`` is off it is not named)
                    (("h", "lin", -0.9, 5.0),
                     ("n_c", "log", math.log(3.0), math.log(max(nrev * softening_nc_max(strokes), 3.5)))),
                    settles="n_c", before_sliding=before)
    if name == "presliding_range":
        # e from the range fixed (−1: the stiffness rising with friction squared) to beyond the
        # stiffness fixed (2): a contact's tangential stiffness seldom grows faster than its friction
        return Term(name, {}, (("e", "lin", -1.0, 2.0),))
    if name == "rate_stiffness":
        st = cmp_.params.stribeck
        v_ref = min(abs(st.positive.vs), abs(st.negative.vs))
        # speeds below the rest threshold count as rest (at least 10⁻³ v_s: an exactly logged
        # position has no noise to set that threshold)
        v_floor = min(max(cmp_.v_rest, 1e-3 * v_ref), v_ref)
        return Term(name, {"v_ref": v_ref, "v_floor": v_floor}, (("c1", "lin", -2.0, 2.0), ("c2", "lin", -1.0, 1.0)))
    if name == "travel_stiffness":
        # loops from the smallest counted (min_excursion) to twice the presliding range, where a
        # stroke ends in gross sliding (``gross_sliding``) and its transition is the whole curve's
        # (a path logged exactly, with no presliding range: a thousandth of the travel, so that
        # no logarithm meets a travel of 0)
        z = max(cmp_.z_presliding, cmp_.min_excursion) or 1e-3 * float(np.ptp(cmp_.path)) or 1.0
        return Term(name, {"s_ref": z, "s_floor": max(cmp_.min_excursion, 1e-3 * z), "s_cap": 2.0 * z,
                           "min_excursion": cmp_.min_excursion},
                    (("c1", "lin", -2.0, 2.0), ("c2", "lin", -1.0, 1.0)))
    if name == "presliding_stiffness":
        return Term(name, {}, (("kappa", "log", math.log(0.05), math.log(20.0)),))
    raise KeyError(name)


def _entry(term: Term, u: np.ndarray) -> dict:
    vals = dict(term.fixed)
    for (pname, tr, _, _), ui in zip(term.free, u):
        vals[pname] = term.value(pname, tr, ui)
    if term.name == "position_ripple":
        # amplitude and phase of each harmonic from its sine and cosine parts (linear in them)
        cs, cc = vals.pop("cs"), vals.pop("cc")
        vals["a"] = float(min(math.hypot(cs, cc), 0.95))
        vals["phase"] = float(math.atan2(cc, cs))
        cs2, cc2 = vals.pop("cs2"), vals.pop("cc2")
        vals["a2"] = float(min(math.hypot(cs2, cc2), 0.5, max(0.0, 0.95 - vals["a"])))
        vals["phase2"] = float(math.atan2(cc2, cs2))
    return {"name": term.name, "params": vals}


def _entries(terms: list, u: np.ndarray) -> list:
    """The entries of ``terms`` from their free parameters laid end to end in ``u``."""
    out, i = [], 0
    for term in terms:
        out.append(_entry(term, u[i:i + len(term.free)]))
        i += len(term.free)
    return out


def _entry_to_u(term: Term, params: dict) -> np.ndarray:
    vals = dict(params)
    if term.name == "position_ripple":
        vals["cs"] = vals["a"] * math.cos(vals["phase"])
        vals["cc"] = vals["a"] * math.sin(vals["phase"])
        vals["cs2"] = vals.get("a2", 0.0) * math.cos(vals.get("phase2", 0.0))
        vals["cc2"] = vals.get("a2", 0.0) * math.sin(vals.get("phase2", 0.0))
    out = []
    for pname, tr, lo, hi in term.free:
        u = term.coordinate(pname, tr, vals[pname])
        out.append(min(max(u, lo), hi))
    return np.array(out)


class FreeSteadyCurve:
    """Part of the alternative every effect must beat: an additive correction to the steady
    friction S(v) of any shape — hat functions in log|v| per sliding direction, knots a factor
    ``ratio`` apart over the velocities the recording visits — one constant at rest, and (for
    friction taken from an applied force) a term proportional to the mean acceleration. It
    is linear in its coefficients, so it is fitted by least squares inside every evaluation
    (profiled out). An effect is then named only for what no steady-state curve explains:
    a change within a constant-velocity hold, between two visits of one speed, along the
    position, with the load or with the reversals — never a misfit of S(v) that a speed
    schedule ordered in time would make look like a drift."""

    def __init__(self, velocity: np.ndarray, v_rest: float, ratio: float = 2.0,
                 acceleration: np.ndarray | None = None, memory_offset: np.ndarray | None = None):
        n = len(velocity)
        self.memory_offset = memory_offset  # see ``initial_memory``
        # friction taken from an applied force: the inertia is free as well (a term I·ā, linear
        # in I), so an inertia held by the fit, or off, is not a residual an effect could take
        self.acceleration = acceleration
        self.n = n
        i0 = np.zeros(n, dtype=np.int64)
        i1 = np.zeros(n, dtype=np.int64)
        w0 = np.zeros(n)
        w1 = np.zeros(n)
        rest = np.abs(velocity) <= v_rest
        k = 1  # column 0: the constant at rest
        i0[rest] = 0
        w0[rest] = 1.0
        for sign in (1.0, -1.0):
            m = (velocity * sign) > v_rest
            if m.sum() < 10:
                continue
            u = np.log(np.abs(velocity[m]))
            lo, hi = float(np.percentile(u, 0.5)), float(np.percentile(u, 99.5))
            nk = max(2, int(math.ceil((hi - lo) / math.log(ratio))) + 1)
            knots = np.linspace(lo, hi, nk) if hi > lo else np.array([lo, lo + 1.0])
            pos = np.clip((np.clip(u, knots[0], knots[-1]) - knots[0]) / (knots[1] - knots[0]), 0, nk - 1 - 1e-12)
            j = np.floor(pos).astype(np.int64)
            fr = pos - j
            i0[m], w0[m] = k + j, 1.0 - fr
            i1[m], w1[m] = k + np.minimum(j + 1, nk - 1), fr
            k += nk
        self.k = k
        self.rest = rest
        self._cache = {}
        self._masks = {}
        self.i0, self.i1, self.w0, self.w1 = i0, i1, w0, w1

    def _on(self, idx: np.ndarray) -> "CurveSamples":
        """The curve's parts at the samples ``idx``, kept for the index arrays in use (a
        least-squares fit evaluates the same samples many times): up to 16 of them, and up to
        CURVE_CACHE_RECORDS records' worth of samples, however long the record."""
        hit = self._cache.get(id(idx))
        if hit is not None and hit.idx is idx:
            return hit
        i0, i1, w0, w1 = self.i0[idx], self.i1[idx], self.w0[idx], self.w1[idx]
        k = self.k
        G = (np.bincount(i0 * k + i0, w0 * w0, k * k) + np.bincount(i1 * k + i1, w1 * w1, k * k)
             + np.bincount(i0 * k + i1, w0 * w1, k * k) + np.bincount(i1 * k + i0, w1 * w0, k * k)).reshape(k, k)
        fixed = [a[idx] for a in self._fixed()]
        held = sum(len(a.idx) for a in self._cache.values())
        if len(self._cache) >= 16 or held + len(idx) > CURVE_CACHE_RECORDS * self.n:
            self._cache.clear()
        at = CurveSamples(idx, i0, i1, w0, w1, G, self.rest[idx], fixed)
        self._cache[id(idx)] = at
        return at

    def solve(self, r: np.ndarray, idx: np.ndarray, extra=()) -> tuple[np.ndarray, np.ndarray]:
        """Least-squares coefficients of the hat functions and of the ``extra`` columns fitted
        to ``r`` at the samples ``idx`` (``r`` and the columns given at those samples only; a
        coefficient they give no sample of stays 0), and the inverse normal matrix (the
        coefficients' covariance per unit residual variance)."""
        at = self._on(idx)
        i0, i1, w0, w1 = at.i0, at.i1, at.w0, at.w1
        k = self.k
        K = k + len(extra)
        b = np.zeros(K)
        b[:k] = np.bincount(i0, w0 * r, k) + np.bincount(i1, w1 * r, k)
        G = np.zeros((K, K))
        G[:k, :k] = at.G
        for j, em in enumerate(extra):
            b[k + j] = em @ r
            G[k + j, :k] = G[:k, k + j] = np.bincount(i0, w0 * em, k) + np.bincount(i1, w1 * em, k)
            for jj in range(j + 1):
                G[k + j, k + jj] = G[k + jj, k + j] = em @ extra[jj]
        # a ridge of 10⁻⁹ of the largest hat's square on the hats (1 where one has no sample), of
        # its own square on each extra column: one of the largest diagonal of all weighed the
        # hats against the acceleration's column, whose square follows the units (a record in
        # mm had a million times the ridge it had in m, and its alternative ended a quarter worse)
        d = np.diag(G).copy()
        ridge = np.concatenate([np.full(k, d[:k].max() if k else 1.0), d[k:]])
        G[np.diag_indices(K)] += 1e-9 * ridge + (d == 0)
        Ginv = np.linalg.inv(G)
        return Ginv @ b, Ginv

    def dense(self) -> np.ndarray:
        """The hat functions as an n × k matrix (for a regression that filters them)."""
        hats = np.zeros((self.n, self.k))
        rows = np.arange(self.n)
        np.add.at(hats, (rows, self.i0), self.w0)
        np.add.at(hats, (rows, self.i1), self.w1)
        return hats

    def evaluate(self, c: np.ndarray, extra: list, at: "CurveSamples | None" = None) -> np.ndarray:
        """The correction with coefficients ``c`` (hats, then ``extra`` columns) over every
        sample, or at the samples of ``at`` (the columns then given there)."""
        if at is None:
            out = c[self.i0] * self.w0 + c[self.i1] * self.w1
        else:
            out = c[at.i0] * at.w0 + c[at.i1] * at.w1
        for j, col in enumerate(extra):
            out = out + c[self.k + j] * col
        return out

    def fit(self, r: np.ndarray, mask: np.ndarray, model: np.ndarray | None = None) -> np.ndarray:
        """The correction over every sample fitted to ``r`` on ``mask``. With ``model`` (the
        model's friction), one more column: a level of its own for the friction at rest, the
        transition curve's, which need not share S(v)'s level g."""
        idx = self._indices(mask)
        c = self.solve(r[idx], idx, self._extra(model, self._on(idx)))[0]
        return self.evaluate(c, self._extra(model))

    def _indices(self, mask: np.ndarray) -> np.ndarray:
        """The samples of ``mask``, one index array per mask in use (``_on`` keeps the curve's
        parts by that array)."""
        hit = self._masks.get(id(mask))
        if hit is None or hit[0] is not mask:
            if len(self._masks) >= 16:
                self._masks.clear()
            self._masks[id(mask)] = hit = (mask, np.flatnonzero(mask))
        return hit[1]

    def _fixed(self) -> list:
        """The fixed columns beside the hats, in their order: the memory's constant, the mean
        acceleration (each where the curve has it)."""
        return [a for a in (self.memory_offset, self.acceleration) if a is not None]

    def _extra(self, model, at: "CurveSamples | None" = None) -> list:
        """The columns beside the hats — the level at rest (with ``model``, the model's
        friction), then ``_fixed`` — over every sample, or at the samples of ``at``."""
        if at is None:
            return ([] if model is None else [np.where(self.rest, model, 0.0)]) + self._fixed()
        return ([] if model is None else [np.where(at.rest, model[at.idx], 0.0)]) + at.fixed

    def residual_at(self, measured: np.ndarray, model: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """``measured − model`` minus the correction fitted to it (with the level at rest) at
        the samples ``idx``, evaluated there: what a least-squares step works on, computed at
        those samples only."""
        r = measured[idx] - model[idx]
        at = self._on(idx)
        extra = self._extra(model, at)
        return r - self.evaluate(self.solve(r, idx, extra)[0], extra, at)


CURVE_CACHE_RECORDS = 6  # ``FreeSteadyCurve._on`` keeps its parts for at most this many records' worth of samples


class CurveSamples(NamedTuple):
    """``FreeSteadyCurve``'s parts at a set of samples: each sample's two hat functions (indices
    and weights), their normal matrix, which samples are at rest, and the fixed columns there
    (the memory's constant, the mean acceleration, where the curve has them)."""

    idx: np.ndarray
    i0: np.ndarray
    i1: np.ndarray
    w0: np.ndarray
    w1: np.ndarray
    G: np.ndarray
    rest: np.ndarray
    fixed: list


@dataclass(frozen=True)
class ModelNuisance:
    """What the model written leaves free beside its parameters, fitted to a residual by
    linear least squares: the constant of ``initial_memory`` and, for friction taken from an
    applied force by eq. (8), the change ΔI of the inertia it was taken with (the residual then
    holds ΔI·ā, linear in ΔI). ``correction`` over every sample."""

    correction: np.ndarray
    d_inertia: float = 0.0


def model_nuisance(r: np.ndarray, mask: np.ndarray, offset: np.ndarray | None,
                   acceleration: np.ndarray | None) -> ModelNuisance:
    cols, names = [], []
    if offset is not None and (mask & (offset > 0)).any():
        cols.append(offset)
        names.append("memory")  # the constant of ``initial_memory``
    if acceleration is not None and np.any(acceleration[mask] != 0):
        cols.append(acceleration)
        names.append("d_inertia")
    if not cols:
        return ModelNuisance(np.zeros_like(r))
    X = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(X[mask], r[mask], rcond=None)
    # f̄ = I_true·ā + F, so r = f̄ − I·ā − F_model ≈ (I_true − I)·ā: the coefficient of ā is ΔI
    vals = {nm: float(c) for nm, c in zip(names, coef)}
    return ModelNuisance(X @ coef, vals.get("d_inertia", 0.0))


class Engine:
    """Predicts the compared signal for the base parameters, a level g, a stiffness κ0 and
    a list of effect entries, through ``model.effects``' factors and the simulator's scale
    arrays. Caches the stiffness-dependent simulation in friction space (a friction factor
    multiplies the output exactly there)."""

    def __init__(self, params: FrictionParams, cmp_: Comparison, free_steady: bool = True):
        self.p = params.replace(effects=())
        self.c = cmp_
        self.free = FreeSteadyCurve(cmp_.velocity, cmp_.v_rest, acceleration=cmp_.acceleration,
                                    memory_offset=cmp_.memory_offset) if free_steady else None
        self.ctx = cmp_.context()
        self.scored = np.ones(len(cmp_.time), bool) if cmp_.scored is None else cmp_.scored
        self._sims = []  # [(base, key, friction)], the most recently used last (``SIM_CACHE``)
        self._steadies = []  # [SteadyAlong], the same way
        self.sims = 0
        self.sim_seconds = 0.0  # spent in the simulations themselves (``DiagnosisWork``)
        self.free_inertia = False  # the model written: eq. (8)'s inertia left free beside it (``model_nuisance``)
        # the friction effects' factor a presliding range following them follows, where it is held
        # (``following_held``); None: the current one, every simulation keyed by the friction effects
        self.follow = None
        self._follow_token = 0

    def following_held(self, entries) -> None:
        """Hold the factor a presliding range following the friction effects follows at that of
        ``entries``' friction effects (None: follow the current ones again). A stiffness
        candidate and the alternative it must beat are then both fitted with the friction
        effects free but the stiffness following them as that alternative fitted them: a
        Jacobian column of a friction effect asks for no simulation, where otherwise each of
        them, a ripple's five and a load's one, simulates the whole record (on a rotary table
        made apart, two thirds of a diagnosis naming a load and a ripple went to the softening
        candidate's cross-validation). Exact at those entries; the folds' refits move the
        friction effects a little, and where a stiffness candidate is named its round's σ of
        the friction effects are of those refits."""
        follow = None
        if entries is not None and follows_friction(entries):
            follow = effect_scales([e for e in entries if EFFECTS[e["name"]].acts_on == "friction"], self.ctx)[0]
        self._follow_token += 1  # (the simulations kept while following the current factor stay valid: 0 in their key)
        self.follow = follow

    def loss(self) -> dict:
        """Least-squares loss on residuals in noise floors (``unit``): plain in friction; in
        position, soft-L1 beyond a few noise floors, because one window where the open-loop
        plant runs off (stick-slip on the falling Stribeck branch) would otherwise outweigh all
        the others."""
        if self.c.space == "friction":
            return {}
        return {"loss": "soft_l1", "f_scale": 3.0 * self.c.noise / self.unit}

    @property
    def unit(self) -> float:
        """What the least squares' residuals are divided by: the noise floor. Their optimum is
        the same in any unit, but the gradient test that ends a least-squares run is absolute
        (scipy's gtol, 10⁻⁸): a galvanometer axis made apart, its friction 2·10⁻⁵ N·m, had every
        fold's refit stop before its first step, and its softening written with σ = 0."""
        noise = float(self.c.noise)
        return noise if math.isfinite(noise) and noise > 0.0 else 1.0

    def score(self, r: np.ndarray) -> float:
        """The loss summed over residuals ``r`` (what cross-validation compares)."""
        if self.c.space == "friction":
            return float(np.sum(r**2))
        f = 3.0 * self.c.noise
        return float(np.sum(2.0 * f * f * (np.sqrt(1.0 + (r / f) ** 2) - 1.0)))

    def nuisance(self, r: np.ndarray, mask: np.ndarray, model: np.ndarray) -> np.ndarray:
        """The alternative's free steady curve (and level at rest) fitted to the residual
        ``r`` of the prediction ``model`` on ``mask``; without it, ``model_nuisance`` (the
        memory's constant, and the inertia where ``free_inertia`` is set)."""
        if self.free is not None:
            return self.free.fit(r, mask, model)
        return self.model_nuisance(r, mask).correction

    def model_nuisance(self, r: np.ndarray, mask: np.ndarray) -> ModelNuisance:
        """The nuisance of the model written (``model_nuisance``): the memory's constant, and the
        inertia where ``free_inertia`` is set."""
        return model_nuisance(r, mask, self.c.memory_offset, self.c.acceleration if self.free_inertia else None)

    def residual_at(self, model: np.ndarray, idx: np.ndarray) -> np.ndarray:
        """The residual of the prediction ``model`` beside the engine's nuisance (``nuisance``)
        fitted on the samples ``idx`` (a least-squares step's thinned set: ~20 coefficients
        need no more), at those samples, in noise floors (``unit``): what every least squares
        of the diagnosis minimises."""
        meas = self.c.measured
        if self.free is not None:
            return self.free.residual_at(meas, model, idx) / self.unit
        r = meas[idx] - model[idx]
        off = self.c.memory_offset
        acc = self.c.acceleration if self.free_inertia else None
        if off is not None or acc is not None:
            r = r - model_nuisance(r, np.ones(len(idx), bool), None if off is None else off[idx],
                                   None if acc is None else acc[idx]).correction
        return r / self.unit

    def set_base(self, params: FrictionParams) -> None:
        self.p = params.replace(effects=())

    def scales(self, g: float, k0: float, entries) -> tuple[np.ndarray, np.ndarray | None]:
        fs, ss = effect_scales(entries, self.ctx, self.follow)
        fs = np.full(len(self.c.time), g) if fs is None else g * fs
        ss = None if (ss is None and k0 == 1.0) else (np.full(len(self.c.time), k0) if ss is None else k0 * ss)
        return fs, ss

    def predict(self, g: float, k0: float, entries) -> np.ndarray:
        fs, ss = self.scales(g, k0, entries)
        c = self.c
        if c.space == "friction":
            return c.filtered(fs * self._simulated(self.sim_key(k0, entries), ss))
        return self._windows(fs, ss)

    def sim_key(self, k0: float, entries) -> tuple:
        """What the simulation in friction space depends on besides the base: κ0 and the
        stiffness effects, and the friction effects too where one of them follows their factor
        (``presliding_range``) and that factor is not held (``following_held``)."""
        everything = follows_friction(entries) and self.follow is None
        held = self._follow_token if self.follow is not None else 0
        return (k0, held, tuple((e["name"], tuple(sorted(e["params"].items()))) for e in entries
                                if everything or EFFECTS[e["name"]].acts_on == "stiffness"))

    def simulated(self, k0: float, entries) -> np.ndarray:
        """The friction simulated along the path (friction space), before the friction factor
        and the filter: what ``predict`` multiplies by the factor and filters."""
        return self._simulated(self.sim_key(k0, entries), self.scales(1.0, k0, entries)[1])

    def _simulated(self, key, ss) -> np.ndarray:
        """The friction simulated along the path for the base and the stiffness ``key``, from
        the last SIM_CACHE simulations where one matches: a finite-difference Jacobian perturbs
        one parameter at a time, and every column of a level or a friction factor after one of
        a stiffness (or of the base's n, σ1, S(v)) asks again for the unperturbed simulation."""
        for i, (p, k, sim) in enumerate(self._sims):
            if k == key and p == self.p:
                self._sims.append(self._sims.pop(i))
                return sim
        sa = self._steady()
        # along the shared S(v)'s own copies of the path, checked once when they were made
        sim = self._counted(friction_along, self.p, sa, stiffness_scale=ss)
        self._sims = self._sims[-(SIM_CACHE - 1):] + [(self.p, key, sim)]
        return sim

    def _counted(self, simulate, *args, **kw) -> np.ndarray:
        """One simulation of the record, counted and timed (``DiagnosisWork``)."""
        t0 = perf_counter()
        out = simulate(*args, **kw)
        self.sim_seconds += perf_counter() - t0
        self.sims += 1
        return out

    def _steady(self) -> SteadyAlong:
        """v and S(v) of the base along the path, from the last STEADY_CACHE S(v) (a refit of
        S(v) perturbs its levels one at a time; every other simulation shares the base's)."""
        for i, sa in enumerate(self._steadies):
            if sa.same_curve(self.p):
                self._steadies.append(self._steadies.pop(i))
                return sa
        sa = steady_along(self.p, self.c.time, self.c.path)
        self._steadies = self._steadies[-(STEADY_CACHE - 1):] + [sa]
        return sa

    def _windows(self, fs, ss) -> np.ndarray:
        from ..model.windows import simulate_windows

        c = self.c
        if not hasattr(self, "_starts"):
            self._starts = np.array([a for a, _ in c.windows], dtype=np.int64)
            v0 = c.velocity[self._starts].copy()
            v0[np.abs(v0) < c.v_rest] = 0.0
            self._x0 = c.path[self._starts].copy()
            self._v0 = v0
        return self._counted(simulate_windows, self.p, c.time, c.force, self._starts, self._x0, self._v0,
                             friction_scale=fs, stiffness_scale=ss)


@dataclass
class FitResult:
    g: float
    k0: float
    entries: list
    pred: np.ndarray  # the model with the alternative's free steady curve (what is scored)
    rss: float
    u: np.ndarray
    model: np.ndarray = None  # the model alone: what the parameter set predicts


SIM_CACHE = 4  # simulations the engine keeps (each one float per sample)
STEADY_CACHE = 2  # v and S(v) along the path the engine keeps (each two floats per sample)
FIT_SAMPLES = 6000  # residuals a least-squares step works on (an even subsample; the effects are slow)


def _thinned(mask: np.ndarray) -> np.ndarray:
    idx = np.flatnonzero(mask)
    stride = max(1, int(math.ceil(len(idx) / FIT_SAMPLES)))
    return idx[::stride]


LEVEL_RANGE = 5.0  # the alternative's level g within ×1/5 … ×5 of the file's
STIFFNESS_RANGE = 20.0  # its presliding stiffness κ0 within ×1/20 … ×20


def _factor_said(x: float, span: float) -> str:
    """'×0.830', or '×20.000 (at the end of its range ×1/20–×20)': a factor at a bound of its
    range is where the record pushed it, not where it settled."""
    at = abs(abs(math.log(x)) - math.log(span)) <= SETTLE_TOL
    return f"×{x:.3f}" + (f" (at the end of its range ×1/{span:g}–×{span:g})" if at else "")


def _fit_bounds(terms: list, fit_k0: bool) -> tuple[np.ndarray, np.ndarray]:
    """Bounds of ``_fit``'s vector: log g, (log κ0), every term's free parameters."""
    lo, hi = [-math.log(LEVEL_RANGE)], [math.log(LEVEL_RANGE)]
    if fit_k0:
        lo.append(-math.log(STIFFNESS_RANGE))
        hi.append(math.log(STIFFNESS_RANGE))
    for term in terms:
        for _, _, a, b in term.free:
            lo.append(a)
            hi.append(b)
    return np.array(lo), np.array(hi)


def _unpack(u: np.ndarray, terms: list, fit_k0: bool, k0: float) -> tuple:
    """(g, κ0, entries) of ``_fit``'s vector (κ0 = ``k0`` where it is not fitted)."""
    if fit_k0:
        return math.exp(u[0]), math.exp(u[1]), _entries(terms, u[2:])
    return math.exp(u[0]), k0, _entries(terms, u[1:])


DIFF_STEP = 1e-4  # relative step of ``_fit``'s forward differences (scipy's ``diff_step``)


def _stepped(u: np.ndarray, j: int, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """``u`` with its j-th entry moved by the forward-difference step scipy's ``least_squares``
    takes with ``diff_step`` (the relative step times |u_j|, signed as u_j; √ε·max(1, |u_j|)
    where that vanishes; turned back where it would leave the bounds), so that a Jacobian
    made here is the one it would make."""
    sign = 1.0 if u[j] >= 0.0 else -1.0
    h = DIFF_STEP * sign * abs(u[j])
    if (u[j] + h) - u[j] == 0.0:
        h = math.sqrt(np.finfo(float).eps) * sign * max(1.0, abs(u[j]))
    if not lo[j] <= u[j] + h <= hi[j] and abs(h) <= max(u[j] - lo[j], hi[j] - u[j]):
        h = -h
    out = u.copy()
    out[j] += h
    return out


@dataclass
class StiffnessChord:
    """The simulated friction's derivative in each entry of a fit's vector that changes the
    simulation (κ0, the stiffness effects, and a friction effect a presliding range follows
    where its factor is not held), taken once at ``anchor``.

    A fold's refit in cross-validation starts from the fit on every fold and moves little, so
    its Jacobian takes those columns along a chord from the anchor, corrected after each step
    (``jacobian``), and computes the others, which only multiply a simulation already made,
    afresh. Every function value is still the exact simulation: the refit's steps are accepted
    on the true residual. Without it each Jacobian of a stiffness candidate's fold refit
    simulated the record once per such entry (on a rotary table made apart, 1,700 of a
    diagnosis's 2,700 simulations). Not used for the model written's refit: there a plain chord
    of n, σ1 and S(v) stalls once the refit moves, and one taken afresh where it missed a step
    saves a seventh of the time at a written gap over 5 % worse on some recordings
    (docs/diagnosis-history.md, Speed)."""

    anchor: np.ndarray
    columns: dict  # index in the vector → d(simulated friction)/du_j at the anchor, per sample

    @classmethod
    def at(cls, engine: Engine, terms: list, u: np.ndarray, fit_k0: bool, k0: float) -> "StiffnessChord | None":
        """The chord at ``u``, or None where no entry changes the simulation (or the engine
        compares positions, where every evaluation simulates anyway)."""
        if engine.c.space != "friction":
            return None
        lo, hi = _fit_bounds(terms, fit_k0)
        u = np.clip(u, lo + 1e-9, hi - 1e-9)
        _, kk, entries = _unpack(u, terms, fit_k0, k0)
        key = engine.sim_key(kk, entries)
        moved = {}  # the steps that change the simulation, found before anything is simulated
        for j in range(len(u)):
            uj = _stepped(u, j, lo, hi)
            _, kj, ej = _unpack(uj, terms, fit_k0, k0)
            if engine.sim_key(kj, ej) != key:
                moved[j] = (uj[j] - u[j], kj, ej)
        if not moved:
            return None
        base = engine.simulated(kk, entries)
        return cls(u, {j: (engine.simulated(kj, ej) - base) / h for j, (h, kj, ej) in moved.items()})

    def jacobian(self, engine: Engine, terms: list, fit_k0: bool, k0: float, idx: np.ndarray, resid):
        """The Jacobian of ``resid`` (``_fit``'s residual on the samples ``idx``) for
        ``least_squares``: forward differences, with the simulation of a column in ``columns``
        moved along the chord instead of simulated again. The chord follows the refit
        (Broyden's update: after each step the columns are corrected by the least change that
        makes them reproduce the change of the simulation the step made), on a copy: every
        refit starts from the anchor's."""
        lo, hi = _fit_bounds(terms, fit_k0)
        js = sorted(self.columns)
        C = np.stack([self.columns[j] for j in js], axis=1)  # samples × chord entries
        last = [None, None]  # the vector and the simulation of the last Jacobian

        def jac(u):
            r0 = resid(u)
            _, kk, entries = _unpack(u, terms, fit_k0, k0)
            sim = engine.simulated(kk, entries)
            if last[0] is not None:
                step = (u - last[0])[js]
                ss = float(step @ step)
                if ss > 0.0:
                    C[...] += np.outer((sim - last[1]) - C @ step, step / ss)
            last[0], last[1] = u.copy(), sim
            J = np.empty((len(r0), len(u)))
            for j in range(len(u)):
                uj = _stepped(u, j, lo, hi)
                h = uj[j] - u[j]
                if j in self.columns:
                    gj, kj, ej = _unpack(uj, terms, fit_k0, k0)
                    fs, _ = engine.scales(gj, kj, ej)
                    rj = engine.residual_at(engine.c.filtered(fs * (sim + h * C[:, js.index(j)])), idx)
                else:
                    rj = resid(uj)
                J[:, j] = (rj - r0) / h
            return J

        return jac


def _fit(engine: Engine, terms: list, u0: np.ndarray, mask: np.ndarray, *, fit_k0: bool, k0: float,
         max_nfev: int = 60, chord: StiffnessChord | None = None) -> FitResult:
    """Least squares over log g, (log κ0), and every term's free parameters, on ``mask``;
    with ``chord``, the columns of the entries that change the simulation come from it."""
    lo, hi = _fit_bounds(terms, fit_k0)
    u0 = np.clip(u0, lo + 1e-9, hi - 1e-9)
    idx = _thinned(mask)
    if engine.c.space == "position":
        max_nfev = min(max_nfev, 12)  # every evaluation simulates the whole recording

    def resid(u):
        g, kk, entries = _unpack(u, terms, fit_k0, k0)
        m = engine.predict(g, kk, entries)
        return engine.residual_at(m, idx)

    jac = "2-point" if chord is None else chord.jacobian(engine, terms, fit_k0, k0, idx, resid)
    sol = least_squares(resid, u0, jac=jac, bounds=(lo, hi), method="trf", x_scale="jac", diff_step=DIFF_STEP,
                        max_nfev=max_nfev, **engine.loss())
    g, kk, entries = _unpack(sol.x, terms, fit_k0, k0)
    return fit_result(engine, g, kk, entries, sol.x, mask)


def fit_result(engine: Engine, g: float, k0: float, entries: list, u: np.ndarray, mask: np.ndarray) -> FitResult:
    """The prediction of a fitted (g, κ0, entries), with and without the engine's nuisance."""
    meas = engine.c.measured
    model = engine.predict(g, k0, entries)
    pred = model + engine.nuisance(meas - model, mask, model)
    return FitResult(g, k0, entries, pred, float(np.sum((meas - pred)[mask] ** 2)), u, model)


REFIT_BASE_U = 8  # refit_transition's vector: log g, log κ0, log n, log σ1, then Fs, Fc factors per side
CURVE_FACTOR_MAX = 20.0  # each segment of a piecewise-linear F_d refitted within this factor of the file's
CURVE_GROUPS_MAX = 8  # … in at most this many groups of neighbouring segments (each one simulation per Jacobian)
CURVE_MIN_GAIN = 0.1  # … and only if the model alone then leaves this much less RMS gap
SIGMA1_REFIT_MAX = 100.0  # σ1 refits within this factor of the file's
N_REFIT = (1.0, 40.0)  # n of eq. (5) refits within this range (at 40 the transition is all but a corner)
INERTIA_ABSENT = 0.05  # friction following the acceleration as if I were under this share of the I it was taken with
BASE_OFF_NOISE = 2.0  # with nothing named, the base is said to be off only if it leaves over this many noise floors


def inertia_beside_notes(inertia: float, d_i: float, acc_sd: float, noise: float) -> list:
    """What the inertia refitted beside the model alone says (``model_nuisance``'s ``d_i``
    added to the ``inertia`` the friction was taken with): the value, and where it is no
    positive inertia, or under INERTIA_ABSENT of it, what that may mean — unless the inertial
    term itself, I·ẍ with ẍ's sd ``acc_sd``, spans under the noise floor: then the refitted I
    is whatever the misfit asks and says nothing of the machine's (a rudder stock made apart,
    2·10⁴ kg·m² at 10⁻³ rad/s², read "as if I were −7070" and was told to give the inertia
    it had been given)."""
    span = inertia * acc_sd
    unread = span < noise
    notes = [f"the gaps of the model as given and written are of friction taken from the applied force with the "
             f"inertia refitted beside it: the recording's friction follows the acceleration as if I were "
             f"{inertia + d_i:.4g}, against the {inertia:.4g} it was taken with (not written: a misfit of the model "
             f"that follows the acceleration enters it too)"
             + (f"; the inertial term I·ẍ spans {span:.3g} (its sd here), under the noise floor {noise:.3g}: the "
                f"record does not read the inertia, and that value says nothing of it" if unread else "")]
    if inertia + d_i < INERTIA_ABSENT * inertia and not unread:
        # a measured friction logged under a force's name (``torque``) carries no I·ẍ at all
        what = ("no positive inertia at all" if inertia + d_i <= 0 else
                f"under {INERTIA_ABSENT:.0%} of the inertia the friction was taken with")
        notes.append(f"that is {what}: the column read as the applied force shows almost no inertial term (or a "
                     f"misfit of the model follows the acceleration): {NAME_IT_FRICTION}; if it is the applied "
                     f"force, give this machine's inertia (--params)")
    return notes


def base_off_verdict(rms_base_refit: float, noise: float, candidates, seen: bool = False) -> str:
    """What is said of a base that is off with nothing named (``Diagnosis.base_off``). Where the
    base refitted alone comes within BASE_OFF_NOISE noise floors, the base, not a missing effect,
    is what is off. Where it still leaves more, that rest is neither: no candidate was named for
    it, and a time variation or a force the library has no candidate for (a friction cycling with
    the temperature, gravity on a joint) would leave the same. ``seen``: candidates were seen and
    not named (confounded, not settling, not where they must show, not used): part of that rest
    may be theirs (a ball screw's load ramp, confounded with a drift, took 75 % of it held out)."""
    if noise > 0 and rms_base_refit > BASE_OFF_NOISE * noise:
        rest = f"what it leaves refitted alone ({rms_base_refit / noise:.1f} × the noise floor)"
        if seen:
            return (f"the base is off, and no candidate is named for {rest}, though the candidates seen and not named "
                    f"(above) may hold part of it: they, a contact this model's base cannot follow, or an effect "
                    f"outside the candidates ({', '.join(candidates)})")
        return (f"the base is off, and {rest} no candidate takes up: a contact this model's base cannot follow, or "
                f"an effect outside the candidates ({', '.join(candidates)})")
    return "the base, not a missing effect, is what is off"


def size_not_shown(name: str, values: dict, sd: dict) -> str | None:
    """Why every amplitude of the effect ``name`` (``EffectParam.shape_of``'s: a drift's b, a
    ripple's a and a2) is not told from none at ``values`` ± ``sd``, or None (one shows, or the
    effect has no such amplitude)."""
    eff = EFFECTS[name]
    amplitudes = sorted({a for p in eff.params for a in p.shape_of})
    weak = [why for a in amplitudes if (why := eff.amplitude_not_shown(a, values, sd))]
    return "; ".join(weak) if amplitudes and len(weak) == len(amplitudes) else None


def unread_load_note(columns: list) -> str:
    """The note on the columns not read that may hold a normal load (``may_be_load``): how to
    read a load among them, and, for a mass (``is_mass``), how to weigh it — a mass is refused as
    a load (``unit_of``), so naming it as one is no advice."""
    masses = [str(c) for c in columns if is_mass(str(c))]
    parts = ["a load that presses the contact among them is read with --columns normal_load=<column>"
             ] if len(masses) < len(columns) else []
    if masses:
        parts.append(f"{', '.join(masses)} {'is a mass' if len(masses) == 1 else 'are masses'}: a load is the whole "
                     f"force pressing the contact, the mass's weight m·g with what presses it without that mass "
                     f"(never 0), written in N as a column of its own and read with --columns normal_load=<column>")
    parts.append("only then is normal_load a candidate")
    return f"columns not read as any signal: {', '.join(map(str, columns))} — " + "; ".join(parts)


def load_not_pressing(load: np.ndarray, mask: np.ndarray | None, column: str, unit: str = "") -> str | None:
    """What to say of a normal-load column at or below 0 on some of the samples compared
    (``mask``), or None: the load candidate's (N/N0)^α makes friction vanish there (a joint's
    payload logged as its weight alone, 0 while unloaded, read α 0.23 and a gap 120 % worse)."""
    n = load if mask is None or not mask.any() else load[mask]
    low = n <= 0.0
    if not low.any():
        return None
    u = f" {unit}" if unit else ""
    return (f"the normal load ({column}) is at or below 0 on {np.mean(low):.1%} of the samples compared (down to "
            f"{float(np.min(n)):.3g}{u}): the load candidate's (N/N0)^α makes friction vanish there, so a friction "
            f"that follows a load added to one always there (a payload beside its carriage) does not fit it; a load "
            f"column is the whole force pressing the contact, never 0")


TURN_BACK = 0.25  # a temperature that comes back this share of its range from its extreme has turned back


def temperature_course(time: np.ndarray, temp: np.ndarray, unit: str = "") -> tuple[str, bool] | None:
    """How a logged temperature goes over ``time``, in words, and whether it turns back (rises,
    then falls by over TURN_BACK of its range, or the reverse): read on the temperature
    averaged over a fiftieth of the samples, so that a sensor's noise makes no turn. None with
    under 10 finite samples."""
    ok = np.isfinite(temp)
    if ok.sum() < 10:
        return None
    t, T = time[ok], temp[ok]
    w = max(1, len(T) // 50)
    sm = uniform_filter1d(T.astype(float), w, mode="nearest")
    first, last = float(sm[0]), float(sm[-1])
    i_hi, i_lo = int(np.argmax(sm)), int(np.argmin(sm))
    hi, lo = float(sm[i_hi]), float(sm[i_lo])
    rng = hi - lo
    u = f" {unit}" if unit else ""
    if rng <= 0:
        return f"stays at {first:.4g}{u}", False
    if hi - first > TURN_BACK * rng and hi - last > TURN_BACK * rng:
        return (f"rises from {first:.4g} to {hi:.4g}{u} by {t[i_hi]:.4g} s, then falls to {last:.4g}{u}", True)
    if first - lo > TURN_BACK * rng and last - lo > TURN_BACK * rng:
        return (f"falls from {first:.4g} to {lo:.4g}{u} by {t[i_lo]:.4g} s, then rises to {last:.4g}{u}", True)
    return f"goes from {first:.4g} to {last:.4g}{u} (between {lo:.4g} and {hi:.4g})", False


def unsettled_among(candidates: list, s: "Settings") -> list:
    """With ``Settings.must_settle`` (the default): the candidates (``Evidence.as_dict``) with
    held-out evidence that were not named because their change is not seen to settle within
    the session (``Term.unsettled``)."""
    if not s.must_settle:
        return []  # such a candidate is named, with that caveat in the notes
    return [c for c in candidates if c.get("unsettled") and c.get("evident")]


def seen_unnamed(confounded: list, unused: list, candidates: list, s: "Settings") -> bool:
    """Whether any candidate was seen and not named: confounded, not settling, not where it must
    show, or not used by the model written (``base_off_verdict``'s ``seen``)."""
    return bool(confounded or unused or unsettled_among(candidates, s) or elsewhere_among(candidates))


def elsewhere_among(candidates: list) -> list:
    """The candidates (``Evidence.as_dict``) that gain held out, but not where their physics
    must show (``Evidence.elsewhere``), and were not named."""
    return [c for c in candidates if c.get("elsewhere") and not c.get("significant")]


def _at_range_end(x: float, ends) -> bool:
    """Whether a value a refit ranges on a log scale ended at one of its range's ``ends``."""
    ends = [e for e in ends if e > 0]
    return x > 0 and bool(ends) and min(abs(math.log(x / e)) for e in ends) < 0.01


# what marks the provenance.held entries a diagnosis writes for n, σ1 and the transition curve
# at a bound (``unresolved_curve``, the refit's range ends): a later diagnosis says its own
DIAGNOSIS_BOUNDS = ("the diagnosis's refit range", "the record does not resolve that shape")


def unresolved_curve(written: FrictionParams, cp: ComparedPath, k0: float, unit: str = "") -> str | None:
    """Why the transition curve ``written`` (its z already divided by the stiffness ``k0`` the
    refit put on it) is not resolved by the record, or None: knots closer together than twice
    the position's resolution (one encoder step, or one noise sd), the spacing under which
    ``fit`` places no knot. A refit whose κ0 compresses the curve that far (a 0.01° encoder's
    joint made apart, κ0 ×18: knots from 26 µrad, the step 175 µrad) writes a shape the sensor
    cannot see, which is a bound the record pushed it to, not an estimate."""
    tc = written.transition_curve
    if written.model != "leuven" or tc.kind != "piecewise_linear" or len(tc.z) < 2:
        return None
    res = cp.step if cp.step > 0 else cp.sd
    spacing = float(np.min(np.diff(np.asarray(tc.z, dtype=float))))
    if res <= 0 or spacing >= 2.0 * res:
        return None
    u = f" {unit}" if unit else ""
    return ((f"with the presliding stiffness ×{k0:.3g} the file's, " if abs(math.log(k0)) > 0.01 else "")
            + f"its knots lie {spacing:.3g}{u} apart (up to "
            f"{tc.z[-1]:.3g}{u}), under twice the position's resolution ({res:.3g}{u}, "
            f"{'an encoder step' if cp.step > 0 else 'its noise sd'}): the record does not resolve that shape, so "
            f"the curve written is a bound the refit reached, not an estimate")


REFIT_NFEV_FROM = 20  # least-squares steps of a refit that starts from another's solution (each step simulates)


def curve_groups(params: FrictionParams, refit_curve: bool) -> np.ndarray:
    """The group of each segment of a piecewise-linear F_d whose rise ``refit_transition``
    scales by one factor: every segment its own up to CURVE_GROUPS_MAX segments, else that many
    runs of neighbours. Empty: the curve is not refitted."""
    tc = params.transition_curve
    if not refit_curve or tc.kind != "piecewise_linear":
        return np.zeros(0, dtype=np.int64)
    nseg = len(tc.F) - 1
    return (np.arange(nseg) * min(nseg, CURVE_GROUPS_MAX)) // nseg


def refit_length(params: FrictionParams, refit_curve: bool) -> int:
    """Length of ``refit_transition``'s base vector (before the terms' parameters)."""
    groups = curve_groups(params, refit_curve)
    return REFIT_BASE_U + (int(groups.max()) + 1 if len(groups) else 0)


@dataclass(frozen=True)
class TransitionRefit:
    """What ``refit_transition`` found: the base with n, σ1, S(v) (and the transition curve's
    segments) updated, the level, the stiffness, the terms' entries, and the solution vector
    (a warm start for the next)."""

    params: FrictionParams
    g: float
    k0: float
    entries: list
    u: np.ndarray


def refit_transition(engine: Engine, params: FrictionParams, terms: list, prior_u: np.ndarray,
                     mask: np.ndarray, start: np.ndarray | None = None, max_nfev: int = 40,
                     refit_curve: bool = False) -> TransitionRefit:
    """Part of the alternative: the level g, the presliding stiffness κ0, the exponent n of
    eq. (5) (how sharply presliding turns into sliding), the micro-viscous σ1 of eq. (3) and
    the levels of S(v) (Fs, Fc per side, each within a factor 1.5), refitted together by output
    error: what an effect must beat is the best the base model can do on its own. With
    ``refit_curve``, the rise of a piecewise-linear F_d over each of its segments too (within
    CURVE_FACTOR_MAX): a curve identified on a few presliding branches at the start of a
    session (or on branches an effect distorted) is reshaped by every transition of the whole
    record. ``start``: a solution vector to start from (the bounds stay those of ``params``)."""
    if params.model != "leuven":
        return TransitionRefit(params, 1.0, 1.0, [], np.zeros(0))
    from ..model import Stribeck, StribeckSide

    n0, s10 = float(params.n), float(max(params.sigma1, 1e-12))
    sp, sn = params.stribeck.positive, params.stribeck.negative
    # S(v) levels per side, Fs and Fc as factors; vs, δ and σ2 held: a session whose speeds rise
    # with time would let them take up a drift in time
    NS = REFIT_BASE_U - 4
    nb = refit_length(params, refit_curve)
    NC = nb - REFIT_BASE_U
    tc = params.transition_curve
    groups = curve_groups(params, refit_curve)
    rise = np.diff(np.asarray(tc.F, dtype=float)) if NC else np.zeros(0)

    def side(s, f):
        return StribeckSide(Fs=s.Fs * f[0], Fc=s.Fc * f[1], vs=s.vs, delta=s.delta, sigma2=s.sigma2)

    def unpack(u):
        g, kk, ln, ls = math.exp(u[0]), math.exp(u[1]), u[2], u[3]
        fac = np.exp(u[4:4 + NS])
        entries = _entries(terms, u[nb:])
        st = Stribeck(side(sp, fac[:2]), side(sn, fac[2:]))
        p = params.replace(n=float(n0 * math.exp(ln)), sigma1=float(s10 * math.exp(ls)), stribeck=st)
        if NC:
            F = np.concatenate([[0.0], np.cumsum(rise * np.exp(u[REFIT_BASE_U:nb][groups]))])
            p = p.replace(transition_curve=TransitionCurve(kind="piecewise_linear", z=tc.z, F=tuple(map(float, F))))
        return g, kk, p, entries

    idx = _thinned(mask)

    def resid(u):
        g, kk, p, entries = unpack(u)
        engine.set_base(p)
        m = engine.predict(g, kk, entries)
        return engine.residual_at(m, idx)

    # a refit, not a new identification: each S(v) value within a factor 1.5 of the fit's
    b = math.log(1.5)
    c = math.log(CURVE_FACTOR_MAX)
    lo = np.concatenate([[-math.log(5), -math.log(20), math.log(N_REFIT[0] / n0), -math.log(SIGMA1_REFIT_MAX)], np.full(NS, -b),
                         np.full(NC, -c), [f[2] for t in terms for f in t.free]])
    hi = np.concatenate([[math.log(5), math.log(20), math.log(N_REFIT[1] / n0), math.log(SIGMA1_REFIT_MAX)], np.full(NS, b),
                         np.full(NC, c), [f[3] for t in terms for f in t.free]])
    u0 = np.concatenate([np.zeros(nb), prior_u]) if start is None else np.asarray(start, float)
    u0 = np.clip(u0, lo + 1e-9, hi - 1e-9)
    sol = least_squares(resid, u0, bounds=(lo, hi), method="trf", x_scale="jac", diff_step=1e-3,
                        max_nfev=max_nfev if engine.c.space == "friction" else 15, **engine.loss())
    g, kk, p, entries = unpack(sol.x)
    engine.set_base(p)
    return TransitionRefit(p, g, kk, entries, sol.x)


@dataclass(frozen=True)
class BaseRefit:
    """The base refitted alone (``refit_base``): what every candidate must beat."""

    alone: TransitionRefit  # as the model alone: its memory's constant and the inertia free, no free steady curve
    refit_curve: bool  # whether the transition curve's segments were reshaped (CURVE_MIN_GAIN)
    refit: TransitionRefit  # then beside the free steady curve, as the decision compares
    null: FitResult  # the level and stiffness, and the file's own effects, refitted beside it
    curve_note: str | None  # what the reshaping of the curve gave, for the notes


def refit_base(engine: Engine, base_params: FrictionParams, prior_terms: list, prior_u: np.ndarray,
               allm: np.ndarray, may_refit_curve: bool) -> BaseRefit:
    """n, σ1, the levels of S(v) (and, where that pays clearly, the transition curve's segments)
    refitted to the friction the engine compares (``engine.c.measured``), with the file's own
    effects ``prior_terms`` at ``prior_u``; the engine's base is left at the refit."""
    cmp_ = engine.c
    meas = cmp_.measured
    # first as the model alone (its memory's constant and inertia free, as the model written), then
    # beside the free steady curve from there: a curve the fit left far off (a segment of the
    # stiffness of a jump) would otherwise stay where the free curve's flat valley holds it
    free = engine.free
    engine.free, engine.free_inertia = None, True
    note = None
    try:
        alone = refit_transition(engine, base_params, prior_terms, prior_u, allm)
        nc = refit_length(base_params, True) - REFIT_BASE_U if may_refit_curve and base_params.model == "leuven" else 0
        refit_curve = False
        if nc:
            # the curve's segments are reshaped only where that pays clearly (CURVE_MIN_GAIN): a
            # curve that already fits stays as the file has it, so the decision is not moved by a
            # reshaping the data do not ask for
            shaped = refit_transition(engine, base_params, prior_terms, prior_u, allm, refit_curve=True,
                                      start=np.concatenate([alone.u[:REFIT_BASE_U], np.zeros(nc),
                                                            alone.u[REFIT_BASE_U:]]), max_nfev=REFIT_NFEV_FROM)
            gaps = []
            for r in (alone, shaped):
                engine.set_base(r.params)
                gaps.append(_rms((meas - fit_result(engine, r.g, r.k0, r.entries, r.u, allm).pred)[allm]))
            gap_plain, gap_shaped = gaps
            refit_curve = gap_shaped < (1.0 - CURVE_MIN_GAIN) * gap_plain
            note = (f"the transition curve's segments refitted to the whole record: the model alone leaves "
                    f"{gap_shaped:.3g} against {gap_plain:.3g} with the file's shape — "
                    + ("kept" if refit_curve else f"under {CURVE_MIN_GAIN:.0%} less, the file's shape kept"))
            if refit_curve:
                alone = shaped
    finally:
        engine.free, engine.free_inertia = free, False
    # then beside the free steady curve, as the decision compares (without it, with the inertia held)
    base_refit = refit_transition(engine, base_params, prior_terms, prior_u, allm, start=alone.u,
                                  refit_curve=refit_curve, max_nfev=REFIT_NFEV_FROM)
    # the level and stiffness start where the base's refit left them (κ0 and the curve's
    # segments were fitted together: from κ0 = 1 the reshaped curve would start off its basin)
    refit_prior_u = base_refit.u[len(base_refit.u) - len(prior_u):] if len(base_refit.u) else prior_u
    null = _fit(engine, prior_terms, np.concatenate([[math.log(base_refit.g), math.log(base_refit.k0)], refit_prior_u]),
                allm, fit_k0=True, k0=1.0)
    return BaseRefit(alone, refit_curve, base_refit, null, note)


# ---------------------------------------------------------------- screening a candidate's shape
def engine_params_for_scale(cmp_: Comparison) -> FrictionParams:
    return cmp_.params


def _ripple_wavelengths(cmp_: Comparison, resid: np.ndarray, base: np.ndarray, lam_min: float, count: int = 3,
                        keep: np.ndarray | None = None) -> list:
    """Wavelengths of the strongest peaks in the spectrum of the relative residual against
    position (sliding samples, binned on a uniform position grid; only ``keep``'s, where given)."""
    moving = np.abs(cmp_.velocity) > cmp_.v_rest
    if keep is not None:
        moving = moving & keep
    if cmp_.space == "friction":
        ok = moving & (np.abs(base) > 0.2 * np.max(np.abs(base)))
        y = resid[ok] / base[ok]
        x = cmp_.path[ok]
    else:
        # position space: I·ë of the window residual is the friction error (smoothed: the
        # residual holds the encoder staircase), relative to the friction level
        nwin = cmp_.windows[0][1] - cmp_.windows[0][0] if cmp_.windows else 42
        wl = min(max(7, nwin // 6), 101) | 1
        scale = np.abs(stribeck_curve(engine_params_for_scale(cmp_), cmp_.velocity)) + 1e-300
        y = savgol_filter(resid, wl, 3, deriv=2) / scale
        x = cmp_.path
        ok = moving
        y = y[ok]
        x = x[ok]
    if len(x) < 64 or np.ptp(x) <= 0:
        return []
    nb = int(min(8192, max(256, len(x) // 4)))
    edges = np.linspace(x.min(), x.max(), nb + 1)
    idx = np.clip(np.searchsorted(edges, x) - 1, 0, nb - 1)
    s = np.bincount(idx, y, nb)
    c = np.bincount(idx, None, nb)
    have = c > 0
    prof = np.zeros(nb)
    prof[have] = s[have] / c[have]
    if have.sum() < 32:
        return []
    prof[have] -= prof[have].mean()
    prof[~have] = 0.0
    spec = np.abs(np.fft.rfft(prof * np.hanning(nb)))
    dxb = (edges[1] - edges[0])
    k = np.arange(len(spec))
    # at least 3 periods over the range, 4 bins a period, not shorter than lam_min
    valid = (k >= 3) & (k <= nb // 4) & (k <= nb * dxb / max(lam_min, 1e-300))
    out = []
    sp = np.where(valid, spec, 0.0)
    for _ in range(count):
        i = int(np.argmax(sp))
        if sp[i] <= 0:
            break
        # parabolic refinement of the peak
        if 0 < i < len(spec) - 1:
            a, b, cc = spec[i - 1], spec[i], spec[i + 1]
            den = a - 2 * b + cc
            # the vertex of the parabola through the three bins; it lies within half a bin of
            # the peak bin unless the neighbours are flat (then it is not refined)
            di = 0.5 * (a - cc) / den if den != 0 else 0.0
            di = di if abs(di) <= 0.5 else 0.0
        else:
            di = 0.0
        out.append(nb * dxb / (i + di))
        sp[max(i - 2, 0):i + 3] = 0.0
    return out


TRAVEL_FORCE_SIGMAS = 5.0  # a force along the travel is said only this many block-jackknife σ clear of none
TRAVEL_FORCE_BLOCKS = 10  # contiguous blocks of the sliding samples its σ is taken over (their errors are not white)
TRAVEL_FORCE_BINS = 24  # bins of one period the residual is folded into (``TravelForce.up``, ``.down``)
# the share of the sliding residual's RMS it must take out, as a candidate must gain held out
# (``Settings.min_gain``'s default): a tribometer of the suite read 8.6 σ at a third of its
# noise floor, most of it at its slowest speed, taking out 0.03 % of what the base refitted
# alone left there
TRAVEL_FORCE_MIN_GAIN = 0.03


class SlidingRuns(NamedTuple):
    """The sliding samples of a residual, cut into runs (contiguous sliding one way), each run's
    own offset — S(v)'s misfit at its speed, a drift — taken out (``within``): what a force
    along the travel is read from (``travel_force``, ``travel_spring``)."""
    idx: np.ndarray  # the sliding samples, indices into the comparison
    up: np.ndarray  # moving the positive way, per sliding sample
    run: np.ndarray  # its run, per sliding sample
    count: np.ndarray  # samples per run

    def within(self, col: np.ndarray) -> np.ndarray:
        """``col`` less its run's mean: the least squares with an offset per run, by
        Frisch–Waugh–Lovell, on the residual and on the columns alike."""
        return col - (np.bincount(self.run, col) / self.count)[self.run]


def sliding_runs(cmp_: Comparison, mask: np.ndarray) -> SlidingRuns | None:
    """The runs of ``mask``'s sliding samples (|v| above the comparison's rest), or None where
    there are too few each way to say anything along the travel."""
    v = cmp_.velocity
    idx = np.flatnonzero(mask & (np.abs(v) > cmp_.v_rest))
    up = v[idx] > 0
    if len(idx) < 20 * TRAVEL_FORCE_BLOCKS or up.sum() < 10 * TRAVEL_FORCE_BLOCKS or (~up).sum() < 10 * TRAVEL_FORCE_BLOCKS:
        return None
    run = np.cumsum(np.concatenate([[True], (np.diff(idx) != 1) | (up[1:] != up[:-1])])) - 1
    return SlidingRuns(idx, up, run, np.bincount(run))


class SignKeeping(NamedTuple):
    """A force along the travel read each way of the motion (``sign_keeping``): the part keeping
    its sign, per column, the part following the motion's, and the evidence it is one force."""
    keeps: np.ndarray
    follows: np.ndarray
    sd: float  # the part keeping its sign: σ per column, jackknifed over TRAVEL_FORCE_BLOCKS blocks
    halves: tuple  # in the slower and the faster half of the sliding: (size, σ per column) each
    speed_gap: float  # how far the two halves lie apart, and that difference's σ
    speed_gap_sd: float
    gain: float  # the share of the sliding residual's RMS the part keeping its sign takes out


def sign_keeping(runs: SlidingRuns, X: np.ndarray, y: np.ndarray, speed: np.ndarray) -> SignKeeping:
    """Least squares of ``y`` (the sliding residual, ``within`` its runs) on ``X``: m columns
    moving up, then the same m moving down (each ``within`` its runs). Friction opposes the
    motion, so its part changes sign with the direction; a force along the travel — a motor's
    cogging, gravity on a joint, a spring or a cable — does not: the half-sum of the two
    directions' coefficients is that force, the half-difference the part following the motion.
    ``speed`` is |v| per sliding sample."""
    up = runs.up
    m = X.shape[1] // 2

    def parts(rows):
        c = np.linalg.lstsq(X[rows], y[rows], rcond=None)[0]
        return 0.5 * (c[:m] + c[m:]), 0.5 * (c[:m] - c[m:])

    def keeping(rows):
        """The part keeping its sign on ``rows`` (a boolean mask of the sliding samples), and its
        σ per column, jackknifed over TRAVEL_FORCE_BLOCKS contiguous blocks of them."""
        at = np.flatnonzero(rows)
        if min((rows & up).sum(), (rows & ~up).sum()) < 10 * TRAVEL_FORCE_BLOCKS:
            return np.full(m, np.nan), math.inf  # one way too few to say (not shown)
        block = np.full(len(y), -1)
        block[at] = np.minimum(np.arange(len(at)) * TRAVEL_FORCE_BLOCKS // len(at), TRAVEL_FORCE_BLOCKS - 1)
        jack = np.array([parts(rows & (block != b))[0] for b in range(TRAVEL_FORCE_BLOCKS)])
        nb = TRAVEL_FORCE_BLOCKS
        return parts(rows)[0], math.sqrt((nb - 1) / nb * np.sum((jack - jack.mean(axis=0)) ** 2) / m)

    everywhere = np.ones(len(y), dtype=bool)
    keeps, follows = parts(everywhere)
    _, sd = keeping(everywhere)
    # a force along the travel is the same at every speed; a disturbance periodic in time (a
    # limit cycle, a hum) reads as one along the travel only at one speed, its period in
    # position the speed's multiple: the slower and the faster half of the sliding must both
    # show it, and agree
    med = np.median(speed)
    slow = speed < med
    if slow.mean() < 0.25:
        # speeds in levels, the slowest holding half the sliding or more: split above it
        slow = speed <= med
    (ks, ss), (kf, sf) = keeping(slow), keeping(~slow)
    # the force keeping its sign, either way: within(u·c) + within(d·c) = within(c)
    force = (X[:, :m] + X[:, m:]) @ keeps
    gain = 1.0 - math.sqrt(np.mean((y - force) ** 2) / max(np.mean(y ** 2), 1e-300))
    size = np.linalg.norm
    return SignKeeping(keeps, follows, sd, ((float(size(ks)), ss), (float(size(kf)), sf)), float(size(ks - kf)),
                       math.hypot(ss, sf), float(gain))


def _shown_along(size: float, following: float, sd: float, halves: tuple, speed_gap: float, speed_gap_sd: float,
                 gain: float) -> bool:
    """A force along the travel is said where it is clear of none by TRAVEL_FORCE_SIGMAS σ, twice
    the part following the motion, seen at both halves of the speeds alike (each by 3 σ, the
    two within 3 σ of each other), and takes out TRAVEL_FORCE_MIN_GAIN of the sliding residual's
    RMS."""
    return bool(size > TRAVEL_FORCE_SIGMAS * sd and size > 2.0 * following
                and all(a > 3.0 * s for a, s in halves) and speed_gap < 3.0 * speed_gap_sd
                and gain >= TRAVEL_FORCE_MIN_GAIN)


@dataclass
class TravelForce:
    """A force periodic along the travel that keeps its sign whichever way the motion goes
    (``travel_force``): amplitudes in the force's units, the wavelength in the position's."""
    wavelength: float
    amplitude: float  # of the part that keeps its sign both ways
    sd: float  # its σ, jackknifed over TRAVEL_FORCE_BLOCKS blocks of the sliding
    following: float  # amplitude of the part that follows the motion's sign, as a friction ripple does
    phase: float  # the part keeping its sign is amplitude·sin(2π·x/wavelength + phase)
    # the residual folded over one period, TRAVEL_FORCE_BINS bins of position within it: its mean
    # in each bin moving up and moving down (None where a bin has no sample), the evidence to look at
    up: tuple = ()
    down: tuple = ()
    # the part keeping its sign in the slower and in the faster half of the sliding, each as
    # (amplitude, σ per component), and how far the two lie apart, with that difference's σ
    halves: tuple = ()
    speed_gap: float = 0.0
    speed_gap_sd: float = 0.0
    gain: float = 0.0  # the share of the sliding residual's RMS it takes out (each run's own offset out first)

    def along(self, cmp_: "Comparison") -> np.ndarray:
        """The force along the compared path, as the comparison sees friction (``filtered``)."""
        return cmp_.filtered(self.amplitude * np.sin(2.0 * math.pi * cmp_.path / self.wavelength + self.phase))

    @property
    def shown(self) -> bool:
        return _shown_along(self.amplitude, self.following, self.sd, self.halves, self.speed_gap, self.speed_gap_sd,
                            self.gain)


def travel_force(cmp_: Comparison, resid: np.ndarray, mask: np.ndarray, lam_min: float) -> TravelForce | None:
    """The part of the residual periodic along the travel that keeps its sign both ways, or
    None. At the strongest wavelength of the residual against position in the sliding, each
    direction is fitted as an offset per run + A_d·sin θ + B_d·cos θ (``sign_keeping``)."""
    if cmp_.space != "friction":
        return None
    runs = sliding_runs(cmp_, mask)
    if runs is None:
        return None
    # each run has an offset of its own taken out of the residual and of the columns alike: a
    # slow run shorter than a period had leaked its level into the wave (a linear-motor stage
    # made apart, its cogging read 0.76 N slow, 1.10 fast)
    idx, up, within = runs.idx, runs.up, runs.within
    x, y = cmp_.path[idx], within(resid[idx])
    spread = np.zeros_like(resid)
    spread[idx] = y
    sliding = np.zeros(len(resid), dtype=bool)
    sliding[idx] = True
    lams = _ripple_wavelengths(cmp_, spread, np.ones_like(resid), lam_min, 1, keep=sliding)
    if not lams:
        return None
    u, d = up.astype(float), (~up).astype(float)

    def waves(lam):
        """sin θ and cos θ of the whole path, seen as the measurement sees a force along it (the
        comparison's moving average, ``filtered``), at the sliding samples: averaged over 0.05 s,
        a ball screw's motor turning at 100 rad/s passes 5 rad, more than its cogging's period of
        π, and the faster half of the sliding read a fraction of the slower's."""
        th = 2.0 * math.pi * cmp_.path / lam
        return cmp_.filtered(np.sin(th))[idx], cmp_.filtered(np.cos(th))[idx]

    def columns(lam):
        sn, cs = waves(lam)
        return np.column_stack([within(u * sn), within(u * cs), within(d * sn), within(d * cs)])

    def rss(lam):
        A = columns(lam)
        return float(np.sum((y - A @ np.linalg.lstsq(A, y, rcond=None)[0]) ** 2))

    # the spectrum's peak is read to within a bin; the least squares places it (±3 %, a bin
    # being a period less over the range, at least 3 periods a range). Over a travel of many
    # periods the squares have a local minimum every λ²/span in λ (the wave slips a period over
    # the span): a grid at a quarter of that first, then the best cell refined (a ball screw's
    # π rad over 300 rad of travel: a local search from the peak stopped at 3.095)
    span = float(np.ptp(x))
    cell = 0.25 * lams[0] ** 2 / max(span, lams[0])
    grid = np.linspace(0.97 * lams[0], 1.03 * lams[0], int(np.clip(math.ceil(0.06 * lams[0] / cell), 7, 400)) + 1)
    best = grid[int(np.argmin([rss(g) for g in grid]))]
    step = grid[1] - grid[0]
    lam = float(minimize_scalar(rss, bounds=(best - step, best + step), method="bounded",
                                options={"xatol": 1e-5 * lams[0]}).x)
    k = sign_keeping(runs, columns(lam), y, np.abs(cmp_.velocity[idx]))
    frac = np.mod(x / lam, 1.0)
    b = np.minimum((frac * TRAVEL_FORCE_BINS).astype(int), TRAVEL_FORCE_BINS - 1)

    def folded(rows):
        n = np.bincount(b[rows], minlength=TRAVEL_FORCE_BINS)
        tot = np.bincount(b[rows], y[rows], minlength=TRAVEL_FORCE_BINS)
        mean = np.where(n > 0, tot / np.maximum(n, 1), np.nan)
        return tuple(float(m) if np.isfinite(m) else None for m in mean - np.nanmean(mean))  # (None: JSON's null)

    return TravelForce(lam, float(np.hypot(*k.keeps)), k.sd, float(np.hypot(*k.follows)),
                       float(math.atan2(k.keeps[1], k.keeps[0])), folded(up), folded(~up),
                       k.halves, k.speed_gap, k.speed_gap_sd, k.gain)


@dataclass
class TravelSpring:
    """A force in proportion to the travel that keeps its sign whichever way the motion goes
    (``travel_spring``): ``rate`` in the force's units per the position's, the force being
    rate·(x − centre), its constant part any run's offset. A spring — a valve's actuator spring
    whose datasheet rate, 4 % off, left 2 kN/m in the net force a user wrote — gravity on a joint
    near its angle, a cable: no friction effect holds it, and a periodic search cannot see it."""
    rate: float
    sd: float  # its σ, jackknifed over TRAVEL_FORCE_BLOCKS blocks of the sliding
    following: float  # the rate of the part that follows the motion's sign
    centre: float  # the middle of the travel compared
    span: float  # the travel compared, so that rate × span is the force's range over it
    halves: tuple = ()  # (|rate|, σ) in the slower and the faster half of the sliding
    speed_gap: float = 0.0
    speed_gap_sd: float = 0.0
    gain: float = 0.0  # the share of the sliding residual's RMS it takes out (each run's own offset out first)
    # the evidence to look at, the least squares' own (Frisch–Waugh–Lovell): the residual against
    # the position, each less its run's mean and the slopes taken out beside (``travel_spring``),
    # in TRAVEL_FORCE_BINS bins of the second over ``within_range``; the mean moving up and moving
    # down (None where a bin has no sample). The slope of both is ``rate`` where a force keeps its sign
    within_range: tuple = (0.0, 0.0)
    up: tuple = ()
    down: tuple = ()
    # read with a drift in time beside it (``travel_spring``: where without it the halves disagree)
    drift_beside: bool = False

    @property
    def shown(self) -> bool:
        return _shown_along(abs(self.rate), abs(self.following), self.sd, self.halves, self.speed_gap,
                            self.speed_gap_sd, self.gain)


class AlongTravel(NamedTuple):
    """What a force along the travel is read from where no ``Comparison`` is built (``fit``'s
    recordings, the column as logged): the path, its velocity and mean acceleration, the speed
    under which it rests; nothing averaged."""
    path: np.ndarray
    velocity: np.ndarray
    v_rest: float
    acceleration: np.ndarray | None = None
    time: np.ndarray | None = None
    space: str = "friction"

    def filtered(self, a: np.ndarray) -> np.ndarray:
        return a


def travel_spring(cmp_: Comparison | AlongTravel, resid: np.ndarray, mask: np.ndarray) -> TravelSpring | None:
    """The part of the residual in proportion to the travel that keeps its sign both ways, or
    None: each direction fitted as an offset per run + k_d·x (``sign_keeping``). Within a run a
    slope in x is one in time too, but friction's — a transition's tail after a reversal, a
    drift — follows the motion's sign and falls in the half-difference."""
    if cmp_.space != "friction":
        return None
    runs = sliding_runs(cmp_, mask)
    if runs is None:
        return None
    at = cmp_.path[mask]
    centre = 0.5 * float(at.max() + at.min())
    # the path as the measurement sees it (the comparison's moving average), from the middle
    x = cmp_.filtered(cmp_.path - centre)[runs.idx]
    u, d = runs.up.astype(float), (~runs.up).astype(float)
    vel = cmp_.velocity[runs.idx]
    t = cmp_.time[runs.idx] if getattr(cmp_, "time", None) is not None else None
    # what else rises along a run whichever way, taken out beside the runs' offsets: S(v)'s slope
    # where a run's speed varies along it (a valve made apart, its positioner's fast strokes at
    # 31–68 mm/s about 40, read its spring 25 % short, 3.7 σ), each way apart; and an inertia off
    # by ΔI, which leaves −ΔI·ā in friction taken from an applied force (ā > 0 where a run
    # starts, < 0 where it stops). Where friction is logged as such the acceleration goes beside
    # it too: the model's σ2·v is at the step's middle (v its backward difference, eq. (3) over
    # the step), half a sample behind the log's, and leaves σ2·(Δt/2)·ẍ — on a crank (ẍ = −ω²x)
    # a spring of σ2·Δt·ω²/2, read 6.4 ± 0.3 N/m where that is 5.9 and said; there a spring and a
    # mass cannot be told apart, and with ẍ beside it its σ says so (ẍ over a tenth of a
    # stroke, ``stroke_scale_window``: over the 5 samples of the path's smoothing the noise of ẍ,
    # which the model's σ2·v shares, read 8.6 ± 0.5 N/m on its own)
    acc = cmp_.acceleration
    if acc is None and t is not None:
        acc = mean_acceleration(cmp_.velocity, cmp_.time, stroke_scale_window(cmp_))
    nuisance = [u * vel, d * vel] + ([] if acc is None else [acc[runs.idx]])
    ts, X, y = _spring_beside(runs, x, resid, nuisance, np.abs(vel))
    drift = False
    if not ts.shown and t is not None:
        # where that is not said, read again with a drift in time beside it: its sign follows the
        # motion's, and along a run it reads as a slope in x of ġ·|S|/|v| whichever way, told from
        # a spring's (the same at every speed) by the runs' speeds only — so only where it is
        # asked (a vertical axis made apart warming up read its 3 kN/m gas spring 3 % high in its
        # slower half, 3.7 σ from the faster; with the drift beside it, 2,998 ± 1 both halves
        # alike). Beside it always, a valve made apart whose strokes ran at three speeds read its
        # spring 5,528 ± 625 N/m for 7,500, where 7,462 ± 218 without
        again = _spring_beside(runs, x, resid, nuisance + [(u - d) * (t - t.mean())], np.abs(vel))
        if again[0].shown:
            (ts, X, y), drift = again, True
    xw = X[:, 0] + X[:, 1]  # the position as the least squares sees it: less its run's mean and the slopes beside
    lo, hi = float(xw.min()), float(xw.max())
    b = np.clip(((xw - lo) / max(hi - lo, 1e-300) * TRAVEL_FORCE_BINS).astype(int), 0, TRAVEL_FORCE_BINS - 1)

    def binned(rows):
        n = np.bincount(b[rows], minlength=TRAVEL_FORCE_BINS)
        mean = np.bincount(b[rows], y[rows], minlength=TRAVEL_FORCE_BINS) / np.maximum(n, 1)
        return tuple(float(m) if c > 0 else None for m, c in zip(mean, n))  # (None: JSON's null)

    return dataclasses.replace(ts, centre=centre, span=float(np.ptp(at)), within_range=(lo, hi), up=binned(runs.up),
                               down=binned(~runs.up), drift_beside=drift)


def stroke_scale_window(cmp_: Comparison | AlongTravel) -> int:
    """Samples (odd) to take a mean acceleration over beside a slope along the runs: a tenth of
    the median stroke (sliding one way, all of it, not only its steady part), so that the
    position's noise, twice differenced, is averaged out on the motion's own scale, and never
    under the path's smoothing window."""
    every = sliding_runs(cmp_, np.ones(len(cmp_.velocity), bool))
    stroke = 0 if every is None else int(np.median(every.count))
    return 2 * (max(stroke // 10, int(getattr(cmp_, "window", 3)), 3) // 2) + 1

def spring_note(ts: TravelSpring, model: str, fu: str, pu: str) -> str:
    """The diagnosis's note on a force in proportion to the travel, as ``model`` leaves it."""
    return (f"a force in proportion to the travel: what {model} leaves in the steady sliding, each run less its "
            f"own mean, rises by {ts.rate:.4g} ± {ts.sd:.2g} {fu}/{pu} along the travel whichever way the motion "
            f"goes ({abs(ts.rate) * ts.span:.3g} {fu} over the {ts.span:.3g} {pu} compared; the part following the "
            f"motion's sign, as a friction's would, {ts.following:.2g} {fu}/{pu}"
            + ("; read with a drift in time beside it, which the slower and the faster runs asked for"
               if ts.drift_beside else "")
            + "): a spring, gravity or a cable, or a spring rate taken off the applied force wrongly, not a "
            "friction effect — no candidate holds it; compensate it apart from friction; it is left in the "
            "friction compared (a friction effect may take up a part of it)")


def _spring_beside(runs: SlidingRuns, x: np.ndarray, resid: np.ndarray, nuisance: list,
                   speed: np.ndarray) -> tuple["TravelSpring", np.ndarray, np.ndarray]:
    """``travel_spring``'s least squares: each direction's slope in ``x`` of ``resid`` (at the
    sliding samples), with each run's offset and the ``nuisance`` columns taken out beside it
    (Frisch–Waugh–Lovell); the reading (its evidence not yet binned) and the columns and
    residual as the least squares saw them."""
    u, d = runs.up.astype(float), (~runs.up).astype(float)
    X = np.column_stack([runs.within(u * x), runs.within(d * x)])
    y = runs.within(resid[runs.idx])
    Z = np.column_stack([runs.within(c) for c in nuisance])
    X, y = (c - Z @ np.linalg.lstsq(Z, c, rcond=None)[0] for c in (X, y))
    k = sign_keeping(runs, X, y, speed)
    return (TravelSpring(float(k.keeps[0]), k.sd, float(k.follows[0]), 0.0, 0.0, k.halves, k.speed_gap,
                         k.speed_gap_sd, k.gain), X, y)


def _screen_starts(name: str, term: Term, cmp_: Comparison, resid: np.ndarray, base: np.ndarray) -> list:
    """Starting values (transformed) for the shape parameter, before amplitudes are solved."""
    T = float(cmp_.time[-1] - cmp_.time[0])
    if name == "time_drift":
        return [("tau", term.coordinate("tau", "log", v)) for v in T * np.geomspace(0.1, 3.0, 6)]
    if name == "cyclic_softening":
        nrev = float(significant_reversals(cmp_.path, term.fixed["min_excursion"])[-1]) or 1.0
        return [("n_c", term.coordinate("n_c", "log", max(v, 3.0))) for v in nrev * np.geomspace(0.05, 0.5, 4)]
    if name == "position_ripple":
        lam_min = term.value("wavelength", "log", term.free[2][2])
        return [("wavelength", term.coordinate("wavelength", "log", v))
                for v in _ripple_wavelengths(cmp_, resid, base, lam_min)]
    return [(None, None)]


def _amplitude_names(name):
    return {"time_drift": ("b",), "cyclic_softening": ("h",), "position_ripple": ("cs", "cc", "cs2", "cc2"), "normal_load": ("alpha",),
            "presliding_stiffness": ("kappa",)}[name]


def screen(engine: Engine, name: str, term: Term, prior: list, prior_u: np.ndarray, base_fit: FitResult,
           mask: np.ndarray) -> tuple[float, np.ndarray] | None:
    """The best start for a candidate: for each shape value, the amplitudes by one secant
    (Gauss-Newton) step from zero effect. Returns that step's residual sum of squares and
    the full u vector for ``_fit``."""
    meas = engine.c.measured
    r0 = (meas - base_fit.pred)[mask]
    best = None
    amps = _amplitude_names(name)
    neutral = {"b": 0.0, "h": 0.0, "cs": 0.0, "cc": 0.0, "cs2": 0.0, "cc2": 0.0, "alpha": 0.0, "kappa": 0.0}
    deltas = {"b": 0.1, "h": -0.2, "cs": 0.05, "cc": 0.05, "cs2": 0.05, "cc2": 0.05, "alpha": 0.5, "kappa": 0.2}
    free_names = [f[0] for f in term.free]
    for shape_name, shape_val in _screen_starts(name, term, engine.c, meas - base_fit.pred, base_fit.pred):
        u = np.array([neutral.get(n, 0.0) for n in free_names])
        if shape_name is not None:
            u[free_names.index(shape_name)] = shape_val
        cols = []
        for a in amps:
            ua = u.copy()
            ua[free_names.index(a)] = deltas[a]
            col = engine.predict(base_fit.g, base_fit.k0, prior + [_entry(term, ua)]) - base_fit.model
            cols.append(((col - engine.nuisance(col, mask, base_fit.model))[mask]) / deltas[a])
        J = np.column_stack(cols)
        coef, *_ = np.linalg.lstsq(J, r0, rcond=None)
        for a, cf in zip(amps, coef):
            lo, hi = next((f[2], f[3]) for f in term.free if f[0] == a)
            u[free_names.index(a)] = float(np.clip(cf, lo, hi))
        rss = float(np.sum((r0 - J @ coef) ** 2))
        if best is None or rss < best[0]:
            best = (rss, u)
    if best is None:
        return None
    head = [math.log(base_fit.g)]
    return best[0], np.concatenate([head, prior_u, best[1]])


SOFTENING_MIN_COUNT = 6  # a softening threshold tried must count this many reversals (n_c ≥ 3 must be seen settling)
# thresholds fitted in full and carried into every fold, of those screened: a full fit and its
# refits in the folds cost about 2 s each on 100,000 samples, a screen a tenth of that
SOFTENING_FITTED = 2


def softening_thresholds(cmp_: Comparison, tries: int = 1) -> list:
    """The back-travels a softening's reversal is tried with, from the comparison's
    ``min_excursion`` (a quarter of the presliding range, or the position's noise) up by
    factors of 2, ``tries`` of them at most (``Settings.softening_thresholds``), while they
    still count SOFTENING_MIN_COUNT reversals; one counting the
    same reversals as a smaller one is left out. What wears a contact in need not be every
    back-travel past the presliding range: a session whose presliding tests make many small
    cycles early would, counted that way, show the change late and never settle. A back-travel
    the user set (``--threshold min_excursion``) is what counts, and it alone is tried."""
    reading = getattr(cmp_, "reading", None)
    if tries <= 1 or (reading is not None and "min_excursion" in reading.set_by_user):
        return [cmp_.min_excursion]
    out, seen = [], None
    for k in range(tries):
        th = cmp_.min_excursion * 2.0**k
        count = significant_reversals(cmp_.path, th)
        if count[-1] < SOFTENING_MIN_COUNT:
            break
        if seen is not None and np.array_equal(count, seen):
            continue
        out.append(th)
        seen = count
    return out or [cmp_.min_excursion]


def fit_candidate(engine: Engine, name: str, cmp_: Comparison, strokes: SpeedOrder | None, alt: "Alternative",
                  mask: np.ndarray, k0: float, tries: int = 1) -> list:
    """The candidate ``name`` fitted beside the alternative ``alt`` (``screen``, then ``_fit``):
    [(term, fit)], the least residual first. A softening's reversal threshold is a shape
    parameter as well: each of ``softening_thresholds`` is screened, and the
    SOFTENING_FITTED best by the screen's one step are fitted (the first is the one written;
    the cross-validation chooses among them again in every fold)."""
    ths = softening_thresholds(cmp_, tries) if name == "cyclic_softening" else [None]
    starts = []
    for th in ths:
        term = _terms_for(name, cmp_, strokes, th)
        screened = screen(engine, name, term, alt.fit.entries, alt.u, alt.fit, mask)
        if screened is not None:
            starts.append((screened[0], term, screened[1]))
    starts.sort(key=lambda s_: s_[0])
    out = [(term, _fit(engine, alt.terms + [term], u0, mask, fit_k0=alt.fit_k0, k0=k0))
           for _, term, u0 in starts[:SOFTENING_FITTED]]
    return sorted(out, key=lambda o: o[1].rss)


# ---------------------------------------------------------------- cross-validation
def fold_masks(n: int, folds: int, blocks_per_fold: int, windows=None) -> list:
    """Held-out masks: ``folds·blocks_per_fold`` contiguous blocks dealt round-robin (in
    position space, whole windows are kept together)."""
    nb = folds * blocks_per_fold
    block = np.minimum((np.arange(n) * nb) // max(n, 1), nb - 1)
    if windows:
        orig = block.copy()
        for a, b in windows:
            block[a:b] = orig[a]
    fold = block % folds
    return [fold == k for k in range(folds)]


@dataclass
class Evidence:
    name: str
    params: dict
    rms_in: float  # in-sample RMS with the candidate
    heldout_sse: np.ndarray | None  # per fold (None: not cross-validated, see PRESCREEN)
    null_sse: np.ndarray | None
    informative: np.ndarray | None  # per fold: the candidate changes the held-out prediction
    delta_bic: float
    correction: np.ndarray = field(repr=False, default=None)  # prediction − alternative's prediction
    fit: FitResult = field(repr=False, default=None)
    not_where_it_shows: str | None = None  # the regime where it had to help and did not
    where: str | None = None  # the regime where its physics shows
    gain_where: float | None = None  # pooled held-out gain there
    folds_where: str | None = None  # folds improved / informative there
    against: Alternative | None = field(repr=False, default=None)  # the alternative it is judged against
    rms_alt: float = 0.0  # that alternative's in-sample RMS
    unsettled: str | None = None  # why its change is not seen settling within the session (``Term.unsettled``)
    fold_entries: list | None = field(repr=False, default=None)  # per fold: every entry refitted on the other folds

    @property
    def beside(self) -> str | None:
        """What the alternative held besides the named effects."""
        return self.against.beside if self.against is not None else None

    @property
    def cross_validated(self) -> bool:
        return self.heldout_sse is not None

    @property
    def in_sample_gain(self) -> float:
        return float(1 - self.rms_in / self.rms_alt) if self.rms_alt else 0.0

    @property
    def folds_improved(self) -> int:
        return int(np.sum((self.heldout_sse < self.null_sse) & self.informative)) if self.cross_validated else 0

    @property
    def folds_informative(self) -> int:
        return int(np.sum(self.informative)) if self.cross_validated else 0

    @property
    def heldout_gain(self) -> float:
        """Pooled held-out gain; for a candidate not cross-validated, its in-sample gain (an upper bound)."""
        if not self.cross_validated:
            return self.in_sample_gain
        return float(1.0 - math.sqrt(np.sum(self.heldout_sse) / max(np.sum(self.null_sse), 1e-300)))

    def gains_held_out(self, s: Settings) -> bool:
        """Better held out in most informative folds, and by ``min_gain`` pooled."""
        k = self.folds_informative
        return bool(self.cross_validated and k >= 2 and self.folds_improved > k / 2 and self.heldout_gain >= s.min_gain)

    def evident(self, s: Settings) -> bool:
        """Gains held out (``gains_held_out``), and where its physics shows."""
        return self.gains_held_out(s) and self.not_where_it_shows is None

    def elsewhere(self, s: Settings) -> bool:
        """Gains held out, but not in the regime where its physics must show (a drift beside a
        ripple on a sweep: better in the transitions, not in the steady sliding)."""
        return self.gains_held_out(s) and self.not_where_it_shows is not None

    def passes(self, s: Settings) -> bool:
        """Evident, and (``Settings.must_settle``) seen to settle within the session."""
        return self.evident(s) and (self.unsettled is None or not s.must_settle)

    def as_dict(self, s: Settings) -> dict:
        return {"name": self.name, "description": EFFECTS[self.name].description, "params": self.params,
                "rms_after": self.rms_in, "reduction": self.in_sample_gain, "cross_validated": self.cross_validated,
                "heldout_gain": self.heldout_gain, "folds_improved": self.folds_improved,
                "folds_informative": self.folds_informative, "delta_bic": self.delta_bic, "passes": self.passes(s),
                "not_where_it_shows": self.not_where_it_shows, "where": self.where, "gain_where": self.gain_where,
                "folds_where": self.folds_where, "beside": self.beside, "unsettled": self.unsettled,
                "evident": self.evident(s), "elsewhere": self.elsewhere(s),
                "significant": False, "refitted": True}


@dataclass
class Alternative:
    """What a candidate must beat: the fit without it (terms and their vector u, without log g),
    with its held-out SSE and predictions per fold once ``held_out`` has been asked for."""

    fit: FitResult
    terms: list
    u: np.ndarray
    beside: str | None = None  # what it holds besides the named effects
    fit_k0: bool = False  # κ0 is refitted with every candidate (u then starts with log κ0)
    sse: np.ndarray | None = None
    preds: list | None = None
    same_as: "Alternative | None" = None  # predicts as this one does (its held-out scores are that one's)

    def held_out(self, engine: Engine, masks: list, k0: float) -> tuple:
        """(SSE per fold, predictions per fold), cross-validated on first use only: when no
        candidate comes near the threshold in-sample, the alternative is never cross-validated."""
        if self.same_as is not None:
            return self.same_as.held_out(engine, masks, k0)
        if self.sse is None:
            u = np.concatenate([[math.log(self.fit.g)], self.u])
            self.sse, self.preds, _ = cross_validate(engine, self.terms, u, masks, k0, fit_k0=self.fit_k0)
        return self.sse, self.preds


HELD_STIFFNESS = {"rate_stiffness": "a stiffness varying with speed",
                  "travel_stiffness": "a stiffness varying with the stroke's travel",
                  "presliding_range": "a presliding range following the friction effects"}


def stiffness_alternative(engine: Engine, cmp_: Comparison, plain: Alternative, k0: float, mask: np.ndarray,
                          held: tuple) -> Alternative:
    """The alternative a stiffness effect is judged against: ``plain`` with the stiffness
    effects ``held`` (``HELD_STIFFNESS``), fitted with it and never named.

    ``rate_stiffness``: a presliding stiffness that varies smoothly with the sliding speed (the
    speed at the sample, smoothed). A contact whose transition depends on speed otherwise than
    eq. (5) says shows, to the model, a stiffness that follows the speed; where a session's
    speeds rise with the number of reversals (a sweep in rising order), that would otherwise be
    credited to a softening or hardening with the reversals. (The speed of the stroke a sample
    belongs to in its place was tried on a LuGre guideway whose slow strokes fall mid-session: a
    softening stayed named on one of its two controls — README, recordings made apart.)

    ``travel_stiffness``: a presliding stiffness that varies smoothly with the travel of the
    stroke before the last reversal (which sets the force the contact turned at, and is known
    when the stroke starts). Eq. (5)'s memory keeps Masing's rule, every branch the same curve
    from its reversal; a contact that does not (a Dahl-like one, whose stiffness after a
    reversal grows with the force it turned at) shows the model the branches after small loops
    softer than those after large ones, and where a session's loops grow with the number of reversals (presliding cycles of
    rising amplitude, then strokes) that was credited to a hardening: a linear rig made apart,
    Dahl presliding, named one on its control (h 0.13, n_c 5.8) and nothing once its loops'
    amplitudes were shuffled.

    ``presliding_range`` (where a friction effect is in the model): the presliding range
    following that effect's factor. A named drift or load scales eq. (3)'s F whole, the
    presliding stiffness with it; a contact whose stiffness does not follow (a drift of the
    lubricant, not of the asperities' elasticity) leaves the transitions a stiffness changing
    as the drift goes on, which on a session of regular strokes is a trend in the reversals
    too — a softening by accident.

    The presliding stiffness κ0 is refitted with it and with every candidate judged against
    it: a softening starts stiffer than the average the alternative's κ0 holds."""
    extra = [_terms_for(name, cmp_) for name in held]
    terms = plain.terms + extra
    u0 = np.concatenate([[math.log(plain.fit.g), math.log(k0)], plain.u] + [np.zeros(len(t.free)) for t in extra])
    fr = _fit(engine, terms, u0, mask, fit_k0=True, k0=k0)
    return Alternative(fr, terms, fr.u[1:], held_said(held), fit_k0=True)


def held_said(held: tuple) -> str:
    """The stiffness effects ``held`` as a sentence lists them: "a, b and c"."""
    said = [HELD_STIFFNESS[n] for n in held]
    return ", ".join(said[:-1]) + (" and " if len(said) > 1 else "") + said[-1]


# the friction candidates fitted with a presliding range following them (``range_alternative``):
# a temperature and a load move the friction level, and a contact's elasticity need not follow.
# Not a ripple: a range changing along the position is not a wavy guide's physics, and it let the
# ripple's factor fit a force along the travel that keeps its sign (3 % of a tribometer's friction
# added along its stroke was named a ripple, where without it the reading said it apart)
RANGE_FOLLOWS = ("time_drift", "normal_load")


def range_alternative(cmp_: Comparison, plain: Alternative) -> Alternative:
    """``plain`` with a presliding range (``presliding_range``, e = 0) that a friction candidate
    fitted beside it follows: the candidate then decides, with its own factor, whether the
    transitions' range follows it. Without a friction effect in ``plain`` that range does
    nothing, so this alternative predicts as ``plain`` does (``same_as``).

    Used only while ``plain`` holds no friction effect (the caller's test).

    Eq. (3)'s factor scales the transition curve's forces with the friction and keeps the range
    to break-away; a contact whose elasticity does not follow a warm-up or a load (a
    Maxwell-slip contact whose slip levels move: F(z) → m·F(z/m)) stretches the range instead.
    Without the range, such a drift or load leaves the transitions a stiffness changing as it
    goes on, a trend in the reversal count on regular strokes that a softening takes up in the
    same round. A candidate is judged both ways (``diagnose``'s ``judge``); on a sweep in rising
    speeds, where the sliding cannot tell a drift from the shape of S(v), the range is what lets
    the drift's fit keep the sliding's change and leave the transitions' to the range."""
    term = _terms_for("presliding_range", cmp_)
    fit = dataclasses.replace(plain.fit, entries=list(plain.fit.entries) + [_entry(term, np.zeros(len(term.free)))])
    return Alternative(fit, plain.terms + [term], np.concatenate([plain.u, np.zeros(len(term.free))]),
                       HELD_STIFFNESS["presliding_range"], plain.fit_k0, same_as=plain)


def held_stiffness(terms: list, settings: Settings) -> tuple:
    """The stiffness effects a stiffness candidate is judged beside, given the model's ``terms``
    (``stiffness_alternative``): each not in the model already, a presliding range only beside a
    friction effect."""
    have = {t.name for t in terms}
    out = []
    if settings.rate_nuisance and "rate_stiffness" not in have:
        out.append("rate_stiffness")
    if settings.travel_nuisance and "travel_stiffness" not in have:
        out.append("travel_stiffness")
    if (settings.range_nuisance and "presliding_range" not in have
            and any(EFFECTS[n].acts_on == "friction" for n in have)):
        out.append("presliding_range")
    return tuple(out)


def own_gain(engine: Engine, fit: FitResult, name: str | None = None) -> float:
    """What effect ``name`` of ``fit`` (default: its last; a fit on the engine's scored
    samples, as the model written is) does itself: 1 − its RMS gap over the gap with that
    effect's amplitudes at no effect (``Effect.without``), everything else as fitted (the
    engine's nuisance solved again). The base the engine holds must be the fit's own."""
    name = fit.entries[-1]["name"] if name is None else name
    off = [{"name": e["name"], "params": EFFECTS[e["name"]].without(e["params"])} if e["name"] == name else e
           for e in fit.entries]
    without = fit_result(engine, fit.g, fit.k0, off, fit.u, engine.scored)
    return float(1.0 - math.sqrt(fit.rss / max(without.rss, 1e-300)))


def without_term(terms: list, u: np.ndarray, name: str) -> tuple[list, np.ndarray]:
    """A step's (terms, u) — u: log g, then each term's free parameters in order — without the
    term of effect ``name``."""
    i = next(k for k, t in enumerate(terms) if t.name == name)
    start = 1 + sum(len(t.free) for t in terms[:i])
    return terms[:i] + terms[i + 1:], np.delete(u, np.arange(start, start + len(terms[i].free)))


def _effective_n(resid: np.ndarray) -> float:
    r = resid - resid.mean()
    rho = float(np.dot(r[1:], r[:-1]) / max(np.dot(r, r), 1e-300))
    rho = min(max(rho, 0.0), 0.999)
    return len(r) * (1 - rho) / (1 + rho)


PRESCREEN = 0.5  # a candidate gaining less than this fraction of min_gain in-sample is not cross-validated
CV_NFEV = 25  # least-squares steps of a fold's refit (it starts from the fit on every fold)
CV_NFEV_STIFFNESS = 10  # … where κ0 and a stiffness varying with speed are refitted too (each step simulates)


def cross_validate(engine: Engine, terms: list, u_full: np.ndarray, masks: list, k0: float, fit_k0: bool = False,
                   others: tuple = ()) -> tuple:
    """Held-out SSE per fold, the held-out predictions, and each fold's effect entries (fitted
    on the other folds). ``others``: further (terms, u_full) of the same candidate at other
    values of a shape chosen from the data (a softening's reversal threshold); each fold
    refits them all and keeps the one that fits its training blocks best, so the held-out
    score pays for that choice as for any fitted parameter."""
    meas = engine.c.measured
    sse = np.zeros(len(masks))
    preds, entries = [], []
    nfev = (CV_NFEV_STIFFNESS if fit_k0 else CV_NFEV) if engine.c.space == "friction" else 5
    starts = [(tm, u, StiffnessChord.at(engine, tm, u, fit_k0, k0)) for tm, u in ((terms, u_full), *others)]
    for i, held in enumerate(masks):
        train = ~held & engine.scored
        fits = [_fit(engine, tm, u, train, fit_k0=fit_k0, k0=k0, max_nfev=nfev, chord=ch) for tm, u, ch in starts]
        fr = min(fits, key=lambda f: engine.score((meas - f.pred)[train]))
        sse[i] = engine.score((meas - fr.pred)[held])
        preds.append(fr.pred)
        entries.append(fr.entries)
    return sse, preds, entries


def jackknife_sd(full: float, folds, *, angle: bool = False) -> float:
    """Delete-a-group jackknife standard error of an estimate from its k refits each leaving
    one fold out: √((k − 1)/k · Σ(θ_i − θ̄)²). For the mean of k equal groups it is exactly
    the standard error estimated from the k group means, sd(group means)/√k. An angle's deviations are taken from the full estimate, wrapped
    to (−π, π], so a phase near ±π does not count a turn as spread."""
    d = np.asarray(folds, dtype=np.float64) - full
    if angle:
        d = np.angle(np.exp(1j * d))
    k = len(d)
    return float(math.sqrt((k - 1) / k * np.sum((d - d.mean()) ** 2))) if k >= 2 else float("nan")


def with_model_shift(sd: dict, decided: dict, written: dict) -> dict:
    """σ of an effect's written parameters: the folds' jackknife σ (``effect_sds``, of the
    values ``decided`` beside the free steady curve) and, in quadrature, how far the model
    written moved each value from there (refitted without that curve, n, σ1 and S(v) take up
    part of what the curve held, and the effect moves with them). The jackknife sees only the
    data's part; the shift is a sample of the model's own (on the rotary table made apart, a
    ripple's phase was decided at 1.118 ± 0.007 and written at 1.197, the truth 1.13). A
    phase's shift is wrapped to [−π, π]."""
    out = {}
    for k, v in sd.items():
        if k in decided and k in written and math.isfinite(v):
            d = written[k] - decided[k]
            if k.startswith("phase"):
                d = math.remainder(d, 2.0 * math.pi)
            out[k] = math.hypot(v, d)
        else:
            out[k] = v
    return out


def effect_sds(terms: list, full: list, folds: list, named) -> dict:
    """{effect: {parameter: σ}} for the named effects among ``terms``: each free parameter's
    jackknife σ (``jackknife_sd``) over the cross-validation's leave-one-fold-out refits
    ``folds`` around the fit on every fold, ``full`` (entries in the order of ``terms``). The
    refits are beside the alternative's free steady curve: σ says how far the estimate moves
    with the data, not how far its shape is from the contact's.
    A parameter at a bound of its range (``Term.at_bounds``: a saturation scale named without
    settling, a drift's end value at its floor) gets none: the bound, not the data, holds it
    there in every fold, and their spread would be about 0."""
    out = {}
    for j, term in enumerate(terms):
        if term.name not in named:
            continue
        est = full[j]["params"]
        held = term.at_bounds(_entry_to_u(term, est))
        out[term.name] = {k: jackknife_sd(v, [f[j]["params"][k] for f in folds], angle=k.startswith("phase"))
                          for k, v in est.items() if k not in term.fixed and k not in held}
    return out


# ---------------------------------------------------------------- the result
@dataclass(frozen=True)
class DiagnosisWork:
    """Where a diagnosis's time went: its wall time, and the simulations of the record it made
    (each a whole pass of the model along the compared path, or of the plant over every window)
    with the time spent in them; the rest is the work around them (the effects' factors, the
    filter, the residuals, the least-squares steps). ``leuven-friction bench`` reports it."""

    seconds: float
    simulations: int
    simulation_seconds: float


@dataclass
class Diagnosis:
    effects: list  # names of the effects named, in order
    steps: list  # per step: {name, params, rms, regimes, evidence}
    confounded: list  # [{effects: [a, b], evidence: {...}, experiment: str}]
    candidates: list  # the last round's candidates (dicts)
    rms_before: float
    rms_after: float
    rms_base_refit: float
    regimes: dict
    space: str
    noise: float
    notes: list
    params_before: FrictionParams
    params_after: FrictionParams
    settings: Settings = field(default_factory=Settings)
    time: np.ndarray = field(repr=False, default=None)
    measured: np.ndarray = field(repr=False, default=None)
    model_before: np.ndarray = field(repr=False, default=None)
    model_after: np.ndarray = field(repr=False, default=None)
    step_predictions: list = field(repr=False, default_factory=list)  # the model alone, step by step
    scored_predictions: list = field(repr=False, default_factory=list)  # with the free steady curve
    compared: np.ndarray = field(repr=False, default=None)  # the samples compared (``initial_memory``)
    explaining: dict = field(repr=False, default_factory=dict)
    # effects that passed held out but that the model written does not use: [{name, own_gain}]
    unused: list = field(default_factory=list)
    work: DiagnosisWork | None = None
    # the motion reading's thresholds as used, in SI as `diagnose --threshold` takes them: a
    # diagnosis of a file this one wrote counts reversals from a quarter of that file's presliding
    # range (``reversal_threshold``), so it may compare another span unless given the same
    reading: dict = field(default_factory=dict)
    # nothing named, and the base refitted alone leaves clearly less than the model as given
    # (over BASE_OFF_NOISE noise floors): the base, not a missing effect, is what is off
    base_off: bool = False
    # a force periodic along the travel that keeps its sign both ways (``travel_force``), where shown
    travel_force: TravelForce | None = None
    # a force in proportion to the travel that keeps its sign both ways (``travel_spring``), where shown
    travel_spring: TravelSpring | None = None
    # the recording's normal load's SI unit, N or N·m (a tilting moment), where it has one
    load_unit: str | None = None
    # a candidate that passed where the model before it already left under the noise floor beside
    # the free steady curve, and so was not named: {name, heldout_gain, folds_improved,
    # folds_informative, gap_over_noise}
    under_noise: dict | None = None

    @property
    def units(self) -> dict:
        """The units an effect's values are in: the parameter set's, and the load's (N0's)."""
        return {**dict(self.params_before.units), **({"normal_load": self.load_unit} if self.load_unit else {})}

    # the first named effect, for callers that show one
    @property
    def effect(self) -> str | None:
        return self.effects[0] if self.effects else None

    @property
    def description(self) -> str | None:
        return EFFECTS[self.effect].description if self.effect else None

    @property
    def unsettled(self) -> list:
        """With ``Settings.must_settle`` (the default): the last round's candidates with held-out
        evidence that were not named because their change is not seen to settle within the
        session (``Term.unsettled``)."""
        return unsettled_among(self.candidates, self.settings)

    def not_where_it_shows(self, c: dict) -> str:
        """Why a candidate of ``elsewhere`` is not named, in words (the text report and the HTML)."""
        # in the candidates table's terms: the held-out RMS there falls (−) or rises (+), and the
        # folds are those where it falls
        g = c["gain_where"] or 0.0
        better, informative = str(c["folds_where"]).split("/")
        return (f"in {c['not_where_it_shows']}, where its physics must show, its held-out RMS "
                f"{'falls' if g > 0 else 'rises'} by {100 * abs(g):.1f} % pooled and falls in {better} of "
                f"{informative} folds (it must fall by ≥ {100 * self.settings.min_gain:.0f} % there, in most folds)")

    @property
    def elsewhere(self) -> list:
        """The last round's candidates that gain held out, but not where their physics must show
        (``Evidence.elsewhere``): not named, and said."""
        return elsewhere_among(self.candidates)

    def seen_not_named(self) -> list:
        """[(candidate, why it is not named)] of the last round's candidates the evidence shows
        but the diagnosis does not name (``unsettled``, ``elsewhere``, then ``under_noise``): the text report and
        the HTML list the same ones for the same reasons."""
        un = self.under_noise
        return ([(c, c["unsettled"]) for c in self.unsettled]
                + [(c, self.not_where_it_shows(c)) for c in self.elsewhere]
                + ([(un, f"the model before it leaves {un['gap_over_noise']:.2f} × the noise floor: what it takes is "
                         f"within the noise")] if un is not None else []))

    def seen_unnamed(self) -> bool:
        """Whether any candidate was seen and not named (``seen_unnamed``)."""
        return seen_unnamed(self.confounded, self.unused, self.candidates, self.settings)

    def not_named(self) -> list:
        """What the evidence shows but the diagnosis does not name, one short line each: an
        effect seen that is not seen to settle within the session (with ``Settings.must_settle``),
        one that gains held out but not where it must show, and pairs of effects confounded
        with each other."""
        return ([f"{c['name']} seen, not named (its change is not seen to settle, or to repeat, within the session: a trend or a step would look the same)" for c in self.unsettled]
                + [f"{c['name']} seen, not named (it gains held out, but not in {c['not_where_it_shows']})"
                   for c in self.elsewhere]
                + [f"{c['effects'][0]} and {c['effects'][1]} confounded" for c in self.confounded]
                + [f"{c['name']} passed, not named (the model written does not use it)" for c in self.unused]
                + ([f"a force along the travel, not a friction effect (period {self.travel_force.wavelength:.3g}, "
                    f"amplitude {self.travel_force.amplitude:.3g})"] if self.travel_force is not None else [])
                + ([f"a force in proportion to the travel, not a friction effect (rate {self.travel_spring.rate:.3g})"]
                   if self.travel_spring is not None else []))

    @property
    def effect_params(self) -> dict | None:
        # steps: [model as given, base refit, + first effect, + second effect, …]
        return self.steps[2]["params"] if self.effects else None

    def named_labels(self) -> list:
        """The effects named, each with the way it acts as written ("cyclic_softening
        (hardening)", ``Effect.sense_of``)."""
        written = {e["name"]: e["params"] for e in self.written_effects()}
        return [f"{n} ({w})" if (w := EFFECTS[n].sense_of(written.get(n, {}))) else n for n in self.effects]

    def written_effects(self) -> list:
        """[{name, params, sd, held}] of every effect in the model written, as the file has them:
        the last step's model, every effect refitted together — with two effects the first one's
        values and σ there differ from its own step's line. ``held``: why a parameter has no σ
        (not determined there, as the file's provenance.held says; a drift beside a load read
        b 0.285 ± 3.1 there, written without a σ, and a reader of the JSON saw only an empty sd)."""
        if not self.effects or self.params_after is None:
            return []
        unc = self.params_after.uncertainty
        held = (self.params_after.provenance or {}).get("held") or {}
        return [{"name": e["name"], "params": dict(e["params"]),
                 "sd": {k: unc[f"effects.{i}.params.{k}"] for k in e["params"] if f"effects.{i}.params.{k}" in unc},
                 "held": {k: held[f"effects.{i}.params.{k}"] for k in e["params"] if f"effects.{i}.params.{k}" in held}}
                for i, e in enumerate(self.params_after.effects)]

    def written_said(self, units=None) -> list[tuple[str, str]]:
        """(name, values in words) of each effect in the model written (``written_effects``), in
        ``units`` (the set's by default; the explorer shows its own spelling): what the text and
        HTML reports and the explorer list."""
        return [(e["name"], format_values(e["name"], e["params"], units or self.units, e["sd"], e["held"]))
                for e in self.written_effects()]

    def summary(self) -> dict:
        return {
            "effects": list(self.effects), "effect": self.effect, "effect_params": self.effect_params,
            # the units every number here is in: the parameter set's (the recording is read into SI)
            "units": self.units,
            "space": self.space, "noise": self.noise, "rms_before": self.rms_before, "rms_after": self.rms_after,
            "rms_base_refit": self.rms_base_refit, "steps": self.steps, "regimes": self.regimes,
            "confounded": self.confounded, "unsettled": [c["name"] for c in self.unsettled], "unused": self.unused,
            "under_noise": self.under_noise,
            "base_off": self.base_off,
            "travel_force": None if self.travel_force is None else asdict(self.travel_force),
            "travel_spring": None if self.travel_spring is None else asdict(self.travel_spring),
            "elsewhere": [c["name"] for c in self.elsewhere], "written_effects": self.written_effects(),
            "candidates": self.candidates, "notes": list(self.notes),
            "work": None if self.work is None else asdict(self.work),
            "reading": dict(self.reading),
            "settings": {"folds": self.settings.folds, "blocks": self.settings.folds * self.settings.blocks_per_fold,
                         "min_gain": self.settings.min_gain, "confound_corr": self.settings.confound_corr,
                         "must_settle": self.settings.must_settle, "reading": dict(self.settings.reading),
                         # (taken out, the force along the travel is out of ``measured`` and every gap)
                         "travel_force_out": self.settings.travel_force_out,
                         "beside_confounded": self.settings.beside_confounded},
        }

    def text(self) -> str:
        u = self.params_before.units.get("force" if self.space == "friction" else "position", "")
        pu = self.params_before.units.get("position", "")
        L = []
        if self.effects:
            L.append("Missing effects named (out-of-sample evidence): " + ", ".join(self.named_labels()))
        elif self.under_noise is not None:
            L.append("No missing effect named: the model already leaves less than the noise floor beside the free "
                     "steady curve, so nothing beyond the noise is left for an effect to explain.")
        elif self.confounded:
            L.append("No missing effect named: what improves the held-out prediction is explained as well by two "
                     "candidates confounded with each other (below).")
        elif self.unsettled:
            L.append("No missing effect named: what improves the held-out prediction is not seen to settle, or to "
                     "repeat, within the session (required here).")
        elif self.unused:
            L.append("No missing effect named: what improved the held-out prediction is not used by the model written.")
        elif self.elsewhere:
            L.append("No missing effect named: what improves the held-out prediction does not improve it where its "
                     "physics must show.")
        else:
            # both halves of the rule (``Evidence.gains_held_out``): a candidate better in most folds
            # can still be worse pooled, where one fold's prediction runs far off
            L.append(f"No missing effect named: nothing improves the held-out prediction both in most folds and by "
                     f"≥ {100 * self.settings.min_gain:.0f} % pooled.")
        for c, why in self.seen_not_named():
            L.append(f"Seen, not named: {c['name']} improves the held-out prediction by {100 * c['heldout_gain']:.1f} % "
                     f"(folds {c['folds_improved']}/{c['folds_informative']}), but {why}"
                     + (": what it takes up lies elsewhere, and may be another effect's or the base's." if c.get("elsewhere")
                        else "."))
        if self.travel_force is not None:
            tf = self.travel_force
            L.append(f"Seen, not a friction effect: a force along the travel, of period {tf.wavelength:.4g} {pu} and "
                     f"amplitude {tf.amplitude:.3g} ± {tf.sd:.2g} {u}, keeps its sign whichever way the motion goes "
                     f"(cogging, gravity, a spring or a cable; notes).")
        if self.travel_spring is not None:
            ts = self.travel_spring
            L.append(f"Seen, not a friction effect: a force in proportion to the travel, {ts.rate:.3g} ± {ts.sd:.2g} "
                     f"{u}/{pu} ({abs(ts.rate) * ts.span:.3g} {u} over the {ts.span:.3g} {pu} compared), keeps its "
                     f"sign whichever way the motion goes (a spring, gravity, a cable, or a spring rate taken off "
                     f"the force wrongly; notes).")
        if not self.effects and self.noise > 0 and self.rms_base_refit > BASE_OFF_NOISE * self.noise:
            # nothing named is not "nothing there": the rest the base refitted alone leaves is said
            L.append(f"Left unexplained: the base refitted alone still leaves {self.rms_base_refit / self.noise:.1f} × "
                     f"the noise floor, "
                     + ("part of which the candidates above, not named, may hold" if self.seen_unnamed() else
                        f"which no candidate ({', '.join(self.settings.candidates)}) takes up")
                     + ("" if self.travel_force is None else "; the force along the travel above is "
                        + ("taken out of it" if self.settings.travel_force_out else "part of it"))
                     + ("" if self.travel_spring is None else "; the force in proportion to the travel above is "
                        "part of it")
                     + " (the regimes below say where).")
        for c in self.unused:
            L.append(f"Passed, not named: {c['name']} improved the held-out prediction beside a free steady curve, but "
                     f"in the model written (n, σ1 and S(v) refitted with it) it removes only {100 * c['own_gain']:.1f} % "
                     f"of the gap that model leaves with its amplitude at no effect.")
        for c in self.confounded:
            a, b = c["effects"]
            L.append(f"Confounded: {a} and {b} explain the same part of the residual ({confounding_reason(c)}). "
                     f"Neither is named. To separate them: {c['experiment']}.")
        L.append(f"Compared in {self.space}; noise floor {self.noise:.4g} {u}.")
        for n in self.notes:
            L.append(f"  {n}")
        L.append(f"RMS gap, step by step ({u}): of the model written, and beside a free steady curve S(v) (what "
                 f"the decision compares)" + ("" if self.effects else "; nothing named: the model written is the "
                                               "one given, the alternative a step of the comparison only"))
        nz = self.noise if self.noise > 0 else float("nan")
        # the two columns' heads, over their numbers (a user read them as unlabelled)
        L.append(f"  {'':{STEP_LABEL_WIDTH}s} {'model written':24s}beside a free steady curve")
        for s in self.steps:
            label = s["label"]
            if len(label) > STEP_LABEL_WIDTH:  # (the alternative's, with its factors) on a line of its own
                L.append(f"  {label}")
                label = ""
            # a named step's own evidence beside its gaps: what the decision rested on
            held = (f"   held out −{100 * s['heldout_gain']:.1f} % (folds {s['folds']})"
                    if s.get("heldout_gain") is not None and s.get("folds") else "")
            L.append(f"  {label:{STEP_LABEL_WIDTH}s} {s['rms']:.4g} ({s['rms'] / nz:.2f} × noise)   "
                     f"{s['rms_free']:.4g} ({s['rms_free'] / nz:.2f} × noise){held}")
            if s.get("params"):
                own = "" if "params_decided" in s else f"the file's {s.get('name') or 'effect'}, refitted with it: "
                L.append("      " + own + format_values(s["name"], s["params"], self.units, s.get("sd")))
            if s.get("params_decided") and s.get("params") and s["params_decided"] != s["params"]:
                # σ counts the move from the value the folds' spread belongs to: show where that was
                L.append("      decided beside the free steady curve: "
                         + format_values(s["name"], s["params_decided"], self.units))
        if len(self.effects) > 1:
            L.append("Effects as written to the file (the last step's model, every effect refitted together):")
            for name, said in self.written_said():
                L.append(f"  {name:22s} " + said)
        L.append("Per regime (RMS before → after the refit → final, the model written; the noise floor of that "
                 "regime's samples):")
        for k, r in self.regimes.items():
            nr = r["noise"]
            tail = f"   noise {nr:.3g} ({r['rms_after'] / nr:.1f} ×)" if nr and math.isfinite(nr) else ""
            L.append(f"  {k:22s} n={r['n']:7d}  {r['rms_before']:.4g} → {r['rms_base_refit']:.4g} → {r['rms_after']:.4g}"
                     + tail)
        L.append(f"Candidates, last round (blocked CV: {self.settings.folds} folds of "
                 f"{self.settings.blocks_per_fold} contiguous blocks; each RMS change is the candidate's against the "
                 f"alternative, − where it falls (better), + where it rises; named if better held out in most "
                 f"informative folds and ≥ {100 * self.settings.min_gain:.0f} % pooled"
                 + ("; settling required: one whose change is not seen to settle within the session is seen, not named"
                    if self.settings.must_settle else "") + "):")
        for c in self.candidates:
            mark = "*" if c["significant"] else ("+" if c["passes"] else " ")
            why = ""
            if c.get("where") and str(c.get("folds_where", "")).endswith("/0"):
                # no fold where it moves the prediction there: a gain would be 0/0
                why = f"  in {c['where']}: it changes no fold's prediction — not enough"
            elif c.get("where"):
                why = (f"  in {c['where']}: {-100 * c['gain_where']:+.1f} %, folds {c['folds_where']}"
                       + (" — not enough" if c.get("not_where_it_shows") else ""))
            if c.get("unsettled") and c.get("evident"):
                # (only where it is what stops it: one short of the bar anyway needs no second reason)
                why += f"  — {c['unsettled']}"
            beside = f"  (beside {c['beside']})" if c.get("beside") else ""
            if not c.get("cross_validated", True):
                # (two decimals: a fall just short of the bar must not print as the bar itself)
                L.append(f" {mark} {c['name']:20s} in-sample RMS {-100 * c['reduction']:+6.2f} %: not cross-validated "
                         f"(only a fall of over {100 * PRESCREEN * self.settings.min_gain:.1f} % in-sample is)  "
                         f"ΔBIC {c['delta_bic']:10.1f}{beside}")
                continue
            L.append(f" {mark} {c['name']:20s} held-out RMS {-100 * c['heldout_gain']:+6.1f} %  folds "
                     f"{c['folds_improved']}/{c['folds_informative']}  in-sample {-100 * c['reduction']:+5.1f} %  "
                     f"ΔBIC {c['delta_bic']:10.1f}{why}{beside}")
        return "\n".join(L)


REST_UNRESOLVED = 0.25  # friction moving by more than this share of its sliding level while the position rests
REST_MIN_LEFT = 0.2  # ... leaves those rests out, unless that would leave less than this share compared


@dataclass(frozen=True)
class UnresolvedRest:
    mask: np.ndarray  # samples at rest whose compared path does not move
    ratio: float  # how far the friction moves over such rests, as a share of the sliding level
    runs: int

    @property
    def unresolved(self) -> bool:
        return self.ratio > REST_UNRESOLVED


def unresolved_rest(cmp_: Comparison) -> UnresolvedRest:
    """Does the position resolve presliding? Over every rest (below the rest speed, the compared
    path unchanged, at least two averaging lengths long) the range of the friction taken from
    the applied force, weighted by the rest's length, as a share of the median |friction| in
    gross sliding. A sensor that resolves presliding sees the contact's spring move while the
    applied force changes, so its rests hold a nearly constant friction (2–10 % on the
    generator's robot joints and linear stages); an encoder step as long as the whole
    presliding range (an 18-bit joint encoder on a stiff contact) hides it, and the friction
    swings across the static band while the position stands (88–117 % on such joints): the
    model, driven along that position, cannot know it."""
    path, meas, L = cmp_.path, cmp_.measured, max(cmp_.average, 1)
    still = np.r_[False, np.diff(path) == 0.0] & (np.abs(cmp_.velocity) < cmp_.v_rest)
    edges = np.flatnonzero(np.diff(np.r_[0, still.astype(np.int8), 0]))
    runs = [(a, b) for a, b in zip(edges[::2], edges[1::2]) if b - a >= 2 * L]
    sliding = gross_sliding(cmp_)
    level = float(np.median(np.abs(meas[sliding]))) if sliding.any() else float(np.median(np.abs(meas)))
    if not runs or level <= 0:
        return UnresolvedRest(still, 0.0, len(runs))
    span = np.array([np.ptp(meas[a + L // 2:b - L // 2]) for a, b in runs])
    w = np.array([b - a for a, b in runs], dtype=float)
    return UnresolvedRest(still, float(np.sum(span * w) / np.sum(w)) / level, len(runs))


def stroke_ends(x: np.ndarray, min_excursion: float) -> np.ndarray:
    """Sample indices that bound the strokes of the path ``x``: its start, each significant
    reversal (back-travel over ``min_excursion``, at the turning point), its end."""
    count = significant_reversals(x, min_excursion)
    return np.r_[0, np.flatnonzero(np.diff(count) > 0) + 1, len(x) - 1]


def median_stroke(cmp_: Comparison) -> float:
    """The stroke over which half the travel is made: the travel-weighted median of the
    travels between two significant reversals of the path (back-travel over
    ``min_excursion``), the ends of the record counting as reversals. A velocity flickering
    about the rest threshold in a dwell makes no stroke, and a controller holding the
    position at rest, which reverses many times by a few noise widths, makes strokes that
    carry no travel: a plain median of them (hundreds, against a session's tens of real
    strokes) took a stage's 2·10⁻⁶ m for its stroke beside a presliding range of 8·10⁻⁶ m."""
    x = cmp_.path
    turns = stroke_ends(x, cmp_.min_excursion)
    travel = np.abs(np.diff(x[turns]))
    travel = np.sort(travel[travel > cmp_.min_excursion])
    if not len(travel):
        return 0.0
    cum = np.cumsum(travel)
    return float(travel[int(np.searchsorted(cum, 0.5 * cum[-1]))])


def observed_presliding_range(cmp_: Comparison) -> float | None:
    """The presliding range the recording itself shows: the median, over the strokes between
    significant reversals, of the travel from the turn after which the compared friction has
    covered 90 % of its swing from the turn to the stroke's sliding level (the median of its
    middle third), a swing of at least 20 noise floors. None from fewer than three strokes.

    Used where the transition curve was not identified (a fit that found no presliding
    branches holds its starting file's curve, another machine's in other units): the range
    sets what counts as gross sliding and the shortest ripple that can be told from the
    hysteresis after each turn. A range under the position's resolution reads as the few
    samples the crossing takes: an upper bound on it."""
    x, F = cmp_.path, cmp_.measured
    turns = stroke_ends(x, cmp_.min_excursion)
    out = []
    for r, nxt in zip(turns[1:-1], turns[2:]):
        direction = np.sign(x[nxt] - x[r])
        mid = slice(r + (nxt - r) // 3, r + 2 * (nxt - r) // 3)
        if direction == 0 or mid.stop - mid.start < 5:
            continue
        swing = direction * (float(np.median(F[mid])) - F[r])
        if swing < 20.0 * cmp_.noise:
            continue
        past = np.flatnonzero(direction * (F[r:mid.stop] - F[r]) > 0.9 * swing)
        if len(past):
            out.append(direction * (x[r + int(past[0])] - x[r]))
    return float(np.median(out)) if len(out) >= 3 else None


def gross_sliding(cmp_: Comparison) -> np.ndarray:
    """Samples in gross sliding (``segment.gross_sliding_mask``) of the compared path, beyond
    twice the presliding range the comparison takes."""
    return gross_sliding_mask(cmp_.path, cmp_.velocity, cmp_.v_rest, cmp_.z_presliding)


def steady_sliding(cmp_: Comparison) -> np.ndarray:
    """Gross sliding at a steady velocity (``segment.steady_velocity_mask``, over a window each
    side of the path's smoothing and the averaging, at least 5 samples). There the friction is
    S(v) times the effects, with no transient of the motion (a controller settling, a turn)
    whose misfit a time-ordered schedule could pass off as an effect."""
    w = max(cmp_.window, 2 * cmp_.average, 5)
    return gross_sliding(cmp_) & steady_velocity_mask(cmp_.velocity, w, cmp_.v_rest)


@dataclass(frozen=True)
class SpeedOrder:
    """How a session's speeds follow its course: the holds of steady sliding in time
    (``speed_order``), or the strokes in the count of significant reversals (``stroke_order``)."""

    count: int  # holds (visits of one speed in one direction), or strokes, compared
    rho: float  # |Spearman's rank correlation| of their speeds with their order (nan: too few)


SPEED_ORDER_RHO = 0.8  # |ρ| from which speeds in order confound a drift with S(v), a softening with a rate dependence
SAME_SPEED = math.log(1.25)  # consecutive stretches this close in speed, same direction: one hold


def steady_holds(time: np.ndarray, velocity: np.ndarray, steady: np.ndarray, min_samples: int = 10) -> np.ndarray:
    """The holds of steady sliding, one row each: (mean time, mean ln|v|, direction). A hold is
    a run of consecutive stretches of steady sliding in one direction at speeds within 25 % of
    each other (at a slow level an encoder's steps break the steadiness into fragments); one
    shorter than ``min_samples`` is left out."""
    edges = np.flatnonzero(np.diff(np.r_[0, steady.astype(np.int8), 0]))
    holds = []  # [samples, Σ samples·t, Σ samples·ln|v|, sign]
    for a, b in zip(edges[::2], edges[1::2]):
        n, sg = b - a, np.sign(np.median(velocity[a:b]))
        ls = math.log(max(float(np.median(np.abs(velocity[a:b]))), 1e-300))
        if holds and holds[-1][3] == sg and abs(holds[-1][2] / holds[-1][0] - ls) < SAME_SPEED:
            holds[-1][0] += n
            holds[-1][1] += n * float(np.mean(time[a:b]))
            holds[-1][2] += n * ls
        else:
            holds.append([n, n * float(np.mean(time[a:b])), n * ls, sg])
    return np.array([(h[1] / h[0], h[2] / h[0], h[3]) for h in holds if h[0] >= min_samples]).reshape(-1, 3)


def speed_order(time: np.ndarray, velocity: np.ndarray, steady: np.ndarray, min_samples: int = 10) -> SpeedOrder:
    """|Spearman's ρ| between the time and the speed |v| of each hold of steady sliding
    (``steady_holds``; each hold counted once, however long): a sweep that visits its speed
    levels in order has |ρ| near 1, and then S(v)'s shape fitted to it takes up any slow change
    in time."""
    return holds_order(steady_holds(time, velocity, steady, min_samples))


def holds_order(holds: np.ndarray) -> SpeedOrder:
    """``speed_order`` of holds already made (``steady_holds``)."""
    return _rank_order(holds[:, 0], holds[:, 1])


REVISIT_SHARE = 0.25  # two holds at one speed and direction this share of the session apart: a level visited again


def levels_revisited(holds: np.ndarray, span: float) -> int:
    """How many holds (``steady_holds``) have another at the same speed (within SAME_SPEED) and
    direction at least REVISIT_SHARE of the session's ``span`` away in time. With none, the free
    steady curve the decision compares beside holds each level at the one time it was visited,
    and a slow drift is taken up level by level, whatever the order of the levels."""
    t, ls, sg = holds[:, 0], holds[:, 1], holds[:, 2]
    same = (np.abs(ls[:, None] - ls[None, :]) < SAME_SPEED) & (sg[:, None] == sg[None, :])
    far = np.abs(t[:, None] - t[None, :]) >= REVISIT_SHARE * span
    return int(np.sum(np.any(same & far, axis=1)))


def stroke_order(reversals: np.ndarray, velocity: np.ndarray, v_rest: float, min_samples: int = 5) -> SpeedOrder:
    """|Spearman's ρ| between the count of significant reversals and the speed of each stroke
    between two of them (the 90th percentile of |v| over its moving samples: its top speed, not
    its transitions or dwells). A session whose strokes run faster with every reversal (a
    sweep, slowest first) has |ρ| near 1, and then a presliding stiffness that changes with the
    reversals cannot be told from one that depends on the speed of the stroke. Every moving
    stroke counts, a presliding experiment's loops too: counting only strokes into gross
    sliding was tried, and with a fitted base's shorter presliding range a robot joint's torque
    ramps then count as sliding at scattered speeds (ρ 0.88 → 0.75 on one control)."""
    v = np.abs(velocity)
    ks, spd = [], []
    for k in np.unique(reversals):
        m = (reversals == k) & (v > v_rest)
        if m.sum() >= min_samples:
            ks.append(float(k))
            spd.append(math.log(float(np.quantile(v[m], 0.9))))
    return _rank_order(np.array(ks), np.array(spd))


def _rank_order(order: np.ndarray, log_speed: np.ndarray) -> SpeedOrder:
    if len(order) < 4:
        return SpeedOrder(len(order), math.nan)
    # ties take their mean rank (a level visited forward and back, at once, is one rank)
    return SpeedOrder(len(order), _corr(rankdata(order), rankdata(log_speed)))


def load_order(cmp_: Comparison, mask: np.ndarray) -> SpeedOrder:
    """How the normal load follows time: |Spearman ρ| of the load against time over the samples
    compared (at most 4,000 of them, evenly spread; NaN without a varying load). Near 1 where the
    load rises (or falls) over the session, steps or not: a drift in time then follows the same
    trend, and a load's exponent fitted alone takes part of a drift up."""
    return _time_order(cmp_.time, cmp_.load, mask)


def travel_order(cmp_: Comparison, mask: np.ndarray) -> SpeedOrder:
    """How the compared path follows time: |Spearman ρ| of position against time over the
    samples compared (at most 4,000 of them, evenly spread). Near 1 where the session covers
    its travel one way — a disc or a spindle turning one way, a feed run once along its axis —
    and every position is passed once, at one time."""
    return _time_order(cmp_.time, cmp_.path, mask)


def _time_order(time: np.ndarray, signal: np.ndarray | None, mask: np.ndarray) -> SpeedOrder:
    """|Spearman ρ| of ``signal`` against ``time`` over the samples in ``mask`` (at most 4,000
    of them, evenly spread); NaN without a signal, with too few samples or a constant one."""
    idx = np.flatnonzero(mask)
    idx = idx[:: max(1, len(idx) // 4000)]
    if signal is None or len(idx) < 4 or np.ptp(signal[idx]) == 0:
        return SpeedOrder(len(idx), math.nan)
    return SpeedOrder(len(idx), abs(_corr(rankdata(time[idx]), rankdata(signal[idx]))))


RIPPLE_ONE_WAY_PERIODS = 8  # a ripple along a travel covered one way must repeat this often over it


def ripple_on_one_way_travel(params: dict, span: float, order: SpeedOrder) -> str | None:
    """Why a ripple is not told from a trend along the session (``Term.unsettled``'s kind of
    reason), or None: on a travel covered one way (``travel_order``, |ρ| ≥ SPEED_ORDER_RHO)
    the position is a clock, and a ripple of under RIPPLE_ONE_WAY_PERIODS periods over it is a
    slow change in time, or in sliding distance (a run-in, wear), as well: a pin-on-disc made
    apart, its friction running in over 3 m of sliding, had that run-in named a ripple of 130 rad
    (2.6 periods of its 341 rad)."""
    if not (order.rho >= SPEED_ORDER_RHO):  # (NaN: too few samples to tell)
        return None
    lam = float(params["wavelength"])
    periods = span / lam
    if periods >= RIPPLE_ONE_WAY_PERIODS:
        return None
    return (f"its wavelength {lam:.3g} repeats {periods:.1f} times over a travel the session covers one way "
            f"(position follows time, |Spearman ρ| {order.rho:.2f}): a slow change in time or in sliding distance "
            f"(a run-in, wear) would look the same. To tell: {EFFECTS['position_ripple'].separated_by}")


def load_changing(load: np.ndarray) -> np.ndarray:
    """The samples where a logged load changes: a step (one sample's change over 5 × the
    column's sample-to-sample noise), or, over a window of a 200th of the record, a ramp (the
    means of the window's two halves apart by over 5 × the σ their noise gives that difference,
    σ·√(4/W)). Per sample, a ramp of 800 N over 10 s at 500 Hz moves 0.16 N, under a load cell's
    noise: only the steps had counted, 6 samples of a joint's 25,000 of ramps."""
    n = len(load)
    step_sd = _mad_sd(np.diff(load))
    changing = np.abs(np.gradient(load)) > 5 * (step_sd + 1e-300)
    w = max(2, n // 400)  # half the window
    if n > 4 * w:
        c = np.concatenate([[0.0], np.cumsum(load - load[0])])
        mean = (c[w:] - c[:-w]) / w  # mean[i] = mean of load[i : i + w]
        diff = np.zeros(n)
        diff[w:n - w + 1] = np.abs(mean[w:] - mean[:-w])  # at i: load[i : i+w] against load[i-w : i]
        # the noise σ = step_sd/√2 of one sample gives the difference of two w-sample means σ·√(2/w)
        changing |= diff > 5 * step_sd / math.sqrt(w) + 1e-300
    return changing


def regime_masks(cmp_: Comparison) -> dict:
    v = cmp_.velocity
    m = {"all": np.ones(len(v), bool), "presliding": np.abs(v) <= cmp_.v_rest, "sliding, v > 0": v > cmp_.v_rest,
         "sliding, v < 0": v < -cmp_.v_rest}
    if cmp_.load is not None and np.ptp(cmp_.load) > 0:
        m["load changing"] = load_changing(np.asarray(cmp_.load, dtype=float))
    return m


MEMORY_UNKNOWN_MAX = 0.5  # the most of a recording whose start may be left out


@dataclass(frozen=True)
class InitialMemory:
    """How the start of a recording is compared (see ``initial_memory``)."""

    scored: np.ndarray  # samples compared
    offset: np.ndarray | None  # 1 on the samples whose memory holds an unknown constant, else 0
    t_first: float  # time of the first sample compared
    t_known: float  # time from which the memory is the model's (nan: never within the record)


def initial_memory(cmp_: Comparison) -> InitialMemory:
    """The hysteresis memory at the start of a recording (the extrema of section III-B's
    stacks, the current F_b) is the machine's history before the log, which the data do not
    show: the model starts from F_h = 0 with only the outer loop, the machine from wherever
    it was (from a virgin contact, its first curve is not the model's F_d either). So:
    - until the first significant reversal (the first curve), nothing is compared;
    - from there until the first gross sliding resets both memories to the outer loop, every
      curve starts from a reversal point that inherits the first curve's difference: the
      model and the machine differ by a constant there, which the comparison leaves free;
    - the stroke that leads into that first gross sliding is left out: on it the curve
      passes back over the first curve's extremum and the two memories merge;
    - a recording that slides before it reverses is compared from its first gross sliding.
    If that would leave out more than half the recording, everything is compared as the
    model starts (and the caller says so)."""
    n = len(cmp_.time)
    everything = InitialMemory(np.ones(n, bool), None, float(cmp_.time[0]), float("nan"))
    gs = gross_sliding(cmp_)
    i_reset = int(np.argmax(gs)) if gs.any() else n
    rev = significant_reversals(cmp_.path, cmp_.min_excursion)
    i_rev = int(np.argmax(rev >= 1)) if rev[-1] >= 1 else n
    if i_reset == 0:
        return InitialMemory(np.ones(n, bool), None, float(cmp_.time[0]), float(cmp_.time[0]))
    first = min(i_rev, i_reset)
    if first > MEMORY_UNKNOWN_MAX * n:
        return everything
    scored = np.zeros(n, bool)
    scored[first:] = True
    offset = None
    if i_rev < i_reset < n:
        # the start of the stroke that slides: the last sample moving the other way, + 1
        v = cmp_.velocity[:i_reset]
        other = np.flatnonzero(v * np.sign(cmp_.velocity[i_reset]) < -cmp_.v_rest)
        i_stroke = int(other[-1]) + 1 if len(other) else i_rev
        scored[i_stroke:i_reset] = False
        offset = np.zeros(n)
        offset[i_rev:i_stroke] = 1.0
    elif i_rev < i_reset:
        offset = np.zeros(n)
        offset[i_rev:] = 1.0
    t_known = float(cmp_.time[i_reset]) if i_reset < n else float("nan")
    return InitialMemory(scored, offset, float(cmp_.time[first]), t_known)


@dataclass(frozen=True)
class UnseenAtGaps:
    """What the time gaps of a log hide from the comparison (``unseen_at_gaps``)."""

    gaps: np.ndarray  # indices where the log resumes after a gap (``segment.time_gaps``)
    mask: np.ndarray  # samples not compared because of them
    threshold: float  # a step longer than this is a gap (s)
    longest: float  # the longest gap (s)

    def note(self) -> str:
        return (f"{len(self.gaps)} time gap(s) in the log (steps over {self.threshold:.3g} s, five times the 99th "
                f"percentile of the steps; the longest {self.longest:.3g} s): the motion there is not seen, so "
                f"{int(self.mask.sum())} samples are not compared — those whose smoothing or averaging reaches across "
                f"a gap, and after each gap those until the first gross sliding, the model's memory not holding what "
                f"the contact did unseen")


def unseen_at_gaps(cmp_: Comparison) -> UnseenAtGaps | None:
    """Where the log has time gaps (samples lost, a pause): the samples whose path smoothing or
    eq. (8)'s averaging reaches across one mix the motion before and after it with what was not
    seen; and after a gap the contact's hysteresis memory (section III-B's stacks) may hold
    reversals the log did not see, which only the next gross sliding wipes, as at the start of a
    record (``initial_memory``). None where the log has no gap."""
    t = cmp_.time
    threshold = gap_threshold(t)
    gaps = time_gaps(t, threshold)
    if not len(gaps):
        return None
    n = len(t)
    mask = across_gaps(n, gaps, max(cmp_.window, cmp_.average) // 2 + 1)
    gs = gross_sliding(cmp_)
    ends = np.concatenate([gaps[1:], [n]])
    for g, end in zip(gaps, ends):
        sliding = np.flatnonzero(gs[g:end] & ~mask[g:end])
        mask[g:end if not len(sliding) else g + int(sliding[0])] = True
    return UnseenAtGaps(gaps, mask, threshold, float(np.max(t[gaps] - t[gaps - 1])))


def _rms(a) -> float:
    return float(np.sqrt(np.mean(a**2))) if len(a) else float("nan")


EXPLAINS = {"time_drift": "time", "normal_load": "load", "position_ripple": "position", "cyclic_softening": "reversals",
            "presliding_stiffness": "velocity"}


def moved_from_held(held, before: FrictionParams, after: FrictionParams, g: float, curve_reshaped: bool) -> dict:
    """{path: (before, after)} of the parameters a fit's provenance holds that the model written
    moved beyond the common level g (``bake`` scales every force by it): a Coulomb side's F_s
    refitted apart from F_c, n or σ1 refitted, the curve reshaped segment by segment. A side
    with nothing in the record to move it, or v_s, δ, σ2 the refit holds, stays held."""
    if not isinstance(held, Mapping):
        return {}
    out = {}
    for path in held:
        if path.startswith("transition_curve"):
            if curve_reshaped:
                out[path] = ("the file's shape", "reshaped")
            continue
        try:
            b, a = float(get_value(before, path)), float(get_value(after, path))
        except (ParameterError, TypeError, ValueError):
            continue
        scale = g if path.endswith((".Fs", ".Fc", ".sigma2")) or path == "sigma1" else 1.0
        if not math.isclose(a, scale * b, rel_tol=1e-6, abs_tol=1e-300):
            out[path] = (f"{b:.4g}", f"{a:.4g}")
    return out


def bake(params: FrictionParams, g: float, k0: float) -> FrictionParams:
    """The parameters with every force scaled by g and the presliding stiffness by κ0 —
    exactly the model whose friction is g·F with F_d(κ0·z)."""
    from ..model import Stribeck, StribeckSide

    def side(s):
        return StribeckSide(Fs=s.Fs * g, Fc=s.Fc * g, vs=s.vs, delta=s.delta, sigma2=s.sigma2 * g)

    tc = params.transition_curve
    if tc.kind == "piecewise_linear":
        new_tc = TransitionCurve(kind=tc.kind, z=tuple(z / k0 for z in tc.z), F=tuple(f * g for f in tc.F))
    else:
        sh = dict(tc.shape)
        new_tc = TransitionCurve(kind=tc.kind, shape={"A": sh["A"] * g, "z0": sh["z0"] / k0, "k": sh["k"] * g * k0})
    kw = dict(stribeck=Stribeck(side(params.stribeck.positive), side(params.stribeck.negative)), transition_curve=new_tc,
              sigma1=params.sigma1 * g)
    if params.sigma0 is not None:
        kw["sigma0"] = params.sigma0 * g * k0
    return params.replace(**kw)


def scored_comparison(rec: Recording, params: FrictionParams, s: Settings) -> Comparison:
    """The comparison a diagnosis of ``rec`` with ``params`` makes, with the samples it scores
    (``Comparison.scored``: the start whose memory the log does not show, and rests the sensor
    does not resolve, left out) and its noise floor settled there; its choices in its notes."""
    cmp_ = comparison_of(rec, params, s.space, dict(s.reading))
    cmp_.z_presliding = presliding_range(params)
    stroke = median_stroke(cmp_)
    # a transition curve identified on presliding data (uncertainties given) is trusted: the
    # strokes of a presliding experiment are shorter than its range by design
    identified = any(k.startswith("transition_curve") for k in params.uncertainty)
    if stroke > 0 and cmp_.z_presliding > stroke / 8 and not identified:
        # a transition curve held from another machine (a fit without presliding data keeps
        # its starting file's) can claim a presliding range as long as the strokes: the
        # recording's own crossings after its turns say how long it is, else an eighth of the stroke
        seen = observed_presliding_range(cmp_) if cmp_.space == "friction" else None
        use = min(seen, stroke / 8) if seen else stroke / 8
        cmp_.notes.append(f"the model's presliding range {cmp_.z_presliding:.3g} is over an eighth of the median "
                          f"stroke {stroke:.3g} and was not identified: "
                          + (f"the friction covers 90 % of its swing {seen:.3g} after a turn (median over the "
                             f"strokes), and {use:.3g}" if seen else f"{use:.3g}")
                          + " is used to tell gross sliding and the shortest ripple")
        cmp_.z_presliding = use
    reversal_threshold(cmp_)
    cmp_.params = params
    meas = cmp_.measured
    n = len(meas)
    allm = np.ones(n, bool)
    if cmp_.space == "friction":
        mem = initial_memory(cmp_)
        allm = mem.scored
        cmp_.memory_offset = mem.offset
        if not allm.all():
            cmp_.notes.append(f"compared from {mem.t_first:.4g} s on ({int(allm.sum())} of {n} samples): the first "
                              f"curve starts from the machine's history before the log, which the data do not show")
        if mem.offset is not None:
            until = "its end" if math.isnan(mem.t_known) else f"{mem.t_known:.4g} s"
            cmp_.notes.append(f"from {mem.t_first:.4g} s to {until} (the first gross sliding) the hysteresis memory still "
                              f"holds that history: a constant of its own is left free there, and the stroke into "
                              f"that sliding, where the two memories merge, is left out")
        elif allm.all() and math.isnan(mem.t_known):
            cmp_.notes.append("the recording reverses late: the model's memory at its start (F_h = 0, the outer loop "
                              "only) is assumed for every sample")
    unseen = unseen_at_gaps(cmp_)
    if unseen is not None:
        allm = allm & ~unseen.mask
        cmp_.notes.append(unseen.note())
    if cmp_.inertia is not None:
        rest = unresolved_rest(cmp_)
        if rest.unresolved and (allm & ~rest.mask).sum() < REST_MIN_LEFT * allm.sum():
            cmp_.notes.append(f"while the position rests the friction taken from the applied force moves by "
                              f"{rest.ratio:.0%} of the sliding level: the sensor does not resolve presliding, but "
                              f"leaving those rests out would leave under {REST_MIN_LEFT:.0%} of the record, so "
                              f"they are compared and the gap there says more about the sensor than the model")
        elif rest.unresolved:
            allm = allm & ~rest.mask
            cmp_.notes.append(f"while the position rests (the compared path unchanged) the friction taken from "
                              f"the applied force moves by {rest.ratio:.0%} of the sliding level (a length-weighted "
                              f"mean over {rest.runs} rests; over {REST_UNRESOLVED:.0%} means the sensor does not "
                              f"resolve presliding): the friction there is set by what is applied, not by a motion "
                              f"the model could be driven along, and those {int(rest.mask.sum())} samples are not "
                              f"compared; a change of the presliding spring alone (cyclic_softening) may not show "
                              f"in what is left: a finer position sensor would tell")
    cmp_.scored = allm
    settle_noise_floor(cmp_, allm)
    return cmp_


@one_blas_thread
def diagnose(rec: Recording, params: FrictionParams, *, progress=None, settings: Settings | None = None) -> Diagnosis:
    """Run the workflow on one recording with the current model ``params``."""
    s = settings or Settings()
    started = perf_counter()
    say = progress or (lambda frac, msg: None)
    say(0.01, "choosing where to compare")
    lacking = [e["name"] for e in params.effects if e["name"] in EFFECTS and "load" in EFFECTS[e["name"]].needs]
    if lacking and rec.normal_load is None:
        # (a set diagnosed on a recording with a load column, then used on one without)
        raise DataError(f"{rec.source}: the model carries {lacking[0]}, which needs a normal-load column, and the "
                        f"recording has none: diagnose it with a model without that effect (fit this recording "
                        f"first), or give the load (--columns normal_load=<column>)")
    cmp_ = scored_comparison(rec, params, s)
    load_like = [c for c in getattr(rec, "ignored", None) or [] if may_be_load(str(c))]
    if rec.normal_load is None and load_like:
        # no load candidate without a load: a column the reader passed over may be one (a
        # pitch bearing's bending moment, left out where the user named only the drive torque);
        # one whose unit is of another kind (a winding's °C) is not offered as one
        cmp_.notes.append(unread_load_note(load_like))
    if cmp_.load is not None and ("normal_load" in s.candidates or any(e["name"] == "normal_load" for e in params.effects)):
        said = load_not_pressing(cmp_.load, cmp_.scored, rec.columns.get("normal_load", "normal_load"),
                                 rec.units.get("normal_load", ""))
        if said:
            cmp_.notes.append(said)
    if rec.temperature is not None and "time_drift" in s.candidates:
        # read, and used by no candidate: said, with its course over the span compared (a stage's
        # winding warmed and cooled within the session: a one-way drift was named and nothing
        # said the change had turned back)
        span = cmp_.scored if cmp_.scored is not None and cmp_.scored.any() else np.ones(len(cmp_.time), bool)
        t_lo, t_hi = float(cmp_.time[span][0]), float(cmp_.time[span][-1])
        inside = (rec.time >= t_lo) & (rec.time <= t_hi)
        col = rec.columns.get("temperature", "temperature")
        course = temperature_course(rec.time[inside], rec.temperature[inside], header_unit(col) or "")
        if course is not None:
            said, turns = course
            cmp_.notes.append(f"a temperature is logged ({col}): over the span compared it {said}. No candidate reads a "
                              f"temperature: a friction that follows it is seen as time_drift, a first-order approach "
                              f"in time"
                              + (", which a temperature that turns back does not follow: a drift named here holds "
                                 "only part of that change, and its b and τ are not the temperature's" if turns else ""))
    base_params = params.replace(effects=())
    meas = cmp_.measured
    n = len(meas)
    allm = cmp_.scored
    engine = Engine(base_params, cmp_, s.free_steady)
    # the model as given, its own effects included
    prior0 = [dict(e) for e in params.effects]
    pred_given = engine.predict(1.0, 1.0, prior0)
    # the model as given, beside what the model written leaves free as well (``model_nuisance``):
    # the constant of the memory's unknown start (``initial_memory``) and, for friction taken
    # from an applied force, eq. (8)'s inertia (not written either). So a file written by a
    # diagnosis starts the next one from the gap its last step showed
    pred_given_c = pred_given + model_nuisance(meas - pred_given, allm, cmp_.memory_offset, cmp_.acceleration).correction
    rms0 = _rms((meas - pred_given_c)[allm])
    if not math.isfinite(rms0):
        # (nothing is compared to a model that does not simulate: every gap would read "nan")
        bad = int(np.sum(~np.isfinite(pred_given[allm])))
        raise DataError(f"{rec.source}: the model as given does not simulate along this recording ({bad} of "
                        f"{int(allm.sum())} samples compared are not finite): check the parameter file's values "
                        f"(n = {params.n:g}, the transition curve, S(v)) or fit this recording first")
    say(0.05, "refitting the level and presliding stiffness (the alternative)")
    # the strokes' order sets how far a softening must be seen to settle (``softening_nc_max``):
    # for one the file carries as for a candidate
    reversals = cmp_.context().reversals
    strokes = stroke_order(reversals[allm], cmp_.velocity[allm], cmp_.v_rest)
    # whether the travel is covered one way, where a ripple must repeat often to be one
    # (``ripple_on_one_way_travel``)
    travel, travel_span = travel_order(cmp_, allm), float(np.ptp(cmp_.path[allm]))
    prior_terms = []
    prior_u = np.zeros(0)
    for e in prior0:
        if e["name"] in EFFECTS and e["name"] != "presliding_stiffness":
            tm = _terms_for(e["name"], cmp_, strokes, e["params"].get("min_excursion"))
            tm = dataclasses.replace(tm, fixed={k: e["params"][k] for k in tm.fixed})
            prior_terms.append(tm)
            prior_u = np.concatenate([prior_u, _entry_to_u(tm, e["params"])])
    base = refit_base(engine, base_params, prior_terms, prior_u, allm, s.refit_curve)
    # what the base refitted alone leaves along the travel that no friction effect holds
    # a force in proportion to the travel (a spring: the periodic search below does not see it),
    # read in the steady sliding, where friction is S(v) times the effects and no turn's
    # transition, misfit at one end of the travel moving up and at the other moving down, enters
    resid_alone = meas - base.null.pred
    ts = travel_spring(cmp_, resid_alone, allm & steady_sliding(cmp_))
    ts = ts if ts is not None and ts.shown else None
    tf = travel_force(cmp_, resid_alone, allm, ripple_min_wavelength(cmp_))
    tf = tf if tf is not None and tf.shown else None
    out = s.travel_force_out
    pu, fu = params.units.get("position", ""), params.units.get("force", "")
    taken_out = ("; it is taken out of the friction compared, and the base (n, σ1, S(v), the curve) refitted again "
                 "without it, before the candidates are judged (every gap here and the figures are without it), so "
                 "that none is credited with the part of it a friction effect can fit" if out else "")
    if ts is not None:
        cmp_.notes.append(spring_note(ts, "the base refitted alone", fu, pu))
    if tf is not None:
        cmp_.notes.append(f"a force along the travel: what the base refitted alone leaves in the sliding holds a "
                          f"period of {tf.wavelength:.4g} {pu} of amplitude {tf.amplitude:.3g} ± {tf.sd:.2g} {fu} "
                          f"that keeps its sign whichever way the motion goes (the part following the motion's "
                          f"sign, as a friction ripple's does, {tf.following:.2g}): cogging, gravity, a spring or a "
                          f"cable, not a friction effect — no candidate holds it; compensate it apart from friction"
                          + taken_out)
    if out and tf is not None:
        # a ball screw's cogging of period π rad, left in, was named a friction ripple of 3.3 rad
        # that took 10 % of the gap: a ripple follows the motion's sign and fits a part of any
        # such force. A new array, not in place: ``measured`` may be the recording's own friction
        # column; the engine and every gap read ``cmp_.measured``
        meas = cmp_.measured = meas - tf.along(cmp_)
        pred_given_c = pred_given + model_nuisance(meas - pred_given, allm, cmp_.memory_offset,
                                                   cmp_.acceleration).correction
        rms0 = _rms((meas - pred_given_c)[allm])
        # the base as if the force had not been there: refitted with it in, its S(v) and curve
        # leaned on the force's part a friction level can hold
        base = refit_base(engine, base_params, prior_terms, prior_u, allm, s.refit_curve)
    if base.curve_note:
        cmp_.notes.append(base.curve_note)
    alone, refit_curve, base_refit, null = base.alone, base.refit_curve, base.refit, base.null
    base_params = base_refit.params
    k0 = null.k0
    # the file's own effects, refitted here with the base: one that does next to nothing on this
    # recording is said (a set diagnosed on another recording carries what this one may not show;
    # nothing named, the model written is the file as given, its effect included)
    made_from = sorted({os.path.basename(str(d)) for key in ("data", "diagnosed")
                        for d in (params.provenance or {}).get(key, []) or []} - {os.path.basename(rec.source)})
    for e in null.entries:
        if e["name"] in HELD_STIFFNESS or e["name"] not in {t.name for t in prior_terms}:
            continue
        own = own_gain(engine, null, e["name"])
        if own < PRESCREEN * s.min_gain:
            cmp_.notes.append(f"the file's {e['name']} is not seen in this recording: refitted here "
                              f"({format_values(e['name'], e['params'], params.units)}) it removes {max(own, 0.0):.1%} "
                              f"of the gap left with it switched off, under {PRESCREEN * s.min_gain:.1%}"
                              + (f"; the file was made from {', '.join(made_from)}" if made_from else ""))
    masks = [m & allm for m in fold_masks(n, s.folds, s.blocks_per_fold, cmp_.windows)]
    # the transitions: within twice the presliding range of a reversal (at rest or moving),
    # after the first significant reversal: before it the model runs on its virgin curve, a
    # property of the hysteresis model itself, not of a softening contact
    transition = ~gross_sliding(cmp_) & (reversals >= 1)
    # where each candidate must help as well, held out: a stiffness effect where the presliding
    # spring shows (in the transitions after the first reversal), else it could only stand in for a
    # misfit of break-away; a friction factor of time, position or reversals in steady
    # sliding, else it could only stand in for the transition curve's misfit (largest where
    # a session starts with presliding). The load is measured, not made by the motion: a load
    # effect is judged wherever the load varies.
    sliding = steady_sliding(cmp_)
    holds = steady_holds(cmp_.time, cmp_.velocity, sliding & allm)
    order = holds_order(holds)
    if "time_drift" in s.candidates and abs(order.rho) >= SPEED_ORDER_RHO:
        # a drift in time is then a slope of S(v) as well: the base's S(v) refit and the free
        # steady curve the decision compares beside take part of it up before time_drift is tried
        cmp_.notes.append(f"the session slides at speeds in order of time (|Spearman ρ| {order.rho:.2f} over "
                          f"{order.count} holds of steady sliding, those faster than |v| = {cmp_.v_rest:.3g}: slower "
                          f"runs are not told from presliding here): a slow change in time and the shape of "
                          f"S(v) are confounded here, and part of a drift is taken as S(v). To tell: visit the "
                          f"speed levels in a shuffled order, or repeat the first ones at the session's end")
    if "cyclic_softening" in s.candidates and abs(strokes.rho) >= SPEED_ORDER_RHO:
        # the stiffness varying with speed a softening is judged beside (stiffness_alternative) then
        # takes up part of a true softening, and a transition whose dependence on speed eq. (5)
        # misses looks like a softening: the two are the same trend along such a session
        cmp_.notes.append(f"the strokes run at speeds in order of the reversals (|Spearman ρ| {strokes.rho:.2f} over "
                          f"{strokes.count} strokes): a presliding stiffness changing with the reversals "
                          f"(cyclic_softening) and one depending on the stroke's speed follow the same trend "
                          f"here; a softening is credited only with what the latter leaves, and either may be "
                          f"the cause. To tell: repeat the slowest strokes at the session's end")
    loads = load_order(cmp_, allm) if {"normal_load", "time_drift"} <= set(s.candidates) else None
    if loads is not None and loads.rho >= SPEED_ORDER_RHO:
        # (said whichever is named: two alike candidates are each judged beside the other, but a
        # load's α fitted where only it passes may still hold part of a drift, beyond its σ)
        cmp_.notes.append(f"the normal load follows time (|Spearman ρ| {loads.rho:.2f}): a load effect and a drift in "
                          f"time follow the same trend here, and the load's exponent may hold part of a drift (its σ "
                          f"does not include that). To tell: {separating_experiment('normal_load', 'time_drift')}")
    must_show = {nm: (transition if EFFECTS[nm].acts_on == "stiffness" else sliding) for nm in EFFECTS
                 if nm != "normal_load"}
    regimes_m = regime_masks(cmp_)
    r0 = meas - pred_given
    steps = [{"label": "model as given", "name": None, "params": None, "rms": rms0,
              "rms_free": _rms((r0 - engine.nuisance(r0, allm, pred_given))[allm])},
             {"label": "", "name": None, "params": None, "rms": _rms((meas - null.model)[allm]),
              "rms_free": _rms((meas - null.pred)[allm])}]
    step_preds = [pred_given_c]
    scored = [pred_given + engine.nuisance(r0, allm, pred_given), null.pred]
    named = []
    # after each round that named an effect: its effects' parameter σ (``effect_sds``) and the values
    # they belong to, each effect as fitted beside the free steady curve; an unused last one goes back a round
    rounds = [({}, {})]
    # the file's own effects are refitted with every candidate: theirs too (not a held stiffness, HELD_STIFFNESS)
    refitted_prior = {t.name for t in prior_terms if t.name not in HELD_STIFFNESS}
    confounded = []
    cur, cur_terms, cur_u = null, list(prior_terms), null.u[2:] if len(null.u) > 2 else np.zeros(0)
    fits = [(list(prior_terms), np.concatenate([[math.log(null.g)], null.u[2:]]))]  # per step: terms, u
    cands_out = []
    excluded = set()
    names = [c for c in s.candidates if c in EFFECTS and not (EFFECTS[c].needs and any(
        getattr(cmp_.context(), nd) is None or (nd == "load" and np.ptp(cmp_.load) <= 0) for nd in EFFECTS[c].needs))]
    names = [c for c in names if c not in {e["name"] for e in prior0}]
    # the last winner, the rivals it did not clearly beat, the state before it was named, and the
    # alike rivals told apart in its favour
    pending = None
    under_noise = None  # a winner not named: the model before it already under the noise floor
    carried: tuple = ()  # a round taken back: the better ones of the pairs it had found confounded
    for _ in range(2 * s.max_effects):  # a round taken back (below) excludes two candidates or more
        step = len(named)
        if step >= s.max_effects:
            break
        say(0.1 + 0.8 * step / s.max_effects, f"step {step + 1}: cross-validating the alternative")
        evid = []
        todo = [c for c in names if c not in named and c not in excluded]
        plain = Alternative(cur, cur_terms, cur_u)
        beside_stiffness = None
        held = held_stiffness(cur_terms, s)
        if held and any(EFFECTS[c].acts_on == "stiffness" for c in todo):
            say(0.1 + 0.8 * step / s.max_effects,
                f"step {step + 1}: the alternative with {held_said(held)}")
            beside_stiffness = stiffness_alternative(engine, cmp_, plain, k0, allm, held)

        def judge(name: str, alt: Alternative) -> Evidence | None:
            """The candidate ``name`` fitted beside ``alt`` and, unless it is far from the
            threshold in-sample, cross-validated against it."""
            # a stiffness candidate, and the alternative it must beat, follow the friction effects as
            # that alternative fitted them (``Engine.following_held``)
            engine.following_held(alt.fit.entries if alt is beside_stiffness else None)
            rss_null = alt.fit.rss
            options = fit_candidate(engine, name, cmp_, strokes, alt, allm, k0, s.softening_thresholds)
            if not options:
                return None
            term, fr = options[0]
            terms = alt.terms + [term]
            rms_c, rms_a = _rms((meas - fr.pred)[allm]), _rms((meas - alt.fit.pred)[allm])
            n_eff = _effective_n(meas - fr.pred)
            dbic = n_eff * math.log(max(fr.rss, 1e-300) / max(rss_null, 1e-300)) + len(term.free) * math.log(n_eff)
            if rms_c > (1.0 - PRESCREEN * s.min_gain) * rms_a:
                # held out, a candidate does worse than in-sample: one this far below the threshold
                # on the data it was fitted to is not cross-validated
                return Evidence(name, fr.entries[-1]["params"], rms_c, None, None, None, dbic, fr.pred - alt.fit.pred,
                                fr, against=alt, rms_alt=rms_a)
            null_sse, null_preds = alt.held_out(engine, masks, k0)
            _, preds, fold_entries = cross_validate(engine, terms, fr.u, masks, k0, fit_k0=alt.fit_k0,
                                                    others=tuple((alt.terms + [t], f.u) for t, f in options[1:]))
            sse = np.array([engine.score((meas - preds[i])[m]) for i, m in enumerate(masks)])
            # a fold where the candidate hardly changes the held-out prediction says nothing
            informative = np.array([np.sum((preds[i] - null_preds[i])[m] ** 2) > INFORMATIVE * max(null_sse[i], 1e-300)
                                    for i, m in enumerate(masks)])
            where = must_show.get(name)
            failed_where = where_name = gain_there = folds_there = None
            if where is not None:
                where_name = "the transitions" if EFFECTS[name].acts_on == "stiffness" else "steady sliding"
                sp = np.array([engine.score((meas - preds[i])[m & where]) for i, m in enumerate(masks)])
                npre = np.array([engine.score((meas - null_preds[i])[m & where]) for i, m in enumerate(masks)])
                inf_p = np.array([np.sum((preds[i] - null_preds[i])[m & where] ** 2) > INFORMATIVE * max(npre[i], 1e-300)
                                  for i, m in enumerate(masks)])
                gain_there = 1.0 - math.sqrt(np.sum(sp) / max(np.sum(npre), 1e-300))
                folds_there = f"{int(np.sum((sp < npre) & inf_p))}/{int(inf_p.sum())}"
                if not (inf_p.sum() >= 2 and np.sum((sp < npre) & inf_p) > inf_p.sum() / 2 and gain_there >= s.min_gain):
                    failed_where = where_name
            unsettled = term.unsettled(fr.u[len(fr.u) - len(term.free):], strokes)
            if name == "position_ripple":
                unsettled = unsettled or ripple_on_one_way_travel(fr.entries[-1]["params"], travel_span, travel)
            return Evidence(name, fr.entries[-1]["params"], rms_c, sse, null_sse, informative, dbic,
                            fr.pred - alt.fit.pred, fr, failed_where, where_name, gain_there, folds_there,
                            alt, rms_a, unsettled, fold_entries)

        for j, name in enumerate(todo):
            say(0.1 + 0.8 * (step + (j + 1) / (len(todo) + 1)) / s.max_effects, f"step {step + 1}: {name}")
            alts = [beside_stiffness if (beside_stiffness is not None and EFFECTS[name].acts_on == "stiffness") else plain]
            # only while no friction effect is in the model: the range, following their product, would
            # otherwise reshape the transitions under that effect alone, and the candidate be credited
            # with what the range does by itself (``range_alternative`` is ``plain`` only there)
            if (s.range_with_friction and name in RANGE_FOLLOWS
                    and not any(EFFECTS[t.name].acts_on == "friction" for t in plain.terms)):
                alts.append(range_alternative(cmp_, plain))
            judged = [e for e in (judge(name, a) for a in alts) if e is not None]
            if judged:
                # with a range following it and without, each judged on its own: the one that passes,
                # else the one furthest along the rule (evident, then gaining held out), then better
                # held out (a rotary table's warm-up passed without the range and not with it; drifts
                # hidden by rising sweeps of the suite pass with it only)
                evid.append(max(judged, key=lambda e: (e.passes(s), e.evident(s), e.gains_held_out(s), e.heldout_gain)))
        engine.following_held(None)
        if pending is not None:
            # a rival the last winner did not clearly beat, its correction unlike the winner's, that
            # no longer gains held out beside it: the two explained the same part of the residual
            # after all (a linear stage's drift on a sweep in rising speeds: a softening won by
            # 4.51 % to 4.49 % held out, and the drift, 19 % better in the steady sliding alone,
            # gained 0.2 % beside it). Both are reported confounded and the round is taken back.
            last, alike, before, beaten, leaders = pending
            pending = None
            subsumed = [(o, now) for o in alike for now in evid if now.name == o.name and not now.gains_held_out(s)]
            if subsumed:
                for o, now in subsumed:
                    confounded.append(_confounding(last, o, s, beside_gain=now.heldout_gain))
                # those told apart in its favour (``told_apart``) explained what it did: confounded with it too
                confounded.extend(_confounding(last, o, s) for o in beaten)
                excluded |= {last.name} | {o.name for o, _ in subsumed}
                cur, cur_terms, cur_u, k0 = before.cur, before.cur_terms, before.cur_u, before.k0
                named.pop()
                del steps[before.steps:], scored[before.scored:], fits[before.fits:], rounds[before.rounds:]
                del cmp_.notes[before.notes:]
                # the round is run again from the same model, its confounded pairs out of the running
                # and not found again: a winner there is judged beside their better ones all the same,
                # the winner taken back among them (it leads the pairs found confounded just now)
                carried = tuple(confounded_leaders([], (*leaders, last)))
                continue
        passing = sorted([e for e in evid if e.passes(s)], key=lambda e: -e.heldout_gain)
        cands_out = [e.as_dict(s) for e in sorted(evid, key=lambda e: -e.heldout_gain)]

        def beside(o: Evidence) -> Alternative | None:
            """The alternative ``o`` was judged against with ``o`` added as it was fitted, refitted
            (None for one refitting κ0, a stiffness candidate's)."""
            if o.against is None or o.against.fit_k0:
                return None
            terms = o.against.terms + [_terms_for(o.name, cmp_, strokes, o.params.get("min_excursion"))]
            fr = _fit(engine, terms, o.fit.u, allm, fit_k0=False, k0=o.fit.k0)
            return Alternative(fr, terms, fr.u[1:])

        def told_apart(e: Evidence, o: Evidence) -> str | None:
            """Of two alike candidates (``_corr`` over ``confound_corr``, neither clearly better):
            each judged beside the other as fitted. The one that still passes beside the other,
            where the other no longer gains held out beside it, shows a part of the residual of
            its own ("e" or "o": a load with steps on a rising schedule, which a drift in time
            follows everywhere but at the steps); "both" where each passes beside the other (two
            effects); None otherwise (confounded, as a load that rises as a drift would). Said in
            the notes either way."""
            alt_o, alt_e = beside(o), beside(e)
            if alt_o is None or alt_e is None:
                return None
            say(0.1 + 0.8 * (step + 0.95) / s.max_effects, f"step {step + 1}: {e.name} and {o.name}, each beside the other")
            ev_e, ev_o = judge(e.name, alt_o), judge(o.name, alt_e)
            engine.following_held(None)
            ok = {"e": ev_e is not None and ev_e.passes(s), "o": ev_o is not None and ev_o.passes(s)}
            gains = {"e": ev_e is not None and ev_e.gains_held_out(s), "o": ev_o is not None and ev_o.gains_held_out(s)}
            # (one passing beside the other while the other still gains beside it, but does not
            # pass — not where its physics shows, or not settling — is not told apart either)
            which = ("both" if ok["e"] and ok["o"] else "e" if ok["e"] and not gains["o"]
                     else "o" if ok["o"] and not gains["e"] else None)

            def said(ev: Evidence | None, a: Evidence, b: Evidence) -> str:
                if ev is None or not ev.cross_validated:
                    return f"{a.name} beside {b.name} gains under the bar in-sample"
                return (f"{a.name} beside {b.name} gains {ev.heldout_gain:.1%} held out (folds "
                        f"{ev.folds_improved}/{ev.folds_informative})")
            outcome = {"both": "each shows a part of its own", "e": f"{e.name} shows a part of its own",
                       "o": f"{o.name} shows a part of its own", None: "not told apart: confounded"}[which]
            cmp_.notes.append(f"{e.name} and {o.name} explain much the same part (correlation of their corrections "
                              f"{_corr(e.correction, o.correction):.2f}, held-out gains {e.heldout_gain:.1%} and "
                              f"{o.heldout_gain:.1%}); each fitted beside the other: {said(ev_e, e, o)}, "
                              f"{said(ev_o, o, e)} — {outcome}")
            return which

        def stands_apart(c: Evidence, e: Evidence) -> tuple:
            """``c``, passing this round, judged beside ``e`` as fitted, ``e`` being confounded
            (``choose_winner``): whether it still passes, and its held-out gain there (None
            under the bar in-sample). Said in the notes either way."""
            alt = beside(e)
            if alt is None:
                return True, None  # (``e`` refits κ0: nothing to judge beside; as before)
            say(0.1 + 0.8 * (step + 0.97) / s.max_effects, f"step {step + 1}: {c.name} beside {e.name}")
            ev = judge(c.name, alt)
            engine.following_held(None)
            ok = ev is not None and ev.passes(s)
            gain = ev.heldout_gain if ev is not None and ev.cross_validated else None
            cmp_.notes.append(f"{c.name} passed judged without {e.name}, which is confounded; fitted beside it, "
                              + ("it gains under the bar in-sample" if gain is None else
                                 f"it gains {gain:.1%} held out (folds {ev.folds_improved}/{ev.folds_informative})")
                              + (" and passes: it shows a part of its own" if ok else
                                 " — not named: it stood in for the confounded part"))
            return ok, gain

        notes_before = len(cmp_.notes)  # (a round taken back takes the notes of its telling apart too)
        choice = choose_winner(
            passing, lambda e, o: _corr(e.correction, o.correction) >= s.confound_corr and not _clearly_better(e, o, s),
            told_apart if s.tell_apart else (lambda e, o: None), stands_apart if s.beside_confounded else None,
            carried)
        confounded.extend(_confounding(p.e, p.o, s, p.beside_gain, p.stood_in) for p in choice.confounded)
        winner, beaten, blocked = choice.winner, choice.beaten, choice.blocked
        excluded |= blocked
        if winner is None:
            break
        gap_now = _rms((meas - cur.pred)[allm])
        if gap_now < cmp_.noise:
            # a model that already leaves less than the noise alone would leaves nothing for an
            # effect to explain: what a candidate gains there is the noise's own structure (a
            # haptic joint made apart, its encoder coarser than its presliding, had a ripple named
            # at 0.56 → 0.48 noise floors) — or an effect the noise floor hides, which is said
            cmp_.notes.append(f"{winner.name} passed (held out {winner.heldout_gain:.1%}, folds {winner.folds_improved}/"
                              f"{winner.folds_informative}), but the model before it already leaves {gap_now:.4g} beside "
                              f"the free steady curve, {gap_now / cmp_.noise:.2f} × the noise floor: nothing beyond the "
                              f"noise is left for an effect to explain, so none is named (what it gains is the noise's "
                              f"own structure, or an effect as small as the noise, which this record cannot show)")
            under_noise = {"name": winner.name, "heldout_gain": float(winner.heldout_gain),
                           "folds_improved": int(winner.folds_improved),
                           "folds_informative": int(winner.folds_informative),
                           "gap_over_noise": float(gap_now / cmp_.noise)}
            break
        for c in cands_out:
            c["significant"] = c["name"] == winner.name
        # the passing rivals it did not clearly beat (their corrections unlike its own): looked at
        # again beside it in the next round
        alike = [o for o in passing if o is not winner and o.name not in blocked and not _clearly_better(winner, o, s)]
        pending = (winner, alike, _LoopState(cur, list(cur_terms), cur_u, k0, len(steps), len(scored), len(fits),
                                             len(rounds), notes_before), beaten,
                   tuple(confounded_leaders(choice.confounded, carried))) if alike else None
        carried = ()
        named.append(winner.name)
        # σ of every named effect's parameters from this round's cross-validation, where they were
        # all refitted with the winner; the last round's go into the file written
        cur_terms = winner.against.terms + [_terms_for(winner.name, cmp_, strokes, winner.params.get("min_excursion"))]
        sds = effect_sds(cur_terms, winner.fit.entries, winner.fold_entries, set(named) | refitted_prior)
        decided = {e["name"]: dict(e["params"]) for e in winner.fit.entries}  # the values σ belong to
        rounds.append((sds, decided))
        say(0.1 + 0.8 * (step + 1) / s.max_effects, f"adding {winner.name} and refitting everything together")
        # the model goes on as the one that was cross-validated: an effect judged beside a
        # stiffness varying with speed keeps it (held, not named: on clean recordings it takes up
        # how the transition's dependence on speed differs from eq. (5)), with the κ0 refitted there
        if winner.unsettled:
            cmp_.notes.append(f"{winner.name} is named because settling is not required here (`diagnose "
                              f"--no-require-settling`), but {winner.unsettled}")
        if winner.beside:
            held_now = [t.name for t in winner.against.terms if t.name in HELD_STIFFNESS]
            cmp_.notes.append(f"{winner.name} was judged beside {winner.beside} ({', '.join(held_now)}, held with it "
                              f"in the model written, not named)")
        head = 2 if winner.against.fit_k0 else 1  # log g (and log κ0, refitted with it)
        k0 = winner.fit.k0
        refit = _fit(engine, cur_terms, np.concatenate([[math.log(winner.fit.g)], winner.fit.u[head:]]),
                     allm, fit_k0=False, k0=k0)
        cur = refit
        cur_u = refit.u[1:]
        steps.append({"label": f"+ {winner.name}", "name": winner.name, "params": dict(refit.entries[-1]["params"]),
                      "rms": _rms((meas - refit.model)[allm]), "rms_free": _rms((meas - refit.pred)[allm]),
                      "heldout_gain": winner.heldout_gain, "sd": sds.get(winner.name, {}),
                      "params_decided": dict(winner.fit.entries[-1]["params"]),
                      "folds": f"{winner.folds_improved}/{winner.folds_informative}"})
        if (said := cur_terms[-1].pinned(_entry_to_u(cur_terms[-1], winner.fit.entries[-1]["params"]))):
            cmp_.notes.append(said)  # (of the values σ belong to: ``effect_sds``)
        scored.append(refit.pred)
        fits.append((list(cur_terms), refit.u))
    say(0.95, "refitting the model that is written (without the free steady curve)")
    # the model written is refitted from the model as given, without the free steady curve, its first
    # step from the base refitted as the model alone: the alternative's own n, σ1 and S(v) leaned
    # on that curve (its free inertia, its level at rest)
    written = written_fits(engine, params.replace(effects=()), fits, refit_curve=refit_curve,
                           start=alone.u if len(alone.u) else None)
    # an effect named last that the model written does not use is not named: refitted with n,
    # σ1, S(v) and the curve, those took up what it explained beside the free steady curve (on a
    # clean linear stage a softening's h went from −0.07 in the decision to −0.008 written)
    unused = []
    while named and (own := own_gain(engine, written[-1][0])) < PRESCREEN * s.min_gain:
        gone = named.pop()
        unused.append({"name": gone, "own_gain": own})
        cmp_.notes.append(f"{gone} is not named: in the model written it removes under {PRESCREEN * s.min_gain:.1%} "
                          f"of the gap left with it switched off; the model written is the step before's")
        steps.pop()
        scored.pop()
        written.pop()
        rounds.pop()  # the model written is the step before's: so are its effects' σ
        engine.set_base(written[-1][1])
    # an effect named before others that does next to nothing itself in the model written with them
    # all: a later one took up what it stood in for (a voice-coil stage made apart: a softening named
    # second, beside a ripple, stood in for part of a warm-up named third, and was written at
    # h = −0.009 ± 0.08). It is not named, and the model written is refitted without it
    while len(named) > 1:
        owns = {nm: own_gain(engine, written[-1][0], nm) for nm in named[:-1]}
        gone = min(owns, key=owns.get)
        if owns[gone] >= PRESCREEN * s.min_gain:
            break
        k = named.index(gone)
        later = named[k + 1:]
        named.pop(k)
        unused.append({"name": gone, "own_gain": owns[gone]})
        cmp_.notes.append(f"{gone} is not named: in the model written with {', '.join(later)}, named after it, it "
                          f"removes {max(owns[gone], 0.0):.1%} of the gap left with it switched off, under "
                          f"{PRESCREEN * s.min_gain:.1%}: what it stood in for when it was named, "
                          f"{' and '.join(later)} explain{'s' if len(later) == 1 else ''}; the model written is "
                          f"refitted without it (the steps after it were decided with it in the model)")
        del steps[2 + k], scored[2 + k], rounds[1 + k]
        fits = [f if i < 1 + k else (*without_term(*f, gone),) for i, f in enumerate(fits) if i != 1 + k]
        written = written_fits(engine, params.replace(effects=()), fits, refit_curve=refit_curve,
                               start=alone.u if len(alone.u) else None)
    friction_named = [nm for nm in named if EFFECTS[nm].acts_on == "friction" and "load" not in EFFECTS[nm].needs]
    if friction_named and rec.normal_load is None and load_like:
        # (a gantry made apart, its payload logged in kg and so not read: a drift "rising" fivefold
        # was named for five payload changes, up and down, on a session with no warm-up)
        cmp_.notes.append(f"{' and '.join(friction_named)} named while no normal load is read (columns not read: "
                          f"{', '.join(map(str, load_like))}): friction that follows a load changed during the "
                          f"session is taken up by a friction effect in time or along the travel; if one of those "
                          f"columns is that load, name it (--columns normal_load=<column>), as a force with "
                          f"its unit in the header (N, kN, lbf …; not a mass), and diagnose again")
    sds, decided = rounds[-1]
    if "time_drift" in s.candidates and len(holds) >= 4 and abs(order.rho) < SPEED_ORDER_RHO:
        span = float(cmp_.time[allm][-1] - cmp_.time[allm][0]) if allm.any() else 0.0
        if levels_revisited(holds, span) == 0:
            # (where the levels follow time, the note on the speed order above says more)
            said = (f"no speed level of the steady sliding is visited again later in the session ({len(holds)} "
                    f"holds): beside the free steady curve each level holds a drift's value at its one visit")
            if "time_drift" in named:
                cmp_.notes.append(f"{said}, so the drift was decided on the changes within holds and at the "
                                  f"transitions, and a slow one reads short and small (τ and |b| may be below the "
                                  f"contact's: on a rotary table made apart, τ = 12.9 ± 3.3 s for 44.3). To tell: "
                                  f"visit a speed level again late in the session")
            else:
                # said whatever was named: a drift the schedule hides is not named (a slide made apart,
                # its ten speeds shuffled and each run once, with a warm-up drift of 25 %: nothing named;
                # each run twice: the drift named)
                cmp_.notes.append(f"{said}, so a slow change in time is taken as the shape of S(v) there, and only "
                                  f"what it changes within holds and at the transitions is seen. To tell: visit a "
                                  f"speed level again late in the session")
    (null, *_), (final, final_base, final_reid, reidentified) = written[0], written[-1]
    for st, (wf, *_) in zip(steps[1:], written):
        st["rms"] = _rms((meas - wf.pred)[allm])  # the model alone, beside the memory's constant (and inertia)
        if wf.entries:
            st["params"] = dict(wf.entries[-1]["params"])
            if st["name"] is None:  # the alternative's row: the file's own effect, refitted with it
                st["name"] = wf.entries[-1]["name"]
        if "params_decided" in st:  # a step that named an effect (the alternative's may carry the file's own)
            st["sd"] = with_model_shift(st["sd"], st["params_decided"], st["params"])
        step_preds.append(wf.pred)
    # the alternative's level scales the model's friction beneath the free steady curve, which
    # adds what the steady sliding asks: g is then what presliding and the transitions ask; the
    # model written refits the S(v) levels themselves (its note below): two different factors.
    # "level ×g" read as a change of S(v) by that much, and "all friction ×0.778" as friction
    # 22 % lower, on a guideway made apart whose sliding friction rose by up to 12 %
    steps[1]["label"] = (f"alternative (free steady curve): the model's friction {_factor_said(null.g, LEVEL_RANGE)} "
                         f"beneath the curve, presliding stiffness {_factor_said(null.k0, STIFFNESS_RANGE)}")
    cmp_.notes.append(f"the alternative's factor ×{null.g:.3f} scales the model's friction beneath the free steady "
                      f"curve, which sets the steady sliding from the data: it is what presliding and the transitions "
                      f"ask, not a change of S(v) (the model written refits a level of its own: its note)")
    if final_reid is not None:
        cmp_.notes.append(f"S(v) identified anew for the model written from the steady sliding ({final_reid.levels} speed "
                          f"levels, the level and the friction effects divided out; the Markov estimator, holding what "
                          f"they do not determine): the gap there is {final_reid.gap_new:.3g} against "
                          f"{final_reid.gap_file:.3g} with the file's S(v) at its best level per side (the levels' "
                          f"noise {final_reid.noise:.3g}) — "
                          + ("the model written refitted from it and from the file's, and from it left less: kept"
                             if reidentified else
                             "the model written refitted from it and from the file's, and from the file's left less: "
                             "the file's kept" if final_reid.used else
                             # (2 levels: both curves pass through them, "0 against 4.7e-18" read as a verdict)
                             "both within the levels' noise, nothing to tell them apart: the file's kept"
                             if max(final_reid.gap_new, final_reid.gap_file) <= final_reid.noise else
                             "worse: the file's kept" if final_reid.gap_new >= final_reid.gap_file else
                             f"not clearly better (under {STEADY_MIN_GAIN:.0%} less, or the file's within "
                             f"{STEADY_MISFIT:g} noise sds): the file's kept")
                          # "kept" is the shape the refit of the model written starts from, not the
                          # values it writes: that refit moves the levels (the next note; a guide made
                          # apart read "the file's kept" and then found σ2 60.0 written as 56.9)
                          + ("" if reidentified else " as the start of the model written, whose refit (below) moves "
                             "its levels"))
    # σ1's refit bound is on it before the level g is baked in: the value said and written is g × that
    at_level = f" before the level ×{final.g:.4g}" if abs(final.g - 1.0) > 5e-4 else ""
    if params.model == "leuven":
        # the values as written: the common level g is baked into the forces and σ1 (``bake``)
        levels = [final.g * getattr(getattr(final_base.stribeck, sd), k) / getattr(getattr(params.stribeck, sd), k)
                  for sd in ("positive", "negative") for k in ("Fs", "Fc")]
        # σ1 refits within a factor SIGMA1_REFIT_MAX of the file's (``refit_transition``): at that bound the
        # record wants it further, and the value written is a bound, not an estimate
        s1_ends = (params.sigma1 / SIGMA1_REFIT_MAX, params.sigma1 * SIGMA1_REFIT_MAX)
        s1_bound = (f" (at its bound, a factor {SIGMA1_REFIT_MAX:g} from the file's{at_level}: the record pushes it "
                    f"further)"
                    if _at_range_end(final_base.sigma1, s1_ends) else "")
        # n at an end of its refit range: the record asks for a shape beyond it, say which way
        n_bound = (f" (at the end of its range {N_REFIT[0]:g}–{N_REFIT[1]:g}: the record pushes it further, "
                   + (f"its transitions run into sliding more gradually than eq. (5) does at n = {N_REFIT[0]:g}"
                      if final_base.n < math.sqrt(N_REFIT[0] * N_REFIT[1]) else
                      f"its transitions end in sliding more abruptly than eq. (5) does at n = {N_REFIT[1]:g}, a corner")
                   + ": the contact's shape, not the data's noise)"
                   if _at_range_end(final_base.n, N_REFIT) else "")
        cmp_.notes.append(f"the model written (every step; no free steady curve) refits, besides the level "
                          f"(×{final.g:.4g}, in the values that follow), the stiffness and the effects: "
                          f"n {params.n:.3g} → {final_base.n:.3g}{n_bound}, "
                          f"σ1 {params.sigma1:.3g} → {final.g * final_base.sigma1:.3g}"
                          f"{s1_bound}, "
                          f"the S(v) levels ×{min(levels):.3f} … ×{max(levels):.3f}"
                          + (", the transition curve's segments" if refit_curve else "")
                          + ("" if named or s.refit_base else " (nothing named: the parameter file is left as it was)"))
    if cmp_.inertia is not None:
        # the gaps of the model alone (as given, and written) leave eq. (8)'s I free beside it, so
        # that an inertia off in the file is not a friction misfit; it is not written: on a
        # servo-driven stage a misfit of the model that follows the acceleration enters it as well
        d_i = model_nuisance(meas - final.model, allm, cmp_.memory_offset, cmp_.acceleration).d_inertia
        cmp_.notes.extend(inertia_beside_notes(cmp_.inertia, d_i, float(np.std(cmp_.acceleration[allm])), cmp_.noise))
    regimes = {}
    # what the file written predicts: nothing named, it is the model as given (the base refitted
    # alone is a step of the report, not the file: the diagnosis adds effects, `fit` makes bases)
    rebased = not named and s.refit_base
    after = final.pred if (named or rebased) else pred_given_c
    rms_alt = _rms((meas - null.pred)[allm])
    base_off = bool(not named and rms_alt < (1.0 - CURVE_MIN_GAIN) * rms0 and rms0 > BASE_OFF_NOISE * cmp_.noise)
    if base_off:
        # (a model within two noise floors is at the noise level, whatever a refit gains there)
        # by the file's name (a fit given the path from elsewhere made the same file), the
        # diagnosis's own record first
        prov0 = params.provenance or {}
        name = os.path.basename(rec.source)
        made_by = next((what for what, key in (("diagnosis", "diagnosed"), ("fit", "data"))
                        if name in {os.path.basename(str(d)) for d in prov0.get(key, [])}), None)
        fitted_here = made_by is not None
        cmp_.notes.append(f"nothing named, so the model written is the one given, which leaves {rms0:.4g}; the "
                          f"base refitted alone (the alternative) leaves {rms_alt:.4g} — "
                          + base_off_verdict(rms_alt, cmp_.noise, s.candidates,
                                             seen=seen_unnamed(confounded, unused, cands_out, s)) + ": "
                          + (f"the {made_by} of {name} that made the file holds or misses what the refit moves "
                             f"(see its held parameters, and the refit's values above)" if fitted_here else
                             "fit it to this recording (`leuven-friction fit`) or give --params closer to it")
                          + ("; the base refitted alone as the model written is what is written (--refit-base)"
                             if rebased else f"; `diagnose --refit-base --out` writes the base refitted alone as the "
                             f"model written (it leaves {_rms((meas - final.pred)[allm]):.4g})")
                          # κ0 scales z in F_d(κ0·z): far from 1, the file's curve is not the record's
                          + (f"; the alternative's presliding stiffness is ×{null.k0:.3g} the file's (F_d(κ0·z)): the "
                             f"whole record's transitions are far from the file's transition curve"
                             if not 0.5 <= null.k0 <= 2.0 else ""))
    for k, m in regimes_m.items():
        m = m & allm
        if m.any():
            regimes[k] = {"n": int(m.sum()), "rms_before": _rms((meas - pred_given_c)[m]),
                          "rms_base_refit": _rms((meas - null.pred)[m]), "rms_after": _rms((meas - after)[m]),
                          "noise": cmp_.noise_on(m)}
    new_params = params  # nothing named: the model stays as it was (unless ``refit_base``)
    if named or rebased:
        # S(v) and the transition curve are rescaled: their old uncertainties no longer apply
        unc = {k: v for k, v in params.uncertainty.items()
               if not (k.startswith("stribeck.") or k.startswith("transition_curve") or k in ("n", "sigma1")
                       or k.startswith("effects."))}
        # the σ of the named effects and of the file's own (``effect_sds``, from the last round);
        # a held entry (rate_stiffness) and the fixed parameters (a reference, a start, a
        # threshold) get none: they were not estimated
        written_sd = [with_model_shift(sds.get(e["name"], {}), decided.get(e["name"], {}), e["params"])
                      for e in final.entries]
        # a shape whose amplitude the data do not tell from none (a second harmonic's phase) is
        # not an estimate: no σ, and provenance.held says why
        loose = {f"effects.{i}.params.{k}": f"not determined: {why}; the value is where the fit left it"
                 for i, (e, sd) in enumerate(zip(final.entries, written_sd))
                 for k, why in EFFECTS[e["name"]].undetermined(e["params"], sd).items()}
        unc.update({f"effects.{i}.params.{k}": v for i, sd in enumerate(written_sd) for k, v in sd.items()
                    if math.isfinite(v) and f"effects.{i}.params.{k}" not in loose})
        for e, sd in zip(final.entries, written_sd):
            weak = size_not_shown(e["name"], e["params"], sd) if e["name"] in named else None
            if weak:
                # named on held-out evidence, which is of the change's presence, not of its size (a
                # stage's warm-up that came and went, fitted as one approach: b −0.25 ± 0.14)
                cmp_.notes.append(f"{e['name']} is named on its held-out evidence, but in the model written (n, σ1 and "
                                  f"S(v) refitted with it) its size is not told from none ({weak}; σ from the spread "
                                  f"over the folds): a change is seen, its size is not pinned down")
        prov = dict(params.provenance)
        # (the bounds a diagnosis says, below, are said again by this one or not at all)
        held_before = {k: v for k, v in (prov.get("held") or {}).items()
                       if not k.startswith("effects.") and not any(m in str(v) for m in DIAGNOSIS_BOUNDS)}
        prov.pop("held", None)  # (an older file's entries of its effects go: their indices are the old file's)
        if held_before or loose:
            prov["held"] = {**held_before, **loose}
        # the recordings diagnosed, beside the fit's ``data``: a later diagnosis's advice names which made the file
        prov["diagnosed"] = [*[d for d in prov.get("diagnosed", []) if d != rec.source], rec.source]
        written_params = bake(final_base.replace(effects=()), final.g, final.k0)
        moved = moved_from_held(held_before, params, written_params, final.g, refit_curve)
        if moved:
            # no longer held at the value the fit's provenance gives (F_s "held at F_c", n "fixed
            # at 7"): the entry goes, and provenance.diagnosis says where the refit took it
            prov["held"] = {k: v for k, v in prov["held"].items() if k not in moved}
        if reidentified:
            # a side of S(v) identified anew holds what its steady levels do not determine, not what the file's did
            prov["held"] = {**{k: v for k, v in (prov.get("held") or {}).items()
                               if not any(k.startswith(f"stribeck.{sd}.") for sd in final_reid.sides)},
                            **final_reid.held}
        # n and σ1 where the refit left them at an end of its range: a bound the record pushed them
        # to, not an estimate (no σ is written for either)
        ends = ({"n": (final_base.n, N_REFIT, f"{N_REFIT[0]:g}–{N_REFIT[1]:g}"),
                 "sigma1": (final_base.sigma1, s1_ends, f"a factor {SIGMA1_REFIT_MAX:g} either way from the file's{at_level}")}
                if params.model == "leuven" else {})
        at_end = {k: (f"at the end of the diagnosis's refit range ({said}): the record pushes it further (the "
                      f"contact's shape, not the data's noise), so the value written is a bound, not an estimate")
                  for k, (v, rng, said) in ends.items() if _at_range_end(v, rng)}
        unresolved = unresolved_curve(written_params, cmp_.reading.compared, final.k0, cmp_.position_unit)
        if unresolved:
            at_end["transition_curve"] = unresolved
            cmp_.notes.append(f"the model written's transition curve: {unresolved}")
        if at_end:
            prov["held"] = {**(prov.get("held") or {}), **at_end}
        held = [e["name"] for e in final.entries if e["name"] not in named]
        prov["diagnosis"] = ((f"{', '.join(named)} added (blocked cross-validation)" if named else
                              "nothing named; the base refitted alone (--refit-base)")
                             + (f", {', '.join(held)} held with them" if held else "") + f"; level ×{final.g:.4g}, "
                             f"presliding stiffness ×{final.k0:.4g}, n {params.n:.3g} → {final_base.n:.3g}, "
                             f"σ1 {params.sigma1:.3g} → {written_params.sigma1:.3g}, "
                             + (f"S(v) identified anew from the steady sliding ({', '.join(final_reid.sides)}), then "
                                if reidentified else "")
                             + "the S(v) levels"
                             + (", the transition curve's segments" if refit_curve else "")
                             + f" refitted by output error in {cmp_.space}"
                             + (f"; moved from held: {', '.join(f'{k} {a} → {b}' for k, (a, b) in moved.items())}"
                                if moved else "")
                             # a user found the file's σ gone and nothing saying why
                             + "; no σ is written for S(v), the transition curve, n or σ1: the fit's were of "
                               "the values before this refit, and no new ones are computed")
        new_params = written_params.replace(
            effects=tuple(_clean_entry(e, cmp_) for e in final.entries), uncertainty=unc, provenance=prov)
    # the reversals as the softening named counts them (its own back-travel), else the comparison's
    th = next((e["params"]["min_excursion"] for e in final.entries if e["name"] == "cyclic_softening"), cmp_.min_excursion)
    pu = cmp_.position_unit or ""
    explaining = {"time": ("time (s)", cmp_.time), "position": (f"position ({pu})" if pu else "position", cmp_.path),
                  "velocity": (f"velocity ({pu}/s)" if pu else "velocity", cmp_.velocity),
                  "reversals": ("significant reversals", significant_reversals(cmp_.path, th))}
    if cmp_.load is not None:
        lu = rec.units.get("normal_load", "")
        explaining["load"] = (f"normal load ({lu})" if lu else "normal load", cmp_.load)
    say(1.0, "done")
    return Diagnosis(effects=named, steps=steps, confounded=confounded, candidates=cands_out, rms_before=rms0,
                     rms_after=_rms((meas - after)[allm]), rms_base_refit=rms_alt, regimes=regimes,
                     space=cmp_.space, noise=cmp_.noise, notes=cmp_.notes, params_before=params,
                     params_after=new_params, settings=s, time=cmp_.time, measured=meas, model_before=pred_given_c,
                     model_after=after, compared=allm, step_predictions=step_preds, scored_predictions=scored, explaining=explaining,
                     unused=unused, work=DiagnosisWork(perf_counter() - started, engine.sims, engine.sim_seconds),
                     reading={"window": int(cmp_.window), "v_rest": float(cmp_.v_rest),
                              "min_excursion": float(cmp_.min_excursion)}, base_off=base_off,
                     travel_force=tf, travel_spring=ts,
                     load_unit=rec.units.get("normal_load") if rec.normal_load is not None else None,
                     under_noise=under_noise)


WRITTEN_NFEV = 20  # least-squares iterations per step of the model written
STEADY_MIN_GAIN = 0.25  # S(v) re-identified for the model written only if it leaves this much less steady gap
STEADY_MISFIT = 2.0  # … and the file's leaves more than this many times the levels' noise


@dataclass(frozen=True)
class SteadyReidentification:
    """S(v) identified anew for the model written from the recording's steady sliding
    (``steady_stribeck``), with both gaps there: the file's S(v) (each side at its best level) and
    the new one."""

    stribeck: Stribeck
    gap_file: float
    gap_new: float
    levels: int
    noise: float  # sd of a level's mean (pooled): what the gaps there cannot go below
    sides: tuple = ()  # the sides identified anew ("positive", "negative")
    held: dict = field(default_factory=dict)  # {"stribeck.<side>.<name>": why the levels do not determine it}

    @property
    def used(self) -> bool:
        """The file's S(v) misfits the steady levels beyond their noise, and the new one
        clearly less: a file that fits stays as it is (a gain in the noise is no reason)."""
        return self.gap_file > STEADY_MISFIT * self.noise and self.gap_new < (1.0 - STEADY_MIN_GAIN) * self.gap_file


def steady_stribeck(params: FrictionParams, cmp_: Comparison, factor: np.ndarray, mask: np.ndarray) -> SteadyReidentification | None:
    """The Markov estimator (``fit_side_honest``: what the levels do not determine is held) run
    on the compared friction divided by ``factor`` (the level g times the step's friction
    effects) over the steady sliding in ``mask``: in gross sliding at a steady velocity the
    friction is S(v) + σ2·v times those factors, whatever the transition curve. A fit whose
    Markov levels averaged over a load or a temperature (F_s held at F_c, σ2 held at 0) leaves
    the model written several noise floors in sliding that no refit of the levels within a factor
    1.5 can take up. None where no side has levels."""
    from .markov import NAMES, fit_side_honest, fit_sides_honest

    if params.model != "leuven" or cmp_.space != "friction":
        return None
    y = cmp_.measured / np.where(factor != 0, factor, 1.0)
    levels = speed_levels(cmp_.velocity, y, mask, max(cmp_.window, cmp_.average))
    if len(levels.velocity) == 0:
        return None
    sides, gap_file, gap_new, anew, held = [], 0.0, 0.0, [], {}
    both = {"positive": params.stribeck.positive, "negative": params.stribeck.negative}
    try:
        decisions = fit_sides_honest(levels)  # (a side short of levels takes δ from the other)
    except IdentificationError:
        decisions = {}
    for name, sign in (("positive", 1), ("negative", -1)):
        old = getattr(params.stribeck, name)
        m = levels.velocity * sign > 0
        try:
            dec = (decisions.get(name) or fit_side_honest(levels, sign)) if m.any() else None
        except IdentificationError:
            dec = None
        if dec is None or dec.fit is None:
            sides.append(old)
            continue
        v, F, w = levels.velocity[m], levels.friction[m], levels.count[m]
        new = StribeckSide(**{k: float(dec.fit.values[k]) for k in NAMES})
        s_old, s_new = (stribeck_curve(params.replace(stribeck=Stribeck(**{**both, name: sd})), v) for sd in (old, new))
        c = float(np.sum(w * F * s_old) / max(np.sum(w * s_old * s_old), 1e-300))  # the file's side at its best level
        gap_file += float(np.sum(w * (F - c * s_old) ** 2))
        gap_new += float(np.sum(w * (F - s_new) ** 2))
        sides.append(new)
        anew.append(name)
        held.update({f"stribeck.{name}.{k}": f"{why} (the diagnosis's steady sliding)" for k, why in dec.held.items()})
    total = float(np.sum(levels.count))
    noise = math.sqrt(float(np.sum(levels.count * levels.variance)) / total)
    return SteadyReidentification(Stribeck(*sides), math.sqrt(gap_file / total), math.sqrt(gap_new / total),
                                  len(levels.velocity), noise, tuple(anew), held)


def written_fits(engine: Engine, base: FrictionParams, fits: list, refit_curve: bool = False,
                 start: np.ndarray | None = None) -> list:
    """The model that goes into the parameter file at every step, refitted to the recording
    alone (the free steady curve of the alternative helps decide, it is not part of the
    model): from ``base``, n, σ1, the S(v) levels (with ``refit_curve``, the curve's segments),
    the level g, stiffness κ0 and that step's effects (``refit_transition``). Every step is
    refitted in full, so each gap is the best the model does with those effects and the gain of
    a step is not held down by a base tuned without its effect. A step starts where the one
    before ended, its new effect where the decision's fit left it; the first from ``start`` (a
    whole solution vector: the same base and the file's own effects refitted as the model
    alone, before the alternative's free curve was added — its stiffness and curve segments were
    fitted together). The gaps are of friction taken from an applied force with the inertia
    refitted beside the model (``model_nuisance``; not written). Each step is refitted from the
    file's S(v) and, where the file's misfits the steady sliding (``SteadyReidentification.used``),
    also from S(v) identified there anew (``steady_stribeck``) and from where the step before
    ended if that was from such an S(v); the smallest gap is kept. Returns (FitResult, refitted
    base, the step's re-identification or None, whether the kept refit started from a new
    S(v)) per step."""
    engine.free = None
    engine.free_inertia = True
    mask = engine.scored
    if base.model != "leuven":
        # n, σ1 and the S(v) levels refitted are the Leuven model's: the level, stiffness and effects only
        engine.set_base(base)
        return [(_fit(engine, terms, np.concatenate([[u[0], 0.0], u[1:]]), mask, fit_k0=True, k0=1.0), base, None, False)
                for terms, u in fits]
    out, prev = [], None
    nb = refit_length(base, refit_curve)
    steady = steady_sliding(engine.c) & mask
    chosen = None  # the base and solution the step before kept
    for terms, u in fits:
        # u: log g, then the terms' parameters (the decision's fit)
        if prev is None and start is not None:
            u_start = np.array(start, float)  # the first step's terms are the file's own, as ``start``'s
        else:
            u_start = np.concatenate([np.r_[u[0], np.zeros(nb - 1)] if prev is None else prev[:nb], u[1:]])
        # S(v) identified anew from the steady sliding, the step's friction effects and level divided
        # out (so it stays at the file's scale, where g and the curve are), where it fits there clearly
        # better than the file's with each side at its best level
        fs = effect_scales(_entries(terms, u[1:]), engine.ctx)[0]
        reid = steady_stribeck(base, engine.c, math.exp(u[0]) * (1.0 if fs is None else fs), steady)
        # refitted from the file's S(v) and, where it is used, from the new one; the better kept: an
        # effect the decision fitted beside the free curve (a drift a speed-ordered sweep shares with
        # S(v)) is only part of it, and S(v) from the steady sliding divided by that part can start
        # the refit in a worse basin than the file's (robot joint 1009: 0.255 against 0.145)
        starts = [(base, u_start)]
        if reid is not None and reid.used:
            us = u_start.copy()
            us[0] = u[0]  # the level and the S(v) factors were relative to the file's S(v)
            us[4:REFIT_BASE_U] = 0.0
            starts.append((base.replace(stribeck=reid.stribeck), us))
        if chosen is not None and chosen[0] is not base:
            # and from where the step before ended, where that was from a new S(v): the new effect's
            # start (the decision's, beside the free curve) can lead the other two off (linear stage
            # 1014, a drift after the load: 2.06 from either, the step before 0.66)
            starts.append((chosen[0], np.concatenate([chosen[1][:nb], u[1:]])))
        best = None
        for b, us in starts:
            # a refit of a model the decision has already fitted: fewer steps than the alternative's
            r = refit_transition(engine, b, terms, u[1:], mask, start=us, max_nfev=WRITTEN_NFEV, refit_curve=refit_curve)
            fr = fit_result(engine, r.g, r.k0, r.entries, r.u, mask)
            if b is base:
                prev = r.u  # the next step starts from the file's S(v) refitted, as well
            if best is None or fr.rss < best[0].rss:
                best = (fr, r, b)
        fr, r, b = best
        chosen = (b, r.u)
        engine.set_base(r.params)
        out.append((fr, r.params, reid, b is not base))
    return out


def _clean_entry(e: dict, cmp_: Comparison) -> dict:
    return {"name": e["name"], "params": {k: float(v) for k, v in e["params"].items()}}


def _corr(a: np.ndarray, b: np.ndarray) -> float:
    a = a - a.mean()
    b = b - b.mean()
    d = math.sqrt(float(np.dot(a, a)) * float(np.dot(b, b)))
    return float(abs(np.dot(a, b)) / d) if d > 0 else 0.0


class _LoopState(NamedTuple):
    """The decision loop's state before a winner is named, to take the naming back: the model
    it goes on from, and the lengths of the lists a naming extends."""

    cur: "FitResult"
    cur_terms: list
    cur_u: np.ndarray
    k0: float
    steps: int
    scored: int
    fits: int
    rounds: int
    notes: int


def _clearly_better(e: "Evidence", o: "Evidence", s: Settings) -> bool:
    """Whether ``e`` predicts clearly better held out than ``o``: by ``clear_margin`` of its gain,
    and in most folds."""
    return bool(e.heldout_gain - o.heldout_gain >= s.clear_margin * e.heldout_gain
                and int(np.sum(e.heldout_sse < o.heldout_sse)) > len(e.heldout_sse) / 2)


class Pair(NamedTuple):
    """Two candidates reported confounded (``choose_winner``): ``e`` the better held out; where
    ``o`` stood in for ``e``'s part (``stood_in``), what ``o`` gains held out beside ``e``."""

    e: "Evidence"
    o: "Evidence"
    stood_in: bool = False
    beside_gain: float | None = None


class Choice(NamedTuple):
    """One round's decision among the passing candidates (``choose_winner``)."""

    winner: "Evidence | None"
    beaten: list  # the winner's alike rivals told apart in its favour: gain nothing beside it
    blocked: set  # names out of the running from this round on (confounded, or beaten)
    confounded: list  # ``Pair``s reported confounded, in the order found


def choose_winner(passing: list, alike, told_apart, stands_apart=None, confounded_before: tuple = ()) -> Choice:
    """The round's winner among ``passing`` (best held out first): the first not blocked that has
    no alike rival left. ``alike(e, o)``: their corrections alike and ``e`` not clearly better;
    ``told_apart(e, o)``: "e" (``o`` gains nothing beside ``e``: beaten, out with ``e`` named),
    "o" (``e`` gains nothing beside ``o``: ``e`` out, ``o`` looked at in its turn), "both" (each
    shows a part of its own: ``e`` may win, ``o`` is looked at again next round) or None (the two
    are confounded: ``e``, its alike rivals and those it beat are all out, reported in pairs).

    A candidate that would win after a pair was found confounded this round was judged without
    the pair's part of the residual, which neither of them took: ``stands_apart(c, e)`` judges it
    beside the pair's better ``e`` and returns (passes, held-out gain or None). One that does not
    pass there stood in for that part (a ball screw's load ramp, confounded with a drift, left a
    ripple of 41 rad, a trend along the travel, to pass) and is reported confounded with
    ``e``; one that passes wins. ``confounded_before``: the better ones of the pairs confounded
    when this round was run before, from the same model, and then taken back (out of the running
    now, and not found again): a winner is judged beside them too."""
    blocked: set = set()
    pairs: list = []
    for e in passing:
        if e.name in blocked:
            continue
        rivals, beaten = [], []
        for o in passing:
            if o is e or o.name in blocked or not alike(e, o):
                continue
            which = told_apart(e, o)
            if which == "e":
                beaten.append(o)
            elif which == "o":
                rivals = None
                blocked.add(e.name)
                break
            elif which is None:
                rivals.append(o)
        if rivals is None:
            continue
        if rivals:
            pairs.extend(Pair(e, o) for o in rivals + beaten)
            blocked |= {o.name for o in rivals + beaten} | {e.name}
            continue
        if stands_apart is not None:
            leaders = confounded_leaders(pairs, confounded_before)
            judged = [(lead, stands_apart(e, lead)) for lead in leaders]
            failed = [(lead, gain) for lead, (ok, gain) in judged if not ok]
            if failed:
                # (those it beat were out only with it named: each is looked at in its own turn)
                pairs.extend(Pair(lead, e, True, gain) for lead, gain in failed)
                blocked.add(e.name)
                continue
        return Choice(e, beaten, blocked | {o.name for o in beaten}, pairs)
    return Choice(None, [], blocked, pairs)


def confounded_leaders(pairs: list, before: tuple = ()) -> list:
    """The better ones of the confounded ``pairs`` that did not stand in (``Pair``), after those
    of ``before``, each once (evidence compares by identity, not by value)."""
    leaders: list = []
    for lead in [*before, *(p.e for p in pairs if not p.stood_in)]:
        if all(lead is not other for other in leaders):
            leaders.append(lead)
    return leaders


def _confounding(e: "Evidence", o: "Evidence", s: Settings, beside_gain: float | None = None,
                 stood_in: bool = False) -> dict:
    """The report of two candidates confounded: their corrections alike (``correlation``), or
    ``o`` gaining only ``beside_gain`` held out once ``e`` is in the model (None: under the bar
    in-sample); ``stood_in``: ``o`` passed judged without ``e``'s part, which nothing took."""
    return {"effects": [e.name, o.name], "correlation": _corr(e.correction, o.correction),
            "gains": [e.heldout_gain, o.heldout_gain], "beside_gain": beside_gain, "stood_in": stood_in,
            "evidence": {e.name: e.as_dict(s), o.name: o.as_dict(s)}, "experiment": separating_experiment(e.name, o.name)}


def confounding_reason(c: dict) -> str:
    """Why a pair is reported confounded, in words (the report and its HTML)."""
    a, b = c["effects"]
    if c.get("stood_in"):
        beside = ("under the bar in-sample" if c.get("beside_gain") is None
                  else f"{100 * c['beside_gain']:.1f} % held out, not enough")
        return (f"{b} passed ({100 * c['gains'][1]:.1f} % held out) judged without {a} ({100 * c['gains'][0]:.1f} %), "
                f"itself confounded, whose part nothing took; beside {a} it gains {beside}")
    if c.get("beside_gain") is not None:
        return (f"neither gains clearly more held out ({100 * c['gains'][0]:.1f} % vs {100 * c['gains'][1]:.1f} %), "
                f"and beside {a}, {b} gains {100 * c['beside_gain']:.1f} %")
    return (f"correlation of their corrections {c['correlation']:.2f}; held-out gain {100 * c['gains'][0]:.1f} % vs "
            f"{100 * c['gains'][1]:.1f} %")


def separating_experiment(a: str, b: str) -> str:
    ea, eb = EFFECTS[a], EFFECTS[b]
    return f"for {a}: {ea.separated_by}; for {b}: {eb.separated_by}"


@dataclass(frozen=True)
class FrictionCompared:
    """A recording's friction beside a model's, as the diagnosis compares them."""

    time: np.ndarray
    measured: np.ndarray
    model: np.ndarray
    left_out: tuple = ()  # the set's effects the recording cannot drive (``drivable``), not predicted

    @property
    def rms(self) -> float:
        return _rms(self.measured - self.model)


def drivable(params: FrictionParams, has_load: bool) -> tuple[FrictionParams, tuple]:
    """``params`` without the effects that need a normal load where the recording has none, and
    their names: a set a load recording's diagnosis extended, shown beside a recording without a
    load, is drawn without that effect (and says so) rather than not at all."""
    if has_load:
        return params, ()
    out = tuple(e["name"] for e in params.effects if e["name"] in EFFECTS and "load" in EFFECTS[e["name"]].needs)
    if not out:
        return params, ()
    return params.replace(effects=tuple(e for e in params.effects if e["name"] not in out)), out


@dataclass
class GapAsGiven:
    """How far a parameter set leaves a recording's friction, as a diagnosis compares the model
    as given (``gap_as_given``): the RMS over the samples it scores, against its noise floor and
    per regime."""

    total: float
    noise: float
    regimes: dict  # regime name: RMS there
    start: float  # the time scoring starts (``Comparison.scored``)
    unit: str = ""

    def said(self) -> str:
        """In words, as ``fit`` reports it."""
        u = self.unit
        # each regime against the floor too: a short regime far off hides in the total (a
        # gimbal made apart read 2.0 × the floor overall, its 345 presliding samples 19 ×)
        parts = [f"{k} {v:.3g}" + (f" ({v / self.noise:.1f} ×)" if self.noise > 0 else "")
                 for k, v in self.regimes.items()]
        return (f"RMS {self.total:.3g} {u}" + (f" ({self.total / self.noise:.1f} × the noise floor {self.noise:.3g} {u})"
                                              if self.noise > 0 else "")
                + f"; per regime ({u}{', × the floor' if self.noise > 0 else ''}): {', '.join(parts)} "
                  f"(from {self.start:.4g} s on)")


def gap_as_given(rec: Recording, params: FrictionParams) -> GapAsGiven:
    """How far ``params`` leaves the recording's friction, compared as a diagnosis compares the
    model as given (``scored_comparison``, ``friction_compared``, beside ``model_nuisance``):
    what a fit says of itself in friction, whatever its own cost was (a feed axis made apart was
    refined to 0.4 µm of position while its presliding friction stood 9 N off, which only
    `diagnose` then said), and the gap the explorer's proposals state (there the RMS over every
    sample, the start whose memory the log does not show included, had read 0.018 N·m for a
    spindle's fit that `fit` and `diagnose` put at 0.0023)."""
    cmp_ = scored_comparison(rec, params, Settings())
    m = cmp_.scored
    r = cmp_.measured - friction_compared(rec, params, cmp_).model
    r = r - model_nuisance(r, m, cmp_.memory_offset, cmp_.acceleration).correction
    regimes = {k: _rms(r[w & m]) for k, w in regime_masks(cmp_).items() if k != "all" and (w & m).any()}
    return GapAsGiven(_rms(r[m]), float(cmp_.noise), regimes, float(cmp_.time[np.argmax(m)]),
                      params.units.get("force", ""))


def gap_by_regime(rec: Recording, params: FrictionParams) -> str:
    """``gap_as_given`` in words."""
    return gap_as_given(rec, params).said()


def friction_compared(rec: Recording, params: FrictionParams, cmp_: Comparison | None = None) -> FrictionCompared:
    """The recording's friction and the one ``params`` (its effects included) predicts, compared
    as the diagnosis compares them (``comparison_of``, or ``cmp_`` made by it for this
    recording): friction taken from an applied force by eq. (8) averaged over the comparison's
    window, never from a twice differentiated position, and the model driven along the smoothed
    path and averaged the same way. The explorer's proposals state this gap and plot these two
    (from I·ẍ differenced twice, a slide's clean fit had shown 33 N, the noise of I·ẍ alone 31 N,
    where the diagnosis read 8.8 N)."""
    from ..model.effects import predict

    cmp_ = cmp_ or comparison_of(rec, params, "friction")
    params, left_out = drivable(params, cmp_.load is not None)
    model = predict(params, "displacement", Signals(time=cmp_.time, position=cmp_.path, load=cmp_.load)).friction_force
    return FrictionCompared(cmp_.time, cmp_.measured, cmp_.filtered(model), left_out)
