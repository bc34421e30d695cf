"""The installed layout: one import name, every product folder in the wheel, no checkout tool
imported by the product. (tests/slow/test_wheel.py builds and installs the wheel itself.)"""

import ast
import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CONFIG = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
PRODUCT = {"leuven_friction": "leuven_friction", "leuven_friction.model": "model",
           "leuven_friction.identify": "identify", "leuven_friction.app": "app",
           "leuven_friction.sample_data": "sample_data"}


def test_package_dir_maps_the_root_folders_under_one_name():
    assert CONFIG["package-dir"] == PRODUCT


def test_every_product_folder_is_a_listed_package():
    listed = set(CONFIG["packages"])
    for name, folder in PRODUCT.items():
        for init in (ROOT / folder).rglob("__init__.py"):
            rel = init.parent.relative_to(ROOT / folder).parts
            assert ".".join((name, *rel)) in listed, f"{init.parent} is not in [tool.setuptools] packages"
    assert all(p.startswith("leuven_friction") for p in listed)  # no generic top-level names


def test_samples_are_package_data():
    patterns = CONFIG["package-data"]["leuven_friction.sample_data"]
    for csv in (ROOT / "sample_data").glob("*.csv"):
        assert any(csv.match(p) for p in patterns)


def _imports(path: Path):
    tree = ast.parse(path.read_text(), str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield 0, a.name
        elif isinstance(node, ast.ImportFrom):
            yield node.level, node.module or ""


def test_product_imports_no_checkout_tool_and_its_own_parts_relatively():
    tools = re.compile(r"^(bench|synth|tests|model|identify|app|sample_data)(\.|$)")
    for folder in ("model", "identify", "app", "sample_data"):
        for py in (ROOT / folder).rglob("*.py"):
            for level, module in _imports(py):
                assert not (level == 0 and tools.match(module)), f"{py.relative_to(ROOT)} imports {module}"


def test_the_checkout_imports_its_parts_without_an_install():
    # `python -c` in the repository root puts that folder first on sys.path, where
    # leuven_friction/ holds only __init__.py: without an editable install's finder the parts,
    # which sit beside it, were not found (ModuleNotFoundError: leuven_friction.identify)
    import subprocess
    import sys

    code = ("import sys; sys.meta_path[:] = [f for f in sys.meta_path if 'editable' not in repr(f).lower()]; "
            "import leuven_friction.identify.fit as f, leuven_friction.app.cli as c; print(f.__file__); print(c.__file__)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True).stdout
    assert [Path(p) for p in out.split()] == [ROOT / "identify" / "fit.py", ROOT / "app" / "cli.py"], out


def test_every_output_flag_has_its_short_form(tmp_path):
    # `-o` is what a user types first; it is the same flag as `--out` on every command that writes
    from leuven_friction.app.cli import build_parser, main

    ap = build_parser()
    for argv in (["simulate", "-o", "a.csv"], ["fit", "x.csv", "-o", "a.yaml"], ["diagnose", "x.csv", "--params", "p.yaml",
                                                                                   "-o", "a.yaml"], ["samples", "-o", "d"]):
        assert ap.parse_args(argv).out == argv[argv.index("-o") + 1], argv
    assert main(["samples", "-o", str(tmp_path / "copied")]) == 0
    shipped = sorted(p.name for p in (ROOT / "sample_data").glob("*.csv"))
    assert shipped and sorted(p.name for p in (tmp_path / "copied").glob("*.csv")) == shipped
