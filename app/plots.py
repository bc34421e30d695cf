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


def shown_unit(unit: str) -> str:
    """A unit as the page writes it (N·m, not the files' N*m)."""
    return unit.replace("*", "·")


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


# ---------------------------------------------------------------- the explorer's overview
OVERVIEW_TITLE = "Model overview"
MODEL_STYLE = {"main": dict(color=COLORS[0], width=2), "proposal": dict(color=COLORS[2], width=2, dash="dash"),
               "overlay": dict(color=COLORS[4], width=1.5, dash="dot")}
_ANN = dict(xref="paper", yref="paper", showarrow=False, font=dict(size=13), xanchor="left", yanchor="bottom")


def _ax(title: str, domain, anchor: str, **kw) -> dict:
    # fixed margins instead of automargin: automargin makes Plotly lay the figure out again per
    # axis, which costs the live view tens of milliseconds in the browser on every change
    return dict(AXIS, title=dict(text=title, standoff=4), domain=domain, anchor=anchor, **dict(dict(automargin=False), **kw))


def abcd_marks(r) -> dict:
    """Indices of the turning points A, B, C, D of an A→B→C→D force ramp (Figs. 2, 10)."""
    f = r.applied_force
    d = np.sign(np.diff(f))
    iB = int(np.argmax(d < 0)) if np.any(d < 0) else len(f) - 1
    rest = d[iB:]
    iC = iB + int(np.argmax(rest > 0)) if np.any(rest > 0) else len(f) - 1
    return {"A": 0, "B": iB, "C": iC, "D": len(f) - 1}


def stribeck_band(p, v: np.ndarray, cov: np.ndarray | None = None):
    """±1σ of S(v) + σ2·v from the parameter uncertainties (per side: the fit's covariance
    when given, else the stored standard deviations taken as uncorrelated), or None."""
    from ..model import stribeck_curve as _S

    names = ("Fs", "Fc", "vs", "delta", "sigma2")
    var = np.zeros_like(v)
    any_unc = False
    for side, mask in (("positive", v > 0), ("negative", v < 0)):
        sd = np.array([p.uncertainty.get(f"stribeck.{side}.{k}", 0.0) for k in names])
        if not np.any(sd > 0):
            continue
        any_unc = True
        J = np.zeros((mask.sum(), 5))
        base = _S(p, v[mask])
        for j, k in enumerate(names):
            h = max(abs(getattr(getattr(p.stribeck, side), k)) * 1e-6, 1e-12)
            sp = getattr(p.stribeck, side)
            from dataclasses import replace as _rep

            q = p.replace(stribeck=_rep(p.stribeck, **{side: _rep(sp, **{k: getattr(sp, k) + h})}))
            J[:, j] = (_S(q, v[mask]) - base) / h
        C = np.diag(sd**2) if cov is None else cov[side]
        var[mask] = np.einsum("ij,jk,ik->i", J, C, J)
    return np.sqrt(var) if any_unc else None


