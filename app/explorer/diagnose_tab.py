"""The Diagnose tab: look for the physical effect the model misses in the uploaded data.

``identify.diagnose.diagnose`` runs in this tab's job thread with stage and percentage,
can be cancelled, and its result is a proposal (the extended model), never an overwrite.
"""

from __future__ import annotations

import viser

from ...identify.diagnose import base_off_verdict
from ...model.effects import EFFECTS
from ...model.errors import FrictionError
from .. import plots
from .context import Context, Proposal, plot_config
from .data_tab import without_cli_hints
from .jobs import Cancelled, JobThread

MAX_FIGURES = 8  # steps, signal, up to three named effects, a force along the travel periodic and in proportion, cross-validation


class DiagnoseTab:
    def __init__(self, ctx: Context, gui: viser.GuiApi, panel, propose):
        self.ctx = ctx
        self.propose = propose
        self.shown = None  # the recording whose diagnosis the tab shows
        self.status_of = None  # the recording the line under the Diagnose button is about
        self.failed_of = None  # the recording whose failed diagnosis the tab's text says
        with panel.add_tab("Diagnose"):
            self.gui_text = gui.add_markdown("Upload a recording, then press **Diagnose** (left): the workflow looks "
                                             "for the physical effect the model misses, adds it and refits. The "
                                             "result is a proposal you accept or discard.")
            # the figures of the HTML report (plots.diagnosis_report_figures): the gap step by step,
            # the compared signal, one residual per named effect, a force along the travel (periodic, in
            # proportion to it) where one is seen, the cross-validation evidence
            self.gui_plots = [gui.add_plotly(plots.hysteresis_figure([]), aspect=0.55, config=plot_config(f"diagnosis_{i}"),
                                             visible=False) for i in range(MAX_FIGURES)]
            self.gui_csv = gui.add_button("Save plot data (CSV)", visible=False, hint="the figures shown, one file")
        with gui.add_folder("Diagnose", order=3.0):
            self.gui_run = gui.add_button("Diagnose", disabled=True,
                                          hint="find the effect the current model misses in the uploaded data")
            # Settings.must_settle (``diagnose --require-settling``): read when a diagnosis starts
            self.gui_settle = gui.add_checkbox("Require settling", initial_value=True,
                                               hint="an effect whose change is not seen to settle within the session (a "
                                                    "softening still going at the end, or over after the first "
                                                    "reversals; a drift that is a straight trend, or over in "
                                                    "the first tenth) is listed as seen, not named: a trend or a step "
                                                    "along the session's schedule would look the same")
            self.gui_cancel = gui.add_button("Cancel diagnosis", visible=False, color="red")
            self.gui_progress = gui.add_progress_bar(0.0, visible=False)
            self.gui_status = gui.add_markdown("")
        self.job = JobThread(f"diagnose-{ctx.client.client_id}", {"diagnose": self._diagnose}, self._failed)

        @self.gui_run.on_click
        def _(_) -> None:
            if not self.job.submit("diagnose"):
                self.gui_status.content = "A diagnosis is already running."

        @self.gui_cancel.on_click
        def _(_) -> None:
            self.job.cancel()

        @self.gui_csv.on_click
        def _(event) -> None:
            parts = [plots.figure_csv(h.figure, name=f"diagnosis_{i + 1}") for i, h in enumerate(self.gui_plots)
                     if h.visible]
            text = parts[0] + "".join(p.split("\n", 1)[1] for p in parts[1:])  # one header
            event.client.send_file_download("diagnosis_plots.csv", text.encode(), save_immediately=True)

        ctx.listeners.append(self._on_change)

    def _on_change(self, reason: str) -> None:
        if self.ctx.proposal is None and "see the proposal" in self.gui_status.content:
            self.gui_status.content = ""
        if reason == "recording" and not self.job.busy():
            rec = self.ctx.recording
            self.gui_run.disabled = rec is None or rec.position is None
            if self.gui_status.content and self.status_of != self.ctx.session.recording_name:
                # a result or a failure of the recording before is not left under the button
                self.gui_status.content = ""
            name = self.ctx.session.recording_name
            last = self.shown or self.failed_of  # the recording the tab's text is about
            if rec is not None and last is not None and last != name:
                self._show_none(f"The last diagnosis was of {last}; press **Diagnose** (left) for {name}.")

    def _show_none(self, text: str) -> None:
        """The tab without a diagnosis: ``text``, no figures (a diagnosis of another recording, or
        one that failed, is not left on show as if it were this one's)."""
        with self.ctx.client.atomic():
            self.gui_text.content = text
            for handle in self.gui_plots:
                handle.visible = False
            self.gui_csv.visible = False
        self.shown = self.failed_of = None

    def _busy(self, on: bool) -> None:
        self.gui_run.disabled = on
        self.gui_cancel.visible = on
        self.gui_progress.visible = on
        if on:
            self.gui_progress.value = 0.0

    def _failed(self, kind: str, e: Exception) -> None:
        self._busy(False)
        self.gui_status.content = f"⚠ diagnosis failed: {e}"
        self.status_of = self.ctx.session.recording_name
        self.ctx.notify("Diagnosis failed", f"{self.ctx.session.recording_name}: {type(e).__name__}: {e}", "red")

    def _diagnose(self) -> None:
        from ...identify.diagnose import Settings, diagnose

        ctx = self.ctx
        rec = ctx.recording
        if rec is None:
            self.gui_status.content = "Upload a recording first."
            return
        name = ctx.session.recording_name
        before = ctx.params
        self._busy(True)

        def report(frac, msg):
            self.gui_progress.value = 100.0 * frac
            self.gui_status.content = f"Diagnosing **{name}**: {msg} — {100 * frac:.0f} %"

        try:
            d = diagnose(rec, before.replace(model="leuven"), progress=self.job.progress_for(report),
                         settings=Settings(must_settle=bool(self.gui_settle.value)))
        except Cancelled:
            self._busy(False)
            self.gui_status.content = "Diagnosis cancelled."
            self.status_of = name
            raise
        except FrictionError as e:
            self._busy(False)
            msg = without_cli_hints(str(e) if name in str(e) else f"{name}: {e}")
            self.gui_status.content = f"⚠ {msg}"
            self.status_of = name
            self._show_none(f"**Diagnosis of {name} failed**: {msg}")
            self.failed_of = name
            ctx.notify("Diagnosis failed", msg, "red")
            return
        self._busy(False)
        self.shown = name
        with ctx.client.atomic():
            # the report without the command line's options (the page has its own controls, or none)
            self.gui_text.content = f"**Diagnosis of {name}**\n\n```\n{report_on_page(d.text())}\n```"
            figures = plots.diagnosis_report_figures(d)[:MAX_FIGURES]
            for i, handle in enumerate(self.gui_plots):
                if i < len(figures):
                    handle.figure = figures[i]
                handle.visible = i < len(figures)
            self.gui_csv.visible = True
        if d.effects:
            named = ", ".join(d.effects)
            units = {k: plots.shown_unit(v) for k, v in d.units.items()}
            text = ("Effects, in the order named: "
                    + "; ".join(f"**{name}** ({EFFECTS[name].description})" for name in d.effects)
                    # the values written (every effect refitted together, ± 1 σ): they have no controls
                    + ".\n\nAs written: " + "; ".join(f"**{name}**: {said}" for name, said in d.written_said(units))
                    + "\n\nGap after each step: "
                    + " → ".join(f"{s['rms']:.3g}" for s in d.steps)
                    + "\n\nPer regime (RMS before → after): "
                    + "; ".join(f"{k} {r['rms_before']:.3g} → {r['rms_after']:.3g}" for k, r in d.regimes.items()))
            self.propose(Proposal(f"diagnosis: {named}", d.params_after.replace(model=before.model), text,
                                  d.rms_before, d.rms_after))
        self.gui_status.content = status_line(d)
        self.status_of = name


