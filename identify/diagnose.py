"""The discrepancy workflow: compare, name, add, refit, show the gap shrink.

1. **Compare** — simulate the current model on the recorded motion (the path of
   ``leuven-friction simulate --input``) and break the residual down by regime.
2. **Name** — the alternative every effect must beat is the current model with S(v) refitted
   to every sample by simulation (output error). Every candidate of ``model.effects.EFFECTS``
   is screened against that model's residual (its columns fitted by least squares, its shape
   parameter scanned; the presliding effects by re-simulation). The ``leading`` candidates are
   then refitted properly — S(v) and the effect together, by simulation — and judged by the
   Bayesian information criterion with the effective number of independent samples (lag-1
   autocorrelation of the residual), plus a practical threshold: an effect must remove at least
   ``MIN_REDUCTION`` of the RMS gap to be named (on long recordings BIC alone calls a 1 %
   improvement "very strong").
3. **Add** — the winner becomes part of the model (its parameters in ``effects``, the stretched
   transition curve, or the direction asymmetry) with the refitted S(v), and the gap before
   and after is reported overall and per regime.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from ..model import FrictionParams, Stribeck, StribeckSide, simulate_displacement, transition_curve_values
from ..model.effects import (EFFECTS, SHAPE, Signals, apply_effects, basis, direction_scaled_path, reversal_count,
                           stiffness_scaled)

from .data import DataError, Recording, velocity_of

MIN_REDUCTION = 0.10  # RMS fraction an effect must remove to be named
BIC_THRESHOLD = -10.0  # "very strong" evidence on Kass & Raftery's scale
V_SLIDE = 1e-3  # |v| above which a sample counts as sliding (position units per second)
NEAR_REVERSAL_S = 0.1


@dataclass
class Diagnosis:
    effect: str | None
    description: str | None
    effect_params: dict | None
    rms_before: float
    rms_after: float
    regimes: dict  # regime -> {"n", "rms_before", "rms_after"}
    candidates: list  # ranked dicts: name, rms_after, reduction, delta_bic, params, significant
    params_before: FrictionParams
    params_after: FrictionParams
    time: np.ndarray = field(repr=False, default=None)
    measured: np.ndarray = field(repr=False, default=None)
    model_before: np.ndarray = field(repr=False, default=None)
    model_after: np.ndarray = field(repr=False, default=None)
    explaining: dict = field(repr=False, default_factory=dict)  # name -> (label, values)
    rms_base_refit: float | None = None  # the current model with only S(v) refitted

    def summary(self) -> dict:
        return {
            "effect": self.effect,
            "description": self.description,
            "effect_params": self.effect_params,
            "rms_before": self.rms_before,
            "rms_after": self.rms_after,
            "rms_base_refit": self.rms_base_refit,
            "regimes": self.regimes,
            "candidates": self.candidates,
        }

    def text(self) -> str:
        u = self.params_before.units.get("force", "")
        lines = []
        if self.effect:
            lines.append(f"Missing effect: {self.effect} — {self.description}.")
            lines.append("  parameters: " + ", ".join(f"{k} = {v:.4g}" for k, v in self.effect_params.items()))
        else:
            lines.append("No significant missing effect: the base model explains the data to within its noise.")
        lines.append(f"RMS gap: {self.rms_before:.4g} {u} before, {self.rms_after:.4g} {u} after "
                     f"({100 * (1 - self.rms_after / self.rms_before):.1f} % smaller)")
        if self.rms_base_refit is not None:
            lines.append(f"(refitting S(v) alone, without an effect, gives {self.rms_base_refit:.4g} {u})")
        lines.append("Per regime (RMS before → after):")
        for k, r in self.regimes.items():
            lines.append(f"  {k:28s} n={r['n']:7d}  {r['rms_before']:.4g} → {r['rms_after']:.4g}")
        lines.append("Candidates (best first):")
        for c in self.candidates:
            mark = "*" if c["significant"] else " "
            how = "refitted" if c["refitted"] else "screened"
            lines.append(f" {mark} {c['name']:22s} RMS -{100 * c['reduction']:5.1f} %   ΔBIC {c['delta_bic']:10.1f}  ({how})")
        return "\n".join(lines)


def friction_signal(rec: Recording, params: FrictionParams) -> np.ndarray:
    """The measured friction, or the applied force minus I·ẍ (eq. (8)) when only that exists."""
    if rec.friction is not None:
        return rec.friction
    if rec.force is None or rec.position is None:
        raise DataError(f"{rec.source}: diagnosis needs a friction column, or applied force and position")
    v = velocity_of(rec)
    a = np.zeros_like(v)
    a[1:] = np.diff(v) / np.diff(rec.time)
    return rec.force - params.inertia * a


def simulate_signals(params: FrictionParams, rec: Recording) -> Signals:
    """The model's signals along the recorded motion (with a stored direction asymmetry, the
    positive increments of the path rescaled, see ``model.effects.direction_scaled_path``)."""
    if rec.position is None:
        raise DataError(f"{rec.source}: diagnosis needs a position column")
    x = rec.position
    for eff in params.effects:
        if eff.get("name") == "sign_asymmetry":
            x = direction_scaled_path(x, eff["params"]["c_up"])
    r = simulate_displacement(params, rec.time, x)
    fd = transition_curve_values(params, r.z) if params.model == "leuven" else r.hysteresis_force
    return Signals(time=rec.time, position=rec.position, velocity=r.velocity, friction=r.friction_force,
                   transition=fd, reversals=reversal_count(r.velocity), load=rec.normal_load)


def regime_masks(s: Signals) -> dict:
    v = s.velocity
    masks = {"all": np.ones(len(v), bool), "presliding": np.abs(v) < V_SLIDE, "sliding, v > 0": v >= V_SLIDE,
             "sliding, v < 0": v <= -V_SLIDE}
    rev_idx = np.flatnonzero(np.diff(s.reversals) > 0) + 1
    near = np.zeros(len(v), bool)
    for i in rev_idx:
        near[i : np.searchsorted(s.time, s.time[i] + NEAR_REVERSAL_S)] = True
    masks["within 0.1 s of a reversal"] = near
    for label, values in (("position", s.position), ("time", s.time), ("reversals", s.reversals),
                          ("load", s.load)):
        if values is None or np.ptp(values) == 0:
            continue
        edges = np.unique(np.quantile(values, np.linspace(0, 1, 5)))
        for a, b in zip(edges[:-1], edges[1:]):
            masks[f"{label} {a:.3g}…{b:.3g}"] = (values >= a) & (values <= b)
    return masks


def _rms(a):
    return float(np.sqrt(np.mean(a**2))) if len(a) else float("nan")


def _effective_n(resid: np.ndarray) -> float:
    r = resid - resid.mean()
    rho = float(np.dot(r[1:], r[:-1]) / max(np.dot(r, r), 1e-300))
    rho = min(max(rho, 0.0), 0.999)
    return len(r) * (1 - rho) / (1 + rho)


def _linear_fit(B, resid):
    coef, *_ = np.linalg.lstsq(B, resid, rcond=None)
    return coef, resid - B @ coef


def _scan(fn, grid):
    """Best of ``fn(shape) -> rss`` over a log grid, then refined between the neighbours."""
    vals = [fn(g) for g in grid]
    i = int(np.argmin(vals))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, len(grid) - 1)]
    if hi > lo:
        r = minimize_scalar(lambda lg: fn(np.exp(lg)), bounds=(np.log(lo), np.log(hi)), method="bounded",
                            options={"xatol": 1e-3})
        if r.fun < vals[i]:
            return float(np.exp(r.x))
    return float(grid[i])


RESIMULATED = {
    # presliding effects that change what is simulated, with their one parameter
    "presliding_stiffness": lambda p, rec, c: simulate_displacement(stiffness_scaled(p, c), rec.time,
                                                                     rec.position).friction_force,
    "sign_asymmetry": lambda p, rec, c: simulate_displacement(p, rec.time,
                                                              direction_scaled_path(rec.position, c)).friction_force,
}


def fit_candidate(name: str, s: Signals, resid: np.ndarray, params: FrictionParams, rec: Recording,
                  measured: np.ndarray) -> dict | None:
    """Fit one candidate; returns its parameters, new residual and number of parameters."""
    if name in RESIMULATED:
        def predict(c):
            return RESIMULATED[name](params, rec, c)

        c = _scan(lambda c: float(np.sum((measured - predict(c)) ** 2)), np.exp(np.linspace(np.log(0.25), np.log(4.0), 9)))
        return {"params": {EFFECTS[name][2][0]: c}, "resid": measured - predict(c), "k": 1}
    shape_name = SHAPE.get(name)
    if shape_name is None:
        B = basis(name, s)
        if B is None:
            return None
        coef, new = _linear_fit(B, resid)
        return {"params": dict(zip(EFFECTS[name][2], map(float, coef))), "resid": new, "k": B.shape[1]}
    if name == "position_periodic":
        span = float(np.ptp(s.position)) or 1.0
        grid = np.exp(np.linspace(np.log(span / 200), np.log(span), 40))
    else:  # frictional_lag time constant
        grid = np.exp(np.linspace(np.log(1e-3), np.log(2.0), 16))
    shape = _scan(lambda g: float(np.sum(_linear_fit(basis(name, s, g), resid)[1] ** 2)), grid)
    B = basis(name, s, shape)
    coef, new = _linear_fit(B, resid)
    out = dict(zip(EFFECTS[name][2], map(float, coef)))
    out[shape_name] = shape
    return {"params": out, "resid": new, "k": B.shape[1] + 1}


def _with_stribeck(params: FrictionParams, theta: np.ndarray) -> FrictionParams:
    return params.replace(stribeck=Stribeck(StribeckSide(*map(float, theta[:5])), StribeckSide(*map(float, theta[5:]))))


def output_error_refit(params: FrictionParams, rec: Recording, measured: np.ndarray, name: str | None = None,
                       fit: dict | None = None, max_nfev: int = 6) -> dict:
    """The model refitted by simulation to every sample: S(v) of both signs (10 values), and
    the candidate effect's parameters — its linear coefficients solved at every step
    (variable projection) with its shape parameter held, or its one parameter when the effect
    changes the simulation. Returns params, effect parameters and the residual."""
    theta0 = params.stribeck.as_array()
    resim = name in RESIMULATED
    key = EFFECTS[name][2][0] if resim else None
    u0 = np.zeros(10 + (1 if resim else 0))
    shape_name = SHAPE.get(name) if name else None
    shape = fit["params"].get(shape_name) if (fit and shape_name) else None
    c_resim = fit["params"][key] if resim else None
    state = {}

    def residual(u):
        # θ = θ0·exp(u): every S(v) value keeps its sign (Table I convention)
        p = _with_stribeck(params, theta0 * np.exp(u[:10]))
        if resim:
            r = measured - RESIMULATED[name](p, rec, c_resim * np.exp(u[10]))
            coef = None
        else:
            s = simulate_signals(p, rec)
            r = measured - s.friction
            coef = None
            if name is not None:
                B = basis(name, s, shape)
                coef, r = _linear_fit(B, r)
        state[u.tobytes()] = (p, coef)
        return r

    # a refit, not a new identification: each S(v) value stays within a factor 3 of where it
    # started (unbounded, S(v) drifts into shapes that fit one recording and mean nothing)
    bound = np.full(len(u0), np.log(3.0))
    if resim:
        bound[10] = np.log(20.0)
    sol = least_squares(residual, u0, bounds=(-bound, bound), method="trf", diff_step=1e-4, max_nfev=max_nfev,
                        x_scale=1.0)
    r = residual(sol.x)
    p, coef = state[sol.x.tobytes()]
    eff = None
    if resim:
        eff = {key: float(c_resim * np.exp(sol.x[10]))}
    elif name is not None:
        eff = dict(zip(EFFECTS[name][2], map(float, coef)))
        if shape_name:
            eff[shape_name] = float(shape)
    k = (1 if resim else (len(EFFECTS[name][2]) + (1 if shape_name else 0))) if name else 0
    return {"params": eff, "base": p, "resid": r, "k": k}


def diagnose(rec: Recording, params: FrictionParams, *, progress=None, leading: int = 3) -> Diagnosis:
    """Run the workflow on one recording with the current model ``params``."""
    say = progress or (lambda frac, msg: None)
    measured = friction_signal(rec, params)
    say(0.02, "simulating the current model on the recorded motion")
    s_cur = simulate_signals(params, rec)
    resid_cur = measured - s_cur.friction
    rms0 = _rms(resid_cur)
    # the alternative every effect must beat: the same model with S(v) refitted to all samples
    say(0.05, "refitting S(v) to every sample (output error)")
    base = output_error_refit(params, rec, measured)
    s = simulate_signals(base["base"], rec)
    resid = measured - s.friction
    rss_base = float(np.sum(resid**2))
    names = [n for n in EFFECTS if not (n == "normal_load" and rec.normal_load is None)]
    screened = []
    for i, name in enumerate(names):
        say(0.15 + 0.35 * i / len(names), f"screening {name}")
        fit = fit_candidate(name, s, resid, base["base"], rec, measured)
        if fit is not None:
            screened.append((float(np.sum(fit["resid"] ** 2)), name, fit))
    screened.sort(key=lambda x: x[0])
    cands = []
    for j, (rss_screen, name, fit) in enumerate(screened):
        if j < leading:
            say(0.5 + 0.4 * j / leading, f"refitting the model with {name}")
            fit = output_error_refit(base["base"], rec, measured, name, fit)
        else:
            fit["base"] = base["base"]
        rss1 = float(np.sum(fit["resid"] ** 2))
        n_eff = _effective_n(fit["resid"])
        dbic = n_eff * np.log(max(rss1, 1e-300) / rss_base) + fit["k"] * np.log(n_eff)
        reduction = 1.0 - np.sqrt(rss1 / rss_base)
        cands.append({"name": name, "description": EFFECTS[name][0], "params": fit["params"],
                      "rms_after": _rms(fit["resid"]), "reduction": float(reduction), "delta_bic": float(dbic),
                      "refitted": j < leading,
                      "significant": bool(j < leading and dbic < BIC_THRESHOLD and reduction >= MIN_REDUCTION),
                      "_resid": fit["resid"], "_base": fit["base"]})
    cands.sort(key=lambda c: (not c["refitted"], c["delta_bic"]))
    winner = cands[0] if cands and cands[0]["significant"] else None
    for c in cands[1:]:
        c["significant"] = False  # one effect is named per run; run again to look for another
    say(0.95, "reporting")
    if winner is None:
        after_resid, new_params, model_after = resid_cur, params, s_cur.friction
    else:
        after_resid = winner["_resid"]
        model_after = measured - after_resid
        fitted = winner["_base"]
        entry = {"name": winner["name"], "params": winner["params"]}
        if winner["name"] == "presliding_stiffness":
            fitted = stiffness_scaled(fitted, winner["params"]["scale"])
            entry["applied_to"] = "transition_curve"
        elif winner["name"] == "sign_asymmetry":
            entry["applied_to"] = "displacement path"
        # S(v) was refitted by output error: the Markov standard deviations no longer apply
        unc = {k: v for k, v in params.uncertainty.items() if not k.startswith("stribeck.")}
        prov = dict(params.provenance, diagnosis=f"{winner['name']} added; S(v) refitted by simulation")
        new_params = fitted.replace(effects=tuple(params.effects) + (entry,), uncertainty=unc, provenance=prov)
    regimes = {}
    for k, m in regime_masks(s_cur).items():
        if m.any():
            regimes[k] = {"n": int(m.sum()), "rms_before": _rms(resid_cur[m]), "rms_after": _rms(after_resid[m])}
    explaining = {"position": ("position", s.position), "time": ("time (s)", s.time),
                  "velocity": ("velocity", s.velocity), "reversals": ("number of reversals", s.reversals)}
    if s.load is not None:
        explaining["load"] = ("normal load", s.load)
    for c in cands:
        c.pop("_resid")
        c.pop("_base")
    say(1.0, "done")
    return Diagnosis(
        effect=winner["name"] if winner else None, description=winner["description"] if winner else None,
        effect_params=winner["params"] if winner else None, rms_before=rms0, rms_after=_rms(after_resid),
        regimes=regimes, candidates=cands, params_before=params, params_after=new_params, time=rec.time,
        measured=measured, model_before=s_cur.friction, model_after=model_after, explaining=explaining,
        rms_base_refit=_rms(resid),
    )


def model_with_effects(params: FrictionParams, rec: Recording) -> np.ndarray:
    """The friction predicted by ``params`` including its stored output effects."""
    return apply_effects(params.effects, simulate_signals(params, rec))
