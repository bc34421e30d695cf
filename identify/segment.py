"""Cutting a recording into the pieces the estimators need, with thresholds taken from the data.

No absolute constants: every threshold is derived from the recording itself (sample rate,
noise floors of position, velocity and force estimated from the data, the velocity levels
present) and collected in a :class:`Thresholds` record that the fit report prints and the
user can override by name (``fit --threshold v_floor=1e-4``).

* :func:`prepare` — velocity from position (Savitzky–Golay slope, window chosen from the
  position noise and the slowest motion), the better of that and a recorded velocity column,
  the friction sign (action or reaction), the normal-load plateau;
* :func:`constant_velocity_levels` → ``markov.Levels``;
* :func:`force_branches` — presliding from applied-force ramps between turning points;
* :func:`motion_branches` — presliding from a reversed prescribed motion with measured friction:
  each crossing from one sliding level to the other (:func:`crossings`, ended by
  :func:`crossing_end`) is a sample of the transition curve;
* :func:`sliding_levels` — levels of S(v) from steady gross sliding binned by speed
  (:func:`speed_levels`, shared with the diagnosis), for a recording with no speed sweep.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields

import numpy as np
from numba import njit
from scipy.signal import savgol_filter

from .data import Recording
from .errors import DataError, IdentificationError
from .markov import STRIBECK_MIN_SPEEDS, Levels, distinct_speeds
from .mle import Branch, Gaussian, Quantized


def robust_sd(a) -> float:
    """Standard deviation from the median absolute deviation (outliers, steps ignored)."""
    a = np.asarray(a, dtype=float)
    if len(a) == 0:
        return 0.0
    return float(1.4826 * np.median(np.abs(a - np.median(a))))


def white_noise_sd(a) -> float:
    """σ of white noise on a slow signal: second differences have variance 6σ²."""
    a = np.asarray(a, dtype=float)
    return robust_sd(np.diff(a, 2)) / np.sqrt(6.0) if len(a) > 3 else 0.0


def detect_noise(x) -> object:
    """Encoder-like (values on a grid of one step) → ``Quantized``; else ``Gaussian``."""
    parts = [np.asarray(a, dtype=float) for a in (x if isinstance(x, (list, tuple)) else [x])]
    x = np.concatenate(parts)
    d = np.abs(np.concatenate([np.diff(a) for a in parts]))
    scale = np.max(np.abs(x)) if len(x) else 1.0
    white = float(np.sqrt(np.mean([white_noise_sd(a) ** 2 for a in parts if len(a) > 3]))) if parts else 0.0
    d = d[d > 1e-9 * scale]
    if len(d):
        # the grid step: the smallest step, or the smallest difference between distinct small
        # steps (a fast motion may never show a single step: 3, 4, 5 steps → step 1)
        q = float(np.quantile(d, 0.01)) if len(d) > 100 else float(np.min(d))
        u = np.unique(np.round(d[d <= 20 * q] / (1e-6 * q)) * (1e-6 * q))
        du = np.diff(u)
        du = du[du > 0.05 * q]
        if len(du) and np.min(du) < 0.9 * q:
            q = float(np.min(du))
        # on a grid when the steps between readings are whole multiples of the smallest step
        # (tested on the steps, not the readings: a file's rounding of large readings must
        # not hide the grid); the step is the mean single step, and the test is on steps of up
        # to GRID_TEST_STEPS of it: the smallest step carries the file's rounding, which a
        # fast motion's hundreds of steps multiply (a 26-bit encoder written in degrees to 9
        # decimals: 5.364·10⁻⁶ deg read 8·10⁻⁵ short, 746 steps a sample off the grid by 0.06,
        # and the position taken for one without noise)
        single = d[np.round(d / q) == 1]
        q = float(np.mean(single)) if len(single) else q
        k = d / q
        small = k <= GRID_TEST_STEPS
        if q > 0 and small.any() and np.quantile(np.abs(k - np.round(k))[small], 0.99) < 0.02:
            # a grid finer than the noise on it is the digits the file was written with, not
            # an encoder (a capacitive sensor's 20 nm written to 10⁻¹⁰ m was read as a
            # 10⁻¹⁰ m encoder, its noise as 2.9·10⁻¹¹): the noise is then the sensor's
            if white <= GRID_UNDER_NOISE * q:
                return Quantized(step=q, jitter=0.25 * q)
    return Gaussian(sigma=max(white, 1e-12 * max(scale, 1e-300)))


GRID_UNDER_NOISE = 2.0  # a grid whose step is under half the white noise on it is no encoder's
GRID_TEST_STEPS = 50  # steps of up to this many grid steps tell whether readings lie on a grid


def noise_sd(noise) -> float:
    """Standard deviation of a position noise model (a uniform quantisation error: q/√12)."""
    return noise.step / np.sqrt(12.0) if isinstance(noise, Quantized) else noise.sigma


# a position whose noise is under this fraction of its travel shows none: the finest linear
# scales and encoders resolve about 10⁻⁷ of their travel, a number written with its digits 10⁻⁹
NOISELESS = 1e-8


def _listing_short(cols: list) -> str:
    return ", ".join(cols[:6]) + (f" and {len(cols) - 6} more" if len(cols) > 6 else "")


MIN_PLATEAU_SHARE = 0.5  # a normal-load plateau holding less of the recording is not where to fit


def checked_threshold(name: str, value, kind: str = "positive"):
    """One threshold a user sets (``--threshold name=value``) as a number, refused in one line
    unless finite and in its range: kind "window" an odd whole number of samples ≥ 5, "count"
    a whole number of samples ≥ 2, "non_negative" ≥ 0, "positive" > 0."""
    v = float(value)
    if not np.isfinite(v):
        raise DataError(f"--threshold {name}={v}: must be finite")
    if kind == "window":
        if v != int(v) or v < 5 or int(v) % 2 == 0:
            raise DataError(f"--threshold {name}={v:g}: must be an odd whole number of samples, at least 5")
        return int(v)
    if kind == "count":
        if v != int(v) or v < 2:
            raise DataError(f"--threshold {name}={v:g}: must be a whole number of samples, at least 2")
        return int(v)
    if v < 0 or (v == 0 and kind == "positive"):
        raise DataError(f"--threshold {name}={v:g}: must be {'> 0' if kind == 'positive' else '>= 0'}")
    return v


@dataclass
class Thresholds:
    """Every threshold of the segmentation, derived from the recording (SI units)."""

    rate: float = 0.0  # median sample rate (Hz)
    gap: float = 0.0  # a time step longer than this splits the recording (s)
    x_noise: float = 0.0  # position noise σ (quantisation: step/√12)
    window: int = 0  # Savitzky–Golay window (samples)
    v_noise: float = 0.0  # σ of the velocity estimate used
    f_noise: float = 0.0  # σ of the force (or friction) signal
    v_floor: float = 0.0  # below this |v| counts as standstill / presliding
    rel_tol: float = 0.0  # a constant-velocity run stays within rel_tol·|v| (+ 3 v_noise)
    min_run: int = 0  # shortest constant-velocity run (samples)
    f_turn: float = 0.0  # force excursion that confirms a turning point
    x_turn: float = 0.0  # displacement that confirms a motion reversal
    load_tol: float = 0.0  # normal load within this of its plateau counts as constant
    min_travel: float = 0.0  # a level must travel at least this (0: none; only set by the user)
    velocity_source: str = ""
    notes: list = field(default_factory=list)

    # the thresholds a user may set: each is applied before anything uses it. The others
    # (rate, gap, noise floors) are measurements of the recording, not settings.
    SETTABLE = ("window", "v_floor", "rel_tol", "min_run", "f_turn", "x_turn", "load_tol", "min_travel")

    @classmethod
    def checked(cls, values: dict | None) -> dict:
        """The user's overrides as numbers, each refused in one line unless it is a settable
        threshold with a finite value in its range (window: an odd count ≥ 5; min_run: a
        count ≥ 2; min_travel ≥ 0; the others > 0)."""
        out = {}
        for k, v in (values or {}).items():
            if k not in cls.SETTABLE:
                what = "is measured from the recording, not a setting" if k in {f.name for f in fields(cls)} \
                    else "is not a threshold"
                raise DataError(f"--threshold {k}: {what} (settable: {', '.join(cls.SETTABLE)})")
            out[k] = checked_threshold(k, v, {"window": "window", "min_run": "count",
                                              "min_travel": "non_negative"}.get(k, "positive"))
        return out

    def override(self, values: dict) -> "Thresholds":
        for k, v in values.items():
            setattr(self, k, v)
            self.notes.append(f"{k} set to {v:g} by the user")
        return self

    def values(self) -> dict:
        """Every threshold by name, as the number (or text) it is: what the report prints and
        the parameter file's provenance records."""
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "notes"}

    def lines(self) -> list[str]:
        return [f"{k:15s} = {v:.4g}" if isinstance(v, float) else f"{k:15s} = {v}" for k, v in self.values().items()]


