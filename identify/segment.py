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
        raise ValueError(f"{rec.source}: needs a force or friction column for constant-velocity levels")
    v = _smooth(velocity_of(rec), 9)
    out_v, out_F, out_var, out_n = [], [], [], []
    start = 0
    n = len(v)
    while start < n:
        if abs(v[start]) < v_floor:
            start += 1
            continue
        ref = v[start]
        end = start
        while end < n and abs(v[end] - ref) <= rel_tol * abs(ref) and np.sign(v[end]) == np.sign(ref):
            end += 1
            if end - start > 20:
                ref = np.median(v[start:end])
        travel = abs(rec.position[end - 1] - rec.position[start]) if rec.position is not None else np.inf
        if end - start >= min_samples and travel >= min_travel:
            s = start + int(settle_fraction * (end - start))
            seg = slice(s, end - 5)
            out_v.append(float(np.mean(v[seg])))
            out_F.append(float(np.mean(F[seg])))
            cnt = seg.stop - seg.start
            out_var.append(float(np.var(F[seg], ddof=1) / cnt))
            out_n.append(cnt)
        start = max(end, start + 1)
    return Levels(np.array(out_v), np.array(out_F), np.array(out_var), np.array(out_n))


def detect_noise(x: np.ndarray) -> object:
    """Encoder-like (values on a grid of one step) → ``Quantized``; else ``Gaussian`` with σ
    from the spread of second differences (a slow signal's curvature is negligible there)."""
    d = np.abs(np.diff(x))
    d = d[d > 0]
    if len(d):
        q = np.min(d)
        k = x / q
        if q > 0 and np.max(np.abs(k - np.round(k))) < 1e-6 and len(np.unique(np.round(k))) < 0.5 * len(x):
            return Quantized(step=float(q), jitter=float(0.25 * q))
    sigma = float(np.std(np.diff(x, 2)) / np.sqrt(6.0))
    return Gaussian(sigma=max(sigma, 1e-15))


def presliding_branches(rec: Recording, Fs_pos: float, Fs_neg: float, *, v_max: float = 2e-3,
                        min_points: int = 20, decimate: int = 1) -> list[Branch]:
    """Branches of the applied force between its turning points, where the joint stays in
    presliding (|v| < ``v_max``). Each branch is cut where it would close the previous
    internal loop (passing the older turning point), since past it the path follows an older
    curve. D = F_s(direction) − F_b with F_b the force at the reversal."""
    if rec.force is None or rec.position is None:
        raise ValueError(f"{rec.source}: presliding branches need position and applied force columns")
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
