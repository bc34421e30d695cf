"""``leuven-friction serve``: the explorer, one page per browser tab, top to bottom.

**Features:**
* the user's recording first: plotted on upload, columns/units/sign shown and remappable,
  then fitted; fits and diagnoses come back as proposals to accept or discard;
* every parameter as a text box (``1e-3``, ``0,005``) and a slider (log scale where the
  parameter spans decades), with its unit and a hint; sanity warnings (|Fc| > |Fs|);
* one overview figure: presliding hysteresis with A–D, Stribeck curve (log |v|),
  stick-slip, and the data with the model;
* a history of parameter sets to compare and restore; YAML load and export; PNG and CSV
  of every plot; the session survives a reload or a restart (per-user state file).

Each tab of the page (Model, Data, Diagnose, Parameter sets, Experiment) is an object that
owns its controls, its view and its job thread; callbacks only set state and enqueue.
"""

from __future__ import annotations

import threading
import time

import numpy as np
import viser

from ...model import FrictionParams
from .context import Context
from .data_tab import DataTab
from .diagnose_tab import DiagnoseTab
from .experiment_tab import ExperimentTab
from .model_tab import ModelTab
from .session import Session, SessionStore
from .sets_tab import SetsTab

CONTROLS_WIDTH = 370
VIEW_WIDTH = 880  # fits 1280 px beside the controls; widened to the window on the first camera message
CANVAS_MIN = 125  # px the dock layout leaves to the (empty) 3D canvas

# The slider's own number box is a browser numeric input that garbles "1e-3": hidden, the
# text box above each slider is the number entry. viser's own notifications (upload
# progress) go to the bottom, so they never cover the plot tabs. The fit's and the diagnosis's
# reports (markdown code blocks) wrap their long lines instead of running off the panel.
STYLE = """<style>
.mantine-Slider-root + .mantine-NumberInput-root, .mantine-Slider-root ~ .mantine-NumberInput-root,
.mantine-Slider-root ~ div .mantine-NumberInput-input {display:none !important;}
.mantine-Notifications-root[data-position="top-left"] {top:auto !important; bottom:12px !important;}
pre {white-space:pre-wrap !important; overflow-wrap:anywhere;}
</style>"""


