"""Self-contained HTML report of a diagnosis (Plotly embedded: readable offline)."""

from __future__ import annotations

import html

import plotly.io as pio

from ..identify.diagnose import confounding_reason
from ..model.effects import format_values
from . import plots


def _table(rows: list, header: list) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def diagnosis_html(d, source: str) -> str:
    figs = plots.diagnosis_report_figures(d)
    parts = []
    for i, fig in enumerate(figs):
        parts.append(pio.to_html(fig, include_plotlyjs=(i == 0), full_html=False, config={"displaylogo": False}))
    title = f"Friction model diagnosis — {html.escape(source)}"
    units = d.units
    steps = _table([[s["label"], f"{s['rms']:.4g}", f"{s['rms'] / d.noise:.2f}" if d.noise else "",
                     f"{s['rms_free']:.4g}", format_values(s["name"], s.get("params") or {}, units, s.get("sd")),
                     format_values(s["name"], s.get("params_decided") or {}, units)]
                    for s in d.steps],
                   ["step", "RMS gap of the model written", "× noise floor", "RMS beside a free S(v) (decided on)",
                    "effect parameters (± 1 σ: the folds' jackknife and the move from the value decided on)",
                    "decided on, beside the free S(v)"])
    if len(d.effects) > 1:
        steps += "<h2>Effects as written to the file</h2>" + _table(
            [list(row) for row in d.written_said(units)],
            ["effect", "values (every effect refitted together, ± 1 σ)"])
    conf = ""
    if d.confounded:
        conf = "<h2>Confounded candidates</h2>" + _table(
            [[" / ".join(c["effects"]), confounding_reason(c), c["experiment"]] for c in d.confounded],
            ["candidates", "why they are confounded", "experiment that separates them"])
    seen = d.seen_not_named()
    if seen:
        conf += "<h2>Seen, not named</h2>" + _table(
            [[c["name"], f"{100 * c['heldout_gain']:.1f} %", f"{c['folds_improved']}/{c['folds_informative']}", why]
             for c, why in seen],
            ["candidate", "held-out gain", "folds", "why it is not named"])
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{title}</title>
<style>body{{font-family:Arial,sans-serif;max-width:1100px;margin:2em auto;}} pre{{background:#f6f6f6;padding:1em;white-space:pre-wrap;overflow-wrap:anywhere;}}
table{{border-collapse:collapse;margin:1em 0;}} td,th{{border:1px solid #ccc;padding:4px 8px;text-align:left;}}</style>
</head><body>
<h1>{title}</h1>
<h2>Gap step by step</h2>
{steps}
{conf}
<pre>{html.escape(d.text())}</pre>
{''.join(f'<div>{p}</div>' for p in parts)}
</body></html>
"""