@dataclass
class Prepared:
    """A recording with the derived signals the segmentation works on."""

    rec: Recording
    velocity: np.ndarray
    friction: np.ndarray | None  # measured friction (action sign) or None
    force: np.ndarray | None  # applied force or None
    position_noise: object
    usable: np.ndarray  # samples not excluded (normal load off its plateau)
    chunks: list  # (start, end) index ranges without time gaps
    th: Thresholds
    sign_flipped: bool = False
    notes: list = field(default_factory=list)
    # the median travel over which a measured friction crossed to sliding after a reversal of
    # the motion (``presliding_reach``); 0 where it is not seen (no friction logged, too few crossings)
    reach: float = 0.0
    # the normal load's (lowest, highest) where it is not held at one plateau and every sample
    # is used (S(v) and the transition curve then average over the loads); None otherwise
    load_range: tuple[float, float] | None = None

    @property
    def source(self) -> str:
        return self.rec.source


def gap_threshold(t: np.ndarray) -> float:
    """A time step longer than this is a gap in the log (samples lost, a pause in logging):
    five times the 99th percentile of the steps, robust to files mixing sample rates."""
    return 5.0 * float(np.quantile(np.diff(t), 0.99))


def time_gaps(t: np.ndarray, gap: float | None = None) -> np.ndarray:
    """Indices i where the log resumes after a gap (t[i] − t[i−1] over ``gap_threshold``)."""
    if len(t) < 3:
        return np.zeros(0, dtype=int)
    return np.flatnonzero(np.diff(t) > (gap_threshold(t) if gap is None else gap)) + 1


def across_gaps(n: int, gaps: np.ndarray, half: int) -> np.ndarray:
    """Samples whose window of ``half`` samples either side reaches across a gap (``time_gaps``):
    an average, a slope or a smoothing taken there mixes two stretches of motion with the
    unseen one between them."""
    out = np.zeros(n, bool)
    for g in gaps:
        out[max(g - half, 0):min(g + half, n)] = True
    return out


def piecewise_slope(t: np.ndarray, x: np.ndarray, w: int, gap: float) -> np.ndarray:
    """``local_slope`` on each stretch of the log between time gaps (``time_gaps``), none
    taken across one: there the motion is not seen. A stretch of one sample gets 0."""
    v = np.zeros(len(t))
    for a, b in _chunks(t, gap):
        dts = np.diff(t[a:b])
        v[a:b] = local_slope(t[a:b], x[a:b], w, uniform=bool(np.ptp(dts) <= 0.01 * float(np.median(dts))))
    return v


def _chunks(t, gap):
    cut = np.flatnonzero(np.diff(t) > gap) + 1
    edges = np.concatenate([[0], cut, [len(t)]])
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:]) if b - a >= 2]


def local_slope(t, x, w, uniform):
    """Local least-squares slope over ``w`` samples: Savitzky–Golay (order 2) on uniform
    sampling, a running linear regression (cumulative sums) on irregular sampling."""
    n = len(x)
    if n < 5:
        return np.gradient(x, t) if n > 1 else np.zeros(n)
    w = min(w, n - (1 - n % 2))
    if w < 3:
        return np.gradient(x, t)
    if uniform and w <= 101:
        dt = (t[-1] - t[0]) / (n - 1)
        return savgol_filter(x, w, 2, deriv=1, delta=dt, mode="interp")
    # long windows, or irregular sampling: the same slope (a centred quadratic's derivative at
    # the centre is the least-squares line's slope) from cumulative sums, O(n) instead of O(n·w)
    h = w // 2
    out = np.empty(n)
    step = SLOPE_CHUNK_WINDOWS * w
    for a in range(0, n, step):
        b = min(a + step, n)
        lo, hi = max(a - h, 0), min(b + h, n)
        out[a:b] = _running_slope(t[lo:hi], x[lo:hi], h)[a - lo:b - lo]
    return out


SLOPE_CHUNK_WINDOWS = 50  # cumulative sums restart every this many windows (``_running_slope``)


def _running_slope(t, x, h):
    """The least-squares line's slope over the 2h + 1 samples centred on each one (clipped at
    the ends), from cumulative sums taken from the piece's first sample. The piece must be
    short: the window's Σ(t − t̄)² is a difference of two such sums, and their rounding grows
    with the piece's length cubed — over a whole record of 10⁵ samples it took up to 25 % off a
    5-sample window's slope (3–5 % in RMS), and a cylinder's inertia read from it came out 197
    and 222 kg for 250 (``local_slope`` takes pieces of SLOPE_CHUNK_WINDOWS windows: under 10⁻⁸
    of the slope)."""
    n = len(t)
    tc = t - t[0]
    xc = x - x[0]
    c = lambda a: np.concatenate([[0.0], np.cumsum(a)])  # noqa: E731
    S1, St, Sx, Stt, Stx = c(np.ones(n)), c(tc), c(xc), c(tc * tc), c(tc * xc)
    i = np.arange(n)
    lo, hi = np.clip(i - h, 0, n), np.clip(i + h + 1, 0, n)
    m = S1[hi] - S1[lo]
    st, sx, stt, stx = St[hi] - St[lo], Sx[hi] - Sx[lo], Stt[hi] - Stt[lo], Stx[hi] - Stx[lo]
    den = stt - st * st / m
    return np.where(den > 0, (stx - st * sx / m) / np.where(den > 0, den, 1.0), 0.0)