class Explorer:
    """All of one browser tab."""

    def __init__(self, client: viser.ClientHandle, store: SessionStore, start: FrictionParams, start_label: str,
                 start_data: tuple | None = None):
        gui = client.gui
        session, why = store.load()
        restored = session is not None
        if session is None:
            session = Session(params=start)
        if start_data is not None and not restored:
            session.recording_name, session.recording_bytes = start_data
        self.ctx = ctx = Context(client=client, session=session, store=store)
        ctx.fit_on_start = start_data is not None and not restored  # `serve --data`: fit it at start

        # ---------------------------------------------------------------- layout
        gui.main_panel.dock_left()
        gui.main_panel.set_width(CONTROLS_WIDTH)
        panel = gui.add_panel()
        panel.dock_right()
        panel.set_width(VIEW_WIDTH)
        self.panel = panel
        gui.add_html(STYLE, order=1000)
        gui.add_markdown("**Leuven friction model** — eqs. (3)–(7) of Swevers et al.", order=0.0)
        self.gui_session = gui.add_markdown(self._session_note(restored, why, session), order=0.1)
        self.gui_message = gui.add_markdown("", order=0.2)
        ctx.status = lambda text: setattr(self.gui_message, "content", text)
        # the note at the top says what the page started from; a recording uploaded since replaces it
        self._noted_recording = session.recording_name
        ctx.listeners.append(self._on_change)

        # ---------------------------------------------------------------- tabs, top to bottom
        self.sets = SetsTab(ctx, gui, start_label)  # its proposal box first: seen without scrolling
        self.model = ModelTab(ctx, gui, panel)
        self.data = DataTab(ctx, gui, panel, self.sets.propose)
        self.diagnose = DiagnoseTab(ctx, gui, panel, self.sets.propose)
        self.sets.add_view(panel)
        self.experiment = ExperimentTab(ctx, gui, panel)

        # ---------------------------------------------------------------- 3D view: optional
        self._stop = threading.Event()
        self._sized = False
        self.link = None

        self.model.gui_3d.on_update(lambda _: self._toggle_3d())
        threading.Thread(target=self._background, daemon=True, name=f"page-{client.client_id}").start()
        self.model.request()

    @staticmethod
    def _session_note(restored: bool, why: str | None, s: Session) -> str:
        if why:
            return f"⚠ {why} — started from the defaults."
        if restored:
            rec = f", recording **{s.recording_name}**" if s.recording_name else ""
            return f"Session restored (saved {s.saved_at}): {len(s.history)} parameter sets{rec}."
        return "New session: changes are saved as you work and come back after a reload."

    def _on_change(self, reason: str) -> None:
        name = self.ctx.session.recording_name
        if reason == "recording" and name and name != self._noted_recording:
            self._noted_recording = name
            self.gui_session.content = (f"Recording **{name}** uploaded. Changes are saved as you work and come "
                                        "back after a reload.")

    def _toggle_3d(self) -> None:
        on = self.ctx.session.model_view.get("three_d", False) or self.model.gui_3d.value
        scene = self.ctx.client.scene
        if on and self.link is None:
            self.panel.set_width(VIEW_WIDTH)
            scene.add_grid("/ground", width=2.0, height=2.0, cell_size=0.1)
            scene.add_box("/base", color=(90, 90, 90), dimensions=(0.3, 0.3, 0.1), position=(0, 0, 0.05))
            self.link = scene.add_box("/link", color=(70, 130, 180), dimensions=(0.8, 0.08, 0.06), position=(0, 0, 0.15))
        elif not on and self.link is not None:
            scene.reset()
            self.link = None

    def _fill_window(self) -> None:
        """Widen the plot panel over the (empty) 3D canvas once the browser's width is known.

        The camera reports the canvas width: before the panels are docked that is the whole
        window, afterwards the canvas beside them. Either gives the room there is; the dock
        layout keeps the canvas ~120 px wide whatever the panels ask for, so the plots are
        widened only by what is left beyond that, never at the controls' expense."""
        t0 = time.time()
        last, since = None, time.time()
        while not self._stop.wait(0.2) and time.time() - t0 < 15:
            try:
                w = int(self.ctx.client.camera.image_width)
            except Exception:  # no camera message yet
                continue
            if w != last:
                last, since = w, time.time()
                continue
            if time.time() - since < 1.0:
                continue
            if w >= CONTROLS_WIDTH + VIEW_WIDTH:  # the whole window
                target = w - CONTROLS_WIDTH - CANVAS_MIN - 40
            else:  # the canvas beside the docked panels
                target = VIEW_WIDTH + w - CANVAS_MIN - 20
            if not self.ctx.session.model_view.get("three_d", False) and target > VIEW_WIDTH + 20:
                self.panel.set_width(target)
            return

    def _background(self) -> None:
        """The page's slow loop: table refresh, session saving, the optional 3D time-lapse of
        the stick-slip run (the link turns with the joint, orange while slipping)."""
        self._fill_window()
        tick, frame, last_save = 0, 0, 0.0
        while not self._stop.wait(0.05):
            tick += 1
            now = time.time()
            if tick % 8 == 0:
                self.sets.refresh()
            if self.ctx.dirty and now - last_save > 1.0 and not self.model.job.busy():
                self.ctx.save()
                last_save = now
            r = getattr(self.model, "last_slip", None)
            if self.link is None or r is None or self.model.job.busy():
                continue
            i = (frame * 50) % len(r.time)
            ang = float(r.position[i] - r.position[0]) * 10.0
            self.link.wxyz = (np.cos(ang / 2), 0.0, 0.0, np.sin(ang / 2))
            slipping = abs(r.velocity[i]) > 0.05 * max(np.max(np.abs(r.velocity)), 1e-300)
            self.link.color = (230, 120, 40) if slipping else (70, 130, 180)
            frame += 1

    def stop(self) -> None:
        self._stop.set()
        if self.ctx.dirty:
            self.ctx.save()
        for tab in (self.model, self.data, self.diagnose, self.experiment):
            tab.job.stop()


def serve(params: FrictionParams, host: str = "127.0.0.1", port: int = 8080, data: str | None = None,
          ready=None, start_label: str | None = None) -> None:
    """Run the explorer until interrupted. ``ready(url)`` is called once it listens."""
    from pathlib import Path

    server = viser.ViserServer(host=host, port=port, verbose=False)
    store = SessionStore()
    start_data = (Path(data).name, Path(data).read_bytes()) if data else None
    label = start_label or ("start: " + (params.provenance.get("source") or "parameters given at start"))
    pages: dict[int, Explorer] = {}

    @server.on_client_connect
    def _(client: viser.ClientHandle) -> None:
        pages[client.client_id] = Explorer(client, store, params, label, start_data)

    @server.on_client_disconnect
    def _(client: viser.ClientHandle) -> None:
        page = pages.pop(client.client_id, None)
        if page is not None:
            page.stop()

    url = f"http://{host}:{server.get_port()}"
    print(f"leuven-friction explorer at {url}", flush=True)
    print(f"session state: {store.dir}", flush=True)
    if ready is not None:
        ready(url)
    try:
        while True:
            time.sleep(1.0)
    except KeyboardInterrupt:
        pass
    finally:
        server.stop()
