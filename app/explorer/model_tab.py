"""The Model tab: every parameter as a control, and the overview plot that follows them.

Controls (left): model kind, overlay, view options, Stribeck parameters per side, the
presliding parameters, the transition-curve knots. View (right): one figure with the four
views together — presliding hysteresis (A–D marked), Stribeck curve, stick-slip, and the
data with the model (or the transition curve when no data are loaded). A change only
records the new value and queues a redraw; the tab's job thread draws the latest state.
"""

from __future__ import annotations

import time

import numpy as np
import viser

from ...model import FrictionParams, TransitionCurve, as_model, stribeck_curve
from ...model.errors import FrictionError, ParameterError
from ...model.experiments import abcd_levels, abcd_ramp, stick_slip, stick_slip_setup
from .. import plots
from .context import Context, plot_config
from .controls import ParamControl, value_for
from .fields import SIDE_MARK, fields_of, sanity_warnings, with_values
from .jobs import JobThread

LIVE_RAMP_RATE = 20.0  # force units/s at Fs⁺ = 36: the live A→B→C→D ramp runs 20× faster than Fig. 10
STICK_SLIP_S = 3.0
MAX_DATA_SIM = 200_000  # samples of a recording the live view simulates (the rest is cut, and said)
OVERVIEW_ASPECT = 0.66  # viser's aspect is height/width: 4 views fit 1280×720 above the fold


def to_piecewise(p: FrictionParams) -> FrictionParams:
    tc = p.transition_curve
    if tc.kind == "piecewise_linear":
        return p
    from ...model.simulate import transition_curve_values

    zk = np.array([0.0, 0.02, 0.2, 0.5, 1.0]) * 6 * tc.shape["z0"]
    return p.replace(transition_curve=TransitionCurve(z=tuple(zk), F=tuple(transition_curve_values(p, zk))))