def moving_average(a, w):
    """Centred moving average over w samples (shrinking at the ends), O(n): the value of a
    local least-squares line at the window's centre."""
    a = np.asarray(a, dtype=float)
    n = len(a)
    h = int(w) // 2
    c = np.concatenate([[0.0], np.cumsum(a - a[0])])
    i = np.arange(n)
    lo, hi = np.clip(i - h, 0, n), np.clip(i + h + 1, 0, n)
    return (c[hi] - c[lo]) / (hi - lo) + a[0]


def _slope_noise(x_noise, w, dt):
    """σ of a least-squares slope over w equally spaced samples with white noise x_noise."""
    return x_noise * np.sqrt(12.0 / (w * (w * w - 1.0))) / dt


def check_force_or_friction(rec: Recording) -> None:
    """A fit needs an applied force or a measured friction: refused in one line otherwise,
    naming the columns that were not recognised and how to name one."""
    if rec.force is None and rec.friction is None:
        why = rec.unrecognised("force", "friction")
        # two columns that could each be the force may be the force and a load pressing the contact
        # (a pitch bearing's drive torque and its blade's bending moment): say how to name that too
        load = ("; another of them, a load pressing the contact, with --columns normal_load=<column>"
                if "force" in rec.ambiguous and rec.normal_load is None else "")
        raise IdentificationError(f"{rec.source}: needs a force (applied force/torque) or a friction column"
                                  + (f"; {why}: name it with --columns force=<column> (applied) or "
                                     f"friction=<column> (measured){load}" if why else ""))


