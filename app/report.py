"""Self-contained HTML report of a diagnosis (Plotly embedded: readable offline)."""

from __future__ import annotations

import html

import plotly.io as pio

from . import plots


def diagnosis_html(d, source: str) -> str:
    figs = plots.diagnosis_figures(d)
    parts = []
    for i, fig in enumerate(figs):
        parts.append(pio.to_html(fig, include_plotlyjs=(i == 0), full_html=False, config={"displaylogo": False}))
    title = f"Friction model diagnosis — {html.escape(source)}"
    return f"""<!DOCTYPE html>
<html><head><meta charset="utf-8"><title>{title}</title>
<style>body{{font-family:Arial,sans-serif;max-width:1100px;margin:2em auto;}} pre{{background:#f6f6f6;padding:1em;}}</style>
</head><body>
<h1>{title}</h1>
<pre>{html.escape(d.text())}</pre>
{''.join(f'<div>{p}</div>' for p in parts)}
</body></html>
"""