def overview_figure(*, units: dict, hyst: list, strib: list, slip: list, bottom: dict, log_v: bool = True,
                    levels=None, band=None, notes: tuple = ()) -> go.Figure:
    """The four views an engineer looks at together, in one figure (one update per change).

    ``hyst``: (label, role, SimResult of the A→B→C→D ramp or None) — role main/proposal/overlay;
    an overlay gets its own axes (top/right), so it never rescales the main loop.
    ``strib``: (label, role, v, S(v)); ``slip``: (label, role, SimResult); ``bottom``: the
    fourth view, ``{"kind": "data", t, measured, model: [(label, role, F)]}`` or
    ``{"kind": "curve", z, F, zk, Fk, sigma}`` (the transition curve and its knots).
    """
    pu, fu = units.get("position", "rad"), shown_unit(units.get("force", "N*m"))
    data, ann = [], []
    L, R, TOP, BOT = [0.0, 0.44], [0.56, 1.0], [0.58, 0.94], [0.0, 0.42]
    layout = dict(
        xaxis=_ax(f"displacement (µ{pu})", L, "y"), yaxis=_ax(f"friction ({fu})", TOP, "x"),
        xaxis2=_ax(f"|v| ({pu}/s), log" if log_v else f"velocity ({pu}/s)", R, "y2", type="log" if log_v else "linear"),
        yaxis2=_ax(f"|friction| ({fu})" if log_v else f"friction ({fu})", TOP, "x2"),
        xaxis3=_ax("time (s)", L, "y3"), yaxis3=_ax(f"position ({pu})", [0.25, 0.42], "x3"),
        yaxis6=_ax(f"friction ({fu})", [0.0, 0.19], "x6"), xaxis6=_ax("", L, "y6", matches="x3", showticklabels=False),
        xaxis4=_ax("", R, "y4"), yaxis4=_ax("", BOT, "x4"),
    )
    layout["xaxis3"]["anchor"] = "y6"  # the time axis under the lower stick-slip plot
    layout["xaxis6"]["anchor"] = "y3"

    # --- presliding hysteresis, A–D marked
    has_loop = False
    # an overlay gets its own axes only when there is a main loop whose scale it could hide
    own_axes = any(r is not None for _, role, r in hyst if role != "overlay")
    for label, role, r in hyst:
        if r is None:
            continue
        x, F = _thin(r.position, r.friction_force, n=600)
        ax = dict(xaxis="x5", yaxis="y5") if role == "overlay" and own_axes else dict(xaxis="x", yaxis="y")
        data.append(dict(type="scatter", x=x * 1e6, y=F, mode="lines", name=label, line=MODEL_STYLE[role],
                         legendgroup=label, **ax))
        if role == "main":
            has_loop = True
            m = abcd_marks(r)
            data.append(dict(type="scatter", x=[r.position[i] * 1e6 for i in m.values()],
                             y=[r.friction_force[i] for i in m.values()], mode="markers+text", text=list(m),
                             textposition="top left", marker=dict(color="black", size=7), name="A–D", showlegend=False,
                             hoverinfo="x+y+text"))
        if role == "overlay" and own_axes:
            layout["xaxis5"] = dict(AXIS, overlaying="x", side="top", anchor="y", showgrid=False,
                                    title=dict(text=f"{label} displacement (µ{pu})", standoff=2),
                                    tickfont=dict(color=COLORS[4]), automargin=False)
            layout["yaxis5"] = dict(AXIS, overlaying="y", side="right", anchor="x", showgrid=False,
                                    tickfont=dict(color=COLORS[4]), automargin=False)
    if not has_loop:
        # nothing drawn yet (the page's first figure, before its first simulation) is not the static model
        static = any(r is None for _, role, r in hyst if role == "main")
        ann.append(dict(_ANN, x=0.22, y=0.76, xanchor="center", yanchor="middle", font=dict(size=12, color="#555"),
                        text="the static model has no presliding:<br>friction jumps at v = 0, no hysteresis curve"
                        if static else "simulating …"))
    ann.append(dict(_ANN, x=0.0, y=0.955, text="<b>Presliding hysteresis</b> A→B→C→D"))

    # --- Stribeck curve S(v) + σ2·v
    for label, role, v, S in strib:
        for sign, dash in ((1, None), (-1, "dot")):
            m = v * sign > 0
            xx, yy = (np.abs(v[m]), np.abs(S[m])) if log_v else (v[m], S[m])
            line = dict(MODEL_STYLE[role], **({"dash": dash} if dash and role == "main" else {}))
            data.append(dict(type="scatter", x=xx, y=yy, mode="lines", xaxis="x2", yaxis="y2", line=line,
                             name=f"{label} ({'v > 0' if sign > 0 else 'v < 0'})", showlegend=False, legendgroup=label))
    if band is not None:
        v, S, sd = band
        for sign in (1, -1):
            m = v * sign > 0
            xx = np.abs(v[m]) if log_v else v[m]
            lo, hi = (np.abs(S[m] - sd[m]), np.abs(S[m] + sd[m])) if log_v else (S[m] - sd[m], S[m] + sd[m])
            data.append(dict(type="scatter", x=np.concatenate([xx, xx[::-1]]), y=np.concatenate([hi, lo[::-1]]),
                             fill="toself", fillcolor="rgba(31,119,180,0.18)", line=dict(width=0), xaxis="x2", yaxis="y2",
                             name="±1σ", showlegend=sign > 0, hoverinfo="skip"))
    if levels is not None and len(levels.velocity):
        lv, lf = levels.velocity, levels.friction
        data.append(dict(type="scatter", x=np.abs(lv) if log_v else lv, y=np.abs(lf) if log_v else lf, mode="markers",
                         xaxis="x2", yaxis="y2", name="measured levels", marker=dict(color="black", size=5),
                         error_y=dict(array=np.sqrt(levels.variance), thickness=1, width=2)))
    ann.append(dict(_ANN, x=0.56, y=0.955, text="<b>Stribeck curve</b> S(v) + σ2·v" +
                    (" (solid v > 0, dotted v < 0)" if log_v else "")))

    # --- stick-slip under P control
    for label, role, r in slip:
        t, x, F = _thin(r.time, r.position, r.friction_force, n=600)
        data.append(dict(type="scatter", x=t, y=x, mode="lines", xaxis="x3", yaxis="y3", line=MODEL_STYLE[role],
                         name=label, showlegend=False, legendgroup=label))
        data.append(dict(type="scatter", x=t, y=F, mode="lines", xaxis="x6", yaxis="y6", line=MODEL_STYLE[role],
                         name=f"{label} friction", showlegend=False, legendgroup=label))
    ann.append(dict(_ANN, x=0.0, y=0.43, text="<b>Stick-slip</b> under P position control"))

    # --- the fourth view
    if bottom.get("kind") == "data":
        t, y = _thin(bottom["t"], bottom["measured"], n=1500)
        data.append(dict(type="scattergl" if len(t) > 3000 else "scatter", x=t, y=y, mode="markers", xaxis="x4",
                         yaxis="y4", name="measured", marker=dict(size=2.5, color="#7f7f7f")))
        for label, role, F in bottom.get("model", ()):
            tt, ff = _thin(bottom["t"], F, n=1500)
            data.append(dict(type="scatter", x=tt, y=ff, mode="lines", xaxis="x4", yaxis="y4",
                             line=dict(MODEL_STYLE[role], width=1.2), name=f"{label} on the data", showlegend=False))
        layout["xaxis4"]["title"] = dict(text="time (s)", standoff=4)
        layout["yaxis4"]["title"] = dict(text=f"friction ({fu})", standoff=4)
        ann.append(dict(_ANN, x=0.56, y=0.43, text=f"<b>Data with the model</b> {bottom.get('name', '')}"))
    else:
        z, F = bottom.get("z", ()), bottom.get("F", ())
        if len(z):
            data.append(dict(type="scatter", x=np.asarray(z) * 1e6, y=F, mode="lines", xaxis="x4", yaxis="y4",
                             line=MODEL_STYLE["main"], name="F_d(z)", showlegend=False))
            sig = bottom.get("sigma")
            data.append(dict(type="scatter", x=np.asarray(bottom["zk"]) * 1e6, y=bottom["Fk"], mode="markers",
                             xaxis="x4", yaxis="y4", marker=dict(color="black", size=6), name="knots", showlegend=False,
                             **({"error_y": dict(array=sig, thickness=1)} if sig is not None else {})))
        else:
            ann.append(dict(_ANN, x=0.78, y=0.2, xanchor="center", text="no transition curve in this model",
                            font=dict(size=12, color="#555")))
        layout["xaxis4"]["title"] = dict(text=f"z (µ{pu})", standoff=4)
        layout["yaxis4"]["title"] = dict(text=f"F_d ({fu})", standoff=4)
        ann.append(dict(_ANN, x=0.56, y=0.43, text="<b>Transition curve</b> F_d(z) — upload data to see it here"))
    for i, n in enumerate(notes):
        ann.append(dict(_ANN, x=1.0, xanchor="right", y=1.0 + 0.04 * i, text=n, font=dict(size=11, color="#a05a00")))
    layout.update(
        title=dict(text=OVERVIEW_TITLE, x=0.0, y=0.995, font=dict(size=1, color="white")),
        annotations=ann, plot_bgcolor="white", paper_bgcolor="white", hovermode="closest",
        font=dict(family="Open Sans, Arial, sans-serif", size=11), margin=dict(l=62, r=48, t=26, b=44),
        legend=dict(orientation="h", x=0.0, y=1.04, xanchor="left", yanchor="bottom", font=dict(size=11)),
    )
    return go.Figure(dict(data=data, layout=layout), _validate=False)


