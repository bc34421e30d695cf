"""Fit speed: the sample session, and a ~1,000,000-row robot-joint recording from the independent
generator (synth/recordings.py) fitted with the output-error refinement."""

from __future__ import annotations

import io
import time
from pathlib import Path

import numpy as np
import pandas as pd

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.fit import fit_recordings

ROOT = Path(__file__).resolve().parent.parent


def big_session(rows: int = 1_000_000) -> bytes:
    from synth.samples import PRESLIDING_LEVELS, constant_velocity, force_ramps

    cv = constant_velocity(rate=2000.0)
    n_pre = rows - len(cv)
    levels = PRESLIDING_LEVELS
    duration = np.sum(np.abs(np.diff(levels))) / 2.0
    t, x, f = force_ramps(levels, sample=duration / n_pre)
    rng = np.random.default_rng(5)
    pre = pd.DataFrame({"time": t, "position": x + rng.normal(0, 5e-8, len(t)), "torque": f})
    cv = cv.assign(time=cv["time"] + t[-1] + 1e-3, position=cv["position"] + x[-1])
    df = pd.concat([pre, cv], ignore_index=True).iloc[:rows]
    buf = io.StringIO()
    df.to_csv(buf, index=False, float_format="%.10g")
    return buf.getvalue().encode()


def generator_session(rows: int) -> bytes:
    """A robot-joint session from the independent generator (synth/recordings.py) at the
    sample rate that gives about ``rows`` rows, as CSV bytes."""
    from synth.recordings import make_recording

    probe, _ = make_recording("robot_joint", 11, rate=500.0)
    rate = min(10_000.0, 500.0 * rows / len(probe))
    df, _ = make_recording("robot_joint", 11, rate=rate)
    buf = io.StringIO()
    df.iloc[:rows].to_csv(buf, index=False, float_format="%.10g")
    return buf.getvalue().encode()


def bench_identification(quick: bool = False, progress=print) -> dict:
    """Fit times: the sample session, and a ~1,000,000-row generator recording (10 kHz robot
    joint) with the output-error refinement, against a baseline run in the same process
    (pandas parsing the same CSV bytes)."""
    path = ROOT / "sample_data" / "session_mixed.csv"
    t0 = time.perf_counter()
    fit_recordings([load_recording(path)])
    t_sample = time.perf_counter() - t0
    rows = 200_000 if quick else 1_000_000
    progress(f"making a {rows}-row recording")
    content = generator_session(rows)
    t0 = time.perf_counter()
    pd.read_csv(io.BytesIO(content))
    t_parse = time.perf_counter() - t0
    progress("fitting it")
    t0 = time.perf_counter()
    rec = load_recording(content, name="big_session.csv")
    t_load = time.perf_counter() - t0
    res = fit_recordings([rec])
    t_big = time.perf_counter() - t0
    return {
        "fit_sample_session_s": t_sample,
        "fit_big_recording_s": t_big,
        "fit_big_recording_load_s": t_load,
        "fit_big_recording_rows": len(rec),
        "fit_big_recording_over_csv_parse": t_big / t_parse,
        "fit_big_recording_refined": bool(res.refinement.get("done")),
        "fit_big_recording_levels": int(len(res.levels.velocity)),
        "fit_big_recording_branches": int(res.n_branches),
    }
