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