# ---------------------------------------------------------------- an uploaded recording, before any fit
RECORDING_TITLE = "Recording"


def reversal_windows(x: np.ndarray, v: np.ndarray, max_windows: int = 8) -> list[tuple[int, int]]:
    """Sample ranges from each velocity reversal to the next (at most ``max_windows``)."""
    s = np.sign(v)
    nz = np.flatnonzero(s != 0)
    if len(nz) < 2:
        return []
    flips = nz[1:][s[nz[1:]] != s[nz[:-1]]]
    bounds = list(flips) + [len(x) - 1]
    return [(int(a), int(b)) for a, b in zip(bounds[:-1], bounds[1:]) if b - a > 3][:max_windows]


def recording_figure(*, name: str, t, position, friction, friction_label: str, units: dict, velocity=None,
                     levels=None, model_curves: list = (), band=None) -> go.Figure:
    """Signals against time (top), friction against velocity with the constant-velocity
    levels found (bottom left), friction against displacement from each reversal (bottom right)."""
    pu, fu = units.get("position", "?"), shown_unit(units.get("force", "?"))
    data, ann = [], []
    TOP1, TOP2, BOT, L, R = [0.78, 1.0], [0.55, 0.74], [0.0, 0.42], [0.0, 0.44], [0.56, 1.0]
    layout = dict(
        xaxis=_ax("", [0, 1], "y", showticklabels=False, matches="x2"), yaxis=_ax(f"position ({pu})", TOP1, "x"),
        xaxis2=_ax("time (s)", [0, 1], "y2"), yaxis2=_ax(f"{friction_label} ({fu})", TOP2, "x2"),
        xaxis3=_ax(f"velocity ({pu}/s)", L, "y3"), yaxis3=_ax(f"{friction_label} ({fu})", BOT, "x3"),
        xaxis4=_ax(f"displacement since reversal ({pu})", R, "y4"), yaxis4=_ax(f"{friction_label} ({fu})", BOT, "x4"),
    )
    if position is not None:
        tt, xx = _thin(t, position, n=2000)
        data.append(dict(type="scatter", x=tt, y=xx, mode="lines", line=dict(color=COLORS[0], width=1), name="position",
                         showlegend=False))
    if friction is not None:
        tt, ff = _thin(t, friction, n=2000)
        data.append(dict(type="scatter", x=tt, y=ff, mode="lines", xaxis="x2", yaxis="y2", line=dict(color=COLORS[1], width=1),
                         name=friction_label, showlegend=False))
    ann.append(dict(_ANN, x=0.0, y=1.005, text=f"<b>{name}</b>: signals against time"))
    if velocity is not None and friction is not None:
        vv, ff = _thin(velocity, friction, n=3000)
        data.append(dict(type="scatter", x=vv, y=ff, mode="markers", xaxis="x3", yaxis="y3",
                         marker=dict(size=2, color="#9a9a9a"), name="samples", showlegend=False))
        for label, role, v, S in model_curves:
            data.append(dict(type="scatter", x=v, y=S, mode="lines", xaxis="x3", yaxis="y3", line=MODEL_STYLE[role],
                             name=label, showlegend=False))
        if band is not None:
            v, S, sd = band
            for sign in (1, -1):
                m = v * sign > 0
                data.append(dict(type="scatter", x=np.concatenate([v[m], v[m][::-1]]),
                                 y=np.concatenate([S[m] + sd[m], (S[m] - sd[m])[::-1]]), fill="toself",
                                 fillcolor="rgba(31,119,180,0.18)", line=dict(width=0), xaxis="x3", yaxis="y3",
                                 name="±1σ", showlegend=False, hoverinfo="skip"))
        if levels is not None and len(levels.velocity):
            data.append(dict(type="scatter", x=levels.velocity, y=levels.friction, mode="markers", xaxis="x3", yaxis="y3",
                             marker=dict(color="black", size=6, symbol="diamond"), name="levels found", showlegend=False,
                             error_y=dict(array=np.sqrt(levels.variance), thickness=1)))
        nlev = 0 if levels is None else len(levels.velocity)
        ann.append(dict(_ANN, x=0.0, y=0.43, text=f"<b>Friction vs velocity</b> — {nlev} levels of S(v) found"))
    if position is not None and friction is not None and velocity is not None:
        wins = reversal_windows(position, velocity)
        for i, (a, b) in enumerate(wins):
            xx, ff = _thin(position[a:b] - position[a], friction[a:b], n=400)
            data.append(dict(type="scatter", x=xx, y=ff, mode="lines", xaxis="x4", yaxis="y4",
                             line=dict(color=COLORS[i % 6], width=1), name=f"reversal {i + 1}", showlegend=False))
        ann.append(dict(_ANN, x=0.56, y=0.43, text=f"<b>Around reversals</b> — first {len(wins)} shown"))
    layout.update(title=dict(text=RECORDING_TITLE, font=dict(size=1, color="white")), annotations=ann,
                  plot_bgcolor="white", paper_bgcolor="white", font=dict(family="Open Sans, Arial, sans-serif", size=11),
                  margin=dict(l=60, r=20, t=22, b=40), showlegend=False)
    return go.Figure(dict(data=data, layout=layout), _validate=False)


