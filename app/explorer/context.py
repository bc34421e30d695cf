"""What the tabs of one browser page share: the client, the session, and a few verbs."""

from __future__ import annotations

import threading
from dataclasses import dataclass, field
from typing import Callable

import viser

from ...model import FrictionParams
from .session import Session, SessionStore

PLOT_CONFIG = {"displayModeBar": "hover", "displaylogo": False, "modeBarButtons": [["toImage"]],
               "toImageButtonOptions": {"format": "png", "scale": 2}}


def plot_config(filename: str) -> dict:
    """Plotly's own "download plot as PNG" button (the only one kept), named per plot."""
    return dict(PLOT_CONFIG, toImageButtonOptions=dict(PLOT_CONFIG["toImageButtonOptions"], filename=filename))


@dataclass
class Proposal:
    """Parameters a fit or a diagnosis suggests; applied only when the user accepts."""

    label: str  # "fit of X.csv", "diagnosis: position_periodic"
    params: FrictionParams
    text: str  # what was estimated / held, the gap before and after (markdown)
    gap_before: float | None = None
    gap_after: float | None = None


@dataclass
class Context:
    client: viser.ClientHandle
    session: Session
    store: SessionStore
    lock: threading.RLock = field(default_factory=threading.RLock)
    recording: object | None = None  # identify.data.Recording of the session's upload (signs applied)
    fit: object | None = None  # the last FitResult (levels, covariances) of the recording
    proposal: Proposal | None = None
    listeners: list = field(default_factory=list)  # called with (reason) when params/proposal/recording change
    status: Callable[[str], None] = lambda text: None
    dirty: bool = False  # the session changed since it was last saved
    fit_on_start: bool = False

    @property
    def params(self) -> FrictionParams:
        return self.session.params

    def notify(self, title: str, body: str, color: str = "blue", seconds: float = 6.0) -> None:
        """A message at the top of the controls (pop-up notifications would cover the plot tabs)."""
        mark = {"red": "✖", "yellow": "⚠", "green": "✔"}.get(color, "ℹ")
        self.status(f"{mark} **{title}** — {body}")

    def changed(self, reason: str) -> None:
        for fn in list(self.listeners):
            fn(reason)

    def set_params(self, p: FrictionParams, reason: str = "edit") -> None:
        with self.lock:
            self.session.params = p
        self.changed(reason)

    def save(self) -> None:
        with self.lock:
            self.dirty = False
            err = self.store.save(self.session)
        if err:
            self.status(f"⚠ {err}")
