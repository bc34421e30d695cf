"""Running the command line as a user does, on a recording written to a real file."""

import json

import yaml

from leuven_friction.app.cli import main


def diagnose_file(tmp_path, df, name: str, float_format: str = "%.10g") -> dict:
    """``df`` written to ``tmp_path/name``, ``leuven-friction diagnose`` run on it (a fit
    first: no parameter file), its JSON report read back."""
    path = tmp_path / name
    df.to_csv(path, index=False, float_format=float_format)
    out = tmp_path / "report.json"
    assert main(["diagnose", str(path), "--json", str(out)]) == 0
    return json.loads(out.read_text())


def fit_then_diagnose(tmp_path, csv: str, name: str) -> tuple[dict, dict]:
    """``leuven-friction fit`` on the recording at ``csv``, then ``diagnose`` with the file it
    wrote, as a user runs them (the default settings): the parameter file and the JSON report,
    read back."""
    base, rep = tmp_path / f"{name}.yaml", tmp_path / f"{name}.json"
    assert main(["fit", csv, "--out", str(base)]) == 0
    assert main(["diagnose", csv, "--params", str(base), "--json", str(rep)]) == 0
    return yaml.safe_load(base.read_text()), json.loads(rep.read_text())


def simulated_fit_then_diagnose(tmp_path, simulate, name: str) -> tuple[dict, dict]:
    """Session ``name`` of a simulator made apart (``simulate(out_dir, [name])`` writes it and
    gives its path), then ``fit_then_diagnose`` on it: the default settings, as a user runs them."""
    (csv,) = simulate(str(tmp_path), [name])
    return fit_then_diagnose(tmp_path, csv, name)


def written(rep: dict, name: str) -> dict:
    """The effect ``name`` as a diagnosis's JSON report says the file has it (values and σ)."""
    return next(e for e in rep["written_effects"] if e["name"] == name)
