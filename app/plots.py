"""Plotly figures: pure functions of model results, shared by the web app and the HTML report.

Figures are written as plain Plotly dicts and wrapped without validation: building a
validated ``go.Figure`` costs ~50 ms per plot, which the live app cannot afford on every
slider move. The styling is therefore explicit (no named template).
"""

from __future__ import annotations

import numpy as np
import plotly.graph_objects as go

from ..model import stribeck_curve
from ..model.experiments import ExperimentResult

COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")
MAX_POINTS = 1000


def _thin(*arrays, n=MAX_POINTS):
    """Every k-th sample so that a plot holds at most ``n`` points (keeps the last one)."""
    size = len(arrays[0])
    if size <= n:
        return arrays
    idx = np.unique(np.concatenate([np.arange(0, size, int(np.ceil(size / n))), [size - 1]]))
    return tuple(a[idx] for a in arrays)


AXIS = dict(gridcolor="#e5e5e5", zerolinecolor="#bbbbbb", linecolor="#444444", ticks="outside", automargin=True)


class _Fig:
    """Collects traces as dicts; ``_layout`` wraps them into an unvalidated go.Figure."""

    def __init__(self):
        self.data = []
        self.layout = {}

    def add_trace(self, trace: dict, row: int | None = None, col: int | None = None):
        if row == 2:
            trace = dict(trace, xaxis="x2", yaxis="y2")
        self.data.append(trace)


def _scatter(x, y, **kw) -> dict:
    return dict(type="scatter", x=np.asarray(x), y=np.asarray(y), **kw)


def _layout(fig: _Fig, title: str, xlabel: str, ylabel: str, **extra) -> go.Figure:
    layout = dict(title=dict(text=title), xaxis=dict(AXIS, title=dict(text=xlabel)),
                  yaxis=dict(AXIS, title=dict(text=ylabel)), plot_bgcolor="white", paper_bgcolor="white",
                  font=dict(family="Open Sans, Arial, sans-serif", size=12),
                  margin=dict(l=60, r=20, t=50, b=50), legend=dict(orientation="h", y=-0.2))
    for k, v in extra.items():
        layout[k] = dict(layout.get(k, {}), **v) if isinstance(v, dict) else v
    layout.update(fig.layout)
    return go.Figure(dict(data=fig.data, layout=layout), _validate=False)


def hysteresis_figure(runs: list, units: dict | None = None) -> go.Figure:
    """Presliding force–displacement: (label, SimResult) pairs of the A→B→C→D ramp."""
    u = units or {"position": "rad", "force": "N*m"}
    fig = _Fig()
    for i, (label, r) in enumerate(runs):
        x, F = _thin(r.position, r.friction_force)
        fig.add_trace(_scatter(x=x * 1e6, y=F, mode="lines", name=label, line=dict(color=COLORS[i % 6])))
    return _layout(fig, "Presliding hysteresis (A→B→C→D ramp)", f"displacement (µ{u['position']})", f"friction ({u['force']})")


def stribeck_figure(params_list: list, levels=None, units: dict | None = None) -> go.Figure:
    """S(v) + σ2·v for both velocity signs; measured levels as points when given."""
    u = units or {"position": "rad", "force": "N*m"}
    vmax = 0.3
    if levels is not None and len(levels.velocity):
        vmax = float(np.max(np.abs(levels.velocity))) * 1.1
    mags = np.logspace(np.log10(vmax) - 3.5, np.log10(vmax), 300)
    v = np.concatenate([-mags[::-1], mags])
    fig = _Fig()
    for i, (label, p) in enumerate(params_list):
        F = stribeck_curve(p, v)
        fig.add_trace(_scatter(x=v[v > 0], y=F[v > 0], mode="lines", name=f"{label} (v > 0)", line=dict(color=COLORS[i % 6])))
        fig.add_trace(_scatter(x=v[v < 0], y=F[v < 0], mode="lines", name=f"{label} (v < 0)",
                                 line=dict(color=COLORS[i % 6], dash="dot")))
    if levels is not None and len(levels.velocity):
        fig.add_trace(_scatter(x=levels.velocity, y=levels.friction, mode="markers", name="measured levels",
                                 error_y=dict(array=np.sqrt(levels.variance)), marker=dict(color="black", size=6)))
    return _layout(fig, "Constant-velocity friction S(v) + σ2·v", f"velocity ({u['position']}/s)", f"friction ({u['force']})")