def figure_csv(fig, name: str | None = None) -> str:
    """The data behind a figure, one row per point: trace, x, y (and ±σ where drawn); with
    ``name``, a first column naming the figure (several figures in one file)."""
    import csv
    import io

    out = io.StringIO()
    w = csv.writer(out)
    w.writerow((["figure"] if name is not None else []) + ["trace", "x_axis", "x", "y", "sigma"])
    lead = [name] if name is not None else []
    for tr in fig.data if hasattr(fig, "data") else fig["data"]:
        tr = tr if isinstance(tr, dict) else tr.to_plotly_json()
        x, y = tr.get("x"), tr.get("y")
        if x is None or y is None:
            continue
        err = (tr.get("error_y") or {}).get("array")
        tr_name = tr.get("name", "")
        axis = tr.get("xaxis", "x")
        for i, (a, b) in enumerate(zip(np.asarray(x).tolist(), np.asarray(y).tolist())):
            w.writerow(lead + [tr_name, axis, a, b, "" if err is None else float(np.asarray(err)[i])])
    return out.getvalue()


# ---------------------------------------------------------------- diagnosis report (model-owned effects)
EFFECT_VARIABLE = {"time_drift": "time", "normal_load": "load", "position_ripple": "position",
                   "cyclic_softening": "reversals", "presliding_stiffness": "velocity"}


