"""The benchmark ships with the product: it imports nothing from the source checkout, and its
C reference is package data."""

import shutil
import subprocess
import sys

import numpy as np
import pytest


def test_product_bench_imports_nothing_from_the_checkout(tmp_path):
    code = ("import sys, leuven_friction.app.bench as b\n"
            "import leuven_friction.app.bench.simulator, leuven_friction.app.bench.io, leuven_friction.app.bench.scale\n"
            "import leuven_friction.app.bench.startup, leuven_friction.app.bench.cport\n"
            "print(sorted(m for m in sys.modules if m == 'bench' or m.startswith(('bench.', 'synth'))))\n"
            "print(len(leuven_friction.app.bench.cport.source_text()) > 1000)")
    r = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout.split("\n")[:2] == ["[]", "True"]


def test_c_port_matches_the_kernel_bit_for_bit(kuka, kuka_lugre):
    from leuven_friction.app.bench.cport import build
    from leuven_friction.app.bench.simulator import _run_c, _run_kernel, motions
    from leuven_friction.model.simulate import pack

    cport = build()
    if isinstance(cport, str):
        # without a C compiler the benchmark skips the port with a note; with one, a port that
        # fails to compile is a defect of the shipped source
        if shutil.which("cc") or shutil.which("gcc") or shutil.which("clang"):
            pytest.fail(f"a C compiler is present, yet the port did not build: {cport}")
        pytest.skip(cport)
    for params in (kuka, kuka_lugre):
        code, p, kind, tz, tF = pack(params)
        for t, x in motions(20_000).values():
            a = [np.empty(len(t)) for _ in range(4)]
            b = [np.empty(len(t)) for _ in range(4)]
            _, st_a = _run_kernel(code, p, kind, tz, tF, params, t, x, a)
            _, st_b = _run_c(cport, code, p, tz, tF, params, t, x, b)
            for u, w in zip(a, b):
                np.testing.assert_array_equal(u, w)
            np.testing.assert_array_equal(st_a, st_b)
