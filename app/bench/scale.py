"""Cost against size: ``fit`` and ``simulate --input`` on recordings of 1e4, 1e5, 1e6 and
5e6 rows (--quick: up to 1e6), each in a fresh process, with wall time and peak resident
memory. The recording is one test session stored as two files, force ramps and
constant-velocity runs (``recording.session_files``); ``simulate`` is driven by the ramps and
runs together as one file.

Cost per row (seconds per million rows) is reported next to each size: linear growth shows
as a constant."""

from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np

from .measure import run_command

SIZES = (10_000, 100_000, 1_000_000, 5_000_000)


def bench_scale(quick: bool = False, progress=print, sizes=None) -> dict:
    from ...identify.io import write_table
    from .recording import session_files

    sizes = sizes or (SIZES[:3] if quick else SIZES)
    out: dict = {"scale_rows": list(sizes)}
    with tempfile.TemporaryDirectory(prefix="leuven-friction-scale-") as tmp:
        d = Path(tmp)
        for n in sizes:
            files = session_files(n)
            paths = []
            for name, cols in files.items():
                p = d / f"{name}_{n}.csv"
                write_table(cols, p)
                paths.append(str(p))
            whole = d / f"session_{n}.csv"
            ramps, runs = files["ramps"], files["runs"]
            write_table({"time": np.concatenate([ramps["time"], ramps["time"][-1] + 1e-3 + runs["time"]]),
                         "position": np.concatenate([ramps["position"], runs["position"]])}, whole)
            sim = run_command(["simulate", "--input", str(whole), "--out", str(d / f"sim_{n}.csv")])
            progress(f"simulate {n} rows: {sim['seconds']:.2f} s ({sim['cpu_seconds']:.2f} s CPU), "
                     f"peak {sim['peak_rss_mb']:.0f} MB")
            fit = run_command(["fit", *paths, "--out", str(d / f"fit_{n}.yaml")])
            progress(f"fit {n} rows: {fit['seconds']:.2f} s ({fit['cpu_seconds']:.2f} s CPU), "
                     f"peak {fit['peak_rss_mb']:.0f} MB")
            for what, r in (("simulate", sim), ("fit", fit)):
                out[f"scale_{what}_{n}_s"] = r["seconds"]
                out[f"scale_{what}_{n}_cpu_s"] = r["cpu_seconds"]
                out[f"scale_{what}_{n}_s_per_million_rows"] = r["seconds"] / n * 1e6
                out[f"scale_{what}_{n}_peak_rss_mb"] = r["peak_rss_mb"]
            for f in d.iterdir():
                f.unlink()
    return out
