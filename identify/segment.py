"""Cutting a recording into the pieces the estimators need, without hand work.

* constant-velocity segments (both directions) → ``markov.Levels``;
* presliding branches (slow applied-force ramps between reversals) → ``mle.Branch``;
* the noise model of the position signal (quantised encoder or Gaussian sensor).
"""

from __future__ import annotations

import numpy as np

from .data import Recording, velocity_of
from .markov import Levels
from .mle import Branch, Gaussian, Quantized
from .errors import IdentificationError


def _smooth(a, w):
    if w <= 1:
        return a
    k = np.ones(w) / w
    return np.convolve(a, k, mode="same")


def constant_velocity_levels(rec: Recording, *, rel_tol: float = 0.03, min_samples: int = 50,
                             v_floor: float = 2e-4, min_travel: float = 1e-3, settle_fraction: float = 0.4) -> Levels:
    """Runs where the (smoothed) velocity stays within ``rel_tol`` of its run median and above
    ``v_floor`` over at least ``min_travel`` of motion (presliding creep never travels that
    far: Table II's curve ends at 5e-4 rad); the first ``settle_fraction`` of each run is dropped (the approach to sliding
    is slow at low speed). Friction: the friction column if present, else the applied force
    (at constant velocity I·ẍ = 0, so f = F)."""
    F = rec.friction if rec.friction is not None else rec.force
    if F is None:
        raise IdentificationError(f"{rec.source}: needs a force or friction column for constant-velocity levels")
    v = _smooth(velocity_of(rec), 9)
    w = 10
    steady = np.abs(v) > v_floor
    same = np.zeros(len(v), dtype=bool)
    same[w:] = np.abs(v[w:] - v[:-w]) <= rel_tol * np.abs(v[w:])
    steady &= same
    edges = np.flatnonzero(np.diff(np.concatenate([[0], steady.astype(np.int8), [0]])))
    out_v, out_F, out_var, out_n = [], [], [], []
    for start, end in zip(edges[::2], edges[1::2]):
        if end - start < min_samples:
            continue
        s = start + int(settle_fraction * (end - start))
        seg = slice(s, end - 5)
        vs = v[seg]
        # one level, not a slow acceleration: the whole kept part within rel_tol of its median
        if np.ptp(vs) > 2 * rel_tol * abs(np.median(vs)):
            continue
        travel = abs(rec.position[end - 1] - rec.position[start]) if rec.position is not None else np.inf
        if travel < min_travel:
            continue
        cnt = seg.stop - seg.start
        out_v.append(float(np.mean(vs)))
        out_F.append(float(np.mean(F[seg])))
        out_var.append(float(np.var(F[seg], ddof=1) / cnt))
        out_n.append(cnt)
    return Levels(np.array(out_v), np.array(out_F), np.array(out_var), np.array(out_n))


def detect_noise(x) -> object:
    """Encoder-like (values on a grid of one step) → ``Quantized``; else ``Gaussian`` with σ
    from the spread of second differences (a slow signal's curvature is negligible there;
    white noise of σ gives second differences of variance 6σ²)."""
    parts = [np.asarray(a, dtype=float) for a in (x if isinstance(x, (list, tuple)) else [x])]
    x = np.concatenate(parts)
    d = np.abs(np.concatenate([np.diff(a) for a in parts]))
    d = d[d > 0]
    if len(d):
        q = np.min(d)
        k = x / q
        if q > 0 and np.max(np.abs(k - np.round(k))) < 1e-6 and len(np.unique(np.round(k))) < 0.5 * len(x):
            return Quantized(step=float(q), jitter=float(0.25 * q))
    # robust (median absolute deviation): velocity steps elsewhere in the file are outliers
    d2 = np.concatenate([np.diff(a, 2) for a in parts if len(a) > 2])
    sigma = float(1.4826 * np.median(np.abs(d2 - np.median(d2))) / np.sqrt(6.0))
    return Gaussian(sigma=max(sigma, 1e-15))


def presliding_branches(rec: Recording, Fs_pos: float, Fs_neg: float, *, v_max: float = 2e-4,
                        min_points: int = 20, decimate: int = 1) -> list[Branch]:
    """Branches of the applied force between its turning points, where the joint stays in
    presliding (|v| < ``v_max``). Each branch is cut where it would close the previous
    internal loop (passing the older turning point), since past it the path follows an older
    curve. D = F_s(direction) − F_b with F_b the force at the reversal."""
    if rec.force is None or rec.position is None:
        raise IdentificationError(f"{rec.source}: presliding branches need position and applied force columns")
    f = rec.force
    fs = _smooth(f, 5)
    df = np.sign(np.diff(fs))
    for i in range(1, len(df)):  # hold the direction through flat stretches
        if df[i] == 0:
            df[i] = df[i - 1]
    turns = [0] + list(np.flatnonzero(df[1:] != df[:-1]) + 1) + [len(f) - 1]
    v = np.abs(_smooth(velocity_of(rec), 9))
    branches = []
    for k in range(len(turns) - 1):
        a, b = turns[k], turns[k + 1]
        if b - a < min_points:
            continue
        direction = np.sign(f[b] - f[a])
        if direction == 0:
            continue
        fb = f[a]
        dF = direction * (f[a:b + 1] - fb)
        limit = np.inf
        if k >= 1:
            prev = f[turns[k - 1]]
            if direction * (prev - fb) > 0:
                limit = direction * (prev - fb)
        D = (Fs_pos if direction > 0 else -Fs_neg) - direction * fb
        if D <= 0:
            continue
        keep = (dF >= 0) & (dF < min(limit, 0.97 * D)) & (v[a:b + 1] < v_max)
        idx = np.flatnonzero(keep)
        if len(idx) < min_points:
            continue
        idx = idx[: np.argmax(np.diff(np.concatenate([idx, [idx[-1] + 2]])) > 1) + 1]  # contiguous from the reversal
        idx = idx[::decimate]
        if len(idx) < min_points:
            continue
        branches.append(Branch(force=dF[idx], displacement=direction * rec.position[a:b + 1][idx], D=float(D)))
    return branches
