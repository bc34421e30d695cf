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


def forced_bristle_mass(mass: float, seconds: float = 20.0, rate: float = 1000.0, sub: int = 20, step: float = 1e-6,
                        force_noise: float = 0.005, seed: int = 0):
    """A mass ``mass`` under an applied force of two sines (1.6 N at 0.4 Hz, 0.5 N at 3.1 Hz),
    its friction a bristle (Dahl-like, stiffness 2·10⁴ N/m) whose limit follows a Gaussian
    Stribeck curve (F_c 0.5, F_s 0.7 N, v_s 0.01 m/s) plus 0.3 N·s/m viscous; explicit Euler at
    ``sub`` substeps a sample (the bristle's state implicit), the position logged on a ``step``
    encoder, the force with white noise. It never slides steadily. Returns (t, x, f)."""
    rng = np.random.default_rng(seed)
    dt, n = 1.0 / (rate * sub), int(seconds * rate)
    x = v = z = 0.0
    k, fc, fs, vs, s2 = 2e4, 0.5, 0.7, 0.01, 0.3
    t = np.arange(n) / rate
    f = 1.6 * np.sin(2 * np.pi * 0.4 * t) + 0.5 * np.sin(2 * np.pi * 3.1 * t)
    xs = np.empty(n)
    for i in range(n):
        for _ in range(sub):
            g = fc + (fs - fc) * np.exp(-(v / vs) ** 2)
            z = (z + dt * v) / (1.0 + dt * k * abs(v) / g)  # implicit in z: k|v|/g·dt reaches 2 at 1 m/s
            v += dt * (f[i] - k * z - s2 * v) / mass
            x += dt * v
        xs[i] = np.round(x / step) * step
    return t, xs, f + rng.normal(0.0, force_noise, n)
