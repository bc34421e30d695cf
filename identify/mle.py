"""Maximum-likelihood estimator of the transition curve F_d (Section IV-B, Table II).

Presliding data: branches of a slow applied-force ramp, each starting at a velocity reversal.
Neglecting inertia, σ1 and σ2 (the paper's eq. (9)), the displacement along a branch after a
force change ΔF ≥ 0 from the reversal is

    x(ΔF) = ∫_0^ΔF (dF_d⁻¹/dF) / (1 - (F/D)^n) dF,      D = F_s(direction) - F_b,

so for a piecewise-linear F_d with given knot abscissas the ordinates set the displacement
curve. Each data set carries its own noise model on the measured displacement:
``Gaussian(sigma)`` (a proximity sensor) or ``Quantized(step, jitter)`` (an encoder: the
reading is the true position plus Gaussian jitter, rounded to the step; the likelihood of a
reading is the probability mass of its quantisation bin). Several data sets are combined in
one likelihood; each branch has an unknown displacement offset (the sensor's zero). The
covariance is the inverse of the Hessian of the negative log-likelihood at the optimum.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares
from scipy.special import hyp2f1, log_ndtr

from .errors import IdentificationError

GRID = 400  # force grid of a motion-driven branch, on which x(ΔF) is inverted


@dataclass(frozen=True)
class Gaussian:
    sigma: float

    def __post_init__(self):
        object.__setattr__(self, "sigma", float(self.sigma))  # a plain number in reports and YAML, not numpy's repr

    def residuals(self, measured, predicted):
        """r with -log L = ½·Σr² (+ const)."""
        return (measured - predicted) / self.sigma

    def nll(self, measured, predicted):
        r = self.residuals(measured, predicted)
        return 0.5 * float(np.sum(r * r))


@dataclass(frozen=True)
class Quantized:
    step: float
    jitter: float

    def __post_init__(self):
        object.__setattr__(self, "step", float(self.step))
        object.__setattr__(self, "jitter", float(self.jitter))

    def _log_mass(self, measured, predicted):
        # log P(reading) = log(Φ(hi) - Φ(lo)) for the reading's bin; the mirror image keeps
        # both tails accurate
        a = (measured + 0.5 * self.step - predicted) / self.jitter
        b = (measured - 0.5 * self.step - predicted) / self.jitter
        flip = a + b > 0
        hi = np.where(flip, -b, a)
        lo = np.where(flip, -a, b)
        la, lb = log_ndtr(hi), log_ndtr(lo)
        return la + np.log1p(-np.exp(np.minimum(lb - la, -1e-16)))

    def residuals(self, measured, predicted):
        """r with -log L = ½·Σr² + const: r = ±sqrt(2·(log P_max - log P)), where P_max is
        the mass of a bin centred on the prediction. Zero when the prediction sits in the
        middle of its bin and signed by the direction of the miss, so r is continuous."""
        lp = self._log_mass(measured, predicted)
        lp_max = self._log_mass(np.zeros(1), np.zeros(1))[0]
        return np.sign(predicted - measured) * np.sqrt(np.maximum(2.0 * (lp_max - lp), 0.0))

    def nll(self, measured, predicted):
        return -float(np.sum(self._log_mass(measured, predicted)))


@dataclass
class Branch:
    """One presliding branch: force change since the reversal (≥ 0) and displacement from it
    (in the branch's direction), with D = F_s - F_b of its direction (> 0).

    ``driven='force'``: the force is the applied input and the displacement is measured (its
    noise model is the data set's). ``driven='motion'``: the displacement is the imposed input
    and the friction change is measured (the data set's noise model is on force)."""

    force: np.ndarray
    displacement: np.ndarray
    D: float
    driven: str = "force"
    t_end: float = float("nan")  # time of the branch's last sample in its recording
    observed: bool = True  # the reversal that starts the branch is in the record (else: on the outer loop)


def branch_prediction(br: Branch, z_knots, F_knots, n, offset):
    """(measured, predicted) of one branch in the space its noise model lives in."""
    if br.driven == "motion":
        fg = np.linspace(0.0, 0.999 * br.D, GRID)
        xg = branch_displacement(z_knots, F_knots, n, br.D, fg)
        return br.force, np.interp(br.displacement - offset, xg, fg)
    return br.displacement, branch_displacement(z_knots, F_knots, n, br.D, br.force) + offset


@dataclass
class PreslidingData:
    branches: list
    noise: object
    name: str = "data"
    x_noise: float = 0.0  # σ of the displacement (what the knots must resolve)


@dataclass
class TransitionFit:
    z: np.ndarray
    F: np.ndarray
    stderr: np.ndarray
    covariance: np.ndarray
    n: float
    n_stderr: float | None
    nll: float
    offsets: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    flat: tuple = ()  # knots i whose increment F_i − F_(i−1) ended at its lower bound: the data do not resolve it
    unbounded: tuple = ()  # … at its upper bound: the data do not bound F_d there (not an estimate)
    beyond: tuple = ()  # knots i whose segment starts above every force change a branch reaches (``asked_force``)
    asked: float = 0.0  # that largest force change
    chi2: float = 0.0  # Σ r² over the branches with Gaussian noise (quantised readings have no χ²)
    dof: int = 0  # … their samples less the parameters they share and their own offsets

    @property
    def loose(self) -> tuple:
        """Knots i whose rise F_i − F_(i−1) has a σ over half its size: the branches do not
        determine that segment (the rule a Stribeck δ is held by, applied to a rise). A
        presliding branch that runs on past what eq. (5) holds — a lost motion, a backlash taken
        up — ends in such a segment, a last knot shooting up."""
        C, out = self.covariance, []
        for i in range(1, len(self.F)):
            var = C[i - 1, i - 1] + (C[i - 2, i - 2] - 2.0 * C[i - 1, i - 2] if i >= 2 else 0.0)
            if np.isfinite(var) and var > 0.0 and math.sqrt(var) > 0.5 * (self.F[i] - self.F[i - 1]):
                out.append(i)
        return tuple(out)


def asked_force(br: Branch, z_knots, F_knots, n, offset) -> float:
    """The largest force change at which the branch evaluates F_d⁻¹: its largest force change
    (below 0.999·D) where the force is the input, the force it is predicted to reach at its
    furthest displacement where the motion is. A segment of F_d starting above it for every
    branch changes no prediction: the likelihood does not depend on its rise at all."""
    if br.driven == "motion":
        # the prediction interpolates x(ΔF) on ``branch_prediction``'s grid: the grid point above
        # the largest one predicted is where F_d⁻¹ was last evaluated
        fg = np.linspace(0.0, 0.999 * br.D, GRID)
        top = float(np.max(branch_prediction(br, z_knots, F_knots, n, offset)[1]))
        return float(fg[min(int(np.searchsorted(fg, top, side="right")), GRID - 1)])
    return float(min(np.max(br.force), 0.999 * br.D))


def eq5_factor_integral(F, D: float, n: float):
    """∫_0^F dF'/(1 − (F'/D)^n) for 0 ≤ F < D, in closed form: F·₂F₁(1, 1/n; 1 + 1/n; x) with
    x = (F/D)^n (the series F·Σ x^k/(1 + nk)), evaluated through Pfaff's transformation as
    F·₂F₁(1, 1; 1 + 1/n; x/(x − 1))/(1 − x): scipy's ₂F₁ at x near 1 is wrong for a 1/n that is
    not whole (n = 0.7 at 0.999·D: −68 for 19), the transformed argument stays below 0 for every n.
    Exact where a force grid's trapezoids lose accuracy, as F nears D and the factor grows
    without bound (on Table II's curve with n = 7 a grid of 400 was off by 1.5e-7 at 0.97·D,
    three times a proximity sensor's noise)."""
    F = np.asarray(F, dtype=float)
    x = (F / D) ** n
    return F * hyp2f1(1.0, 1.0, 1.0 + 1.0 / n, x / (x - 1.0)) / (1.0 - x)


def branch_displacement(z_knots, F_knots, n, D, force):
    """x(ΔF) of the module docstring, for the force values ``force`` (≥ 0, at most 0.999·D
    used). On each segment of the piecewise-linear F_d, dF_d⁻¹/dF is a constant, so x is a sum of
    those constants times the factor's closed-form integral (``eq5_factor_integral``); beyond
    the last knot the last segment goes on."""
    z_knots, F_knots = np.asarray(z_knots, dtype=float), np.asarray(F_knots, dtype=float)
    top = 0.999 * D
    f = np.clip(np.asarray(force, dtype=float), 0.0, top)
    dz, dF = np.diff(z_knots), np.diff(F_knots)
    slope = np.divide(dz, dF, out=np.zeros(len(dF)), where=dF > 0)
    Fk = np.minimum(F_knots, top)
    Gk = eq5_factor_integral(Fk, D, n)
    # x at each knot (knots past 0.999·D add nothing: the force never gets there); a segment of
    # no force width (two knots at one F_d: F_d flat, its inverse jumping) moves the branch by its
    # z-width times eq. (5)'s factor at that force at once — the limit of a vanishing increment
    step = np.where(dF > 0, slope * np.diff(Gk), dz / (1.0 - (Fk[:-1] / D) ** n))
    at_knot = np.concatenate([[0.0], np.cumsum(step)])
    seg = np.clip(np.searchsorted(F_knots, f, side="right") - 1, 0, len(F_knots) - 2)
    return at_knot[seg] + slope[seg] * (eq5_factor_integral(f, D, n) - Gk[seg])


def _unpack(theta, n_knots, n_branches, fit_n, n_fixed):
    inc = np.exp(theta[:n_knots])
    F = np.concatenate([[0.0], np.cumsum(inc)])
    k = n_knots
    n = float(np.exp(theta[k])) if fit_n else n_fixed
    k += 1 if fit_n else 0
    offsets = theta[k : k + n_branches]
    return F, n, offsets


def _nll_F(F, n, offsets, z_knots, datasets):
    total = 0.0
    i = 0
    for ds in datasets:
        for br in ds.branches:
            total += ds.noise.nll(*branch_prediction(br, z_knots, F, n, offsets[i]))
            i += 1
    return total


def fit_transition_curve(datasets, z_knots, *, n: float = 7.0, fit_n: bool = False, F_start=None) -> TransitionFit:
    """ML ordinates of F_d at the abscissas ``z_knots`` (first 0), from one or more data sets."""
    z_knots = np.asarray(z_knots, dtype=float)
    if z_knots[0] != 0.0 or np.any(np.diff(z_knots) <= 0):
        raise ValueError("transition curve knots: abscissas must start at 0 and increase strictly")
    branches = [br for ds in datasets for br in ds.branches]
    if not branches:
        raise IdentificationError("maximum-likelihood estimator: no presliding branches in the data")
    nk = len(z_knots) - 1
    if F_start is None:
        # the force at which the longest branch has moved z_i (z ≈ x while F_d ≪ D)
        br = max(branches, key=lambda b: np.ptp(b.displacement))
        x_rel = np.maximum.accumulate(br.displacement - br.displacement[0])
        F_start = np.interp(z_knots, x_rel, np.maximum.accumulate(br.force), right=np.max(br.force))
        F_start = np.maximum.accumulate(F_start) + 1e-3 * np.max(br.force) * np.arange(len(z_knots))
        F_start[0] = 0.0
    x_scale = max(np.ptp(b.displacement) for b in branches) or 1.0
    # the increments as log factors of the start's: θ = 0 at the start in any unit, so the
    # optimiser's steps and its stopping test (relative to |θ|) are the same for a recording
    # written in N or in mN — as the log of an increment in the file's unit they were not, and
    # the same recording re-expressed stopped at another point of a flat likelihood
    log_start = np.log(np.diff(F_start))
    theta0 = np.zeros(nk)
    if fit_n:
        theta0 = np.append(theta0, np.log(n))
    # offsets in units of the displacement span: keeps the problem well scaled
    theta0 = np.append(theta0, [(b.displacement[0] if b.driven == "force" else 0.0) / x_scale for b in branches])

    def split(theta):
        th = theta.copy()
        th[:nk] += log_start
        th[nk + (1 if fit_n else 0):] *= x_scale
        return _unpack(th, nk, len(branches), fit_n, n)

    def resid(theta):
        F, nn, off = split(theta)
        out = []
        i = 0
        for ds in datasets:
            for br in ds.branches:
                out.append(ds.noise.residuals(*branch_prediction(br, z_knots, F, nn, off[i])))
                i += 1
        return np.concatenate(out)

    # increments of F_d between knots stay within a physical range (a flat likelihood must not
    # send a segment to infinite stiffness)
    f_max = max(np.max(b.force) for b in branches)
    lo = np.full(len(theta0), -np.inf)
    hi = np.full(len(theta0), np.inf)
    lo[:nk], hi[:nk] = np.log(1e-6 * f_max) - log_start, np.log(20.0 * f_max) - log_start
    if fit_n:
        # n ≥ 1: below it eq. (5)'s slope dz/dx = 1 − |F_d/D|^n has an infinite derivative in F_d
        # at F_d = 0, at every reversal, and the simulator's implicit step (|r|^(n−1) at r = 0)
        # gives NaN (a joint's Maxwell-slip curve fitted n = 0.63, and its file simulated to NaN)
        lo[nk], hi[nk] = np.log(N_MIN), np.log(50.0)
    theta0 = np.clip(theta0, lo + 1e-9, hi - 1e-9)
    ns = nk + (1 if fit_n else 0)

    def jac(theta):
        # shared parameters move every residual; each offset moves only its own branch's
        r0 = resid(theta)
        J = np.zeros((len(r0), len(theta)))
        for j in range(ns):
            h = 1e-7 * max(1.0, abs(theta[j]))
            tp = theta.copy()
            tp[j] += h
            J[:, j] = (resid(tp) - r0) / h
        F, nn, off = split(theta)
        row = 0
        i = 0
        for ds in datasets:
            for br in ds.branches:
                m = len(br.force)
                h = 1e-6
                J[row : row + m, ns + i] = (ds.noise.residuals(*branch_prediction(br, z_knots, F, nn, off[i] + h * x_scale))
                                            - r0[row : row + m]) / h
                row += m
                i += 1
        return J

    best = least_squares(resid, theta0, jac=jac, bounds=(lo, hi), method="trf", x_scale="jac", xtol=1e-12,
                         ftol=1e-12, gtol=1e-12)
    F, nn, off = split(best.x)
    best.fun = float(0.5 * np.sum(best.fun ** 2))
    # an increment held at a bound by the optimiser is where the likelihood kept pushing it:
    # at the lower one a segment the data leave flat, at the upper one (20× the largest force
    # change of any branch) one they do not bound at all
    at = BOUND_TOL * np.maximum(1.0, np.abs(hi[:nk] - lo[:nk]))
    flat = tuple(int(i) + 1 for i in np.flatnonzero(best.x[:nk] <= lo[:nk] + at))
    unbounded = tuple(int(i) + 1 for i in np.flatnonzero(best.x[:nk] >= hi[:nk] - at))
    # a knot whose segment starts above every force change a branch asks of F_d has a rise the
    # likelihood does not depend on: wherever the optimiser leaves it, it is no estimate, and its
    # σ from the Hessian (zero information, inverted by a pseudo-inverse) is no error bar (a
    # stage whose branches slide at 0.55 N wrote two knots above 0.58 N "± 1e-9", flat, and its
    # transitions never reached the other sliding direction)
    offs, asked, i = list(off), 0.0, 0
    for ds in datasets:
        for br in ds.branches:
            asked = max(asked, asked_force(br, z_knots, F, nn, offs[i]))
            i += 1
    beyond = tuple(i for i in range(1, len(F)) if F[i - 1] >= asked)

    # n held at its bound is no estimate: the knots' σ are those with n fixed there
    n_at_bound = bool(fit_n and best.x[nk] <= lo[nk] + BOUND_TOL * (hi[nk] - lo[nk]))
    H = _information(z_knots, F, nn, fit_n and not n_at_bound, off, datasets)
    notes = []
    try:
        cov = np.linalg.inv(H)
        if np.any(np.diag(cov) < 0):
            raise np.linalg.LinAlgError
    except np.linalg.LinAlgError:
        cov = np.linalg.pinv(H)
        notes.append("the likelihood is flat in some direction: error bars are lower bounds")
    sd = np.sqrt(np.abs(np.diag(cov)))
    # goodness of fit where it has a χ² (Gaussian readings): a curve whose shape misfits its
    # branches has σ that say the noise's spread only (the caller says so)
    chi2, samples, gauss, i = 0.0, 0, 0, 0
    for ds in datasets:
        for br in ds.branches:
            if isinstance(ds.noise, Gaussian):
                chi2 += float(np.sum(ds.noise.residuals(*branch_prediction(br, z_knots, F, nn, off[i])) ** 2))
                samples += len(br.force)
                gauss += 1
            i += 1
    dof = max(samples - (ns if gauss else 0) - gauss, 0)
    if n_at_bound:
        # a small n bends the branch away from its first stiffness early: below 1, more gradually
        # than eq. (5) can at any n the simulator takes
        notes.append(f"n at its lower bound {N_MIN:g}: the branches run into sliding more gradually than eq. (5) "
                     f"does at n = {N_MIN:g}; n is held there, not estimated")
    return TransitionFit(
        z=z_knots, F=F, stderr=np.concatenate([[0.0], sd[:nk]]), covariance=cov[:nk, :nk], n=nn,
        n_stderr=float(sd[nk]) if fit_n and not n_at_bound else None, nll=float(best.fun), offsets=list(map(float, off)), notes=notes,
        flat=flat, unbounded=unbounded, beyond=beyond, asked=asked, chi2=chi2, dof=dof,
    )


BOUND_TOL = 1e-3  # a log-increment within this fraction of its range from a bound is at it
N_MIN = 1.0  # the smallest n of eq. (5) the simulator takes (``model.params``' bound; see ``fit_transition_curve``)


def _hessian(f, x, h):
    """Central-difference Hessian with steps ``h``."""
    k = len(x)
    H = np.zeros((k, k))
    f0 = f(x)
    E = np.diag(h)
    for i in range(k):
        H[i, i] = (f(x + E[i]) - 2 * f0 + f(x - E[i])) / h[i] ** 2
        for j in range(i + 1, k):
            H[i, j] = H[j, i] = (f(x + E[i] + E[j]) - f(x + E[i] - E[j]) - f(x - E[i] + E[j])
                                 + f(x - E[i] - E[j])) / (4 * h[i] * h[j])
    return H


def _information(z_knots, F, n, fit_n, offsets, datasets):
    """Observed information: the Hessian of -log L in (F_1..F_k[, n], offsets), the
    curvature of the likelihood at its maximum. Each branch depends on the shared parameters
    and its own offset only, so the matrix is assembled from small per-branch Hessians."""
    nk = len(F) - 1
    ns = nk + (1 if fit_n else 0)
    nb = len(offsets)
    shared = np.concatenate([F[1:], [n] if fit_n else []])
    h_shared = 1e-4 * np.maximum(np.abs(shared), 1e-3 * np.max(np.abs(F)))
    H = np.zeros((ns + nb, ns + nb))
    i = 0
    for ds in datasets:
        scale = getattr(ds.noise, "sigma", None) or ds.noise.jitter
        for br in ds.branches:
            def f(p, br=br, noise=ds.noise):
                FF = np.concatenate([[0.0], p[:nk]])
                nn = p[nk] if fit_n else n
                return noise.nll(*branch_prediction(br, z_knots, FF, nn, p[-1]))

            idx = list(range(ns)) + [ns + i]
            h_off = 0.05 * scale if br.driven == "force" else 1e-3 * max(np.ptp(br.displacement), 1e-300)
            H[np.ix_(idx, idx)] += _hessian(f, np.append(shared, offsets[i]), np.append(h_shared, h_off))
            i += 1
    return H
