"""``leuven-friction serve``: the explorer.

**Features:**
* sliders for every model parameter and every transition-curve knot (add / remove knots;
  the curve stays strictly increasing whatever the user does), model and experiment selectors;
* live Plotly plots docked beside the controls: presliding hysteresis (A→B→C→D), the
  Stribeck curve, stick-slip, the selected paper experiment, with a second model overlaid;
* an animated joint in the 3D scene during the stick-slip run;
* CSV upload that runs the Markov and maximum-likelihood estimators with a progress bar,
  shows the data over the fit and the parameter table, and moves the sliders;
* YAML export (the same file as ``leuven-friction fit``).

Every browser tab gets its own controls and state (uploads are private to the tab). The
callbacks only change that state and wake the tab's worker thread, which recomputes with the
latest values (so a burst of slider moves costs one simulation, in order).
"""

from __future__ import annotations

import threading
import time
import traceback
from pathlib import Path

import numpy as np
import viser

from ..identify.data import DataError, load_recording
from ..identify.fit import fit_recordings
from ..identify.paramfile import params_to_yaml
from ..model import FrictionParams, ParameterError, Stribeck, StribeckSide, TransitionCurve, as_model
from ..model.experiments import EXPERIMENTS, abcd_ramp, run_experiment, stick_slip

from . import plots

LIVE_RAMP_RATE = 10.0  # N·m/s: the live hysteresis plot runs the A→B→C→D ramp 10× faster than Fig. 10
LIVE_STICK_SLIP_S = 3.0
PLOT_CONFIG = {"displayModeBar": False}
SIDES = (("positive", "+"), ("negative", "−"))


def live_figures(params: FrictionParams, compare: str | None):
    """The always-visible figures for the current parameters (and the overlay model), one
    at a time, hysteresis first: each can be sent as soon as it is ready."""
    shown = [(params.model, params)]
    if compare and compare != params.model:
        shown.append((compare, as_model(params, compare)))
    u = params.units
    yield "hysteresis", plots.hysteresis_figure([(label, abcd_ramp(p, rate=LIVE_RAMP_RATE).runs[0]) for label, p in shown], u)
    yield "stribeck", plots.stribeck_figure(shown, units=u)
    slip = [(label, stick_slip(p, duration=LIVE_STICK_SLIP_S).runs[0]) for label, p in shown]
    yield "stick_slip", (plots.stick_slip_figure(slip, u), slip[0][1])


def params_table(params: FrictionParams) -> str:
    """Markdown table of the parameters with their 1-σ uncertainties where known."""
    unc = params.uncertainty

    def cell(path, value):
        s = f"{value:.5g}"
        return f"{s} ± {unc[path]:.2g}" if path in unc else s

    rows = ["| parameter | positive velocity | negative velocity |", "|---|---|---|"]
    for k in ("Fs", "Fc", "vs", "delta", "sigma2"):
        rows.append(f"| {k} | {cell(f'stribeck.positive.{k}', getattr(params.stribeck.positive, k))} | "
                    f"{cell(f'stribeck.negative.{k}', getattr(params.stribeck.negative, k))} |")
    tc = params.transition_curve
    rows += ["", "| z | F_d(z) |", "|---|---|"]
    for i, (z, F) in enumerate(zip(tc.z, tc.F)):
        rows.append(f"| {z:.4g} | {cell(f'transition_curve.F.{i}', F)} |")
    rows.append(f"\nn = {params.n:g}, σ1 = {params.sigma1:g}, I = {params.inertia:g}")
    return "\n".join(rows)


def _slider_range(value: float, sign: int):
    """A slider range around a value of fixed sign (never crossing zero)."""
    mag = abs(value)
    lo, hi = mag * 0.02, mag * 3.0 + 1e-12
    return (lo, hi) if sign > 0 else (-hi, -lo)