def stick_slip_figure(runs: list, units: dict | None = None) -> go.Figure:
    """Position and friction against time under P control."""
    u = units or {"position": "rad", "force": "N*m"}
    fig = _Fig()
    for i, (label, r) in enumerate(runs):
        t, x, F = _thin(r.time, r.position, r.friction_force)
        c = COLORS[i % 6]
        fig.add_trace(_scatter(x=t, y=x, mode="lines", name=f"{label} position", line=dict(color=c)), row=1, col=1)
        fig.add_trace(_scatter(x=t, y=F, mode="lines", name=f"{label} friction", line=dict(color=c, dash="dot")),
                      row=2, col=1)
    return _layout(fig, "Stick-slip under P control", "", f"position ({u['position']})",
                   yaxis=dict(domain=[0.55, 1.0]), xaxis=dict(anchor="y", matches="x2", showticklabels=False),
                   xaxis2=dict(AXIS, title=dict(text="time (s)"), anchor="y2"),
                   yaxis2=dict(AXIS, domain=[0.0, 0.45], title=dict(text=f"friction ({u['force']})")))


def experiment_figure(res: ExperimentResult, units: dict | None = None) -> go.Figure:
    """The figure of one named paper experiment."""
    u = units or {"position": "rad", "force": "N*m"}
    s = res.summary
    fig = _Fig()
    if res.name == "breakaway":
        fig.add_trace(_scatter(x=s["rate"], y=s["breakaway_force"], mode="lines+markers", name="break-away"))
        return _layout(fig, "Break-away force vs force rate (Fig. 13)", f"rate ({u['force']}/s)",
                       f"peak friction ({u['force']})", xaxis=dict(type="log"))
    if res.name == "frictional_lag":
        for i, (label, r) in enumerate(zip(res.labels, res.runs)):
            last = r.time >= r.time[-1] - (r.time[-1] / 2)
            v, F = _thin(r.velocity[last], r.friction_force[last])
            fig.add_trace(_scatter(x=v, y=F, mode="lines", name=label, line=dict(color=COLORS[i % 6])))
        return _layout(fig, "Frictional lag (Fig. 14)", f"velocity ({u['position']}/s)", f"friction ({u['force']})")
    if res.name == "tracking":
        ref = s["reference"]
        for i, (label, r) in enumerate(zip(res.labels, res.runs)):
            t, e = _thin(r.time, ref - r.position)
            fig.add_trace(_scatter(x=t, y=e, mode="lines", name=label, line=dict(color=COLORS[i % 6])))
        return _layout(fig, "Tracking errors (Fig. 17)", "time (s)", f"error ({u['position']})")
    if res.name == "constant_velocity_sweep":
        fig.add_trace(_scatter(x=s["velocity"], y=s["mean_friction"], mode="markers", name="simulated steady state"))
        return _layout(fig, "Constant-velocity sweep (Fig. 8)", f"velocity ({u['position']}/s)", f"friction ({u['force']})")
    if res.name == "stick_slip":
        return stick_slip_figure(list(zip(res.labels, res.runs)), units)
    for i, (label, r) in enumerate(zip(res.labels, res.runs)):
        x, F = _thin(r.position, r.applied_force)
        fig.add_trace(_scatter(x=x, y=F, mode="lines", name=label, line=dict(color=COLORS[i % 6])))
    return _layout(fig, res.name.replace("_", " "), f"displacement ({u['position']})", f"applied force ({u['force']})")