def prepare(rec: Recording, *, friction_sign: str = "auto", overrides: dict | None = None) -> Prepared:
    """Derive the thresholds and signals of one recording; see the module docstring."""
    if rec.position is None:
        raise IdentificationError(f"{rec.source}: needs a position column to find velocity levels and presliding")
    check_force_or_friction(rec)
    th = Thresholds()
    t, x = rec.time, rec.position
    dts = np.diff(t)
    dt = float(np.median(dts))
    th.rate = 1.0 / dt
    th.gap = gap_threshold(t)
    noise = detect_noise(x)
    th.x_noise = float(noise_sd(noise))
    chunks = _chunks(t, th.gap)
    n = len(t)
    # the slowest sustained motion, on a coarse scale (0.5 % of the recording per difference)
    W = max(2, n // 200)
    vc = (x[W:] - x[:-W]) / (t[W:] - t[:-W])
    moving = np.abs(vc) > 10.0 * th.x_noise / (W * dt)
    v_low = float(np.quantile(np.abs(vc[moving]), 0.5)) if moving.sum() > 10 else 0.0
    # window: the slope noise at most 2 % of the typical (median) motion, n/1000 … n/400 samples (at
    # least 5): long enough to average a controller's velocity ripple, short against the
    # runs so accelerations stay visible
    w = max(5, (n // 1000) | 1)
    if v_low > 0:
        while w < max(5, n // 400) and _slope_noise(th.x_noise, w, dt) > 0.02 * v_low:
            w += 2
    overrides = Thresholds.checked(overrides)
    w = overrides.get("window", w)  # a window set by the user is the one the velocity uses
    th.window = int(w)
    v_pos = piecewise_slope(t, x, w, th.gap)
    sd_pos = float(_slope_noise(th.x_noise, w, dt))
    velocity, th.velocity_source, th.v_noise = v_pos, f"position (Savitzky–Golay, {w} samples)", sd_pos
    if rec.velocity is not None:
        sd_col = white_noise_sd(rec.velocity)
        if sd_col < sd_pos:
            velocity, th.velocity_source, th.v_noise = rec.velocity, f"velocity column {rec.columns.get('velocity', '')!r}", sd_col
        th.notes.append(f"velocity: column noise {sd_col:.3g}, position-derived noise {sd_pos:.3g}; "
                        f"used the {'column' if sd_col < sd_pos else 'position-derived velocity'}")
    F = rec.friction if rec.friction is not None else rec.force
    th.f_noise = max(white_noise_sd(F), 1e-12 * float(np.max(np.abs(F)) or 1.0))
    th.v_floor = 5.0 * th.v_noise
    th.rel_tol = 0.06
    th.min_run = int(max(MIN_RUN_FLOOR, 2 * w))
    th.f_turn = 6.0 * th.f_noise
    th.x_turn = max(6.0 * th.x_noise, 2.0 * getattr(noise, "step", 0.0))
    usable = np.ones(n, dtype=bool)
    notes = []
    travel = float(np.ptp(x))
    if travel > 0 and th.x_noise < NOISELESS * travel:
        notes.append(f"the position shows no measurement noise (x_noise {th.x_noise:.3g} over a travel of "
                     f"{travel:.3g}): a simulated or commanded position; a measured one is what the friction "
                     f"acted on (name it with --columns position=<column>)"
                     + (f"; not read: {_listing_short(rec.ignored)}" if rec.ignored else ""))
    if rec.normal_load is not None:
        # the plateau is sought on the load averaged over the window: a sample off it by its
        # sensor's noise alone is on it (a constant 20 kN with 1 % noise had 37 single samples
        # left out against its raw 95th percentile, splitting 3 runs into 6 levels)
        N = moving_average(rec.normal_load, th.window)
        N0 = float(np.quantile(N, 0.95))
        th.load_tol = max(5.0 * white_noise_sd(rec.normal_load), 0.02 * abs(N0))
    th.override(overrides)
    load_range = None
    if rec.normal_load is not None:
        lu = rec.units.get("normal_load", "N")  # N, or N*m for a tilting moment
        usable = np.abs(N - N0) <= th.load_tol
        if usable.mean() >= MIN_PLATEAU_SHARE:
            notes.append(f"normal load: plateau {N0:.4g} {lu}; {int((~usable).sum())} samples off the plateau "
                         f"(|N - N0| > {th.load_tol:.3g} {lu}, N averaged over the window) left out")
        else:
            # a load that varies through the session (a schedule, a drifting contact): keeping
            # only its plateau would leave too little to fit; the base model then averages over
            # the loads, and `diagnose` tells whether the friction follows them
            notes.append(f"normal load: not held at one plateau (only {100 * usable.mean():.0f} % of the samples within "
                         f"{th.load_tol:.3g} {lu} of its 95th percentile {N0:.4g} {lu}; it ranges "
                         f"{np.min(rec.normal_load):.4g}–{np.max(rec.normal_load):.4g} {lu}): every sample is used, "
                         f"S(v) and the transition curve average over the loads (run diagnose to see whether "
                         f"friction follows the load)")
            usable = np.ones(n, dtype=bool)
            load_range = (float(np.min(rec.normal_load)), float(np.max(rec.normal_load)))
    flipped = False
    friction = rec.friction
    if friction is not None:
        mv = (np.abs(velocity) > th.v_floor) & usable
        s = float(np.median(friction[mv] * np.sign(velocity[mv]))) if mv.sum() > 10 else 1.0
        detected = "reaction" if s < 0 else "action"
        choice = detected if friction_sign == "auto" else friction_sign
        if friction_sign == "auto":
            notes.append(f"friction sign: logged as {detected} force "
                         f"({'negative' if s < 0 else 'positive'} while the position increases)"
                         + ("; flipped to the action convention" if detected == "reaction" else ""))
        else:
            notes.append(f"friction sign: {choice} (forced; the data look like {detected})")
        if choice == "reaction":
            friction = -friction
            flipped = True
    prep = Prepared(rec, velocity, friction, rec.force if rec.friction is None else None, noise, usable, chunks, th,
                    flipped, notes, load_range=load_range)
    prep.reach = presliding_reach(prep)
    return prep


MIN_REACH_CROSSINGS = 3  # crossings of a prescribed motion that bound the presliding range (``presliding_reach``)


def presliding_reach(prep: Prepared) -> float:
    """The median travel over which the measured friction crossed to sliding after a reversal of
    the motion (``crossing_range``), over at least MIN_REACH_CROSSINGS crossings; 0 where fewer
    are seen (no friction logged, a motion without reversals): past twice it the contact
    slides, and the transition curve no longer matters (``GROSS_SLIDING``)."""
    ranges = [r for c in crossings(prep) if math.isfinite(r := crossing_range(c, prep.th))]
    return float(np.median(ranges)) if len(ranges) >= MIN_REACH_CROSSINGS else 0.0


def _batch_var_of_mean(a, batches=8):
    """Variance of the mean of a correlated series, from the spread of batch means."""
    m = len(a) // batches
    if m < 2:
        return float(np.var(a, ddof=1) / max(len(a), 1))
    bm = a[: m * batches].reshape(batches, m).mean(axis=1)
    return max(float(np.var(bm, ddof=1) / batches), float(np.var(a, ddof=1) / len(a)))


MIN_RUN_FLOOR = 20  # the shortest run of steady velocity a level is ever taken from (samples)


def steady_runs(prep: Prepared):
    """Each run of steady velocity as (chunk start, run start, run end) in the chunk's samples:
    |v| > v_floor and v within rel_tol·|v| + 3·v_noise of itself over a window, one sign."""
    th, v = prep.th, prep.velocity
    w = max(th.window, 5)
    for a, b in prep.chunks:
        vv = v[a:b]
        steady = (np.abs(vv) > th.v_floor) & prep.usable[a:b]
        same = np.zeros(len(vv), dtype=bool)
        same[w:] = np.abs(vv[w:] - vv[:-w]) <= th.rel_tol * np.abs(vv[w:]) + 3 * th.v_noise
        same[:-w] &= same[w:]
        steady &= same & (np.sign(vv) == np.sign(np.roll(vv, w)))
        edges = np.flatnonzero(np.diff(np.concatenate([[0], steady.astype(np.int8), [0]])))
        for s0, e0 in zip(edges[::2], edges[1::2]):
            yield a, int(s0), int(e0)


def fast_runs(prep: Prepared, levels: Levels, *, cut_short: bool = True) -> list[tuple[float, int]]:
    """(|v|, samples) of each steady run faster than every level of its side (by half as much
    again), only those shorter than ``min_run`` (two windows) where ``cut_short``: a sweep's
    fastest speeds held for less time than the window the velocity is smoothed over asks (a
    pitch bearing made apart held 2 °/s for 7 s at 50 Hz; the window derived from its 141,000
    rows was 141 samples, and its fastest level was lost until ``--threshold window=41``)."""
    th, v = prep.th, prep.velocity
    found = []
    for a, s0, e0 in steady_runs(prep):
        s, e = level_part(a, s0, e0, max(th.window, 5))
        # cut short: the part a level averages is under min_run (a run of min_run or more whose
        # averaged part was not had been lost between the two tests: a stage made apart held
        # ±94 and ±180 mm/s for 805 samples, steady runs of 432–462 at a window of 159, averaged
        # parts of 224–245 under min_run 318, and no note said so)
        if e0 - s0 < MIN_RUN_FLOOR or (cut_short and e - s >= th.min_run):
            continue
        speed = float(np.median(v[a + s0:a + e0]))
        if beyond_levels([speed], levels)[0]:
            found.append((abs(speed), e0 - s0))
    return found


def runs_under_window(prep: Prepared, levels: Levels) -> list[tuple[float, int]]:
    """(|v|, samples) of each run holding a speed faster than every level of its side
    (``beyond_levels``) for less time than the window the velocity is smoothed over, so that no
    steady run shows it there (``fast_runs`` then finds nothing): the velocity is taken again at a
    quarter of that window (odd, at least 5) and its steady runs (as ``steady_runs`` tests them,
    the slope noise of the short window in place of v_noise) of at least MIN_RUN_FLOOR samples
    and two short windows are counted. A tribometer made apart, 189,000 rows at 1 kHz (a window
    of 189), drove triangles at 3–20 mm/s whose legs lasted 0.1–0.5 s: every one was lost, S(v)
    rested on two speeds per side (F_s held at F_c), and nothing said so."""
    th = prep.th
    w = max(th.window, 5)
    short = max(5, (w // 4) | 1)
    if short >= w or prep.rec.position is None:
        return []
    v = piecewise_slope(prep.rec.time, prep.rec.position, short, th.gap)
    noise = float(_slope_noise(th.x_noise, short, 1.0 / th.rate))
    steady = (np.abs(v) > th.v_floor) & prep.usable
    same = np.zeros(len(v), dtype=bool)
    same[short:] = np.abs(v[short:] - v[:-short]) <= th.rel_tol * np.abs(v[short:]) + 3 * noise
    same[:-short] &= same[short:]
    steady &= same & (np.sign(v) == np.sign(np.roll(v, short)))
    edges = np.flatnonzero(np.diff(np.concatenate([[0], steady.astype(np.int8), [0]])))
    found = []
    for s0, e0 in zip(edges[::2], edges[1::2]):
        if e0 - s0 < max(MIN_RUN_FLOOR, 2 * short):
            continue
        speed = float(np.median(v[s0:e0]))
        if beyond_levels([speed], levels)[0]:
            found.append((abs(speed), int(e0 - s0)))
    return found


def beyond_levels(speeds, levels: Levels) -> np.ndarray:
    """Whether each speed is faster than every level of its side (its sign) by
    FASTER_THAN_LEVELS: a sweep's speed the levels so far do not reach."""
    v = np.asarray(speeds, dtype=float)
    top = {sign: float(np.max(np.abs(levels.velocity[levels.velocity * sign > 0]), initial=0.0))
           for sign in (1.0, -1.0)}
    return np.array([s != 0 and abs(s) > FASTER_THAN_LEVELS * top[1.0 if s > 0 else -1.0] for s in v], dtype=bool)


FASTER_THAN_LEVELS = 1.5  # a run this many times faster than every level of its side is beyond them


def level_part(a: int, s0: int, e0: int, window: int, settle_fraction: float = 0.3) -> tuple[int, int]:
    """The samples [s, e) of the steady run a + s0 … a + e0 (``steady_runs``) that a level
    averages: its first ``settle_fraction`` left out (the approach to sliding) and its last half
    window (the smoothing there reaches into the next move)."""
    return a + s0 + int(settle_fraction * (e0 - s0)), a + e0 - window // 2


def constant_velocity_levels(prep: Prepared, *, settle_fraction: float = 0.3) -> Levels:
    """Runs where |v| > v_floor and v stays within rel_tol·|v| + 3·v_noise of itself over a
    window; the first ``settle_fraction`` of each run is dropped (the approach to sliding),
    and a run whose friction still trends (halves differ by > 4σ), or opposes its velocity,
    is not a level, nor is creep (``sliding_only``). Level velocity = travel / time over the
    kept part (exact on quantised positions); variance of the mean friction from batch means
    (the noise is not white under feedback control)."""
    th, rec = prep.th, prep.rec
    F = prep.friction if prep.friction is not None else prep.force
    v, x, t = prep.velocity, rec.position, rec.time
    w = max(th.window, 5)
    out = ([], [], [], [], [])
    trend = ([], [], [], [], [])
    opposing = within_reach = with_speed = strokes_opposing = 0
    span = float(np.ptp(x)) if len(x) else 0.0
    # the motion's reversals, to tell how far each run has travelled from the last one
    turns = {a: a + turning_points(x[a:b], th.x_turn) for a, b in prep.chunks} if prep.reach > 0 else {}
    for a, s0, e0 in steady_runs(prep):
        if e0 - s0 < th.min_run:
            continue
        s, e = level_part(a, s0, e0, w, settle_fraction)
        if e - s < th.min_run:
            continue
        before = turns[a][turns[a] <= s] if prep.reach > 0 else ()
        if len(before) and abs(x[s] - x[before[-1]]) < GROSS_SLIDING * prep.reach:
            # a run whose averaged part starts within twice the presliding range of its last
            # turning point (a chunk's first sample counts as one: a log that starts mid-slide, or
            # after a gap, may lose its first run so) is a stroke of presliding, its friction on
            # the way to S(v), not sliding (a Dahl rig made apart:
            # its presliding triangles' legs, 1–20 µm at 50 µm/s, read 35–44 N where S(v) gives
            # 41.8–44.9; a tribometer's ±10–60 µm oscillations made 13 of its 26 levels, and its
            # S(v) came out as Coulomb)
            within_reach += 1
            continue
        vk = v[s:e]
        med = np.median(vk)
        if np.max(np.abs(vk - med)) > 2 * th.rel_tol * abs(med) + 6 * th.v_noise:
            continue
        vel = (x[e - 1] - x[s]) / (t[e - 1] - t[s])
        if vel * med <= 0 or abs(x[a + e0 - 1] - x[a + s0]) < th.min_travel:
            continue
        f = F[s:e]
        if np.mean(f) * vel <= 0:
            # sliding dissipates: S(v) has the sign of v. A slow creep whose force opposes it
            # is the presliding spring giving back (a robot joint's torque ramps), not a level.
            # One over a tenth of the travel or more no presliding spring gives back over: the
            # applied force holds a constant force beyond friction (a vertical axis made apart,
            # its 40 kg held by the motor, had all 8 of its downward strokes, up to 260 mm, said
            # to be a presliding spring giving back), counted apart for the notes to say
            opposing += 1
            strokes_opposing += abs(x[e - 1] - x[s]) >= STROKE_SHARE * span
            continue
        h = len(f) // 2
        se = np.sqrt(_batch_var_of_mean(f[:h], 4) + _batch_var_of_mean(f[h:], 4))
        step = np.mean(f[h:]) - np.mean(f[:h])
        # a run whose friction still trends (its halves over 4σ apart) has not settled to one
        # value of S(v): a ripple along its travel, a drift in time, a load moving. It is kept
        # as a point of S(v) with half that step in its σ, where its mean may lie off the
        # curve, so that a sweep's slow end lost that way does not take the Stribeck part with
        # it (a feed axis made apart, a 5 mm ripple along its screw: 11 of 24 runs, all the
        # slow ones, and F_s held at F_c); it ends no presliding branch (``Levels.steady``).
        # Only where the speed held: its relative change TREND_NOT_SPEED times under the
        # friction's (S(v)'s slope in log-log seldom reaches 1), else the speed made the trend
        trended = abs(step) > 4 * se
        speed_step = abs(np.mean(vk[h:]) - np.mean(vk[:h])) / abs(vel)
        if trended and abs(step) <= TREND_NOT_SPEED * speed_step * abs(np.mean(f)):
            # the speed moved with it: no steady run (a creep, a stroke of a sinusoidal force);
            # counted, for the notes to say (a valve made apart lost its only 12 mm/s strokes so,
            # their friction 2.2 % up along a spring left in the force, their speed 1.1 %, unsaid)
            with_speed += 1
            continue
        dest = trend if trended else out
        dest[0].append(float(vel))
        dest[1].append(float(np.mean(f)))
        dest[2].append(_batch_var_of_mean(f) + (0.25 * step * step if trended else 0.0))
        dest[3].append(e - s)
        dest[4].append(float(np.mean(t[s:e])))

    def levels(o, **kw):
        return Levels(*(np.array(a, dtype=float) for a in o[:4]), time=np.array(o[4], dtype=float), **kw)

    runs = levels(out, opposing=opposing, creep=within_reach, speed_trend=with_speed,
                  opposing_strokes=int(strokes_opposing))
    if not trend[0]:
        return sliding_only(runs)
    runs = sliding_only(Levels.joined([runs, levels(trend, trended=np.ones(len(trend[0]), bool))]))
    # trending runs add to a sweep; alone, only a sweep of them makes one: on a side with fewer
    # than three settled levels (where creep is not told either, ``sliding_only``) they are
    # left out, and counted (a robot joint swept one way only: its one slow return, creeping
    # under a torque ramp, read 7.4 N·m for an F_s of 14.9) — unless they span a sweep's
    # speeds themselves (a cylinder made apart under a load changing all session: each of its
    # 20 positive runs trended, over 10 speeds, and that side was mirrored from the other)
    keep = np.ones(len(runs.velocity), bool)
    for sign in (1.0, -1.0):
        side = runs.velocity * sign > 0
        alone = side & runs.is_trended
        settled = int(np.sum(side & ~runs.is_trended))
        if settled < TREND_BESIDE and distinct_speeds(runs.velocity[alone]) < STRIBECK_MIN_SPEEDS:
            keep &= ~alone
    return runs if keep.all() else runs.kept(keep, trend_alone=int(np.sum(~keep)))


STROKE_SHARE = 0.1  # a run opposing its velocity over this share of the record's travel is a stroke, not creep
# a trending run is a point of S(v) if its friction moved (relative) this many times more than its speed
TREND_NOT_SPEED = 10.0
TREND_BESIDE = 3  # … and if its side has this many settled levels


CREEP_FRICTION = 0.6  # creep holds less than this fraction of its direction's median level friction,
CREEP_TRAVEL = 0.01  # or travels less than this fraction of the median level's travel;
CREEP_ISOLATED = 0.2  # both, or either one at under this fraction of the next slowest level's speed


def sliding_only(levels: Levels) -> Levels:
    """Leave out runs of steady velocity that are the contact creeping in presliding, not
    points of S(v). Of a direction's levels (at least three), a run is creep if its friction
    is under 60 % of their median (sliding needs about F_c) and its travel (speed × samples)
    under 1 % of theirs (a sweep's slowest level travels about 5 % of its median one; a load or
    a temperature moves the friction, not the travel) — or if it shows one of the two and is
    more than five times slower than the next slowest level (a sweep's speeds lie a factor 2–3
    apart). Such runs — a robot joint's torque held between presliding ramps, creeping at
    8e-5 to 3e-4 rad/s beside sweeps from 2.5e-3 — set the speed that ends presliding
    branches, and none were found. The medians are those of the levels above the fastest
    such gap (``sliding_reference``), so that the sweep sets them however many creeping runs
    there are (a nanopositioning stage made apart, its force ramped slowly in presliding: 12 of
    its 21 positive runs crept at 0.24–1 µm/s under 0.1 N beside a sweep from 20 µm/s at
    0.12–0.16 N, and the medians over all were the creep's own)."""
    keep = np.ones(len(levels.velocity), dtype=bool)
    travel = np.abs(levels.velocity) * levels.count
    for sign in (1.0, -1.0):
        m = np.flatnonzero(levels.velocity * sign > 0)
        if len(m) < 3:
            continue
        speed = np.abs(levels.velocity[m])
        ref = sliding_reference(speed)
        weak = np.abs(levels.friction[m]) < CREEP_FRICTION * np.median(np.abs(levels.friction[m][ref]))
        short = travel[m] < CREEP_TRAVEL * np.median(travel[m][ref])
        # against the next slowest level that shows neither sign (creep often comes in a few runs)
        plain = speed[~(weak | short)]
        # (the fastest level has none to be isolated from)
        isolated = np.array([bool(np.any(plain > v)) and v < CREEP_ISOLATED * np.min(plain[plain > v], initial=np.inf)
                             for v in speed])
        keep[m] = ~((weak & short) | ((weak | short) & isolated))
    if keep.all():
        return levels
    return levels.kept(keep, creep=levels.creep + int(np.sum(~keep)))


def sliding_reference(speed: np.ndarray) -> np.ndarray:
    """Which of a direction's levels (their speeds) set the medians creep is judged against:
    those faster than the fastest gap between neighbouring speeds wider than a factor
    1/CREEP_ISOLATED, where at least three are (a sweep's speeds lie a factor 2–3 apart, creep
    far below them), else all."""
    s = np.sort(speed)
    gaps = np.flatnonzero(s[1:] * CREEP_ISOLATED > s[:-1])
    if len(gaps) == 0 or len(s) - (gaps[-1] + 1) < 3:
        return np.ones(len(speed), dtype=bool)
    return speed >= s[gaps[-1] + 1]


SPEED_BIN = math.log(1.2)  # sliding pooled into speed levels this wide in log|v| (``speed_levels``)
SPEED_MIN_SAMPLES = 10  # … a level needs this many samples
STEADY_TOL = 0.05  # relative change of velocity across a window that still counts as steady
GROSS_SLIDING = 2.0  # gross sliding: this many presliding ranges travelled since the velocity's sign changed


def gross_sliding_mask(x: np.ndarray, v: np.ndarray, v_rest: float, z_range: float) -> np.ndarray:
    """Samples in gross sliding: moving (|v| > ``v_rest``), and more than GROSS_SLIDING
    presliding ranges ``z_range`` travelled since the velocity last changed sign, so the
    transition curve no longer matters and the friction is S(v) times whatever effect acts."""
    moving = np.abs(v) > v_rest
    sgn = np.where(moving, np.sign(v), 0.0)
    # the sign of the last moving sample, carried over rests
    idx = np.maximum.accumulate(np.where(moving, np.arange(len(v)), 0))
    carried = sgn[idx]
    start = np.r_[True, carried[1:] != carried[:-1]]
    run_start = np.maximum.accumulate(np.where(start, np.arange(len(v)), 0))
    travelled = np.abs(x - x[run_start])
    return moving & (travelled > GROSS_SLIDING * z_range)


def steady_velocity_mask(v: np.ndarray, w: int, v_rest: float) -> np.ndarray:
    """Samples whose velocity changes, over ``w`` samples each side, by less than STEADY_TOL of
    itself plus ``v_rest``: there the hysteresis force has caught up with S(v) (it lags the
    velocity by about a presliding range of travel), whether the run is a constant-velocity
    level or the slow middle of a sinusoidal stroke."""
    tol = STEADY_TOL * np.abs(v) + v_rest
    ok = np.ones(len(v), dtype=bool)
    ok[:w] = ok[-w:] = False
    ok[w:] &= np.abs(v[w:] - v[:-w]) <= tol[w:]
    ok[:-w] &= np.abs(v[:-w] - v[w:]) <= tol[:-w]
    return ok


def speed_levels(velocity: np.ndarray, y: np.ndarray, mask: np.ndarray, corr_length: int) -> Levels:
    """Levels of S(v) (the Markov estimator's input, section IV-A) from the samples of steady
    sliding ``mask``: per direction, pooled in bins of SPEED_BIN in log|v|, each level's mean
    speed and mean ``y`` with the variance of that mean over its ``corr_length``-sample
    stretches (neighbouring samples of averaged friction are not independent)."""
    out = [[], [], [], []]
    for sign in (1.0, -1.0):
        m = mask & (velocity * sign > 0)
        if not m.any():
            continue
        lv = np.log(np.abs(velocity[m]))
        b = np.floor((lv - lv.min()) / SPEED_BIN).astype(np.int64)
        for k in np.unique(b):
            sel = b == k
            cnt = int(sel.sum())
            if cnt < SPEED_MIN_SAMPLES:
                continue
            yy = y[m][sel]
            n_eff = max(2.0, cnt / max(corr_length, 1))
            out[0].append(float(np.mean(velocity[m][sel])))
            out[1].append(float(np.mean(yy)))
            out[2].append(float(np.var(yy, ddof=1)) / n_eff)
            out[3].append(cnt)
    return Levels(*(np.array(o, dtype=float) for o in out))


def sliding_levels(prep: Prepared, z_range: float) -> Levels:
    """Levels of S(v) for a recording with no runs of constant velocity (a crank-driven
    tribometer, a sinusoidal applied force): its measured friction in gross sliding
    (``gross_sliding_mask`` beyond ``z_range``, the presliding range its reversals show) where
    the velocity changes by less than STEADY_TOL of itself (plus ``v_floor``) while the contact
    travels one presliding range — the hysteresis force lags S(v) by about that travel, so
    there it has caught up — pooled by speed (``speed_levels``). A level whose friction
    opposes its velocity is left out (sliding dissipates). Empty without a measured friction
    (``fit.friction_by_eq8`` gives one from an applied force where the force reads the inertia)."""
    if prep.friction is None or not z_range > 0:
        return Levels(*(np.zeros(0) for _ in range(4)))
    th, x, t, v = prep.th, prep.rec.position, prep.rec.time, prep.velocity
    mask = np.zeros(len(v), dtype=bool)
    for a, b in prep.chunks:
        if b - a < 3:
            continue
        vv = v[a:b]
        dt = float(np.median(np.diff(t[a:b])))
        acc = moving_average(np.gradient(vv, t[a:b]), max(th.window, 3))
        lag = np.maximum(z_range / np.maximum(np.abs(vv), 1e-300), dt)  # the time one presliding range takes
        steady = np.abs(acc) * lag <= STEADY_TOL * np.abs(vv) + th.v_floor
        mask[a:b] = gross_sliding_mask(x[a:b], vv, th.v_floor, z_range) & steady
    lv = speed_levels(v, prep.friction, mask & prep.usable, th.window)
    keep = lv.friction * lv.velocity > 0
    return lv.kept(keep, opposing=int(np.sum(~keep)))


@njit(cache=True)
def turning_points(s, h):
    """Indices of alternating extrema of ``s``, each confirmed by a move of ``h`` away
    (first and last sample included)."""
    n = len(s)
    idx = np.empty(n, np.int64)
    cnt = 0
    idx[cnt] = 0
    cnt += 1
    direction = 0
    hi_i, hi_v, lo_i, lo_v = 0, s[0], 0, s[0]
    for i in range(1, n):
        y = s[i]
        if y > hi_v:
            hi_i, hi_v = i, y
        if y < lo_v:
            lo_i, lo_v = i, y
        if direction >= 0 and hi_v - y > h:
            if hi_i != idx[cnt - 1]:
                idx[cnt] = hi_i
                cnt += 1
            direction = -1
            lo_i, lo_v = i, y
        elif direction <= 0 and y - lo_v > h:
            if lo_i != idx[cnt - 1]:
                idx[cnt] = lo_i
                cnt += 1
            direction = 1
            hi_i, hi_v = i, y
    if idx[cnt - 1] != n - 1:
        idx[cnt] = n - 1
        cnt += 1
    return idx[:cnt]


def _memory_pieces(fs, turns, Fs_pos, Fs_neg):
    """Assign the samples of an applied-force record to the presliding branch each lies on,
    by the hysteresis memory of Section III-B (the rules of model/kernels.py): a reversal
    starts a branch (pushed on the stack of minima when the force rises, of maxima when it
    falls); when the force gets back to the extremum where the current internal loop began,
    both extrema are wiped out and the older branch continues. The outer bounds F_s-/F_s+
    stay at the bottom of the stacks: a branch continued from them starts at a reversal the
    record never shows (``observed`` False; its displacement offset is unknown).

    Returns {key: (F_b, direction, observed, [(start, stop), ...])} with sample ranges in
    the order they occur (an internal loop's samples belong to the inner branch)."""
    branches: dict = {}
    m, M = [(float(Fs_neg), "outer-", False)], [(float(Fs_pos), "outer+", False)]
    for k in range(len(turns) - 1):
        a, b = int(turns[k]), int(turns[k + 1])
        d = 1.0 if fs[b] > fs[a] else -1.0 if fs[b] < fs[a] else 0.0
        if d == 0.0:
            continue
        entry = (float(fs[a]), a, True)
        (m if d > 0 else M).append(entry)
        active = entry
        r = np.maximum.accumulate(d * fs[a:b + 1])
        cur = a
        while len(m) >= 2 and len(M) >= 2:
            T = M[-1][0] if d > 0 else m[-1][0]
            j = int(np.searchsorted(r, d * T, side="left"))
            if j >= len(r):
                break
            branches.setdefault(active[1], (active[0], d, active[2], []))[3].append((cur, a + j))
            m.pop()
            M.pop()
            active = m[-1] if d > 0 else M[-1]
            cur = a + j
        branches.setdefault(active[1], (active[0], d, active[2], []))[3].append((cur, b + 1))
    return branches


def force_branches(prep: Prepared, Fs_pos: float, Fs_neg: float, v_max: float, *, min_points: int = 20) -> list[Branch]:
    """Applied-force ramps between turning points (confirmed by ``f_turn``), each sample
    assigned by the hysteresis memory (:func:`_memory_pieces`) to the branch it lies on, so
    a branch interrupted by an internal loop continues after the loop closes. A branch ends
    at the first sample out of presliding (|v| ≥ ``v_max``: gross sliding wipes the memory)
    or beyond 97 % of D = F_s(direction) − F_b, F_b the force at the reversal."""
    rec, th = prep.rec, prep.th
    if prep.force is None:
        return []
    out = []
    for a0, b0 in prep.chunks:
        f = prep.force[a0:b0]
        fs = moving_average(f, max(5, th.window | 1)) if len(f) > 7 else f
        turns = turning_points(fs, th.f_turn)
        x = rec.position[a0:b0]
        v = np.abs(prep.velocity[a0:b0])
        ok = prep.usable[a0:b0]
        t = rec.time[a0:b0]
        for start, (fb, d, observed, pieces) in _memory_pieces(fs, turns, Fs_pos, Fs_neg).items():
            if start == 0 and a0 > 0:
                # the log resumes after a time gap: its first sample is no reversal, and what the
                # contact did in the gap is not seen (a cylinder's log with 1 % of its rows lost in
                # six bursts had 29 branches against 24, the extra ones starting mid-ramp)
                continue
            idx = np.concatenate([np.arange(s, e) for s, e in pieces])
            D = (Fs_pos if d > 0 else -Fs_neg) - d * fb
            if D <= 0 or len(idx) < min_points:
                continue
            dF = d * (fs[idx] - fb)
            keep = (dF >= 0) & (dF < 0.97 * D) & (v[idx] < v_max) & ok[idx]
            stop = np.flatnonzero(~keep)
            m = int(stop[0]) if len(stop) else len(keep)
            if m < min_points or np.ptp(dF[:m]) < 10 * th.f_noise:
                continue
            out.append(Branch(force=np.maximum.accumulate(dF[:m]), displacement=d * x[idx[:m]], D=float(D),
                              driven="force", t_end=float(t[idx[m - 1]]), observed=observed))
    return out


@dataclass(frozen=True)
class Crossing:
    """After a reversal of a prescribed motion (a position extremum confirmed by ``x_turn``),
    the friction's crossing from the old sliding level F_b towards the new one: from the
    sample leaving the reversal to the next turning point, the friction change ``dF`` and the
    displacement ``dx``, both positive in the new direction; ``D`` = new level − F_b, the
    level being the median friction over the middle third of the stroke; ``speed``, the
    velocity in the new direction along it."""

    dF: np.ndarray
    dx: np.ndarray
    D: float
    speed: np.ndarray


def crossings(prep: Prepared) -> list[Crossing]:
    """Every crossing of the recording whose swing D is at least 20 friction-noise sds and
    whose stroke has a usable middle third of at least 5 samples (none without a measured
    friction)."""
    rec, th = prep.rec, prep.th
    if prep.friction is None:
        return []
    out = []
    for a0, b0 in prep.chunks:
        x = rec.position[a0:b0]
        F = prep.friction[a0:b0]
        v = prep.velocity[a0:b0]
        ok = prep.usable[a0:b0]
        turns = turning_points(x, th.x_turn)
        for k in range(1, len(turns) - 1):
            r, nxt = turns[k], turns[k + 1]
            direction = np.sign(x[nxt] - x[r])
            if direction == 0 or not ok[r]:
                continue
            # leave the reversal from its last sample (a dwell holds the extremum)
            at = np.flatnonzero(direction * (x[r:nxt] - x[r]) <= 0.5 * th.x_turn / 6.0)
            s = r + (int(at[-1]) if len(at) else 0)
            # F_b: friction at the reversal (mean over the dwell, or the last samples before it)
            lo = max(turns[k - 1], r - 2 * th.window)
            pre = F[lo:s + 1][np.abs(v[lo:s + 1]) <= th.v_floor]
            Fb = float(np.mean(pre)) if len(pre) >= 3 else float(F[s])
            # the new sliding level: friction over the steady middle of the stroke
            mid = slice(s + (nxt - s) // 3, s + 2 * (nxt - s) // 3)
            if mid.stop - mid.start < 5 or not np.all(ok[mid]):
                continue
            level = float(np.median(F[mid]))
            D = direction * (level - Fb)
            if D < 20 * th.f_noise:
                continue
            out.append(Crossing(dF=direction * (F[s:nxt] - Fb), dx=direction * (x[s:nxt] - x[s]), D=float(D),
                                speed=direction * v[s:nxt]))
    return out


PEAK_DROP = 0.05  # of the swing D (and at least 3 friction-noise sds): a fall from a crossing's peak that ends it


def sliding_swing(c: Crossing, window: int) -> np.ndarray:
    """Along a crossing, the swing to the sliding friction at the speed of each sample, as the
    same stroke shows it after its fastest point (slowing down towards the next reversal, far
    from the last one): for a stroke whose speed varies (a crank's sinusoid) the friction
    slides at S(v) + σ2·v of the speed it has, not at a level. nan where the stroke never
    slides that slowly (or fast) after its fastest point. That point is the last where the
    speed, averaged over ``window`` samples, is within 5 % of its top: on a stroke at a
    constant speed reached within presliding, the one fastest noisy sample may lie inside
    presliding, and the "sliding" friction read after it would hold presliding values."""
    smooth = moving_average(c.speed, max(int(window), 3))
    peak = float(np.max(smooth))
    top = int(np.flatnonzero(smooth >= peak - 0.05 * abs(peak))[-1])
    sp, f = c.speed[top:], c.dF[top:]
    order = np.argsort(sp)
    sp, f = sp[order], f[order]
    out = np.full(len(c.dF), np.nan)
    if len(sp) < 2:
        return out
    inside = (c.speed >= sp[0]) & (c.speed <= sp[-1])
    out[inside] = np.interp(c.speed[inside], sp, f)
    return out


def crossing_end(c: Crossing, th: Thresholds) -> tuple[int, float]:
    """Where a crossing has caught up with sliding, and its swing there: the first sample past
    90 % of the swing to the sliding friction at the speed it has reached, as the same stroke
    shows it after its fastest point (``sliding_swing``) — or past 90 % of the swing D to the
    stroke's level, if that comes first or the stroke never slides that slowly. Where the
    friction falls back from a peak first (F_s above the sliding friction reached: a contact
    that sticks, then slips), past 90 % of the swing to that peak; the peak is sought on the
    friction averaged over the smoothing window, so that noise about a flat top makes none.
    Why the speed reached, not the level: on a stroke still speeding up (a crank's sinusoid,
    or a fast level reached through a slow ramp) the level holds the viscous σ2·v of a speed
    not yet reached, and a crossing run to it is gross sliding — on a joint made apart, swept
    over constant speeds through a 150 °/s² ramp, one crossing ran 0.023 rad (100× the others)
    to its level, and the transition curve's knots were placed along it. (0, D) if it never
    gets there."""
    D = c.D
    past = np.flatnonzero(c.dF > 0.9 * D)
    swing = sliding_swing(c, th.window)
    near = np.flatnonzero((swing > 20 * th.f_noise) & (c.dF > 0.9 * swing))
    if len(near) and (not len(past) or near[0] < past[0]):
        D = float(swing[near[0]])
        past = near
    smooth = moving_average(c.dF, max(th.window, 3))
    top = np.maximum.accumulate(smooth)
    fell = np.flatnonzero(top - smooth > max(PEAK_DROP * D, 3.0 * th.f_noise))
    if len(fell) and (not len(past) or fell[0] < past[0]):
        D = float(np.max(smooth[:fell[0] + 1]))
        past = np.flatnonzero(c.dF > 0.9 * D)
    return (int(past[0]) if len(past) else 0), D


MIN_BRANCH_POINTS = 5  # a motion-driven branch needs this many samples before its end


def motion_branches(prep: Prepared, *, min_points: int = MIN_BRANCH_POINTS) -> list[Branch]:
    """Reversals of a prescribed motion with measured friction (``crossings``): each crossing,
    up to its end (``crossing_end``), is one branch with the displacement from the reversal as
    input and the friction change as the measured output. D = the swing to where sliding
    takes over (eq. (5) at the sliding velocity reached)."""
    out = []
    for c in crossings(prep):
        m, D = crossing_end(c, prep.th)
        if m < min_points or c.dx[m - 1] <= prep.th.x_turn:
            continue
        out.append(Branch(force=c.dF[:m], displacement=c.dx[:m], D=D, driven="motion"))
    return out


def crossing_range(c: Crossing, th: Thresholds) -> float:
    """How far a crossing travels before the friction has caught up with sliding
    (``crossing_end``); nan if it never does."""
    m, _ = crossing_end(c, th)
    return float(c.dx[m]) if m else math.nan
