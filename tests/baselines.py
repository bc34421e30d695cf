"""Comparison baselines of the tests: methods the product must beat or examples from the
literature, kept out of the product."""

import numpy as np

from leuven_friction.identify.mle import Gaussian, PreslidingData, fit_transition_curve
from leuven_friction.model import FrictionParams, Stribeck, StribeckSide, default_params


def fit_transition_curve_unweighted(datasets, z_knots, *, n: float = 7.0) -> np.ndarray:
    """Plain least squares on all displacements alike, ignoring the noise models: the
    comparison the ML estimator must beat. Returns the ordinates."""
    pooled = [PreslidingData(ds.branches, Gaussian(1.0), ds.name) for ds in datasets]
    return fit_transition_curve(pooled, z_knots, n=n).F


def canudas_lugre_params() -> FrictionParams:
    """The classic LuGre example of Canudas de Wit et al. (1995), used for Figs. 1 and 2:
    σ0 = 1e5 N/m, σ1 = √1e5 N·s/m, σ2 = 0.4 N·s/m, Fc = 1 N, Fs = 1.5 N, vs = 1e-3 m/s,
    δ = 2, mass 1 kg (symmetric in the two directions)."""
    pos = StribeckSide(Fs=1.5, Fc=1.0, vs=1e-3, delta=2.0, sigma2=0.4)
    neg = StribeckSide(Fs=-1.5, Fc=-1.0, vs=-1e-3, delta=2.0, sigma2=0.4)
    base = default_params()
    return base.replace(model="lugre", stribeck=Stribeck(pos, neg), sigma0=1e5, sigma1=float(np.sqrt(1e5)),
                        inertia=1.0, units={"position": "m", "force": "N", "time": "s"}).validate()
