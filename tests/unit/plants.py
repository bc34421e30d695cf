"""Plants integrated here, not by the product's simulator: test data made by other code."""

import numpy as np


def velocity_loop(inertia: float, friction, levels, n_per: int, dt: float = 2e-3, sub: int = 20, kp: float = 40.0,
                  ki: float = 400.0, tacho_noise: float = 0.01, seed: int = 3):
    """A mass ``inertia`` under a velocity PI loop holding ``levels`` for ``n_per`` samples
    each, friction ``friction(v)``; the loop runs at ``sub`` substeps a sample (explicit
    Euler) and its noisy tachometer makes it hunt around each level; the log keeps the
    last substep of each sample. Returns (t, x, v, f): times, position, velocity, the
    controller's force."""
    rng = np.random.default_rng(seed)
    x = v = integ = 0.0
    xs, vs, fs = [], [], []
    for vc in np.repeat(levels, n_per):
        noise = rng.normal(0, tacho_noise)
        for _ in range(sub):
            e = vc - (v + noise)
            integ += e * dt / sub
            u = kp * e + ki * integ
            v += (u - friction(v)) / inertia * (dt / sub)
            x += v * dt / sub
        xs.append(x)
        vs.append(v)
        fs.append(u)
    return np.arange(len(vs)) * dt, np.array(xs), np.array(vs), np.array(fs)
