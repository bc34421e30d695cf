"""A linear rolling-element guide on a test rig, simulated apart from leuven-friction (numpy
only; it imports nothing of the tool).

Written from the README alone, as a new user would, for a trial of `fit` then `diagnose` on a
machine unlike the project's generators, and kept so that trial runs again
(``tests/slow/test_diagnose_guide_rig.py``).

Carriage (4.5 kg) driven by a linear motor under a PID position loop with acceleration
feed-forward; a load cell between actuator and carriage measures the actuator force, and the
inertial force (m * a of the simulated carriage) is subtracted so the logged column is friction
plus load-cell noise, logged as the force the load cell reads (reaction sign: minus the friction
that opposes positive motion).

Friction: Maxwell-slip bank of 5 elements. Each element's slip limit is its share of a steady
curve S_side(|v|) = Fc + (Fs - Fc) * exp(-|v / vs|), with the side chosen by the sign of the
element's stretch, times (N / 2 kN)^0.7 in the load sessions; a viscous term sigma2 * v
(per side, also scaled by the load factor). Cyclic softening: element stiffnesses scale by
1 - 0.3 * (1 - exp(-n / 15)), n = motion reversals with > 0.5 um back-travel.

Integration: semi-implicit (symplectic) Euler at 20 kHz, logged at 2 kHz: time in ms, position
in µm on a 0.05 µm encoder, friction in mN (40 mN of noise), the normal load in kN (4 N).

Sessions (``SESSIONS``): ``control`` (2 kN, no effect), ``load`` (the load stepped and ramped
over 1.0–3.5 kN, once while the carriage sticks), ``soft`` (the softening), ``load_soft`` (both).

Usage: python -m synth.guide_rig OUT_DIR [control|load|soft|load_soft|all]
"""
import sys
import numpy as np

M = 4.5                       # kg
DT = 1.0 / 20000.0            # 20 kHz integration
DECIM = 10                    # log at 2 kHz
N_REF = 2000.0                # N
ALPHA = 0.7
SOFT_H, SOFT_NC, SOFT_THRESH = 0.3, 15.0, 0.5e-6

# steady curve per side (SI): positive motion side, negative motion side (magnitudes)
SIDE = {
    +1: dict(Fc=18.0, Fs=24.0, vs=4.0e-3, s2=60.0),
    -1: dict(Fc=16.8, Fs=22.6, vs=5.0e-3, s2=54.0),
}
# Maxwell-slip elements: share of the limit, break displacement at F_s+ (m)
SHARE = np.array([0.30, 0.25, 0.20, 0.15, 0.10])
BREAK = np.array([2e-6, 5e-6, 10e-6, 20e-6, 35e-6])
K0 = SHARE * SIDE[+1]["Fs"] / BREAK            # N/m

SPEEDS = [0.5e-3, 1e-3, 2e-3, 5e-3, 10e-3, 25e-3, 60e-3, 120e-3]


# ----------------------------------------------------------------------------- motion profile
class Profile:
    def __init__(self):
        self.v = []          # reference velocity per integration step
        self.marks = []      # (label, t_start, t_end)

    @property
    def t(self):
        return len(self.v) * DT

    def rest(self, T, label="rest"):
        t0 = self.t
        self.v.extend([0.0] * int(round(T / DT)))
        self.marks.append((label, t0, self.t))

    def move(self, dist, vmax, acc, label="move"):
        """trapezoidal velocity profile travelling `dist` (signed) at peak |vmax|."""
        t0 = self.t
        s = np.sign(dist)
        d = abs(dist)
        ta = vmax / acc
        if acc * ta * ta > d:                      # triangular
            ta = np.sqrt(d / acc)
            vmax = acc * ta
            tc = 0.0
        else:
            tc = (d - acc * ta * ta) / vmax
        na, nc = int(round(ta / DT)), int(round(tc / DT))
        ramp = list(np.linspace(0, vmax, na + 1)[1:])
        self.v.extend([s * x for x in ramp] + [s * vmax] * nc + [s * x for x in ramp[::-1]])
        self.marks.append((label, t0, self.t))

    def presliding(self, amps, cycles, period):
        """triangular back-and-forth motions about the current point (amplitude A, +/-)."""
        t0 = self.t
        for A in amps:
            for _ in range(cycles):
                vq = 4 * A / period
                q = int(round(period / 4 / DT))
                self.v.extend([vq] * q + [-vq] * (2 * q) + [vq] * q)
        self.marks.append(("presliding", t0, self.t))


