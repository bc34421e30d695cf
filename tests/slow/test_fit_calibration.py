"""Monte Carlo calibration of the fit on the independent generator: one machine per kind,
fresh sensor noise and schedule jitter per draw; the reported σ must match the empirical
spread of the estimates within ±25 %, and the estimates must centre on the truth."""

import numpy as np
import pytest

from leuven_friction.identify.data import load_recording
from leuven_friction.identify.fit import fit_recordings
from synth.recordings import _random_machine, make_recording

DRAWS = 40
CHECKED = (("positive", "Fc"), ("positive", "Fs"), ("positive", "sigma2"), ("negative", "Fc"))


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["robot_joint", "tribometer"])
def test_reported_sigma_matches_the_spread_over_draws(kind):
    machine = _random_machine(kind, np.random.default_rng(1000))
    est, sds = [], []
    truth = None
    for seed in range(DRAWS):
        df, truth = make_recording(kind, 500 + seed, params=machine)
        res = fit_recordings([load_recording(df.to_csv(index=False).encode(), name=f"{kind}.csv")], refine=False)
        assert not any(f"stribeck.{s}.{k}" in res.held for s, k in CHECKED)
        est.append([getattr(getattr(res.params.stribeck, s), k) for s, k in CHECKED])
        sds.append([res.params.uncertainty[f"stribeck.{s}.{k}"] for s, k in CHECKED])
    est, sds = np.array(est), np.array(sds)
    t = np.array([truth.stribeck[s][k] for s, k in CHECKED])
    ratio = np.std(est, axis=0, ddof=1) / np.sqrt(np.mean(sds ** 2, axis=0))
    assert np.all(np.abs(ratio - 1) < 0.25), ratio
    # unbiased: the mean within 3 standard errors of the truth
    assert np.all(np.abs(est.mean(axis=0) - t) < 3 * est.std(axis=0, ddof=1) / np.sqrt(DRAWS)), (est.mean(axis=0), t)
