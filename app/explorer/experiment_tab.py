"""The Experiment tab: one of the paper's experiments, rerun for the current model."""

from __future__ import annotations

import viser

from ...model.experiments import EXPERIMENTS, run_experiment
from .. import plots
from .context import Context, plot_config
from .jobs import JobThread


class ExperimentTab:
    def __init__(self, ctx: Context, gui: viser.GuiApi, panel):
        self.ctx = ctx
        self.done = None
        with panel.add_tab("Experiment"):
            self.gui_pick = gui.add_dropdown("experiment", tuple(EXPERIMENTS), initial_value="breakaway",
                                             hint="a figure of the paper, simulated with the current model")
            self.gui_rerun = gui.add_button("Run with the current model")
            self.gui_text = gui.add_markdown("Choose an experiment, or press *Run*: it reruns on request (some take seconds).")
            self.gui_plot = gui.add_plotly(plots.hysteresis_figure([]), aspect=0.6, config=plot_config("experiment"))
            self.gui_csv = gui.add_button("Save plot data (CSV)")
        self.job = JobThread(f"experiment-{ctx.client.client_id}", {"run": self._run},
                             lambda kind, e: setattr(self.gui_text, "content", f"⚠ {type(e).__name__}: {e}"))
        self.gui_pick.on_update(lambda _: self.request())
        self.gui_rerun.on_click(lambda _: self.request())

        @self.gui_csv.on_click
        def _(event) -> None:
            event.client.send_file_download(f"experiment_{self.gui_pick.value}.csv",
                                            plots.figure_csv(self.gui_plot.figure).encode(), save_immediately=True)

    def request(self) -> None:
        self.job.submit("run", coalesce=True)

    def _run(self) -> None:
        p, name = self.ctx.params, self.gui_pick.value
        key = (name, id(p))
        if key == self.done:
            return
        self.gui_text.content = f"**{name}** — running…"
        res = run_experiment(name, p)
        with self.ctx.client.atomic():
            self.gui_plot.figure = plots.experiment_figure(res, p.units)
            self.gui_text.content = f"**{name}** — {EXPERIMENTS[name][1]}"
        self.done = key
