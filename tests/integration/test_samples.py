"""The sample recordings shipped with the package: listed, copied out all or none, and usable
by name from any directory."""

import os

import yaml

from leuven_friction import sample_data
from leuven_friction.app.cli import main

REPO_SAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "sample_data")


def test_every_shipped_csv_is_listed(capsys):
    on_disk = sorted(f[:-4] for f in os.listdir(REPO_SAMPLES) if f.endswith(".csv"))
    assert list(sample_data.names()) == on_disk
    assert main(["samples", "--list"]) == 0
    out = capsys.readouterr().out
    assert [line.split()[0] for line in out.splitlines()] == [f"sample:{n}" for n in on_disk]


def test_copy_out_is_byte_identical_and_never_overwrites(tmp_path, capsys):
    dest = tmp_path / "samples"
    assert main(["samples", "--out", str(dest)]) == 0
    for name in sample_data.names():
        assert (dest / f"{name}.csv").read_bytes() == sample_data.path(name).read_bytes()
    (dest / "constant_velocity.csv").write_text("my edits")
    assert main(["samples", "--out", str(dest)]) == 2
    assert "already exists" in capsys.readouterr().err
    assert (dest / "constant_velocity.csv").read_text() == "my edits"
    assert main(["samples", "--out", str(tmp_path / "no" / "dir")]) == 2
    assert not (tmp_path / "no").exists()


def test_fit_a_sample_by_name_from_another_directory(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["fit", "sample:constant_velocity", "--out", "p.yaml"]) == 0, capsys.readouterr().err
    p = yaml.safe_load((tmp_path / "p.yaml").read_text())
    # the sample was simulated from Table I: Fc+ = 27 N·m (noise σ = 0.5 N·m on many samples)
    assert abs(p["stribeck"]["positive"]["Fc"] - 27.0) < 1.0
    assert main(["fit", "sample:nope", "--out", "q.yaml"]) == 2
    assert "no such sample" in capsys.readouterr().err and not (tmp_path / "q.yaml").exists()
