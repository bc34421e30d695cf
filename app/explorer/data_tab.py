"""The Data tab: the user's recording first, then a fit offered as a proposal.

An upload is read and plotted at once (signals against time, friction against velocity
with the levels of S(v) found, friction against displacement from each reversal).
The page lists the columns, units and sign it recognised; a dropdown per signal changes
the mapping. The fit then runs on whatever the data support, in this tab's job thread, and
comes back as a proposal that says what it estimated, what it held and why.
"""

from __future__ import annotations

import io
import re

import numpy as np
import viser

from ...identify.data import (SIGNALS, Recording, load_recording, other_kind_of_machine, other_size_of_machine,
                              velocity_of)
from ...identify.errors import DataError
from ...model.errors import FrictionError
from .. import plots
from .context import Context, Proposal, plot_config
from .jobs import Cancelled, JobThread

NONE = "(none)"
MAPPED = ("time", "position", "force", "friction", "velocity", "normal_load")
SIGNAL_HELP = {"time": "time stamps", "position": "displacement / joint angle", "force": "applied force or motor torque",
               "friction": "measured friction force", "velocity": "velocity (else differentiated from position)",
               "normal_load": "normal load (for load-dependent friction)"}


def web_message(e: Exception, name: str) -> str:
    """A loader's message for a web user: names the file, points at the column dropdowns
    instead of the command line's ``--columns``."""
    msg = str(e)
    msg = re.sub(r",? or give it as (--columns (\"[^\"]*\"|\S+) )?--units \"[^\"]*\"", "", msg)  # (a current's constant: the header says it)
    msg = re.sub(r";?\s*name (it|them) with --columns[^)]*", "; choose it under Columns in the Data tab", msg)
    msg = msg.replace("--columns", "the column dropdowns")
    return msg if name in msg else f"{name}: {msg}"


def as_markdown_text(text: str) -> str:
    """Plain text (a loader's or a fit's note) for a Markdown panel: its * and _ escaped, so
    'torque [mN*m]: converted from mN*m to N*m' keeps its asterisks instead of turning the text
    between them to italics."""
    return re.sub(r"([\\*_])", r"\\\1", str(text))


def _head_table(content: bytes, rows: int):
    """The first ``rows`` rows of a CSV/TSV upload as a data frame (the loader's separator
    guess), or None."""
    import pandas as pd

    from ...identify.io import decode_text

    try:
        text, _ = decode_text(content, "upload")  # UTF-8, or Windows-1252 as the loader reads it
    except DataError:
        return None
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        return None
    first = lines[0]
    sep = "\t" if first.count("\t") > first.count(",") else ("," if "," in first else (";" if ";" in first else r"\s+"))
    try:
        return pd.read_csv(io.StringIO("\n".join(lines[:rows + 1])), sep=sep, engine="python")
    except Exception:
        return None


def header_columns(content: bytes) -> list[str]:
    """The column names of a CSV/TSV upload (the loader's separator guess), or []."""
    head = _head_table(content, 2)
    return [] if head is None else [str(c) for c in head.columns]


def has_numbers(content: bytes) -> bool:
    """Whether a CSV/TSV upload has a column of numbers in its first rows (decimal point or
    comma): a table whose columns could be chosen, not a page of prose."""
    import pandas as pd

    head = _head_table(content, 20)
    if head is None or len(head) == 0:
        return False
    for c in head.columns:
        col = head[c].astype(str).str.strip().str.replace(",", ".", regex=False)
        if pd.to_numeric(col, errors="coerce").notna().mean() > 0.5:
            return True
    return False


def friction_of(rec: Recording) -> tuple[np.ndarray | None, str]:
    if rec.friction is not None:
        return rec.friction, "friction"
    if rec.force is not None:
        return rec.force, "applied force"
    return None, ""


