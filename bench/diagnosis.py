"""The whole diagnose run (base fit, screening, refits, report numbers) on a 100,000-sample
recording with a hidden effect."""

from __future__ import annotations

import io
import time

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.diagnose import diagnose
from leuven_friction.identify.fit import fit_recordings


def bench_diagnosis(quick: bool = False, progress=print) -> dict:
    from synth.effects import make_recording

    samples = 100_000
    df, _ = make_recording("position_periodic", seed=5, samples=samples)
    buf = io.StringIO()
    df.to_csv(buf, index=False)
    content = buf.getvalue().encode()
    progress(f"diagnosing a {samples}-sample recording")
    t0 = time.perf_counter()
    rec = load_recording(content, name="bench.csv")
    d = diagnose(rec, fit_recordings([rec]).params)
    elapsed = time.perf_counter() - t0
    return {"diagnose_100k_s": elapsed, "diagnose_effect": d.effect,
            "diagnose_rms_reduction": 1 - d.rms_after / d.rms_before}
