"""Start-up: help and argument errors must not load the heavy modules (numba, pandas, scipy,
the web stack). Checked on sys.modules in a fresh interpreter, not on time."""

import json
import subprocess
import sys

import pytest

HEAVY = ("numba", "pandas", "scipy", "viser", "plotly", "pyarrow", "yaml")

PROBE = """
import sys, json
from leuven_friction.app.cli import main
try:
    code = main({argv!r})
except SystemExit as e:
    code = e.code
print(json.dumps({{"code": code, "heavy": [m for m in {heavy!r} if m in sys.modules]}}))
"""


@pytest.mark.parametrize("argv, code", [(["--help"], 0), (["simulate", "--help"], 0), (["fit", "--help"], 0),
                                        (["bench", "--help"], 0), (["simulate", "--model", "nonsense"], 2),
                                        (["no-such-command"], 2)])
def test_help_and_argument_errors_load_no_heavy_module(argv, code):
    r = subprocess.run([sys.executable, "-c", PROBE.format(argv=argv, heavy=HEAVY)], capture_output=True, text=True)
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["code"] == code  # help succeeds, an argument error is argparse's exit status 2
    assert out["heavy"] == []


def test_model_package_loads_its_names_on_first_use():
    code = ("import sys; import leuven_friction.model as m; a = 'numba' in sys.modules; "
            "m.simulate_displacement; print(a, 'numba' in sys.modules)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.stdout.split() == ["False", "True"]
