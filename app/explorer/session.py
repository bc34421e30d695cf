"""What a user has done in the explorer, kept so that a reload or a restart loses nothing.

A session is the current parameter set, the history of parameter sets (start, fits,
diagnoses, loaded files, the user's edits), the uploaded recording with its column
mapping, and the view choices. It is saved (atomically) in a per-user state directory:
``$LEUVEN_FRICTION_STATE_DIR``, else ``$XDG_STATE_HOME/leuven-friction``, else
``~/.local/state/leuven-friction``. A page that opens finds the last saved session; all
tabs of one user share that file, the last change wins.
"""

from __future__ import annotations

import datetime as _dt
import json
import os
from dataclasses import dataclass, field
from pathlib import Path

from ...model import FrictionParams
from ...model.errors import FrictionError

SESSION_FILE = "session.json"
RECORDING_FILE = "recording.bin"
MAX_RECORDING_BYTES = 200 * 2**20
MAX_HISTORY = 40


def state_dir() -> Path:
    env = os.environ.get("LEUVEN_FRICTION_STATE_DIR")
    if env:
        return Path(env)
    base = os.environ.get("XDG_STATE_HOME") or os.path.join(os.path.expanduser("~"), ".local", "state")
    return Path(base) / "leuven-friction"


def now() -> str:
    return _dt.datetime.now().strftime("%H:%M:%S")


@dataclass
class Entry:
    """One parameter set in the history."""

    label: str
    params: FrictionParams
    time: str = field(default_factory=now)

    def title(self, i: int) -> str:
        return f"{i + 1}. {self.label} ({self.time})"


@dataclass
class Session:
    params: FrictionParams
    history: list[Entry] = field(default_factory=list)
    recording_name: str | None = None
    recording_bytes: bytes | None = None
    mapping: dict = field(default_factory=dict)  # signal -> column chosen by the user
    flip_friction: bool | None = None  # None: as detected from the data
    model_view: dict = field(default_factory=dict)  # overlay, log |v|, ...
    saved_at: str | None = None

    def add(self, label: str, params: FrictionParams) -> None:
        self.history.append(Entry(label, params))
        del self.history[:-MAX_HISTORY]


def _write_atomic(path: Path, data: bytes) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_bytes(data)
    os.replace(tmp, path)


class SessionStore:
    """Reads and writes the session of this user."""

    def __init__(self, directory: Path | None = None):
        self.dir = Path(directory) if directory else state_dir()

    def save(self, s: Session) -> str | None:
        """Save; returns a one-line reason when it could not (the page shows it)."""
        try:
            self.dir.mkdir(parents=True, exist_ok=True)
            doc = {
                "version": 1,
                "saved_at": _dt.datetime.now().isoformat(timespec="seconds"),
                "params": s.params.to_dict(),
                "history": [{"label": e.label, "time": e.time, "params": e.params.to_dict()} for e in s.history],
                "recording_name": s.recording_name,
                "mapping": s.mapping,
                "flip_friction": s.flip_friction,
                "model_view": s.model_view,
            }
            if s.recording_bytes is not None and len(s.recording_bytes) <= MAX_RECORDING_BYTES:
                rec_path = self.dir / RECORDING_FILE
                if not rec_path.exists() or rec_path.stat().st_size != len(s.recording_bytes) \
                        or rec_path.read_bytes() != s.recording_bytes:
                    _write_atomic(rec_path, s.recording_bytes)
            elif s.recording_bytes is None:
                doc["recording_name"] = None
            _write_atomic(self.dir / SESSION_FILE, json.dumps(doc, indent=1).encode())
            s.saved_at = doc["saved_at"]
            return None
        except OSError as e:
            return f"{self.dir}: cannot save the session ({e.strerror or e})"

    def load(self) -> tuple[Session | None, str | None]:
        """(session, None), or (None, why not) — (None, None) when nothing was saved."""
        path = self.dir / SESSION_FILE
        if not path.exists():
            return None, None
        try:
            doc = json.loads(path.read_text())
            s = Session(params=FrictionParams.from_dict(doc["params"]))
            for e in doc.get("history", []):
                s.history.append(Entry(e["label"], FrictionParams.from_dict(e["params"]), e.get("time", "")))
            s.mapping = dict(doc.get("mapping") or {})
            s.flip_friction = doc.get("flip_friction")
            s.model_view = dict(doc.get("model_view") or {})
            s.saved_at = doc.get("saved_at")
            name = doc.get("recording_name")
            rec_path = self.dir / RECORDING_FILE
            if name and rec_path.exists():
                s.recording_name, s.recording_bytes = name, rec_path.read_bytes()
            return s, None
        except (OSError, ValueError, KeyError, TypeError, FrictionError) as e:
            return None, f"{path}: the saved session cannot be read ({type(e).__name__}: {e})"

    def clear(self) -> None:
        for name in (SESSION_FILE, RECORDING_FILE):
            try:
                (self.dir / name).unlink()
            except OSError:
                pass