def report_on_page(report: str) -> str:
    """The diagnosis report as the page shows it: without the command line's options (the page
    has its own controls, or none), and a torque written N·m as on the rest of the page (N*m is
    the files' spelling; the report's own asterisks, the candidates' marks, stay). A line keeps
    its indent, which sets the report's columns."""
    shown = "\n".join(ln[:len(ln) - len(ln.lstrip())] + without_cli_hints(ln) if "--" in ln else ln
                       for ln in report.splitlines())
    return shown.replace("N*m", plots.shown_unit("N*m"))


def status_line(d) -> str:
    """The verdict of a diagnosis ``d`` under the button: what is named (and proposed), what is
    seen but not named, or that nothing is."""
    others = d.not_named()
    if d.effects:
        return f"Found **{', '.join(d.named_labels())}**: see the proposal." + (f" Also: {'; '.join(others)}." if others else "")
    gap = (f"the model leaves {d.rms_before:.3g}, {d.rms_before / d.noise:.1f} × the noise floor" if d.noise > 0
           else f"the model leaves {d.rms_before:.3g}")
    base = (f"; {base_off_verdict(d.rms_base_refit, d.noise, d.settings.candidates, d.seen_unnamed())} (refitted alone it leaves "
            f"{d.rms_base_refit:.3g}): fit it to this recording" if d.base_off else "")
    if others:
        return f"Nothing named: {'; '.join(others)}. {gap[0].upper()}{gap[1:]}{base} (the Diagnose tab has the evidence)."
    return f"No missing effect named (nothing proposed): {gap}{base}."
