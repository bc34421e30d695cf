"""Start-up of the command line: ``leuven-friction --help`` and an argument error, each in a
fresh interpreter, with the heavy modules the process ended up importing."""

from __future__ import annotations

import json
import subprocess
import sys
import time

HEAVY = ("numba", "pandas", "scipy", "viser", "plotly", "pyarrow")

_PROBE = """
import sys, json
from leuven_friction.app.cli import main
try:
    main({argv!r})
except SystemExit:
    pass
sys.stderr.flush()
print(json.dumps([m for m in {heavy!r} if m in sys.modules]), file=sys.__stdout__)
"""


def _time(argv: list[str], repeat: int) -> tuple[float, list[str]]:
    best = float("inf")
    loaded: list[str] = []
    for _ in range(repeat):
        code = _PROBE.format(argv=argv, heavy=HEAVY)
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
        best = min(best, time.perf_counter() - t0)
        loaded = json.loads(r.stdout.strip().splitlines()[-1]) if r.stdout.strip() else ["?"]
    return best, loaded


def bench_startup(quick: bool = False, progress=print) -> dict:
    repeat = 3 if quick else 5
    t_bare = min(_bare() for _ in range(repeat))
    t_help, mods_help = _time(["--help"], repeat)
    t_err, mods_err = _time(["simulate", "--model", "nonsense"], repeat)
    progress(f"--help {t_help:.3f} s, argument error {t_err:.3f} s (bare interpreter {t_bare:.3f} s)")
    return {
        "startup_help_s": t_help,
        "startup_argument_error_s": t_err,
        "startup_bare_python_s": t_bare,
        "startup_help_heavy_modules": mods_help,
        "startup_argument_error_heavy_modules": mods_err,
    }


def _bare() -> float:
    t0 = time.perf_counter()
    subprocess.run([sys.executable, "-c", "pass"], capture_output=True)
    return time.perf_counter() - t0
