"""Output error over short windows, compiled: the plant I·ẍ = f − F (eq. (8)) driven by the
applied force, re-started at the measured position and velocity at the start of every
window while the hysteresis memory runs on. One call for a whole recording (the diagnosis
evaluates it hundreds of times)."""

from __future__ import annotations

import numpy as np
from numba import njit

from . import kernels as K
from .params import FrictionParams
from .simulate import initial_state, pack


@njit(cache=True, nogil=True)
def _run_windows(model, p, kind, tz, tF, st, t, f, fsc, ksc, starts, x0, v0, X):
    fstep = 1 if fsc.shape[0] > 1 else 0
    kstep = 1 if ksc.shape[0] > 1 else 0
    w = 0
    x = 0.0
    v = 0.0
    for k in range(t.shape[0]):
        if w < starts.shape[0] and k == starts[w]:
            x = x0[w]
            v = v0[w]
            w += 1
            X[k] = x
            continue
        x, v, _, _, _ = K.plant_step(model, p, kind, tz, tF, st, x, v, f[k], t[k] - t[k - 1],
                                     fsc[k * fstep], ksc[k * kstep])
        X[k] = x


def simulate_windows(params: FrictionParams, t: np.ndarray, f: np.ndarray, starts: np.ndarray, x0: np.ndarray,
                     v0: np.ndarray, *, friction_scale=None, stiffness_scale=None) -> np.ndarray:
    """Positions of the plant under the applied force ``f``, re-started at samples ``starts``
    (increasing, the first 0) at positions ``x0`` and velocities ``v0``."""
    code, p, kind, tz, tF = pack(params)
    st = initial_state(params)
    one = np.ones(1)
    fs = one if friction_scale is None else np.ascontiguousarray(friction_scale, dtype=np.float64)
    ks = one if stiffness_scale is None else np.ascontiguousarray(stiffness_scale, dtype=np.float64)
    X = np.empty(len(t))
    _run_windows(code, p, kind, tz, tF, st, np.ascontiguousarray(t, dtype=np.float64),
                 np.ascontiguousarray(f, dtype=np.float64), fs, ks, np.ascontiguousarray(starts, dtype=np.int64),
                 np.ascontiguousarray(x0, dtype=np.float64), np.ascontiguousarray(v0, dtype=np.float64), X)
    return X