def build_profile(seed):
    rng = np.random.default_rng(seed)
    p = Profile()
    amps = [2e-6, 5e-6, 10e-6, 20e-6, 40e-6]
    p.rest(0.5)
    p.presliding(amps, 2, 0.5)
    p.rest(0.3)
    pos_sp = list(rng.permutation(SPEEDS))
    neg_sp = list(rng.permutation(SPEEDS))
    strokes = []
    for a, b in zip(pos_sp, neg_sp):
        strokes += [(+1, a), (-1, b)]
    # shuffle pairs' order too (directions alternate to keep the carriage on the rail)
    for i, (s, v) in enumerate(strokes):
        T_steady = 1.6 if v < 20e-3 else max(0.6, min(1.2, 0.09 / v))
        dist = s * v * (T_steady + v / 2.0)   # acc 2 m/s^2 -> ramp time v/2
        p.move(dist, v, 2.0, label=f"stroke {s * v * 1e3:+.1f} mm/s")
        p.rest(0.25)
        if i % 4 == 3:
            p.presliding(amps, 1, 0.5)
            p.rest(0.25)
    p.presliding(amps, 2, 0.5)
    p.rest(0.5)
    return p


# ----------------------------------------------------------------------------- load schedule
def load_schedule(p, variable):
    n = len(p.v)
    t = np.arange(n) * DT
    if not variable:
        return np.full(n, 2000.0)
    T = t[-1]
    # the ramp while stuck: over the second presliding block (after 4 strokes)
    pres = [m for m in p.marks if m[0] == "presliding"]
    a, b = pres[1][1], pres[1][2]
    knots = [(0.0, 2000.0), (0.20 * a, 2000.0), (0.20 * a + 1e-3, 1000.0),   # step down
             (0.55 * a, 1000.0), (0.85 * a, 2500.0),                        # ramp while sliding/resting
             (a - 0.23, 2500.0), (a - 0.229, 1500.0),                       # step at rest
             (a - 0.2, 1500.0), (a + 1.45, 3500.0),     # ramp WHILE stuck: rest + 2/5/10 um cycles
             (b + 0.05 * (T - b), 3500.0), (b + 0.05 * (T - b) + 1e-3, 3000.0),
             (b + 0.35 * (T - b), 3000.0), (b + 0.60 * (T - b), 1200.0),    # ramp during strokes
             (b + 0.75 * (T - b), 1200.0), (b + 0.75 * (T - b) + 1e-3, 2200.0),
             (T, 2200.0)]
    kt, kv = zip(*knots)
    return np.interp(t, kt, kv)