def _diag_unit(d) -> tuple[str, str]:
    u = d.params_before.units
    return ("friction", u.get("force", "")) if d.space == "friction" else ("position", u.get("position", ""))


def wrapped(label: str, width: int = 24) -> str:
    """A long axis label broken into lines of about ``width`` characters at its spaces (Plotly's
    <br>): a step's label names the alternative's level and stiffness, and on one slanted line it
    ran off the plot."""
    lines, line = [], ""
    for word in label.split(" "):
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}" if line else word
    return "<br>".join(lines + [line])


def diagnosis_steps_figure(d) -> go.Figure:
    """The RMS gap after every step (model as given, the refitted alternative, each effect
    added), of the model written and beside the free steady curve the decision compares
    with, and the recording's noise floor."""
    what, unit = _diag_unit(d)
    labels = [wrapped(s["label"]) for s in d.steps]
    fig = _Fig()
    fig.add_trace(dict(type="bar", x=labels, y=[s["rms"] for s in d.steps], name="model written",
                       marker=dict(color=[COLORS[1]] * 2 + [COLORS[0]] * (len(labels) - 2))))
    fig.add_trace(dict(type="bar", x=labels, y=[s["rms_free"] for s in d.steps], name="beside a free S(v) (decided on)",
                       marker=dict(color="#9ecae1")))
    fig.add_trace(_scatter(labels, [d.noise] * len(labels), mode="lines", name="noise floor",
                           line=dict(color="#444444", dash="dash")))
    return _layout(fig, f"Gap in {what}, step by step", "", f"RMS ({unit})", xaxis=dict(tickangle=0))


