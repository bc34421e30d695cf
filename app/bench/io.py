"""``simulate --input`` end to end on a 1,000,000-row recording (100,000 with --quick):
CSV → CSV and Parquet → Parquet, each in a fresh process as a user runs it, start-up and
compiled-code loading included. Reading and writing are also timed alone, in this process."""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from .measure import run_command


def _recording(n: int) -> dict:
    from .simulator import DT, displacement

    t = np.arange(n) * DT
    rng = np.random.default_rng(11)
    return {"time": t, "position": displacement(t) + rng.normal(0.0, 5e-8, n), "torque": rng.normal(0.0, 1.0, n)}


def bench_io(quick: bool = False, progress=print) -> dict:
    from ...identify.io import read_table_file, write_table

    n = 100_000 if quick else 1_000_000
    out: dict = {"io_rows": n}
    formats = ["csv"]
    try:
        import pyarrow  # noqa: F401

        formats.append("parquet")
    except ImportError:
        out["io_note"] = "pyarrow not installed: Parquet skipped (pip install 'leuven-friction[parquet]')"
        progress(out["io_note"])
    cols = _recording(n)
    with tempfile.TemporaryDirectory(prefix="leuven-friction-bench-") as tmp:
        d = Path(tmp)
        for fmt in formats:
            src = d / f"in.{fmt}"
            warm = d / f"warm_in.{fmt}"
            write_table({k: v[:10] for k, v in cols.items()}, warm)  # imports and compiled code loaded
            read_table_file(warm)  # outside the timing
            t0 = time.perf_counter()
            write_table(cols, src)
            out[f"io_write_{fmt}_s"] = time.perf_counter() - t0
            t0 = time.perf_counter()
            read_table_file(src)
            out[f"io_read_{fmt}_s"] = time.perf_counter() - t0
            run_command(["simulate", "--input", str(src), "--out", str(d / f"warm.{fmt}")])  # compiled code cached
            best = min((run_command(["simulate", "--input", str(src), "--out", str(d / f"out.{fmt}")])
                        for _ in range(2 if quick else 3)), key=lambda r: r["seconds"])
            out[f"simulate_{fmt}_to_{fmt}_s"] = best["seconds"]
            out[f"simulate_{fmt}_to_{fmt}_cpu_s"] = best["cpu_seconds"]
            out[f"simulate_{fmt}_to_{fmt}_peak_rss_mb"] = best["peak_rss_mb"]
            progress(f"simulate --input {n} rows {fmt} -> {fmt}: {best['seconds']:.2f} s ({best['cpu_seconds']:.2f} s CPU), "
                     f"peak {best['peak_rss_mb']:.0f} MB (write {out[f'io_write_{fmt}_s']:.2f} s, "
                     f"read {out[f'io_read_{fmt}_s']:.2f} s in-process)")
    return out