def build_client(client: viser.ClientHandle, initial: FrictionParams, initial_data: bytes | None = None,
                 initial_name: str = "data.csv") -> threading.Event:
    """All GUI of one browser tab, top to bottom. Returns the event that stops its worker."""
    gui = client.gui
    state = {"params": initial, "compare": "lugre", "experiment": "breakaway", "fit": None, "slip": None,
             "suspend": False, "version": 0, "touched": 0.0}
    wake = threading.Event()
    stop = threading.Event()
    lock = threading.Lock()

    def notify(title, body, color):
        client.add_notification(title, body, color=color, auto_close_seconds=8.0)

    # ------------------------------------------------------------ plots, docked right
    if hasattr(gui, "main_panel"):
        gui.main_panel.dock_left()
        gui.main_panel.set_width(380)
    panel = gui.add_panel()
    panel.dock_right()
    panel.set_width(720)
    with panel.add_tab("Hysteresis"):
        gui_hyst = gui.add_plotly(plots.hysteresis_figure([]), aspect=1.2, config=PLOT_CONFIG)
    with panel.add_tab("Stribeck"):
        gui_strib = gui.add_plotly(plots.stribeck_figure([]), aspect=1.2, config=PLOT_CONFIG)
    with panel.add_tab("Stick-slip"):
        gui_slip = gui.add_plotly(plots.stick_slip_figure([]), aspect=1.2, config=PLOT_CONFIG)
    with panel.add_tab("Experiment"):
        gui_exp_md = gui.add_markdown("Choose an experiment on the left.")
        gui_exp = gui.add_plotly(plots.hysteresis_figure([]), aspect=1.2, config=PLOT_CONFIG)
    with panel.add_tab("Diagnose"):
        gui_diag_md = gui.add_markdown("Upload a recording, then press *Diagnose* (left panel, *Data*): the workflow "
                                       "looks for the physical effect the model misses, adds it and refits.")
        gui_diag_plots = [gui.add_plotly(plots.hysteresis_figure([]), aspect=1.3, config=PLOT_CONFIG, visible=False)
                          for _ in range(4)]
    with panel.add_tab("Fit"):
        gui_fit_md = gui.add_markdown("Upload a CSV recording (left panel, *Data*) to fit the model.")
        gui_fit_strib = gui.add_plotly(plots.stribeck_figure([]), aspect=1.2, config=PLOT_CONFIG, visible=False)
        gui_fit_tc = gui.add_plotly(plots.hysteresis_figure([]), aspect=1.2, config=PLOT_CONFIG, visible=False)

    # ------------------------------------------------------------ controls, main panel
    gui.add_markdown("**Leuven friction model** — parameters of eqs. (3)–(7)")
    with gui.add_folder("Model"):
        gui_model = gui.add_dropdown("model", ("leuven", "lugre", "static"), initial_value=initial.model)
        gui_compare = gui.add_dropdown("overlay", ("none", "leuven", "lugre", "static"), initial_value="lugre")
        gui_experiment = gui.add_dropdown("experiment", tuple(EXPERIMENTS), initial_value="breakaway")

    gui_side = {}
    for side, mark in SIDES:
        sp = getattr(initial.stribeck, side)
        sign = 1 if side == "positive" else -1
        # folders other than the first start collapsed: fewer widgets to re-render per change
        with gui.add_folder(f"Stribeck {mark}  (eq. 7)", expand_by_default=side == "positive"):
            h = {}
            for key in ("Fs", "Fc", "vs"):
                lo, hi = _slider_range(getattr(sp, key), sign)
                h[key] = gui.add_slider(f"{key}{mark}", min=lo, max=hi, step=(hi - lo) / 1000, initial_value=getattr(sp, key))
            h["delta"] = gui.add_slider(f"δ{mark}", min=0.1, max=3.0, step=0.01, initial_value=sp.delta)
            h["sigma2"] = gui.add_slider(f"σ2{mark}", min=0.0, max=max(3 * sp.sigma2, 1.0), step=0.01,
                                         initial_value=sp.sigma2)
        gui_side[side] = h

    with gui.add_folder("Presliding", expand_by_default=False):
        gui_n = gui.add_slider("n", min=0.5, max=20.0, step=0.1, initial_value=float(initial.n))
        gui_sigma1 = gui.add_slider("σ1", min=0.0, max=max(5000.0, 3 * initial.sigma1), step=10.0,
                                    initial_value=float(initial.sigma1))
        s0 = float(as_model(initial, "lugre").sigma0)
        gui_sigma0 = gui.add_slider("σ0 (LuGre)", min=s0 / 20, max=s0 * 20, step=s0 / 100, initial_value=s0)
        gui_inertia = gui.add_slider("inertia I", min=0.1, max=max(50.0, 3 * initial.inertia), step=0.1,
                                     initial_value=float(initial.inertia))

    knot_folder = gui.add_folder("Transition curve knots", expand_by_default=False)
    knot_handles: list = []  # [(z number, F slider)] for knots 1..k

    def knot_values():
        z = [0.0] + [hz.value * 1e-6 for hz, _ in knot_handles]
        F = [0.0] + [hF.value for _, hF in knot_handles]
        return z, F

    def build_knots(z, F):
        for hz, hF in knot_handles:
            hz.remove()
            hF.remove()
        knot_handles.clear()
        fmax = max(F) * 2.0
        with knot_folder:
            for i in range(1, len(z)):
                hz = gui.add_number(f"z{i} (µ)", initial_value=round(z[i] * 1e6, 6), min=0.0, step=0.001)
                hF = gui.add_slider(f"F{i}", min=0.0, max=fmax, step=fmax / 2000, initial_value=F[i])
                knot_handles.append((hz, hF))
                _attach_knot(i - 1, hz, hF)

    def _attach_knot(idx, hz, hF):
        # strictly increasing whatever the user does: clamp to just inside the neighbours
        def clamp(handle, values, scale):
            lo = values[idx] if idx > 0 else 0.0
            hi = values[idx + 2] if idx + 2 < len(values) else np.inf
            eps = 1e-6 * scale
            v = min(max(handle.value, lo + eps), hi - eps) if hi > lo + 2 * eps else handle.value
            if v != handle.value:
                handle.value = v
                return True
            return False

        @hz.on_update
        def _(_):
            z, _F = knot_values()
            zz = [v * 1e6 for v in z]
            if not clamp(hz, zz, max(zz)):
                changed()

        @hF.on_update
        def _(_):
            _z, F = knot_values()
            if not clamp(hF, F, max(F)):
                changed()

    tc0 = initial.transition_curve
    if tc0.kind != "piecewise_linear":
        from ..model.simulate import transition_curve_values

        zk = np.array([0.0, 0.02, 0.2, 0.5, 1.0]) * 6 * tc0.shape["z0"]
        tc0 = TransitionCurve(z=tuple(zk), F=tuple(transition_curve_values(initial, zk)))
    build_knots(list(tc0.z), list(tc0.F))
    with gui.add_folder("Knot editing", expand_by_default=False):
        gui_add_knot = gui.add_button("add knot")
        gui_remove_knot = gui.add_button("remove last knot")

    with gui.add_folder("Data"):
        gui_upload = gui.add_upload_button("Upload CSV", mime_type=".csv,.tsv,.txt,text/csv,text/plain", icon=None)
        gui_progress = gui.add_progress_bar(0.0, visible=False)
        gui_table = gui.add_markdown(params_table(initial))
        gui_diagnose = gui.add_button("Diagnose", hint="find the effect the model misses in the uploaded data")
        gui_export = gui.add_button("Export YAML")

    # ------------------------------------------------------------ 3D: the joint during stick-slip
    client.scene.add_grid("/ground", width=2.0, height=2.0, cell_size=0.1)
    client.scene.add_box("/base", color=(90, 90, 90), dimensions=(0.3, 0.3, 0.1), position=(0, 0, 0.05))
    gui_link = client.scene.add_box("/link", color=(70, 130, 180), dimensions=(0.8, 0.08, 0.06),
                                    position=(0, 0, 0.15))

    # ------------------------------------------------------------ reading the controls
    def params_from_controls() -> FrictionParams:
        sides = {side: StribeckSide(**{k: float(h.value) for k, h in gui_side[side].items()}) for side, _ in SIDES}
        z, F = knot_values()
        p = state["params"].replace(
            model=gui_model.value, stribeck=Stribeck(**sides), transition_curve=TransitionCurve(z=tuple(z), F=tuple(F)),
            n=float(gui_n.value), sigma1=float(gui_sigma1.value), sigma0=float(gui_sigma0.value),
            inertia=float(gui_inertia.value),
        )
        return p.validate()

    def set_controls(p: FrictionParams):
        """Move every control to ``p`` (after a fit) without a recompute per control."""
        state["suspend"] = True
        try:
            for side, _ in SIDES:
                sp = getattr(p.stribeck, side)
                for k, h in gui_side[side].items():
                    v = float(getattr(sp, k))
                    h.min, h.max = min(h.min, v), max(h.max, v)
                    h.value = v
            gui_n.value = float(p.n)
            gui_sigma1.value = float(p.sigma1)
            gui_inertia.value = float(p.inertia)
            build_knots(list(p.transition_curve.z), list(p.transition_curve.F))
        finally:
            state["suspend"] = False

    def changed(*_):
        state["touched"] = time.time()
        if state["suspend"]:
            return
        try:
            p = params_from_controls()
        except ParameterError as e:
            notify("Invalid parameters", str(e), "red")
            return
        with lock:
            state["params"] = p
            state["compare"] = None if gui_compare.value == "none" else gui_compare.value
            state["experiment"] = gui_experiment.value
            state["version"] += 1
        wake.set()

    for h in [gui_model, gui_compare, gui_experiment, gui_n, gui_sigma1, gui_sigma0, gui_inertia] + \
            [h for side in gui_side.values() for h in side.values()]:
        h.on_update(changed)

    @gui_add_knot.on_click
    def _(_):
        z, F = knot_values()
        z.append(z[-1] * 1.5 if len(z) > 1 else 1e-5)
        F.append(F[-1] * 1.1 + 1.0)
        state["suspend"] = True
        build_knots(z, F)
        state["suspend"] = False
        changed()

    @gui_remove_knot.on_click
    def _(event):
        z, F = knot_values()
        if len(z) <= 2:
            event.client.add_notification("Cannot remove", "The transition curve needs at least one knot besides (0, 0).",
                                          color="yellow", auto_close_seconds=5.0)
            return
        state["suspend"] = True
        build_knots(z[:-1], F[:-1])
        state["suspend"] = False
        changed()

    @gui_export.on_click
    def _(event):
        try:
            text = params_to_yaml(params_from_controls())
        except ParameterError as e:
            notify("Cannot export", str(e), "red")
            return
        event.client.send_file_download("leuven_friction_params.yaml", text.encode(), save_immediately=True)

    def run_fit(content: bytes, name: str):
        gui_progress.visible = True
        gui_progress.value = 0.0

        def progress(frac, msg):
            gui_progress.value = 100.0 * frac

        try:
            rec = load_recording(content, name=name)
            res = fit_recordings([rec], base=state["params"], progress=progress)
        except (DataError, ValueError, ParameterError) as e:
            notify("Fit failed", str(e), "red")
            return
        except Exception as e:  # the server survives every user mistake; say what happened
            traceback.print_exc()
            notify("Fit failed", f"{name}: {type(e).__name__}: {e}", "red")
            return
        finally:
            gui_progress.visible = False
        state["fit"] = res
        state["recording"] = rec
        fitted = res.params.replace(model=gui_model.value)
        state["params"] = fitted
        set_controls(fitted)
        gui_table.content = params_table(fitted)
        with client.atomic():
            gui_fit_md.content = f"**{name}**\n\n```\n{res.report()}\n```"
            if res.levels is not None and len(res.levels.velocity):
                gui_fit_strib.figure = plots.stribeck_figure([("fit", fitted)], levels=res.levels, units=fitted.units)
                gui_fit_strib.visible = True
            if res.transition_fit is not None:
                gui_fit_tc.figure = plots.transition_fit_figure(res.transition_fit, res.datasets, fitted.units)
                gui_fit_tc.visible = True
        notify("Fit done", f"{name}: {len(res.levels.velocity)} velocity levels, {res.n_branches} presliding branches",
               "green")
        changed()

    @gui_diagnose.on_click
    def _(_):
        from ..identify.diagnose import diagnose

        rec = state.get("recording")
        if rec is None:
            notify("Nothing to diagnose", "Upload a CSV recording first.", "yellow")
            return
        gui_progress.visible = True
        try:
            d = diagnose(rec, state["params"].replace(model="leuven"),
                         progress=lambda frac, msg: setattr(gui_progress, "value", 100.0 * frac))
        except (DataError, ValueError, ParameterError) as e:
            notify("Diagnosis failed", str(e), "red")
            return
        except Exception as e:
            traceback.print_exc()
            notify("Diagnosis failed", f"{type(e).__name__}: {e}", "red")
            return
        finally:
            gui_progress.visible = False
        with client.atomic():
            gui_diag_md.content = f"```\n{d.text()}\n```"
            for handle, fig in zip(gui_diag_plots, plots.diagnosis_figures(d)):
                handle.figure = fig
                handle.visible = True
        if d.effect:
            state["params"] = d.params_after
            set_controls(d.params_after)
            gui_table.content = params_table(d.params_after)
            notify("Effect found", f"{d.effect}: RMS {d.rms_before:.3g} → {d.rms_after:.3g}", "green")
            changed()
        else:
            notify("Nothing missing", "No significant effect: the model explains the data.", "blue")

    @gui_upload.on_upload
    def _(event):
        f = event.target.value
        run_fit(f.content, f.name)

    # ------------------------------------------------------------ the workers: recompute, animate
    exp_wake = threading.Event()

    def worker():
        frame = 0
        while not stop.is_set():
            if wake.wait(timeout=0.05):
                wake.clear()
                with lock:
                    p, compare = state["params"], state["compare"]
                try:
                    for name, fig in live_figures(p, compare):
                        if name == "hysteresis":
                            gui_hyst.figure = fig
                        elif name == "stribeck":
                            gui_strib.figure = fig
                        else:
                            gui_slip.figure, state["slip"] = fig
                        client.flush()
                    frame = 0
                except Exception as e:  # keep the tab alive and the last good plots
                    traceback.print_exc()
                    notify("Simulation failed", f"{type(e).__name__}: {e}", "red")
                exp_wake.set()
            slip = state["slip"]
            if slip is not None and time.time() - state["touched"] > 1.5:
                # time-lapse of the stick-slip run: the link turns with the joint angle,
                # orange while slipping. Paused while the user moves controls, so that the
                # software-rendered 3D view does not slow the plots down.
                i = (frame * 500) % len(slip.time)
                ang = float(slip.position[i]) * 10.0
                gui_link.wxyz = (np.cos(ang / 2), 0.0, 0.0, np.sin(ang / 2))
                slipping = abs(slip.velocity[i]) > 1e-3
                if slipping != state.get("slipping"):
                    gui_link.color = (230, 120, 40) if slipping else (70, 130, 180)
                    state["slipping"] = slipping
                frame += 1

    def experiment_worker():
        # the selected paper experiment can take a second: its own thread, latest state only
        done = None
        while not stop.is_set():
            if not exp_wake.wait(timeout=0.2):
                continue
            exp_wake.clear()
            time.sleep(0.3)  # let a burst of slider moves settle first
            with lock:
                p, exp, version = state["params"], state["experiment"], state["version"]
            if (exp, version) == done:
                continue
            try:
                res = run_experiment(exp, p)
                with client.atomic():
                    gui_exp.figure = plots.experiment_figure(res, p.units)
                    gui_exp_md.content = f"**{exp}** — {EXPERIMENTS[exp][1]}"
                done = (exp, version)
            except Exception as e:
                traceback.print_exc()
                notify("Experiment failed", f"{exp}: {type(e).__name__}: {e}", "red")

    threading.Thread(target=experiment_worker, daemon=True, name=f"experiment-{client.client_id}").start()
    threading.Thread(target=worker, daemon=True, name=f"client-{client.client_id}").start()
    wake.set()
    if initial_data is not None:
        threading.Thread(target=run_fit, args=(initial_data, initial_name), daemon=True).start()
    return stop


def serve(params: FrictionParams, host: str = "127.0.0.1", port: int = 8080, data: str | None = None,
          ready=None) -> None:
    """Run the explorer until interrupted. ``ready(url)`` is called once it listens."""
    server = viser.ViserServer(host=host, port=port, verbose=False)
    data_bytes = Path(data).read_bytes() if data else None
    stops = {}

    @server.on_client_connect
    def _(client: viser.ClientHandle) -> None:
        stops[client.client_id] = build_client(client, params, data_bytes, Path(data).name if data else "data.csv")

    @server.on_client_disconnect
    def _(client: viser.ClientHandle) -> None:
        ev = stops.pop(client.client_id, None)
        if ev is not None:
            ev.set()

    url = f"http://{host}:{server.get_port()}"
    print(f"leuven-friction explorer at {url}", flush=True)
    if ready is not None:
        ready(url)
    try:
        while True:
            time.sleep(1.0)
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
