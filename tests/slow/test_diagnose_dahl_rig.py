"""`fit` then `diagnose` on a linear rig simulated apart from the project (``synth/dahl_rig.py``:
a Dahl contact, which does not keep Masing's rule, under a prescribed motion, its friction
measured in lbf, its position in inches; presliding loops of rising amplitude, then strokes),
as a new user runs them. Every expectation is the simulator's own, not a number the tool
printed."""

import numpy as np
import pytest
import yaml

from leuven_friction.app.cli import main
from synth import dahl_rig as S
from tests.cli_runs import simulated_fit_then_diagnose

LBF = S.LBF


def _fit_and_diagnose(tmp_path, name):  # as a user runs them: the default settings
    return simulated_fit_then_diagnose(tmp_path, S.simulate, name)


@pytest.mark.slow
def test_a_dahl_contact_whose_loops_grow_with_the_reversals_is_no_hardening_beside_the_stroke_before(tmp_path):
    # its small loops are softer than its large ones (stiffness k0 (1 + |F_b|/s) after a reversal),
    # and run in rising amplitude that is a trend in the reversal count: by default a hardening is
    # named on this control (h 0.13 ± 0.05, n_c 5.8), and nothing once the loops are shuffled.
    # Judged beside a stiffness following the travel of the stroke before (an option: it named
    # false softenings elsewhere), nothing is named
    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import Settings, diagnose
    from leuven_friction.identify.paramfile import load_params

    (csv,) = S.simulate(str(tmp_path), ["control"])
    base = tmp_path / "control.yaml"
    assert main(["fit", csv, "--out", str(base)]) == 0
    st = yaml.safe_load(base.read_text())["stribeck"]
    for side, sign, truth in (("positive", 1, S.POS), ("negative", -1, S.NEG)):
        assert st[side]["Fs"] == pytest.approx(sign * truth["Fs"], rel=0.01), st[side]  # N, from lbf
        assert st[side]["Fc"] == pytest.approx(sign * truth["Fc"], rel=0.01), st[side]  # (the load cell drifts 0.2 N)
        assert st[side]["vs"] == pytest.approx(sign * S.VS, rel=0.03), st[side]  # m/s, from inches
        assert st[side]["sigma2"] == pytest.approx(S.SIGMA2, rel=0.03), st[side]
    # the presliding triangles' legs at 50 µm/s that start within twice the presliding range of
    # their reversals are no levels of S(v): of the ten read as levels before (35–44 N, a χ² of
    # 75 for 13), the three longest, past it, are left, and eq. (7) fits the levels within their noise
    from scipy.stats import chi2

    from leuven_friction.identify.fit import fit_recordings

    res = fit_recordings([load_recording(csv)], refine=False)
    assert 1 <= np.sum(np.abs(res.levels.velocity) < 0.9e-4) <= 3, np.sort(np.abs(res.levels.velocity))[:6]
    for side, f in res.stribeck_fit.items():
        assert chi2.sf(f.chi2, f.dof) > 1e-3, (side, f.chi2, f.dof)
    d = diagnose(load_recording(csv), load_params(str(base)), settings=Settings(travel_nuisance=True))
    assert d.effects == [], d.effects
    softening = next(c for c in d.candidates if c["name"] == "cyclic_softening")
    assert "stroke's travel" in softening["beside"], softening["beside"]


@pytest.mark.slow
def test_the_load_on_a_dahl_contact_is_named_with_its_exponent(tmp_path):
    # the whole friction × (N/250 lbf)^0.75, the load stepping among 150–400 lbf out of time order
    _, rep = _fit_and_diagnose(tmp_path, "load")
    assert rep["effects"][0] == "normal_load" and "cyclic_softening" not in rep["effects"], rep["effects"]
    load = next(e for e in rep["written_effects"] if e["name"] == "normal_load")
    assert load["params"]["alpha"] == pytest.approx(S.ALPHA, abs=max(3 * load["sd"]["alpha"], 0.03)), load
    assert rep["rms_after"] < 0.3 * rep["rms_before"], (rep["rms_before"], rep["rms_after"])
