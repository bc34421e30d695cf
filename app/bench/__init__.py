"""``leuven-friction bench``: the product's benchmarks, runnable from an installed wheel.

Sections (each a function returning a flat dict of numbers):

* ``simulator``  the kernel against a plain-C port of the same step and against solve_ivp;
* ``startup``    the command line's start-up (``--help``, an argument error);
* ``io``         ``simulate --input`` end to end, CSV → CSV and Parquet → Parquet;
* ``scale``      fit and simulate on 1e4 … 5e6 rows, time and peak memory per size.

and two sections of the source checkout (``bench/`` beside the sources, built on its own data
generators), run when they can be imported and skipped with a note in an installed copy:

* ``identification``  fit of a 1,000,000-row generator recording with the refinement;
* ``diagnosis``       the whole diagnosis of a 100,000-sample recording.
"""

from __future__ import annotations

import importlib
import time

SECTIONS = ("simulator", "startup", "io", "scale")
CHECKOUT_SECTIONS = {"identification": ("bench.identification", "bench_identification"),
                     "diagnosis": ("bench.diagnosis", "bench_diagnosis")}
ALL_SECTIONS = SECTIONS + tuple(CHECKOUT_SECTIONS)


def _section(name: str):
    mod = importlib.import_module(f".{name}", __name__)
    return getattr(mod, f"bench_{name}")


def run_all(quick: bool = False, progress=print, sections=ALL_SECTIONS) -> dict:
    results: dict = {}
    for name in sections:
        t0 = time.perf_counter()
        if name in CHECKOUT_SECTIONS:
            module, fn = CHECKOUT_SECTIONS[name]
            try:
                run = getattr(importlib.import_module(module), fn)
            except ModuleNotFoundError as e:
                if e.name not in ("bench", module):  # a broken import inside the suite is a bug
                    raise
                note = f"{name}: {module} is not importable here; skipped (it is a tool of the source checkout)"
                progress(note)
                results.setdefault("notes", []).append(note)
                continue
            progress(f"== {name} ({module})")
            results.update(run(quick, progress))
        else:
            progress(f"== {name}")
            results.update(_section(name)(quick=quick, progress=progress))
        results[f"{name}_section_s"] = time.perf_counter() - t0
    return results
