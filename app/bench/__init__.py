"""``leuven-friction bench``: the product's benchmarks, runnable from an installed wheel.

Sections (each a function returning a flat dict of numbers):

* ``simulator``  the kernel against a plain-C port of the same step and against solve_ivp;
* ``startup``    the command line's start-up (``--help``, an argument error);
* ``io``         ``simulate --input`` end to end, CSV → CSV and Parquet → Parquet;
* ``scale``      fit and simulate on 1e4 … 5e6 rows, time and peak memory per size.

and two sections of the source checkout (``bench/`` beside the sources, built on its own data
generators), run when they can be imported and skipped with a note in an installed copy:

* ``identification``  fit of a 1,000,000-row generator recording with the refinement;
* ``diagnosis``       the whole diagnosis of a 100,000-sample tribometer and robot-joint recording.
"""

from __future__ import annotations

import importlib
import sys
import time
from pathlib import Path

SECTIONS = ("simulator", "startup", "io", "scale")
CHECKOUT_SECTIONS = {"identification": ("bench.identification", "bench_identification"),
                     "diagnosis": ("bench.diagnosis", "bench_diagnosis")}
ALL_SECTIONS = SECTIONS + tuple(CHECKOUT_SECTIONS)


def _section(name: str):
    mod = importlib.import_module(f".{name}", __name__)
    return getattr(mod, f"bench_{name}")


def checkout_root() -> Path | None:
    """The source checkout this package runs from (an editable install: ``app/bench/`` sits two
    folders below the repository root), or None for an installed wheel."""
    root = Path(__file__).resolve().parents[2]
    return root if (root / "pyproject.toml").is_file() and (root / "bench" / "__init__.py").is_file() else None


def _checkout_suite(module: str, fn: str):
    """The checkout's benchmark function, or a note saying why it is skipped. Only the checkout's
    own ``bench/`` counts: a distribution that happens to be called ``bench`` is not ours."""
    root = checkout_root()
    if root is None:
        return None, f"{module} is a tool of the source checkout, not of an installed copy; skipped"
    if str(root) not in sys.path:
        sys.path.insert(0, str(root))
    mod = importlib.import_module(module)
    if not Path(mod.__file__).resolve().is_relative_to(root):
        return None, f"{module} resolves to {mod.__file__}, not the checkout's; skipped"
    return getattr(mod, fn), None


def run_all(quick: bool = False, progress=print, sections=ALL_SECTIONS) -> dict:
    results: dict = {}
    for name in sections:
        t0 = time.perf_counter()
        if name in CHECKOUT_SECTIONS:
            run, note = _checkout_suite(*CHECKOUT_SECTIONS[name])
            if run is None:
                progress(f"{name}: {note}")
                results.setdefault("notes", []).append(f"{name}: {note}")
                continue
            progress(f"== {name} ({CHECKOUT_SECTIONS[name][0]})")
            results.update(run(quick, progress))
        else:
            progress(f"== {name}")
            results.update(_section(name)(quick=quick, progress=progress))
        results[f"{name}_section_s"] = time.perf_counter() - t0
    return results