class DataTab:
    def __init__(self, ctx: Context, gui: viser.GuiApi, panel, propose):
        self.ctx = ctx
        self.propose = propose
        self.columns: list[str] = []
        self.previous = None  # the recording before an upload: kept where the upload cannot be read at all
        self.sign_note = ""
        self._quiet = False

        # ---------------------------------------------------------------- view (right)
        with panel.add_tab("Data"):
            self.gui_info = gui.add_markdown("Upload a recording (left panel, **Data**): it is plotted at once, "
                                             "then fitted.")
            self.gui_plot = gui.add_plotly(plots.recording_figure(name="", t=np.zeros(0), position=None, friction=None,
                                                                  friction_label="friction", units={}),
                                           aspect=0.7, config=plot_config("recording"), visible=False)
            self.gui_csv = gui.add_button("Save plot data (CSV)", visible=False)
            self.gui_columns = gui.add_folder("Columns: which column is which signal", visible=False)
            with self.gui_columns:
                self.gui_map = {s: gui.add_dropdown(s, (NONE,), initial_value=NONE, hint=SIGNAL_HELP[s]) for s in MAPPED}
                self.gui_flip = gui.add_checkbox("flip friction sign", False,
                                                 hint="the file's friction/force has the opposite sign convention")
                self.gui_remap = gui.add_button("Apply columns", hint="read the file again with this mapping")
            self.gui_report = gui.add_markdown("")

        # ---------------------------------------------------------------- controls (left)
        with gui.add_folder("Data", order=2.0):
            self.gui_upload = gui.add_upload_button("Upload recording", icon=viser.Icon.UPLOAD,
                                                    mime_type=".csv,.tsv,.txt,.dat,text/csv,text/plain",
                                                    hint="CSV/TSV with time, position and force or friction columns")
            self.gui_status = gui.add_markdown("")
            self.gui_fit = gui.add_button("Fit", disabled=True, hint="fit S(v) and the transition curve: a proposal")
            self.gui_cancel = gui.add_button("Cancel fit", visible=False, color="red")
            self.gui_progress = gui.add_progress_bar(0.0, visible=False)

        self.job = JobThread(f"data-{ctx.client.client_id}", {"load": self._load, "fit": self._fit},
                             lambda kind, e: self._failed(kind, e))

        # ---------------------------------------------------------------- callbacks: set state, enqueue
        @self.gui_upload.on_upload
        def _(event) -> None:
            f = self.gui_upload.value
            with ctx.lock:
                # what was there, to keep if this file cannot be read at all (``_load``)
                s = ctx.session
                self.previous = (s.recording_name, s.recording_bytes, dict(s.mapping or {}), s.flip_friction,
                                 ctx.recording, ctx.fit) if ctx.recording is not None else None
                ctx.session.recording_name, ctx.session.recording_bytes = f.name, f.content
                ctx.session.mapping = {}
                ctx.session.flip_friction = None
                ctx.dirty = True  # saved with the session now, not at the next redraw: a reload keeps it
            ctx.status("")  # the message about what came before (a refused file, a YAML error) is not about this file
            self.job.submit("load", True)

        @self.gui_remap.on_click
        def _(_) -> None:
            with ctx.lock:  # "(none)" is a choice too: that signal from no column, not the one recognised
                ctx.session.mapping = {s: (None if h.value == NONE else h.value) for s, h in self.gui_map.items()}
                ctx.dirty = True
            self.job.submit("load", True)

        @self.gui_flip.on_update
        def _(_) -> None:
            if not self._quiet:  # the user's choice, not the detected convention shown by code
                ctx.session.flip_friction = self.gui_flip.value

        @self.gui_fit.on_click
        def _(_) -> None:
            if not self.job.submit("fit"):
                self.gui_status.content = "A fit is already running."

        @self.gui_cancel.on_click
        def _(_) -> None:
            self.job.cancel()

        @self.gui_csv.on_click
        def _(event) -> None:
            event.client.send_file_download("recording_plot.csv", plots.figure_csv(self.gui_plot.figure).encode(),
                                            save_immediately=True)

        ctx.listeners.append(self._on_change)
        if ctx.session.recording_bytes is not None:
            self.job.submit("load", ctx.fit_on_start)

    def _on_change(self, reason: str) -> None:
        if self.ctx.proposal is None and "see the proposal" in self.gui_status.content:
            self.gui_status.content = ""  # accepted or discarded: the Parameter sets tab has it

    # ------------------------------------------------------------------ jobs
    def _failed(self, kind: str, e: Exception) -> None:
        self._busy(False)
        name = self.ctx.session.recording_name or "the recording"
        self.gui_status.content = f"⚠ {kind} failed: {type(e).__name__}: {e}"
        self.ctx.notify(f"{kind.capitalize()} failed", f"{name}: {type(e).__name__}: {e}", "red")

    def _busy(self, on: bool, what: str = "") -> None:
        self.gui_fit.disabled = on or self.ctx.recording is None
        self.gui_upload.disabled = on
        self.gui_remap.disabled = on
        self.gui_cancel.visible = on
        self.gui_progress.visible = on
        if on:
            self.gui_progress.value = 0.0
            self.gui_cancel.label = f"Cancel {what}"

    def _load(self, then_fit: bool) -> None:
        ctx = self.ctx
        s = ctx.session
        name, content = s.recording_name, s.recording_bytes
        self.columns = header_columns(content)
        opts = (NONE, *self.columns)
        for sig, h in self.gui_map.items():
            h.options = opts
        try:
            rec = load_recording(content, name=name, columns=s.mapping or None, require=("time",))
        except DataError as e:
            msg = web_message(e, name)
            if "no column for" in msg and not has_numbers(content):
                # a page of prose: its first line is no header, and there is nothing to choose
                msg = (f"{name}: no column of numbers: not a recording (a table with time, position and force "
                       f"or friction in columns)")
            # a bad cell is the file's to correct; a column not found or not told apart is chosen here
            bad_row = re.search(r"\brow \d+", msg)
            previous, self.previous = self.previous, None
            if previous is not None and (bad_row or not has_numbers(content)):
                # nothing to choose on this page (no table, no column of numbers — a page of prose
                # —, or a row to correct in the file): the recording that was there stays (a
                # picture or a text uploaded by mistake had replaced it)
                with ctx.lock:
                    (s.recording_name, s.recording_bytes, s.mapping, s.flip_friction, ctx.recording,
                     ctx.fit) = previous
                    ctx.dirty = True
                self.columns = header_columns(s.recording_bytes)
                for sig, h in self.gui_map.items():
                    h.options = (NONE, *self.columns)
                    h.value = ctx.recording.columns.get(sig, NONE)
                kept = f"{msg} — {previous[0]} is kept"
                self.gui_status.content = f"⚠ {kept}"
                ctx.notify("Cannot read the recording", kept, "red", 10.0)
                return
            with ctx.lock:
                ctx.recording, ctx.fit = None, None
            self.gui_status.content = f"⚠ {msg}"
            fix = ("Correct that row of the file (or remove it) and upload it again." if bad_row
                   else "Choose the columns under *Columns* below and press *Apply columns*.")
            self.gui_info.content = (f"**{name}** could not be read: {msg}\n\nColumns in the file: "
                                     + ", ".join(f"`{c}`" for c in self.columns) + f"\n\n{fix}")
            self.gui_columns.visible = True
            self.gui_plot.visible = self.gui_csv.visible = False
            self.gui_fit.disabled = True
            ctx.notify("Cannot read the recording", msg, "red", 10.0)
            ctx.changed("recording")
            return
        self.previous = None
        for sig, h in self.gui_map.items():
            h.value = rec.columns.get(sig, NONE)
        self.gui_columns.visible = True
        from ...identify.segment import constant_velocity_levels, prepare

        detected, sign_note = False, "no friction column: the applied force is taken as it is"
        if rec.friction is not None and rec.position is not None:
            try:  # the loader's own judgement of the sign convention (friction vs velocity)
                prep = prepare(rec, friction_sign="auto")
                detected = prep.sign_flipped
                sign_note = next((n for n in prep.notes if n.startswith("friction sign")), sign_note)
            except FrictionError as e:
                sign_note = f"not checked ({e})"
        flip = s.flip_friction if s.flip_friction is not None else detected
        self._quiet = True
        try:
            self.gui_flip.value = flip
        finally:
            self._quiet = False
        self.gui_flip.disabled = rec.friction is None
        if flip and rec.friction is not None:
            rec.friction = -rec.friction
            if not detected:
                sign_note = "flipped by you (the file looked like the model's convention)"
        elif detected and rec.friction is not None:
            sign_note = "kept as in the file by you (it looked like the opposite convention)"
        levels = None
        F, what = friction_of(rec)
        if F is not None and rec.position is not None:
            try:
                levels = constant_velocity_levels(prepare(rec, friction_sign="action"))
            except FrictionError:
                levels = None
        with ctx.lock:
            ctx.recording, ctx.fit = rec, None
        self.sign_note = sign_note
        self._show_recording(rec, levels, sign_note)
        ctx.changed("recording")
        can_fit = rec.position is not None and F is not None
        self.gui_fit.disabled = not can_fit
        if not can_fit:
            missing = [w for w, ok in (("position", rec.position is not None), ("force or friction", F is not None)) if not ok]
            self.gui_status.content = (f"⚠ {name}: no {' and no '.join(missing)} column recognised: choose it "
                                       "under *Columns* in the Data tab.")
            return
        self.gui_status.content = f"**{name}**: {len(rec)} samples read."
        if then_fit:
            self.job.submit("fit")

    def _show_recording(self, rec: Recording, levels, sign_note: str, fit=None) -> None:
        F, what = friction_of(rec)
        units = {"position": rec.units.get("position", "SI"), "force": rec.units.get("friction", rec.units.get("force", "SI"))}
        curves, band = [], None
        if fit is not None:
            from ...model import stribeck_curve

            vmax = float(np.max(np.abs(velocity_of(rec)))) if rec.position is not None else 1.0
            v = np.linspace(-vmax, vmax, 400)
            v = v[v != 0]
            curves = [("fit", "proposal", v, stribeck_curve(fit.params, v))]
            sd = plots.stribeck_band(fit.params, v)
            if sd is not None:
                band = (v, stribeck_curve(fit.params, v), sd)
        fig = plots.recording_figure(name=rec.source, t=rec.time, position=rec.position, friction=F, friction_label=what,
                                     units=units, velocity=velocity_of(rec) if rec.position is not None else None,
                                     levels=levels, model_curves=curves, band=band)
        rows = ["| signal | column | unit | |", "|---|---|---|---|"]
        for sig in SIGNALS:
            if sig in rec.columns:
                rows.append(f"| {sig} | `{rec.columns[sig]}` | {rec.units.get(sig, '—')} | {SIGNAL_HELP.get(sig, '')} |")
            elif sig == "position" or (sig == "friction" and "force" not in rec.columns):
                rows.append(f"| {sig} | **not found** | | choose its column under *Columns*, below the plot |")
        notes = "; ".join(map(as_markdown_text, rec.notes))
        self.gui_info.content = (f"**{rec.source}** — {len(rec)} samples, {rec.time[-1] - rec.time[0]:.4g} s. "
                                 f"Recognised:\n\n" + "\n".join(rows) + f"\n\nSign: {sign_note}.  \n{notes}")
        with self.ctx.client.atomic():
            self.gui_plot.figure = fig
            self.gui_plot.visible = True
            self.gui_csv.visible = True

    def _fit(self) -> None:
        from ...identify.fit import fit_recordings

        ctx = self.ctx
        rec = ctx.recording
        if rec is None:
            return
        name = ctx.session.recording_name
        self._busy(True, "fit")

        def report(frac, msg):
            self.gui_progress.value = 100.0 * frac
            self.gui_status.content = f"Fitting **{name}**: {msg} — {100 * frac:.0f} %"

        progress = self.job.progress_for(report)
        before = ctx.params
        try:
            res = fit_recordings([rec], base=fit_start(before, rec), progress=progress, friction_sign="action")
        except Cancelled:
            self.gui_status.content = f"Fit of {name} cancelled."
            self._busy(False)
            raise
        except FrictionError as e:
            self._busy(False)
            msg = web_message(e, name)
            self.gui_status.content = f"⚠ {msg}"
            self.gui_report.content = (f"**Nothing was fitted.** {msg}\n\nThe data are plotted above: look for "
                                       "constant-velocity runs or steady sliding at several speeds in both directions "
                                       "(for S(v)) and slow force ramps or reversals of the motion (for the "
                                       "transition curve).")
            ctx.notify("Fit: nothing to estimate", msg, "yellow", 10.0)
            return
        self._busy(False)
        with ctx.lock:
            ctx.fit = res
        self._show_recording(rec, res.levels, self.sign_note, fit=res)
        self.gui_report.content = f"**Fit of {name}**\n\n```\n{res.report()}\n```"
        gap_b, gap_a = gap(rec, before), gap(rec, res.params.replace(model=before.model))
        # a header without units was read as SI: said where the numbers are accepted, not only in the Data tab
        assumed = f"⚠ {name}: {rec.units_assumed}\n\n" if rec.units_assumed else ""
        from ...model import default_params

        why = other_machine(before, rec)  # (the built-in default is never a start: not said each time)
        start = (f"Started from nothing ({why}): what the data do not determine is held at the recording's own "
                 f"scale.\n\n" if why and before != default_params(before.model) else "")
        self.propose(Proposal(f"fit of {name}", res.params.replace(model=before.model),
                              assumed + start + fit_summary(res), gap_b, gap_a))
        self.gui_status.content = f"Fit of **{name}** done: see the proposal."


