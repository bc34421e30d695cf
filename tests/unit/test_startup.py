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


def test_python_dash_m_runs_the_same_command_line():
    r = subprocess.run([sys.executable, "-m", "leuven_friction", "fit", "--help"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.startswith("usage: leuven-friction fit"), (r.returncode, r.stderr)
    r = subprocess.run([sys.executable, "-m", "leuven_friction", "no-such-command"], capture_output=True, text=True)
    assert r.returncode == 2 and "invalid choice" in r.stderr


def test_model_package_loads_its_names_on_first_use():
    code = ("import sys; import leuven_friction.model as m; a = 'numba' in sys.modules; "
            "m.simulate_displacement; print(a, 'numba' in sys.modules)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.stdout.split() == ["False", "True"]


def test_a_first_run_says_the_kernels_are_being_compiled(tmp_path, monkeypatch):
    # numba compiles the kernels on their first use on a machine and caches them: a command says
    # so where no cache is found (that run takes 30–60 s more), and not once one is there
    import importlib.util
    import io
    from types import SimpleNamespace

    import numpy as np

    from leuven_friction.app.cli import say_if_compiling
    from leuven_friction.model import default_params, simulate_displacement

    simulate_displacement(default_params(), np.arange(3) * 1e-3, np.zeros(3))  # the real cache exists now
    assert not say_if_compiling(out=io.StringIO())
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    for stem in ("kernels", "diagnose"):
        (pkg / f"{stem}.py").write_text("")
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name: SimpleNamespace(origin=str(pkg / f"{name.rsplit('.', 1)[-1]}.py")))
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "cache"))
    said = io.StringIO()
    assert say_if_compiling(out=said) and "compiling the simulator's kernels" in said.getvalue()
    (pkg / "__pycache__").mkdir()
    (pkg / "__pycache__" / "kernels.run_force-666.py311.nbi").write_text("")
    assert not say_if_compiling(out=io.StringIO())
    # the diagnosis's own kernels are compiled on its first run, after a fit compiled the
    # simulator's: that run is said too, and not once they are cached
    assert say_if_compiling("identify.diagnose", out=io.StringIO())
    (pkg / "__pycache__" / "diagnose._play-374.py311.nbi").write_text("")
    assert not say_if_compiling("identify.diagnose", out=io.StringIO())


def test_a_diagnosis_in_friction_asks_only_for_the_kernels_it_runs(monkeypatch):
    # the "compiling" note looks for the caches of the kernels a command will run: a comparison
    # in friction never runs the position windows' kernel, so naming it there (never cached by
    # such runs) said "compiling" on every diagnosis of a new user's joint
    import leuven_friction.model.windows as windows
    from leuven_friction.app.cli import diagnosis_kernels
    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import Settings, diagnose
    from leuven_friction.identify.fit import fit_recordings

    def never(*args, **kw):
        raise AssertionError("a comparison in friction ran the position windows' kernel")

    rec = load_recording("sample_data/constant_velocity.csv")  # an applied torque: positions could be compared
    base = fit_recordings([rec], refine=False).params
    monkeypatch.setattr(windows, "simulate_windows", never)
    assert diagnose(rec, base).space == "friction"
    assert "model.windows" not in diagnosis_kernels("friction")
    assert "model.windows" in diagnosis_kernels("position")
    with pytest.raises(AssertionError, match="ran the position windows"):
        diagnose(rec, base, settings=Settings(space="position"))