class ModelTab:
    def __init__(self, ctx: Context, gui: viser.GuiApi, panel):
        self.ctx = ctx
        self.gui = gui
        self.controls: dict[str, ParamControl] = {}
        self.knot_controls: list[ParamControl] = []
        self.redraw_times: list[float] = []
        self._enabled_for = None
        self._cmp = None  # (key, recording, comparison): ``_compared``'s last
        view = ctx.session.model_view

        # ---------------------------------------------------------------- view (right)
        with panel.add_tab("Model"):
            self.gui_plot = gui.add_plotly(plots.overview_figure(units=ctx.params.units, hyst=[], strib=[], slip=[],
                                                                 bottom={}), aspect=OVERVIEW_ASPECT,
                                           config=plot_config("model_overview"))
            self.gui_csv = gui.add_button("Save plot data (CSV)", hint="the numbers behind this figure")

        # ---------------------------------------------------------------- controls (left)
        with gui.add_folder("Model", order=4.0):
            self.gui_kind = gui.add_dropdown("model", ("leuven", "lugre", "static"), initial_value=ctx.params.model,
                                             hint="which friction model the plots simulate")
            self.gui_overlay = gui.add_dropdown("overlay", ("none", "lugre", "leuven", "static"),
                                                initial_value=view.get("overlay", "none"),
                                                hint="a second model drawn on its own axes, for comparison")
            self.gui_logv = gui.add_checkbox("Stribeck: log |v|", view.get("log_v", True),
                                             hint="log-scale velocity axis: shows the Stribeck dip near vs")
            self.gui_3d = gui.add_checkbox("3D joint view", view.get("three_d", False),
                                           hint="animate the joint of the stick-slip run in the 3D scene (costs speed)")
            self.gui_warn = gui.add_markdown("")
        fields = fields_of(to_piecewise(ctx.params))
        for side in ("positive", "negative"):
            with gui.add_folder(f"Stribeck {SIDE_MARK[side]}  (eq. 7)", expand_by_default=side == "positive",
                                order=5.0 if side == "positive" else 6.0):
                for f in fields:
                    if f.path.startswith(f"stribeck.{side}."):
                        self._add(f)
        with gui.add_folder("Presliding", expand_by_default=False, order=7.0):
            for f in fields:
                if f.spec.group == "model":
                    self._add(f)
        self.knot_folder = gui.add_folder("Transition curve knots", expand_by_default=False, order=8.0)
        with self.knot_folder:
            self.gui_add_knot = gui.add_button("add knot", hint="append a knot beyond the last one")
            self.gui_remove_knot = gui.add_button("remove last knot")
        self._build_knots(to_piecewise(ctx.params))

        # ---------------------------------------------------------------- callbacks: set state, enqueue
        self.job = JobThread(f"model-{ctx.client.client_id}", {"redraw": self._redraw},
                             lambda kind, e: ctx.notify("Could not draw", f"{type(e).__name__}: {e}", "red"))

        @self.gui_kind.on_update
        def _(_) -> None:
            try:
                p = as_model(ctx.params, self.gui_kind.value)
            except FrictionError as e:
                self.gui_warn.content = f"⚠ {e}"
                return
            ctx.set_params(p, "model kind")

        for h in (self.gui_overlay, self.gui_logv, self.gui_3d):
            h.on_update(lambda _: self._view_changed())

        @self.gui_add_knot.on_click
        def _(_) -> None:
            tc = to_piecewise(ctx.params).transition_curve
            z, F = list(tc.z), list(tc.F)
            z.append(z[-1] * 1.5)
            F.append(F[-1] * 1.1 + (F[-1] - F[-2]) * 0.1)
            self._set_knots(z, F)

        @self.gui_remove_knot.on_click
        def _(event) -> None:
            tc = to_piecewise(ctx.params).transition_curve
            if len(tc.z) <= 2:
                self.gui_warn.content = "⚠ The transition curve needs at least one knot besides (0, 0)."
                return
            self._set_knots(list(tc.z[:-1]), list(tc.F[:-1]))

        @self.gui_csv.on_click
        def _(event) -> None:
            event.client.send_file_download("model_overview.csv", plots.figure_csv(self.gui_plot.figure).encode(),
                                            save_immediately=True)

        ctx.listeners.append(self._on_change)

    # ------------------------------------------------------------------ building controls
    def _add(self, f) -> None:
        p = self.ctx.params
        c = ParamControl(self.gui, f, value_for(p, f), self._apply)
        self.controls[f.path] = c

    def _build_knots(self, p: FrictionParams) -> None:
        for c in self.knot_controls:
            c.remove()
            self.controls.pop(c.field.path, None)
        self.knot_controls.clear()
        with self.knot_folder:
            for f in fields_of(p):
                if f.spec.group != "transition_curve":
                    continue
                c = ParamControl(self.gui, f, value_for(p, f), self._apply)
                c.set_enabled(self.ctx.params.model in f.models)
                self.controls[f.path] = c
                self.knot_controls.append(c)

    def _set_knots(self, z, F) -> None:
        try:
            p = to_piecewise(self.ctx.params).replace(transition_curve=TransitionCurve(z=tuple(z), F=tuple(F))).validate()
        except ParameterError as e:
            self.gui_warn.content = f"⚠ {e}"
            return
        self._build_knots(p)
        self.ctx.set_params(p, "knots")

    # ------------------------------------------------------------------ state changes
    def _apply(self, f, value, error) -> str | None:
        """A control's new value: applied to the current model, or refused with the reason."""
        if error is None:
            try:
                with self.ctx.lock:
                    p = with_values(to_piecewise(self.ctx.params) if f.path.startswith("transition_curve")
                                    else self.ctx.params, {f.path: value})
            except ParameterError as e:
                error = str(e)
        if error is not None:
            self.gui_warn.content = f"⚠ not applied — {error}"
            # and where the user is looking: the warning sits under the Model folder, out of view
            # while a knot further down is edited
            # (a typed entry's reason names the field already: "Fs⁺: Fs⁺: 'abc' is not a number")
            said = error if error.startswith(f"{f.label}:") else f"{f.label}: {error}"
            self.ctx.notify("Not applied", said, "red")
            return error
        self.ctx.set_params(p, "edit")
        return None

    def _view_changed(self) -> None:
        self.ctx.session.model_view.update(overlay=self.gui_overlay.value, log_v=self.gui_logv.value,
                                           three_d=self.gui_3d.value)
        self.request()

    def _on_change(self, reason: str) -> None:
        p = self.ctx.params
        if reason in ("accepted", "restored", "loaded"):  # move every control to the new set
            if reason != "model kind" and self.gui_kind.value != p.model:
                self.gui_kind.value = p.model
            pw = to_piecewise(p)
            if len(self.knot_controls) != len(pw.transition_curve.z) - 1:
                self._build_knots(pw)
            new_fields = {f.path: f for f in fields_of(pw)}
            for path, c in self.controls.items():
                f = new_fields.get(path, c.field)
                c.show(value_for(pw, f), f)
        if reason != "edit" or self._enabled_for != p.model:
            for c in self.controls.values():
                c.set_enabled(p.model in c.field.models)
            self._enabled_for = p.model
        warn = "\n\n".join(f"⚠ {w}" for w in sanity_warnings(p))
        if warn != self.gui_warn.content:
            self.gui_warn.content = warn
        self.request()

    def request(self) -> None:
        self.job.submit("redraw", coalesce=True)

    # ------------------------------------------------------------------ the job: draw the latest state
    def _compared(self, rec, p):
        """The diagnosis's comparison of the recording (its first MAX_DATA_SIM samples) under
        ``p``, or None where it has none (no position, no friction or applied force). Kept while
        the recording and the inertia stay, which the measured friction hangs on (where the
        comparison prefers the recording's own inertia reading, it judged that once, under the
        set drawn first): a slider's redraw simulates only the model along it."""
        from ...identify.data import Recording
        from ...identify.diagnose import comparison_of

        if rec.position is None or (rec.friction is None and rec.force is None):
            return None
        key = (id(rec), float(p.inertia))
        if self._cmp is not None and self._cmp[0] == key and self._cmp[1] is rec:
            return self._cmp[2]
        n = min(len(rec.time), MAX_DATA_SIM)
        part = rec if n == len(rec.time) else Recording(
            time=rec.time[:n], position=rec.position[:n], source=rec.source, normal_load=None if rec.normal_load is None
            else rec.normal_load[:n], friction=None if rec.friction is None else rec.friction[:n],
            force=None if rec.force is None else rec.force[:n], units=dict(rec.units))
        try:
            cmp_ = comparison_of(part, p, "friction")
        except FrictionError:
            cmp_ = None
        self._cmp = (key, rec, cmp_)
        return cmp_

    def _redraw(self) -> None:
        t0 = time.perf_counter()
        ctx = self.ctx
        with ctx.lock:
            p = ctx.params
            proposal = ctx.proposal
            rec = ctx.recording
            fit = ctx.fit
        view = ctx.session.model_view
        overlay = view.get("overlay", "none")
        shown = [(p.model, "main", p)]
        if proposal is not None:
            shown.append(("proposal", "proposal", proposal.params.replace(model=p.model)))
        if overlay not in ("none", p.model):
            shown.append((overlay, "overlay", as_model(p, overlay)))
        hyst, strib, slip = [], [], []
        vmax = max(abs(p.stribeck.positive.vs), abs(p.stribeck.negative.vs)) * 300
        if fit is not None and getattr(fit, "levels", None) is not None and len(fit.levels.velocity):
            vmax = max(vmax, float(np.max(np.abs(fit.levels.velocity))) * 1.2)
        mags = np.logspace(np.log10(vmax) - 4, np.log10(vmax), 160)
        v = np.concatenate([-mags[::-1], mags])
        for label, role, q in shown:
            lv = abcd_levels(q)  # each model its own Fig. 10 levels: a proposal may be for another machine
            ss = stick_slip_setup(q)
            hyst.append((label, role, None if q.model == "static" else abcd_ramp(q, levels=lv, rate=LIVE_RAMP_RATE * lv[1] / 20).runs[0]))
            if role != "overlay":  # every model kind shares S(v): an overlay would hide under the main curve
                strib.append((label, role, v, stribeck_curve(q, v)))
            slip.append((label, role, stick_slip(q, kp=ss["kp"], velocity=ss["velocity"], duration=STICK_SLIP_S).runs[0]))
        band = None
        if p.uncertainty:
            sd = plots.stribeck_band(p, v)
            if sd is not None:
                band = (v, stribeck_curve(p, v), sd)
        notes = []
        if overlay not in ("none", p.model):
            notes.append(f"{overlay}: same S(v) as {p.model}" +
                         ("; its loop on the top/right axes" if p.model != "static" and overlay != "static" else ""))
        if proposal is not None and dict(proposal.params.units) != dict(p.units):
            pu = proposal.params.units
            notes.append(f"proposal in {pu['position']}, {pu['force']}; current model in {p.units['position']}, "
                         f"{p.units['force']}: accept it to see the data in its own units")
        cmp_ = self._compared(rec, p) if rec is not None else None
        if cmp_ is not None:
            from ...identify.diagnose import friction_compared

            n = len(cmp_.time)
            # every set along the same comparison: the measured friction as the diagnosis takes it
            compared = [(label, role, friction_compared(rec, q, cmp_)) for label, role, q in shown if role != "overlay"]
            model_lines = [(label, role, c.model) for label, role, c in compared]
            left = sorted({name for _, _, c in compared for name in c.left_out})
            if left:
                notes.append(f"drawn without {', '.join(left)}: {rec.source} has no normal-load column")
            bottom = {"kind": "data", "t": cmp_.time, "measured": cmp_.measured, "model": model_lines,
                      "name": rec.source + ("" if n == len(rec.time) else f" (first {n} samples)")}
        else:
            pw = to_piecewise(p)
            if p.model == "leuven":
                from ...model.simulate import transition_curve_values

                zk = np.asarray(pw.transition_curve.z)
                z = np.linspace(0, zk[-1] * 1.3, 200)
                sig = [p.uncertainty.get(f"transition_curve.F.{i}", 0.0) for i in range(len(zk))]
                bottom = {"kind": "curve", "z": z, "F": transition_curve_values(pw, z), "zk": zk,
                          "Fk": np.asarray(pw.transition_curve.F), "sigma": sig if any(sig) else None}
            else:
                bottom = {"kind": "curve", "z": ()}
        fig = plots.overview_figure(units=p.units, hyst=hyst, strib=strib, slip=slip, bottom=bottom,
                                    log_v=view.get("log_v", True),
                                    levels=None if fit is None else fit.levels, band=band, notes=tuple(notes))
        self.gui_plot.figure = fig
        ctx.client.flush()
        self.redraw_times.append(time.perf_counter() - t0)
        self.last_slip = slip[0][2] if slip else None
        ctx.dirty = True  # saved by the page's background loop, off the interaction path
