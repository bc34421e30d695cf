"""The plain-C port of the displacement-driven kernel (``leuven_step.c``), compiled with the
system's C compiler at ``-O2`` and called through ctypes: the benchmark's measure of how far
the compiled Python kernel is from the same step in C."""

from __future__ import annotations

import ctypes
import hashlib
import os
import shutil
import subprocess
import tempfile
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

SOURCE = "leuven_step.c"


@dataclass(frozen=True)
class CPort:
    path: Path
    compiler: str
    _fn: object

    def run_displacement(self, model: int, p, tz, tF, st, t, x, F, Fh, Z, V) -> None:
        d = ctypes.POINTER(ctypes.c_double)

        def ptr(a):
            assert a.dtype == np.float64 and a.flags.c_contiguous
            return a.ctypes.data_as(d)

        self._fn(model, ptr(p), ptr(tz), ptr(tF), len(tz), ptr(st), len(st), ptr(t), ptr(x), len(t),
                 ptr(F), ptr(Fh), ptr(Z), ptr(V))


def source_text() -> str:
    return resources.files(__package__).joinpath(SOURCE).read_text()


def build() -> CPort | str:
    """The compiled port, or the reason there is none (no compiler, or it failed)."""
    cc = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if not cc:
        return "no C compiler (cc) on this machine: the C comparison is skipped"
    src = source_text()
    key = hashlib.sha256((cc + src).encode()).hexdigest()[:16]
    out_dir = Path(tempfile.gettempdir()) / f"leuven-friction-cport-{key}"
    lib = out_dir / "leuven_step.so"
    if not lib.exists():
        out_dir.mkdir(parents=True, exist_ok=True)
        c_file = out_dir / SOURCE
        c_file.write_text(src)
        tmp = out_dir / f"leuven_step.{os.getpid()}.so"
        r = subprocess.run([cc, "-O2", "-shared", "-fPIC", str(c_file), "-o", str(tmp), "-lm"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            return f"{cc} -O2 failed on {SOURCE}: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else r.returncode}"
        os.replace(tmp, lib)
    so = ctypes.CDLL(str(lib))
    fn = so.run_displacement
    d = ctypes.POINTER(ctypes.c_double)
    L = ctypes.c_long
    fn.argtypes = [L, d, d, d, L, d, L, d, d, L, d, d, d, d]
    fn.restype = None
    return CPort(lib, cc, fn)
