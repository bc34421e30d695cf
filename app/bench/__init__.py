"""``leuven-friction bench``: the product's benchmarks, runnable from an installed wheel.

Sections (each a function returning a flat dict of numbers):

* ``simulator``  the kernel against a plain-C port of the same step and against solve_ivp;
* ``startup``    the command line's start-up (``--help``, an argument error);
* ``io``         ``simulate --input`` end to end, CSV → CSV and Parquet → Parquet;
* ``scale``      fit and simulate on 1e4 … 5e6 rows, time and peak memory per size.

Benchmarks of the checkout (``bench/`` beside the sources: identification and diagnosis
suites built on its own data generators) run too when they can be imported.
"""

from __future__ import annotations

import importlib
import time

SECTIONS = ("simulator", "startup", "io", "scale")


def _section(name: str):
    mod = importlib.import_module(f".{name}", __name__)
    return getattr(mod, f"bench_{name}")


def run_all(quick: bool = False, progress=print, sections=SECTIONS) -> dict:
    results: dict = {}
    for name in sections:
        progress(f"== {name}")
        t0 = time.perf_counter()
        results.update(_section(name)(quick=quick, progress=progress))
        results[f"{name}_section_s"] = time.perf_counter() - t0
    for module, fn in (("bench.identification", "bench_identification"), ("bench.diagnosis", "bench_diagnosis")):
        try:
            extra = getattr(importlib.import_module(module), fn)
        except ImportError as e:
            note = f"{module}: not importable here ({e}); skipped (it is a tool of the source checkout)"
            progress(note)
            results.setdefault("notes", []).append(note)
            continue
        progress(f"== {module}")
        results.update(extra(quick, progress))
    return results