def diagnosis_signal_figure(d) -> go.Figure:
    """The compared signal against time: measured, the model as given, the final model."""
    what, unit = _diag_unit(d)
    fig = _Fig()
    t, m, b, a = _thin(d.time, d.measured, d.model_before, d.model_after, n=4000)
    fig.add_trace(_scatter(t, m, mode="markers", name="measured", marker=dict(size=2, color="#7f7f7f")))
    fig.add_trace(_scatter(t, b, mode="lines", name="model as given", line=dict(color=COLORS[1], width=1)))
    fig.add_trace(_scatter(t, a, mode="lines", name="final model" + (f" (+ {', '.join(d.effects)})" if d.effects
                                                                     else " (the one given: nothing named)"),
                           line=dict(color=COLORS[0], width=1)))
    compared = getattr(d, "compared", None)
    if compared is not None and not compared.all() and compared.any():
        # the start the diagnosis leaves out: the memory there is the machine's history before the log
        t1 = float(d.time[int(np.argmax(compared))])
        fig.layout["shapes"] = [dict(type="rect", xref="x", yref="paper", x0=float(d.time[0]), x1=t1, y0=0, y1=1,
                                     fillcolor="#dddddd", opacity=0.5, line=dict(width=0), layer="below")]
        fig.layout["annotations"] = [dict(x=t1, y=1, xref="x", yref="paper", text="compared from here",
                                          showarrow=False, xanchor="left", yanchor="bottom", font=dict(size=10))]
    return _layout(fig, f"Measured and predicted {what}", "time (s)", f"{what} ({unit})")


def diagnosis_residual_figures(d) -> list:
    """For every named effect (or time when none): the residual of the step before it against
    the variable the effect depends on, and the correction the effect made."""
    what, unit = _diag_unit(d)
    figs = []
    named = list(d.effects) or [None]
    for i, name in enumerate(named):
        var = EFFECT_VARIABLE.get(name, "time") if name else "time"
        if var not in d.explaining:
            var = "time"
        label, values = d.explaining[var]
        # the residual the decision saw: beside the alternative's free steady curve
        before = d.scored_predictions[1 + i] if name else d.scored_predictions[-1]
        after = d.scored_predictions[2 + i] if name else before
        x, r, c = _thin(values, d.measured - before, after - before, n=4000)
        fig = _Fig()
        fig.add_trace(_scatter(x, r, mode="markers", name="residual before", marker=dict(size=2, color=COLORS[1])))
        if name:
            fig.add_trace(_scatter(x, c, mode="markers", name=f"{name}'s correction", marker=dict(size=2, color=COLORS[0])))
        title = f"Residual against {label}" + (f": what {name} explains" if name else "")
        figs.append(_layout(fig, title, label, f"measured − model ({unit})"))
    return figs


def diagnosis_travel_force_figure(d) -> go.Figure:
    """A force along the travel (``Diagnosis.travel_force``): the residual the base refitted
    alone leaves in the sliding, folded over the period and averaged, moving up and moving down,
    beside the part that keeps its sign both ways. A friction ripple's two directions mirror each
    other; an added force's lie on one another."""
    tf = d.travel_force
    what, unit = _diag_unit(d)
    pu = d.params_before.units.get("position", "")
    bins = len(tf.up)
    x = (np.arange(bins) + 0.5) * tf.wavelength / bins
    fine = np.linspace(0.0, tf.wavelength, 200)

    def gaps(means):  # an empty bin (None) is a gap in the line
        return [np.nan if m is None else m for m in means]

    fig = _Fig()
    fig.add_trace(_scatter(x, gaps(tf.up), mode="markers+lines", name="moving up", marker=dict(color=COLORS[0])))
    fig.add_trace(_scatter(x, gaps(tf.down), mode="markers+lines", name="moving down", marker=dict(color=COLORS[1])))
    fig.add_trace(_scatter(fine, tf.amplitude * np.sin(2 * np.pi * fine / tf.wavelength + tf.phase), mode="lines",
                           name=f"keeps its sign both ways: {tf.amplitude:.3g} ± {tf.sd:.2g}",
                           line=dict(color="#444444", dash="dash")))
    return _layout(fig, f"A force along the travel: residual folded over {tf.wavelength:.4g} {pu}",
                   f"position within the period ({shown_unit(pu)})" if pu else "position within the period",
                   f"measured − model ({unit})")