def other_machine(current, rec: Recording) -> str | None:
    """Why the explorer's current set cannot be ``rec``'s machine, or None: it is the built-in
    default (the paper's robot joint, whose σ1 and inertia mean nothing for another machine), it
    is in other units (rad against m), or its friction is of another size
    (``identify.data.other_size_of_machine``)."""
    from ...model import default_params

    if current == default_params(current.model):
        return "the current set is the built-in default, the paper's robot joint"
    if other_kind_of_machine(current.units, rec.units):
        return f"the current set is in {current.units.get('position')}, the recording in {rec.units.get('position')}"
    size = other_size_of_machine(current, rec)
    return None if size is None else f"the current set: {size}"


def fit_start(current, rec: Recording):
    """The parameter set a fit of ``rec`` starts from (what it holds comes from there): the
    explorer's current set, unless it cannot be this machine's (``other_machine``); then none,
    as ``leuven-friction fit`` without --params: σ1 and the inertia are then held at the
    recording's own scale."""
    return None if other_machine(current, rec) else current.replace(model="leuven")


def gap(rec: Recording, p) -> float | None:
    """RMS of the measured minus the model's friction, the gap `fit` reports and a diagnosis
    starts from (``identify.diagnose.gap_as_given``), or None where it cannot be simulated."""
    from ...identify.diagnose import gap_as_given

    try:
        return gap_as_given(rec, p).total
    except (FrictionError, ValueError, FloatingPointError, TypeError):
        return None


