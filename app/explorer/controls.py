"""One control per parameter: a text box that takes what a person types, and a slider.

The text box is the number entry (parsed on the server by ``numbers.parse_number``: no
garbling, no clamping); the slider beside it moves the same value, on a log scale for
parameters spanning decades. A value the model cannot take is refused with a message and
not applied; a value outside the slider's range widens the range.
"""

from __future__ import annotations

import math
import threading
from typing import Callable

import viser

try:  # where viser 1.1 keeps it; without it a range change keeps the old tick labels (``set_marks``)
    from viser._messages import GuiSliderMark
except ImportError:  # pragma: no cover - another viser
    GuiSliderMark = None

from ...model import FrictionParams
from ...model.errors import ParameterError
from .fields import Field, check_field, get_value
from .numbers import format_number, parse_number

SLIDER_STEPS = 400


def _exp(x: float) -> float:
    return math.log10(abs(x))


def set_marks(slider, marks) -> None:
    """Give ``slider`` new tick labels ((value, label) pairs). viser 1.1 sends a slider's marks
    to the browser only through its prop ``_marks``: ``slider.marks = …`` sets a plain Python
    attribute the browser never sees, and the labels of the old range stayed under the new one."""
    if GuiSliderMark is None or not hasattr(slider, "_marks"):
        slider.marks = marks  # an older or newer viser: its public way, whatever it does
        return
    slider._marks = tuple(GuiSliderMark(value=float(v), label=label) for v, label in marks)


class ParamControl:
    """The text box and slider of one field."""

    def __init__(self, gui: viser.GuiApi, f: Field, value: float,
                 apply: Callable[[Field, float | None, str | None], str | None]):
        self.field = f
        self.apply = apply
        self.value = value  # the model's value the widgets show (a refused entry goes back to it)
        self._quiet = threading.local()
        self.label = self._label(f)
        self.text = gui.add_text(self.label, format_number(value), hint=self._text_hint(f))
        lo, hi = self._range(value)
        self.slider = gui.add_slider(" ", min=lo, max=hi, step=(hi - lo) / SLIDER_STEPS,
                                     initial_value=self._to_slider(value), marks=self._marks(lo, hi),
                                     hint=self._slider_hint(f))

        @self.text.on_update
        def _(_) -> None:
            if getattr(self._quiet, "on", False):
                return
            try:
                v = parse_number(self.text.value, self.field.label)
            except ParameterError as e:
                self._refused(str(e))
                return
            why = check_field(self.field, v)
            if why:
                self._refused(why)
                return
            if self.apply(self.field, v, None) is None:
                self.value = v
                self._move_slider(v)
            else:
                self._set_text(self.value)

        @self.slider.on_update
        def _(_) -> None:
            if getattr(self._quiet, "on", False):
                return
            v = self._from_slider(self.slider.value)
            if self.apply(self.field, v, None) is None:
                self.value = v
                self._set_text(v)

    @staticmethod
    def _text_hint(f: Field) -> str:
        return f"{f.hint}. Type e.g. 0.005, 5e-3 or 0,005.{' Slider: log scale.' if f.scale == 'log' else ''}"

    @staticmethod
    def _label(f: Field) -> str:
        return f"{f.label} ({f.unit})" if f.unit else f.label

    @classmethod
    def _slider_hint(cls, f: Field) -> str:
        return f"{cls._label(f)}{' — log scale' if f.scale == 'log' else ''}"

    # -- slider coordinates: the value itself, or log10 |value| for a log field
    def _to_slider(self, v: float) -> float:
        return _exp(v) if self.field.scale == "log" else v

    def _from_slider(self, s: float) -> float:
        if self.field.scale == "log":
            return (-1 if self.field.sign < 0 else 1) * float(f"{10 ** s:.6g}")
        return float(f"{s:.6g}")

    def _range(self, v: float) -> tuple[float, float]:
        f = self.field
        if f.scale == "log":
            e = _exp(v) if v != 0 else 0.0
            return math.floor(e - 1.5), math.ceil(e + 1.5)
        lo, hi = f.spec.slider_range(v)
        return (lo, hi) if hi > lo else (lo, lo + 1.0)

    def _marks(self, lo: float, hi: float):
        if self.field.scale == "log":
            es = list(range(int(math.ceil(lo)), int(math.floor(hi)) + 1))
            es = es[:: max(1, math.ceil(len(es) / 4))]
            return tuple((float(e), f"1e{e}") for e in es)
        return ((lo, f"{lo:.3g}"), (hi, f"{hi:.3g}"))

    def _move_slider(self, v: float) -> None:
        s = self._to_slider(v)
        self._quiet.on = True
        try:
            if not (self.slider.min <= s <= self.slider.max):
                lo, hi = self._range(v)
                lo, hi = min(lo, self.slider.min, s), max(hi, self.slider.max, s)
                self.slider.min, self.slider.max = lo, hi
                self.slider.step = (hi - lo) / SLIDER_STEPS
                set_marks(self.slider, self._marks(lo, hi))
            self.slider.value = s
        finally:
            self._quiet.on = False

    def _refused(self, why: str) -> None:
        """An entry the model cannot take: said (``apply`` with the reason), and the box shows the
        value the model still has — a refused "5e-5" left in a knot's box read as applied."""
        self.apply(self.field, None, why)
        self._set_text(self.value)

    def _set_text(self, v: float) -> None:
        self._quiet.on = True
        try:
            self.text.value = format_number(v)
        finally:
            self._quiet.on = False

    def show(self, v: float | None, f: Field | None = None) -> None:
        """Move both widgets to ``v`` (from code: another set was restored or accepted), the
        slider's range centred on it; ``f``: the field in the new set's units."""
        if f is not None and f.unit != self.field.unit:
            self.field = f
            self.label = self._label(f)
            self.text.label = self.label
            # the hints name the units too (they kept the paper's N·m and rad on a slide in N and m)
            self.text.hint = self._text_hint(f)
            self.slider.hint = self._slider_hint(f)
        if v is None:
            return
        self.value = v
        self._set_text(v)
        lo, hi = self._range(v)
        self._quiet.on = True
        try:
            self.slider.min, self.slider.max = lo, hi
            self.slider.step = (hi - lo) / SLIDER_STEPS
            set_marks(self.slider, self._marks(lo, hi))
        finally:
            self._quiet.on = False
        self._move_slider(v)

    def set_enabled(self, on: bool) -> None:
        self.text.disabled = not on
        self.slider.disabled = not on

    def remove(self) -> None:
        self.text.remove()
        self.slider.remove()


def value_for(p: FrictionParams, f: Field) -> float:
    v = get_value(p, f.path)
    if v is None and f.path == "sigma0":  # the LuGre σ0 fitted to the Leuven transition curve (Fig. 4)
        from ...model import as_model

        v = float(as_model(p.replace(model="leuven"), "lugre").sigma0)
    return 1.0 if v is None else v
