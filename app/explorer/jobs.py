"""One worker thread per tab, fed by a command queue.

GUI callbacks only put a command on the queue; the worker runs commands one at a time, in
order. Commands of a *coalescing* kind (a redraw) keep only the latest pending one, so a
burst of slider moves costs one simulation. A long command reports its stage and
percentage through ``progress`` and is cancelled at its next progress report.
"""

from __future__ import annotations

import queue
import threading
import traceback
from dataclasses import dataclass, field
from typing import Callable


class Cancelled(Exception):
    """Raised inside a job's progress callback once the user pressed Cancel."""


@dataclass
class Command:
    kind: str
    args: tuple = ()
    coalesce: bool = False  # keep only the latest pending command of this kind


@dataclass
class JobState:
    running: str | None = None  # kind of the command being run
    cancel: threading.Event = field(default_factory=threading.Event)


class JobThread:
    """Runs ``handlers[kind](*args, progress)`` for each queued command."""

    def __init__(self, name: str, handlers: dict[str, Callable], on_error: Callable[[str, Exception], None]):
        self.name = name
        self.handlers = handlers
        self.on_error = on_error
        self.state = JobState()
        self._queue: queue.Queue = queue.Queue()
        self._latest: dict[str, int] = {}
        self._seq = 0
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True, name=name)
        self._thread.start()

    def submit(self, kind: str, *args, coalesce: bool = False) -> bool:
        """Queue a command. A non-coalescing command of the kind already running is refused
        (returns False): a second press does not start a second job."""
        with self._lock:
            if not coalesce and self.state.running == kind:
                return False
            self._seq += 1
            if coalesce:
                self._latest[kind] = self._seq
            self._queue.put((self._seq, Command(kind, args, coalesce)))
        return True

    def busy(self, kind: str | None = None) -> bool:
        r = self.state.running
        return r is not None and (kind is None or r == kind)

    def cancel(self) -> None:
        self.state.cancel.set()

    def stop(self) -> None:
        self._stop.set()
        self.state.cancel.set()
        self._queue.put((0, None))

    def progress_for(self, report: Callable[[float, str], None]) -> Callable[[float, str], None]:
        def progress(frac: float, msg: str = "") -> None:
            if self.state.cancel.is_set():
                raise Cancelled()
            report(frac, msg)

        return progress

    def _run(self) -> None:
        while not self._stop.is_set():
            seq, cmd = self._queue.get()
            if cmd is None or self._stop.is_set():
                return
            with self._lock:
                if cmd.coalesce and self._latest.get(cmd.kind) != seq:
                    continue  # a newer command of this kind is queued
                self.state.running = cmd.kind
                self.state.cancel.clear()
            try:
                self.handlers[cmd.kind](*cmd.args)
            except Cancelled:
                pass
            except Exception as e:  # the tab survives every failure and says what happened
                traceback.print_exc()
                self.on_error(cmd.kind, e)
            finally:
                with self._lock:
                    self.state.running = None