def transition_fit_figure(fit, datasets, units: dict | None = None) -> go.Figure:
    """Presliding branches (measured displacement minus offset) over the fitted curve."""
    from ..identify.mle import branch_displacement

    u = units or {"position": "rad", "force": "N*m"}
    fig = _Fig()
    i = 0
    for ds in datasets:
        for br in ds.branches:
            f, x = _thin(br.force, br.displacement - fit.offsets[i], n=400)
            fig.add_trace(_scatter(x=x * 1e6, y=f, mode="markers", marker=dict(size=3, color="gray"),
                                     name="measured", showlegend=i == 0))
            model_x = branch_displacement(fit.z, fit.F, fit.n, br.D, br.force)
            fig.add_trace(_scatter(x=model_x * 1e6, y=br.force, mode="lines", line=dict(color=COLORS[0]),
                                     name="model", showlegend=i == 0))
            i += 1
    return _layout(fig, "Presliding branches: data and fitted transition curve", f"displacement since reversal (µ{u['position']})",
                   f"force change ({u['force']})")


# ---------------------------------------------------------------- the discrepancy workflow
EXPLAINED_BY = {"position_periodic": "position", "position_smooth": "position", "time_drift": "time",
                "normal_load": "load", "viscous_shape": "velocity", "cyclic_softening": "reversals",
                "sign_asymmetry": "velocity", "presliding_stiffness": "velocity", "frictional_lag": "time"}


def diagnosis_time_figure(d, units: dict | None = None) -> go.Figure:
    """Measured friction and the model before and after adding the effect, against time."""
    u = units or d.params_before.units
    fig = _Fig()
    t, m, b, a = _thin(d.time, d.measured, d.model_before, d.model_after, n=4000)
    fig.add_trace(_scatter(t, m, mode="markers", name="measured", marker=dict(size=2, color="#7f7f7f")))
    fig.add_trace(_scatter(t, b, mode="lines", name="model before", line=dict(color=COLORS[1], width=1)))
    if d.effect:
        fig.add_trace(_scatter(t, a, mode="lines", name=f"with {d.effect}", line=dict(color=COLORS[0], width=1)))
    return _layout(fig, "Measured and simulated friction", "time (s)", f"friction ({u['force']})")


def regime_figure(d) -> go.Figure:
    """RMS gap per regime, before and after."""
    names = list(d.regimes)
    fig = _Fig()
    fig.add_trace(dict(type="bar", x=names, y=[d.regimes[k]["rms_before"] for k in names], name="before",
                       marker=dict(color=COLORS[1])))
    fig.add_trace(dict(type="bar", x=names, y=[d.regimes[k]["rms_after"] for k in names], name="after",
                       marker=dict(color=COLORS[0])))
    return _layout(fig, "RMS gap per regime", "", f"RMS ({d.params_before.units['force']})", barmode="group",
                   xaxis=dict(tickangle=-40))


def residual_figure(d, variable: str | None = None) -> go.Figure:
    """Residual against the variable that explains the named effect (or time)."""
    var = variable or EXPLAINED_BY.get(d.effect or "", "time")
    if var not in d.explaining:
        var = "time"
    label, values = d.explaining[var]
    fig = _Fig()
    x, rb, ra = _thin(values, d.measured - d.model_before, d.measured - d.model_after, n=4000)
    fig.add_trace(_scatter(x, rb, mode="markers", name="before", marker=dict(size=2, color=COLORS[1])))
    if d.effect:
        fig.add_trace(_scatter(x, ra, mode="markers", name="after", marker=dict(size=2, color=COLORS[0])))
    return _layout(fig, f"Residual against {label}", label, f"measured − model ({d.params_before.units['force']})")


def candidates_figure(d) -> go.Figure:
    """How much of the RMS gap each candidate removes (significant ones in colour)."""
    names = [c["name"] for c in d.candidates]
    fig = _Fig()
    fig.add_trace(dict(type="bar", x=[100 * c["reduction"] for c in d.candidates], y=names, orientation="h",
                       marker=dict(color=[COLORS[2] if c["significant"] else "#bbbbbb" for c in d.candidates]),
                       name="RMS reduction"))
    return _layout(fig, "Candidate effects: RMS gap removed", "% of the RMS gap", "", yaxis=dict(autorange="reversed"))


def diagnosis_figures(d) -> list:
    return [diagnosis_time_figure(d), residual_figure(d), regime_figure(d), candidates_figure(d)]