# ----------------------------------------------------------------------------- simulation
def simulate(p, N, soften, seed):
    vr = np.asarray(p.v)
    n = len(vr)
    xr = np.concatenate([[0.0], np.cumsum(vr[:-1]) * DT])
    ar = np.gradient(vr, DT)
    # servo: 120 Hz bandwidth, PID
    w = 2 * np.pi * 120.0
    kp, kd, ki = M * w * w, 2 * 0.8 * w * M, M * w * w * w / 8.0
    nel = len(K0)
    z = [0.0] * nel                         # element stretch
    k0 = list(K0)
    share = list(SHARE)
    S = {s: SIDE[s] for s in (+1, -1)}
    x = v = integ = 0.0
    # reversal counter (play of width SOFT_THRESH)
    nrev, direction, extreme = 0, 0, 0.0
    kfac = 1.0
    X = np.empty(n // DECIM + 1)
    F = np.empty_like(X)
    NN = np.empty_like(X)
    j = 0
    Ff = 0.0
    exp = np.exp
    for i in range(n):
        e = xr[i] - x
        integ += e * DT
        u = M * ar[i] + kp * e + kd * (vr[i] - v) + ki * integ
        a = (u - Ff) / M
        v += a * DT
        dx = v * DT
        x += dx
        # reversal count
        if True:
            if direction >= 0:
                if x > extreme:
                    extreme = x
                elif extreme - x > SOFT_THRESH:
                    if direction > 0:
                        nrev += 1
                    direction, extreme = -1, x
            if direction < 0:
                if x < extreme:
                    extreme = x
                elif x - extreme > SOFT_THRESH:
                    nrev += 1
                    direction, extreme = 1, x
            if soften:
                kfac = 1.0 - SOFT_H * (1.0 - exp(-nrev / SOFT_NC))
        lf = (N[i] / N_REF) ** ALPHA
        av = abs(v)
        sp, sn = S[1], S[-1]
        Lp = (sp["Fc"] + (sp["Fs"] - sp["Fc"]) * exp(-av / sp["vs"])) * lf
        Ln = (sn["Fc"] + (sn["Fs"] - sn["Fc"]) * exp(-av / sn["vs"])) * lf
        Fe = 0.0
        for m in range(nel):
            k = k0[m] * kfac
            zz = z[m] + dx
            f = k * zz
            if f > share[m] * Lp:
                f = share[m] * Lp
                zz = f / k
            elif f < -share[m] * Ln:
                f = -share[m] * Ln
                zz = f / k
            z[m] = zz
            Fe += f
        Ff = Fe + (sp["s2"] if v > 0 else sn["s2"]) * v * lf
        if i % DECIM == 0:
            X[j], F[j], NN[j] = x, Ff, N[i]
            j += 1
    X, F, NN = X[:j], F[:j], NN[:j]
    t = np.arange(j) * DT * DECIM
    return t, X, F, NN, nrev


def write(name, t, X, F, NN, seed, outdir):
    rng = np.random.default_rng(seed + 7)
    pos_um = np.round(X * 1e6 / 0.05) * 0.05                 # 0.05 um linear encoder
    fric_mN = -(F + rng.normal(0, 0.040, F.size)) * 1e3       # load-cell reading: reaction sign
    load_kN = (NN + rng.normal(0, 4.0, NN.size)) / 1e3        # load sensor, 4 N noise
    path = f"{outdir}/{name}.csv"
    with open(path, "w") as fh:
        fh.write("time [ms],position [um],friction [mN],normal_load [kN]\n")
        for row in zip(t * 1e3, pos_um, fric_mN, load_kN):
            fh.write("%.1f,%.2f,%.1f,%.4f\n" % row)
    return path


SESSIONS = {"control": (False, False, 11), "load": (True, False, 22),
            "soft": (False, True, 33), "load_soft": (True, True, 44)}


def run(name, outdir):
    """Write session ``name`` into ``outdir``; its path."""
    variable, soften, seed = SESSIONS[name]
    p = build_profile(seed)
    N = load_schedule(p, variable)
    t, X, F, NN, nrev = simulate(p, N, soften, seed)
    return write(name, t, X, F, NN, seed, outdir)


def simulate_to(outdir, sessions=tuple(SESSIONS)):
    """Write the sessions asked (``SESSIONS``) into ``outdir``; their paths."""
    return [run(name, outdir) for name in sessions]


if __name__ == "__main__":
    which = sys.argv[2] if len(sys.argv) > 2 else "all"
    for path in simulate_to(sys.argv[1], tuple(SESSIONS) if which == "all" else (which,)):
        print("wrote", path)
