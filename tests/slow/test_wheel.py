"""The wheel as a user installs it (not editable), in a fresh virtual environment, used from
a directory that is not the checkout and that holds a folder named ``model`` of its own, with
packages named ``model``, ``identify`` and ``app`` installed beside ours.

The venv sees the system's site-packages (``--system-site-packages``) so that numpy, scipy,
numba and the rest need not be downloaded again; our own package is installed into the venv
from the wheel, and the checks prove it is that copy that runs. Building the wheel uses pip's
ordinary isolated build (it fetches setuptools from the package index when the build
environment is not cached)."""

import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
SKIP = shutil.ignore_patterns(".git", "__pycache__", "*.egg-info", "build", "dist", ".hypothesis", "artifacts",
                              ".pytest_cache", "node_modules")


def run(cmd, cwd, env=None, check=True):
    r = subprocess.run([str(c) for c in cmd], cwd=cwd, capture_output=True, text=True, env=env)
    if check:
        assert r.returncode == 0, f"{' '.join(map(str, cmd))}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}"
    return r


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    src = tmp / "src"
    shutil.copytree(ROOT, src, ignore=SKIP)  # the checkout stays clean (no build/, no egg-info)
    run([sys.executable, "-m", "pip", "wheel", ".", "--no-deps", "-q", "-w", tmp / "dist"], cwd=src)
    wheel = next((tmp / "dist").glob("leuven_friction-*.whl"))
    venv = tmp / "venv"
    run([sys.executable, "-m", "venv", "--system-site-packages", venv], cwd=tmp)
    bindir = venv / ("Scripts" if os.name == "nt" else "bin")
    py = bindir / "python"
    run([py, "-m", "pip", "install", "-q", "--no-deps", "--force-reinstall", "--no-index", wheel], cwd=tmp)
    site = Path(run([py, "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"], cwd=tmp).stdout.strip())
    # other distributions' generic top-level packages, each of which breaks on import
    for name in ("model", "identify", "app", "bench"):
        (site / name).mkdir()
        (site / name / "__init__.py").write_text(f"raise ImportError('the unrelated package {name} was imported')\n")
    work = tmp / "user"
    (work / "model").mkdir(parents=True)  # a user's own folder named model
    (work / "model" / "__init__.py").write_text("raise ImportError('the user folder model was imported')\n")
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
    env["PATH"] = f"{bindir}{os.pathsep}{env.get('PATH', '')}"
    return {"wheel": wheel, "venv": venv, "py": py, "cli": bindir / "leuven-friction", "cwd": work, "env": env,
            "site": site}


def test_wheel_holds_one_import_name_and_the_samples(installed):
    names = zipfile.ZipFile(installed["wheel"]).namelist()
    tops = {n.split("/")[0] for n in names if not n.split("/")[0].endswith(".dist-info")}
    assert tops == {"leuven_friction"}  # no generic top-level package (model, app, bench, …)
    assert sum(n.startswith("leuven_friction/sample_data/") and n.endswith(".csv") for n in names) >= 5
    assert not any(n.startswith(("leuven_friction/synth", "leuven_friction/tests")) for n in names)


def test_the_installed_copy_runs_not_the_checkout(installed):
    r = run([installed["py"], "-c", "import leuven_friction.model as m, leuven_friction.app.cli as c; "
             "print(m.__file__); print(c.__file__)"], cwd=installed["cwd"], env=installed["env"])
    for line in r.stdout.split():
        assert line.startswith(str(installed["site"])), r.stdout


def test_fit_a_shipped_sample_from_any_directory(installed):
    cli, cwd, env = installed["cli"], installed["cwd"], installed["env"]
    run([cli, "samples", "--out", "data"], cwd=cwd, env=env)
    run([cli, "fit", "data/constant_velocity.csv", "--out", "p.yaml"], cwd=cwd, env=env)
    run([cli, "fit", "sample:constant_velocity", "--out", "q.yaml"], cwd=cwd, env=env)
    for out in ("p.yaml", "q.yaml"):
        p = yaml.safe_load((cwd / out).read_text())
        assert abs(p["stribeck"]["positive"]["Fc"] - 27.0) < 1.0  # Table I's Fc+ behind the sample
    r = run([cli, "fit", "sample:constant_velocity", "--out", "/nonexistent/p.yaml"], cwd=cwd, env=env, check=False)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1


def test_bench_quick_runs_from_the_wheel(installed):
    r = run([installed["cli"], "bench", "--quick", "--json", "b.json"], cwd=installed["cwd"], env=installed["env"])
    assert (installed["cwd"] / "b.json").stat().st_size > 0, r.stderr