def without_cli_hints(text: str) -> str:
    """A note without the command line's option hints ('; --fit-n estimates it'): a web user has
    none. The whole clause that names an option goes (up to the `;` or brackets around it), not
    the option alone: "(another machine's; give --params with this machine's)" had become
    "(another machine's; give)"."""
    t = re.sub(r"[^;()]*--[a-z][\w-]*[^;()]*(\([^()]*\)[^;()]*)?", "", str(text))  # (and its own bracket)
    for a, b in (("(;", "("), (";)", ")"), ("( ", "("), (" )", ")")):
        while a in t:
            t = t.replace(a, b)
    t = re.sub(r"\s*\(\s*\)", "", t)
    t = re.sub(r";\s*;", ";", t)
    return re.sub(r"\s{2,}", " ", re.sub(r";\s*$", "", t)).strip()


def fit_summary(res) -> str:
    """What the fit estimated and what it held, and why (from the fit result)."""
    held = dict(getattr(res, "held", None) or {})
    status = res.status() if callable(getattr(res, "status", None)) else {}
    est = sorted(k for k, v in status.items() if v == "estimated")
    lines = [f"⚠ {as_markdown_text(without_cli_hints(w))}" for w in getattr(res, "warnings", ())]
    if est:
        lines.append(f"**Estimated** ({len(est)}): " + ", ".join(est))
    else:
        lines.append("**Estimated**: " + ", ".join(
            [w for w, ok in (("S(v)", res.stribeck_fit), ("transition curve", res.transition_fit)) if ok] or ["nothing"]))
    if held:
        # each at the value its reason says (the current one, F_c, the slowest level's speed, …)
        lines.append(f"**Held** ({len(held)}), each as its reason says:\n"
                     + "\n".join(f"- {k}: {as_markdown_text(without_cli_hints(r))}" for k, r in held.items()))
    elif not res.stribeck_fit or not res.transition_fit:
        lines.append("**Held**: " + ", ".join(w for w, ok in (("S(v)", res.stribeck_fit),
                                                              ("transition curve", res.transition_fit)) if not ok))
    if res.notes:
        lines.append("Notes:\n" + "\n".join(f"- {as_markdown_text(t)}" for t in map(without_cli_hints, res.notes)
                                              if t))
    return "\n\n".join(lines)