def diagnosis_travel_spring_figure(d) -> go.Figure:
    """A force in proportion to the travel (``Diagnosis.travel_spring``): the residual the base
    refitted alone leaves in the steady sliding against the position, each less its run's mean
    (the least squares' own view), binned, moving up and moving down, beside the slope that
    keeps its sign both ways. Friction's slope mirrors between the two; a spring's lies on both."""
    ts = d.travel_spring
    what, unit = _diag_unit(d)
    pu = d.params_before.units.get("position", "")
    lo, hi = ts.within_range
    bins = len(ts.up)
    x = lo + (np.arange(bins) + 0.5) * (hi - lo) / bins

    def gaps(means):  # an empty bin (None) is a gap in the line
        return [np.nan if m is None else m for m in means]

    fig = _Fig()
    fig.add_trace(_scatter(x, gaps(ts.up), mode="markers+lines", name="moving up", marker=dict(color=COLORS[0])))
    fig.add_trace(_scatter(x, gaps(ts.down), mode="markers+lines", name="moving down", marker=dict(color=COLORS[1])))
    fig.add_trace(_scatter([lo, hi], [ts.rate * lo, ts.rate * hi], mode="lines",
                           name=f"keeps its sign both ways: {ts.rate:.3g} ± {ts.sd:.2g} per {pu or 'unit'}",
                           line=dict(color="#444444", dash="dash")))
    return _layout(fig, "A force in proportion to the travel: residual against position within each run",
                   f"position less its run's mean ({shown_unit(pu)})" if pu else "position less its run's mean",
                   f"measured − model, less its run's mean ({unit})")


def diagnosis_cv_figure(d) -> go.Figure:
    """Out-of-sample evidence of the last round's candidates: pooled held-out RMS gain and the
    share of informative folds improved. A candidate not cross-validated (its in-sample gain
    under the prescreen) is drawn apart, hatched: its bar is an in-sample gain, an upper bound,
    not held-out evidence (one axis had shown both as "held-out")."""
    names = [c["name"] for c in d.candidates]
    fig = _Fig()
    for crossed, label in ((True, "held-out RMS gain (%)"), (False, "in-sample RMS gain, not cross-validated (%)")):
        cs = [c for c in d.candidates if bool(c.get("cross_validated", True)) == crossed]
        if not cs:
            continue
        fig.add_trace(dict(type="bar", x=[100 * c["heldout_gain"] for c in cs], y=[c["name"] for c in cs],
                           orientation="h", name=label,
                           marker=dict(color=[COLORS[2] if c["significant"] else ("#e0a000" if c["passes"] else "#bbbbbb")
                                              for c in cs], **({} if crossed else {"pattern": dict(shape="/")})),
                           text=[f"{c['folds_improved']}/{c['folds_informative']} folds" if crossed
                                 else "in-sample: not cross-validated" for c in cs],
                           textposition="auto"))
    fig.add_trace(_scatter([100 * d.settings.min_gain] * 2, [names[0], names[-1]] if names else [0, 0], mode="lines",
                           name="threshold", line=dict(color="#444444", dash="dash")))
    return _layout(fig, "Candidates, last round: RMS gain (held out; hatched: in-sample)", "% of the RMS",
                   "", yaxis=dict(autorange="reversed", categoryorder="array", categoryarray=names), barmode="overlay")


def diagnosis_report_figures(d) -> list:
    return [diagnosis_steps_figure(d), diagnosis_signal_figure(d), *diagnosis_residual_figures(d),
            *([diagnosis_travel_force_figure(d)] if getattr(d, "travel_force", None) is not None else []),
            *([diagnosis_travel_spring_figure(d)] if getattr(d, "travel_spring", None) is not None else []),
            diagnosis_cv_figure(d)]
