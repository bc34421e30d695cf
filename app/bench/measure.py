"""Run a ``leuven-friction`` command in a fresh interpreter and report what a user waits for:
wall time end to end (start-up, imports and compiled-code loading included), the CPU time of
that process (less sensitive than wall time to other load on a shared machine) and its peak
resident memory."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time

_WRAPPER = """
import json, os, resource, sys
from leuven_friction.app.cli import main
code = main(sys.argv[1:])
with open(os.environ["LEUVEN_FRICTION_BENCH_OUT"], "w") as fh:
    u = resource.getrusage(resource.RUSAGE_SELF)
    # VmHWM, not ru_maxrss: Linux carries ru_maxrss over from the parent through fork/exec
    hwm = [ln for ln in open("/proc/self/status") if ln.startswith("VmHWM:")] if os.path.exists("/proc/self/status") else []
    peak = float(hwm[0].split()[1]) / 1024.0 if hwm else u.ru_maxrss / 1024.0
    json.dump({"code": code, "peak_rss_mb": peak, "cpu_seconds": u.ru_utime + u.ru_stime}, fh)
"""


def run_command(argv: list[str], cwd: str | None = None) -> dict:
    """{"seconds", "cpu_seconds", "peak_rss_mb", "code"} of ``leuven-friction ARGV`` in a child process."""
    with tempfile.NamedTemporaryFile("r", suffix=".json", delete=False) as fh:
        out = fh.name
    try:
        env = dict(os.environ, LEUVEN_FRICTION_BENCH_OUT=out)
        t0 = time.perf_counter()
        r = subprocess.run([sys.executable, "-c", _WRAPPER, *argv], cwd=cwd, env=env, capture_output=True, text=True)
        seconds = time.perf_counter() - t0
        if r.returncode != 0:
            last = (r.stderr.strip().splitlines() or ["?"])[-1]
            raise RuntimeError(f"leuven-friction {' '.join(argv)} failed ({r.returncode}): {last}")
        with open(out) as fh:
            res = json.load(fh)
    finally:
        os.unlink(out)
    res["seconds"] = seconds
    return res
