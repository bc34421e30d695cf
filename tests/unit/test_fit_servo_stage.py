"""`fit` on a position-servoed LuGre stage simulated apart from the project
(``synth/servo_stage_lugre.py``), whose presliding branches slide at a force change well below
the outer loop's span: the transition curve's knots above every force the branches reach are
dropped, said so, and the curve written still carries a transition into sliding."""

import numpy as np

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.fit import fit_recordings
from synth import servo_stage_lugre as S


def test_knots_above_every_branch_force_are_dropped_and_the_curve_reaches_sliding(tmp_path):
    csv = tmp_path / "stage.csv"
    S.record(str(csv), 505, soft_frac=0.40, soft_k=2.5)
    res = fit_recordings([load_recording(csv)])
    assert any("lie above every force change the branches reach" in n for n in res.notes), res.notes
    p = res.params
    z, F = np.array(p.transition_curve.z), np.array(p.transition_curve.F)
    # every knot left is one the branches reach into: its segment starts below the largest force
    # change of any branch (what the note printed), and F_d, extended with its last slope, gets to
    # the outer loop's span within three of the softened bristles' reversal travel
    asked = max(min(np.max(b.force), 0.999 * b.D) for d in res.datasets for b in d.branches)
    assert F[-2] < asked, (F, asked)
    span = p.stribeck.positive.Fs - p.stribeck.negative.Fs
    reach = z[-1] + max(span - F[-1], 0.0) * (z[-1] - z[-2]) / (F[-1] - F[-2])
    assert reach < 3.0 * (S.FS_P + S.FS_N) / (S.SIG0 * (1 - 0.40)), (z, F, span)


def test_an_offset_of_the_force_signal_moves_the_sides_coulomb_sizes_apart_by_twice_it(tmp_path):
    """An offset c added to the force read adds c to the friction both ways, so |F_c⁺| − |F_c⁻|
    moves by 2c; the fit cannot tell an offset from a friction that differs by direction, and
    says both, with the offset that would explain the difference."""
    import pandas as pd

    from leuven_friction.identify.fit import direction_asymmetry

    csv = tmp_path / "stage.csv"
    S.record(str(csv), 505)  # its own 12 mN offset and F_c⁺ 0.34 against F_c⁻ 0.30 N
    shifted = tmp_path / "stage_offset.csv"
    df = pd.read_csv(csv)
    df["force [mN]"] += 30.0  # 0.03 N more
    df.to_csv(shifted, index=False)
    diffs = []
    for path in (csv, shifted):
        p = fit_recordings([load_recording(path)]).params
        d = abs(p.stribeck.positive.Fc) - abs(p.stribeck.negative.Fc)
        sd = np.hypot(p.uncertainty["stribeck.positive.Fc"], p.uncertainty["stribeck.negative.Fc"])
        diffs.append((d, sd))
        said = direction_asymmetry(p)
        assert f"an offset of {d / 2:.3g} N in the force signal" in said, said
    (d0, s0), (d1, s1) = diffs
    assert abs((d1 - d0) - 2 * 0.03) < 3 * np.hypot(s0, s1) + 1e-9, diffs
    # the generator's own: twice its 12 mN offset beside its 0.04 N of direction-dependence
    assert abs(d0 - (FC := S.FC_P - S.FC_N) - 2 * 0.012) < 0.2 * FC, d0


def test_sides_of_one_size_are_not_said_to_differ():
    from leuven_friction.identify.fit import direction_asymmetry
    from leuven_friction.model import default_params

    p = default_params()
    side = p.stribeck.positive
    mirrored = type(side)(Fs=-side.Fs, Fc=-side.Fc + 0.01, vs=-side.vs, delta=side.delta, sigma2=side.sigma2)
    sd = {f"stribeck.{s}.{k}": 0.01 for s in ("positive", "negative") for k in ("Fc", "Fs")}
    q = p.replace(stribeck=type(p.stribeck)(positive=side, negative=mirrored), uncertainty=sd)
    assert direction_asymmetry(q) == ""  # 0.01 apart, σ of the difference 0.014
    far = q.replace(uncertainty={k: 0.001 for k in sd})  # the same 0.01 at 7 σ
    said = direction_asymmetry(far)
    # |F_c⁺| − |F_c⁻| = 27 − 26.99 = 0.01: half of it as an offset; F_s equal in size, which an
    # offset would not leave them
    assert "an offset of 0.005 N*m in the force signal" in said, said
    assert "|F_s⁺| − |F_s⁻| = 0 ± 0.0014 N*m, which an offset alone would make equal to it" in said, said
